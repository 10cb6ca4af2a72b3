"""String and array functions (manual L3284-L4588, L5549-L6388), with the manual's clamping rules.

All array functions return new arrays (L3964).  Each function cites its section; the examples
of the manual are the tests (tests/tm/test_library.py).
"""

from __future__ import annotations

from gplrt.tm.values import Array, TMError, to_int, to_string


def String_IndexOf(s: object, f: object, start: object = 0) -> int:
    """First index of ``f`` from ``start``, -1 if none; ``f == ""`` gives 0 (L3284); on a
    ``string[]``, the index of the first element that contains ``f`` (L3337)."""
    if isinstance(s, list):
        return next((i for i, e in enumerate(s) if to_string(f) in e), -1)
    text, find = to_string(s), to_string(f)
    if find == "":
        return 0
    st = to_int(start)
    if st < 0 or st > len(text):
        return -1
    return text.find(find, st)


def String_LastIndexOf(s: object, f: object, start: object = None) -> int:
    """Last index, searching right to left from ``start`` (default the end); ``f == ""`` gives the
    length (L3382)."""
    if isinstance(s, list):
        return next((i for i in range(len(s) - 1, -1, -1) if to_string(f) in s[i]), -1)
    text, find = to_string(s), to_string(f)
    if find == "":
        return len(text)
    end = len(text) if start is None else to_int(start) + len(find)
    return text.rfind(find, 0, max(0, end))


def String_Substring(s: object, a: object, b: object = -1, c: object = None) -> str:
    """``(s, start[, len])`` clamps (L3537); ``(s, from[, len])`` starts at ``from`` (L3592);
    ``(s, prefix, suffix[, n])`` the n-th ``prefix…suffix`` span (L3620)."""
    text = to_string(s)
    if isinstance(a, str) and isinstance(b, str):
        return GetToken(text, a, b, 1 if c is None else c)
    if isinstance(a, str):
        i = text.find(a)
        return "" if i < 0 else String_Substring(text, i, b)
    start, n = to_int(a), to_int(b)
    if start < 0 or start >= len(text):
        return ""
    return text[start:] if n < 0 else text[start:start + n]


def _split_quoted(text: str, sep: str) -> list[str]:
    out, cur, quoted, i = [], [], False, 0
    while i < len(text):
        if text[i] == '"':
            quoted = not quoted
        if not quoted and text.startswith(sep, i):
            out.append("".join(cur))
            cur = []
            i += len(sep)
            continue
        cur.append(text[i])
        i += 1
    out.append("".join(cur))
    return out


def String_Split(s: object, sep: object, mode: object = 0) -> Array:
    """Split (L3715): mode 0 keeps empty parts, 1 drops them, 2/3 do so without splitting inside
    ``"…"``; an empty separator does not split."""
    text, sp, m = to_string(s), to_string(sep), to_int(mode)
    if sp == "":
        parts = [text]
    elif m in (2, 3):
        parts = [p.strip() if p.strip().startswith('"') else p for p in _split_quoted(text, sp)]
        parts = [p.strip() for p in parts]
    else:
        parts = text.split(sp)
    if m in (1, 3):
        parts = [p for p in parts if p != ""]
    return Array("string", parts)


def String_Replace(s: object, old: object, new: object) -> str:
    """Replace every ``old`` (L3776); an empty ``old`` changes nothing."""
    text, o = to_string(s), to_string(old)
    return text if o == "" else text.replace(o, to_string(new))


def String_Trim(s: object, lead: object = None, trail: object = None) -> str:
    """White space (L3808), or repeated leading ``lead`` and trailing ``trail`` strings (L3849)."""
    text = to_string(s)
    if lead is None:
        return text.strip()
    ld = to_string(lead)
    tr = ld if trail is None else to_string(trail)
    while ld and text.startswith(ld):
        text = text[len(ld):]
    while tr and text.endswith(tr):
        text = text[:-len(tr)]
    return text


def String_ToLower(s: object) -> str:
    """ASCII letters only (L3904)."""
    return "".join(c.lower() if c.isascii() else c for c in to_string(s))


def String_ToUpper(s: object) -> str:
    return "".join(c.upper() if c.isascii() else c for c in to_string(s))


def String_ToInteger(s: object, base: object = 10) -> object:
    """Base 10 (with ``0x``/``0b`` detected), 16 or 2; text that is not a number of that base gives 0
    (L2908, the examples at L2940-L2953)."""
    if isinstance(s, list):
        return Array("int", [String_ToInteger(x, base) for x in s])
    text, b = to_string(s).strip(), to_int(base)
    low = text.lower()
    try:
        if b == 10:
            if low.startswith(("0x", "0b")):
                return to_int(int(low[2:], 16 if low[1] == "x" else 2))
            return to_int(int(text, 10))
        if b == 16:
            return to_int(int(low[2:] if low.startswith("0x") else low, 16)) if not low.startswith("-") else 0
        if b == 2:
            return to_int(int(low[2:] if low.startswith("0b") else low, 2)) if not low.startswith("-") else 0
    except ValueError:
        return 0
    return 0


def _tokens(text: str, p: str, q: str) -> list[tuple[int, int]]:
    """(start, end) of every ``p…q`` token of ``text``, prefix and suffix included, left to right
    without overlap: both given, from a prefix to the next suffix; a prefix alone, from one to
    the next; a suffix alone, from the end of the last token to the next suffix (L5549, L6270)."""
    tokens: list[tuple[int, int]] = []
    if p and q:
        i = 0
        while True:
            a = text.find(p, i)
            if a < 0:
                break
            b = text.find(q, a + len(p))
            if b < 0:
                break
            tokens.append((a, b + len(q)))
            i = b + len(q)
    elif p:
        starts = []
        i = text.find(p)
        while i >= 0:
            starts.append(i)
            i = text.find(p, i + len(p))
        tokens = [(a, starts[j + 1] if j + 1 < len(starts) else len(text)) for j, a in enumerate(starts)]
    else:
        i = 0
        while True:
            b = text.find(q, i)
            if b < 0:
                break
            tokens.append((i, b + len(q)))
            i = b + len(q)
    return tokens


def _strip(tok: str, p: str, q: str) -> str:
    return tok[len(p):len(tok) - len(q) if q else len(tok)]


def GetToken(s: object, prefix: object, suffix: object, n: object = 1, mode: object = 0) -> str:
    """The n-th (``-1`` the last) ``prefix…suffix`` token; mode 1 without prefix and suffix
    (L5549; the examples at L5620-L5688)."""
    text, p, q, k, m = to_string(s), to_string(prefix), to_string(suffix), to_int(n), to_int(mode)
    if p == "" and q == "":
        return text if k in (0, 1) else ""
    tokens = _tokens(text, p, q)
    if k == 0 or not tokens:
        return ""
    if k == -1:
        k = len(tokens)
    if not 1 <= k <= len(tokens):
        return ""
    a, b = tokens[k - 1]
    return _strip(text[a:b], p, q) if m == 1 else text[a:b]


def GetAllTokens(s: object, prefix: object, suffix: object, mode: object = 0) -> Array:
    """Every ``prefix…suffix`` token (L6270): mode 1 and 3 without the prefix and suffix, 2 and 3
    only when the first token starts the text (else ``{}``); no prefix and no suffix: the text."""
    text, p, q, m = to_string(s), to_string(prefix), to_string(suffix), to_int(mode)
    if m not in (0, 1, 2, 3):
        raise TMError(f"GetAllTokens: mode {m} is not 0-3")
    if p == "" and q == "":
        return Array("string", [text])
    tokens = _tokens(text, p, q)
    if m >= 2 and (not tokens or tokens[0][0] != 0):
        return Array("string", [])
    return Array("string", [_strip(text[a:b], p, q) if m in (1, 3) else text[a:b] for a, b in tokens])


# --- arrays (L3957-L4588) -----------------------------------------------------------------------
def _arr(a: object, name: str) -> Array:
    if not isinstance(a, Array):
        if isinstance(a, (list, tuple)):
            return Array("double", a)
        raise TMError(f"{name}: the first argument must be an array")
    return a


def Array_Append(a: object, x: object) -> Array:
    """``a`` and the element(s) ``x`` (L3957)."""
    arr = _arr(a, "Array_Append")
    items = list(x) if isinstance(x, (list, tuple)) else [x]
    return Array(arr.type, list(arr) + items)


def Array_Insert(a: object, i: object, x: object) -> Array:
    """Insert at ``i`` (≥ length appends; < 0 is an error, L3996)."""
    arr = _arr(a, "Array_Insert")
    k = to_int(i)
    if k < 0:
        raise TMError("Array_Insert: the index is negative")
    items = list(x) if isinstance(x, (list, tuple)) else [x]
    k = min(k, len(arr))
    return Array(arr.type, list(arr)[:k] + items + list(arr)[k:])


def Array_Remove(a: object, i: object, n: object = 1) -> Array:
    """Remove ``n`` elements from ``i`` (L4050): an index out of range is an error, too many go to
    the end, ``n`` < 0 removes none."""
    arr = _arr(a, "Array_Remove")
    k, m = to_int(i), to_int(n)
    if not 0 <= k < len(arr):
        raise TMError(f"Array_Remove: index {k} is out of the array")
    items = list(arr)
    if m > 0:
        del items[k:k + m]
    return Array(arr.type, items)


def Array_Equals(a: object, b: object, *rest: object) -> bool:
    """Element-wise equality (L4092); ``(a, ia, b, ib, n)`` compares ``n`` elements."""
    if rest:
        ia, arr_b, ib, n = to_int(b), rest[0], to_int(rest[1]), to_int(rest[2])
        if n == 0:
            return True
        x, y = list(_arr(a, "Array_Equals")), list(_arr(arr_b, "Array_Equals"))
        if n < 0 or ia < 0 or ib < 0 or ia + n > len(x) or ib + n > len(y):
            return False
        return x[ia:ia + n] == y[ib:ib + n]
    return list(_arr(a, "Array_Equals")) == list(_arr(b, "Array_Equals"))


def Array_IndexOf(a: object, x: object, start: object = 0) -> int:
    arr = list(_arr(a, "Array_IndexOf"))
    st = to_int(start)
    for i in range(max(0, st), len(arr)):
        if arr[i] == x:
            return i
    return -1


def Array_LastIndexOf(a: object, x: object, start: object = None) -> int:
    arr = list(_arr(a, "Array_LastIndexOf"))
    st = len(arr) - 1 if start is None else min(to_int(start), len(arr) - 1)
    for i in range(st, -1, -1):
        if arr[i] == x:
            return i
    return -1


def Array_Reverse(a: object, group: object = None) -> Array:
    """Reverse, or reverse inside consecutive groups of 2, 4 or 8 (L4330)."""
    arr = _arr(a, "Array_Reverse")
    items = list(arr)
    if group is None:
        return Array(arr.type, items[::-1])
    g = to_int(group)
    if g not in (2, 4, 8):
        return Array(arr.type, items)
    out: list[object] = []
    for i in range(0, len(items), g):
        out.extend(items[i:i + g][::-1])
    return Array(arr.type, out)


def Array_Sort(a: object, direction: object = 0) -> Array:
    arr = _arr(a, "Array_Sort")
    return Array(arr.type, sorted(arr, reverse=to_int(direction) == 1))


def Array_SubElements(a: object, start: object, n: object = -1) -> Array:
    """Elements from ``start`` (clamped; out of range gives ``{}``, L4490)."""
    arr = _arr(a, "Array_SubElements")
    st, m = to_int(start), to_int(n)
    if not 0 <= st < len(arr):
        return Array(arr.type)
    items = list(arr)[st:]
    return Array(arr.type, items if m < 0 else items[:m])

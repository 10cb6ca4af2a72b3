"""The member tables of the GPL Dictionary spec (``shared/spec/gpl-dictionary.md``), read as data.

The spec is written for people: one table per class with a Member, Kind and Signature column
(§1-§9, §10.1, §11.1-§11.2), tables whose member cell is a whole call (§10.4), tables whose
"Signature" cell holds the kind (§11.3-§11.5), one row naming several members
(`` `tl.Start` / `tl.Stop` ``), a prose list (§10.3 Math) and the constant tables of §13.  This
module turns all of it into :class:`DictMember` records -- which class, Shared or not, readable,
assignable, and how many arguments each form takes -- so that a test can hold the runtime's
catalogue against every member the Dictionary lists.

Argument counts come from the signature snippets: ``X.M(a, b)`` is 2, ``M(a [, b [, c]])`` 1 to 3,
``M(axis1, …, axis12)`` 12, ``X.M`` 0.  A parameter is optional when the Signature or Type cell
says so (``robot optional``, ``every argument optional``, ``first required, rest optional``);
optionality the spec marks only in its Semantics column is "[unconfirmed]" and not used.  A form
followed by ``= v`` is the assignment form.  A member whose row gives no call (``vr.Info`` |
``get``) has no known argument count (``None``).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

#: Object prefixes the Dictionary writes in §10.4 and §11 (``sr.Close``, ``vs.Result``), and the
#: class names it writes as prefixes of Shared members (``File.Copy``, ``XmlDoc.LoadFile``).
PREFIXES = {
    "arr": "Array", "s": "String", "sr": "StreamReader", "sw": "StreamWriter", "ep": "IPEndPoint",
    "sock": "Socket", "tc": "TcpClient", "uc": "UdpClient", "tl": "TcpListener", "mb": "Modbus",
    "vs": "Vision", "vr": "VisResult", "doc": "XmlDoc", "n": "XmlNode", "loc": "Location",
    "rf": "RefFrame", "p": "Profile", "t": "Thread", "e": "Exception", "lt": "Latch",
}
CLASS_PREFIXES = {"File", "Console", "XmlDoc", "Math", "String", "Location", "Move", "Robot",
                  "Controller", "Thread", "Signal", "Latch"}
#: The class a section heading is about (§1-§9, §10.1), by the heading's first word.
SECTION_CLASSES = {
    "Location": "Location", "RefFrame": "RefFrame", "Profile": "Profile", "Move": "Move",
    "Robot": "Robot", "Controller": "Controller", "Thread": "Thread", "Exception": "Exception",
    "Signal": "Signal", "Latch": "Latch", "String": "String",
}

Arity = tuple[int, int]


@dataclass(frozen=True)
class DictMember:
    """One member (or function, constructor or constant) as the Dictionary lists it."""

    owner: str  # GPL class ("Move", "String", "Array"); "" for a function or constant
    name: str
    kind: str  # "ctor" | "member" | "function" | "constant"
    shared: bool
    get: bool  # readable as a value (a property, or a method used as a function)
    set: bool  # assignable (``X.M = v`` or ``X.M(args) = v``)
    read_args: Arity | None  # argument counts of the call / read form; None: not stated
    set_args: Arity | None  # argument counts of the assignment form (without the value)
    line: int  # 1-based line in gpl-dictionary.md
    value: int | None = None  # a constant's value

    @property
    def label(self) -> str:
        if self.kind == "ctor":
            return f"New {self.owner}"
        return f"{self.owner}.{self.name}" if self.owner else self.name


# -- signature snippets -------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Form:
    name: str | None  # the member the snippet calls (None: a bare ``(args)`` snippet)
    params: tuple[str, ...]
    optional: tuple[bool, ...]
    has_call: bool  # written with parentheses
    assigns: bool  # ``... = v``


def _split_params(text: str) -> tuple[tuple[str, ...], tuple[bool, ...]]:
    """``a, b [, c [, d]]`` -> names and whether each is inside brackets; ``a1, …, a12`` is 12."""
    names: list[str] = []
    optional: list[bool] = []
    depth = 0
    token = ""
    token_depth = 0  # the bracket depth where the current parameter starts
    tokens: list[tuple[str, bool]] = []
    for ch in text + ",":
        if ch == "[":
            depth += 1
        elif ch == "]":
            depth -= 1
        elif ch == ",":
            if token.strip():
                tokens.append((token.strip(), token_depth > 0))
            token = ""
        else:
            if not token.strip():
                token_depth = depth
            token += ch
    for i, (tok, opt) in enumerate(tokens):
        if tok in ("…", "..."):
            before = re.search(r"(\d+)$", tokens[i - 1][0]) if i > 0 else None
            after = re.search(r"(\d+)$", tokens[i + 1][0]) if i + 1 < len(tokens) else None
            if before and after:
                for k in range(int(before.group(1)) + 1, int(after.group(1))):
                    names.append(f"arg{k}")
                    optional.append(opt)
            continue
        names.append(re.sub(r"\W", "", tok.split()[0]) if tok.split() else tok)
        optional.append(opt)
    return tuple(names), tuple(optional)


_CALL = re.compile(r"(?:\.\.\.)?(?:(?P<prefix>[A-Za-z_]\w*)\.)?(?P<name>[A-Za-z_]\w*)\s*(?P<call>\((?P<args>[^()]*)\))?"
                   r"(?P<assign>\s*=(?!=))?")
_BARE = re.compile(r"^\((?P<args>[^()]*)\)")


def _forms(snippet: str) -> list[_Form]:
    """The calls written in one backticked snippet (``x = obj.M(a, b)``, ``obj.M(i) = v``, ``(a)``)."""
    s = snippet.strip()
    bare = _BARE.match(s)
    if bare:
        names, opt = _split_params(bare.group("args"))
        return [_Form(None, names, opt, True, False)]
    out: list[_Form] = []
    if s.startswith("Dim ") or s.startswith("New "):  # a constructor: ``New T(args)``
        m = re.search(r"New\s+\w+\s*(\((?P<args>[^()]*)\))?", s)
        if m:
            names, opt = _split_params(m.group("args") or "")
            out.append(_Form("New", names, opt, m.group(1) is not None, False))
        return out
    for m in _CALL.finditer(s.replace("...", "")):
        if m.group("prefix") is None and m.group("call") is None:
            continue  # a plain word (``n``, ``v``), not a member
        names, opt = _split_params(m.group("args") or "")
        out.append(_Form(m.group("name"), names, opt, m.group("call") is not None, bool(m.group("assign"))))
    return out


def _optional_words(text: str, params: tuple[str, ...], optional: tuple[bool, ...]) -> tuple[bool, ...]:
    """Apply what the prose says about optional parameters to a form's parameter list."""
    # a statement about optionality the spec itself marks "[unconfirmed]" is not used
    plain = re.sub(r"[^;|]*\boptional\b[^;|]*\[unconfirmed\]", "", text.replace("`", "").replace("*", ""))
    if re.search(r"every argument optional|all optional|\bup to \d+", plain):
        return tuple(True for _ in params)
    if re.search(r"first required, rest optional", plain):
        return tuple(i > 0 for i in range(len(params)))
    out = list(optional)
    for i, p in enumerate(params):
        if re.search(rf"\b{re.escape(p)}\b(?:\s+[\d.]+)?\s+optional", plain, re.IGNORECASE):
            out[i] = True
    # an optional parameter makes every later one optional too (positional arguments)
    for i in range(1, len(out)):
        out[i] = out[i] or out[i - 1]
    return tuple(out)


def _arity(form: _Form, prose: str) -> Arity:
    opt = _optional_words(prose, form.params, form.optional)
    return sum(1 for o in opt if not o), len(form.params)


def _union(a: Arity | None, b: Arity) -> Arity:
    return b if a is None else (min(a[0], b[0]), max(a[1], b[1]))


# -- tables ---------------------------------------------------------------------------------------------


def _cells(line: str) -> list[str]:
    return [c.strip() for c in line.strip().strip("|").split("|")]


def _ticks(text: str) -> list[str]:
    return re.findall(r"`([^`]+)`", text)


def _kind_words(text: str) -> tuple[bool, bool] | None:
    """(get, set) from a Kind text, or None when it names no property access (a method)."""
    plain = text.replace("*", "")
    get = bool(re.search(r"\bget\b", plain))
    setter = bool(re.search(r"\bget[/-]set\b|\bset\b", plain))
    if not (get or setter):
        return None
    return get or not setter, setter


def _owner_and_name(token: str, section_class: str | None, last_prefix: str | None) -> tuple[str, str, bool]:
    """The class and member named by a Member-cell token (``vs.Result``, ``Angle``, ``New Thread``)."""
    token = token.split("(")[0].strip()
    if "." in token:
        prefix, name = token.split(".", 1)
        if prefix in CLASS_PREFIXES:
            return prefix, name, True
        return PREFIXES[prefix], name, False
    if last_prefix is not None:
        if last_prefix in CLASS_PREFIXES:
            return last_prefix, token, True
        return PREFIXES[last_prefix], token, False
    return section_class or "", token, False


def _row_members(cells: dict[str, str], section_class: str | None, line: int) -> list[DictMember]:
    member_cell = cells.get("member", cells.get("function", ""))
    if member_cell.startswith("("):  # (`Replace`): "do not provide"
        return []
    tokens = _ticks(member_cell)
    if not tokens:
        return []
    if "function" in cells:  # §10.2: functions without a class
        return _function_rows(tokens, cells, line)
    kind_cell = cells.get("kind")
    sig_cell = cells.get("signature", "")
    prose = " | ".join(cells.values())
    snippets = _ticks(sig_cell)
    if kind_cell is None:  # §10.4 / §11.3-§11.5: the Signature cell may hold the kind instead
        kind_cell = sig_cell if _kind_words(sig_cell) else ""
        if not snippets and not kind_cell:  # §10.4: the member cell is the call itself
            snippets = tokens
    kind_parts = kind_cell.split(" / ")
    all_forms = [f for s in snippets for f in _forms(s)]
    out: list[DictMember] = []
    last_prefix: str | None = None
    for i, tok in enumerate(tokens):
        if tok.startswith("New "):
            out.append(_ctor(tok.split()[1], snippets, prose, line))
            continue
        if "." in tok.split("(")[0]:
            last_prefix = tok.split(".", 1)[0]
        owner, name, class_prefix = _owner_and_name(tok, section_class, last_prefix)
        kind_text = kind_parts[i] if len(kind_parts) == len(tokens) else kind_cell
        kind = _kind_words(kind_text) or _kind_words(kind_cell)
        sig_parts = sig_cell.split(" / ")
        sig_text = sig_parts[i] if len(sig_parts) == len(tokens) else sig_cell
        get, setter = kind if kind is not None else ("→" in sig_text, False)  # → a result
        shared = ("Shared" in kind_cell or "Shared" in sig_cell or class_prefix
                  or section_class in ("Move", "Robot", "Controller", "Signal"))
        if re.search(r"\binst\b", kind_cell):
            shared = False
        # the snippets for this member: those naming it, else the i-th of a positional list,
        # else a single snippet that stands for every member of the row (``s.Trim`` …)
        own = [f for f in all_forms if f.name is not None and f.name.lower() == name.lower()]
        if not own and len(all_forms) == len(tokens):
            own = [all_forms[i]]
        elif not own and len(all_forms) == 1:
            own = all_forms
        read: Arity | None = None
        assign: Arity | None = None
        for f in own:
            if f.assigns:
                assign = _union(assign, _arity(f, prose))
            else:
                read = _union(read, _arity(f, prose))
        if setter and assign is None:
            assign = read
        if get and read is None:
            read = assign
        out.append(DictMember(owner, name, "member", bool(shared), get, setter, read, assign, line))
    return out


def _ctor(cls: str, snippets: list[str], prose: str, line: int) -> DictMember:
    """``New T``: the argument counts of the snippets that create a ``T``."""
    arity: Arity | None = None
    for s in snippets:
        if re.search(rf"\bNew\s+{cls}\b", s):
            for f in _forms(s):
                arity = _union(arity, _arity(f, prose))
    return DictMember(cls, "New", "ctor", False, False, False, arity, None, line)


def _function_rows(tokens: list[str], cells: dict[str, str], line: int) -> list[DictMember]:
    sig = cells.get("signature", "")
    forms = [f for s in _ticks(sig) for f in _forms(s)]
    out = []
    for i, name in enumerate(tokens):
        own = [f for f in forms if f.name == name] or ([forms[i]] if len(forms) == len(tokens) else forms[:1])
        arity: Arity | None = None
        for f in own:
            arity = _union(arity, _arity(f, sig))
        out.append(DictMember("", name, "function", True, True, False, arity, None, line))
    return out


def _math(lines: list[str], start: int) -> list[DictMember]:
    """§10.3 is a sentence: functions of one argument unless written with theirs; then constants."""
    text = ""
    i = start
    while i < len(lines) and lines[i].strip() and not lines[i].startswith("#"):
        text += " " + lines[i]
        i += 1
    funcs, _, consts = text.partition("; constants")
    out = []
    for tok in _ticks(funcs):
        form = _forms(tok if "." in tok else f"Math.{tok}")[0]
        arity = (len(form.params), len(form.params)) if form.has_call else (1, 1)
        out.append(DictMember("Math", form.name or tok, "member", True, True, False, arity, None, start + 1))
    for tok in _ticks(consts):
        name = tok.split(".")[-1]
        out.append(DictMember("Math", name, "member", True, True, False, (0, 0), None, start + 1))
    return out


def _constant(cells: list[str], line: int) -> DictMember | None:
    names = _ticks(cells[0])
    if not names or not names[0].startswith("GPL_"):
        return None
    raw = cells[1].split()[0]
    value = int(raw[2:], 16) if raw.upper().startswith("&H") else int(raw)
    return DictMember("", names[0], "constant", True, True, False, None, None, line, value)


def read_dictionary(path: Path) -> list[DictMember]:
    """Every member, function, constructor and constant the Dictionary's tables list."""
    lines = path.read_text(encoding="utf-8").splitlines()
    members: list[DictMember] = []
    section_class: str | None = None
    header: list[str] | None = None
    for i, line in enumerate(lines):
        if line.startswith("#"):
            header = None
            words = re.sub(r"^#+\s*[\d.]+\s*", "", line).split()
            section_class = SECTION_CLASSES.get(words[0]) if words else None
            if line.startswith("### 10.3"):
                members.extend(_math(lines, i + 1))
            continue
        if not line.startswith("|"):
            header = None
            continue
        cells = _cells(line)
        if header is None:
            header = [re.sub(r"\s*\[.*", "", c).split(" /")[0].strip().lower() for c in cells]
            continue
        if set(cells[0]) <= {"-", " ", ":"}:
            continue
        if header[0] == "constant":
            const = _constant(cells, i + 1)
            if const is not None:
                members.append(const)
            continue
        if header[0] not in ("member", "function"):
            continue
        row = dict(zip(header, cells))
        if "returns" in row:
            row["type"] = row.pop("returns")
        members.extend(_row_members(row, section_class, i + 1))
    return members

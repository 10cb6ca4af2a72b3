"""Breaking long generated lines the PEP 8 way (implicit continuation inside parentheses).

A GPL statement written over several lines with `` _`` becomes one Python statement, which can be
far longer than PEP 8's limit.  :func:`wrap` breaks such a line:

* ``global a, b, ...`` -> several ``global`` statements;
* an expression with top-level ``+``, ``and`` or ``or`` (string building, long conditions) ->
  parenthesised, broken *before* the operators (PEP 8's recommended style);
* other top-level binary operators (``*``, ``-``, comparisons) -> the same, broken before the
  loosest of them;
* a call whose arguments run past the limit -> the arguments packed on continuation lines (a
  sole argument that is still too long breaks before its operators without parentheses of its
  own: the call's brackets already carry the continuation).

* anything else with brackets (``f(<args>) != x``) -> the longest bracket group opened, its
  contents on a continuation line.

Lines that cannot be broken this way (one huge string literal) are left alone.  Block headers get
a double continuation indent so that their continuation lines stand apart from the body.
"""

from __future__ import annotations

import keyword
import re
import tokenize
from array import array
from collections.abc import Callable, Iterator
from typing import NamedTuple, overload

LIMIT = 99
_OPS = {"+", "and", "or", "&", "|"}
# how many times a continuation line is broken again: enough for a long chain in an argument of a
# call in a step of another long chain (each level is a bracket group opened, then its contents)
_MAX_DEPTH = 8
# the operators a step of a long chain (ExprLowerer.chunked) is broken before
# ... with Python's precedence of each (higher binds tighter)
_STEP_OPS = {"or": 1, "and": 2, "==": 3, "!=": 3, "<": 3, ">": 3, "<=": 3, ">=": 3, "|": 4, "^": 5,
             "&": 6, "<<": 7, ">>": 7, "+": 8, "-": 8, "*": 9, "/": 9, "//": 9, "%": 9}
# plain and augmented assignment: the expression to break starts after any of them (wrapping the
# whole ``x += a + b`` statement in parentheses would not be Python)
_ASSIGN = {"=", "+=", "-=", "*=", "/=", "//=", "%=", "**=", "@=", "&=", "|=", "^=", "<<=", ">>="}


def _one_line(text: str) -> Callable[[], str]:
    """A ``readline`` that gives ``text`` once, then the end: ``io.StringIO(text).readline`` keeps
    a copy of the text at four bytes a character and hands out another, 10 times the GPL source
    of ``1+1+...`` while its generated line is tokenized (issue 20)."""
    return _Reader(text).readline


class _Reader:
    """:func:`_one_line`'s reader: the text, then empty strings."""

    __slots__ = ("_text",)

    def __init__(self, text: str) -> None:
        self._text = text

    def readline(self) -> str:
        text, self._text = self._text, ""
        return text


class _Tok(NamedTuple):
    """A token of the line being broken, as :class:`_Tokens` hands it out."""

    type: int
    string: str
    start: int  # (columns: the text is one line)
    end: int


class _Tokens:
    """The tokens of one line, kept as three compact arrays (type, start, end; the text of a token
    is cut from the line when asked) rather than a record per token.

    A GPL expression of a million terms is one generated line of ~4 MB (issue 20): a record per
    token (a tuple, two column numbers and its text) cost 93 bytes per character of that line, 186
    times the GPL source; these arrays cost ~5.  A slice is a view of the same arrays, and
    ``toks[i]`` builds the :class:`_Tok` it names, so the code that breaks the line reads tokens as
    it did."""

    __slots__ = ("_text", "_types", "_starts", "_ends", "_lo", "_hi")

    def __init__(self, text: str, types: array[int], starts: array[int], ends: array[int],
                 lo: int = 0, hi: int | None = None) -> None:
        self._text, self._types, self._starts, self._ends = text, types, starts, ends
        self._lo, self._hi = lo, len(types) if hi is None else hi

    @classmethod
    def of(cls, text: str) -> _Tokens:
        """The tokens of ``text`` (one line) but its NEWLINE, NL and ENDMARKER; raises what
        ``tokenize`` raises on text that is not Python."""
        types, starts, ends = array("B"), array("i"), array("i")
        for t in tokenize.generate_tokens(_one_line(text)):
            if t.type not in (tokenize.NEWLINE, tokenize.NL, tokenize.ENDMARKER):
                types.append(t.type)
                starts.append(t.start[1])
                ends.append(t.end[1])
        return cls(text, types, starts, ends)

    def __len__(self) -> int:
        return self._hi - self._lo

    @overload
    def __getitem__(self, i: int) -> _Tok: ...
    @overload
    def __getitem__(self, i: slice) -> _Tokens: ...
    def __getitem__(self, i: int | slice) -> _Tok | _Tokens:
        if isinstance(i, slice):
            lo, hi, _ = i.indices(len(self))
            return _Tokens(self._text, self._types, self._starts, self._ends, self._lo + lo,
                           self._lo + max(lo, hi))
        if i < 0:
            i += len(self)
        if not 0 <= i < len(self):
            raise IndexError(i)
        k = self._lo + i
        start, end = self._starts[k], self._ends[k]
        return _Tok(self._types[k], self._text[start:end], start, end)

    def __iter__(self) -> Iterator[_Tok]:
        for i in range(len(self)):
            yield self[i]

    def __bool__(self) -> bool:
        return self._hi > self._lo


def wrap(indent: int, text: str, limit: int = LIMIT, depth: int = 0) -> list[tuple[int, str]]:
    """``(indent, text)`` lines for one logical line (unchanged when it fits); continuation lines
    that are still too long are broken again (a long argument of a long call).  A text that
    starts with spaces (the lowering writes a one-line body as ``"    x = ..."`` under its
    header) is that much further in: each four spaces are a level, so that breaking it never
    loses its text (a GoTo into a Select with a long subject came out as blank lines)."""
    stripped = text.lstrip(" ")
    if stripped != text and 4 * indent + len(text) > limit:
        levels = -(-(len(text) - len(stripped)) // 4)  # (a partial level counts as a whole one)
        return _wrap_nested(indent + levels, stripped, limit, depth, inside=False)
    return _wrap_nested(indent, text, limit, depth, inside=False)


def _wrap_nested(indent: int, text: str, limit: int, depth: int, inside: bool) -> list[tuple[int, str]]:
    """:func:`wrap`; ``inside``: the line is already within the brackets of an enclosing break."""
    lines = _wrap(indent, text, limit, inside)
    if len(lines) == 1 or depth > _MAX_DEPTH:
        return lines
    out: list[tuple[int, str]] = []
    for i, (ind, txt) in enumerate(lines):
        # the first line too, when it is a piece of the text (an operand packed without brackets
        # of its own) rather than the text's unchanged opening.  Every line of a text inside
        # brackets is inside them, its last one too (a piece "or f(x) != y" of a condition packed
        # without brackets of its own: in brackets of its own it would not be Python)
        if (i > 0 or txt != text) and 4 * ind + len(txt) > limit:
            out.extend(_wrap_nested(ind, txt, limit, depth + 1, inside=inside or i < len(lines) - 1))
        else:
            out.append((ind, txt))
    return out


def _wrap(indent: int, text: str, limit: int, inside: bool = False) -> list[tuple[int, str]]:
    if 4 * indent + len(text) <= limit:
        return [(indent, text)]
    if text.startswith("global "):
        names = text[len("global "):].split(", ")
        out: list[tuple[int, str]] = []
        cur: list[str] = []
        for n in names:
            if cur and 4 * indent + len("global " + ", ".join([*cur, n])) > limit:
                out.append((indent, "global " + ", ".join(cur)))
                cur = []
            cur.append(n)
        out.append((indent, "global " + ", ".join(cur)))
        return out
    if inside and _CHAIN_START.match(text):
        steps = _stream_steps(text)
        if steps:
            return _text_step_lines(indent, text, steps, limit)
    try:
        toks = _Tokens.of(text)
    except (tokenize.TokenError, IndentationError, SyntaxError):
        return [(indent, text)]
    comment = ""
    if toks and toks[-1].type == tokenize.COMMENT:
        comment = "  " + toks[-1].string
        toks = toks[:-1]
    if not toks:
        return [(indent, text)]
    body = text[: toks[-1].end]
    header = body.endswith(":") and toks[0].string in ("if", "elif", "while", "for", "return", "def")
    cont = indent + (2 if header and toks[0].string != "return" else 1)
    # where the expression starts: after the first top-level "=", or after a leading keyword
    start = next((i + 1 for i, tok in _top_level(toks)
                  if tok.type == tokenize.OP and tok.string in _ASSIGN), 0)
    if start == 0 and toks[0].string in ("if", "elif", "while", "return", "raise"):
        start = 1
    end = len(toks) - (1 if header and toks[-1].string == ":" else 0)
    expr = toks[start:end]
    if expr and expr[-1].type == tokenize.OP and expr[-1].string == ",":
        # an argument line of a call being packed ("a + b + c,"): the comma separates it from the
        # next argument and stays outside the break (inside, it would make a tuple, or worse)
        expr = expr[:-1]
    if not expr:
        return [(indent, text)]
    prefix = body[: expr[0].start]
    suffix = body[expr[-1].end:]
    # 0. the steps of a long operator chain, ``(_chain1 := ..., _chain1 := _chain1 + ..., ...)[-1]``
    #    opened by rule 3: one step a line, each broken before its operators
    if inside and not prefix and not suffix and not comment:
        steps = _chain_steps(expr)
        if steps:
            return _step_lines(indent, body, expr, steps, limit)
    # 1. top-level binary operators
    cuts = [i for i, tok in _top_level(expr)
            if i > 0 and tok.string in _OPS and tok.type in (tokenize.OP, tokenize.NAME)]
    if _balanced(expr) and cuts and not any(t.string in ("if", "else", "lambda") for t in expr):
        pieces = _pieces(body, expr, cuts)
        if inside and not prefix and not suffix and not comment:
            # the sole argument of a call already broken open: its brackets carry the continuation
            return _pack(indent, "", pieces, indent, limit, " ")
        lines = [(indent, prefix + "(" + comment)]
        lines.extend(_pack(cont, "", pieces, cont, limit, " "))
        lines.append((indent, ")" + suffix))
        return lines
    # 2. other binary operators (``*``, ``-``, comparisons): broken before the loosest of them
    if _balanced(expr) and not any(t.string in ("if", "else", "lambda") for t in expr):
        loose = _loosest_cuts(expr)
        if loose:
            return _operator_lines(indent, cont, prefix, suffix, comment, body, expr, loose, limit, inside)
    # 3. a call closing at the end of the expression: pack its arguments
    if expr[-1].string == ")":
        depth = 0
        open_at = -1
        for i, tok in enumerate(expr):
            if tok.type == tokenize.OP and tok.string in "([{":
                if depth == 0:
                    open_at = i
                depth += 1
            elif tok.type == tokenize.OP and tok.string in ")]}":
                depth -= 1
        if open_at >= 0 and expr[open_at].string == "(" and open_at + 1 < len(expr) - 1:
            inner = expr[open_at + 1:-1]
            commas = [i for i, tok in _top_level(inner) if tok.string == ","]
            args: list[str] = []
            last = 0
            for c in [*commas, len(inner)]:
                seg = inner[last:c]
                if seg:
                    piece = body[seg[0].start:seg[-1].end]
                    args.append(piece + ("," if c < len(inner) else ""))
                last = c + 1
            head = body[: expr[open_at].end]
            lines = [(indent, head + comment)]
            lines.extend(_pack(cont, "", args, cont, limit, " "))
            lines.append((indent, ")" + suffix))
            return lines
    # 4. otherwise open the longest top-level bracket group: its contents go on a continuation
    #    line (broken again if still too long), the closing bracket and the rest of the line after
    #    ("f(<args>) != x" in a long condition)
    group = _longest_group(toks)
    if group is not None:
        open_tok, close_tok = toks[group[0]], toks[group[1]]
        inner = body[open_tok.end:close_tok.start].strip()
        return [(indent, body[: open_tok.end] + comment), (cont, inner), (indent, body[close_tok.start:])]
    return [(indent, text)]


def _chain_steps(expr: _Tokens) -> list[tuple[int, int]] | None:
    """Where the steps of the tuple that lowers a long operator chain (ExprLowerer.chunked) are
    in ``expr``, as (first, past-last) token indices; None for any other text.  Only that tuple is
    recognised (its elements assign with ``:=``) so that no other output changes shape."""
    commas: list[int] = []
    assigns = False
    for i, tok in _top_level(expr):  # (one pass, no list of the line's top-level tokens)
        if tok.type == tokenize.OP and tok.string == ",":
            commas.append(i)
        elif tok.string == ":=":
            assigns = True
    if not commas or not assigns:
        return None
    steps = [(a + 1, b) for a, b in zip([-1, *commas], [*commas, len(expr)])]
    return None if any(a >= b for a, b in steps) else steps


# the start of the steps of a long operator chain (ExprLowerer.chunked: ``_chain1 := ...``; a GPL
# name is never written ``_chain1`` in Python, py_ident makes it ``_u_chain1``)
_CHAIN_START = re.compile(r"_chain[0-9]+ := ")


def _stream_steps(text: str) -> list[tuple[int, int]] | None:
    """The steps of a long chain's tuple opened by rule 4 (``_chain1 := ..., _chain1 := _chain1
    + ..., ...``) as (start, end) offsets in ``text``, found by reading its tokens as they come
    rather than keeping them: the tokens of a million-term chain's line, even in arrays, were 9
    times its GPL source (issue 20).  None for any other text (a comment, a trailing comma, no
    ``:=`` at the top level, not Python), which the ordinary rules then break."""
    commas: list[int] = []
    assigns = False
    depth = 0
    try:
        for tok in tokenize.generate_tokens(_one_line(text)):
            if tok.type == tokenize.OP:
                if tok.string in "([{":
                    depth += 1
                elif tok.string in ")]}":
                    depth -= 1
                elif depth == 0 and tok.string == ",":
                    commas.append(tok.start[1])
                elif depth == 0 and tok.string == ":=":
                    assigns = True
            elif tok.type == tokenize.COMMENT:
                return None
    except (tokenize.TokenError, IndentationError, SyntaxError):
        return None
    if not commas or not assigns:
        return None
    end = len(text.rstrip())
    steps: list[tuple[int, int]] = []
    for a, b in zip([-1, *commas], [*commas, end]):
        a += 1
        while a < b and text[a] == " ":
            a += 1
        if a >= b:
            return None
        steps.append((a, b))
    return steps


def _text_step_lines(indent: int, text: str, steps: list[tuple[int, int]], limit: int) -> list[tuple[int, str]]:
    """:func:`_step_lines` for the steps at ``steps`` in ``text``, each tokenized on its own."""
    lines: list[tuple[int, str]] = []
    for k, (a, b) in enumerate(steps):
        step = text[a:b]
        seg = _Tokens.of(step)
        lines.extend(_step_pack(indent, step, seg, limit, last=k == len(steps) - 1))
    return lines


def _step_pack(indent: int, body: str, seg: _Tokens, limit: int, last: bool) -> list[tuple[int, str]]:
    """The lines of one step ``seg`` of a long chain, cut before its loosest top-level operators,
    a comma after the last unless it is the ``last`` step."""
    ops = [i for i, tok in _top_level(seg) if i > 0 and _binary_at(seg, i)]
    # cut only before the loosest operators (``a - 3 * b`` breaks before ``-``, not ``*``)
    loosest = min((_STEP_OPS[seg[i].string] for i in ops), default=0)
    pieces = _pieces(body, seg, [i for i in ops if _STEP_OPS[seg[i].string] == loosest])
    lines = _pack(indent, "", pieces, indent, limit - 1, " ")
    if not last:
        lines[-1] = (lines[-1][0], lines[-1][1] + ",")
    return lines


def _loosest_cuts(expr: _Tokens) -> list[int]:
    """The top-level binary operators of ``expr`` that bind loosest (``a * f(x) * g(y)``: both
    ``*``; ``a - 3 * b``: the ``-``), the places a line may be broken before."""
    ops = [i for i, tok in _top_level(expr) if i > 0 and _binary_at(expr, i)]
    loosest = min((_STEP_OPS[expr[i].string] for i in ops), default=0)
    return [i for i in ops if _STEP_OPS[expr[i].string] == loosest]


def _operator_lines(indent: int, cont: int, prefix: str, suffix: str, comment: str, body: str,
                    expr: _Tokens, cuts: list[int], limit: int,
                    inside: bool) -> list[tuple[int, str]]:
    """Rule 1's shape for any operator: parenthesised, broken before the operators at ``cuts``."""
    pieces = _pieces(body, expr, cuts)
    if inside and not prefix and not suffix and not comment:
        return _pack(indent, "", pieces, indent, limit, " ")
    return [(indent, prefix + "(" + comment), *_pack(cont, "", pieces, cont, limit, " "), (indent, ")" + suffix)]


def _binary_at(toks: _Tokens, i: int) -> bool:
    """Whether ``toks[i]`` is a binary operator a chain step may be broken before: any of the
    arithmetic, bitwise and Boolean ones (a step is one operator repeated, ``-`` and ``*`` as
    often as ``+``), but not a sign (``x - -1``: the token before a sign is not an operand)."""
    tok, prev = toks[i], toks[i - 1]
    if tok.string not in _STEP_OPS or tok.type not in (tokenize.OP, tokenize.NAME):
        return False
    if tok.string in ("and", "or"):
        return True
    return prev.type in (tokenize.NUMBER, tokenize.STRING) or prev.string in (")", "]", "}") \
        or (prev.type == tokenize.NAME and not keyword.iskeyword(prev.string))


def _step_lines(indent: int, body: str, expr: _Tokens, steps: list[tuple[int, int]],
                limit: int) -> list[tuple[int, str]]:
    """One line per step (its continuation lines start with an operator), a comma after each but
    the last: the comma stays on the step's last line, inside the tuple's own brackets.  A step is
    cut into pieces only when its lines are made: the pieces of all steps at once (a string per
    operator) were 30 times the GPL source of ``1+1+...`` (issue 20)."""
    lines: list[tuple[int, str]] = []
    for k, (a, b) in enumerate(steps):
        lines.extend(_step_pack(indent, body, expr[a:b], limit, last=k == len(steps) - 1))
    return lines


def _top_level(toks: _Tokens) -> Iterator[tuple[int, _Tok]]:
    """The tokens outside every bracket pair (brackets themselves excluded), with their index:
    the only places a line may be cut or an assignment found without changing its meaning."""
    depth = 0
    for i, tok in enumerate(toks):
        if tok.type == tokenize.OP and tok.string in "([{":
            depth += 1
        elif tok.type == tokenize.OP and tok.string in ")]}":
            depth -= 1
        elif depth == 0:
            yield i, tok


def _balanced(toks: _Tokens) -> bool:
    """Every bracket opened in ``toks`` is closed there (a slice of a line may cut a group)."""
    opened = sum(1 for t in toks if t.type == tokenize.OP and t.string in "([{")
    return opened == sum(1 for t in toks if t.type == tokenize.OP and t.string in ")]}")


def _longest_group(toks: _Tokens) -> tuple[int, int] | None:
    """Indices of the opening and closing token of the longest depth-0 bracket pair with
    something inside, or None."""
    best: tuple[int, int] | None = None
    best_len = 0
    depth = 0
    open_at = -1
    for i, tok in enumerate(toks):
        if tok.type != tokenize.OP:
            continue
        if tok.string in "([{":
            if depth == 0:
                open_at = i
            depth += 1
        elif tok.string in ")]}":
            depth -= 1
            if depth == 0 and i > open_at + 1:
                span = tok.start - toks[open_at].end
                if span > best_len:
                    best, best_len = (open_at, i), span
    return best


def _pieces(body: str, expr: _Tokens, cuts: list[int]) -> list[str]:
    bounds = [0, *cuts, len(expr)]
    out = []
    for a, b in zip(bounds, bounds[1:]):
        out.append(body[expr[a].start:expr[b - 1].end])
    return out


def _pack(indent: int, first_prefix: str, pieces: list[str], cont: int, limit: int,
          sep: str) -> list[tuple[int, str]]:
    """Greedy fill: as many pieces per line as fit, continuation lines at ``cont``."""
    lines: list[tuple[int, str]] = []
    cur_indent, cur = indent, first_prefix
    fresh = True
    for piece in pieces:
        candidate = cur + ("" if fresh else sep) + piece
        if not fresh and 4 * cur_indent + len(candidate) > limit - 1:
            lines.append((cur_indent, cur))
            cur_indent, cur = cont, piece
        else:
            cur = candidate
        fresh = False
    lines.append((cur_indent, cur))
    return lines

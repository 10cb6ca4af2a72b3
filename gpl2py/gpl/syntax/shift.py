"""Moving what is below an edit that added or removed lines (the language server, after Enter).

When an edit inside one procedure changes a file's number of lines, ``syntax/reparse.py`` parses
that procedure again, and every line below it moves by the same number of lines: nothing else
about the nodes there changes (columns change only on the edited lines, which are in the
procedure).  A :class:`Shift` says which lines moved and by how much; :class:`Moves` moves
the nodes in place -- the same objects, so whatever later phases keyed by them (the semantic
pass's symbols and Infos, the lowering's memo) still holds -- and :meth:`Shift.diagnostics` moves
the diagnostics kept for them.  The later phases move the positions they copied out of the nodes
themselves (``semantics/warm.py``, ``pipeline.py``).

Why in place and not an offset applied on read: every phase reads a node's line directly
(``node._line``, ``node.span``), and a per-procedure offset would have to be added in each of them;
moving the nodes below the edit is one walk of what is there (docs/design/lsp.md, "Lines added or
removed").
"""

from __future__ import annotations

from array import array
from typing import NamedTuple

from gpl2py.diagnostics import Diagnostic
from gpl2py.gpl.syntax import ast as A
from gpl2py.source import Span

#: The fields of a node that hold comments (one, or a tuple of them).
_COMMENT_FIELDS = ("leading_comments", "trailing_comment", "header_comment", "end_comments", "end_comment")


class Shift(NamedTuple):
    """Lines of ``path`` after line ``after`` (of the old text) move by ``delta`` (negative: up)."""

    path: str
    after: int
    delta: int

    def line(self, line: int) -> int:
        return line + self.delta if line > self.after else line

    def span(self, span: Span | None) -> Span | None:
        """``span`` moved: its start and its end each moves if it is below the edit (a span
        around the edit, such as its procedure's, grows or shrinks)."""
        if span is None or span[0] != self.path or span[3] <= self.after:
            return span
        return tuple.__new__(Span, (span[0], self.line(span[1]), span[2], span[3] + self.delta, span[4]))

    def moves(self, span: Span | None) -> bool:
        """Whether :meth:`span` changes ``span``."""
        return span is not None and span[0] == self.path and span[3] > self.after

    def diagnostic(self, d: Diagnostic) -> Diagnostic:
        if not self.moves(d.span):
            return d
        return Diagnostic(d.severity, d.code, d.message, self.span(d.span))

    def diagnostics(self, diags: list[Diagnostic]) -> list[Diagnostic]:
        """``diags`` with those below the edit moved (the same list when none is)."""
        if not any(self.moves(d.span) for d in diags):
            return diags
        return [self.diagnostic(d) for d in diags]


class Moves:
    """What lies under each member of one file, flattened the first time it moves, so that the
    next edit adding lines above it moves it by a loop over lists (about a tenth of a walk).

    Typing Enter, again and again, in one procedure moves the same members below it each time:
    walking their trees was a third of such an edit in the largest file of the TCS project
    (docs/design/lsp.md, "Lines added or removed").  The lists stay right because nothing changes
    a node once parsed but a move: an edit parses a procedure again into new nodes, and the
    containers on its way are copied (``reparse._replaced``), so what a list holds is either the
    file's or a member :meth:`forget` dropped.  Kept by the caller with the file's tree (the
    pipeline's parse memo), one per file; a file parsed whole starts a new one."""

    __slots__ = ("_flat",)

    def __init__(self) -> None:
        # id(member) -> (member, its flattened positions); the member is held, so its id is not
        # reused while the entry lives
        self._flat: dict[int, tuple[A.Node, _Flat]] = {}

    def move(self, members: list[A.Node], delta: int) -> None:
        """Move ``members`` and everything under them ``delta`` lines, in place."""
        flat = self._flat
        for member in members:
            kept = flat.get(id(member))
            if kept is None or kept[0] is not member:
                kept = flat[id(member)] = (member, _flatten([member]))
            kept[1].move(delta)

    def forget(self, member: A.Node) -> None:
        """Drop what is kept of ``member``: an edit replaced it (a procedure parsed again, a
        container copied), so its nodes are no longer, or no longer all, the file's."""
        kept = self._flat.get(id(member))
        if kept is not None and kept[0] is member:
            del self._flat[id(member)]


class _Flat(NamedTuple):
    """Every position under some nodes: the nodes (each once: the parser gives the declarators
    of ``Dim a, b As T`` one TypeRef, the one kind of node it shares), their comments, and the
    Chains, whose literal operands' lines are numbers in an array."""

    nodes: list[A.Node]
    comments: list[A.Comment]
    chains: list[A.Chain]

    def move(self, delta: int) -> None:
        for node in self.nodes:
            node._line += delta
            node._end_line += delta
        new = tuple.__new__
        for c in self.comments:
            s = c.span
            c.span = new(Span, (s[0], s[1] + delta, s[2], s[3] + delta, s[4]))
        for chain in self.chains:
            chain.lines = array(chain.lines.typecode, [n + delta if n else 0 for n in chain.lines])


def _flatten(nodes: list[A.Node]) -> _Flat:
    """The positions under ``nodes`` (:class:`_Flat`).  Written for speed: a node's fields are
    read through a plan made once per class, rather than ``Node.children``'s generator."""
    seen: set[int] = set()
    found: list[A.Node] = []
    comments: list[A.Comment] = []
    chains: list[A.Chain] = []
    stack: list[A.Node | None] = list(nodes)
    pop, push, extend, keep = stack.pop, stack.append, stack.extend, found.append
    plans = _PLANS
    while stack:
        node = pop()
        if node is None:
            continue
        cls = type(node)
        plan = plans.get(cls) or _plan(cls)
        kids, fields, kind = plan
        if kind is _SHARED:
            if id(node) in seen:
                continue
            seen.add(id(node))
        keep(node)
        for name in fields:
            value = getattr(node, name)
            if type(value) is tuple:
                comments.extend(value)
            elif value is not None:
                comments.append(value)
        if kind is _CHAIN:
            assert isinstance(node, A.Chain)
            chains.append(node)
            push(node.first)
            extend(x for x in node.operands if isinstance(x, A.Node))
            continue
        for name in kids:
            value = getattr(node, name)
            if type(value) is list:
                extend(value)
            else:
                push(value)
    # in the order they lie in memory: a move then reads it in order (twice as fast as in the
    # tree's order, measured on PARobot.gpl: a node's fields are what a move waits for)
    found.sort(key=id)
    comments.sort(key=id)
    return _Flat(found, comments, chains)


def shift_comments(comments: tuple[A.Comment, ...], delta: int) -> tuple[A.Comment, ...]:
    return tuple(_comment(c, delta) for c in comments)


def _comment(c: A.Comment, delta: int) -> A.Comment:
    s = c.span
    return A.Comment(tuple.__new__(Span, (s[0], s[1] + delta, s[2], s[3] + delta, s[4])), c.text, c.directive)


_SHARED, _CHAIN = "shared", "chain"
#: By node class: its child fields, its comment fields, and whether the tree may share it or it
#: is a Chain (whose literal operands' lines are numbers in an array).
_PLANS: dict[type, tuple[tuple[str, ...], tuple[str, ...], str | None]] = {}


def _plan(cls: type) -> tuple[tuple[str, ...], tuple[str, ...], str | None]:
    slots = {name for k in cls.__mro__ for name in getattr(k, "__slots__", ())}
    kind = _SHARED if cls is A.TypeRef else _CHAIN if cls is A.Chain else None
    plan = _PLANS[cls] = (cls._children, tuple(n for n in _COMMENT_FIELDS if n in slots), kind)  # type: ignore[attr-defined]
    return plan


__all__ = ["Moves", "Shift", "shift_comments"]

"""Moving what is below an edit that added or removed lines (the language server, after Enter).

When an edit inside one procedure changes a file's number of lines, ``syntax/reparse.py`` parses
that procedure again, and every line below it moves by the same number of lines: nothing else
about the nodes there changes (columns change only on the edited lines, which are in the
procedure).  A :class:`Shift` says which lines moved and by how much; :func:`shift_nodes` moves
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


def shift_nodes(nodes: list[A.Node], delta: int, seen: set[int] | None = None) -> None:
    """Move ``nodes`` and everything under them (their comments too) ``delta`` lines, in place.
    A node is moved once even where the tree shares it (the parser gives the declarators of
    ``Dim a, b As T`` one TypeRef, the one kind of node it shares).  Written for speed: it is
    what an edit adding a line near the top of a large file costs (a node's fields read through
    a plan made once per class, rather than ``Node.children``'s generator)."""
    seen = set() if seen is None else seen
    stack: list[A.Node | None] = list(nodes)
    pop, push, extend = stack.pop, stack.append, stack.extend
    plans = _PLANS
    while stack:
        node = pop()
        if node is None:
            continue
        cls = type(node)
        plan = plans.get(cls) or _plan(cls)
        kids, comments, kind = plan
        if kind is _SHARED:
            if id(node) in seen:
                continue
            seen.add(id(node))
        node._line += delta
        node._end_line += delta
        for name in comments:
            value = getattr(node, name)
            if value:
                setattr(node, name, shift_comments(value, delta) if type(value) is tuple else _comment(value, delta))
        if kind is _CHAIN:
            assert isinstance(node, A.Chain)
            node.lines = array(node.lines.typecode, [n + delta if n else 0 for n in node.lines])
            push(node.first)
            extend(x for x in node.operands if isinstance(x, A.Node))
            continue
        for name in kids:
            value = getattr(node, name)
            if type(value) is list:
                extend(value)
            else:
                push(value)


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


__all__ = ["Shift", "shift_comments", "shift_nodes"]

"""Parsing again only the procedure an edit is in (the language server, after a keystroke).

An editor sends the whole text after each change, and most changes are typing inside one
procedure: the other lines of the file are what they were.  :func:`reparse_procedure` then parses
the procedure's lines alone, where they are (blank lines above them, so every position is the
file's), inside a container of the same kind, and gives a tree that is the old one with that
procedure replaced: every other node of the file is the old node, which is what lets the later
phases (semantics/warm.py, the lowering's memo) redo only that procedure.

The changed lines are found as what is left between the longest common head and the longest
common tail of the old and new lines.  When the edit added or removed lines (Enter, a pasted block,
a deleted line), every node below the procedure is moved that many lines, in place
(``syntax/shift.py``): nothing else about them changes, so they stay the nodes the later phases
know, and the :class:`~gpl2py.gpl.syntax.shift.Shift` returned tells those phases what to move in
what they copied from them (symbols' spans, kept diagnostics).

It declines (returns None, and the caller parses the whole file) unless the result is sure to be a
full parse's: every changed line is strictly inside one procedure of a Module or Class (neither
its first line nor its ``End`` line changed), and the procedure parsed alone ends on the line its
``End`` line has moved to, with every diagnostic of its parse on its lines.  A procedure's parse
depends on nothing before its first line (a declaration starts a line) nor after its ``End`` line
(which closes it), so then it is the one a full parse makes; and what follows the ``End`` line
parses as it did, only lower or higher.
"""

from __future__ import annotations

import copy
from itertools import compress, count
from operator import ne

from gpl2py.diagnostics import Diagnostic, DiagnosticSink
from gpl2py.gpl.syntax import ast as A
from gpl2py.gpl.syntax.parser import parse
from gpl2py.gpl.syntax.shift import Moves, Shift, shift_comments
from gpl2py.source import LINE_BREAK, SourceFile


def reparse_procedure(old_text: str, old_unit: A.SourceUnit, old_diags: list[Diagnostic],
                      source: SourceFile, moves: Moves | None = None,
                      ) -> tuple[A.SourceUnit, list[Diagnostic], Shift | None] | None:
    """The tree and diagnostics of ``source`` made from those of the same file's previous text
    (``old_text``, parsed as ``old_unit`` with ``old_diags``) by parsing the one procedure that
    changed, or None when that is not sure to equal a full parse (module docstring).  When the
    edit added or removed lines, the nodes below the procedure are moved in place (the old tree's
    too: they are shared) and the third item says how (:class:`~gpl2py.gpl.syntax.shift.Shift`),
    for the later phases to move what they copied from them; else it is None.  ``moves``: what the
    file's earlier edits kept of the walks of the nodes they moved (the same file's, each time:
    the caller keeps it with the tree, and makes a new one when the file is parsed whole)."""
    old_lines = _lines(old_text)
    new_lines = _lines(source.text)
    delta = len(new_lines) - len(old_lines)
    # the changed lines, old_lines[same:old_end] -> new_lines[same:old_end + delta]: the longest
    # common head, then the longest common tail of what is left
    same = _common(old_lines, new_lines, min(len(old_lines), len(new_lines)), head=True)
    old_end = len(old_lines) - _common(old_lines, new_lines, min(len(old_lines), len(new_lines)) - same, head=False)
    if delta == 0 and same == old_end:
        return None  # (the same text)
    # the changed lines of the old text, 1-based: same + 1 .. old_end (none when lines were only added)
    chain = _enclosing(old_unit, same + 1, old_end)
    if chain is None:
        return None
    proc = chain[-1]
    assert isinstance(proc, A.ProcDecl)
    first, last = proc.span.line, proc.span.end_line
    if first < 2 or new_lines[first - 1][:proc.span.col - 1].strip():
        return None  # (nothing but indentation may precede the declaration on its line)
    container = chain[-2]
    header = "Module Reparsed" if isinstance(container, A.ModuleDecl) else "Class Reparsed"
    closer = "End Module" if isinstance(container, A.ModuleDecl) else "End Class"
    new_last = last + delta
    text = "\n" * (first - 2) + header + "\n" + "\n".join(new_lines[first - 1:new_last]) + "\n" + closer + "\n"
    sink = DiagnosticSink()
    unit = parse(SourceFile(source.path, text), sink)
    found = unit.members[0].members if len(unit.members) == 1 and isinstance(
        unit.members[0], (A.ModuleDecl, A.ClassDecl)) else []
    if len(found) != 1 or not isinstance(found[0], A.ProcDecl):
        return None
    new = found[0]
    if (new.span.line, new.span.end_line) != (first, new_last) or any(
            d.span is None or not first <= d.span.line <= new_last for d in sink):
        return None
    if delta and old_unit.compact_dims:
        return None  # (see _replaced)
    new.leading_comments = proc.leading_comments  # (the comments above it, which were not parsed)
    shift = Shift(source.path, old_end, delta) if delta else None
    diags = _spliced(old_diags, list(sink), source.path, first, last, shift)
    replaced = _replaced(old_unit, chain, new, delta, moves if moves is not None else Moves())
    replaced.compact_dims = old_unit.compact_dims or unit.compact_dims
    return replaced, diags, shift


def _common(a: list[str], b: list[str], most: int, head: bool) -> int:
    """How many lines ``a`` and ``b`` have in common at their head (at their tail when not
    ``head``), at most ``most``.  The first unequal pair is found by iterators that run in C
    (a loop over the lines of a large file in Python took a quarter of parsing one procedure)."""
    unequal = map(ne, a, b) if head else map(ne, reversed(a), reversed(b))
    return min(next(compress(count(), unequal), most), most)


def _lines(text: str) -> list[str]:
    """``text``'s lines as the lexer counts them (``source.LINE_BREAK``): split at line feeds
    alone, a tenth of the regular expression's time, when the text has no carriage return."""
    text = text.removeprefix("\ufeff")
    return text.split("\n") if "\r" not in text else LINE_BREAK.split(text)


def _enclosing(unit: A.SourceUnit, first: int, last: int) -> list[A.Node] | None:
    """The containers from ``unit`` down to the procedure of a Module or Class whose lines strictly
    hold ``first``..``last`` (neither its declaration line nor its End line)."""
    chain: list[A.Node] = [unit]
    members = unit.members
    while True:
        inside = next((m for m in members if m.span.line <= first and last <= m.span.end_line), None)
        if isinstance(inside, (A.ModuleDecl, A.ClassDecl)):
            chain.append(inside)
            members = inside.members
            continue
        if isinstance(inside, A.ProcDecl) and inside.span.line < first and last < inside.span.end_line \
                and len(chain) > 1:
            chain.append(inside)
            return chain
        return None


def _replaced(unit: A.SourceUnit, chain: list[A.Node], new: A.ProcDecl, delta: int, moves: Moves) -> A.SourceUnit:
    """A copy of ``unit`` with ``new`` in place of the last node of ``chain``: the containers on
    the way are new nodes (so whoever compares trees sees which changed), the rest is shared.
    ``delta``: lines the edit added (removed, negative): the containers on the way end that many
    lines further, and what follows the procedure in them is moved (in place: it is shared).

    Not when the file holds a long Dim compactly (``unit.compact_dims``, ast.CompactDeclarators):
    its positions are in arrays, and the declarators made of them when asked (which the analysis
    keeps as its variables' nodes, compared by position) would keep the old lines; a file with one
    is parsed whole when lines are added or removed (:func:`reparse_procedure`)."""
    replacement: A.Node = new
    for parent, child in zip(reversed(chain[:-1]), reversed(chain[1:])):
        twin = copy.copy(parent)
        members = parent.members  # type: ignore[attr-defined]
        twin.members = [replacement if m is child else m for m in members]  # type: ignore[attr-defined]
        moves.forget(child)  # (replaced: parsed again, or copied)
        if delta:
            moves.move(members[members.index(child) + 1:], delta)
            twin._end_line += delta
            # (its comments after the procedure: those above its End line, the one on that line)
            twin.end_comments = shift_comments(twin.end_comments, delta)  # type: ignore[attr-defined]
            if getattr(twin, "end_comment", None) is not None:
                twin.end_comment = shift_comments((twin.end_comment,), delta)[0]  # type: ignore[attr-defined]
        replacement = twin
    assert isinstance(replacement, A.SourceUnit)
    return replacement


def _spliced(old: list[Diagnostic], new: list[Diagnostic], path: str, first: int, last: int,
             shift: Shift | None) -> list[Diagnostic]:
    """The old diagnostics with those on lines ``first``..``last`` of ``path`` replaced by ``new``,
    those below moved by ``shift``."""
    def place(d: Diagnostic) -> int:  # -1 before those lines, 0 on them, 1 after (or elsewhere)
        if d.span is None or d.span.file != path or d.span.line > last:
            return 1
        return -1 if d.span.line < first else 0

    after = [d for d in old if place(d) > 0]
    return [d for d in old if place(d) < 0] + new + (shift.diagnostics(after) if shift is not None else after)


__all__ = ["reparse_procedure"]

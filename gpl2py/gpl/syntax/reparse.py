"""Parsing again only the procedure an edit is in (the language server, after a keystroke).

An editor sends the whole text after each change, and most changes are typing inside one
procedure: the other lines of the file are what they were.  :func:`reparse_procedure` then parses
the procedure's lines alone, where they are (blank lines above them, so every position is the
file's), inside a container of the same kind, and gives a tree that is the old one with that
procedure replaced: every other node of the file is the old node, which is what lets the later
phases (semantics/warm.py, the lowering's memo) redo only that procedure.

It declines (returns None, and the caller parses the whole file) unless the result is sure to be a
full parse's: the file has as many lines as before, every changed line is strictly inside one
procedure of a Module or Class (neither its first line nor its ``End`` line changed), and the
procedure parsed alone ends on the line it ended on, with every diagnostic of its parse on its
lines.  A procedure's parse depends on nothing before its first line (a declaration starts a line)
nor after its ``End`` line (which closes it), so then it is the one a full parse makes.
"""

from __future__ import annotations

import copy

from gpl2py.diagnostics import Diagnostic, DiagnosticSink
from gpl2py.gpl.syntax import ast as A
from gpl2py.gpl.syntax.parser import parse
from gpl2py.source import LINE_BREAK, SourceFile


def reparse_procedure(old_text: str, old_unit: A.SourceUnit, old_diags: list[Diagnostic],
                      source: SourceFile) -> tuple[A.SourceUnit, list[Diagnostic]] | None:
    """The tree and diagnostics of ``source`` made from those of the same file's previous text
    (``old_text``, parsed as ``old_unit`` with ``old_diags``) by parsing the one procedure that
    changed, or None when that is not sure to equal a full parse (module docstring)."""
    old_lines = LINE_BREAK.split(old_text.removeprefix("\ufeff"))
    new_lines = LINE_BREAK.split(source.text.removeprefix("\ufeff"))
    if len(old_lines) != len(new_lines):
        return None
    changed = [i + 1 for i, (a, b) in enumerate(zip(old_lines, new_lines)) if a != b]
    if not changed:
        return None
    chain = _enclosing(old_unit, changed[0], changed[-1])
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
    text = "\n" * (first - 2) + header + "\n" + "\n".join(new_lines[first - 1:last]) + "\n" + closer + "\n"
    sink = DiagnosticSink()
    unit = parse(SourceFile(source.path, text), sink)
    found = unit.members[0].members if len(unit.members) == 1 and isinstance(
        unit.members[0], (A.ModuleDecl, A.ClassDecl)) else []
    if len(found) != 1 or not isinstance(found[0], A.ProcDecl):
        return None
    new = found[0]
    if (new.span.line, new.span.end_line) != (first, last) or any(
            d.span is None or not first <= d.span.line <= last for d in sink):
        return None
    new.leading_comments = proc.leading_comments  # (the comments above it, which were not parsed)
    return _replaced(old_unit, chain, new), _spliced(old_diags, list(sink), source.path, first, last)


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


def _replaced(unit: A.SourceUnit, chain: list[A.Node], new: A.ProcDecl) -> A.SourceUnit:
    """A copy of ``unit`` with ``new`` in place of the last node of ``chain``: the containers on
    the way are new nodes (so whoever compares trees sees which changed), the rest is shared."""
    replacement: A.Node = new
    for parent, child in zip(reversed(chain[:-1]), reversed(chain[1:])):
        twin = copy.copy(parent)
        twin.members = [replacement if m is child else m for m in parent.members]  # type: ignore[attr-defined]
        replacement = twin
    assert isinstance(replacement, A.SourceUnit)
    return replacement


def _spliced(old: list[Diagnostic], new: list[Diagnostic], path: str, first: int, last: int) -> list[Diagnostic]:
    """The old diagnostics with those on lines ``first``..``last`` of ``path`` replaced by ``new``."""
    def place(d: Diagnostic) -> int:  # -1 before those lines, 0 on them, 1 after (or elsewhere)
        if d.span is None or d.span.file != path or d.span.line > last:
            return 1
        return -1 if d.span.line < first else 0

    return [d for d in old if place(d) < 0] + new + [d for d in old if place(d) > 0]


__all__ = ["reparse_procedure"]

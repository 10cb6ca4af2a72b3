"""Code that keeps an error (docs/design/lowering.md, "Code that keeps an error"), in every front end.

A construct the analysis could give no meaning -- an undeclared name, a Sub used as a value, a store
into something that is not a variable, a GoTo to no label, a line the parser could not read -- is
translated only when its error is kept (``--keep-going``) or ignored (``--ignore``, a ``' gpl2py:
ignore`` comment).  It becomes a call of ``compile_error`` that raises, when the program reaches
it, the controller's error for the fault (``gpl2py.messages.RUNTIME_CODES``: -729 *Undefined
symbol* for an undeclared name), so the rest of the program runs, the line fails as the
controller's compiler said it would, and a Try/Catch around it receives the code.

Which error took a construct's meaning is read from the diagnostics (kept or ignored) reported on
the construct's lines: the passes that leave a construct without meaning report why at it, and
the rule is the same for every pass and every kind of construct.  The GPL front end
(``gpl2py.gpl.lower``) and the V+ one (``gpl2py.vplus.lower``) both read it here, each with its
messages' run-time codes (``gpl2py.messages.RUNTIME_CODES``, ``gpl2py.vplus.messages.RUNTIME_CODES``).
"""

from __future__ import annotations

from collections.abc import Mapping

from gpl2py import messages as M
from gpl2py.diagnostics import Diagnostic, DiagnosticSink
from gpl2py.source import Span

#: How many lines of a construct (a statement continued over many) are searched for its error.
_LINES_SEARCHED = 64


class KeptErrors:
    """The errors reported so far (kept and ignored) by file and line, for :meth:`at`."""

    def __init__(self, sink: DiagnosticSink, fallback: int = M.COMPILATION_ERRORS,
                 codes: Mapping[str, int] | None = None) -> None:
        self.sink = sink
        self.fallback = fallback  # the code when the error has none of its own (GPL: -742)
        #: each message's run-time code: GPL's (messages.RUNTIME_CODES) unless a front end's own
        self.codes = codes
        self._seen = -1  # the size of the sink the index was made from
        self._by_line: dict[tuple[str, int], Diagnostic] = {}

    def at(self, span: Span | None) -> tuple[int, str]:
        """The controller's error code and the subject for a construct at ``span``: those of the
        first error on its lines (the leftmost, when a line has several).  No error there (one
        reported on a line of a statement continued past the searched lines) is -742
        *Compilation errors*, what the controller answers for a project that did not compile
        (``fallback``: V+ has its own)."""
        found = self._first(span, whole=True) if span is not None else None
        if found is None:
            return self.fallback, "an error reported at translation"
        runtime = M.message(found.code).runtime if self.codes is None else self.codes.get(found.code)
        return runtime if runtime is not None else self.fallback, f"{found.code}: {found.message}"

    def any(self) -> bool:
        """Whether any error was reported (an ordinary translation has none)."""
        return bool(self._index())

    def on_lines(self, span: Span, whole: bool) -> bool:
        """Whether an error was reported on the lines of ``span`` (``whole``), or on its first."""
        return self._first(span, whole) is not None

    def _first(self, span: Span, whole: bool) -> Diagnostic | None:
        index = self._index()
        last = min(span.end_line, span.line + _LINES_SEARCHED - 1) if whole else span.line
        for line in range(span.line, last + 1):
            found = index.get((span.file, line))
            if found is not None:
                return found
        return None

    def _index(self) -> dict[tuple[str, int], Diagnostic]:
        """The first error of each line, rebuilt when the sink has grown since (an ordinary
        translation reports a few warnings while it lowers, and has no error to index)."""
        size = len(self.sink) + len(self.sink.ignored_errors)
        if size != self._seen:
            self._seen = size
            self._by_line = {}
            errors = [d for d in [*self.sink.errors, *self.sink.ignored_errors] if d.span is not None]
            for d in sorted(errors, key=lambda d: d.span.col if d.span is not None else 0):
                assert d.span is not None
                self._by_line.setdefault((d.span.file, d.span.line), d)
        return self._by_line

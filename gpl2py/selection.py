"""Which diagnostics a run reports: ``--select``/``--ignore`` (or ``[tool.gpl2py]``) by code or
prefix, and ``' gpl2py: ignore[GPL2014]`` comments on a diagnostic's line.

A :class:`Selection` is the filter of a :class:`~gpl2py.diagnostics.DiagnosticSink`: a diagnostic
it does not keep is never added, so everything downstream -- the exit status, the summary counts,
the decision that errors stop the translation, the cache entry -- sees the same, filtered, set.

Decisions:

* **Codes and prefixes.**  ``GPL2014`` is one code; ``GPL20`` every ``GPL20xx``; ``GPL`` all of
  them.  When both lists match a code, the longer (more specific) entry wins, so
  ``--select GPL2 --ignore GPL2014`` reports every ``GPL2xxx`` but ``GPL2014``, and ``--ignore GPL2
  --select GPL2014`` reports ``GPL2014`` alone of them (ruff's rule); equal length: ignored.
* **Errors can be ignored too**, as in mypy (``# type: ignore``): real vendor code breaks rules
  the controller does not enforce.  An ignored error no longer stops the translation; its line is
  translated as ``--keep-going`` translates it: it raises the controller's error for the fault
  when reached (``gpl2py.kept``).  The sink keeps the ignored errors aside for that.
* **GPL9000-GPL9003 are never filtered**: an internal error, a wrong command line or
  configuration is not a finding about the GPL code.
* **Inline comments.**  ``' gpl2py: ignore[GPL2014, GPL3501]`` (codes or prefixes) or
  ``' gpl2py: ignore`` (every code) in a comment suppresses the diagnostics whose position is on
  that physical line; text may follow (a reason).  The comments are found with the lexer, so a
  quote inside a string literal is never taken for a comment; the mapping from lines to codes
  lives here, not in the lexer.  A code in brackets that no diagnostic has is warned about
  (GPL9004): a typo would otherwise suppress nothing, silently.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field

from gpl2py import messages as msg
from gpl2py.diagnostics import Diagnostic, DiagnosticSink
from gpl2py.source import SourceFile, Span

#: What --select, --ignore and the comments accept: "GPL" and up to four digits.
CODE_OR_PREFIX = re.compile(r"GPL\d{0,4}")
#: ``gpl2py: ignore`` with an optional ``[codes]`` anywhere in a comment (case-insensitive).
_DIRECTIVE = re.compile(r"\bgpl2py:\s*ignore\b(?:\[([^\]]*)\])?", re.IGNORECASE)
_NEVER_FILTERED = ("GPL9000", "GPL9001", "GPL9002", "GPL9003")


def parse_codes(values: Iterable[str], where: str) -> tuple[str, ...]:
    """``values`` (``"GPL2014"``, ``"gpl20"``, ``"GPL1001,GPL1002"``) as upper-case codes or
    prefixes; a ValueError names the first that is neither, with the closest real code."""
    out: list[str] = []
    for value in values:
        for part in str(value).split(","):
            code = part.strip().upper()
            if not code:
                continue
            problem = code_problem(code)
            if problem is not None:
                raise ValueError(f"{where} {part.strip()!r}: {problem}")
            out.append(code)
    return tuple(out)


def code_problem(code: str) -> str | None:
    """Why ``code`` (upper case) is no code or prefix of a real diagnostic, or None."""
    codes = [m.code for m in msg.all_messages()]
    if CODE_OR_PREFIX.fullmatch(code) and any(c.startswith(code) for c in codes):
        return None
    close = difflib.get_close_matches(code, codes, n=1, cutoff=0.6)
    hint = f"; did you mean {close[0]}?" if close else ""
    if not CODE_OR_PREFIX.fullmatch(code):
        return f"not a diagnostic code or prefix (GPL and up to four digits: GPL2014, GPL20){hint}"
    return f"no diagnostic has this code{hint}"


@dataclass
class Selection:
    """The filter of a sink: ``select`` (None: every code), ``ignore``, and the suppression comments
    of the sources handed to :meth:`add_sources`."""

    select: tuple[str, ...] | None = None
    ignore: tuple[str, ...] = ()
    #: file (as diagnostics name it) -> line -> suppressed codes (``None``: every code)
    _inline: dict[str, dict[int, tuple[str, ...] | None]] = field(default_factory=dict)
    _scanned: set[str] = field(default_factory=set)

    def __call__(self, diag: Diagnostic) -> bool:
        """Whether ``diag`` is reported."""
        code = diag.code
        if code.startswith(_NEVER_FILTERED):
            return True
        if not self.allows(code):
            return False
        if diag.span is None:
            return True
        lines = self._inline.get(diag.span.file)
        if lines is None or diag.span.line not in lines:
            return True
        codes = lines[diag.span.line]
        return codes is not None and not any(code.startswith(c) for c in codes)

    def allows(self, code: str) -> bool:
        """--select/--ignore alone: the most specific matching entry decides (module docstring)."""
        ignored = max((len(p) for p in self.ignore if code.startswith(p)), default=-1)
        if self.select is None:
            return ignored < 0
        selected = max((len(p) for p in self.select if code.startswith(p)), default=-1)
        return selected > ignored

    def fingerprint(self) -> list[object]:
        """What the cache key must hold: the same sources give other diagnostics under another
        selection (the inline comments are part of the sources already)."""
        return [None if self.select is None else sorted(self.select), sorted(self.ignore)]

    def add_sources(self, sources: Sequence[SourceFile], sink: DiagnosticSink) -> None:
        """Read the ``gpl2py: ignore`` comments of ``sources`` (before they are parsed, so that the
        parser's own diagnostics are filtered too).  A bracketed code that no diagnostic has is
        warning GPL9004 in ``sink``."""
        for source in sources:
            if source.path in self._scanned:
                continue
            self._scanned.add(source.path)
            if "gpl2py" not in source.text.lower():  # the lexer runs only where a comment may be
                continue
            lines: dict[int, tuple[str, ...] | None] = {}
            for text, span in _comments(source):
                found = _DIRECTIVE.search(text)
                if found is None:
                    continue
                codes = self._comment_codes(found.group(1), span, sink)
                if codes is not None and not codes:
                    continue  # only bad codes: suppress nothing (GPL9004 said why)
                line = span.line
                if codes is None or lines.get(line, ()) is None:
                    lines[line] = None
                else:
                    lines[line] = (*(lines.get(line) or ()), *codes)
            if lines:
                self._inline[source.path] = lines

    @staticmethod
    def _comment_codes(bracket: str | None, span: object, sink: DiagnosticSink) -> tuple[str, ...] | None:
        if bracket is None:
            return None  # every code
        good: list[str] = []
        for part in bracket.split(","):
            code = part.strip().upper()
            if not code:
                continue
            problem = code_problem(code)
            if problem is None:
                good.append(code)
            else:
                sink.report(msg.BAD_SUPPRESSION, span, code=part.strip(), problem=problem)  # type: ignore[arg-type]
        return tuple(good)


def _comments(source: SourceFile) -> Iterator[tuple[str, Span]]:
    """The text and place of every comment of ``source``, read by its own language's lexer (a V+
    ``; gpl2py: ignore`` comment; GPL's lexer would take V+'s ``'A`` for a comment)."""
    from gpl2py.languages import frontend_for

    if frontend_for(source.path).name == "vplus":
        from gpl2py.vplus.syntax.lexer import lex

        for c in lex(source, DiagnosticSink()).comments:
            yield c.text, c.span
        return
    from gpl2py.gpl.syntax.lexer import token_chunks
    from gpl2py.gpl.syntax.tokens import TokenKind
    from gpl2py.source import make_span

    for chunk in token_chunks(source, DiagnosticSink()):  # the parse reports the lexer's errors
        for kind, _, value, span in chunk:  # (the parser's plain-tuple tokens)
            if kind is TokenKind.COMMENT:
                yield str(value), make_span(*span)


__all__ = ["CODE_OR_PREFIX", "Selection", "code_problem", "parse_codes"]

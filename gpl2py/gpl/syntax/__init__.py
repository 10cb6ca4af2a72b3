"""The GPL front end: :mod:`~gpl2py.gpl.syntax.lexer` (text -> tokens), :mod:`~gpl2py.gpl.syntax.parser`
(tokens -> :mod:`~gpl2py.gpl.syntax.ast`).  Both report problems to a
:class:`~gpl2py.diagnostics.DiagnosticSink` and never raise on bad input."""

from gpl2py.gpl.syntax.lexer import tokenize
from gpl2py.gpl.syntax.parser import parse, parse_expression

__all__ = ["parse", "parse_expression", "tokenize"]

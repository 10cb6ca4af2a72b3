"""The tokens of V+ source (:mod:`gpl2py.vplus.syntax.lexer` makes them).

V+ is line-oriented: one instruction per line, ``;`` to the end of the line a comment.  Keywords are
not reserved words of the lexer: ``belt`` and ``window.1`` are user names although BELT and WINDOW
are keywords (spec §1.3), so every word is a :attr:`Kind.NAME` and the parser resolves keywords by
position.  A name keeps its sigil (``$`` string, ``#`` precision point, ``%`` belt) in
:attr:`Token.sigil`; dots are ordinary name characters (``dist.to.part``), never member access.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from gpl2py.source import Span


class Kind(enum.Enum):
    """What a token is."""

    __hash__ = object.__hash__

    NAME = "name"
    NUMBER = "number"
    STRING = "string"
    DIRECTIVE = "'.' section line"  # .PROGRAM, .END, .LOCATIONS ... at the start of a line
    OP = "operator"
    NEWLINE = "end of line"
    EOF = "end of file"


@dataclass(slots=True)
class Token:
    """One token.  ``text`` is what the source says (a name without its sigil, an operator, a
    string's contents); ``upper`` the keyword form of a name or directive; ``value`` a number's
    value; ``sigil`` a name's ``$``/``#``/``%`` or ``""``; ``spaced`` whether blanks precede it."""

    kind: Kind
    text: str
    span: Span
    value: float = 0.0
    sigil: str = ""
    spaced: bool = True

    @property
    def upper(self) -> str:
        return self.text.upper()

    def is_op(self, *ops: str) -> bool:
        return self.kind is Kind.OP and self.text in ops

    def is_word(self, *words: str) -> bool:
        """A name without sigil spelled as one of ``words`` (upper case), in any case."""
        return self.kind is Kind.NAME and not self.sigil and self.text.upper() in words

    def shown(self) -> str:
        """The token as a diagnostic quotes it."""
        if self.kind is Kind.NEWLINE:
            return "end of line"
        if self.kind is Kind.EOF:
            return "end of file"
        if self.kind is Kind.STRING:
            return f'"{self.text}"'
        return f"'{self.sigil}{self.text}'"


@dataclass(slots=True, frozen=True)
class Comment:
    """A ``;`` comment: its text after the ``;`` and where it is (the Python writer's Comment)."""

    span: Span
    text: str
    directive: bool = False

"""Token kinds, and the layout of the tokens :mod:`gpl2py.gpl.syntax.lexer` produces (:data:`KIND`).

Every GPL keyword has its own :class:`TokenKind`, so the parser dispatches on ``kind is K.IF``
(identity comparisons on enum members are the cheapest test Python offers) instead of comparing
lowered strings.  Words the seeds reject (``GoSub``, ``With``, ``Enum`` …) are deliberately *not*
keywords: the spec (§1.8) says they must stay usable as names, so they lex as :attr:`TokenKind.IDENT`
and the parser recognises them only in statement position.  Type names (``Integer``, ``String`` …)
are identifiers too; the parser accepts them wherever a type name is expected and semantics checks
them, which keeps ``As MyMod.My_class`` and ``As Integer`` on one code path.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from gpl2py.source import Span


class TokenKind(enum.Enum):
    """What a token is.  Keyword members are named after the keyword in upper case."""

    # Enum.__hash__ is written in Python; the parser looks kinds up in dicts on every token, so use
    # the C-level identity hash (members are singletons and compare by identity anyway).
    __hash__ = object.__hash__

    # literals and names
    IDENT = "identifier"
    INTEGER = "integer literal"
    REAL = "real literal"
    STRING = "string literal"

    # layout
    NEWLINE = "end of line"
    COMMENT = "comment"
    DIRECTIVE = "'#' line"
    EOF = "end of file"
    ERROR = "invalid character"

    # punctuation and operators
    LPAREN = "("
    RPAREN = ")"
    COMMA = ","
    DOT = "."
    COLON = ":"
    PLUS = "+"
    MINUS = "-"
    STAR = "*"
    SLASH = "/"
    BACKSLASH = "\\"
    CARET = "^"
    AMP = "&"
    EQ = "="
    NE = "<>"
    LT = "<"
    GT = ">"
    LE = "<="
    GE = ">="
    SHL = "<<"
    SHR = ">>"
    CARET_EQ = "^="
    STAR_EQ = "*="
    SLASH_EQ = "/="
    BACKSLASH_EQ = "\\="
    PLUS_EQ = "+="
    MINUS_EQ = "-="
    SHL_EQ = "<<="
    SHR_EQ = ">>="
    AMP_EQ = "&="

    # reserved words (spec §1.8)
    ADDRESSOF = "AddressOf"
    AND = "And"
    ANDALSO = "AndAlso"
    AS = "As"
    BYREF = "ByRef"
    BYVAL = "ByVal"
    CALL = "Call"
    CASE = "Case"
    CATCH = "Catch"
    CLASS = "Class"
    CONST = "Const"
    DELEGATE = "Delegate"
    DIM = "Dim"
    DO = "Do"
    ELSE = "Else"
    ELSEIF = "ElseIf"
    END = "End"
    EXIT = "Exit"
    FALSE = "False"
    FINALLY = "Finally"
    FOR = "For"
    FUNCTION = "Function"
    GET = "Get"
    GOTO = "GoTo"
    IF = "If"
    IS = "Is"
    LOOP = "Loop"
    ME = "Me"
    MOD = "Mod"
    MODULE = "Module"
    NEW = "New"
    NEXT = "Next"
    NOT = "Not"
    NOTHING = "Nothing"
    OR = "Or"
    ORELSE = "OrElse"
    PRIVATE = "Private"
    PROPERTY = "Property"
    PUBLIC = "Public"
    REDIM = "ReDim"
    RETURN = "Return"
    SELECT = "Select"
    SET = "Set"
    SHARED = "Shared"
    STATIC = "Static"
    STEP = "Step"
    SUB = "Sub"
    THEN = "Then"
    THROW = "Throw"
    TO = "To"
    TRUE = "True"
    TRY = "Try"
    UNTIL = "Until"
    WHILE = "While"
    XOR = "Xor"


_FIRST_KEYWORD = TokenKind.ADDRESSOF

#: Lower-cased keyword spelling -> kind.  The lexer looks words up here (one dict probe per word).
KEYWORDS: dict[str, TokenKind] = {}
_seen = False
for _kind in TokenKind:
    if _kind is _FIRST_KEYWORD:
        _seen = True
    if _seen:
        KEYWORDS[_kind.value.lower()] = _kind
del _seen, _kind

#: Kinds that are words (keywords); a member name after ``.`` may be any of these (``tl.Stop()``).
KEYWORD_KINDS: frozenset[TokenKind] = frozenset(KEYWORDS.values())

#: Compound assignment operator kinds -> the operator spelling stored in the AST.
COMPOUND_ASSIGN: dict[TokenKind, str] = {
    TokenKind.CARET_EQ: "^=",
    TokenKind.STAR_EQ: "*=",
    TokenKind.SLASH_EQ: "/=",
    TokenKind.BACKSLASH_EQ: "\\=",
    TokenKind.PLUS_EQ: "+=",
    TokenKind.MINUS_EQ: "-=",
    TokenKind.SHL_EQ: "<<=",
    TokenKind.SHR_EQ: ">>=",
    TokenKind.AMP_EQ: "&=",
}

#: Operator/punctuation spelling -> kind (used by the lexer).
OPERATORS: dict[str, TokenKind] = {
    k.value: k
    for k in TokenKind
    if k.value and not k.value[0].isalpha() and k.value[0] not in "'#"
    and k.name not in ("NEWLINE", "EOF", "ERROR")
}


#: The parser's tokens are plain tuples ``(kind, text, value, span)``, read by these indices (or
#: unpacked).  Building a plain tuple is a quarter of the cost of a class instance, and the lexer
#: makes one per token: a tuple and its span as plain tuples halve the lexer's Python work
#: (docs/design/performance.md, "Parsing").  ``span`` is the plain tuple
#: ``(file, line, col, end_line, end_col)``: :class:`~gpl2py.source.Span`'s fields in Span's order,
#: so a node built from it unpacks it like a Span, and ``tuple.__new__(Span, span)`` makes it one
#: where a Span is kept (a diagnostic, a comment).  :class:`Token` is the same record with names,
#: for the code that lists tokens rather than parsing them (:func:`~gpl2py.gpl.syntax.lexer.tokenize`).
KIND, TEXT, VALUE, SPAN = 0, 1, 2, 3

#: A token as the lexer hands it to the parser (see :data:`KIND`).
RawToken = tuple[TokenKind, str, object, tuple[str, int, int, int, int]]


def describe(tok: RawToken) -> str:
    """How a diagnostic names a token: ``'Then'``, ``end of line``, ``identifier 'foo'``."""
    return _describe(tok[KIND], tok[TEXT])


def _describe(kind: TokenKind, text: str) -> str:
    if kind is TokenKind.NEWLINE or kind is TokenKind.EOF:
        return kind.value
    if kind is TokenKind.IDENT:
        return f"identifier '{text}'"
    if kind is TokenKind.COMMENT:
        return "comment"
    if kind in (TokenKind.INTEGER, TokenKind.REAL, TokenKind.STRING):
        return f"{kind.value} {text}"
    return f"'{text}'"


@dataclass(slots=True)
class Token:
    """One token, with named fields: what :func:`~gpl2py.gpl.syntax.lexer.tokenize` lists.

    ``text`` is the exact source spelling (keywords keep their case, for messages); ``value`` is the
    decoded value of a literal (``int`` for integer/hex/octal, ``float`` for reals, ``str`` for
    strings and comments, the text without the leading ``'``) and ``None`` otherwise.
    """

    kind: TokenKind
    text: str
    value: object
    span: Span

    @classmethod
    def of(cls, raw: RawToken) -> Token:
        """The named form of a parser token (:data:`KIND`)."""
        kind, text, value, span = raw
        return cls(kind, text, value, tuple.__new__(Span, span))

    @property
    def line(self) -> int:
        return self.span.line

    @property
    def col(self) -> int:
        return self.span.col

    def describe(self) -> str:
        """How a diagnostic names this token: ``'Then'``, ``end of line``, ``identifier 'foo'``."""
        return _describe(self.kind, self.text)

"""The TMscript tree (spec §2): expressions, statements, functions, a script project.

Nodes carry their span so that every diagnostic and every generated line names its source line.
The tree says what is written; types and names are the semantics' business.

A statement (and a function, a section's block, a switch case) carries the comments the parser
attached to it in ``comments``: those before its first token (the lowering writes them on lines
of their own above it) and those on its line after it (a trailing comment).  A block's
``opening`` comments are those after its ``{`` on the line (or between its statement's head and
the ``{``), its ``closing`` ones those after its last statement up to the end of the ``}`` line.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gpl2py.source import Span
from gpl2py.tmscript.syntax.lexer import Comment


@dataclass(eq=False)
class Node:
    span: Span
    comments: tuple[Comment, ...] = field(default=(), kw_only=True)


# --- expressions ------------------------------------------------------------------------------
@dataclass(eq=False)
class Num(Node):
    value: int | float
    text: str


@dataclass(eq=False)
class Str(Node):
    value: str


@dataclass(eq=False)
class Bool(Node):
    value: bool


@dataclass(eq=False)
class ArrayLit(Node):
    items: list[Node]


@dataclass(eq=False)
class Name(Node):
    name: str


@dataclass(eq=False)
class Call(Node):
    callee: Node  # Name (a function) or Member (a method of a class variable)
    args: list[Node]


@dataclass(eq=False)
class Index(Node):
    obj: Node
    index: Node
    index2: Node | None = None  # Base["name", n] (L14459)


@dataclass(eq=False)
class Member(Node):
    obj: Node
    name: str


@dataclass(eq=False)
class Unary(Node):
    op: str  # - + ! ~ ++ -- (prefix)
    operand: Node


@dataclass(eq=False)
class Postfix(Node):
    op: str  # ++ --
    operand: Node


@dataclass(eq=False)
class Binary(Node):
    op: str
    left: Node
    right: Node


@dataclass(eq=False)
class Cond(Node):
    cond: Node
    then: Node
    other: Node


@dataclass(eq=False)
class Assign(Node):
    op: str  # = += -= ...
    target: Node
    value: Node


@dataclass(eq=False)
class Cast(Node):
    type: str
    array: bool
    operand: Node


# --- statements -------------------------------------------------------------------------------
@dataclass(eq=False)
class Declarator(Node):
    name: str
    init: Node | None


@dataclass(eq=False)
class Decl(Node):
    type: str
    array: bool
    declarators: list[Declarator]


@dataclass(eq=False)
class ClassDecl(Node):
    cls: str
    name: str
    args: list[Node]


@dataclass(eq=False)
class ExprStmt(Node):
    expr: Node


@dataclass(eq=False)
class Block(Node):
    body: list[Node]
    opening: tuple[Comment, ...] = ()
    closing: tuple[Comment, ...] = ()


@dataclass(eq=False)
class If(Node):
    cond: Node
    then: Node
    other: Node | None


@dataclass(eq=False)
class Case(Node):
    op: str | None  # None: equality; "<", ">=", ... (case >= 100, L1529)
    label: Node | None  # None: default
    body: list[Node]


@dataclass(eq=False)
class Switch(Node):
    subject: Node
    cases: list[Case]
    closing: tuple[Comment, ...] = ()  # after the last case, up to the end of the '}' line


@dataclass(eq=False)
class For(Node):
    init: list[Node]
    cond: Node | None
    step: list[Node]
    body: Node


@dataclass(eq=False)
class While(Node):
    cond: Node
    body: Node


@dataclass(eq=False)
class DoWhile(Node):
    body: Node
    cond: Node


@dataclass(eq=False)
class Jump(Node):
    word: str  # break | continue


@dataclass(eq=False)
class Return(Node):
    value: Node | None


@dataclass(eq=False)
class Param(Node):
    type: str
    array: bool
    name: str


@dataclass(eq=False)
class Function(Node):
    ret: str  # void | a type
    ret_array: bool
    name: str
    params: list[Param]
    body: Block


@dataclass(eq=False)
class Script(Node):
    """A script project (``define``/``main``/``closestop``/``errorstop``, functions) or, with
    ``packet``, the statement list of a Listen-node packet or Script node (``statements``)."""

    packet: bool
    define: list[Node] = field(default_factory=list)
    sections: dict[str, Block] = field(default_factory=dict)
    functions: list[Function] = field(default_factory=list)
    statements: list[Node] = field(default_factory=list)
    closing: tuple[Comment, ...] = ()  # after the last item: the comments that end the file


CLASS_TYPES = ("SerialPort", "Socket", "ModbusTCP", "ModbusRTU", "TPoint", "TBase", "TTCP", "FTSensor", "Force")
SECTIONS = ("define", "main", "closestop", "errorstop")

"""The V+ syntax tree: plain dataclasses, one per construct (spec §2).

Every node has ``span``.  Names keep their source spelling and sigil; :func:`key` is the name V+
knows (case-folded, 15 significant characters, the sigil kept: ``$a`` and ``a`` are two variables).
Statements carry ``label`` (the step label of their line, or None) and ``comments`` (the ``;``
comments on their line and the full-line comments just above), which the lowering carries into the
Python.  Instructions without a construct of their own are an :class:`Instr` (keyword, arguments,
trailing words such as ``ALWAYS``): what each means is the semantics' and lowering's business, by
keyword, in one table each.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gpl2py.source import Span
from gpl2py.vplus.syntax.tokens import Comment

#: How many characters of a name V+ keeps (User's Guide L3798-3806).
SIGNIFICANT = 15


def key(sigil: str, name: str) -> str:
    """The name as V+ knows it: case-insensitive, 15 significant characters, with its sigil."""
    return sigil + name.lower()[:SIGNIFICANT]


# --- expressions ---------------------------------------------------------------------------------


@dataclass(eq=False)
class Expr:
    span: Span


@dataclass(eq=False)
class Num(Expr):
    value: float
    text: str


@dataclass(eq=False)
class Str(Expr):
    value: str


@dataclass(eq=False)
class Var(Expr):
    """A variable: ``x``, ``$s``, ``#p``, ``%b``; with ``index`` it is an element (``a[i, j]``), with
    ``whole`` the whole array (``a[]``), with an empty-bracket start ``a[1]`` as DECOMPOSE target."""

    sigil: str
    name: str
    index: list[Expr] | None = None
    whole: bool = False

    @property
    def key(self) -> str:
        return key(self.sigil, self.name)

    @property
    def shown(self) -> str:
        return self.sigil + self.name


@dataclass(eq=False)
class Call(Expr):
    """A function (``ABS(x)``, ``$CHR(65)``, ``#PPOINT(...)``, ``HERE``); ``by`` holds the values
    after ``BY`` in ``SHIFT(t BY dx, dy, dz)`` / ``SCALE(t BY s)``."""

    sigil: str
    name: str
    args: list[Expr | None]
    parens: bool = True
    by: list[Expr | None] | None = None

    @property
    def upper(self) -> str:
        return self.sigil + self.name.upper()


@dataclass(eq=False)
class Unary(Expr):
    op: str  # "-", "NOT", "COM"
    operand: Expr


@dataclass(eq=False)
class Binary(Expr):
    op: str  # upper case: "+", "AND", "==", ":" (compose) ...
    left: Expr
    right: Expr


@dataclass(eq=False)
class Paren(Expr):
    """``(e)``: kept, because ``(x)`` passes a variable by value (User's Guide L1193-1195)."""

    inner: Expr


@dataclass(eq=False)
class Format(Expr):
    """An output format item of TYPE, WRITE, PROMPT, $ENCODE: ``/S``, ``/I0``, ``/C2``, ``/F8.3``."""

    letter: str
    arg: str


# --- statements ----------------------------------------------------------------------------------


@dataclass(eq=False)
class Stmt:
    span: Span
    label: int | None = field(default=None, kw_only=True)
    comments: list[Comment] = field(default_factory=list, kw_only=True)


@dataclass(eq=False)
class Assign(Stmt):
    target: Var
    value: Expr


@dataclass(eq=False)
class SetLoc(Stmt):
    """``SET target = location``."""

    target: Var
    value: Expr


@dataclass(eq=False)
class Here(Stmt):
    """``HERE a:b:c`` assigns the last element so that ``a:b:c`` is the current location."""

    frames: list[Expr]
    target: Var


@dataclass(eq=False)
class DeclItem:
    span: Span
    var: Var
    dims: list[Expr] | None  # AUTO a[5]


@dataclass(eq=False)
class Decl(Stmt):
    kind: str  # AUTO | LOCAL | GLOBAL
    qualifier: str  # "" | DOUBLE | REAL | LOC
    items: list[DeclItem]


@dataclass(eq=False)
class If(Stmt):
    cond: Expr
    then: list[Stmt]
    orelse: list[Stmt] | None


@dataclass(eq=False)
class IfGoto(Stmt):
    cond: Expr
    target: int
    target_span: Span


@dataclass(eq=False)
class Goto(Stmt):
    target: int
    target_span: Span


@dataclass(eq=False)
class CaseArm:
    span: Span
    values: list[Expr] | None  # None: ANY
    body: list[Stmt]
    comments: list[Comment] = field(default_factory=list)


@dataclass(eq=False)
class Case(Stmt):
    subject: Expr
    arms: list[CaseArm]


@dataclass(eq=False)
class DoUntil(Stmt):
    body: list[Stmt]
    cond: Expr


@dataclass(eq=False)
class While(Stmt):
    cond: Expr
    body: list[Stmt]


@dataclass(eq=False)
class For(Stmt):
    var: Var
    start: Expr
    stop: Expr
    step: Expr | None
    body: list[Stmt]


@dataclass(eq=False)
class Exit(Stmt):
    word: str  # EXIT | NEXT
    count: Expr | None


@dataclass(eq=False)
class CallStmt(Stmt):
    """``CALL prog(args)``; ``CALLS $name(args)`` has ``dynamic`` (the string expression)."""

    name: str
    name_span: Span
    args: list[Expr | None]
    dynamic: Expr | None = None


@dataclass(eq=False)
class Return(Stmt):
    word: str  # RETURN | RETURNE


@dataclass(eq=False)
class Execute(Stmt):
    """``EXECUTE [task] prog(args)[, cycles[, step[, priority]]]``."""

    task: Expr | None
    program: str
    program_span: Span
    args: list[Expr | None]
    rest: list[Expr | None]


@dataclass(eq=False)
class React(Stmt):
    """``REACT|REACTI signal, prog(args)[, priority]``; ``REACTE prog``."""

    word: str
    signal: Expr | None
    program: str
    program_span: Span
    args: list[Expr | None]
    priority: Expr | None


@dataclass(eq=False)
class Instr(Stmt):
    """Any other instruction: ``word`` (upper case), ``unit`` (the parenthesised LUN part of an
    I/O instruction, ``WRITE (lun) ...``), ``args`` (values, formats, empty positions None),
    ``target`` (left of ``=`` where the instruction has one: ``TIMER 1 = 0``, ``PARAMETER
    HAND.TIME = 0.1``, ``DECOMPOSE a[] = loc``), ``modifiers`` (``ALWAYS``, ``MONITOR``, ``MMPS``
    ...), ``tier3`` when gpl2py parses but does not run it."""

    word: str
    args: list[Expr | None] = field(default_factory=list)
    unit: list[Expr | None] | None = None
    target: list[Expr | None] | None = None
    modifiers: list[str] = field(default_factory=list)
    tier3: bool = False


# --- programs and files --------------------------------------------------------------------------


@dataclass(eq=False)
class Param:
    span: Span
    var: Var  # whole=True for an array parameter (jts[])


@dataclass(eq=False)
class Program:
    span: Span
    name: str
    name_span: Span
    params: list[Param]
    decls: list[Decl]
    body: list[Stmt]
    comments: list[Comment] = field(default_factory=list)  # on the .PROGRAM line and before it
    trailing: list[Comment] = field(default_factory=list)  # after the last statement
    end_span: Span | None = None

    @property
    def key(self) -> str:
        return key("", self.name)


@dataclass(eq=False)
class Datum:
    """One value of a data section: ``pick 100 200 300 0 180 0``, ``$name "text"``, ``dx 12.5``."""

    span: Span
    var: Var
    values: list[float]
    text: str | None = None  # a string's value


@dataclass(eq=False)
class DataSection:
    span: Span
    kind: str  # LOCATIONS | REALS | DOUBLES | STRINGS
    data: list[Datum]


@dataclass(eq=False)
class Module:
    """One V+ file: its programs and data sections in file order."""

    path: str
    programs: list[Program]
    data: list[DataSection]
    comments: list[Comment] = field(default_factory=list)  # outside every program

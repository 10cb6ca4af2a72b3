"""The GPL abstract syntax tree: plain dataclasses, one per construct, in the style of pycparser's c_ast.

Conventions
-----------
* Every node has ``span`` (a :class:`~gpl2py.source.Span`) as its first field.
* ``_children`` names the fields that hold nodes or lists of nodes, in source order; :meth:`Node.children`
  and the visitors use it, so a node's shape is visible at a glance.
* Nodes compare and hash by identity (``eq=False``) so later passes can key dictionaries on them
  (symbol tables, inferred types).
* Names keep their source spelling; GPL is case-insensitive, so semantics compares ``name.lower()``.
* Operators are stored as canonical strings: ``"+"``, ``"Mod"``, ``"AndAlso"``, ``"<<="`` ...
* ``a(1)`` is an :class:`Invoke` whatever it means (call, array index, indexed property, delegate
  invocation): the parser cannot know, semantics decides (spec §3.7).
* Parentheses are not kept as nodes; precedence is already in the tree shape.
* A run of :data:`CHAIN_MIN` binary operators of one precedence level or more is one
  :class:`Chain` (operators and literal operands in arrays), which means the nested
  :class:`Binary` nodes it stands for; a walker of left spines reads both (``chain_left``).
* A ``Dim`` in a procedure of :data:`DIM_MIN` simple names or more (``Dim v0, v1, ... As Integer``)
  holds its declarators as one :class:`CompactDeclarators` (names and positions in arrays), which
  makes each :class:`VarDeclarator` when asked and means the list of them.

Comments
--------
GPL comments must survive into the generated Python.  Every statement and declaration (subclasses of
:class:`Stmt`) carries ``leading_comments`` (full-line comments and ``#`` lines directly above it) and
``trailing_comment`` (the comment at the end of its line; for a block statement, the comment on its
first line).  A :class:`Block` keeps ``header_comment`` (the comment on the line that opens it, such
as ``Else ' why``) and ``end_comments`` (comments after its last statement, before ``End If`` /
``Next`` / ``Case`` ...).  Block statements keep the comment on their closing line in ``end_comment``.
Containers (:class:`SourceUnit`, :class:`ModuleDecl`, :class:`ClassDecl`) keep their trailing
comments in ``end_comments``.  Comment sequences are tuples: most statements have none, and every
one of them then shares the empty tuple instead of holding an empty list of its own (an eighth of
the syntax tree of dense code: docs/security.md, "Input size").
"""

from __future__ import annotations

from array import array
from bisect import bisect_right
from dataclasses import KW_ONLY, MISSING, Field, InitVar, dataclass, field, fields
from typing import Any, ClassVar, Iterator

from gpl2py.source import Span


@dataclass(slots=True)
class Comment:
    """One comment. ``text`` excludes the leading ``'``; ``directive`` marks a kept ``#`` line.
    Not frozen: like a node's position, its ``span`` is moved in place when an edit adds lines
    above it (``syntax/shift.py``; making each comment again was more than half of that move)."""

    span: Span
    text: str
    directive: bool = False


# --------------------------------------------------------------------------------------------------
# base classes


@dataclass(slots=True, eq=False, init=False)
class Node:
    """Base of every node.  A node is built with its :class:`~gpl2py.source.Span` and gives it back
    as ``node.span`` (assignable, like a field), but it keeps the span's five numbers in its own
    slots rather than a reference to a Span object: every node has a position of its own, and a
    separate object for it cost a third of the memory of a syntax tree (docs/security.md, "Input
    size").  ``node.span`` builds an equal Span on each read."""

    span: InitVar[Span]
    _file: str = field(init=False, repr=False)
    _line: int = field(init=False, repr=False)
    _col: int = field(init=False, repr=False)
    _end_line: int = field(init=False, repr=False)
    _end_col: int = field(init=False, repr=False)
    _children: ClassVar[tuple[str, ...]] = ()

    def __post_init__(self, span: Span) -> None:
        self._file, self._line, self._col, self._end_line, self._end_col = span

    def children(self) -> Iterator[Node]:
        """The child nodes, in source order (lists are flattened, ``None`` skipped)."""
        for name in self._children:
            value = getattr(self, name)
            if value is None:
                continue
            if isinstance(value, list):
                for item in value:
                    if item is not None:
                        yield item
            else:
                yield value


def _get_span(node: Node) -> Span:
    return _new_tuple(Span, (node._file, node._line, node._col, node._end_line, node._end_col))


_new_tuple = tuple.__new__  # (a Span is a tuple: gpl2py.source.make_span without its call)


def span_between(first: Node, last: Node) -> Span:
    """``first.span.to(last.span)`` without building the two spans (the parser's hot path)."""
    return _new_tuple(Span, (first._file, first._line, first._col, last._end_line, last._end_col))


def span_to(first: Node, last: Span) -> Span:
    """``first.span.to(last)`` without building the first span (the parser's hot path)."""
    return _new_tuple(Span, (first._file, first._line, first._col, last[3], last[4]))


# (set after the class is made: in the class body the property would be read as the InitVar's default)
Node.span = property(_get_span, Node.__post_init__, doc="Where the node is in its source file.")  # type: ignore[assignment]


@dataclass(slots=True, eq=False, init=False)
class Expr(Node):
    """Base of expressions."""

    #: What the expression means, filled in by the semantic pass (``semantics.check.InfoTable``,
    #: read as ``Model.info[expr]``): a slot is an eighth of the memory of a dict entry per node
    _info: object = field(default=None, init=False, repr=False)


@dataclass(slots=True, eq=False, init=False)
class Stmt(Node):
    """Base of statements and declarations: anything that occupies a line and can carry comments."""

    _: KW_ONLY
    leading_comments: tuple[Comment, ...] = ()
    trailing_comment: Comment | None = None


# --------------------------------------------------------------------------------------------------
# expressions


@dataclass(slots=True, eq=False, init=False)
class Name(Expr):
    name: str


@dataclass(slots=True, eq=False, init=False)
class IntegerLiteral(Expr):
    """Decimal, ``&H`` or ``&O`` literal. ``value`` is already 32-bit two's complement for hex/octal."""

    value: int
    text: str


@dataclass(slots=True, eq=False, init=False)
class RealLiteral(Expr):
    value: float
    text: str


@dataclass(slots=True, eq=False, init=False)
class StringLiteral(Expr):
    """``value`` is decoded (``""`` -> ``"``)."""

    value: str


@dataclass(slots=True, eq=False, init=False)
class BooleanLiteral(Expr):
    value: bool


@dataclass(slots=True, eq=False, init=False)
class NothingLiteral(Expr):
    pass


@dataclass(slots=True, eq=False, init=False)
class MeExpr(Expr):
    pass


@dataclass(slots=True, eq=False, init=False)
class MemberAccess(Expr):
    """``target.name``; may also be a zero-argument call (``Move.WaitForEOM``), semantics decides."""

    target: Expr
    name: str
    _children: ClassVar[tuple[str, ...]] = ("target",)


@dataclass(slots=True, eq=False, init=False)
class Invoke(Expr):
    """``target(args)``: call, array index, indexed property or delegate invocation (semantics decides)."""

    target: Expr
    args: list[Expr]
    _children: ClassVar[tuple[str, ...]] = ("target", "args")


@dataclass(slots=True, eq=False, init=False)
class Unary(Expr):
    """``-x``, ``+x`` or ``Not x``."""

    op: str
    operand: Expr
    _children: ClassVar[tuple[str, ...]] = ("operand",)


@dataclass(slots=True, eq=False, init=False)
class Binary(Expr):
    """``left op right``; ``op`` is one of ``^ * / \\ Mod + - & << >> = <> < > <= >= Is And AndAlso
    Or OrElse Xor``."""

    op: str
    left: Expr
    right: Expr
    _children: ClassVar[tuple[str, ...]] = ("left", "right")


#: The binary operators by their code in :attr:`Chain.ops`.
CHAIN_OPS: tuple[str, ...] = ("^", "*", "/", "\\", "Mod", "+", "-", "&", "<<", ">>", "=", "<>", "<", ">",
                              "<=", ">=", "And", "AndAlso", "Or", "OrElse", "Xor")
CHAIN_CODES: dict[str, int] = {op: i for i, op in enumerate(CHAIN_OPS)}
#: A run of this many operators of one precedence level or more is parsed into a :class:`Chain`
#: (fewer stay nested :class:`Binary` nodes: every program a person writes keeps its tree).
CHAIN_MIN = 64


@dataclass(slots=True, eq=False, init=False)
class Chain(Expr):
    """``first op1 x1 op2 x2 ...``: a long left-associative run of binary operators of one
    precedence level (at least :data:`CHAIN_MIN`), meaning the nested
    ``Binary(...Binary(Binary(first, op1, x1), op2, x2)..., opn, xn)`` but held compactly.

    Why: ``1+1+...`` of a million terms held an IntegerLiteral and a Binary per two bytes of
    source, 135 times the source (issue 20, docs/security.md "Input size").  Here an operand costs
    a byte for its operator, a reference, and eight bytes of position: a decimal Integer literal
    operand is kept as its value (``operands[k]`` an ``int``, its line and column in ``lines`` and
    ``cols``) and made a node again only when asked (:meth:`operand`); any other operand is its
    node (``lines``/``cols`` 0).  The prefix ``first op1 x1 ... opk xk`` (the Binary that would
    be) spans from ``first`` to the end of ``xk`` (:meth:`prefix_span`): a diagnostic about the
    k-th operator is reported where the nested form reported it."""

    first: Expr
    ops: bytearray  # CHAIN_CODES of each operator
    operands: list[Expr | int]
    lines: array[int]
    cols: array[int]
    _children: ClassVar[tuple[str, ...]] = ("first", "operands")

    def children(self) -> Iterator[Node]:
        yield self.first
        for x in self.operands:
            if isinstance(x, Node):
                yield x

    def op(self, k: int) -> str:
        return CHAIN_OPS[self.ops[k]]

    def literal(self, k: int) -> int | None:
        """The value of operand ``k`` when it is kept as a literal, else None."""
        x = self.operands[k]
        return None if isinstance(x, Node) else x

    def operand(self, k: int) -> Expr:
        """Operand ``k`` as a node (a new IntegerLiteral each time for a literal kept as a value)."""
        x = self.operands[k]
        if isinstance(x, Node):
            return x  # type: ignore[return-value]
        line, col = self.lines[k], self.cols[k]
        text = str(x)
        return IntegerLiteral(_new_tuple(Span, (self._file, line, col, line, col + len(text))), x, text)

    def operand_end(self, k: int) -> tuple[int, int]:
        """(line, column) just past operand ``k``."""
        x = self.operands[k]
        if isinstance(x, Node):
            return x._end_line, x._end_col
        return self.lines[k], self.cols[k] + len(str(x))

    def prefix_span(self, k: int) -> Span:
        """The span of ``first op1 x1 ... opk xk`` (k from 0)."""
        end_line, end_col = self.operand_end(k)
        return _new_tuple(Span, (self._file, self._line, self._col, end_line, end_col))

    def append(self, op: str, x: Expr) -> None:
        """Add ``op x`` at the end (the parser's step); a decimal Integer literal is kept as its value."""
        self.ops.append(CHAIN_CODES[op])
        if type(x) is IntegerLiteral and x._line == x._end_line and x.text == str(x.value) \
                and x.value < 2**31:
            self.operands.append(x.value)
            self.lines.append(x._line)
            self.cols.append(x._col)
        else:
            self.operands.append(x)
            self.lines.append(0)
            self.cols.append(0)
        self._end_line, self._end_col = x._end_line, x._end_col

    def nested(self) -> Binary:
        """The nested Binary nodes this chain stands for, made now (``dump`` shows those: a
        Chain is how the tree is held, not a construct of the language)."""
        left = self.first
        for k in range(len(self.ops)):
            left = Binary(self.prefix_span(k), self.op(k), left, self.operand(k))
        return left  # type: ignore[return-value]

    @staticmethod
    def of(first: Expr) -> Chain:
        """An empty chain starting with ``first`` (:meth:`append` adds its operators)."""
        return Chain(first.span, first, bytearray(), [], array("I"), array("I"))


def chain_left(e: Binary | Chain) -> Expr:
    """The left operand of a Binary, the first operand of a Chain: where a left spine goes on."""
    return e.left if isinstance(e, Binary) else e.first


@dataclass(slots=True, eq=False, init=False)
class TypeRef(Node):
    """A type name as written: ``Integer``, ``Location``, ``MyMod.My_class``."""

    name: str

    @property
    def parts(self) -> list[str]:
        return self.name.split(".")


@dataclass(slots=True, eq=False, init=False)
class New(Expr):
    """``New T`` or ``New T(args)``; ``args`` is ``None`` when no parentheses were written."""

    type: TypeRef
    args: list[Expr] | None
    _children: ClassVar[tuple[str, ...]] = ("type", "args")


@dataclass(slots=True, eq=False, init=False)
class AddressOf(Expr):
    """``AddressOf f`` or ``AddressOf obj.f``; ``target`` is a :class:`Name` or :class:`MemberAccess`."""

    target: Expr
    _children: ClassVar[tuple[str, ...]] = ("target",)


@dataclass(slots=True, eq=False, init=False)
class ErrorExpr(Expr):
    """Stands in for an expression that failed to parse (a diagnostic was reported)."""


# --------------------------------------------------------------------------------------------------
# blocks and statements


@dataclass(slots=True, eq=False, init=False)
class Block(Node):
    """A statement list (procedure body, loop body, If branch ...)."""

    statements: list[Stmt]
    header_comment: Comment | None = None
    end_comments: tuple[Comment, ...] = ()
    _children: ClassVar[tuple[str, ...]] = ("statements",)


@dataclass(slots=True, eq=False, init=False)
class Label(Stmt):
    """``name:`` or ``100:`` at the start of a line; a statement on the same line follows it in the
    enclosing block."""

    name: str


@dataclass(slots=True, eq=False, init=False)
class ErrorStmt(Stmt):
    """Stands in for a line of a procedure body that failed to parse (a diagnostic was reported):
    code translated despite the error raises it when the program reaches the line."""


@dataclass(slots=True, eq=False, init=False)
class Assign(Stmt):
    """``target op value`` where ``op`` is ``=`` or a compound operator (``+=``, ``<<=``, ``&=`` ...)."""

    target: Expr
    op: str
    value: Expr
    _children: ClassVar[tuple[str, ...]] = ("target", "value")


@dataclass(slots=True, eq=False, init=False)
class CallStmt(Stmt):
    """A procedure/method call used as a statement: ``Foo(1)``, ``Move.WaitForEOM``, ``Call Foo(1)``.

    ``expr`` is a :class:`Name`, :class:`MemberAccess` or :class:`Invoke`.
    """

    expr: Expr
    call_keyword: bool = False
    _children: ClassVar[tuple[str, ...]] = ("expr",)


@dataclass(slots=True, eq=False, init=False)
class ElseIfClause(Stmt):
    condition: Expr
    body: Block
    _children: ClassVar[tuple[str, ...]] = ("condition", "body")


@dataclass(slots=True, eq=False, init=False)
class If(Stmt):
    """Block or single-line If.  A single-line If has one statement in ``then_body`` (and maybe in
    ``else_body``) and ``single_line=True``."""

    condition: Expr
    then_body: Block
    elseifs: list[ElseIfClause] = field(default_factory=list)
    else_body: Block | None = None
    single_line: bool = False
    end_comment: Comment | None = None
    _children: ClassVar[tuple[str, ...]] = ("condition", "then_body", "elseifs", "else_body")


@dataclass(slots=True, eq=False, init=False)
class For(Stmt):
    """``For var = start To end [Step step] ... Next [next_var]``; ``var`` may be an array element or
    a field (any postfix expression)."""

    var: Expr
    start: Expr
    end: Expr
    step: Expr | None
    body: Block
    next_var: Expr | None = None
    end_comment: Comment | None = None
    _children: ClassVar[tuple[str, ...]] = ("var", "start", "end", "step", "body", "next_var")


@dataclass(slots=True, eq=False, init=False)
class ForEach(Stmt):
    """``For Each var In collection ... Next``."""

    var: Expr
    collection: Expr
    body: Block
    next_var: Expr | None = None
    end_comment: Comment | None = None
    _children: ClassVar[tuple[str, ...]] = ("var", "collection", "body", "next_var")


@dataclass(slots=True, eq=False, init=False)
class While(Stmt):
    condition: Expr
    body: Block
    end_comment: Comment | None = None
    _children: ClassVar[tuple[str, ...]] = ("condition", "body")


@dataclass(slots=True, eq=False, init=False)
class DoLoop(Stmt):
    """All ``Do``/``Loop`` forms.  ``condition`` is ``None`` for the plain infinite loop;
    ``test_at_top`` says where it is tested; ``until`` is True for ``Until`` (loop while it is False)."""

    condition: Expr | None
    test_at_top: bool
    until: bool
    body: Block
    end_comment: Comment | None = None
    _children: ClassVar[tuple[str, ...]] = ("condition", "body")


@dataclass(slots=True, eq=False, init=False)
class CaseValue(Node):
    """``Case 3`` / ``Case "red"``."""

    value: Expr
    _children: ClassVar[tuple[str, ...]] = ("value",)


@dataclass(slots=True, eq=False, init=False)
class CaseRange(Node):
    """``Case 1 To 5`` (VB form; not documented for GPL, accepted)."""

    low: Expr
    high: Expr
    _children: ClassVar[tuple[str, ...]] = ("low", "high")


@dataclass(slots=True, eq=False, init=False)
class CaseIs(Node):
    """``Case Is > 5`` (VB form; not documented for GPL, accepted). ``op`` is a comparison."""

    op: str
    value: Expr
    _children: ClassVar[tuple[str, ...]] = ("value",)


@dataclass(slots=True, eq=False, init=False)
class CaseClause(Stmt):
    """``Case a, b To c, Is > d`` and its block; ``items`` is empty for ``Case Else``."""

    items: list[CaseValue | CaseRange | CaseIs]
    body: Block
    is_else: bool = False
    _children: ClassVar[tuple[str, ...]] = ("items", "body")


@dataclass(slots=True, eq=False, init=False)
class Select(Stmt):
    """``Select [Case] subject``; ``cases`` in order, the ``Case Else`` clause (if any) last."""

    subject: Expr
    cases: list[CaseClause]
    end_comment: Comment | None = None
    end_comments: tuple[Comment, ...] = ()
    _children: ClassVar[tuple[str, ...]] = ("subject", "cases")


@dataclass(slots=True, eq=False, init=False)
class GoTo(Stmt):
    label: str


@dataclass(slots=True, eq=False, init=False)
class Exit(Stmt):
    """``Exit Sub|Function|Property|For|Do|While|Select|Try``; ``kind`` in canonical case."""

    kind: str


@dataclass(slots=True, eq=False, init=False)
class Return(Stmt):
    value: Expr | None
    _children: ClassVar[tuple[str, ...]] = ("value",)


@dataclass(slots=True, eq=False, init=False)
class Throw(Stmt):
    """``Throw exc``; ``value`` is ``None`` for a bare ``Throw`` (rethrow, not documented for GPL)."""

    value: Expr | None
    _children: ClassVar[tuple[str, ...]] = ("value",)


@dataclass(slots=True, eq=False, init=False)
class CatchClause(Stmt):
    """``Catch ex`` (GPL: a predeclared variable) or ``Catch ex As Exception`` (extension: ``type``)."""

    variable: str | None
    type: TypeRef | None
    body: Block
    _children: ClassVar[tuple[str, ...]] = ("type", "body")


@dataclass(slots=True, eq=False, init=False)
class FinallyClause(Stmt):
    body: Block
    _children: ClassVar[tuple[str, ...]] = ("body",)


@dataclass(slots=True, eq=False, init=False)
class Try(Stmt):
    body: Block
    catch: CatchClause | None
    finally_: FinallyClause | None
    end_comment: Comment | None = None
    _children: ClassVar[tuple[str, ...]] = ("body", "catch", "finally_")


@dataclass(slots=True, eq=False, init=False)
class ReDim(Stmt):
    """``ReDim target(bounds)``; ``preserve``: ``ReDim Preserve``, which keeps the elements that fit."""

    target: Expr
    bounds: list[Expr]
    preserve: bool = False
    _children: ClassVar[tuple[str, ...]] = ("target", "bounds")


# --------------------------------------------------------------------------------------------------
# declarations


@dataclass(slots=True, eq=False, init=False)
class VarDeclarator(Node):
    """One declared name.

    ``bounds`` is ``None`` for a scalar; for an array it has one entry per dimension: the upper-bound
    expression, or ``None`` when not given (``x()`` -> ``[None]``, ``x(,)`` -> ``[None, None]``).
    ``As New T(args)`` sets ``new=True`` and ``new_args``; ``= expr`` sets ``initializer``.  In
    ``Dim a, b As Integer`` both declarators share the same ``type`` node (spec §3.4).
    """

    name: str
    bounds: list[Expr | None] | None
    type: TypeRef | None
    new: bool = False
    new_args: list[Expr] | None = None
    initializer: Expr | None = None
    _children: ClassVar[tuple[str, ...]] = ("bounds", "type", "new_args", "initializer")


@dataclass(slots=True, eq=False, init=False)
class VarDecl(Stmt):
    """``Dim``/``Static``/``Const`` or modifier-only (``Public x As Integer``) declarations.

    ``keyword`` is ``"Dim"``, ``"Static"``, ``"Const"`` or ``None``; ``modifiers`` holds ``Public``,
    ``Private``, ``Shared`` in source order (canonical case).
    """

    keyword: str | None
    modifiers: list[str]
    declarators: list[VarDeclarator] | CompactDeclarators
    _children: ClassVar[tuple[str, ...]] = ("declarators",)

    @property
    def is_const(self) -> bool:
        return self.keyword == "Const"

    def children(self) -> Iterator[Node]:
        """The declarators; of a compact list, the type of each group (the nodes it holds): its
        names are made declarators only when asked, through ``declarators``, as a Chain's literal
        operands are (a walker that stacked a declarator per name held them all at once)."""
        decls = self.declarators
        if type(decls) is CompactDeclarators:
            return (type_ for _, _, type_ in decls.groups())
        return iter(decls)

    @property
    def compact(self) -> bool:
        """Whether the declarators are a :class:`CompactDeclarators` (every one simple)."""
        return type(self.declarators) is CompactDeclarators

    def expanded(self) -> VarDecl:
        """This declaration with its declarators in a list (``dump`` shows that form)."""
        if not self.compact:
            return self
        return VarDecl(self.span, self.keyword, self.modifiers, list(self.declarators),
                       leading_comments=self.leading_comments, trailing_comment=self.trailing_comment)


#: A ``Dim`` in a procedure body of this many names or more, every one simple (no bounds, no
#: ``New``, no value), is parsed into a :class:`CompactDeclarators` (fewer stay a list of
#: :class:`VarDeclarator`: every declaration a person writes keeps its tree).
DIM_MIN = 64


class CompactDeclarator(VarDeclarator):
    """A declarator of a :class:`CompactDeclarators`, made when asked.  Each ask makes a new one,
    so it compares and hashes by its position (its file, line and column, which no other
    declarator of the file has): every one made for the same name is the same declarator, as a
    key of the analysis's tables (``Model.redeclared``) and as a variable's ``decl``."""

    __slots__ = ()

    def __eq__(self, other: object) -> bool:
        return self is other or (type(other) is CompactDeclarator and self._line == other._line
                                 and self._col == other._col and self._file == other._file)

    def __hash__(self) -> int:
        return hash((self._line, self._col, self._file))


class CompactDeclarators:
    """The declarators of a long ``Dim`` of simple names (``Dim v0, v1, ... As Integer``; groups
    of names, each group with its type), held compactly: the names in one string, a name's line
    and column in arrays; a :class:`CompactDeclarator` is made only when a consumer asks for it
    (indexing, iteration), one at a time.

    Why: a ``Dim`` of 26,000 names held a VarDeclarator (120 bytes), an interned name (55) and a
    column number per name, 35 times the source (issue 20, docs/security.md "Input size").  A
    name costs its characters and twelve bytes here.  It means the list of declarators exactly:
    declarator ``i`` is ``VarDeclarator(span, name, None, type)``, its span from its name to the
    end of its group's type, as the parser gives a declarator of a list.

    The parser fills it (:meth:`add`, :meth:`close_group`, :meth:`done`); it has at least one
    name and every name has a group (a type)."""

    __slots__ = ("file", "_names", "_parts", "_chunks", "_starts", "lines", "cols", "_group_ends", "_group_types",
                 "_group_pos")

    def __init__(self, file: str) -> None:
        self.file = file
        self._names = ""  # every name, one after the other (:meth:`done`)
        self._parts: list[str] = []  # the names added since the last chunk was joined
        self._chunks: list[str] = []  # the names added before, 1,024 a string
        self._starts = array("I", [0])  # where name i starts in _names; one past the end last
        self.lines = array("I")
        self.cols = array("I")
        self._group_ends = array("I")  # one past the last name of each group
        self._group_types: list[TypeRef] = []
        self._group_pos = array("I")  # each group's end: line, column

    # -- built by the parser

    def add(self, name: str, line: int, col: int) -> None:
        parts = self._parts
        parts.append(name)
        self._starts.append(self._starts[-1] + len(name))
        self.lines.append(line)
        self.cols.append(col)
        if len(parts) >= 1024:  # (a list of the names' strings would cost what the declarators did)
            self._chunks.append("".join(parts))
            parts.clear()

    def close_group(self, type_: TypeRef, end_line: int, end_col: int) -> None:
        """The names added since the last group are declared ``As type_``, which ends there."""
        self._group_ends.append(len(self.lines))
        self._group_types.append(type_)
        self._group_pos.extend((end_line, end_col))

    def done(self) -> CompactDeclarators:
        """Join the names added so far (the parser calls it when the list ends)."""
        if self._parts or self._chunks:
            self._names += "".join(self._chunks) + "".join(self._parts)
            self._chunks.clear()
            self._parts.clear()
        return self

    def typed(self) -> int:
        """How many names have their group (a type) yet."""
        return self._group_ends[-1] if self._group_ends else 0

    # -- read

    def __len__(self) -> int:
        return len(self.lines)

    def name(self, i: int) -> str:
        return self._names[self._starts[i]:self._starts[i + 1]]

    def group(self, i: int) -> int:
        """The group of name ``i``."""
        return bisect_right(self._group_ends, i)

    def type(self, i: int) -> TypeRef:
        return self._group_types[self.group(i)]

    def groups(self) -> Iterator[tuple[int, int, TypeRef]]:
        """Each group: the index of its first name, one past its last, its type."""
        start = 0
        for end, type_ in zip(self._group_ends, self._group_types):
            yield start, end, type_
            start = end

    def __getitem__(self, i: int) -> CompactDeclarator:
        if not 0 <= i < len(self.lines):
            raise IndexError(i)
        g = self.group(i)
        line, col = self.lines[i], self.cols[i]
        span = _new_tuple(Span, (self.file, line, col, self._group_pos[2 * g], self._group_pos[2 * g + 1]))
        return CompactDeclarator(span, self.name(i), None, self._group_types[g])

    def __iter__(self) -> Iterator[CompactDeclarator]:
        return (self[i] for i in range(len(self.lines)))

    def declarators(self) -> tuple[list[VarDeclarator], list[VarDeclarator]]:
        """The names as plain VarDeclarators, as the parser made them before it knew the list was
        long: those of the closed groups (typed, their spans to the group's end) and those still
        waiting for their type (their spans the name alone).  (A name with bounds, ``New`` or a
        value, or a list that ends without a type, turns a list back into declarators.)"""
        self.done()
        typed = self.typed()
        done: list[VarDeclarator] = []
        for i in range(typed):
            d = self[i]
            done.append(VarDeclarator(d.span, d.name, None, d.type))
        waiting: list[VarDeclarator] = []
        for i in range(typed, len(self.lines)):
            name, line, col = self.name(i), self.lines[i], self.cols[i]
            span = _new_tuple(Span, (self.file, line, col, line, col + len(name)))
            waiting.append(VarDeclarator(span, name, None, None))
        return done, waiting


@dataclass(slots=True, eq=False, init=False)
class Param(Node):
    """``[Optional] [ByVal|ByRef] name[()] As T [= default]``.

    ``by_ref`` is False by default (GPL default is ByVal); ``array_rank`` is 0 for scalars.
    ``Optional``/defaults are an extension that real code uses (the manual excludes them).
    """

    name: str
    type: TypeRef | None
    by_ref: bool = False
    array_rank: int = 0
    optional: bool = False
    default: Expr | None = None
    _children: ClassVar[tuple[str, ...]] = ("type", "default")


@dataclass(slots=True, eq=False, init=False)
class ProcDecl(Stmt):
    """``Sub`` or ``Function`` (``kind``); a constructor is a Sub named ``New``."""

    kind: str
    name: str
    modifiers: list[str]
    params: list[Param]
    return_type: TypeRef | None
    body: Block
    end_comment: Comment | None = None
    _children: ClassVar[tuple[str, ...]] = ("params", "return_type", "body")


@dataclass(slots=True, eq=False, init=False)
class Accessor(Stmt):
    """A property's ``Get`` or ``Set`` block; ``param`` is the Set parameter (``None`` if omitted:
    then it is implicitly ``value``)."""

    kind: str
    param: Param | None
    body: Block
    end_comment: Comment | None = None
    _children: ClassVar[tuple[str, ...]] = ("param", "body")


@dataclass(slots=True, eq=False, init=False)
class PropertyDecl(Stmt):
    name: str
    modifiers: list[str]
    type: TypeRef | None
    getter: Accessor | None
    setter: Accessor | None
    end_comment: Comment | None = None
    end_comments: tuple[Comment, ...] = ()
    _children: ClassVar[tuple[str, ...]] = ("type", "getter", "setter")


@dataclass(slots=True, eq=False, init=False)
class DelegateDecl(Stmt):
    kind: str
    name: str
    modifiers: list[str]
    params: list[Param]
    return_type: TypeRef | None
    _children: ClassVar[tuple[str, ...]] = ("params", "return_type")


@dataclass(slots=True, eq=False, init=False)
class ClassDecl(Stmt):
    name: str
    modifiers: list[str]
    members: list[Stmt]
    end_comment: Comment | None = None
    end_comments: tuple[Comment, ...] = ()
    _children: ClassVar[tuple[str, ...]] = ("members",)


@dataclass(slots=True, eq=False, init=False)
class ModuleDecl(Stmt):
    name: str
    members: list[Stmt]
    end_comment: Comment | None = None
    end_comments: tuple[Comment, ...] = ()
    _children: ClassVar[tuple[str, ...]] = ("members",)


@dataclass(slots=True, eq=False, init=False)
class SourceUnit(Node):
    """One parsed file: its modules (and top-level classes, AMB-1).  Members that were misplaced at
    the top level (reported) are kept too, so later errors can still be found.

    ``compact_dims``: whether a Dim of the file holds its declarators compactly (or did, before
    an edit: :class:`CompactDeclarators`), which the language server's moving of lines cannot
    move (``syntax/reparse.py``)."""

    path: str
    members: list[Stmt]
    end_comments: tuple[Comment, ...] = ()
    compact_dims: bool = False
    _children: ClassVar[tuple[str, ...]] = ("members",)


# --------------------------------------------------------------------------------------------------
# visitors and dump


def _install_inits(root: type[Node]) -> None:
    """Give ``root`` and every node class below it an ``__init__`` with the signature the
    dataclass would write (span first, then the fields, keyword-only ones after ``*``), which
    unpacks the span into the five position slots itself.

    Why not the dataclass's: it calls ``__post_init__`` for the span, a second Python call per
    node, and a parse makes one node per two tokens; and it compiles one function per class at
    import, where this compiles them all in one go (``gpl2py check``'s start-up).  The classes
    are dataclasses with ``init=False``; ``fields()``, ``repr`` and ``dump`` are unchanged.
    """
    classes = [root]
    for cls in classes:  # (a slots dataclass replaces its class: skip the replaced ones)
        classes.extend(c for c in cls.__subclasses__() if globals().get(c.__name__) is c)
    namespace: dict[str, object] = {"_FACTORY": _FACTORY}
    source: list[str] = []
    for i, cls in enumerate(classes):
        params, keywords, body = ["self", "span"], [], []
        for f in fields(cls):  # (without the span, an InitVar, and ClassVars)
            if f.name in _POSITION:
                continue  # unpacking the span sets them
            default = _default_name(f, i, namespace)
            if not f.init:
                if default is not None:
                    body.append(f"self.{f.name} = {default}" + ("()" if f.default is MISSING else ""))
                continue
            if f.default_factory is not MISSING:  # type: ignore[misc]
                param = f"{f.name}=_FACTORY"
                body.append(f"self.{f.name} = {default}() if {f.name} is _FACTORY else {f.name}")
            else:
                param = f.name if default is None else f"{f.name}={default}"
                body.append(f"self.{f.name} = {f.name}")
            (keywords if f.kw_only else params).append(param)
        signature = ", ".join(params + (["*"] + keywords if keywords else []))
        source.append(f"def _init_{i}({signature}):\n"
                      f"    self._file, self._line, self._col, self._end_line, self._end_col = span\n"
                      + "".join(f"    {line}\n" for line in body))
    exec("".join(source), namespace)  # noqa: S102 - source built above from the field tables only
    for i, cls in enumerate(classes):
        init = namespace[f"_init_{i}"]
        init.__qualname__ = f"{cls.__qualname__}.__init__"  # type: ignore[attr-defined]
        init.__module__ = cls.__module__  # type: ignore[attr-defined]
        cls.__init__ = init  # type: ignore[misc]


_POSITION = ("_file", "_line", "_col", "_end_line", "_end_col")
_FACTORY = object()  # "no argument": the field's default_factory makes its value


def _default_name(f: Field[Any], i: int, namespace: dict[str, object]) -> str | None:
    """The name under which the generated ``__init__`` of class ``i`` finds ``f``'s default (or
    default factory); ``None`` when it has neither."""
    value = f.default if f.default is not MISSING else f.default_factory  # type: ignore[misc]
    if value is MISSING:
        return None
    name = f"_d_{i}_{f.name}"
    namespace[name] = value
    return name


_install_inits(Node)


class NodeVisitor:
    """Calls ``visit_<ClassName>(node)``; falls back to :meth:`generic_visit`, which visits children."""

    def visit(self, node: Node) -> Any:
        method = getattr(self, "visit_" + type(node).__name__, None)
        if method is None:
            return self.generic_visit(node)
        return method(node)

    def generic_visit(self, node: Node) -> Any:
        for child in node.children():
            self.visit(child)
        return None


class NodeTransformer(NodeVisitor):
    """Like :class:`NodeVisitor`, but the result of each visit replaces the child.

    Returning ``None`` from a visit removes a child that lives in a list (and sets a single child
    to ``None``); returning a list splices several nodes into a list field.
    """

    def generic_visit(self, node: Node) -> Any:
        for name in node._children:
            value = getattr(node, name)
            if isinstance(value, list):
                new: list[Any] = []
                for item in value:
                    if not isinstance(item, Node):
                        new.append(item)
                        continue
                    result = self.visit(item)
                    if result is None:
                        continue
                    if isinstance(result, list):
                        new.extend(result)
                    else:
                        new.append(result)
                value[:] = new
            elif isinstance(value, Node):
                setattr(node, name, self.visit(value))
        return node


_DUMP_SKIP = frozenset(
    {"_file", "_line", "_col", "_end_line", "_end_col", "_info", "leading_comments", "trailing_comment", "end_comment", "end_comments", "header_comment",
     "compact_dims"}
)


def dump(node: Node, *, comments: bool = True, positions: bool = True) -> str:
    """A readable, indented rendering of ``node`` (used by ``gpl2py dump-ast``).

    One line per node: ``ClassName field=value ... @line:col``; child nodes are indented below,
    list fields get a ``field:`` heading.  Comments are shown as ``' text`` lines when ``comments``.

    The walk uses an explicit stack, not recursion: a long operator chain (``a & b & … `` continued
    over hundreds of lines) is a left-leaning tree as deep as it is long, and must not exhaust the
    Python stack.
    """
    out: list[str] = []
    stack: list[str | tuple[Node, int]] = [(node, 0)]
    while stack:
        item = stack.pop()
        if isinstance(item, str):
            out.append(item)
        else:
            stack.extend(reversed(_dump_node(item[0], item[1], out, comments, positions)))
    return "\n".join(out) + "\n"


def _dump_node(
    node: Node, depth: int, out: list[str], comments: bool, positions: bool
) -> list[str | tuple[Node, int]]:
    """Append ``node``'s own lines to ``out``; return what follows them, in order (child nodes to
    render at a depth, and literal lines such as field headings and closing comments)."""
    if isinstance(node, Chain):
        node = node.nested()
    elif isinstance(node, VarDecl):
        node = node.expanded()
    pad = "  " * depth
    if comments:
        for c in getattr(node, "leading_comments", ()):
            out.append(f"{pad}{_comment(c)}")
    scalars: list[str] = []
    nested: list[tuple[str, Any]] = []
    for f in fields(node):
        if f.name in _DUMP_SKIP or f.name == "_":
            continue
        value = getattr(node, f.name)
        if isinstance(value, Node) or (
            isinstance(value, list) and any(isinstance(v, Node) for v in value)
        ):
            nested.append((f.name, value))
        elif isinstance(value, list) and f.name in node._children:
            if value:  # e.g. bounds [None]
                scalars.append(f"{f.name}={value!r}")
        elif value is None or value == [] or (f.default is not MISSING and value == f.default):
            continue  # unset optional parts and fields at their default stay out of the way
        else:
            scalars.append(f"{f.name}={value!r}")
    head = f"{pad}{'VarDeclarator' if isinstance(node, VarDeclarator) else type(node).__name__}"
    if scalars:
        head += " " + " ".join(scalars)
    if positions:
        head += f" @{node.span.line}:{node.span.col}"
    if comments:
        for attr in ("trailing_comment", "header_comment"):
            c = getattr(node, attr, None)
            if c is not None:
                head += f"  {_comment(c)}"
    out.append(head)
    follow: list[str | tuple[Node, int]] = []
    for name, value in nested:
        if isinstance(value, Node):
            if len(nested) > 1 or not isinstance(node, (Block,)):
                follow.append(f"{pad}  {name}:")
                follow.append((value, depth + 2))
            else:
                follow.append((value, depth + 1))
        else:
            follow.append(f"{pad}  {name}:")
            for item in value:
                follow.append(f"{pad}    None" if item is None else (item, depth + 2))
    if comments:
        for c in getattr(node, "end_comments", ()):
            follow.append(f"{pad}  {_comment(c)}")
        c = getattr(node, "end_comment", None)
        if c is not None:
            follow.append(f"{pad}  (end) {_comment(c)}")
    return follow


def _comment(c: Comment) -> str:
    return c.text if c.directive else "'" + c.text

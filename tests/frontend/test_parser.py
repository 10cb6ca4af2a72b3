"""Parser tests: the AST shape of every construct, operator precedence, comments, and recovery."""

from __future__ import annotations

import pytest

from gpl2py.diagnostics import DiagnosticSink, Severity
from gpl2py.source import SourceFile
from gpl2py.gpl.syntax import ast as A
from gpl2py.gpl.syntax.parser import parse, parse_expression


def parse_text(text: str) -> tuple[A.SourceUnit, DiagnosticSink]:
    sink = DiagnosticSink()
    return parse(SourceFile("t.gpl", text), sink), sink


def body(stmts: str) -> tuple[list[A.Stmt], DiagnosticSink]:
    """Parse statements inside ``Module M / Sub Main``; returns the Sub's statements."""
    indented = "\n".join("        " + line for line in stmts.strip("\n").splitlines())
    unit, sink = parse_text(f"Module M\n    Sub Main()\n{indented}\n    End Sub\nEnd Module\n")
    proc = unit.members[0].members[0]  # type: ignore[attr-defined]
    assert isinstance(proc, A.ProcDecl)
    return proc.body.statements, sink


def ok(stmts: str) -> list[A.Stmt]:
    out, sink = body(stmts)
    assert [d.header() for d in sink] == []
    return out


def errors(text: str) -> list[tuple[int, int, str]]:
    _, sink = parse_text(text)
    return [(d.span.line, d.span.col, d.code) for d in sink if d.severity is Severity.ERROR]


def _walk(node: A.Node) -> list[A.Node]:
    """``node`` and every node below it, in source order."""
    out = [node]
    for c in node.children():
        out.extend(_walk(c))
    return out


def sx(e: A.Node | None) -> str:
    """A compact prefix rendering of an expression, for shape assertions."""
    if e is None:
        return "None"
    if isinstance(e, A.Name):
        return e.name
    if isinstance(e, (A.IntegerLiteral, A.RealLiteral)):
        return e.text
    if isinstance(e, A.StringLiteral):
        return repr(e.value)
    if isinstance(e, A.BooleanLiteral):
        return str(e.value)
    if isinstance(e, A.NothingLiteral):
        return "Nothing"
    if isinstance(e, A.MeExpr):
        return "Me"
    if isinstance(e, A.Binary):
        return f"({e.op} {sx(e.left)} {sx(e.right)})"
    if isinstance(e, A.Unary):
        return f"({e.op} {sx(e.operand)})"
    if isinstance(e, A.MemberAccess):
        return f"{sx(e.target)}.{e.name}"
    if isinstance(e, A.Invoke):
        return f"{sx(e.target)}[{', '.join(sx(a) for a in e.args)}]"
    if isinstance(e, A.New):
        args = "" if e.args is None else f"[{', '.join(sx(a) for a in e.args)}]"
        return f"(New {e.type.name}{args})"
    if isinstance(e, A.AddressOf):
        return f"(AddressOf {sx(e.target)})"
    return type(e).__name__


def expr(text: str) -> str:
    sink = DiagnosticSink()
    e = parse_expression(SourceFile("e.gpl", text), sink)
    assert [d.header() for d in sink] == []
    return sx(e)


# --------------------------------------------------------------------------- precedence


@pytest.mark.parametrize(
    ("text", "shape"),
    [
        ("a + b * c", "(+ a (* b c))"),
        ("a * b + c", "(+ (* a b) c)"),
        ("a - b - c", "(- (- a b) c)"),  # left-associative
        ("2 ^ 3 ^ 2", "(^ (^ 2 3) 2)"),  # left-associative (spec: 2^3^2 = 64)
        ("-x ^ 2", "(- (^ x 2))"),  # negation binds looser than ^
        ("2 * -4", "(* 2 (- 4))"),
        ("x ^ -1", "(^ x (- 1))"),
        ("+a", "(+ a)"),
        ("a * b / c", "(/ (* a b) c)"),
        ("a / b \\ c", "(\\ (/ a b) c)"),  # \ below * and /
        ("a \\ b * c", "(\\ a (* b c))"),
        ("a Mod b \\ c", "(Mod a (\\ b c))"),  # Mod below \
        ("a + b Mod c", "(+ a (Mod b c))"),  # + below Mod
        ("a & b + c", "(& a (+ b c))"),  # & below +
        ("a << b & c", "(<< a (& b c))"),  # shifts below &
        ("a >> 1 << 2", "(<< (>> a 1) 2)"),
        ("a = b << c", "(= a (<< b c))"),  # comparisons below shifts
        ("a <> b", "(<> a b)"),
        ("a < b", "(< a b)"),
        ("a > b", "(> a b)"),
        ("a <= b", "(<= a b)"),
        ("a >= b", "(>= a b)"),
        ("a Is Nothing", "(Is a Nothing)"),
        ("a = b = c", "(= (= a b) c)"),
        ("Not a = b", "(Not (= a b))"),  # Not below comparisons
        ("Not child Is Nothing", "(Not (Is child Nothing))"),
        ("Not a And b", "(And (Not a) b)"),  # And below Not
        ("a And b Or c", "(Or (And a b) c)"),
        ("a Or b And c", "(Or a (And b c))"),
        ("a AndAlso b OrElse c", "(OrElse (AndAlso a b) c)"),
        ("a Or b Xor c", "(Xor (Or a b) c)"),  # Xor lowest
        ("a Xor b Or c", "(Xor a (Or b c))"),
        ("(a + b) * c", "(* (+ a b) c)"),
        ("x < -y", "(< x (- y))"),
        ("a And Not b", "(And a (Not b))"),
        ("- - a", "(- (- a))"),
    ],
)
def test_operator_precedence_and_associativity(text: str, shape: str) -> None:
    assert expr(text) == shape


def test_primaries() -> None:
    assert expr("Me.count") == "Me.count"
    assert expr("a.b(1).c") == "a.b[1].c"
    assert expr("del_obj(index)(3)") == "del_obj[index][3]"
    assert expr("New Location") == "(New Location)"
    assert expr("New IPEndPoint(\"\", 1234)") == "(New IPEndPoint['', 1234])"
    assert expr("New MyMod.My_class()") == "(New MyMod.My_class[])"
    assert expr("New My_template(AddressOf my_obj.My_fn)") == "(New My_template[(AddressOf my_obj.My_fn)])"
    assert expr("True Or False") == "(Or True False)"
    assert expr("tl.Stop()") == "tl.Stop[]"  # keywords are fine as member names
    assert expr("x.Select.End") == "x.Select.End"
    assert expr("&H20 + .9") == "(+ &H20 .9)"


def test_expression_spans_cover_the_source() -> None:
    sink = DiagnosticSink()
    e = parse_expression(SourceFile("e.gpl", "a + foo(1, 2) * 3"), sink)
    assert isinstance(e, A.Binary)
    assert (e.span.col, e.span.end_col) == (1, 18)
    assert (e.right.span.col, e.right.span.end_col) == (5, 18)


def test_isnot_is_reported_but_parsed() -> None:
    sink = DiagnosticSink()
    e = parse_expression(SourceFile("e.gpl", "a IsNot Nothing"), sink)
    assert sx(e) == "(Not (Is a Nothing))"
    assert [d.code for d in sink] == ["GPL1103"]
    assert "IsNot" in sink.errors[0].message


# --------------------------------------------------------------------------- statements


def test_assignment_versus_equality_by_position() -> None:
    (s,) = ok("x = a = b")
    assert isinstance(s, A.Assign) and s.op == "=" and sx(s.target) == "x"
    assert sx(s.value) == "(= a b)"


@pytest.mark.parametrize("op", ["^=", "*=", "/=", "\\=", "+=", "-=", "<<=", ">>=", "&="])
def test_every_compound_assignment(op: str) -> None:
    (s,) = ok(f"a(i).b {op} y + 1")
    assert isinstance(s, A.Assign)
    assert s.op == op
    assert sx(s.target) == "a[i].b"
    assert sx(s.value) == "(+ y 1)"


def test_call_statements_with_and_without_parentheses() -> None:
    stmts = ok(
        """
Move.WaitForEOM
Robot.Home
Console.WriteLine("x")
Call MyProcedure (1, 2, 3)
MyProcedure (1, 2, 3)
My_Sub ( Loc1 )
aa.Increment
MyProc
"""
    )
    assert all(isinstance(s, A.CallStmt) for s in stmts)
    assert [sx(s.expr) for s in stmts] == [  # type: ignore[attr-defined]
        "Move.WaitForEOM",
        "Robot.Home",
        "Console.WriteLine['x']",
        "MyProcedure[1, 2, 3]",
        "MyProcedure[1, 2, 3]",
        "My_Sub[Loc1]",
        "aa.Increment",
        "MyProc",
    ]
    assert [s.call_keyword for s in stmts] == [False, False, False, True, False, False, False, False]  # type: ignore[attr-defined]


def test_block_if_with_elseif_and_else() -> None:
    (s,) = ok(
        """
If a Then
    x = 1
ElseIf b Then
    x = 2
ElseIf c Then
    x = 3
Else
    x = 4
End If
"""
    )
    assert isinstance(s, A.If) and not s.single_line
    assert sx(s.condition) == "a"
    assert [sx(c.condition) for c in s.elseifs] == ["b", "c"]
    assert s.else_body is not None and len(s.else_body.statements) == 1
    assert (s.span.line, s.span.col, s.span.end_line, s.span.end_col) == (3, 9, 11, 15)


def test_single_line_if_with_else_and_nested_if() -> None:
    (s, t, u) = ok(
        """
If c < 0 Then Exit For
If a Then x = 1 Else x = 2
If a Then If b Then Return
"""
    )
    assert isinstance(s, A.If) and s.single_line
    assert isinstance(s.then_body.statements[0], A.Exit)
    assert isinstance(t, A.If) and t.else_body is not None
    assert sx(t.else_body.statements[0].value) == "2"  # type: ignore[attr-defined]
    assert isinstance(u, A.If) and isinstance(u.then_body.statements[0], A.If)


def test_else_if_on_one_line_reads_as_elseif_with_a_warning() -> None:
    out, sink = body("If a Then\n    x = 1\nElse If b Then\n    x = 2\nEnd If")
    (s,) = out
    assert isinstance(s, A.If) and len(s.elseifs) == 1 and s.else_body is None
    assert [d.code for d in sink] == ["GPL1118"] and not sink.errors


def test_for_next_with_step_and_element_variable() -> None:
    s, t = ok("For i = 10 To 1 Step -1\n    x += i\nNext i\nFor a(2).b = 1 To n\nNext")
    assert isinstance(s, A.For)
    assert (sx(s.var), sx(s.start), sx(s.end), sx(s.step), sx(s.next_var)) == ("i", "10", "1", "(- 1)", "i")
    assert isinstance(t, A.For) and sx(t.var) == "a[2].b" and t.step is None and t.next_var is None


def test_for_each() -> None:
    (s,) = ok("For Each v In arr\n    x += v\nNext")
    assert isinstance(s, A.ForEach) and sx(s.var) == "v" and sx(s.collection) == "arr"


def test_while_and_all_do_forms() -> None:
    stmts = ok(
        """
While Not tl.Pending()
    Thread.Sleep(5000)
End While
Do While x < 3
Loop
Do Until x >= 3
Loop
Do
Loop While c <> 27
Do
Loop Until done
Do
    Exit Do
Loop
"""
    )
    w = stmts[0]
    assert isinstance(w, A.While) and sx(w.condition) == "(Not tl.Pending[])"
    forms = [(s.test_at_top, s.until, sx(s.condition)) for s in stmts[1:]]  # type: ignore[attr-defined]
    assert forms == [
        (True, False, "(< x 3)"),
        (True, True, "(>= x 3)"),
        (False, False, "(<> c 27)"),
        (False, True, "done"),
        (False, False, "None"),
    ]


def test_select_both_spellings_and_all_case_forms() -> None:
    s, t = ok(
        """
Select x
    Case 1, 3, 5
        y = 1
    Case "red", color2, "blue" & "green"
        y = 2
    Case Else
        y = 3
End Select
Select Case n
    Case 1 To 5, Is > 10, Is <= -1
    Case Else
End Select
"""
    )
    assert isinstance(s, A.Select) and sx(s.subject) == "x"
    assert [len(c.items) for c in s.cases] == [3, 3, 0]
    assert s.cases[2].is_else
    assert sx(s.cases[1].items[2].value) == "(& 'blue' 'green')"  # type: ignore[union-attr]
    assert isinstance(t, A.Select)
    items = t.cases[0].items
    assert isinstance(items[0], A.CaseRange) and (sx(items[0].low), sx(items[0].high)) == ("1", "5")
    assert isinstance(items[1], A.CaseIs) and items[1].op == ">"
    assert isinstance(items[2], A.CaseIs) and items[2].op == "<=" and sx(items[2].value) == "(- 1)"


@pytest.mark.parametrize("kind", ["Sub", "Function", "Property", "For", "Do", "While", "Select", "Try"])
def test_every_exit(kind: str) -> None:
    (s,) = ok(f"exit {kind.lower()}")
    assert isinstance(s, A.Exit) and s.kind == kind


def test_return_goto_throw_redim() -> None:
    stmts = ok("Return\nReturn x + 1\nGoTo retry\nGoto 100\nThrow exc\nThrow\nReDim Count(9)\nReDim TwoD(1, 100)")
    assert isinstance(stmts[0], A.Return) and stmts[0].value is None
    assert sx(stmts[1].value) == "(+ x 1)"  # type: ignore[attr-defined]
    assert [s.label for s in stmts[2:4]] == ["retry", "100"]  # type: ignore[attr-defined]
    assert isinstance(stmts[4], A.Throw) and sx(stmts[4].value) == "exc"
    assert isinstance(stmts[5], A.Throw) and stmts[5].value is None
    r = stmts[7]
    assert isinstance(r, A.ReDim) and sx(r.target) == "TwoD" and [sx(b) for b in r.bounds] == ["1", "100"]


def test_redim_preserve_is_parsed_without_a_diagnostic() -> None:
    """The vendor's TCS uses ReDim Preserve on locals and on arrays inside objects (real-code.md)."""
    stmts = ok("ReDim Preserve a(10)\nReDim Preserve item.values(n + 1)\nReDim Preserve m(2, k)\nReDim b(3)")
    assert [s.preserve for s in stmts] == [True, True, True, False]  # type: ignore[attr-defined]
    assert sx(stmts[1].target) == "item.values" and sx(stmts[1].bounds[0]) == "(+ n 1)"  # type: ignore[attr-defined]
    assert [sx(b) for b in stmts[2].bounds] == ["2", "k"]  # type: ignore[attr-defined]


def test_preserve_stays_an_ordinary_name() -> None:
    stmts = ok("ReDim Preserve(3)\nPreserve = 1")
    assert isinstance(stmts[0], A.ReDim) and not stmts[0].preserve and sx(stmts[0].target) == "Preserve"
    assert isinstance(stmts[1], A.Assign)


def test_try_catch_finally_forms() -> None:
    s, t = ok(
        """
Try
    test()
Catch exc1
    Console.WriteLine("Exception!")
Finally
    Exit Try
End Try
Try
    x = 1
Catch ex As Exception
End Try
"""
    )
    assert isinstance(s, A.Try) and s.catch is not None and s.catch.variable == "exc1"
    assert s.finally_ is not None and isinstance(s.finally_.body.statements[0], A.Exit)
    assert isinstance(t, A.Try) and t.catch is not None and t.catch.type is not None
    assert t.catch.type.name == "Exception" and t.finally_ is None


def test_labels_indented_numeric_and_followed_by_statement() -> None:
    stmts = ok("retry:\n    _exit:\n100: x = 1\ndone:")
    assert [type(s).__name__ for s in stmts] == ["Label", "Label", "Label", "Assign", "Label"]
    assert [s.name for s in stmts if isinstance(s, A.Label)] == ["retry", "_exit", "100", "done"]


def test_label_at_end_of_sub_before_end_sub() -> None:
    unit, sink = parse_text("Module M\nSub S\n    GoTo done\ndone:\nEnd Sub\nEnd Module\n")
    assert not sink.errors
    proc = unit.members[0].members[0]  # type: ignore[attr-defined]
    assert isinstance(proc.body.statements[-1], A.Label)


# --------------------------------------------------------------------------- declarations


def test_dim_with_several_clauses_shares_types() -> None:
    (d,) = ok("Dim a, b As Single, c As Integer")
    assert isinstance(d, A.VarDecl) and d.keyword == "Dim"
    assert [(v.name, v.type.name) for v in d.declarators] == [("a", "Single"), ("b", "Single"), ("c", "Integer")]  # type: ignore[union-attr]
    assert d.declarators[0].type is d.declarators[1].type


def test_declarator_forms() -> None:
    stmts = ok(
        """
Dim x(3,4) As Integer
Dim y(,) As Integer
Dim z() As Double
Dim loc As New Location
Dim bb As New cc(15)
Dim l2 As Location = New Location
Dim n As Integer = 1
Static jj As Short
Const MaxCount As Integer = 10
Dim t As MyMod.My_class
"""
    )
    ds = [s.declarators[0] for s in stmts]  # type: ignore[attr-defined]
    assert [sx(b) for b in ds[0].bounds] == ["3", "4"]
    assert ds[1].bounds == [None, None]
    assert ds[2].bounds == [None]
    assert ds[3].new and ds[3].new_args is None and ds[3].type.name == "Location"
    assert ds[4].new and [sx(a) for a in ds[4].new_args] == ["15"]
    assert sx(ds[5].initializer) == "(New Location)" and not ds[5].new
    assert sx(ds[6].initializer) == "1"
    assert stmts[7].keyword == "Static"  # type: ignore[attr-defined]
    assert stmts[8].is_const and sx(ds[8].initializer) == "10"  # type: ignore[attr-defined]
    assert ds[9].type.name == "MyMod.My_class" and ds[9].type.parts == ["MyMod", "My_class"]


def test_module_class_members_and_modifiers() -> None:
    unit, sink = parse_text(
        """
Module MyMod
    Public ModVar As Integer
    Private Const K As Double = 2.5
    Public Class My_class
        Public Shared MaxSize As Integer
        Private Shared Size2 As Integer
        Public Class Inner
        End Class
    End Class
    Delegate Function My_template(ByVal arg1 As Integer) As String
    Public Delegate Sub Callback()
    Public Shared Function Twice(ByRef v As Integer, Optional ByVal k As Integer = 2, arr() As Double) As Integer
        Return v * k
    End Function
End Module
Class TopLevel
End Class
"""
    )
    assert not sink.errors, [d.header() for d in sink]
    mod, top = unit.members
    assert isinstance(mod, A.ModuleDecl) and mod.name == "MyMod"
    assert isinstance(top, A.ClassDecl)  # AMB-1: accepted at top level
    var, const, cls, dlg, dlg2, fn = mod.members
    assert isinstance(var, A.VarDecl) and var.keyword is None and var.modifiers == ["Public"]
    assert isinstance(const, A.VarDecl) and const.is_const and const.modifiers == ["Private"]
    assert isinstance(cls, A.ClassDecl) and cls.modifiers == ["Public"]
    assert cls.members[0].modifiers == ["Public", "Shared"]  # type: ignore[attr-defined]
    assert isinstance(cls.members[2], A.ClassDecl)  # nested class
    assert isinstance(dlg, A.DelegateDecl) and dlg.kind == "Function" and dlg.return_type.name == "String"  # type: ignore[union-attr]
    assert isinstance(dlg2, A.DelegateDecl) and dlg2.kind == "Sub" and dlg2.params == []
    assert isinstance(fn, A.ProcDecl) and fn.modifiers == ["Public", "Shared"]
    p0, p1, p2 = fn.params
    assert (p0.name, p0.by_ref, p0.optional) == ("v", True, False)
    assert (p1.name, p1.by_ref, p1.optional, sx(p1.default)) == ("k", False, True, "2")
    assert (p2.name, p2.array_rank, p2.type.name) == ("arr", 1, "Double")  # type: ignore[union-attr]


def test_property_constructor_and_set_parameter() -> None:
    unit, sink = parse_text(
        """
Module M
Public Class cc
    Private size_in As Integer
    Public Property Size As Integer
        Get
            Return size_in
        End Get
        Set (value As Integer)
            size_in = value
        End Set
    End Property
    Public Sub New
        size_in = 25
    End Sub
    Public Sub New (value As Integer)
        size_in = value
    End Sub
    Property Bare As Integer
        Set
        End Set
    End Property
End Class
End Module
"""
    )
    assert not sink.errors, [d.header() for d in sink]
    cls = unit.members[0].members[0]  # type: ignore[attr-defined]
    prop = cls.members[1]
    assert isinstance(prop, A.PropertyDecl) and prop.getter is not None and prop.setter is not None
    assert prop.setter.param is not None and prop.setter.param.name == "value"
    assert isinstance(prop.getter.body.statements[0], A.Return)
    ctor1, ctor2 = cls.members[2:4]
    assert ctor1.name == "New" and ctor1.params == [] and len(ctor2.params) == 1
    bare = cls.members[4]
    assert bare.getter is None and bare.setter is not None and bare.setter.param is None


def test_property_with_empty_parentheses_is_a_plain_property() -> None:
    unit, sink = parse_text(
        """
Module M
Public Class Cell
    Private name_in As String
    Public Property Name() As String
        Get()
            Return name_in
        End Get
        Set(ByVal value As String)
            name_in = value
        End Set
    End Property
    Public Property Item(ByVal i As Integer) As String
        Get
            Return name_in
        End Get
    End Property
End Class
End Module
"""
    )
    assert [(d.span.line, d.span.col, d.code) for d in sink] == [(13, 25, "GPL1103")]  # only Item(i)
    name = unit.members[0].members[0].members[1]  # type: ignore[attr-defined]
    assert isinstance(name, A.PropertyDecl) and name.name == "Name" and name.type.name == "String"  # type: ignore[union-attr]
    assert name.getter is not None and name.setter is not None and name.setter.param.name == "value"  # type: ignore[union-attr]


def test_declaration_errors() -> None:
    # E07 (no type), several names with New, array initialiser, rank 5
    out, sink = body(
        "Dim BlackObject1\nDim a, b As New Location\nDim c(3) As Integer = 4\nDim d(1,1,1,1,1) As Integer"
    )
    assert [(d.span.line, d.code) for d in sink] == [(3, "GPL1107"), (4, "GPL1112"), (5, "GPL1113"), (6, "GPL1114")]
    assert len(out) == 4  # still in the tree


@pytest.mark.parametrize("block", [
    "If c Then\n{d}\nEnd If",
    "If c Then\nElseIf d Then\n{d}\nElse\n{d}\nEnd If",
    "Select n\nCase 1\n{d}\nCase Else\n{d}\nEnd Select",
    "For ii = 1 To 10\n{d}\nNext ii",
    "While c\n{d}\nEnd While",
    "Do\n{d}\nLoop Until c",
    "Try\n{d}\nCatch ex As Exception\n{d}\nFinally\n{d}\nEnd Try",
])
def test_declarations_inside_blocks_parse_without_a_diagnostic(block: str) -> None:
    """The manual (§3.2.6) allows Dim only at a procedure's outermost level; the vendor's TCS
    declares in If/Select/loop blocks and the controller compiles it (real-code.md)."""
    decls = "Dim jj As Integer = ii * 2\nDim torques(12) As Double\nDim loc As New Location\nStatic n As Integer\nConst k As Integer = 3"
    stmts = ok(block.replace("{d}", decls))
    assert len(stmts) == 1
    found = [n for n in _walk(stmts[0]) if isinstance(n, A.VarDecl)]
    assert found and len(found) % 5 == 0
    assert [s.keyword for s in found[:5]] == ["Dim", "Dim", "Dim", "Static", "Const"]  # type: ignore[attr-defined]


# --------------------------------------------------------------------------- comments


def test_comments_are_attached_to_statements_blocks_and_containers() -> None:
    unit, sink = parse_text(
        """' file header
#Region "All"
Module M ' the module
    ' before x
    Dim x As Integer ' x's comment
    Sub S()
        ' lead 1
        ' lead 2
        x = 1 ' trailing
        If x Then ' if line
            y = 2
            ' end of then
        Else ' else line
            y = 3
        End If ' after end if
        ' last in body
    End Sub
    ' end of module
End Module
#End Region
"""
    )
    assert not sink.errors
    mod = unit.members[0]
    assert [c.text for c in mod.leading_comments] == [" file header", '#Region "All"']
    assert mod.leading_comments[1].directive
    assert mod.trailing_comment.text == " the module"
    x = mod.members[0]
    assert [c.text for c in x.leading_comments] == [" before x"] and x.trailing_comment.text == " x's comment"
    proc = mod.members[1]
    assign, if_ = proc.body.statements
    assert [c.text for c in assign.leading_comments] == [" lead 1", " lead 2"]
    assert assign.trailing_comment.text == " trailing"
    assert if_.trailing_comment.text == " if line"
    assert [c.text for c in if_.then_body.end_comments] == [" end of then"]
    assert if_.else_body.header_comment.text == " else line"
    assert if_.end_comment.text == " after end if"
    assert [c.text for c in proc.body.end_comments] == [" last in body"]
    assert [c.text for c in mod.end_comments] == [" end of module"]
    assert [c.text for c in unit.end_comments] == ["#End Region"]


def test_continuation_comment_joins_the_trailing_comment() -> None:
    out, sink = body("x = a + _ ' first\n    b ' second")
    assert out[0].trailing_comment.text == " first  second"
    assert [d.code for d in sink] == ["GPL1005"]


# --------------------------------------------------------------------------- continuation


def test_continuation_across_many_lines_inside_parameter_list_and_expression() -> None:
    params = ", _\n".join(f"    ByVal p{i} As Integer" for i in range(22))
    terms = " _\n".join(f"        + p{i}" for i in range(22))
    text = f"Module M\nFunction F( _\n{params})  As Integer\n    Return 0 _\n{terms}\nEnd Function\nEnd Module\n"
    unit, sink = parse_text(text)
    assert not sink.errors, [d.header() for d in sink]
    fn = unit.members[0].members[0]
    assert len(fn.params) == 22
    ret = fn.body.statements[0]
    assert isinstance(ret, A.Return)
    n = 0
    e = ret.value
    while isinstance(e, A.Binary):
        n += 1
        e = e.left
    assert n == 22


# --------------------------------------------------------------------------- unsupported VB


@pytest.mark.parametrize(
    ("line", "word"),
    [
        ("GoSub 100", "GoSub"),
        ("With obj", "With"),
        ("On Error GoTo handler", "On Error"),
        ("Resume Next", "Resume"),
        ("Erase arr", "Erase"),
        ("Continue For", "Continue"),
        ("Stop", "Stop"),
        ("End", "'End' statement"),
        ("Set x = y", "Set"),
        ("For i As Integer = 1 To 3", "loop variable"),
        ("Wend", "Wend"),
        ("Rem old style", "REM"),
    ],
)
def test_unsupported_vb_statements(line: str, word: str) -> None:
    extra = "\nNext" if line.startswith("For") else ""
    _, sink = body(line + extra)
    assert [d.code for d in sink] == ["GPL1103"]
    assert word in sink.errors[0].message and "not supported in GPL" in sink.errors[0].message
    assert sink.errors[0].span.line == 3


def test_unsupported_words_remain_usable_as_names() -> None:
    stmts = ok("with = 1\nstop(2)\nerase.x = 3\ncontinue += 1")
    assert [type(s).__name__ for s in stmts] == ["Assign", "CallStmt", "Assign", "Assign"]


@pytest.mark.parametrize(
    ("member", "word"),
    [
        ("Enum Colors", "Enum"),
        ("Structure Point", "Structure"),
        ("Imports System", "Imports"),
        ("Option Strict On", "Option"),
        ("Friend x As Integer", "Friend"),
    ],
)
def test_unsupported_vb_declarations(member: str, word: str) -> None:
    _, sink = parse_text(f"Module M\n    {member}\nEnd Module\n")
    assert [d.code for d in sink][:1] == ["GPL1103"] and word in sink.errors[0].message


# --------------------------------------------------------------------------- recovery


def test_several_errors_in_one_file_are_all_reported_with_positions() -> None:
    text = """Module M
    Sub A()
        x = (1 +
        y = 2
        z = 3 4
        If a Then
            w = )
        End If
        Dim q
    End Sub
    Sub B()
        v = 1 : w = 2
        Call 3
    End Sub
End Module
"""
    assert errors(text) == [
        (3, 17, "GPL1101"),  # expected an expression at end of line
        (5, 15, "GPL1102"),  # trailing token
        (7, 17, "GPL1101"),
        (9, 13, "GPL1107"),  # no type
        (12, 15, "GPL1111"),  # ':' separator
        (13, 14, "GPL1100"),  # Call needs a procedure
    ]


def test_unclosed_block_is_one_diagnostic_at_its_opener() -> None:
    text = "Module M\n    Sub A()\n        If a Then\n            x = 1\n    End Sub\n    Sub B()\n        y = 2\n    End Sub\nEnd Module\n"
    unit, sink = parse_text(text)
    assert [(d.span.line, d.code) for d in sink] == [(3, "GPL1105")]
    assert "End If" in sink.errors[0].message and "End Sub" in sink.errors[0].message
    assert [p.name for p in unit.members[0].members] == ["A", "B"]  # B still parsed


def test_stray_end_is_one_diagnostic() -> None:
    text = "Module M\n    Sub A()\n        x = 1\n        End If\n        Next\n        Loop\n        y = 2\n    End Sub\nEnd Module\n"
    unit, sink = parse_text(text)
    assert [(d.span.line, d.code) for d in sink] == [(4, "GPL1104"), (5, "GPL1104"), (6, "GPL1104")]
    assert len(unit.members[0].members[0].body.statements) == 2


def test_missing_end_sub_before_next_sub() -> None:
    text = "Module M\n    Sub A()\n        x = 1\n    Sub B()\n        y = 2\n    End Sub\nEnd Module\n"
    unit, sink = parse_text(text)
    assert [(d.span.line, d.code) for d in sink] == [(2, "GPL1105")]
    assert [p.name for p in unit.members[0].members] == ["A", "B"]


def test_end_sub_closing_a_function_is_one_error_at_that_line() -> None:
    text = """Module M
    Public Function C() As Integer
        Return 1
    End Sub
    Public Sub D()
        Select Case x
            Case 1
                y = 2
    End Function
    Public Sub E()
    End Sub
End Module
"""
    unit, sink = parse_text(text)
    assert [(d.span.line, d.span.col, d.code, d.message) for d in sink] == [
        (4, 5, "GPL1100", "expected 'End Function', found 'End Sub'"),
        (6, 9, "GPL1105", "'Select' block is not closed: expected 'End Select' before 'End Function'"),
        (9, 5, "GPL1100", "expected 'End Sub', found 'End Function'"),
    ]
    c, d, e = unit.members[0].members  # type: ignore[attr-defined]
    assert (c.name, c.kind, len(c.body.statements)) == ("C", "Function", 1)
    assert (d.name, d.kind, d.span.end_line) == ("D", "Sub", 9) and isinstance(d.body.statements[0], A.Select)
    assert e.name == "E"


def test_missing_end_module_and_eof_inside_blocks() -> None:
    assert errors("Module M\n    Sub A()\n        While x\n") == [(3, 9, "GPL1105"), (2, 5, "GPL1105"), (1, 1, "GPL1105")]


def test_broken_block_header_still_opens_the_block() -> None:
    # The header is broken, but its End still matches: exactly one diagnostic.
    assert errors("Module M\nSub A()\n    If x = Then\n        y = 1\n    End If\n    For i = 1 To\n    Next\nEnd Sub\nEnd Module\n") == [
        (3, 12, "GPL1101"),
        (6, 17, "GPL1101"),
    ]


def test_mismatched_nesting() -> None:
    text = "Module M\nSub A()\n    While a\n        Do\n    End While\nEnd Sub\nEnd Module\n"
    assert errors(text) == [(4, 9, "GPL1105")]


def test_statements_outside_procedures_and_members_outside_modules() -> None:
    text = "x = 1\nSub Orphan()\nEnd Sub\nModule M\n    y = 2\n    Property P As Integer\n        Get\n        End Get\n    End Property\nEnd Module\n"
    assert errors(text) == [(1, 1, "GPL1109"), (2, 1, "GPL1110"), (5, 5, "GPL1109"), (6, 5, "GPL1123")]


def test_select_and_try_structure_errors() -> None:
    text = """Module M
Sub A()
    Select x
        y = 1
        Case 1
        Case Else
        Case 2
    End Select
    Try
        z = 1
    End Try
    Try
    Catch
    End Try
    Try
    Catch e
    Catch f
    End Try
End Sub
End Module
"""
    assert errors(text) == [(4, 9, "GPL1124"), (7, 9, "GPL1100"), (9, 5, "GPL1100"), (13, 5, "GPL1116"), (17, 5, "GPL1115")]


def test_deep_nesting_is_a_diagnostic_not_a_crash() -> None:
    _, sink = body("x = " + "(" * 5000 + "1" + ")" * 5000)
    assert [(d.code, d.span.line) for d in sink] == [("GPL1117", 3)]  # one, no cascade
    _, sink = body("x = " + "-" * 5000 + "1")
    assert [(d.code, d.span.line) for d in sink] == [("GPL1117", 3)]  # one, no cascade
    _, sink = body("x = 2 ^ " + "-" * 5000 + "1")  # the signs of a '^' operand (was a RecursionError)
    assert [(d.code, d.span.line) for d in sink] == [("GPL1117", 3)]  # one, no cascade
    text = "Module M\nSub A()\n" + "If a Then\n" * 400 + "End If\n" * 400 + "End Sub\nEnd Module\n"
    _, sink = parse_text(text)
    assert [d.code for d in sink] == ["GPL1117"]  # one diagnostic, no cascade of unclosed blocks
    text = "Module M\n" + "Class C\n" * 3000 + "End Class\n" * 3000 + "End Module\n"
    unit, sink = parse_text(text)  # was a RecursionError
    assert [(d.code, d.span.line) for d in sink] == [("GPL1117", 103)]
    assert "classes nested too deeply" in sink.errors[0].message
    depth, node = 0, unit.members[0]
    while node.members:  # type: ignore[attr-defined]
        node, depth = node.members[0], depth + 1  # type: ignore[attr-defined]
    assert depth == 101  # every class up to the limit is kept (the last one empty)
    text = "Module M\n" + "Class C\n" * 60 + "Sub S()\n" + "If a Then\n" * 60 + "End If\n" * 60
    _, sink = parse_text(text + "End Sub\n" + "End Class\n" * 60 + "End Module\n")
    assert [d.code for d in sink] == ["GPL1117"]  # classes and blocks count together


def test_nested_select_has_the_block_depth_guard() -> None:
    # Select parses its Case blocks without the guard every other block passes through: 1,000
    # levels were internal error GPL9000 (RecursionError), 500 a message about an "expression"
    opened = {"If": ("If a Then\n", "End If\n"), "Select": ("Select Case a\nCase 1\n", "End Select\n"),
              "While": ("While a\n", "End While\n")}
    for kind, (head, tail) in opened.items():
        for depth in (150, 500, 1000):
            text = "Module M\nSub A()\n" + head * depth + tail * depth + "End Sub\nEnd Module\n"
            _, sink = parse_text(text)
            assert [d.code for d in sink] == ["GPL1117"], (kind, depth, [d.header() for d in sink])
            assert "blocks nested too deeply (more than 100 levels)" in sink.errors[0].message
            # the 100th nested construct is refused (Module and Sub are two levels): an If or While
            # at the first token of its body, a Select at its own header
            lines = head.count("\n")
            hundredth = 3 + 99 * lines
            assert sink.errors[0].span.line == (hundredth if kind == "Select" else hundredth + 1), kind


def test_dump_is_readable() -> None:
    unit, _ = parse_text("Module M\nSub A() ' hi\n    x = 1 + 2\nEnd Sub\nEnd Module\n")
    text = A.dump(unit)
    assert "ModuleDecl name='M' @1:1" in text
    assert "ProcDecl kind='Sub' name='A' @2:1  ' hi" in text
    assert "Binary op='+' @3:9" in text


def test_dump_of_a_long_continued_concatenation_does_not_recurse() -> None:
    # 1,500 '&' operands over ' _' lines: a left-leaning Binary tree 1,500 deep (was RecursionError)
    lines = ['s = "a" _'] + [f'    & "x{i}" _' for i in range(1500)] + ['    & "end"']
    unit, sink = parse_text("Module M\nSub A()\nDim s As String\n" + "\n".join(lines) + "\nEnd Sub\nEnd Module\n")
    assert list(sink) == []
    text = A.dump(unit, comments=False)
    binaries = [line for line in text.splitlines() if line.lstrip().startswith("Binary op='&'")]
    assert len(binaries) == 1501
    assert binaries[-1].lstrip() == "Binary op='&' @4:5"  # the innermost, '"a" & "x0"', starts at "a"
    assert "StringLiteral value='end' @1505:7" in text


def test_visitor_and_transformer() -> None:
    unit, _ = parse_text("Module M\nSub A()\n    x = a + b\n    f(a)\nEnd Sub\nEnd Module\n")

    class Names(A.NodeVisitor):
        def __init__(self) -> None:
            self.seen: list[str] = []

        def visit_Name(self, node: A.Name) -> None:
            self.seen.append(node.name)

    v = Names()
    v.visit(unit)
    assert v.seen == ["x", "a", "b", "f", "a"]

    class Rename(A.NodeTransformer):
        def visit_Name(self, node: A.Name) -> A.Node:
            return A.Name(node.span, node.name.upper())

    Rename().visit(unit)
    v2 = Names()
    v2.visit(unit)
    assert v2.seen == ["X", "A", "B", "F", "A"]


def test_missing_then_is_one_diagnostic_in_both_forms() -> None:
    text = "Module M\nSub A()\n    If x = 1 y = 2\n    If z > 0\n        w = 1\n    End If\n    v = 3\nEnd Sub\nEnd Module\n"
    assert errors(text) == [(3, 14, "GPL1100"), (4, 13, "GPL1100")]


def test_stray_block_keywords_name_their_opener() -> None:
    _, sink = body("Else\nCase 1\nCatch e\nLoop\nNext\nEnd Select")
    messages = [d.message for d in sink]
    assert messages == [
        "'Else' without a matching 'If'",
        "'Case' without a matching 'Select'",
        "'Catch' without a matching 'Try'",
        "'Loop' without a matching 'Do'",
        "'Next' without a matching 'For'",
        "'End Select' without a matching 'Select'",
    ]


def test_head_trap_in_a_declaration_is_a_syntax_error_at_the_literal() -> None:
    out, sink = body('Dim s As String &HEAD\nx = s & HEAD')
    assert [(d.span.line, d.span.col, d.code) for d in sink] == [(3, 25, "GPL1102")]
    assert "&HEAD" in sink.errors[0].message
    assert sx(out[1].value) == "(& s HEAD)"  # type: ignore[attr-defined]


def test_diagnostic_header_is_file_line_col() -> None:
    _, sink = parse_text("Module M\nSub A()\n\tx = = 1\nEnd Sub\nEnd Module\n")
    assert [d.header() for d in sink] == ["t.gpl:3:6: error GPL1101: expected an expression, found '='"]


def test_a_file_of_many_token_chunks_parses_whole_with_exact_positions() -> None:
    # The parser reads the lexer's tokens in chunks of CHUNK (1,024) and slides its window at
    # each boundary: statements, look-aheads ('End' + 'If') and spans that straddle a boundary
    # must come out as in a short file.  Statements of varying length put the boundaries at
    # every place in a statement.
    lines = ["Module M", "    Sub Main()"]
    expected: list[tuple[int, str]] = []  # (line, target name) of every assignment
    for i in range(3000):
        pad = " + 1" * (i % 7)
        if i % 50 == 0:
            lines += [f"        If v{i} = {i} Then", f"            w{i} = a({i}, b.c){pad}", "        End If"]
            expected.append((len(lines) - 1, f"w{i}"))
        else:
            lines.append(f"        v{i} = a({i}, b.c){pad} ' note {i}")
            expected.append((len(lines), f"v{i}"))
    lines += ["        x = = 1", "    End Sub", "End Module"]
    text = "\n".join(lines) + "\n"
    unit, sink = parse_text(text)
    assigns = [n for n in _walk(unit) if isinstance(n, A.Assign)]
    assert [(a.span.line, sx(a.target)) for a in assigns] == expected + [(len(lines) - 2, "x")]
    last = assigns[-2]
    assert (last.span.col, last.span.end_col) == (9, len(lines[last.span.line - 1].split(" '")[0]) + 1)
    assert last.trailing_comment is not None and last.trailing_comment.text == " note 2999"
    # the one error, after every boundary, at its exact place
    assert errors(text) == [(len(lines) - 2, 13, "GPL1101")]

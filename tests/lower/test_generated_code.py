"""The shape and quality of the generated Python (issue part 4, docs/design/lowering.md).

These tests look at the text a user would read: plain Python where static types allow, runtime
calls only where GPL differs, GPL names kept (Python keywords/builtins get a trailing underscore),
comments carried, PEP 8 layout, no exec/eval, and a source map back to GPL lines.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import libcst
import pycodestyle

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.pywriter.wrap import wrap
from gpl2py.transpile import transpile
from gpltest import generated_main_module as gen
from gpltest import main_body

REPO = Path(__file__).resolve().parents[2]


def test_typed_arithmetic_is_plain_python(tmp_path: Path) -> None:
    text = gen(tmp_path, """        Dim a, b, c As Double
        Dim i As Integer
        c = a * b + a / 2.0 - b
        i = i + 1
        c = i
        Console.WriteLine(c)""")
    body = main_body(text)
    # a product of two Doubles may overflow: computed plainly, checked inline before the store
    assert "_v1 = a * b + a / 2.0 - b\n    if _v1 - _v1 != 0.0:  # Infinity or NaN\n" in body
    assert "        chk_double(_v1)\n    c = _v1\n" in body
    # Integer store of arithmetic: range check (§4.2 rule 4), inline; i + 1 can only pass the top
    assert "i = chk_int32(_v2) if (_v2 := i + 1) > 2147483647 else _v2" in body
    assert "c = float(i)" in body


def test_bounded_double_products_are_not_checked(tmp_path: Path) -> None:
    body = main_body(gen(tmp_path, """        Dim x, s As Double
        Dim i As Integer
        x = i * 0.001 + Math.Sin(x) * 3
        s = s + x
        Console.WriteLine(s)"""))
    assert "x = i * 0.001 + sin(x) * 3" in body and "s = s + x" in body and "chk_double" not in body


def test_gpl_semantics_call_the_runtime(tmp_path: Path) -> None:
    text = gen(tmp_path, """        Dim d As Double
        Dim i, j As Integer
        Dim s As String
        Dim b As Boolean
        i = d
        d = i / j
        d = i Mod j
        d = 2.34 + s
        s = s & d
        i = b
        b = i And j
        b = b And b
        Console.WriteLine(s & d & i & b)""")
    body = main_body(text)
    for line in ("i = to_int32(d)", "d = div(i, j)", "d = float(mod(i, j))", "d = add(2.34, s)",
                 "s = s + to_string(d)", "i = bool_num(b)", "b = i & j != 0", "b = b & b"):
        assert line in body, (line, body)


def test_integer_for_loop_uses_range_and_keeps_the_final_value(tmp_path: Path) -> None:
    body = main_body(gen(tmp_path, """        Dim i, n, s As Integer
        For i = 1 To n
            s = s + i
        Next
        Console.WriteLine(i)"""))
    # one Python loop; paced_range gives other threads their turn every 1024 iterations
    # (lowering.md, "Loops and other threads")
    assert "for i in paced_range(1, n + 1):" in body
    assert "_k1" not in body and "min(" not in body
    assert "i = max(1, n + 1)" in body  # read after the loop: the first value past the end


def test_the_final_value_of_a_literal_for_is_a_literal(tmp_path: Path) -> None:
    body = main_body(gen(tmp_path, """        Dim i, s As Integer
        For i = 1 To 80
            s = s + i
        Next
        Console.WriteLine(i)
        For i = 5 To 1 Step -1
            s = s + i
        Next
        Console.WriteLine(i)
        For i = 7 To 3
            s = s + i
        Next
        Console.WriteLine(i)"""))
    for line in ("i = 81  #", "i = 0  #", "i = 7  #"):  # an empty loop leaves its start value
        assert line in body, (line, body)
    assert "max(" not in body and "min(" not in body


def test_a_for_counter_nobody_reads_afterwards_gets_no_final_store(tmp_path: Path) -> None:
    body = main_body(gen(tmp_path, """        Dim i, n, s As Integer
        Dim a(9) As Integer
        For i = 0 To n - 1
            s = s + a(i)
        Next
        For i = 9 To 0 Step -1
            a(i) = s
        Next"""))
    assert "for i in paced_range(0, n):" in body  # To n - 1: range's own stop
    assert "for i in range(9, -1, -1):" in body  # few literal steps: a plain range
    assert "max(" not in body and "min(" not in body  # each loop sets i before its body reads it


def test_for_loop_writing_its_variable_stays_a_while_loop(tmp_path: Path) -> None:
    body = main_body(gen(tmp_path, """        Dim i As Integer
        For i = 1 To 10 Step 2
            i = i + 1
        Next"""))
    assert "range(" not in body and "while i <= 10:" in body


def test_names_keep_spelling_and_avoid_python_keywords(tmp_path: Path) -> None:
    text = gen(tmp_path, """        Dim str, len As Integer
        Dim _hidden As Integer
        Dim MixedCase As Integer
        str = 1
        len = str + 1
        _hidden = len
        mixedcase = _HIDDEN
        Console.WriteLine(MIXEDCASE)""")
    body = main_body(text)
    assert "str_ = 1" in body and "len_ = chk_int32(_v1) if (_v1 := str_ + 1) > 2147483647 else _v1" in body
    assert "_u_hidden = len_" in body and "MixedCase = _u_hidden" in body
    assert "Console.WriteLine(MixedCase)" in body


def test_comments_are_carried(tmp_path: Path) -> None:
    text = gen(tmp_path, """        Dim i As Integer
        ' explain the next line
        i = 3   ' trailing note
        If i > 2 Then   ' header note
            i = 1
        End If""")
    assert "    # explain the next line\n    i = 3  # trailing note\n" in text
    assert "if i > 2:  # header note" in text


def test_comments_of_class_members_are_carried(tmp_path: Path) -> None:
    """Comments on fields, Consts, delegates and properties of a class, and on the lines that open
    and close a Module or a Class, are carried; a method's comments stand above its decorator."""
    text = gen(tmp_path, "", decls="""    Class Box   ' header note
        ' about count
        Public count As Integer   ' count note
        Public Shared total As Integer = 3   ' total note
        Public Const LIMIT As Integer = 9   ' limit note
        ' about the hook
        Delegate Sub Hook(ByVal x As Integer)   ' hook note
        ' about size
        Public Property Size As Integer   ' size note
            Get
                Return count
            End Get
            ' before the end
        End Property   ' end property note
        ' about reset
        Public Shared Sub Reset()
            total = 0
        End Sub
    End Class   ' end class note""")
    for line in ("    total = 0  # total note\n", "    LIMIT = 9  # limit note\n",
                 '    # about the hook\n    Hook = delegate_type("Hook", 1)  # hook note\n',
                 "    def __init__(self) -> None:\n        # about count\n        self.count = 0  # count note\n",
                 "    # about size\n    # size note\n    @property\n    def Size(self) -> int:\n",
                 "    # before the end\n    # end property note\n",
                 "    # about reset\n    @staticmethod\n    def Reset() -> None:\n",
                 "    # end class note\n"):
        assert line in text, (line, text)
    module = tmp_path / "Main.gpl"
    module.write_text("Module Main   ' module note\n    Public Sub Main()\n    End Sub\nEnd Module   ' end note\n")
    out = transpile(str(module), DiagnosticSink())
    assert out is not None
    py = out.files["main/main_mod.py"]
    assert py.startswith('"""Module Main, transpiled by gpl2py from Main.gpl."""\n# module note\n'), py
    assert "\n# end note\n" in py


def test_goto_free_procedures_stay_structured(tmp_path: Path) -> None:
    body = main_body(gen(tmp_path, """        Dim i As Integer
        While i < 3
            i += 1
        End While"""))
    assert "for _ in paced():\n        if i >= 3:\n            break\n" in body and "_g" not in body


def test_a_loop_whose_literal_test_never_ends_it_has_no_test(tmp_path: Path) -> None:
    body = main_body(gen(tmp_path, """        Dim i As Integer
        While True
            i += 1
            If i > 3 Then Exit While
        End While
        Do
            i += 1
        Loop Until False"""))
    assert "True" not in body and "False" not in body, body
    assert body.count("for _ in paced():\n") == 2


def test_no_exec_or_eval_and_valid_python_for_all_frontend_sources() -> None:
    for src in sorted((REPO / "tests/frontend/sources").glob("*.gpl")):
        out = transpile(str(src), DiagnosticSink(), keep_going=True)
        assert out is not None
        for name, text in out.files.items():
            if name.endswith(".py"):
                libcst.parse_module(text)
                compile(text, name, "exec")
                assert not re.search(r"\b(exec|eval)\(", text), name


def test_pep8_layout(tmp_path: Path) -> None:
    out = transpile(str(REPO / "samples/tcp_command_server"), DiagnosticSink(), keep_going=True)
    assert out is not None
    paths = []
    for name, text in out.files.items():
        if name.endswith(".py"):
            p = tmp_path / name.replace("/", "_")
            p.write_text(text)
            paths.append(str(p))
    style = pycodestyle.StyleGuide(max_line_length=99, quiet=True)
    assert style.check_files(paths).total_errors == 0


def test_long_lines_are_broken_before_operators() -> None:
    text = "x = " + " + ".join(f"CStr(value_{i})" for i in range(20))
    lines = wrap(1, text)
    assert len(lines) > 2 and all(4 * ind + len(t) <= 99 for ind, t in lines)
    assert lines[0] == (1, "x = (") and lines[-1] == (1, ")")
    assert all(t.startswith("+ ") for _, t in lines[2:-1])
    rebuilt = " ".join(t for _, t in lines).replace("( ", "(").replace(" )", ")")
    assert rebuilt.replace("(", "").replace(")", "") == text.replace("(", "").replace(")", "")
    assert wrap(1, "global " + ", ".join(f"name_{i}" for i in range(30)))[0][1].startswith("global ")


def test_source_map_points_at_gpl_lines(tmp_path: Path) -> None:
    f = tmp_path / "Main.gpl"
    f.write_text("Module Main\n    Public Sub Main()\n        Dim i As Integer\n        i = 1\n"
                 "        i = 2\n        Console.WriteLine(i)\n    End Sub\nEnd Module\n")
    out = transpile(str(f), DiagnosticSink())
    assert out is not None
    smap = json.loads(out.files["main/_sourcemap.json"])["modules"]["main_mod.py"]
    assert smap["source"] == "Main.gpl"
    py = out.files["main/main_mod.py"].splitlines()
    runs = smap["runs"]

    def gpl_line(n: int) -> int:
        return max((r for r in runs if r[0] <= n), key=lambda r: r[0])[1]

    assert gpl_line(py.index("    i = 1") + 1) == 4
    assert gpl_line(py.index("    i = 2") + 1) == 5


def test_procedures_are_registered_for_name_lookup(tmp_path: Path) -> None:
    text = gen(tmp_path, "", decls="    Private Sub Helper()\n    End Sub\n", name="Station")
    # into this package's own registry (gplrt.lang.procedures: one registry per project)
    assert 'register_procedure("Station", "Helper", gpl_entry(Helper), public=False, package=__package__)' in text
    assert 'register_procedure("Station", "Main", gpl_entry(Main), public=True, package=__package__)' in text


def test_long_gpl_comments_are_reflowed_and_moved_above_long_statements(tmp_path: Path) -> None:
    words = " ".join(f"word{i}" for i in range(40))
    text = gen(tmp_path, f"""        Dim total As Integer
        ' {words}
        total = total + 1   ' {words}""")
    body = main_body(text)
    assert all(len(line) <= 99 for line in text.splitlines()), text
    comment_lines = [ln.strip() for ln in body.splitlines() if ln.strip().startswith("#")]
    assert len(comment_lines) == 6  # each 40-word comment on three lines, none lost
    assert " ".join(c[2:] for c in comment_lines[:3]) == words
    assert " ".join(c[2:] for c in comment_lines[3:]) == words
    lines = body.splitlines()
    stmt = next(i for i, ln in enumerate(lines) if "total = chk_int32(_v1) if (_v1 := total + 1)" in ln)
    assert lines[stmt - 1].strip().startswith("# word")  # the trailing comment sits just above
    (tmp_path / "s").mkdir()
    short = gen(tmp_path / "s", """        Dim total As Integer
        total = total + 1   ' one more""")
    assert "else _v1  # one more" in short  # a short one stays trailing


def test_an_indented_gpl_comment_after_code_starts_with_one_space(tmp_path: Path) -> None:
    """``x = 1   '   note``: after code the comment reads ``# note`` (pycodestyle E262 wants exactly
    '# '); the same comment on its own line keeps its indentation."""
    text = gen(tmp_path, """        Dim total As Integer
        '    indented note
        total = total + 1   '    indented note
        If total > 0 Then   '\tafter a tab
            total = 0
        End If""")
    body = main_body(text)
    assert "    #    indented note\n" in body
    assert "total = chk_int32(_v1) if (_v1 := total + 1) > 2147483647 else _v1  # indented note\n" in body
    assert "if total > 0:  # after a tab\n" in body
    path = tmp_path / "m.py"
    path.write_text(text)
    assert pycodestyle.StyleGuide(max_line_length=99, quiet=True).check_files([str(path)]).total_errors == 0


def test_reflowed_comments_with_runs_of_spaces_have_no_trailing_whitespace(tmp_path: Path) -> None:
    """A long GPL comment with aligned columns (runs of spaces) breaks inside a run; no piece may
    end in spaces (pycodestyle W291), and every word is kept in order."""
    words = [f"col{i}" for i in range(12)]
    aligned = (" " * 9).join(words)
    text = gen(tmp_path, f"""        Dim total As Integer
        ' {aligned}
        total = total + 1   ' {aligned}""")
    comments = [ln for ln in main_body(text).splitlines() if ln.strip().startswith("#")]
    assert len(comments) >= 4 and all(ln == ln.rstrip() for ln in comments), comments
    assert " ".join(" ".join(c.split()[1:]) for c in comments).split() == words * 2
    path = tmp_path / "m.py"
    path.write_text(text)
    assert pycodestyle.StyleGuide(max_line_length=99, quiet=True).check_files([str(path)]).total_errors == 0


def test_comparison_with_a_boolean_literal_is_the_condition_itself(tmp_path: Path) -> None:
    body = main_body(gen(tmp_path, """        Dim ok As Boolean
        If ok = True Then Console.WriteLine(1)
        If ok = False Then Console.WriteLine(2)
        If True <> ok Then Console.WriteLine(3)
        If ok <> False Then Console.WriteLine(4)"""))
    assert "if ok:" in body and "if not ok:" in body and "== True" not in body and "!= False" not in body
    assert body.count("if ok:") == 2 and body.count("if not ok:") == 2


def test_a_long_condition_breaks_inside_a_call_that_is_compared(tmp_path: Path) -> None:
    text = gen(tmp_path, """        Dim text As String
        Dim ii As Integer
        If ii <> 0 And text.Substring(ii - 1, 1).ToLower() <> "e" And text.Substring(ii, 1).ToUpper() <> "QQQ" Then
            Console.WriteLine(1)
        End If""")
    assert all(len(line) <= 99 for line in text.splitlines()), text
    compile(text, "m.py", "exec")


def test_byref_parameters_are_annotated_as_cells(tmp_path: Path) -> None:
    text = gen(tmp_path, "        Console.WriteLine(1)", decls="""    Sub Bump(ByRef n As Integer, ByVal k As Double, ByRef s As String)
        n = n + 1
    End Sub""")
    assert "def Bump(n: Ref[int], k: float, s: Ref[str]) -> None:" in text
    assert "from gplrt.lang.gpltypes import Ref\n" in text

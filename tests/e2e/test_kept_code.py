"""Generated code a person keeps (issue 13, item 5), checked by what the programs do.

Each test runs a transpiled program and checks its output (the behaviour a user sees), then the
shape of the Python that gave it: Exit Try without loop-and-flag scaffolding, a ByRef Integer
store on one line that still raises -710, modules without empty ``_reset``/``_init``, and
``paced_range`` (the runtime's range with a checkpoint every 1024 iterations).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from gpl2py.gpl.lower.statements import PACE as LOWERING_PACE
from gplrt.threads import scheduler
from gplrt.threads.scheduler import PACE, paced_range
from gpltest import run_gpl

EXIT_TRY = """Module Main
    Public Sub Main()
        Dim i, j, n As Integer
        Dim e As Exception
        Try
            For i = 1 To 5
                j = 0
                While j < 10
                    j += 1
                    n += 1
                    If i = 2 And j = 3 Then Exit Try
                End While
            Next
            Console.WriteLine("not reached")
        Catch e
            Console.WriteLine("no error expected")
        Finally
            Console.WriteLine("finally " & CStr(n))
        End Try
        Console.WriteLine("after " & CStr(i) & " " & CStr(j))
        Try
            Throw New Exception
        Catch e
            Do
                n += 1
                If n > 20 Then Exit Try
            Loop
            Console.WriteLine("not reached either")
        Finally
            Console.WriteLine("finally again " & CStr(n))
        End Try
        Console.WriteLine("done")
    End Sub
End Module
"""


def test_exit_try_from_nested_loops_and_from_a_catch(tmp_path: Path) -> None:
    r = run_gpl(tmp_path, EXIT_TRY)
    assert r.status == 0, r.log
    assert r.output == "finally 13\nafter 2 3\nfinally again 21\ndone\n"
    code = r.files[f"{r.package.__name__}/main_mod.py"]
    assert code.count("raise ExitTry") == 2 and code.count("except ExitTry:") == 2
    # no loop of its own: the two are the While's and the Do's
    assert "_jump" not in code and code.count("for _ in paced():") == 2


BYREF = """Module Main
    Sub Bump(ByRef count As Integer)
        count += 1
    End Sub
    Public Sub Main()
        Dim n As Integer
        Dim e As Exception
        n = 2147483646
        Bump(n)
        Console.WriteLine(CStr(n))
        Try
            Bump(n)
        Catch e
            Console.WriteLine("error " & CStr(e.ErrorCode) & ", n still " & CStr(n))
        End Try
    End Sub
End Module
"""


def test_a_byref_integer_increment_is_one_line_and_still_overflows(tmp_path: Path) -> None:
    r = run_gpl(tmp_path, BYREF)
    assert r.output == "2147483647\nerror -710, n still 2147483647\n", r.log
    code = r.files[f"{r.package.__name__}/main_mod.py"]
    # one line, as every Integer store: the range tested inline, on the side an increment can
    # leave (docs/design/lowering.md, "Storing")
    stores = [line.strip() for line in code.splitlines() if line.strip().startswith("count.value =")]
    assert stores == ["count.value = chk_int32(_v1) if (_v1 := count.value + 1) > 2147483647 else _v1"]


MODULES = {
    "Main.gpl": """Module Main
    Public Sub Main()
        Console.WriteLine(Names.Greeting() & " " & CStr(Counter.total))
    End Sub
End Module
""",
    "Names.gpl": """Module Names
    Public Function Greeting() As String
        Return "hello"
    End Function
End Module
""",
    "Counter.gpl": """Module Counter
    Public total As Integer = 3
    Public spare As Integer
End Module
""",
}


def test_modules_without_variables_have_no_empty_reset_or_init(tmp_path: Path) -> None:
    r = run_gpl(tmp_path, MODULES)
    assert r.output == "hello 3\n", r.log
    pkg = r.package.__name__
    for module in ("main_mod", "names"):
        assert "def _reset" not in r.files[f"{pkg}/{module}.py"]
        assert "def _init" not in r.files[f"{pkg}/{module}.py"]
    counter = r.files[f"{pkg}/counter.py"]
    assert "def _reset" in counter and "def _init" in counter
    init_body = counter.split("def _init")[1].split("\n\n\n")[0]
    assert "total = 3" in init_body and "spare" not in init_body  # no initializer: nothing to run
    init = r.files[f"{pkg}/__init__.py"]
    assert "counter._reset()" in init and "counter._init()" in init
    assert "names._reset()" not in init and "names._init()" not in init


@pytest.mark.parametrize("args", [(0, 0), (0, 1), (1, 1025), (0, 1024), (0, 1025), (5, 5000), (3000, -7, -1),
                                  (10, 0, -1), (-2048, 2049)])
def test_paced_range_gives_the_values_of_range(args: tuple[int, ...]) -> None:
    assert list(paced_range(*args)) == list(range(*args))


def test_paced_range_checkpoints_between_slices_only(monkeypatch: pytest.MonkeyPatch) -> None:
    calls: list[int] = []
    seen: list[int] = []
    monkeypatch.setattr(scheduler, "checkpoint", lambda: calls.append(len(seen)))
    for i in paced_range(0, 3 * PACE + 5):
        seen.append(i)
    assert calls == [PACE, 2 * PACE, 3 * PACE]  # before each slice but the first
    calls.clear()
    seen.clear()
    for i in paced_range(0, PACE):
        seen.append(i)
    assert calls == [] and isinstance(paced_range(0, PACE), range)  # a short loop is a plain range


def test_the_lowering_and_the_runtime_agree_on_the_pace() -> None:
    assert LOWERING_PACE == PACE


RETRY = """Module Main
    Public Sub Main()
        Dim tries As Integer
        Dim e As Exception
        Try
retry:
            tries += 1
            If tries < 3 Then
                e = New Exception
                e.ErrorCode = -153
                Throw e
            End If
            Console.WriteLine("done after " & CStr(tries))
        Catch e
            Console.WriteLine("retry after " & CStr(e.ErrorCode))
            GoTo retry
        End Try
    End Sub
End Module
"""


def test_a_retry_from_the_top_of_a_try_is_a_plain_loop(tmp_path: Path) -> None:
    r = run_gpl(tmp_path, RETRY)
    assert r.output == "retry after -153\nretry after -153\ndone after 3\n", r.log
    code = r.files[f"{r.package.__name__}/main_mod.py"]
    assert "_g1" not in code and code.count("while True:") == 1  # no dispatch loop in the Try body
    assert "            checkpoint()\n            continue\n" in code  # the retry is a scheduling point


NEXT_ITEM = """Module Main
    Public Sub Main()
        Dim i, total As Integer
        Dim words(5) As String
        words(1) = "a"
        words(3) = "'comment"
        words(4) = "b"
        i = -1
        Do
            i += 1
            If i > 5 Then Exit Do
            If words(i).Length = 0 Then GoTo next_word
            If words(i).Substring(0, 1) = "'" Then GoTo next_word
            total += 1
            Console.WriteLine(words(i))
next_word:
        Loop
        Console.WriteLine(CStr(total))
    End Sub
End Module
"""


def test_a_goto_to_the_end_of_a_loop_body_is_continue(tmp_path: Path) -> None:
    r = run_gpl(tmp_path, NEXT_ITEM)
    assert r.output == "a\nb\n2\n", r.log
    code = r.files[f"{r.package.__name__}/main_mod.py"]
    # no dispatch loop in the body: the Do loop is the only one, and its next turn (the for) is the
    # scheduling point of the two continues
    assert "_g1" not in code and code.count("for _ in paced():") == 1 and "while" not in code
    assert code.count("        continue\n") == 2 and "checkpoint()" not in code
    assert "# next_word:" in code


EXIT_LABEL = """Module Main
    Function Check(ByVal n As Integer) As Integer
        Dim ret As Integer
        Dim i As Integer
        ret = -1
        If n < 0 Then GoTo _exit
        For i = 1 To n
            If i = 7 Then GoTo _exit
        Next
        ret = n
_exit:
        Return ret
    End Function
    Sub Report(ByVal n As Integer)
        If n = 0 Then GoTo done
        Console.WriteLine("n " & CStr(n))
done:
    End Sub
    Public Sub Main()
        Console.WriteLine(CStr(Check(-3)) & " " & CStr(Check(9)) & " " & CStr(Check(4)))
        Report(0)
        Report(2)
    End Sub
End Module
"""


def test_a_goto_to_the_exit_label_is_the_exit_itself(tmp_path: Path) -> None:
    r = run_gpl(tmp_path, EXIT_LABEL)
    assert r.output == "-1 -1 4\nn 2\n", r.log
    code = r.files[f"{r.package.__name__}/main_mod.py"]
    assert "_g1" not in code and "while True" not in code and "_jump" not in code
    assert code.count("return ret\n") == 3  # the two jumps and the label's own Return
    assert "# _exit:" in code and "# done:" in code


def test_no_unreachable_return_after_a_try_whose_body_and_catch_return(tmp_path: Path) -> None:
    src = """Module Main
    Function Safe(ByVal a As Integer, ByVal b As Integer) As Integer
        Dim e As Exception
        Try
            Return a \\ b
        Catch e
            Return e.ErrorCode
        End Try
    End Function
    Public Sub Main()
        Console.WriteLine(CStr(Safe(7, 2)) & " " & CStr(Safe(1, 0)))
    End Sub
End Module
"""
    r = run_gpl(tmp_path, src)
    assert r.output == "3 -709\n", r.log
    code = r.files[f"{r.package.__name__}/main_mod.py"]
    body = code.split("def Safe")[1].split("\n\n\n")[0]
    assert body.rstrip().endswith("return e.ErrorCode")  # nothing unreachable after the try

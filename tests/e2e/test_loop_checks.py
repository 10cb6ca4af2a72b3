"""Range checks that a loop's own test makes unnecessary are left out, and only those
(docs/design/lowering.md, "Storing"): ``i = i + 1`` right after ``While i < n`` found ``i`` below
an Integer, and ``Mod`` of a counter that no store can make negative.  Each program here prints
what the controller prints; the ones that must still overflow or keep the dividend's sign do."""

from __future__ import annotations

from pathlib import Path

from gpltest import run_gpl

GUARDED = """Module Main
    Public Sub Main()
        Dim i, n, steps As Integer
        i = 2147483640
        n = 2147483647
        While i < n
            i += 1
            steps = steps + 1
        End While
        Console.WriteLine(CStr(i) & " " & CStr(steps))
        i = 2147483640
        Do While i < 2147483647
            i = i + 1
        Loop
        Console.WriteLine(CStr(i))
    End Sub
End Module
"""


def test_an_increment_the_loop_test_bounds_reaches_the_top_of_the_range(tmp_path: Path) -> None:
    r = run_gpl(tmp_path, GUARDED)
    assert r.output == "2147483647 7\n2147483647\n", r.log
    code = r.files[f"{r.package.__name__}/main_mod.py"]
    assert code.count("        i = i + 1\n") == 2  # the two guarded increments, unchecked
    assert "steps = chk_int32(" in code  # the loop test says nothing about steps


UNGUARDED = """Module Main
    Public Sub Main()
        Dim i, n As Integer
        Dim e As Exception
        n = 2147483647
        i = 2147483646
        Try
            While i < n
                i = i + 2
            End While
        Catch e
            Console.WriteLine("step 2: " & CStr(e.ErrorCode) & " at " & CStr(i))
        End Try
        i = 2147483646
        Try
            While i < n
                Console.WriteLine("before")
                i += 1
                i += 1
            End While
        Catch e
            Console.WriteLine("not first: " & CStr(e.ErrorCode) & " at " & CStr(i))
        End Try
        i = 2147483646
        Try
            While i <= n
                i += 1
            End While
        Catch e
            Console.WriteLine("<=: " & CStr(e.ErrorCode) & " at " & CStr(i))
        End Try
    End Sub
End Module
"""


def test_increments_the_test_does_not_bound_still_overflow(tmp_path: Path) -> None:
    r = run_gpl(tmp_path, UNGUARDED)
    assert r.output == ("step 2: -710 at 2147483646\n"
                        "before\nnot first: -710 at 2147483647\n"
                        "<=: -710 at 2147483647\n"), r.log


MOD = """Module Main
    Public Sub Main()
        Dim i, k, count As Integer
        While i < 10
            i += 1
            If i Mod 3 = 0 Then count += 1
        End While
        k = 5
        k = k - 12
        Console.WriteLine(CStr(count) & " " & CStr(i Mod 4) & " " & CStr(k Mod 3) & " " & CStr(k \\ 2))
    End Sub
End Module
"""


def test_mod_of_a_counter_is_plain_and_of_anything_else_keeps_the_sign(tmp_path: Path) -> None:
    r = run_gpl(tmp_path, MOD)
    assert r.output == "3 2 -1 -3\n", r.log
    code = r.files[f"{r.package.__name__}/main_mod.py"]
    assert "if i % 3 == 0:" in code and "i % 4" in code  # i only counts up from 0
    assert "k % 3 if k >= 0 else -(-k % 3)" in code  # k was made negative

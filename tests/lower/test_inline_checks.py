"""Integer stores test their range inline, and a few conversions and operators are plain Python.

The checks behind benchmarks/runtime_speed.py's kernels: an Integer store is
``x = chk_int32(_v) if (_v := ...) > 2147483647 else _v`` rather than a call on every store, tested
on one end only where the other cannot be passed, and on both ends through a cheaper first test
(±(2**30 - 1)) with the exact one behind it; ``Mod`` by a positive literal, ``CStr`` of an
Integer and ``Len`` of a String make no call.  What a program sees must not change: each case
below runs on the simulated controller and checks its output, at and beyond the range's ends.
"""

from __future__ import annotations

from pathlib import Path

from gpltest import generated_main_module as gen
from gpltest import main_body, module_src, run_gpl


def test_overflow_at_each_end_is_710_and_the_variable_keeps_its_value(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, module_src("""    Public Sub Main()
        Dim i, k, n As Integer
        Dim ex As Exception
        i = 2147483646
        For n = 0 To 3
            Try
                i = i + n
                Console.WriteLine("up " & CStr(i))
            Catch ex
                Console.WriteLine("up " & CStr(ex.ErrorCode) & " " & CStr(i))
            End Try
        Next
        k = -2147483647
        For n = 0 To 2
            Try
                k = k - n
                Console.WriteLine("down " & CStr(k))
            Catch ex
                Console.WriteLine("down " & CStr(ex.ErrorCode) & " " & CStr(k))
            End Try
        Next
        Try
            k -= 1
        Catch ex
            Console.WriteLine("compound " & CStr(ex.ErrorCode) & " " & CStr(k))
        End Try
    End Sub"""))
    assert result.output == (
        "up 2147483646\nup 2147483647\nup -710 2147483647\nup -710 2147483647\n"
        "down -2147483647\ndown -2147483648\ndown -710 -2147483648\n"
        "compound -710 -2147483648\n"), result.log


def test_an_operation_inside_the_sum_is_tested_at_both_ends(tmp_path: Path) -> None:
    """``v * 2 + 1`` adds a non-negative literal, but ``v * 2`` may be far below the range: the
    store must still test the lower end (a one-ended test would store -4294967295)."""
    result = run_gpl(tmp_path, module_src("""    Function Scale(ByVal v As Integer) As Integer
        Return v * 2 + 1
    End Function

    Public Sub Main()
        Dim r, v As Integer
        Dim ex As Exception
        v = -2147483647
        Try
            r = v * 2 + 1
            Console.WriteLine("store " & CStr(r))
        Catch ex
            Console.WriteLine("store " & CStr(ex.ErrorCode))
        End Try
        Try
            r = Scale(v)
            Console.WriteLine("return " & CStr(r))
        Catch ex
            Console.WriteLine("return " & CStr(ex.ErrorCode))
        End Try
        Console.WriteLine(Scale(-1073741824) & " " & Scale(1073741823))
    End Sub"""))
    assert result.output == "store -710\nreturn -710\n-2147483647 2147483647\n", result.log


def test_values_between_2_to_30_and_the_range_end_are_stored(tmp_path: Path) -> None:
    """The first test of a two-ended check is ±(2**30 - 1): beyond it, the exact test decides."""
    result = run_gpl(tmp_path, module_src("""    Public Class Acc
        Public total As Integer
        Public Sub Add(ByVal v As Integer)
            total = total + v
        End Sub
    End Class

    Public Sub Main()
        Dim a As New Acc()
        Dim ex As Exception
        a.Add(1073741823)
        a.Add(1)
        a.Add(1073741823)
        Console.WriteLine(a.total)
        Try
            a.Add(1)
        Catch ex
            Console.WriteLine(CStr(ex.ErrorCode) & " " & CStr(a.total))
        End Try
        a.total = 0
        a.Add(-2147483647)
        a.Add(-1)
        Console.WriteLine(a.total)
        Try
            a.Add(-1)
        Catch ex
            Console.WriteLine(CStr(ex.ErrorCode) & " " & CStr(a.total))
        End Try
    End Sub"""))
    assert result.output == "2147483647\n-710 2147483647\n-2147483648\n-710 -2147483648\n", result.log


def test_mod_cstr_and_len_keep_gpl_results(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, module_src("""    Public Sub Main()
        Dim i, n As Integer
        Dim s As String
        s = ""
        For i = -7 To 7 Step 7
            s = s & CStr(i Mod 3) & "," & CStr(i) & ";"
        Next
        For n = 0 To 4
            s = s & CStr(n Mod 3)
        Next
        Console.WriteLine(s)
        Console.WriteLine(Len(s) & " " & Len(""))
    End Sub"""))
    assert result.output == "-1,-7;0,0;1,7;01201\n19 0\n", result.log


def test_the_checks_and_operators_are_inline(tmp_path: Path) -> None:
    body = main_body(gen(tmp_path, """        Dim i, n, total As Integer
        Dim s As String
        For n = 1 To 10
            total = total + n
            i = i - 1
            total = total * 3
            s = s & CStr(i Mod 4)
        Next
        Console.WriteLine(Len(s))"""))
    assert "total = chk_int32(_v1) if (_v1 := total + n) > 2147483647 else _v1" in body
    assert "i = chk_int32(_v2) if (_v2 := i - 1) < -2147483648 else _v2" in body
    assert "if ((_v3 := total * 3) > 1073741823 or _v3 < -1073741823) else _v3" in body
    assert "str(i % 4 if i >= 0 else -(-i % 4))" in body
    assert "Console.WriteLine(len(s))" in body

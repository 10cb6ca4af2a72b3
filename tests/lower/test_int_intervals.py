"""Integer stores are range-checked only where the operands' types allow an overflow.

The lowering bounds an integer expression from its operands' static types (interval analysis):
where the result provably fits the target, the store is plain Python; everywhere else the
controller's -710 *Arithmetic overflow* must still be raised.
"""

from __future__ import annotations

from pathlib import Path

from gpltest import module_src, run_gpl
from gpltest import generated_main_module as gen
from gpltest import main_body


def test_bounded_expressions_need_no_check(tmp_path: Path) -> None:
    body = main_body(gen(tmp_path, """        Dim i, acc, m As Integer
        Dim b As Byte
        acc = ((acc * 75 + i) And &H7FFF) + (i \\ 3) - (i >> 2)
        m = (i And &HFF) + (acc And &HFF) + b
        Console.WriteLine(acc + m)"""))
    assert "acc = ((acc * 75 + i) & 0x7FFF)" in body
    assert "chk_int32((" not in body.split("m = ")[0]
    assert "m = (i & 0xFF) + (acc & 0xFF) + b" in body


def test_unbounded_expressions_keep_their_check(tmp_path: Path) -> None:
    body = main_body(gen(tmp_path, """        Dim i, acc As Integer
        Dim s As Short
        acc = acc * 75 + i
        s = (i And &H7FFF) + 1
        Console.WriteLine(acc + s)"""))
    assert "acc = chk_int32(_v1) if ((_v1 := acc * 75 + i) > 1073741823 or _v1 < -1073741823) else _v1" in body
    assert "s = chk_int16((i & 0x7FFF) + 1)" in body


def test_the_checks_that_remain_still_raise_710(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, module_src("""    Public Sub Main()
        Dim i, acc As Integer
        Dim s As Short
        Dim ex As Exception
        i = 32767
        Try
            s = (i And &H7FFF) + 1
        Catch ex
            Console.WriteLine("short " & CStr(ex.ErrorCode))
        End Try
        acc = 2000000000
        Try
            acc = acc * 75 + i
        Catch ex
            Console.WriteLine("integer " & CStr(ex.ErrorCode))
        End Try
        acc = ((acc * 75 + i) And &H7FFF) + (i \\ 3) - (i >> 2)
        Console.WriteLine(acc)
    End Sub"""))
    expected_acc = ((2000000000 * 75 + 32767) & 0x7FFF) + 32767 // 3 - (32767 >> 2)
    assert result.output == f"short -710\ninteger -710\n{expected_acc}\n"

"""``Throw ex`` with ``ex`` still Nothing is -757 *Object not instantiated*, a GPL error its
caller's Catch receives (it was -201 *System internal consistency error*; PARobot.gpl:3152 can
reach it)."""

from __future__ import annotations

from pathlib import Path

from gpltest import module_src, run_gpl

PROGRAM = """    Sub Fail()
        Dim ex As Exception
        Throw ex
    End Sub

    Public Sub Main()
        Try
            Fail()
        Catch e As Exception
            Console.WriteLine("caught " & CStr(e.ErrorCode))
        End Try
    End Sub"""


def test_throwing_nothing_is_object_not_instantiated(tmp_path: Path) -> None:
    res = run_gpl(tmp_path, module_src(PROGRAM))
    assert (res.output, res.status) == ("caught -757\n", 0), res.log

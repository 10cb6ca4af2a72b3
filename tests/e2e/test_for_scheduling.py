"""A long counted For loop (lowered to ``for ... in paced_range``) reaches a scheduling point every 1024
iterations, so in virtual time it cannot starve the other GPL threads (docs/design/lowering.md)."""

from __future__ import annotations

from pathlib import Path

from gpltest import run_gpl

SRC = """Module Main
    Public seen As Integer
    Public Sub Worker()
        Console.WriteLine("worker ran")
        seen = 1
    End Sub
    Public Sub Main()
        Dim t As New Thread("Worker")
        Dim ii, x As Integer
        t.Start()
        For ii = 1 To {n}
            x += 1
        Next
        Console.WriteLine("loop done " & CStr(x) & " " & CStr(ii))
    End Sub
End Module
"""


def _run(tmp_path: Path, n: int) -> tuple[str, str]:
    # a short slice (10 scheduling points) keeps the test fast; the default is 1000
    r = run_gpl(tmp_path, SRC.format(n=n), slice_checkpoints=10)
    assert r.status == 0, r.log
    return r.output, r.files[f"{r.package.__name__}/main_mod.py"]


def test_long_for_loop_lets_other_threads_run(tmp_path: Path) -> None:
    output, code = _run(tmp_path, 200000)
    assert "for ii in paced_range(1, 200001):" in code  # one range loop, paced by the runtime
    assert output == "worker ran\nloop done 200000 200001\n"


def test_short_literal_for_loop_has_no_scheduling_point(tmp_path: Path) -> None:
    output, code = _run(tmp_path, 1000)
    assert "for ii in range(1, 1001):" in code
    assert output.splitlines()[0] == "loop done 1000 1001"  # the worker runs when Main ends

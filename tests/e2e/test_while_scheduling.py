"""A transpiled ``While``/``Do`` loop is ``for _ in paced(): if <exit>: break``: every turn is a
checkpoint of the thread's slice, taken by the ``for`` from the thread's ``ThreadCtx.turns``
(docs/design/lowering.md, "Loops and other threads").  These programs would hang or print other
numbers if a loop took no checkpoints, took them from a dead iterator, or did not share the
thread's slice."""

from __future__ import annotations

from pathlib import Path

from gpltest import run_gpl


def _run(tmp_path: Path, src: str, slice_checkpoints: int = 10) -> tuple[str, str]:
    r = run_gpl(tmp_path, src, slice_checkpoints=slice_checkpoints)
    assert r.status == 0, r.log
    return r.output, r.files[f"{r.package.__name__}/main_mod.py"]


SPIN = """Module Main
    Public seen As Integer
    Public Sub Worker()
        Console.WriteLine("worker ran")
        seen = 1
    End Sub
    Public Sub Main()
        Dim t As New Thread("Worker")
        Dim spins As Integer
        t.Start()
        While seen = 0
            spins += 1
        End While
        Console.WriteLine("spun " & CStr(spins))
    End Sub
End Module
"""


def test_a_busy_wait_lets_the_thread_it_waits_for_run(tmp_path: Path) -> None:
    output, code = _run(tmp_path, SPIN)
    assert "for _ in paced():\n        if seen != 0:\n            break\n" in code
    # slice of 10 checkpoints: the first test and nine turns, then the worker runs
    assert output == "worker ran\nspun 9\n"


TIMER = """Module Main
    Public Sub Main()
        Dim t0 As Double
        Dim n As Integer
        t0 = Controller.Timer
        Do
            n += 1
        Loop Until Controller.Timer >= t0 + 0.05
        Console.WriteLine(CStr(n))
    End Sub
End Module
"""


def test_spinning_on_the_timer_lets_virtual_time_pass(tmp_path: Path) -> None:
    # 1 ms of virtual time per slice of 10 checkpoints: 50 ms is 500 turns of the loop
    output, code = _run(tmp_path, TIMER)
    assert "for _ in paced():" in code and "checkpoint()" not in code
    assert output == "500\n"


NESTED = """Module Main
    Public Sub Main()
        Dim i, j As Integer
        Dim t0 As Double
        t0 = Controller.Timer
        i = 0
        While i < 100
            i += 1
            j = 0
            Do While j < 99
                j += 1
            Loop
        End While
        Console.WriteLine(CStr(CInt((Controller.Timer - t0) * 1000)) & " ms")
    End Sub
End Module
"""


def test_nested_loops_share_the_threads_slice(tmp_path: Path) -> None:
    # a turn per test: the outer loop's 101 and 100 inner runs of 100, 10,101 checkpoints; at 10
    # per 1 ms slice, 1,010 slices end
    output, _ = _run(tmp_path, NESTED)
    assert output == "1010 ms\n"


ABORT = """Module Main
    Public inner As Integer
    Public Sub Worker()
        Dim x, k As Integer
        Try
            While True
                x += 1
            End While
        Finally
            k = 0
            While k < 5
                k += 1
            End While
            inner = k
        End Try
    End Sub
    Public Sub Main()
        Dim t As New Thread("Worker")
        t.Start()
        Thread.Sleep(5)
        t.Abort()
        t.Join()
        Console.WriteLine("finally ran its loop to " & CStr(inner))
    End Sub
End Module
"""


def test_an_aborted_loop_leaves_the_finally_its_own_loops(tmp_path: Path) -> None:
    # the Abort is raised from inside the thread's turns iterator; the loop in the Finally must
    # still get turns (from a fresh iterator), not end at once
    output, _ = _run(tmp_path, ABORT, slice_checkpoints=1000)
    assert output == "finally ran its loop to 5\n"

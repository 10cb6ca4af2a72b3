"""A tiny project and setup for the sweep tests: each parameter set's ``mode`` chooses what the
run does, so one sweep can hold runs that end well, fail, stall, run into the time-out, or whose
setup raises (itself, or in a call into gpl2py) or kills its worker, each in a few milliseconds
of wall time."""

from __future__ import annotations

from pathlib import Path

from gpltest import write_project

MAIN = """\
Module Main
    Public parts As Integer

    Public Sub Main()
        Dim i As Integer
        Dim exc As Exception
        Console.WriteLine("start")
        If Signal.DIO(10001) Then
            exc = New Exception
            exc.ErrorCode = -3100
            Throw exc
        End If
        If Signal.DIO(10002) Then
            Thread.WaitEvent(1, -1)
        End If
        While Signal.DIO(10003)
            Thread.Sleep(100)
        End While
        For i = 1 To parts
            Signal.DIO(1) = True
            Thread.Sleep(250)
            Signal.DIO(1) = False
            Console.WriteLine("part " & CStr(i))
        Next
        Console.WriteLine("done")
    End Sub
End Module
"""

#: The line of ``Throw exc`` in Main.gpl, where mode "fail" ends.
THROW_LINE = MAIN.splitlines().index("            Throw exc") + 1

SETUP = '''\
import os
import signal
import time


def setup(sim, params, cell):
    mode = params["mode"]
    if "log" in params:  # which Dask task ran this set (each time it was tried), one line a try
        from distributed import get_worker

        with open(params["log"], "a") as log:
            log.write(f"{params['n']} {get_worker().get_current_task()}\\n")
    if mode == "fail":
        sim.io.set_input(10001, True)
    elif mode == "stall":
        sim.io.set_input(10002, True)
    elif mode == "loop":
        sim.io.set_input(10003, True)
    elif mode == "setup":
        raise ValueError("no conveyor on this cell")
    elif mode == "nomodule":
        cell.module("Conveyor")  # raises inside gpl2py.notebook: the row names this line
    elif mode == "kill" and not os.path.exists(params["marker"]):
        open(params["marker"], "w").close()
        if "log" in params:
            time.sleep(1.0)  # the rows of the sets before it leave the worker first (they are reported)
        os.kill(os.getpid(), signal.SIGKILL)  # the worker dies mid-run, the first time only
    elif mode == "killall":
        if "log" in params:
            time.sleep(1.0)  # the rows of the sets before it leave the worker first (they are reported)
        os.kill(os.getpid(), signal.SIGKILL)  # every worker that tries it dies
    cell.module("Main").parts = params["parts"]
'''

#: The line of the ``raise`` in SETUP.
RAISE_LINE = SETUP.splitlines().index('        raise ValueError("no conveyor on this cell")') + 1
#: The line of ``cell.module("Conveyor")`` in SETUP (the project has no module Conveyor).
NO_MODULE_LINE = next(i for i, line in enumerate(SETUP.splitlines(), 1) if 'cell.module("Conveyor")' in line)


def tiny_project(root: Path) -> tuple[str, Path]:
    """The project folder and its setup file, under ``root``."""
    project = write_project(root, {"Main.gpl": MAIN}, name="Tiny")
    setup = root / "tiny_setup.py"
    setup.write_text(SETUP)
    return project, setup

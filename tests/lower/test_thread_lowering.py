"""``New Thread("Proc")`` is lowered with the calling GPL module named (``_module=``), as
``New Delegate("Proc")`` is (``from_name(name, "Module")``).

The start procedure resolves as seen from the module executing the ``New`` (Private procedures
of that module included, gplrt.threads.thread).  With the module in the generated code the runtime
does not infer it from the Python caller's frame; the tests below make that inference fail
loudly, so a program only runs when the lowering passed the module itself.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from gpltest import run_gpl
from gplrt.threads import thread as thread_module

MAIN = """Module Main
    Public Sub Main()
        Dim r As New Tools.Runner
        r.Go()
        Tools.Go2()
        Dim t As New Thread("Work", 3, "m3")
        t.Start()
        t.Join()
    End Sub
    Sub Work()
        Console.WriteLine("Main.Work " & CStr(Thread.CurrentThread.Argument))
    End Sub
End Module
"""

TOOLS = """Module Tools
    Public Class Runner
        Public Sub Go()
            Dim t As New Thread("Work", 1, "w1")
            t.Start()
            t.Join()
        End Sub
    End Class
    Public Sub Go2()
        Dim t As Thread
        t = New Thread("Work", 2, "w2")
        t.Start()
        t.Join()
    End Sub
    Sub Work()
        Console.WriteLine("Tools.Work " & CStr(Thread.CurrentThread.Argument))
    End Sub
End Module
"""


@pytest.fixture
def no_inference(monkeypatch: pytest.MonkeyPatch) -> None:
    def refuse(frame: object) -> str | None:
        raise AssertionError("the runtime had to infer the calling module of New Thread")

    monkeypatch.setattr(thread_module, "_calling_module", refuse)


def test_each_module_starts_its_own_private_procedure(tmp_path: Path, no_inference: None) -> None:
    result = run_gpl(tmp_path, {"Main.gpl": MAIN, "Tools.gpl": TOOLS})
    assert result.output.splitlines() == ["Tools.Work 1", "Tools.Work 2", "Main.Work 3"]
    assert result.sim.controller.error_log == []
    tools = next(text for name, text in result.files.items() if name.endswith("tools.py"))
    assert 'Thread("Work", 1.0, "w1", _module="Tools")' in tools


def test_a_private_procedure_of_another_module_is_still_refused(tmp_path: Path, no_inference: None) -> None:
    main = """Module Main
    Public Sub Main()
        Dim t As Thread
        Dim ex As Exception
        Try
            t = New Thread("Tools.Work")
            Console.WriteLine("created")
        Catch ex
            Console.WriteLine(CStr(ex.ErrorCode))
        End Try
    End Sub
End Module
"""
    result = run_gpl(tmp_path, {"Main.gpl": main, "Tools.gpl": TOOLS})
    assert result.output.splitlines() == ["-729"]

"""``New Thread("Proc")`` in transpiled GPL: which procedure a name reaches.

The manuals give no rule for the thread's start procedure; we resolve it like any other name in
the calling module (see ``gplrt.threads.thread``): a procedure of the caller's own module, Public
or Private (module members are Private by default, and real code often declares its thread
procedures as a plain ``Sub``), then the one Public procedure of that name; a qualified
``"Module.Proc"`` names exactly that module's procedure, which must be Public unless it is the
caller's own module.
"""

from __future__ import annotations

from pathlib import Path

from gpltest import run_gpl

MAIN = """Module Main
    Public total As Integer
    Public Sub Main()
        Start("Worker", 1)
        Start("Main.Worker", 2)
        Start("Tools.Helper", 3)
        Start("Helper", 4)
        Start("Tools.Hidden", 5)
        Start("Hidden", 6)
        Start("Tools.Elsewhere", 7)
        Start("Nowhere.Worker", 8)
        Console.WriteLine("total " & CStr(total))
    End Sub
    Sub Start(ByVal name As String, ByVal arg As Integer)
        Dim t As Thread
        Dim ex As Exception
        Try
            t = New Thread(name, arg, "t" & CStr(arg))
            t.Start()
            t.Join()
        Catch ex
            Console.WriteLine(name & " " & CStr(ex.ErrorCode))
        End Try
    End Sub
    Sub Worker()
        Console.WriteLine("Main.Worker arg " & CStr(Thread.CurrentThread.Argument))
        total += 1
    End Sub
End Module
"""

TOOLS = """Module Tools
    Public Sub Helper()
        Console.WriteLine("Tools.Helper arg " & CStr(Thread.CurrentThread.Argument))
    End Sub
    Sub Hidden()
        Console.WriteLine("Tools.Hidden must not run")
    End Sub
End Module
"""

OTHER = """Module Other
    Public Sub Elsewhere()
        Console.WriteLine("Other.Elsewhere must not run for Tools.Elsewhere")
    End Sub
End Module
"""


def test_thread_start_procedures_resolve_like_names_in_the_calling_module(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, {"Main.gpl": MAIN, "Tools.gpl": TOOLS, "Other.gpl": OTHER})
    assert result.output.splitlines() == [
        "Main.Worker arg 1",
        "Main.Worker arg 2",
        "Tools.Helper arg 3",
        "Tools.Helper arg 4",
        "Tools.Hidden -729",     # Private to another module
        "Hidden -729",
        "Tools.Elsewhere -729",  # Tools has no Elsewhere; Other's Public one is not it
        "Nowhere.Worker -798",   # no such module
        "total 2",
    ]
    assert result.sim.controller.error_log == []


def test_a_thread_started_from_module_init_code_finds_its_private_procedure(tmp_path: Path) -> None:
    src = """Module Main
    Dim poller As New Thread("Poll")
    Public Sub Main()
        poller.Start()
        poller.Join()
        Console.WriteLine("done")
    End Sub
    Private Sub Poll()
        Console.WriteLine("polling")
    End Sub
End Module
"""
    result = run_gpl(tmp_path, src)
    assert result.output.splitlines() == ["polling", "done"]


def test_a_start_procedure_with_parameters_is_an_argument_mismatch_at_new(tmp_path: Path) -> None:
    src = """Module Main
    Public Sub Main()
        Dim t As Thread
        Dim ex As Exception
        Try
            t = New Thread("Worker")
            t.Start()
            t.Join()
        Catch ex
            Console.WriteLine("New Thread " & CStr(ex.ErrorCode))
        End Try
    End Sub
    Public Sub Worker(ByVal n As Integer)
        Console.WriteLine("ran with " & CStr(n))
    End Sub
End Module
"""
    result = run_gpl(tmp_path, src)
    assert result.output.splitlines() == ["New Thread -741"]
    assert result.sim.controller.error_log == []

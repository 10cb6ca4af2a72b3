"""Built-in members take the arguments real GPL gives them (issue 11, item 8).

The vendor's TCP Command Server (TCS 3.0C1, ``shared/corpus``) makes the calls below; each
program makes the same call in a few lines and checks its result.  Members the simulated
controller does not implement keep their real signature, so the call translates, and a GPL
``Catch`` sees -204 *Not implemented* naming the member.  A call with the wrong number or type of
arguments is a translation error, as on a controller.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from gpltest import analyze_text, module_src, run_gpl

from gplrt.io.vision import ScriptedVisionServer, VisionToolResult, set_vision_server
from gplrt.sim import Simulation

REPORT = """
    Dim ex As Exception

    Sub Report(ByVal what As String)
        Console.WriteLine(what & " " & CStr(ex.ErrorCode) & " " & ex.Message)
    End Sub
"""


def test_members_the_simulator_lacks_translate_and_raise_204_into_a_catch(tmp_path: Path) -> None:
    """Dictionary members the simulator does not implement (gpl-dictionary §4-§6) keep their real
    signatures: the calls translate and a Catch sees -204 naming the member.  (The members TCS
    calls -- Trigger, ForceOverlap, jog and torque modes, JointToMotor -- are simulated and run in
    tests/motion/test_servo_gripper.py.)"""
    src = module_src(REPORT + """
    Public Sub Main()
        Dim speeds(6) As Double
        Dim dacs(6) As Double
        Dim cor(10) As Double
        Dim button As Integer
        Dim p As New Profile
        Try
            Move.SetSpeeds(speeds, p)
        Catch ex
            Report("SetSpeeds")
        End Try
        Try
            Move.StartVelocityCntrl(0, 0, speeds, p)
        Catch ex
            Report("StartVelocityCntrl")
        End Try
        Try
            Move.StartRealTimeMod(1, 0)
        Catch ex
            Report("StartRealTimeMod")
        End Try
        Try
            Move.SetRealTimeMod(speeds)
        Catch ex
            Report("SetRealTimeMod")
        End Try
        Try
            Move.StartSpeedDAC(1, 2, speeds, dacs)
        Catch ex
            Report("StartSpeedDAC")
        End Try
        Try
            Robot.DefLinComp(1, 1, 0, 100, 10, cor)
        Catch ex
            Report("DefLinComp")
        End Try
        Try
            Controller.ShowDialogMCP(1, "ready?", button)
        Catch ex
            Report("ShowDialogMCP")
        End Try
        Try
            Console.WriteLine(Controller.Command("show thread"))
        Catch ex
            Report("Command")
        End Try
        Console.WriteLine("done")
    End Sub
""")
    res = run_gpl(tmp_path, src)
    assert res.status == 0, res.log
    lines = res.output.splitlines()
    assert lines[-1] == "done"
    # Controller.Command is the console now (gplrt.controller.commands): Show Thread's table
    assert lines[-3].split() == ["Project", "Thread", "State"]
    assert lines[-2].split() == [res.sim.project, "Main", "Running"]
    lines = lines[:-2]
    expected = [("SetSpeeds", "Move"), ("StartVelocityCntrl", "Move"), ("StartRealTimeMod", "Move"),
                ("SetRealTimeMod", "Move"), ("StartSpeedDAC", "Move"), ("DefLinComp", "Robot"),
                ("ShowDialogMCP", "Controller")]
    assert lines[:-1] == [f"{what} -204 *Not implemented*: not available in the simulated controller: {owner}.{what}"
                          for what, owner in expected], res.output


def test_power_enabled_is_read_bare_assigned_bare_and_assigned_with_a_timeout(tmp_path: Path) -> None:
    """Cmd.gpl:351-365 reads ``Controller.PowerEnabled``, assigns it, and assigns
    ``Controller.PowerEnabled(timeout) = True``; PARobot.gpl:2917 does it through a variable
    ``CTL As Controller``.  A power-up slower than the timeout is -1025 *Timeout enabling power*;
    a timeout of 0 waits as long as power takes."""
    src = module_src(REPORT + """
    Private CTL As Controller

    Public Sub Main()
        Const PWR_ENB_TIMEOUT As Integer = 30
        Dim t0 As Double
        Console.WriteLine("power " & CStr(-Controller.PowerEnabled And 1))
        t0 = Controller.Timer(1)
        Try
            Controller.PowerEnabled(2) = True
        Catch ex
            Report("2 s")
            Console.WriteLine("waited " & CStr(CInt(Controller.Timer(1) - t0)))
        End Try
        Controller.PowerEnabled(0) = True
        Console.WriteLine("power " & CStr(-Controller.PowerEnabled And 1) & " after " _
                          & CStr(CInt(Controller.Timer(1) - t0)))
        Controller.PowerEnabled = False
        Console.WriteLine("power " & CStr(-Controller.PowerEnabled And 1))
        CTL.PowerEnabled(PWR_ENB_TIMEOUT) = True
        Console.WriteLine("power " & CStr(-CTL.PowerEnabled And 1) & " state " & CStr(Controller.PowerState))
    End Sub
""")

    def slow_power(sim: Simulation) -> None:
        sim.controller.power_up_time = 5.0

    res = run_gpl(tmp_path, src, setup=slow_power)
    assert res.status == 0, res.log
    assert res.output.splitlines() == [
        "power 0",
        "2 s -1025 *Timeout enabling power*",
        "waited 2",
        "power 1 after 5",  # the power-up went on: it is the controller's, not the thread's
        "power 0",
        "power 1 state 20",
    ]


def test_a_variable_of_a_global_class_reaches_its_shared_members(tmp_path: Path) -> None:
    """PARobot.gpl:2614 ``Private CTL As Controller  ' Shorthand for Controller class``, then
    ``CTL.PDbNum(...) = v`` and ``x = CTL.PDbNum(...)``; PDbNum's assignment takes the key too."""
    src = module_src("""
    Private CTL As Controller

    Public Sub Main()
        CTL.PDbNum(601) = 50
        Console.WriteLine(CStr(CTL.PDbNum(601)))
        Controller.PDbNum(601, 1, 1, 1, 0) = 40
        Console.WriteLine(CStr(Controller.PDbNum(601)))
    End Sub
""")
    res = run_gpl(tmp_path, src)
    assert res.status == 0, res.log
    assert res.output.splitlines() == ["50", "40"]


@pytest.fixture
def vision() -> Iterator[None]:
    server = ScriptedVisionServer()
    server.add_process("Find", {
        "part": [VisionToolResult(info=[1.0]), VisionToolResult(info=[2.0]), VisionToolResult(info=[3.0])],
        "hole": [VisionToolResult(info=[10.0]), VisionToolResult(info=[20.0])],
    })
    server.properties[("system", "Exposure")] = "7"
    set_vision_server(server)
    yield
    set_vision_server(None)


def test_vision_result_count_bare_result_with_0_1_2_arguments_and_tool_property(
        tmp_path: Path, vision: None) -> None:
    """Cmd.gpl:1932 ``vis.ResultCount`` without parentheses and Cmd.gpl:1955/1957
    ``vis.Result()`` / ``vis.Result(name, index)``: no name is the process's first tool ("the
    default result").  ``vis.ToolProperty("tool.prop")`` reads and assigns like the two-argument
    form."""
    src = module_src("""
    Dim vis As New Vision
    Dim vr As VisResult

    Public Sub Main()
        vis.Process("Find")
        Console.WriteLine("count " & CStr(vis.ResultCount) & " " & CStr(vis.ResultCount("hole")))
        vr = vis.Result()
        Console.WriteLine("default " & CStr(vr.Info(0)))
        vr = vis.Result("hole")
        Console.WriteLine("hole " & CStr(vr.Info(0)))
        vr = vis.Result("hole", 2)
        Console.WriteLine("hole 2 " & CStr(vr.Info(0)))
        vis.ToolProperty("part.Threshold") = "42"
        Console.WriteLine("threshold " & vis.ToolProperty("part", "Threshold"))
        vis.ToolProperty("part", "Threshold") = "43"
        Console.WriteLine("threshold " & vis.ToolProperty("part.Threshold"))
        Console.WriteLine("exposure " & vis.ToolProperty("system.Exposure"))
    End Sub
""")
    res = run_gpl(tmp_path, src)
    assert res.status == 0, res.log
    assert res.output.splitlines() == ["count 3 2", "default 1", "hole 10", "hole 2 20", "threshold 42",
                                       "threshold 43", "exposure 7"]


def test_dictionary_forms_whose_meaning_is_unknown_are_204(tmp_path: Path) -> None:
    """gpl-dictionary §9.1 ``Signal.DIO(channel, count)`` and §2 ``rf.Pos(location)`` translate;
    the simulator does not guess what they do (-204), while their plain forms work."""
    src = module_src(REPORT + """
    Public Sub Main()
        Dim rf As New RefFrame
        Dim loc As New Location
        rf.Loc.XYZ(10, 20, 30)
        Console.WriteLine("pos " & CStr(rf.Pos.X))
        Try
            loc = rf.Pos(loc)
        Catch ex
            Report("Pos")
        End Try
        Signal.DIO(1) = True
        Console.WriteLine("dio " & CStr(-Signal.DIO(1) And 1))
        Try
            Signal.DIO(1, 2) = True
        Catch ex
            Report("DIO")
        End Try
    End Sub
""")
    res = run_gpl(tmp_path, src)
    assert res.status == 0, res.log
    assert res.output.splitlines() == [
        "pos 10",
        "Pos -204 *Not implemented*: not available in the simulated controller: RefFrame.Pos(location)",
        "dio 1",
        "DIO -204 *Not implemented*: not available in the simulated controller: Signal.DIO(signal, count)",
    ]


def test_robot_offsets_are_assigned_with_and_without_a_robot_number(tmp_path: Path) -> None:
    """``Robot.Tool = loc`` (Cmd.gpl:1528) and ``Robot.Tool(robot) = loc``; ``Robot.Custom(index)
    = v`` has one argument fewer than its read form ``Robot.Custom(robot, index)`` (custom.htm)."""
    src = module_src("""
    Public Sub Main()
        Dim t As Location
        t = Location.XYZValue(0, 0, 25, 0, 0, 0)
        Robot.Tool = t
        Console.WriteLine("tool " & CStr(Robot.Tool.Z))
        t.Z = 40
        Robot.Tool(1) = t
        Console.WriteLine("tool " & CStr(Robot.Tool(1).Z))
        Robot.Custom(2) = 5
        Console.WriteLine("custom " & CStr(Robot.Custom(0, 2)) & " " & CStr(Robot.Custom(1, 1)))
    End Sub
""")
    res = run_gpl(tmp_path, src)
    assert res.status == 0, res.log
    assert res.output.splitlines() == ["tool 25", "tool 40", "custom 5 0"]


@pytest.mark.parametrize(("statement", "code", "message"), [
    ("Move.Trigger(1)", "GPL2004", "'Trigger' takes 3 to 4 argument(s), 1 given"),
    ("Move.ForceOverlap(0, 100, 5)", "GPL2004", "'ForceOverlap' takes 2 argument(s), 3 given"),
    ("Move.SetTorques()", "GPL2004", "'SetTorques' takes 1 argument(s), 0 given"),
    ('Move.SetTorques("high")', "GPL2005", "type mismatch: a String value cannot be used as Double()"),
    ("Robot.JointToMotor(1, arr)", "GPL2004", "'JointToMotor' takes 3 argument(s), 2 given"),
    ("Move.SetSpeeds(arr)", "GPL2004", "'SetSpeeds' takes 2 argument(s), 1 given"),
    ("Controller.PowerEnabled(1, 2) = True", "GPL2004", "'PowerEnabled' takes 0 to 1 argument(s), 2 given"),
    ("b = Controller.PowerEnabled(5)", "GPL2012",
     "'Controller.PowerEnabled' is not an array, procedure or delegate and cannot take arguments"),
    ("Robot.Custom(1, 2) = 3", "GPL2004", "'Custom' takes 0 to 1 argument(s), 2 given"),
    ('vis.ToolProperty("a", "b", "c") = "x"', "GPL2004", "'ToolProperty' takes 1 to 2 argument(s), 3 given"),
    ("x = vis.Result(\"a\", 1, Nothing, 4)", "GPL2004", "'Result' takes 0 to 3 argument(s), 4 given"),
    ("c = New Controller", "GPL2036", "'Controller' has only Shared members and cannot be created with New"),
])
def test_wrong_arguments_are_translation_errors(tmp_path: Path, statement: str, code: str, message: str) -> None:
    model, sink = analyze_text(tmp_path, module_src(f"""
    Public Sub Main()
        Dim b As Boolean
        Dim c As Controller
        Dim vis As New Vision
        Dim x As VisResult
        Dim arr(3) As Double
        {statement}
    End Sub
"""))
    assert [(d.code, d.message) for d in sink if d.severity.value == "error"] == [(code, message)]

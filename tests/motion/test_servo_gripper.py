"""The PF400 servo gripper, jog, torque mode, Move.Trigger and Move.ForceOverlap, driven by
transpiled GPL the way PARobot.gpl drives them (gplrt/motion/servo.py, gplrt/motion/special.py)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from gpltest import module_src, run_gpl
from gplrt.sim import Simulation

# A grip with a force limit, as a plug-in would write it: the joint-to-motor scale, the PID limit
# written, a close narrower than the plate, then the PID torque read back (12304 - 12331).
GRIP = """
    Public Released As Boolean

    Public Sub Reset()
        Thread.WaitEvent(&H1, -1)
        Controller.PDbNum(10352, 1, 0, 5) = 0
        Released = True
    End Sub

    Public Sub Main()
        Dim mm(5), enc(5) As Double
        Dim p As New Profile
        Dim t As New Thread("Main.Reset")
        Dim pid As Double
        p.InRange = 0
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home
        mm(4) = 1
        Robot.JointToMotor(1, mm, enc)
        Console.WriteLine("scale " & CStr(enc(4)))
        Move.OneAxis(5, 120, False, p)
        Move.WaitForEOM
        Controller.PDbNum(10352, 1, 0, 5) = -2500
        Move.OneAxis(5, 73, False, p)
        Move.WaitForEOM
        pid = Controller.PDbNum(12304, 1, 0, 5) - Controller.PDbNum(12331, 1, 0, 5)
        Console.WriteLine("closed at " & CStr(Robot.WhereAngles.Angle(5)) & " set " _
            & CStr(Robot.DestAngles.Angle(5)) & " pid " & CStr(pid) & " eot " & CStr(Signal.DIO(210002)))
        t.Start
        Move.Trigger(0, 50, t, &H1)
        Move.OneAxis(5, 120, False, p)
        Thread.Sleep(10)
        Console.WriteLine("released early: " & CStr(Released))
        Move.WaitForEOM
        Thread.Sleep(10)
        Console.WriteLine("released: " & CStr(Released) & " limit " & CStr(Controller.PDbNum(10352, 1, 0, 5)))
    End Sub
"""


def _loaded(tmp_path: Path, source: str, start: str = "Main") -> tuple[Any, Simulation]:
    """The transpiled project of one module ``source``, imported, and a Simulation for it (for a
    test that acts on the simulated robot between the program's steps)."""
    from gpl2py.run import import_package  # noqa: F401 - (gpltest imports through it)
    from gpltest import transpile_to
    import importlib
    import sys

    package, _, _ = transpile_to(tmp_path, module_src(source), start=start)
    sys.path.insert(0, str(tmp_path / "out"))
    try:
        pkg = importlib.import_module(package)
    finally:
        sys.path.remove(str(tmp_path / "out"))
    return pkg, Simulation(capture=True, project=package)


def _grip(tmp_path: Path, plate: float | None) -> list[str]:
    from gplrt.motion.servo import gripper_of

    pkg, sim = _loaded(tmp_path, GRIP)
    with sim:
        gripper_of(sim).plate_width = plate
    assert pkg.main(sim) == 0, sim.console.log_text
    return sim.console.output.splitlines()


def test_gripping_a_plate_reads_the_force_limit_and_the_trigger_releases_it(tmp_path: Path) -> None:
    lines = _grip(tmp_path, 80.0)
    assert lines[0] == "scale 170.599"
    assert lines[1] == "closed at 80 set 73 pid -2500 eot 0"  # held open by the plate, torque at the limit
    assert lines[2:] == ["released early: 0", "released: -1 limit 0"]


def test_closing_on_nothing_closes_fully(tmp_path: Path) -> None:
    lines = _grip(tmp_path, None)
    assert lines[1] == "closed at 73 set 73 pid 0 eot -1"


def test_jog_free_and_torque_modes(tmp_path: Path) -> None:
    res = run_gpl(tmp_path, module_src("""
    Public Sub Main()
        Dim torques(12) As Double
        Dim p As New Profile
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home
        Move.StartJogMode()
        Move.SetJogCommand(1, 1, 100)
        Thread.Sleep(2000)
        Console.WriteLine("jog " & CStr(Robot.TrajState) & " z " & CStr(Robot.WhereAngles.Angle(1)))
        Try
            Move.OneAxis(1, 10, False, p)
        Catch ex As Exception
            Console.WriteLine("move in jog mode: " & CStr(ex.ErrorCode))
        End Try
        Move.SetJogCommand(4, 2, 50)
        Thread.Sleep(1000)
        Console.WriteLine("free z " & CStr(Robot.WhereAngles.Angle(1)))
        Move.StopSpecialModes
        Console.WriteLine("stopped " & CStr(Robot.TrajState))
        Move.StartTorqueCntrl(&H1, 0, torques)
        Move.SetTorques(torques)
        Thread.Sleep(1000)
        Console.WriteLine("zero torque " & CStr(Robot.TrajState) & " z " & CStr(Robot.WhereAngles.Angle(1)))
        torques(0) = -1
        Move.SetTorques(torques)
        Thread.Sleep(1000)
        Console.WriteLine("drift z " & CStr(Robot.WhereAngles.Angle(1)))
        Move.StopSpecialModes
        Move.OneAxis(1, 100, False, p)
        Move.WaitForEOM
        Console.WriteLine("position mode z " & CStr(Robot.WhereAngles.Angle(1)))
    End Sub
    """))
    # jog: 100 % of DataID 2820 (3 %) of J1's 500 mm/s = 15 mm/s from 1.5 mm; torque -1 %: 7.5 mm/s down
    assert res.output.splitlines() == [
        "jog 10 z 31.5", "move in jog mode: -1017", "free z 31.5", "stopped 1",
        "zero torque 8 z 31.5", "drift z 24", "position mode z 100"], res.output + res.log


# Real lab code (a "Freedrive" command added to TCS, issue 20) frees every axis at once with axis
# -1; the hand (``push``) then moves each of them between the two procedures.
FREEDRIVE = """
    Public Sub FreeAll()
        Dim p As New Profile
        Dim start As New Location
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home
        start.Angles(300, 10, 90, -100, 90)
        Move.Loc(start, p)
        Move.WaitForEOM
        Move.StartJogMode()
        Move.SetJogCommand(4, -1, 1)
        Console.WriteLine("free " & CStr(Robot.TrajState))
    End Sub

    Public Sub Back()
        Dim p As New Profile
        Dim ax As Integer
        Dim text As String = "by hand"
        For ax = 1 To 5
            text = text & " " & CStr(Robot.WhereAngles.Angle(ax))
        Next
        Console.WriteLine(text)
        Try
            Move.SetJogCommand(1, -1, 50)
        Catch ex As Exception
            Console.WriteLine("jog axis -1: " & CStr(ex.ErrorCode))
        End Try
        Move.StopSpecialModes
        Console.WriteLine("left " & CStr(Robot.TrajState))
        Move.OneAxis(1, 200, False, p)
        Move.WaitForEOM
        Console.WriteLine("moved " & CStr(Robot.WhereAngles.Angle(1)) & " " & CStr(Robot.WhereAngles.Angle(3)))
    End Sub
"""


def test_jog_axis_minus_one_frees_every_axis_until_jog_mode_ends(tmp_path: Path) -> None:
    """``Move.SetJogCommand(4, -1, 1)`` (real lab code; docs/design/real-code.md): every axis is
    free, so the hand moves all five; after ``StopSpecialModes`` the robot moves under program
    control again from where the hand left it (a joint jog of axis -1 is still -1002).  The
    simulator refused axis -1 with -1002."""
    from gplrt.motion.special import push

    pkg, sim = _loaded(tmp_path, FREEDRIVE, start="FreeAll")

    def session() -> None:
        pkg.init()
        pkg.main_mod.FreeAll()
        push(sim, 1, {1: 350.0, 2: 20.0, 3: 100.0, 4: -90.0, 5: 100.0})  # every axis, by hand
        pkg.main_mod.Back()

    sim.call(session)
    assert sim.console.output.splitlines() == [
        "free 10", "by hand 350 20 100 -90 100", "jog axis -1: -1002", "left 1", "moved 200 100"], sim.console.log_text


def test_force_overlap_runs_two_axes_side_by_side(tmp_path: Path) -> None:
    res = run_gpl(tmp_path, module_src("""
    Public Sub Main()
        Dim p As New Profile
        Dim t0 As Double
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home
        Move.OneAxis(1, 300, False, p)
        Move.WaitForEOM
        t0 = Controller.Timer(1)
        Move.OneAxis(3, 60, False, p)
        Move.ForceOverlap(0, 100)
        Move.OneAxis(4, 90, False, p)
        Thread.Sleep(200)
        Console.WriteLine(CStr(Robot.TrajState) & " " & CStr(Robot.WhereAngles.Angle(3) > 12) & " " _
            & CStr(Robot.WhereAngles.Angle(4) > 0))
        Move.WaitForEOM
        Console.WriteLine(CStr(Robot.WhereAngles.Angle(3)) & " " & CStr(Robot.WhereAngles.Angle(4)))
    End Sub
    """))
    assert res.output.splitlines() == ["6 -1 -1", "60 90"], res.output + res.log

"""gplrt.notebook.Cell: load through the cache, call procedures, I/O, robot state, plots."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from gplrt.lang.errors import GplException
from gplrt.notebook import Cell, ProjectError
from gpltest import module_src, write_project

STATION = module_src("""\
    Public count As Integer
    Public last As String
    Public Const DOUT_BUSY As Integer = 3
    Public Const DIN_START As Integer = 10005

    Public Sub Init()
        last = "ready"
    End Sub

    Public Function Scale(ByVal a As Integer, ByVal b As Double) As Double
        count += 1
        Return a * b
    End Function

    Private Function Secret() As Integer
        Return 42
    End Function

    ' Sets the busy output, waits for the start button, then moves to a taught point.
    Public Sub Cycle()
        Dim target As New Location
        Dim prof As New Profile
        Signal.DIO(DOUT_BUSY) = True
        While Not Signal.DIO(DIN_START)
            Thread.Sleep(10)
        End While
        Controller.PowerEnabled = True
        While Not Controller.PowerEnabled
            Thread.Sleep(10)
        End While
        Robot.Attached = 1
        Robot.Home
        target.XYZ(300, 150, 200, 0, 90, 180)
        Move.Loc(target, prof)
        Move.WaitForEOM
        Robot.Attached = 0
        Signal.DIO(DOUT_BUSY) = False
        last = "moved"
    End Sub

    Public Sub Main()
        Console.WriteLine("station up, count " & CStr(count))
    End Sub""", "Station")


@pytest.fixture
def cell(tmp_path: Path) -> Cell:
    proj = write_project(tmp_path, {"Station.gpl": STATION}, start="Station.Main", name="Station")
    return Cell.load(proj, robot="PF400SX", clock="virtual", echo=False)


def test_call_public_procedures_with_arguments_after_init(cell: Cell) -> None:
    assert cell.get("Station.last") == ""  # imported, not initialised
    cell.init()
    assert cell.get("Station.last") == "ready"
    assert cell.call("Station.Scale", 3, 2.5) == 7.5
    assert cell.call("scale", 2, 0.5) == 1.0  # case-insensitive, unique Public name
    assert cell.get("station.COUNT") == 2
    assert cell.run_main() == 0
    assert cell.console == "station up, count 2\n"


def test_private_and_unknown_procedures_are_refused_with_gpl_codes(cell: Cell) -> None:
    with pytest.raises(GplException) as info:
        cell.call("Station.Secret")
    assert info.value.ErrorCode == -729 and "Private" in str(info.value)
    with pytest.raises(GplException) as info:
        cell.call("Station.Nothing")
    assert info.value.ErrorCode == -729 and "Station.Scale" in str(info.value)


def test_inputs_outputs_motion_and_where(cell: Cell) -> None:
    worker = cell.start("Station.Cycle")
    cell.run_for(0.5)
    assert cell.output(3) is True  # busy, waiting for the start input
    assert cell.get("Station.last") == "ready"
    cell.set_input(10005, True)
    cell.run_for(30.0)
    assert worker.ThreadState != 1  # not running any more
    assert cell.get("Station.last") == "moved" and cell.output(3) is False
    assert [(s, v) for _, s, v in cell.outputs_written()] == [(3, True), (3, False)]
    pose = cell.where()
    assert pose.cartesian is not None
    assert np.allclose(pose.cartesian, (300, 150, 200, 0, 90, 180), atol=1e-6)
    assert pose.matrix is not None and np.allclose(pose.matrix[:3, 3], (300, 150, 200), atol=1e-6)
    # the joints reproduce the pose through the robot's own forward kinematics
    from gplrt.motion.registry import robot_of

    state = robot_of(cell.sim, 1)
    assert np.allclose(state.forward(np.array(pose.joints))[:3, 3], (300, 150, 200), atol=1e-6)


def test_plots_of_the_motion(cell: Cell, tmp_path: Path) -> None:
    cell.start("Station.Cycle")
    cell.set_input(10005, True)
    cell.run_for(30.0)
    tr = cell.trace()
    assert np.allclose(tr.xyz[-1], (300, 150, 200), atol=1e-6)
    fig = cell.plot_joints()
    assert [line.get_label() for line in fig.axes[0].get_lines()] == list(tr.names)
    fig = cell.plot_path()
    xs = fig.axes[0].get_lines()[0].get_xdata()
    assert math.isclose(xs[-1], 300, abs_tol=1e-6)
    png = cell.save_plot(tmp_path / "plots" / "station.png")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_history_is_chosen_at_load_and_the_plots_say_what_they_leave_out(tmp_path: Path) -> None:
    proj = write_project(tmp_path, {"Station.gpl": STATION}, start="Station.Main", name="Station")
    short = Cell.load(proj, history=1, signal_history=1, echo=False)
    assert short.sim.history == 1 and short.sim.io.trace_window == 1
    everything = Cell.load(proj, history=None, signal_history=None, echo=False)
    assert everything.sim.history is None and everything.sim.io.trace_window is None
    for cell in (short, everything):
        for _ in range(20):  # (a window is trimmed a batch at a time: at least 17 motions past 1)
            cell.start("Station.Cycle")
            cell.set_input(10005, True)
            cell.run_for(5.0)
            cell.set_input(10005, False)
    assert [v for _, s, v in everything.outputs_written() if s == 3] == [True, False] * 20
    assert len(short.outputs_written()) < 40 and short.sim.io.trace_dropped > 0
    tr, full = short.trace(), everything.trace()
    assert full.complete
    assert not tr.complete and tr.times[0] > full.times[0]  # the window starts later...
    assert np.allclose(tr.xyz[-1], full.xyz[-1], atol=1e-9)  # ...and ends where the robot is
    texts = [t.get_text() for ax in short.plot_joints().axes for t in ax.texts]
    assert any("earlier motions dropped" in t for t in texts), texts
    with pytest.raises(ValueError, match="history window"):
        Cell.load(proj, history=0, echo=False)


def test_robot_model_and_clock_are_chosen_at_load(tmp_path: Path) -> None:
    proj = write_project(tmp_path, {"Station.gpl": STATION}, start="Station.Main", name="Station")
    arm = Cell.load(proj, robot="ARM6", clock="real", speed=50, echo=False)
    assert arm.sim.mode == "real" and len(arm.where().joints) == 6
    pf = Cell.load(proj, robot="PF400SX", echo=False)
    assert pf.sim.mode == "virtual" and len(pf.where().joints) == 5
    with pytest.raises(GplException) as info:
        Cell.load(proj, robot="R2D2")
    assert info.value.ErrorCode == -221


@pytest.mark.parametrize("robot", [None, 400, ["PF400SX"]])
def test_a_robot_that_is_not_a_model_name_is_221(tmp_path: Path, robot: object) -> None:
    proj = write_project(tmp_path, {"Station.gpl": STATION}, start="Station.Main", name="Station")
    with pytest.raises(GplException) as info:
        Cell.load(proj, robot=robot)  # type: ignore[arg-type]
    assert info.value.ErrorCode == -221 and "a robot model is a name" in str(info.value)


def test_stubs_that_are_not_a_path_are_named(tmp_path: Path) -> None:
    proj = write_project(tmp_path, {"Station.gpl": STATION}, start="Station.Main", name="Station")
    with pytest.raises(TypeError, match="stubs is the folder of Python stubs"):
        Cell.load(proj, stubs=5)  # type: ignore[arg-type]


def test_two_loads_share_the_cache_entry_but_not_module_state(tmp_path: Path, private_cache: Path) -> None:
    proj = write_project(tmp_path, {"Station.gpl": STATION}, start="Station.Main", name="Station")
    a = Cell.load(proj, echo=False)
    entries = sorted(private_cache.iterdir())
    assert len(entries) == 1  # the load wrote its entry here: else the checks below compare nothing
    stamps = {p: p.stat().st_mtime_ns for p in private_cache.rglob("*") if "__pycache__" not in p.parts}
    b = Cell.load(proj, echo=False)
    assert sorted(private_cache.iterdir()) == entries
    assert {p: p.stat().st_mtime_ns for p in private_cache.rglob("*") if "__pycache__" not in p.parts} == stamps
    a.call("Station.Scale", 1, 1.0)
    b.init()
    assert a.get("Station.count") == 1 and b.get("Station.count") == 0


def test_echo_prints_console_output_as_it_comes(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    proj = write_project(tmp_path, {"Station.gpl": STATION}, start="Station.Main", name="Station")
    cell = Cell.load(proj)
    cell.run_main()
    assert capsys.readouterr().out == "station up, count 0\n" == cell.console


def test_project_errors_raise_with_diagnostics(tmp_path: Path) -> None:
    proj = write_project(tmp_path, {"Main.gpl": module_src("    Public Sub Main()\n        x = 1\n    End Sub")})
    with pytest.raises(ProjectError) as info:
        Cell.load(proj)
    assert "Main.gpl:3:9: error GPL2001" in str(info.value)

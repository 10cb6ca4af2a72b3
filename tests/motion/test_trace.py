"""Traces: sampled arrays that end on target, PNG plots, and bit-identical repeated runs."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402

from gplrt.controller.services import Controller  # noqa: E402
from gplrt.geometry.location import Location  # noqa: E402
from gplrt.motion.move import Move  # noqa: E402
from gplrt.motion.plot import plot_joints, plot_path_xy  # noqa: E402
from gplrt.motion.profile import Profile  # noqa: E402
from gplrt.motion.robot_class import Robot  # noqa: E402
from gplrt.sim import Simulation  # noqa: E402
from gplrt.threads.thread import Thread  # noqa: E402


def pick_and_place(cycles: int = 3) -> None:
    """A small cell program: joint moves between stations, straight approach/depart, blends."""
    Robot.Attached = 1
    Controller.PowerEnabled = True
    Robot.Home()
    fast, straight, blend = Profile(), Profile(), Profile()
    fast.Speed = 100.0
    straight.Straight = True
    blend.InRange = -2.0
    pick, place = Location(), Location()
    pick.XYZ(450.0, -150.0, 250.0, -20.0, 90.0, 180.0)
    place.XYZ(350.0, 300.0, 320.0, 60.0, 90.0, 180.0)
    for loc in (pick, place):
        loc.ZClearance, loc.ZWorld = 60.0, False
    for _ in range(cycles):
        for loc in (pick, place):
            Move.Approach(loc, blend)
            Move.Loc(loc, straight)
            Move.WaitForEOM()
            Thread.Sleep(50)  # gripper
            Move.Approach(loc, straight)
    Move.Loc(Location.from_angles((300.0, 0.0, 90.0, 0.0, 100.0)), fast)
    Move.WaitForEOM()


def run_once() -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    sim = Simulation(capture=True)
    assert sim.run_main(pick_and_place) == []
    assert sim.console.log_text == ""  # no unhandled GPL error in the thread
    times, joints, xyz = sim.trace(1)
    return times, joints, xyz, sim.now()


def test_trace_arrays_and_final_sample_on_target() -> None:
    sim = Simulation(capture=True)
    target = (500.0, 20.0, 80.0, -30.0, 90.0)

    def main() -> None:
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home()
        Move.Loc(Location.from_angles(target), Profile())
        Move.WaitForEOM()

    sim.run_main(main)
    assert sim.console.log_text == ""
    tr = sim.trace(1, dt=0.01)
    assert tr.joints.shape == (len(tr.times), 5) and tr.xyz.shape == (len(tr.times), 3)
    assert np.all(np.diff(tr.times) > 0)
    assert tuple(tr.joints[-1]) == target
    assert tr.names == ("Z", "Shoulder", "Elbow", "Wrist", "Gripper")
    seg = sim.robots[1].queue.last
    assert tr.times[-1] == seg.end
    robot = sim.robots[1]
    assert np.allclose(tr.xyz[-1], robot.forward(np.array(target))[:3, 3], atol=1e-12)


def test_same_program_twice_gives_bit_identical_traces() -> None:
    a, b = run_once(), run_once()
    assert a[3] == b[3]
    for x, y in zip(a[:3], b[:3]):
        assert x.shape == y.shape and x.tobytes() == y.tobytes()
    assert a[3] > 5.0  # the program really moved for a while


def test_plots_write_png_files(tmp_path: Path) -> None:
    sim = Simulation(capture=True)
    sim.run_main(lambda: pick_and_place(1))
    assert sim.console.log_text == ""
    tr = sim.trace(1)
    for name, fn in (("joints.png", plot_joints), ("path.png", plot_path_xy)):
        fig = fn(tr)
        out = tmp_path / name
        fig.savefig(out)
        assert out.exists() and out.stat().st_size > 1000
        import matplotlib.pyplot as plt

        plt.close(fig)

"""Motion benchmark: planning cost of Move.Loc against a bare Ruckig call, and the virtual-time factor.

Printed figures (all measured in this one run, on this machine):

1. ``Move.Loc`` planning time per call (joint-interpolated, and straight-line) against a bare
   ``Ruckig.calculate`` for the same number of axes (5, a PF400SX) — target ≤ 3× for joint moves;
   a straight line also solves the IK along the path (reported, no target).
2. The virtual-time factor of a 200-move pick-and-place program run through the Python API on a
   GPL thread: simulated controller seconds per wall-clock second — target ≥ 1,000×.

The machine may be shared and noisy, so every figure is the best of several runs (noise only
ever adds time; the minimum is the figure closest to the code's own cost).

Run:  .venv/bin/python benchmarks/motion_speed.py
"""

from __future__ import annotations

import sys
import time

import numpy as np
from ruckig import InputParameter, Ruckig, Trajectory

from gplrt.controller.services import Controller
from gplrt.geometry.location import Location
from gplrt.motion.move import Move
from gplrt.motion.profile import Profile
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation

N_PLAN = 400
#: Runs per figure; the best is reported (see the module docstring).
BEST_OF = 5


def bare_ruckig(n_calls: int) -> float:
    """Seconds per Ruckig.calculate of a 5-axis move (new Trajectory each time, as Move.Loc does)."""
    otg, inp = Ruckig(5), InputParameter(5)
    inp.max_velocity = [250.0, 180.0, 360.0, 360.0, 200.0]
    inp.max_acceleration = [3500.0, 600.0, 920.0, 4000.0, 10000.0]
    inp.max_jerk = [35000.0, 6000.0, 9200.0, 40000.0, 100000.0]
    rng = np.random.default_rng(1)
    targets = rng.uniform([1.5, -80, 20, -300, 70], [1100, 80, 340, 300, 130], size=(n_calls, 5))
    t = time.perf_counter()
    for i in range(n_calls):
        inp.current_position = list(targets[i - 1])
        inp.target_position = list(targets[i])
        otg.calculate(inp, Trajectory(5))
    return (time.perf_counter() - t) / n_calls


def plan_cost(straight: bool, n_calls: int) -> float:
    """Seconds per Move.Loc call (queue emptied between calls so each plans from rest)."""
    sim = Simulation(capture=True)
    result: list[float] = []

    def main() -> None:
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home()
        prof = Profile()
        prof.Straight = straight
        robot = sim.robots[1]
        rng = np.random.default_rng(2)
        if straight:
            base = Location()
            base.XYZ(400.0, 0.0, 300.0, 0.0, 90.0, 180.0)
            Move.Loc(base, Profile())
            Move.WaitForEOM()
            goals = []
            for dx, dy, dz in rng.uniform([-60, -60, -100], [60, 60, 100], size=(n_calls, 3)):
                g = base.Clone()
                g.XYZ(400.0 + dx, dy, 300.0 + dz, 0.0, 90.0, 180.0)
                goals.append(g)
        else:
            qs = rng.uniform([1.5, -80, 20, -300, 70], [1100, 80, 340, 300, 130], size=(n_calls, 5))
            goals = [Location.from_angles(q) for q in qs]
        spent = 0.0
        for g in goals:
            t = time.perf_counter()
            Move.Loc(g, prof)
            spent += time.perf_counter() - t
            robot.queue.history.clear()  # next call plans from rest again: measure planning only
            robot.queue._starts.clear()
            robot.queue.rest = np.array(robot.model.inverse(g.matrix(), 0, robot.model.ready_joints())
                                        if g.Type == 0 else g.axis_values(), dtype=float)
        result.append(spent / len(goals))

    sim.run_main(main)
    if sim.console.log_text:
        raise SystemExit(sim.console.log_text)
    return result[0]


def pick_and_place(moves: int) -> None:
    Robot.Attached = 1
    Controller.PowerEnabled = True
    Robot.Home()
    transit, straight = Profile(), Profile()
    transit.Speed = 100.0
    transit.InRange = -5.0
    straight.Straight = True
    straight.Speed = 50.0
    stations = []
    for x, y, yaw in ((450.0, -200.0, -30.0), (350.0, 300.0, 60.0), (-300.0, 400.0, 120.0)):
        loc = Location()
        loc.XYZ(x, y, 250.0, yaw, 90.0, 180.0)
        loc.ZClearance, loc.ZWorld = 80.0, False
        stations.append(loc)
    done = 0
    i = 0
    while done < moves:
        loc = stations[i % len(stations)]
        Move.Approach(loc, transit)  # joint, blended into the straight move below
        Move.Loc(loc, straight)
        Move.WaitForEOM()
        Controller.SleepTick(25)  # gripper
        Move.Approach(loc, straight)
        done += 3
        i += 1
    Move.WaitForEOM()


def virtual_time_factor(moves: int = 200) -> tuple[float, float, float]:
    sim = Simulation(capture=True)
    t = time.perf_counter()
    sim.run_main(lambda: pick_and_place(moves))
    wall = time.perf_counter() - t
    if sim.console.log_text:
        raise SystemExit(sim.console.log_text)
    return sim.now(), wall, sim.now() / wall


def main() -> int:
    Simulation(capture=True)  # warm-up: imports, model build
    plan_cost(False, 20)
    # interleaved, so that a burst of load on the machine hits both sides of the ratio alike
    bares, joints, lines = [], [], []
    for _ in range(BEST_OF):
        bares.append(bare_ruckig(N_PLAN))
        joints.append(plan_cost(False, N_PLAN))
        lines.append(plan_cost(True, N_PLAN // 4))
    bare, joint, line = min(bares), min(joints), min(lines)
    print(f"bare Ruckig.calculate (5 axes)     {bare * 1e6:8.1f} us")
    print(f"Move.Loc joint (PF400SX, 5 axes)   {joint * 1e6:8.1f} us   ratio {joint / bare:5.2f}x   (target <= 3x)")
    print(f"Move.Loc straight (IK along path)  {line * 1e6:8.1f} us   ratio {line / bare:5.2f}x")
    sim_s, wall, factor = max((virtual_time_factor(200) for _ in range(BEST_OF)), key=lambda r: r[2])
    print(f"200-move pick-and-place: {sim_s:.2f} simulated s in {wall:.3f} wall s = {factor:,.0f}x   (target >= 1,000x)")
    return 0


if __name__ == "__main__":
    sys.exit(main())

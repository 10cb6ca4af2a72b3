"""Motion benchmark: planning cost of Move.Loc against a bare Ruckig call, and the virtual-time factor.

Printed figures (all measured in this one run, on this machine):

1. ``Move.Loc`` planning time per call against a bare ``Ruckig.calculate`` of as many axes as
   the robot has (5, a PF400SX) — target <= 3x — for three kinds of move, each planned from
   rest at the previous call's goal:

   * joint-interpolated to an Angles Location: the bare call gets exactly the Ruckig input
     Move.Loc produces (the robot's limits at the Profile's percentages, the same start and
     target joints), so the ratio is the cost of everything Move.Loc adds — the attach, power
     and homed checks, the joint-limit check, the Profile scaling, the queue bookkeeping;
   * joint-interpolated to the same goals as Cartesian Locations: all that plus their IK;
   * straight line to a Cartesian Location: what the controller does when it plans one
     (gpl-classes §22.4) — the destination's IK (an unreachable destination is refused at once)
     and a 1-DOF Ruckig profile of the path parameter; its joints are solved cycle by cycle while
     it runs (motion/path_run.py).  For reference the run also prints a bare 1-axis
     ``Ruckig.calculate`` fed the very inputs those plans used, and what executing each line to
     its end costs (every 16 ms cycle solved: what WaitForEOM pays).
2. The virtual-time factor of a 200-move pick-and-place program run through the Python API on a
   GPL thread: simulated controller seconds per wall-clock second — target >= 1,000x.

The machine may be shared and noisy.  The two sides of a ratio are timed in alternating blocks of
``BLOCK`` calls on the same goals, so a burst of load hits both alike, and each side's figure is
its fastest block (noise only ever adds time; the minimum is the figure closest to the code's own
cost).

Run:  .venv/bin/python benchmarks/motion_speed.py
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable

import numpy as np
from ruckig import InputParameter, Ruckig, Trajectory

from gplrt.controller.services import Controller
from gplrt.geometry.location import Location
from gplrt.motion.move import Move
from gplrt.motion.profile import Profile
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation

#: Calls per timed block, and alternating blocks per side.
BLOCK = 50
ROUNDS = 40
#: Runs of the pick-and-place program; the fastest is reported.
BEST_OF = 5


def _bare(joint_pairs: list[tuple[list[float], list[float]]], lim: tuple[list[float], ...]) -> Callable[[int], None]:
    """A block of bare Ruckig calls: goal ``i`` from its start, with Move.Loc's own limits
    (a new Trajectory each time, as Move.Loc makes)."""
    vel, acc, _, jerk = lim
    otg, inp = Ruckig(5), InputParameter(5)
    inp.max_velocity = vel
    inp.max_acceleration = acc
    inp.min_acceleration = [-a for a in acc]
    inp.max_jerk = jerk

    def block(i0: int) -> None:
        for q0, q1 in joint_pairs[i0:i0 + BLOCK]:
            inp.current_position = q0
            inp.target_position = q1
            otg.calculate(inp, Trajectory(5))

    return block


def _bare_scalar(inputs: list[tuple[float, float, float, float]]) -> Callable[[int], None]:
    """A block of bare 1-axis Ruckig calls: the path parameter 0 -> 1 with the limits (u̇, ü accel,
    ü decel, jerk) Move.Loc's straight plan of goal ``i`` used."""
    otg, inp = Ruckig(1), InputParameter(1)
    inp.current_position, inp.target_position = [0.0], [1.0]

    def block(i0: int) -> None:
        for v, acc, dec, jerk in inputs[i0:i0 + BLOCK]:
            inp.max_velocity = [v]
            inp.max_acceleration = [acc]
            inp.min_acceleration = [-dec]
            inp.max_jerk = [jerk]
            otg.calculate(inp, Trajectory(1))

    return block


def plan_costs() -> dict[str, float]:
    """Seconds per call of each side (see ``main`` for what each is).

    Every Move.Loc plans from rest at the previous call's goal, as a program's motions do: the
    queue is emptied between calls (the previous motion "has ended") and the robot rests at the
    joints that motion was planned to, so that only planning is timed."""
    sim = Simulation(capture=True)
    result: dict[str, float] = {}

    def main() -> None:
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home()
        joint, straight = Profile(), Profile()
        straight.Straight = True
        robot = sim.robots[1]
        queue = robot.queue
        rng = np.random.default_rng(2)
        n = BLOCK * ROUNDS
        qs = rng.uniform([1.5, -80, 20, -300, 70], [1100, 80, 340, 300, 130], size=(n + 1, 5))
        joint_goals = [Location.from_angles(q) for q in qs]
        cart_goals = []
        for q in qs:  # the same goals as Cartesian Locations, with the arm configuration they have
            g = Location.from_matrix(robot.forward(q))
            g.Config = robot.model.config_of(q.tolist())
            cart_goals.append(g)
        pairs = [(qs[i].tolist(), qs[i + 1].tolist()) for i in range(n)]
        base = Location()
        base.XYZ(400.0, 0.0, 300.0, 0.0, 90.0, 180.0)
        line_goals = []
        for dx, dy, dz in rng.uniform([-60, -60, -100], [60, 60, 100], size=(n + 1, 3)):
            g = base.Clone()
            g.XYZ(400.0 + dx, dy, 300.0 + dz, 0.0, 90.0, 180.0)
            line_goals.append(g)
        bare = _bare(pairs, robot.limits.joint_limits(joint, 100.0).lists)

        def from_previous_goal() -> None:
            """The previous motion has ended: the robot rests where it was planned to."""
            last = queue.last
            queue.history.clear()
            queue._starts.clear()
            queue._run_index = 0
            if last is not None:
                queue.rest = last.q_end

        def rest_at(goal: Location) -> None:
            """The robot at rest on a Cartesian ``goal`` a motion took it to."""
            from_previous_goal()
            queue.rest = np.array(robot.model.inverse(goal.matrix(), 0, queue.rest.tolist()))
            robot.remember_pose(queue.rest, goal.total_pose())

        def moves(goals: list[Location], prof: Profile) -> Callable[[int], None]:
            def block(i0: int) -> None:
                for i in range(i0, i0 + BLOCK):
                    from_previous_goal()
                    Move.Loc(goals[i + 1], prof)
            return block

        # the straight plans' own Ruckig inputs, recorded in a pass of the same moves
        import gplrt.motion.robot as robot_module

        recorded: list[tuple[float, float, float, float]] = []
        plan_scalar = robot_module.plan_scalar

        def record(s0: float, v0: float, a0: float, s1: float, v: float, acc: float, dec: float, jerk: float):  # type: ignore[no-untyped-def]
            recorded.append((v, acc, dec, jerk))
            return plan_scalar(s0, v0, a0, s1, v, acc, dec, jerk)

        robot_module.plan_scalar = record
        try:
            rest_at(line_goals[0])
            for i in range(n):
                from_previous_goal()
                Move.Loc(line_goals[i + 1], straight)
        finally:
            robot_module.plan_scalar = plan_scalar
        assert len(recorded) == n
        bare1 = _bare_scalar(recorded)

        def executed(i0: int) -> None:
            for i in range(i0, i0 + BLOCK):
                from_previous_goal()
                Move.Loc(line_goals[i + 1], straight)
                queue.advance(queue.end_time)  # every cycle to the end, as WaitForEOM runs them
                if queue.fault is not None:
                    raise SystemExit(f"benchmark line {i} stopped: {queue.fault}")

        sides = {"bare": bare, "joint": moves(joint_goals, joint), "joint_cart": moves(cart_goals, joint),
                 "bare1": bare1, "line": moves(line_goals, straight), "line_run": executed}
        for _ in range(2):  # the first pass warms up; only the second is kept
            best = dict.fromkeys(sides, float("inf"))
            for r in range(ROUNDS):
                for name, side in sides.items():
                    if name in ("line", "line_run"):
                        rest_at(line_goals[r * BLOCK])  # each line from the previous line's goal
                    t = time.perf_counter()
                    side(r * BLOCK)
                    best[name] = min(best[name], (time.perf_counter() - t) / BLOCK)
        result.update(best)

    sim.run_main(main)
    if sim.console.log_text:
        raise SystemExit(sim.console.log_text)
    return result


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
    c = plan_costs()
    bare = c["bare"]
    print(f"bare Ruckig.calculate (5 axes)          {bare * 1e6:8.1f} us")
    for key, label in (("joint", "Move.Loc joint, Angles goal"), ("joint_cart", "Move.Loc joint, Cartesian goal (IK)"),
                       ("line", "Move.Loc straight, Cartesian goal")):
        print(f"{label:<40}{c[key] * 1e6:8.1f} us   ratio {c[key] / bare:5.2f}x   (target <= 3x)")
    print(f"  for reference: bare Ruckig (1 axis)   {c['bare1'] * 1e6:8.1f} us   (the straight plans' own inputs; "
          f"straight = {c['line'] / c['bare1']:.1f}x)")
    print(f"  a straight line executed to its end   {c['line_run'] * 1e6:8.1f} us   (its cycles' IK, run as the "
          f"motion is read or WaitForEOM waits: not planning)")
    virtual_time_factor(20)  # warm-up
    sim_s, wall, factor = max((virtual_time_factor(200) for _ in range(BEST_OF)), key=lambda r: r[2])
    print(f"200-move pick-and-place: {sim_s:.2f} simulated s in {wall:.3f} wall s = {factor:,.0f}x   (target >= 1,000x)")
    return 0


if __name__ == "__main__":
    sys.exit(main())

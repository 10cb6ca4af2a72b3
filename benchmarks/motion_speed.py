"""Motion benchmark: what a Move costs against its floor, and the virtual-time factor of a cell.

Every figure is measured in this one run, side by side (``_sidebyside``): the two sides of a
ratio run in turns, each sample a block of ``--block`` calls on the same goals, and what is
printed is the median of ``--runs`` samples with their spread, and the median of the per-turn
ratios with theirs.  Each ``Move.Loc`` is planned from rest at the previous call's goal, as a
program's motions are.

1. Planning, against its floor (issue 14, item 2):

   * joint ``Move.Loc`` to an Angles Location, target <= 2x a bare ``Ruckig.calculate`` of the
     robot's 5 axes fed the very input the Move produces (start, target, the Profile's limits);
   * joint ``Move.Loc`` to a Cartesian Location, target <= 2.5x the same bare call plus one IK
     call (``model.inverse_pose`` of the goal, with its Config, seeded by the start);
   * straight ``Move.Loc``, target <= 3x a bare 1-axis ``Ruckig.calculate`` of the path
     parameter fed the limits the Move computed, plus the destination's IK (which stays in the
     Move: an unreachable destination is refused there).

2. Executing a straight line — its 16 ms cycles solved and checked, as ``WaitForEOM`` runs them
   (``MotionQueue.advance`` to the motion's end) — target <= 3x a vectorised numpy evaluation of
   the same cycles: the path parameter of every cycle from the Ruckig profile's polynomials, the
   tool poses of all of them, and their IK in one ``model.inverse_path`` call.

3. The virtual-time factor of ``samples/pick_and_place`` placing 200 parts with its I/O set-up
   (``samples/notebook/cell_io.py``), transpiled and run on the virtual clock: controller
   seconds per wall-clock second (target >= 2,000x, median of ``--cell-runs``) and per CPU
   second of the process.

Every absolute figure is printed twice: as measured, and normalised by the reference workload R
(``_reference``) run in the same turns -- times in µR (millionths of R), the cell's factors in
controller seconds per R -- which is the figure to compare between machines.

Run:  .venv/bin/python benchmarks/motion_speed.py [--runs 21] [--block 50] [--cell-runs 5] [--parts 200]
"""

from __future__ import annotations

import argparse
import gc
import os
import statistics
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
from ruckig import InputParameter, Ruckig, Trajectory

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _reference import HOW_TO_COMPARE, Reference, times_r  # noqa: E402
from _sidebyside import Pair, Samples, collector, side_by_side  # noqa: E402

import gplrt.motion.robot as robot_module  # noqa: E402
from gplrt.controller.services import Controller  # noqa: E402
from gplrt.geometry.location import Location  # noqa: E402
from gplrt.motion.kinematics import RobotModel  # noqa: E402
from gplrt.motion.move import Move  # noqa: E402
from gplrt.motion.path_run import CYCLE, END_GAP  # noqa: E402
from gplrt.motion.planner import Plan  # noqa: E402
from gplrt.motion.profile import Profile  # noqa: E402
from gplrt.motion.queue import PathSegment  # noqa: E402
from gplrt.motion.robot_class import Robot  # noqa: E402
from gplrt.motion.straight import LinePath  # noqa: E402
from gplrt.sim import Simulation  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
PARTS = 200


def _cursor(block: int) -> Callable[[], int]:
    """The first goal index of each successive block (each side of a ratio keeps its own, so
    both sides see the same goals in the same order)."""
    state = [0]

    def nxt() -> int:
        i0 = state[0]
        state[0] += block
        return i0

    return nxt


def _profile_u(plan: Plan, times: np.ndarray) -> np.ndarray:
    """The path parameter at ``times`` from the 1-DOF Ruckig profile's jerk polynomials, in
    numpy (Ruckig's own ``at_time`` formula, phase by phase)."""
    prof = plan.traj.profiles[0][0]
    starts = np.concatenate(((0.0,), np.cumsum(prof.t)))
    k = np.clip(np.searchsorted(starts, times, side="right") - 1, 0, 6)
    dt = times - starts[k]
    p, v, a, j = (np.asarray(x)[k] for x in (prof.p[:7], prof.v[:7], prof.a[:7], prof.j))
    return p + dt * (v + dt * (a / 2.0 + dt * j / 6.0))


def _numpy_cycles(plan: Plan, path: LinePath, q0: np.ndarray, model: RobotModel) -> np.ndarray:
    """Every cycle of one line at once: u(t), the poses (lerp and Rodrigues slerp), the IK."""
    end = plan.duration
    times = np.arange(1, int(end / CYCLE) + 1) * CYCLE
    times = np.append(times[times < end - END_GAP], end)
    us = np.clip(_profile_u(plan, times), 0.0, 1.0)
    T0, T1 = path.T0, path.T1
    R0 = T0[:3, :3]
    w = path.slerp.w  # log3(R0ᵀ R1), computed once per line as the runtime does
    theta = float(np.linalg.norm(w))
    T = np.zeros((len(us), 4, 4))
    T[:, 3, 3] = 1.0
    if theta > 0.0:
        k = w / theta
        K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
        a = theta * us
        T[:, :3, :3] = R0 @ (np.eye(3) + np.sin(a)[:, None, None] * K + (1.0 - np.cos(a))[:, None, None] * (K @ K))
    else:
        T[:, :3, :3] = R0
    T[:, :3, 3] = T0[:3, 3] + (T1[:3, 3] - T0[:3, 3]) * us[:, None]
    q = model.inverse_path(T, np.broadcast_to(q0, (len(us), len(q0))))
    if q is None:
        raise SystemExit("the vectorised IK refused a benchmark line")
    return q


def motion_pairs(runs: int, block: int, ref: Reference) -> dict[str, Pair]:
    """The (Move, floor) pairs of sections 1 and 2 of the module docstring, R run in every turn."""
    sim = Simulation(capture=True)
    pairs: dict[str, Pair] = {}

    def main() -> None:
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home()
        joint, straight = Profile(), Profile()
        straight.Straight = True
        robot = sim.robots[1]
        model = robot.model
        queue = robot.queue
        rng = np.random.default_rng(2)
        n = block * (runs + 1)  # one untimed warm-up sample per side
        qs = rng.uniform([1.5, -80, 20, -300, 70], [1100, 80, 340, 300, 130], size=(n + 1, 5))
        joint_goals = [Location.from_angles(q) for q in qs]
        cart_goals = []
        for q in qs:  # the same goals as Cartesian Locations, with the arm configuration they have
            g = Location.from_matrix(robot.forward(q))
            g.Config = model.config_of(q.tolist())
            cart_goals.append(g)
        line_goals = []
        for dx, dy, dz in rng.uniform([-60, -60, -100], [60, 60, 100], size=(n + 1, 3)):
            g = Location()
            g.XYZ(400.0 + dx, dy, 300.0 + dz, 0.0, 90.0, 180.0)
            line_goals.append(g)

        def from_previous_goal() -> None:
            """The previous motion has ended: the robot rests where it was planned to."""
            last = queue.last
            queue.history.clear()
            queue._starts.clear()
            queue._run_index = 0
            queue.paths_pending = False
            if last is not None:
                queue.rest = last.q_end

        def rest_at(goal: Location) -> None:
            """The robot at rest on a Cartesian ``goal`` a motion took it to."""
            from_previous_goal()
            queue.rest = np.array(model.inverse(goal.matrix(), 0, queue.rest.tolist()))
            robot.remember_pose(queue.rest, goal.total_pose())

        def moves(goals: list[Location], prof: Profile, lines: bool = False) -> Callable[[], None]:
            at = _cursor(block)

            def run() -> None:
                i0 = at()
                if lines:
                    rest_at(goals[i0])  # each line from the previous line's goal
                for i in range(i0, i0 + block):
                    from_previous_goal()
                    Move.Loc(goals[i + 1], prof)

            return run

        # -- joint moves: bare Ruckig with Move.Loc's own input (plus the goal's IK) --------------
        vel, acc, _, jerk = robot.limits.joint_limits(joint, 100.0).lists
        starts = [q.tolist() for q in qs]
        poses = [g.total_pose() for g in cart_goals]
        configs = [int(g.Config) for g in cart_goals]

        def bare_joint(with_ik: bool) -> Callable[[], None]:
            otg, inp = Ruckig(5), InputParameter(5)
            inp.max_velocity = vel
            inp.max_acceleration = acc
            inp.min_acceleration = [-a for a in acc]
            inp.max_jerk = jerk
            inverse_pose = model.inverse_pose
            at = _cursor(block)

            def run() -> None:
                i0 = at()
                for i in range(i0, i0 + block):
                    q0 = starts[i]
                    q1 = inverse_pose(poses[i + 1], configs[i + 1], q0) if with_ik else starts[i + 1]
                    inp.current_position = q0
                    inp.target_position = q1
                    otg.calculate(inp, Trajectory(5))

            return run

        pairs["joint"] = side_by_side(moves(joint_goals, joint), bare_joint(False), runs, reference=ref)
        pairs["joint_cart"] = side_by_side(moves(cart_goals, joint), bare_joint(True), runs, reference=ref)

        # -- straight lines: the plans' own 1-DOF limits and start joints, from an untimed pass -----
        recorded: list[tuple[float, float, float, float]] = []
        plan_scalar = robot_module.plan_scalar

        def record(s0: float, v0: float, a0: float, s1: float, v: float, a: float, d: float, j: float) -> Plan:
            recorded.append((v, a, d, j))
            return plan_scalar(s0, v0, a0, s1, v, a, d, j)

        lines: list[tuple[Plan, LinePath, np.ndarray]] = []
        robot_module.plan_scalar = record  # type: ignore[assignment]
        try:
            rest_at(line_goals[0])
            for i in range(n):
                from_previous_goal()
                Move.Loc(line_goals[i + 1], straight)
                seg = queue.last
                assert isinstance(seg, PathSegment) and seg.plan is not None and seg.path_joints is not None
                path = seg.path_joints.path
                assert isinstance(path, LinePath)
                lines.append((seg.plan, path, seg.q_start))
        finally:
            robot_module.plan_scalar = plan_scalar
        line_poses = [g.total_pose() for g in line_goals]

        def bare_line() -> Callable[[], None]:
            otg, inp = Ruckig(1), InputParameter(1)
            inp.current_position, inp.target_position = [0.0], [1.0]
            inverse_pose = model.inverse_pose
            at = _cursor(block)

            def run() -> None:
                i0 = at()
                for i in range(i0, i0 + block):
                    inverse_pose(line_poses[i + 1], 0, lines[i][2].tolist())
                    v, a, d, j = recorded[i]
                    inp.max_velocity = [v]
                    inp.max_acceleration = [a]
                    inp.min_acceleration = [-d]
                    inp.max_jerk = [j]
                    otg.calculate(inp, Trajectory(1))

            return run

        pairs["line"] = side_by_side(moves(line_goals, straight, lines=True), bare_line(), runs, reference=ref)

        # -- executing the lines: the cycles as WaitForEOM runs them, against one numpy pass -------
        def executed(i0: int) -> float:
            """Seconds the cycles of lines ``i0 …`` took (their Move.Loc calls are not counted)."""
            rest_at(line_goals[i0])
            spent = 0.0
            for i in range(i0, i0 + block):
                from_previous_goal()
                Move.Loc(line_goals[i + 1], straight)
                t = time.perf_counter()
                queue.advance(queue.end_time)
                spent += time.perf_counter() - t
                if queue.fault is not None:
                    raise SystemExit(f"benchmark line {i} stopped: {queue.fault}")
            return spent

        def vectorised(i0: int) -> float:
            t = time.perf_counter()
            for i in range(i0, i0 + block):
                plan, path, q0 = lines[i]
                _numpy_cycles(plan, path, q0, model)
            return time.perf_counter() - t

        ta: list[float] = []
        tb: list[float] = []
        with collector(True):
            for r in range(runs + 1):  # in turns, the first (warm-up) pair dropped
                gc.collect()
                a = executed(r * block)
                gc.collect()
                b = vectorised(r * block)
                ref.run(record=r > 0, match=a + b)
                if r:
                    ta.append(a)
                    tb.append(b)
        pairs["line_run"] = Pair(Samples(ta), Samples(tb), Samples(ref.wall[-runs:]))

    sim.run_main(main)
    if sim.console.log_text:
        raise SystemExit(sim.console.log_text)
    return pairs


def _cell_project(folder: Path, parts: int) -> Path:
    """``samples/pick_and_place`` copied to ``folder`` with ``parts`` parts to place."""
    import shutil

    dest = folder / "pick_and_place"
    shutil.copytree(ROOT / "samples" / "pick_and_place", dest)
    cell = dest / "Cell.gpl"
    text = cell.read_text(encoding="utf-8")
    changed = text.replace("PARTS_TO_PLACE As Integer = 8", f"PARTS_TO_PLACE As Integer = {parts}")
    if changed == text:
        raise SystemExit("samples/pick_and_place/Cell.gpl: PARTS_TO_PLACE not found")
    cell.write_text(changed, encoding="utf-8")
    return dest


def cell_factors(runs: int, ref: Reference, parts: int = PARTS) -> tuple[list[float], list[float], float, str]:
    """(wall factors, CPU factors, controller seconds, last console line) of ``runs`` runs of
    the cell placing ``parts`` parts, after one untimed run; R runs after each (``ref``)."""
    from gpl2py.diagnostics import DiagnosticSink
    from gpl2py.run import build, import_built

    sys.path.insert(0, str(ROOT / "samples" / "notebook"))
    import cell_io

    with tempfile.TemporaryDirectory() as tmp:
        project = _cell_project(Path(tmp), parts)
        sink = DiagnosticSink()
        built = build(project, sink, cache_dir=Path(tmp) / "cache")
        if built is None:
            raise SystemExit("the pick-and-place sample did not translate")
        package = import_built(built)

    def once() -> tuple[float, float, float, str]:
        sim = Simulation(capture=True)
        cell_io.wire(sim.io)
        gc.collect()
        wall, cpu = time.perf_counter(), time.process_time()
        package.main(sim)
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
        lines = sim.console.output.strip().splitlines()
        sim.close(0.0)
        return sim.now(), wall, cpu, lines[-1] if lines else ""

    once()
    ref.run(record=False)
    walls: list[float] = []
    cpus: list[float] = []
    seconds, last = 0.0, ""
    for _ in range(runs):
        seconds, wall, cpu, last = once()
        ref.run(match=wall)
        walls.append(seconds / wall)
        cpus.append(seconds / cpu)
    return walls, cpus, seconds, last


def _row(label: str, pair: Pair, floor: str, target: float) -> str:
    ratio = pair.ratio
    verdict = "met" if ratio <= target else "NOT met"
    return (f"{label:<34}{pair.a.text(1e-6, 'us')}  {pair.a_in_r.text(1e-6, 'µR')}\n"
            f"{'  floor: ' + floor:<34}{pair.b.text(1e-6, 'us')}  {pair.b_in_r.text(1e-6, 'µR')}\n"
            f"{'  ratio':<34}{pair.ratio_text()}   target <= {target:g}x: {verdict}")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=21, help="samples per side (>= 5)")
    ap.add_argument("--block", type=int, default=50, help="calls per sample")
    ap.add_argument("--cell-runs", type=int, default=5, help="runs of the 200-part cell (>= 5)")
    ap.add_argument("--parts", type=int, default=PARTS, help=f"parts the cell places (default {PARTS})")
    args = ap.parse_args(argv)
    per = args.block
    ref = Reference()
    pairs = motion_pairs(args.runs, args.block, ref)
    for p in pairs.values():  # per call (per line), not per block
        p.a.values[:] = [v / per for v in p.a.values]
        p.b.values[:] = [v / per for v in p.b.values]
    print(_row("Move.Loc joint, Angles goal", pairs["joint"], "Ruckig.calculate, 5 axes", 2.0))
    print(_row("Move.Loc joint, Cartesian goal", pairs["joint_cart"], "Ruckig 5 axes + IK", 2.5))
    print(_row("Move.Loc straight line", pairs["line"], "Ruckig 1 axis + IK", 3.0))
    print(_row("straight line executed", pairs["line_run"], "numpy, all cycles at once", 3.0))
    load = os.getloadavg()[0]
    walls, cpus, seconds, last = cell_factors(args.cell_runs, ref, args.parts)
    load = max(load, os.getloadavg()[0])
    wall = statistics.median(walls)
    n = args.cell_runs
    wall_r = Samples(times_r(walls, ref.wall[-n:]))
    cpu_r = Samples(times_r(cpus, ref.cpu[-n:]))
    print(f"pick-and-place, {args.parts} parts ({seconds:.1f} controller s; {last!r}):")
    print(f"  wall-clock factor {wall:9,.0f}x (spread {min(walls):,.0f}-{max(walls):,.0f}, {len(walls)} runs)"
          f"   target >= 2,000x: {'met' if wall >= 2000 else 'NOT met'}")
    print(f"  CPU-time factor   {statistics.median(cpus):9,.0f}x (spread {min(cpus):,.0f}-{max(cpus):,.0f})"
          f"   (load average {load:.1f} on {os.cpu_count()} CPUs: the wall clock is shared, the CPU time is not)")
    print(f"  normalised: wall {wall_r.text(1, 'controller s per R (wall)')}, "
          f"CPU {cpu_r.text(1, 'controller s per R (CPU)')}")
    print(ref.line())
    print(HOW_TO_COMPARE)
    return 0


if __name__ == "__main__":
    sys.exit(main())

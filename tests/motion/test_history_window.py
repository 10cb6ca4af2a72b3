"""The motion history and the signal trace keep a bounded window (issue 14 item 4).

A long run must not grow without limit: each robot keeps its last ``Simulation(history=N)``
motions and the I/O map its last ``signal_history`` changes.  What reads them (the trace, plots,
``Robot.Where``, ``TrajState``, the motions still to run) keeps working on the window, and the
trace says what it no longer holds.
"""

from __future__ import annotations

import gc
import tracemalloc
import weakref

import numpy as np
import pytest

from gplrt.controller.services import Controller
from gplrt.controller.signals import IoMap, Signal
from gplrt.geometry.location import Location
from gplrt.motion.move import Move
from gplrt.motion.profile import Profile
from gplrt.motion.queue import DEFAULT_HISTORY, PathSegment
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation

A = (300.0, 10.0, 90.0, -100.0, 100.0)
B = (250.0, 0.0, 100.0, -90.0, 100.0)


def _moves(count: int, *, line_every: int = 4, wait: bool = True, blend: bool = False) -> None:
    """On the calling GPL thread: ``count`` motions, joint moves between two Angles and, every
    ``line_every``-th, a straight line out and back (the costly kind: its cycles are kept)."""
    Robot.Attached = 1
    Controller.PowerEnabled = True
    Robot.Home()
    joint, line = Profile(), Profile()
    line.Straight = True
    if blend:
        line.InRange = -5.0
    Move.Loc(Location.from_angles(A), joint)
    Move.WaitForEOM()
    start = Robot.Where()
    away = start.Clone()
    away.XYZ(start.X + 100.0, start.Y - 50.0, start.Z - 30.0, start.Yaw, 90.0, 180.0)
    lines = 0
    for i in range(count):
        if line_every and i % line_every == line_every - 1:
            Move.Loc(away if lines % 2 == 0 else start, line)
            lines += 1
        else:
            Move.Loc(Location.from_angles(A if i % 2 else B), joint)
        if wait:
            Move.WaitForEOM()
    Move.WaitForEOM()


def _peak_bytes(count: int) -> int:
    """tracemalloc's peak over a run of ``count`` motions on a default Simulation."""
    sim = Simulation(capture=True)
    gc.collect()
    tracemalloc.start()
    try:
        sim.run_main(lambda: _moves(count))
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert not sim.console.log_text, sim.console.log_text
    queue = sim.robots[1].queue
    assert len(queue.history) <= queue.trim_at and queue.dropped + len(queue.history) == count + 1
    sim.close(0.0)
    return peak


def test_ten_thousand_motions_use_at_most_10_mb_more_than_a_thousand() -> None:
    # Without the window the history grew 3.7 KB per joint move and 27 KB per straight line:
    # these 9,000 more motions (a quarter of them lines) took 39 MB more (measured before the window).
    small = _peak_bytes(1_000)
    large = _peak_bytes(10_000)
    assert large - small <= 10 * 2**20, f"{(large - small) / 2**20:.1f} MB more for 9,000 more motions"


def _run(sim: Simulation, count: int, **kw: object) -> None:
    sim.run_main(lambda: _moves(count, **kw))  # type: ignore[arg-type]
    assert not sim.console.log_text, sim.console.log_text


def test_the_window_keeps_the_last_motions_and_the_robot_carries_on() -> None:
    sim = Simulation(capture=True, history=20)
    _run(sim, 200)
    queue = sim.robots[1].queue
    assert 20 <= len(queue.history) <= 20 + 16
    assert queue.dropped + len(queue.history) == 200 + 1  # (+ the first move to A)
    assert queue.window_start == queue.history[0].t0 > 0.0
    with sim.as_gpl_thread():
        Robot.Attached = 1
        assert Robot.WhereAngles().axis_values() == pytest.approx(queue.history[-1].q_end.tolist(), abs=1e-9)
        assert Robot.TrajState() == 1  # idle
        # the robot still moves, from where it is
        Move.Loc(Location.from_angles(B), Profile())
        Move.WaitForEOM()
        assert Robot.WhereAngles().axis_values() == pytest.approx(B, abs=1e-9)


def test_the_trace_starts_at_the_window_and_says_what_was_dropped() -> None:
    sim = Simulation(capture=True, history=20)
    _run(sim, 100)
    queue = sim.robots[1].queue
    tr = sim.trace(1, 0.05)
    assert tr.dropped == queue.dropped > 0 and tr.window == 20 and not tr.complete
    assert tr.times[0] == queue.window_start
    assert tr.joints[-1] == pytest.approx(queue.history[-1].q_end, abs=1e-9)
    assert f"{queue.dropped} of them" in tr.note and "history=None" in tr.note
    assert tr.note in repr(tr)


def test_history_none_keeps_every_motion() -> None:
    sim = Simulation(capture=True, history=None)
    _run(sim, 120)
    queue = sim.robots[1].queue
    assert queue.dropped == 0 and len(queue.history) == 121
    tr = sim.trace(1, 0.05)
    assert tr.complete and tr.note == "" and tr.times[0] == queue.history[0].t0
    assert "dropped" not in repr(tr)


def test_the_window_can_be_changed_on_a_running_session() -> None:
    sim = Simulation(capture=True, history=None)
    _run(sim, 60)
    sim.history = 10
    with sim.as_gpl_thread():
        Robot.Attached = 1
        Move.Loc(Location.from_angles(A), Profile())
        Move.Loc(Location.from_angles(B), Profile())
        Move.WaitForEOM()
    # trimming happens as motions are queued, a batch at a time
    queue = sim.robots[1].queue
    assert queue.window == 10 and queue.dropped > 0 and len(queue.history) <= 10 + 16


@pytest.mark.parametrize("bad", [0, -5, 2.5, "100", True])
def test_a_window_that_is_not_a_whole_number_is_refused(bad: object) -> None:
    with pytest.raises(ValueError, match="history window"):
        Simulation(history=bad)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="history window"):
        Simulation(signal_history=bad)  # type: ignore[arg-type]
    sim = Simulation()
    with pytest.raises(ValueError, match="history window"):
        sim.history = bad  # type: ignore[assignment]
    assert sim.history == DEFAULT_HISTORY


def test_a_motion_still_queued_is_never_dropped() -> None:
    """With a window smaller than the motion queue, the motions still to run stay (and run)."""
    sim = Simulation(capture=True, history=1)
    _run(sim, 40, wait=False)
    queue = sim.robots[1].queue
    assert queue.dropped > 0
    with sim.as_gpl_thread():
        Robot.Attached = 1
        assert Robot.WhereAngles().axis_values() == pytest.approx(queue.history[-1].q_end.tolist(), abs=1e-9)


def test_blended_lines_do_not_keep_the_dropped_ones_alive() -> None:
    """A blended line links to the motion it blends out of: a chain of them must not keep every
    dropped line (and its solved cycles) alive."""
    sim = Simulation(capture=True, history=8)
    refs: list[weakref.ref[PathSegment]] = []

    def main() -> None:
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home()
        Move.Loc(Location.from_angles(A), Profile())
        Move.WaitForEOM()
        start = Robot.Where()
        line = Profile()
        line.Straight = True
        line.InRange = -5.0
        for i in range(80):
            goal = start.Clone()
            goal.XYZ(start.X + (60.0 if i % 2 == 0 else 0.0), start.Y + (i % 4) * 10.0, start.Z, start.Yaw, 90.0, 180.0)
            Move.Loc(goal, line)
            last = sim.robots[1].queue.last
            if isinstance(last, PathSegment):
                refs.append(weakref.ref(last))
        Move.WaitForEOM()

    sim.run_main(main)
    assert not sim.console.log_text, sim.console.log_text
    assert any(getattr(sim.robots[1].queue.history[-1], "prev", None) is not None for _ in [0])  # they did blend
    gc.collect()
    alive = sum(r() is not None for r in refs)
    assert alive <= 8 + 16 + 2, f"{alive} of {len(refs)} lines still alive"


def test_the_signal_trace_keeps_its_window() -> None:
    sim = Simulation(capture=True, signal_history=10)
    with sim.as_gpl_thread():
        for i in range(100):
            Signal.set_DIO(1, i % 2 == 0)
    io = sim.io
    assert 10 <= len(io.trace) <= 10 + 16
    assert io.trace_dropped + len(io.trace) == 100
    assert [c.value for c in io.output_trace()][-2:] == [True, False]  # the last ones are kept, in order
    everything = IoMap(trace_window=None)
    sim2 = Simulation(capture=True, io=everything)
    assert sim2.io.trace_window is None  # a given IoMap keeps its own window
    with sim2.as_gpl_thread():
        for i in range(100):
            Signal.set_DIO(1, i % 2 == 0)
    assert len(everything.trace) == 100 and everything.trace_dropped == 0


def test_the_plot_of_a_window_says_earlier_motions_were_dropped() -> None:
    pytest.importorskip("matplotlib")
    from gplrt.motion.plot import plot_joints, plot_path_xy

    sim = Simulation(capture=True, history=20)
    _run(sim, 60)
    tr = sim.trace(1, 0.05)
    for plot in (plot_joints, plot_path_xy):
        fig = plot(tr)
        texts = [t.get_text() for ax in fig.axes for t in ax.texts]
        assert any("earlier motions dropped" in t and str(tr.dropped) in t for t in texts), texts
    complete = Simulation(capture=True, history=None)
    _run(complete, 10)
    fig = plot_joints(complete.trace(1, 0.05))
    assert not [t for ax in fig.axes for t in ax.texts]
    assert np.isfinite(tr.xyz).all()

"""The sampled motion of a robot: times, joints and tool positions as numpy arrays.

``trace(session, robot)`` samples every segment the robot was ever given, from the start of the
first to the end of the last, every ``dt`` seconds (default: the trajectory-generator period,
DataID 600, 4 ms on a PF400), and always includes the exact end, so the last row is the final
target.  Robots without kinematics give ``xyz`` filled with NaN.

A trace is what the robot has done: taken while motions still run, it ends at the controller's
present time.  Reading further would run a straight line's cycles ahead of the clock, and a stop
found there would reach the program before it happened (path_run).

A trace covers what the robot's history still holds: the last ``Simulation(history=N)`` motions
(``gplrt.motion.queue``).  When older ones were dropped the trace starts at the first motion kept,
and says so: ``dropped`` counts the motions before it and ``note`` is a sentence for a plot or a
report (``plot.py`` writes it on the figure).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from gplrt.session import Session

DEFAULT_DT = 0.004


@dataclass(frozen=True, repr=False)
class Trace:
    """``times`` (N,), ``joints`` (N, axes) in mm/deg, ``xyz`` (N, 3) tool-tip mm, ``names`` of the
    axes; ``dropped``: the motions before ``times[0]`` the history no longer holds, of a history
    that keeps ``window`` motions (None: every one)."""

    times: NDArray[np.float64]
    joints: NDArray[np.float64]
    xyz: NDArray[np.float64]
    names: tuple[str, ...]
    dropped: int = 0
    window: int | None = None

    def __iter__(self) -> Iterator[NDArray[np.float64]]:
        """``times, joints, xyz = sim.trace(1)``."""
        return iter((self.times, self.joints, self.xyz))

    @property
    def complete(self) -> bool:
        """True when the trace starts at the robot's first motion (nothing was dropped)."""
        return self.dropped == 0

    @property
    def note(self) -> str:
        """"" for a complete trace, else what is missing and how to keep it."""
        if not self.dropped:
            return ""
        return (f"motions before t = {self.times[0]:.3f} s dropped ({self.dropped} of them; the history keeps "
                f"the last {self.window}): Simulation(history=None) or gpl2py run --history all keeps every one")

    def __repr__(self) -> str:
        span = f"t = {self.times[0]:.3f}-{self.times[-1]:.3f} s" if len(self.times) else "empty"
        text = f"<Trace {len(self.times)} samples of {', '.join(self.names)}, {span}>"
        return f"{text[:-1]}; {self.note}>" if self.dropped else text


def _default_dt(sim: Session, robot_number: int) -> float:
    pdb = sim.pdb
    if pdb is not None and pdb.has(600, 1):
        return float(pdb.get_num(600, 1))
    return DEFAULT_DT


def trace(sim: Session, robot: int = 1, dt: float | None = None) -> Trace:
    """The sampled motion of robot ``robot`` of ``sim`` so far (module docstring)."""
    state = sim.robot(int(robot))
    step = float(dt) if dt is not None else _default_dt(sim, robot)
    hist = state.queue.history
    n = state.axis_count
    if not hist:
        q = state.queue.rest[None, :].copy()
        times = np.array([float(sim.scheduler.clock.now())])
    else:
        now = float(sim.scheduler.clock.now())
        t0, t1 = hist[0].t0, min(max(seg.end for seg in hist), now)
        if t1 < t0:  # nothing has started yet
            t0 = t1 = now
        count = int(np.floor((t1 - t0) / step)) + 1
        times = t0 + step * np.arange(count)
        if times[-1] < t1:
            times = np.append(times, t1)
        q = np.empty((len(times), n))
        with state.lock:  # (reading runs the path cycles: the robot's own thread may be queueing)
            queue = state.queue
            for i, t in enumerate(times):
                q[i] = queue.joints_at(float(t))
    xyz = np.full((len(times), 3), np.nan)
    if state.model.has_kinematics:
        for i in range(len(times)):
            xyz[i] = state.forward(q[i])[:3, 3]
    queue = state.queue
    return Trace(times, q, xyz, tuple(state.model.joint_names), queue.dropped, queue.window)

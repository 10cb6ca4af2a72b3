"""The motion queue: planned segments with absolute start times on the controller clock.

There is no servo thread: the robot's state at time ``t`` is read off the segment that covers
``t`` (``MotionQueue.state_at``).  A segment covers ``[t0, end)`` where ``end`` is its planned
end, or the time it was cut at (blended into the next motion, or stopped by RapidDecel / power
loss), plus its settling time.

``history`` keeps the segments for the trace, in a bounded window: the last ``window`` motions
(``Simulation(history=N)``, default :data:`DEFAULT_HISTORY`; None keeps every one).  Older,
finished motions are dropped in batches as new ones are queued (``MotionQueue.trim``), so a
robot's memory does not grow with the length of a run; ``dropped`` counts them and
``window_start`` is the time the history now starts at.  A motion still to run, or whose path
cycles have not all run, is never dropped.

Segment kinds:

* :class:`JointSegment` — a synchronised Ruckig trajectory of all axes;
* :class:`PathSegment` — a 1-D Ruckig trajectory of the path parameter of a line/arc, mapped to
  joints by IK cycle by cycle as far as the state is read (``path_run.PathRun``; velocities and
  accelerations by finite differences of ``q(u)``).  ``MotionQueue.advance`` runs those cycles
  up to the time read: an error found on the way stops the robot at the last good cycle, drops
  the rest of the queue and is kept in ``MotionQueue.fault`` for the robot to report;
* :class:`BlendedPathSegment` — a line, arc or circle that starts while the previous motion runs
  out (corner rounding, InRange < 0), the two superimposed in Cartesian space until that motion ends;
* :class:`DwellSegment` — ``Move.Delay``: the robot holds still.
"""

from __future__ import annotations

import bisect
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from gplrt.motion.limits import Vec
from gplrt.motion.planner import Plan
from gplrt.motion.profile import Profile
from gplrt.lang.errors import AXIS_OVER_SPEED, GplException
from gplrt.motion.path_run import PathRun
from gplrt.session import check_window

#: A Profile's values, taken when a motion is queued (cheaper than a Clone on every Move; the
#: same tuple while the Profile is unchanged: ``Profile.values``).
profile_values = Profile.values


def profile_from_values(values: tuple[object, ...]) -> Profile:
    prof = Profile.__new__(Profile)
    for name, value in zip(Profile.FIELDS, values):
        setattr(prof, name, value)
    prof._values = None
    return prof


#: Motions a robot's history keeps by default (``Simulation(history=...)``, ``gpl2py run --history``):
#: about 4 MB for joint moves, 27 MB for straight lines (measured: 3.7 KB and 27 KB each).
DEFAULT_HISTORY = 1000

_H = 1e-5  # path-parameter step for q'(u), q''(u)
#: The virtual clock counts whole nanoseconds: a time within this of a segment's end *is* its end,
#: so that ``WaitForEOM`` followed by ``Where`` reads the exact target.
CLOCK_RESOLUTION = 1e-9


@dataclass(eq=False, slots=True, weakref_slot=True)
class Segment:
    """Common part of every queued segment (times in controller seconds).

    Slotted (every subclass too): one is made per ``Move``, and a slotted record is cheaper to
    build and to read (``benchmarks/motion_speed.py``).  A subclass that overrides a method calls
    its base by name (``PathSegment.state(self, t)``): a slotted dataclass has no bare
    ``super()`` before Python 3.14."""

    t0: float
    duration: float
    q_start: Vec
    q_end: Vec
    profile: tuple[object, ...] | None = None  # Profile values when queued (profile_values)
    settle: float = 0.0
    blend: bool = False
    blend_tolerance: float = 0.0
    cut: float | None = None  # absolute time the motion was cut at (blend / stop)
    kind: str = "joint"

    @property
    def motion_end(self) -> float:
        """When this segment's own motion ends (its cut time if it was cut)."""
        return self.cut if self.cut is not None else self.t0 + self.duration

    @property
    def end(self) -> float:
        """End of the segment including settling (the next segment starts here)."""
        return self.motion_end if self.cut is not None else self.t0 + self.duration + self.settle

    @property
    def target(self) -> Vec:
        return self.q_end

    def state(self, t: float) -> tuple[Vec, Vec, Vec]:
        """(joints, joint velocities, joint accelerations) at absolute time ``t``."""
        raise NotImplementedError

    def joints(self, t: float) -> Vec:
        return self.state(t)[0]

    def rates(self, ts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Joint velocities and accelerations (N×n) at the absolute times ``ts`` — exact here;
        path segments give the cheaper chain-rule estimate (``PathJoints.rates``)."""
        states = [self.state(float(t)) for t in ts]
        return np.array([st[1] for st in states]), np.array([st[2] for st in states])


@dataclass(eq=False, slots=True)
class JointSegment(Segment):
    plan: Plan | None = None

    def rates(self, ts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        assert self.plan is not None
        _, v, a = self.plan.sample(np.asarray(ts, dtype=float) - self.t0)
        return v, a

    def state(self, t: float) -> tuple[Vec, Vec, Vec]:
        assert self.plan is not None
        local = t - self.t0
        if local >= self.duration - CLOCK_RESOLUTION:
            z = np.zeros(len(self.q_end))
            return self.q_end.copy(), z, z.copy()
        p, v, a = self.plan.at(local)
        return np.array(p), np.array(v), np.array(a)


@dataclass(eq=False, slots=True)
class PathSegment(Segment):
    """A Cartesian path motion: ``plan`` is the 1-D profile of its path parameter, and
    ``path_joints`` its joints cycle by cycle (``path_run.PathRun``).

    The ``PathRun`` is built the first time the motion's cycles or joints are read (``run_inputs``
    holds what it is built from until then): a straight ``Move.Loc`` queues its motion without it,
    as the controller plans a line's profile when it is queued and solves its joints as it runs."""

    plan: Plan | None = None
    run: PathRun | None = None
    #: (path, Tool/Base kinematics, start joints, extra-axis targets, their mask, destination
    #: joints, hard maximum speeds, accelerations): ``path_joints``'s arguments, until it is built
    run_inputs: tuple[object, ...] | None = None

    @property
    def path_joints(self) -> PathRun | None:
        run = self.run
        if run is None and self.run_inputs is not None:
            path, frames, q0, q_extra, mask, q1, max_speed, max_accel = self.run_inputs  # type: ignore[misc]
            assert self.plan is not None
            run = self.run = PathRun(path, self.plan, frames.ik, frames.ik_between, q0, q_extra, mask, q1,
                                     max_speed, max_accel, frames.ik_path)
            self.run_inputs = None
        return run

    def parameter(self, t: float) -> tuple[float, float, float]:
        assert self.plan is not None
        p, v, a = self.plan.at(t - self.t0)
        return p[0], v[0], a[0]

    def parameters(self, ts: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``parameter(t)`` at every time of ``ts``: (u, u̇, ü) arrays."""
        assert self.plan is not None
        u, ud, udd = self.plan.sample(np.asarray(ts, dtype=float) - self.t0)
        return u[:, 0], ud[:, 0], udd[:, 0]

    def rates(self, ts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        pj = self.path_joints
        assert pj is not None
        return pj.rates(*self.parameters(ts))

    def _stopped(self, t: float, run: PathRun) -> Vec | None:
        """The joints the robot stopped at if a mid-path error stopped it by ``t`` (the cycles
        up to ``t`` are run first)."""
        fault = run.run_to(t - self.t0)
        return fault.q.copy() if fault is not None else None

    def joints(self, t: float) -> Vec:
        pj = self.path_joints  # (a property: read once)
        assert pj is not None
        stopped = self._stopped(t, pj)
        if stopped is not None:
            return stopped
        if t - self.t0 >= self.duration - CLOCK_RESOLUTION:
            return self.q_end.copy()
        return pj.joints(self.parameter(t)[0])

    def state(self, t: float) -> tuple[Vec, Vec, Vec]:
        pj = self.path_joints  # (a property: read once)
        assert pj is not None
        stopped = self._stopped(t + _H, pj)
        if stopped is not None and pj.fault is not None and t - self.t0 >= pj.fault.t:
            z = np.zeros(len(stopped))
            return stopped, z, z.copy()
        if t - self.t0 >= self.duration - CLOCK_RESOLUTION:
            z = np.zeros(len(self.q_end))
            return self.q_end.copy(), z, z.copy()
        u, ud, udd = self.parameter(t)
        lo, hi = max(0.0, u - _H), min(1.0, u + _H)
        mid = min(max(u, lo + 1e-12), hi)
        q_lo, q_mid, q_hi = pj.joints(lo), pj.joints(mid), pj.joints(hi)
        d1 = (q_hi - q_lo) / (hi - lo)
        d2 = (q_hi - 2.0 * q_mid + q_lo) / ((hi - lo) / 2.0) ** 2 if hi - lo > 1.5 * _H else np.zeros_like(d1)
        return pj.joints(u), d1 * ud, d2 * ud * ud + d1 * udd


#: Time step (s) of the central differences that give joint velocity/acceleration in a blend.
_BLEND_DT = 1e-4


@dataclass(eq=False, slots=True)
class BlendedPathSegment(PathSegment):
    """A Cartesian path (line, arc, circle) entered while the previous (blending) motion is
    still running out; below, "the line" stands for any of them.

    The line is planned from rest at the previous motion's target (the *via* pose) and starts at
    the blend time; until the previous motion's own end (``prev_end``) the two are superimposed
    in Cartesian space: position ``p_prev(t) + (p_line(t) − p_via)``, orientation
    ``R_prev(t) · R_viaᵀ · R_line(t)``, and the joints are the IK of that pose (seeded by the
    previous motion's joints, so the arm keeps its branch).  At the blend time the line adds
    nothing (it starts at rest), at ``prev_end`` the previous motion adds nothing (it ends on
    the via at rest): position, velocity and acceleration are continuous, the robot does not stop,
    and the tool never leaves the corner by more than the previous motion's remaining distance to
    the via — ``|InRange|`` when the blend starts as the tool comes within ``|InRange|`` of it.
    """

    prev: Segment | None = None
    prev_end: float = 0.0
    via: np.ndarray | None = None  # 4×4 (mm): the previous target, where the line starts
    forward: Callable[[Vec], np.ndarray] | None = None

    def joints(self, t: float) -> Vec:
        if t >= self.prev_end:
            return PathSegment.joints(self, t)  # (a slotted dataclass: no bare super())
        assert self.prev is not None and self.via is not None and self.forward is not None
        pj = self.path_joints
        assert pj is not None
        q_prev = self.prev.joints(t)
        T_prev = self.forward(q_prev)
        u = self.parameter(t)[0]
        T_line = pj.path.pose(u)
        T = np.eye(4)
        T[:3, :3] = T_prev[:3, :3] @ self.via[:3, :3].T @ T_line[:3, :3]
        T[:3, 3] = T_prev[:3, 3] + T_line[:3, 3] - self.via[:3, 3]
        seed = np.array(q_prev, dtype=float)
        m = pj.extra_mask
        seed[m] += (pj.extra_end[m] - pj.extra_start[m]) * u  # axes the line moves linearly (rail)
        return (pj.ik_between or pj.ik)(T, seed)

    def state(self, t: float) -> tuple[Vec, Vec, Vec]:
        if t - _BLEND_DT >= self.prev_end:
            return PathSegment.state(self, t)
        h = _BLEND_DT
        q_lo, q_mid, q_hi = self.joints(t - h), self.joints(t), self.joints(t + h)
        return q_mid, (q_hi - q_lo) / (2.0 * h), (q_hi - 2.0 * q_mid + q_lo) / (h * h)


@dataclass(eq=False, slots=True)
class DwellSegment(Segment):
    kind: str = "delay"

    def state(self, t: float) -> tuple[Vec, Vec, Vec]:
        z = np.zeros(len(self.q_end))
        return self.q_end.copy(), z, z.copy()


@dataclass
class MotionQueue:
    """Segments in time order; the robot rests at ``rest`` before the first one."""

    rest: Vec
    history: list[Segment] = field(default_factory=list)
    _starts: list[float] = field(default_factory=list)
    #: The error that stopped a path motion mid-way, until the robot reports it.
    fault: GplException | None = None
    #: Index of the first segment whose cycles may not all have run (``advance``).
    _run_index: int = 0
    #: A path segment was queued whose cycles may not all have run: ``advance`` has work (a
    #: queue of joint moves only skips it, on the hot path of Move.Loc).
    paths_pending: bool = False
    #: How many motions ``history`` keeps (None: all; see the module docstring).
    window: int | None = None
    #: The controller clock (``trim`` drops only motions that have ended by now).
    clock: Callable[[], float] | None = None
    #: Motions dropped from the front of ``history`` so far (``trim``).
    dropped: int = 0
    #: ``len(history)`` beyond which appending trims (a batch at a time: see ``trim``).
    trim_at: float = float("inf")

    def __post_init__(self) -> None:
        self.set_window(self.window)

    def set_window(self, window: int | None) -> None:
        """Keep the last ``window`` motions from now on (None: every motion).  The history is
        trimmed a batch of a quarter window at a time, so that dropping costs O(1) per motion."""
        self.window = window = check_window(window, "motions")
        self.trim_at = float("inf") if window is None else window + max(16, window // 4)

    @property
    def window_start(self) -> float:
        """The controller time the kept history starts at (-inf while nothing was dropped)."""
        if not self.dropped:
            return float("-inf")
        return self.history[0].t0 if self.history else float("inf")

    def trim(self) -> None:
        """Drop the oldest motions beyond ``window`` that have ended (by ``clock``) and whose path
        cycles have all run.  The robot rested, before what is kept, where the last dropped motion
        ended (``rest``).  A motion that blends or overlaps out of its predecessor keeps a link to
        it (``prev``); the link of the motion two back from what is kept is cut, so a long chain
        of blended lines cannot keep every dropped line alive."""
        window, history = self.window, self.history
        if window is None or self.clock is None:
            return
        k = len(history) - window
        if self.paths_pending:
            k = min(k, self._run_index)
        now = self.clock() + CLOCK_RESOLUTION
        while k > 0 and history[k - 1].end > now:
            k -= 1
        if k <= 0:
            return
        self.rest = history[k - 1].q_end
        del history[:k]
        del self._starts[:k]
        self._run_index = max(0, self._run_index - k)
        self.dropped += k
        link: Segment | None = history[0] if history else None
        for _ in range(2):
            link = getattr(link, "prev", None)
        if link is not None and getattr(link, "prev", None) is not None:
            link.prev = None  # type: ignore[attr-defined]

    def advance(self, t: float) -> None:
        """Run the path motions' cycles up to ``t``, as the controller has by then: the first
        error found stops the robot at its last good cycle (``cut_at``) and is kept in ``fault``."""
        history = self.history
        i = min(self._run_index, len(history))
        while i < len(history):
            seg = history[i]
            if seg.t0 > t:
                break
            if isinstance(seg, PathSegment) and (run := seg.path_joints) is not None:
                end_local = seg.motion_end - seg.t0
                fault = run.run_to(min(t - seg.t0, end_local))
                if fault is not None:
                    self.cut_at(seg.t0 + fault.t, fault.q)
                    seg.cut, seg.q_end = seg.t0 + fault.t, fault.q.copy()  # (even when not the last)
                    self.fault = fault.error
                    self._run_index = len(history)
                    return
                if run.done < end_local - 1e-12:
                    break
                if run.final is not None and not np.array_equal(run.final, seg.q_end):
                    if seg is history[-1]:
                        seg.q_end = run.final.copy()  # nothing was planned from the other turn yet
                    else:  # the next motion starts a whole turn away: the servo cannot follow
                        err = GplException(AXIS_OVER_SPEED, axis=int(np.flatnonzero(run.final != seg.q_end)[0]) + 1,
                                           detail="the path ends a whole turn away from the next motion's start")
                        q_stop = run.qs[-2].copy()
                        t_stop = seg.t0 + run.ts[-2]
                        self.cut_at(t_stop, q_stop)
                        seg.cut, seg.q_end = t_stop, q_stop
                        self.fault = err
                        self._run_index = len(history)
                        return
            i += 1
        self._run_index = i
        if i >= len(history):
            self.paths_pending = False

    def append(self, seg: Segment) -> None:
        if isinstance(seg, PathSegment):
            self.paths_pending = True
        self.history.append(seg)
        self._starts.append(seg.t0)
        if len(self.history) > self.trim_at:
            self.trim()

    @property
    def last(self) -> Segment | None:
        return self.history[-1] if self.history else None

    @property
    def end_time(self) -> float:
        """When the last queued segment ends (settling included)."""
        last = self.last
        return last.end if last is not None else float("-inf")

    def final_joints(self) -> Vec:
        """Where the robot is when everything queued has run (``Robot.DestAngles``)."""
        last = self.last
        return (last.q_end if last is not None else self.rest).copy()

    def segment_at(self, t: float) -> Segment | None:
        """The segment covering ``t``, or None when the robot is at rest (before/after all)."""
        i = bisect.bisect_right(self._starts, t) - 1
        if i < 0:
            return None
        seg = self.history[i]
        # A segment cut for a blend hands over to its successor, which starts at the cut time.
        # One that ends by itself is over within CLOCK_RESOLUTION of its end: the clock may stop
        # that short of it (WaitForEOM returns there), and the robot is then at rest on q_end.
        end = seg.end
        return seg if t < end - CLOCK_RESOLUTION or (t < end and seg.cut is not None) else None

    def state_at(self, t: float) -> tuple[Vec, Vec, Vec]:
        if self.paths_pending:
            self.advance(t)
        seg = self.segment_at(t)
        if seg is not None:
            return seg.state(t)
        q = self._resting_joints(t)
        z = np.zeros(len(q))
        return q, z, z.copy()

    def joints_at(self, t: float) -> Vec:
        if self.paths_pending:
            self.advance(t)
        seg = self.segment_at(t)
        return seg.joints(t) if seg is not None else self._resting_joints(t)

    def _resting_joints(self, t: float) -> Vec:
        i = bisect.bisect_right(self._starts, t) - 1
        return (self.history[i].q_end if i >= 0 else self.rest).copy()

    def pending(self, t: float) -> int:
        """Number of segments not finished at ``t``."""
        count = 0
        for seg in reversed(self.history):  # in time order: stop at the first finished one
            if seg.end <= t + CLOCK_RESOLUTION:  # the clock may stop up to 1 ns short of ``end``
                break
            count += 1
        return count

    def cut_at(self, t: float, q: Vec) -> None:
        """Stop everything at ``t`` with the robot at ``q``: later segments are dropped."""
        while self.history and self.history[-1].t0 > t:
            self.history.pop()
            self._starts.pop()
        last = self.last
        if last is not None and last.end > t:
            last.cut = max(t, last.t0)
            last.q_end = q.copy()

"""A robot's motion limits read from its parameter database, and their scaling by a Profile.

Everything here is in GPL units (mm, degrees, seconds): the planner runs Ruckig directly in these
units, which keeps every number a user sees in a trace equal to the number Ruckig produced.

DataIDs (robot-models.md §2.4-§2.5): 2700/2702 per-axis 100 % joint speed/acceleration (2702 is
also the deceleration reference), 2701/2703 Cartesian speed/acceleration ([1] linear mm/s, [2]
rotation deg/s), 2704-2706 caps on Profile.Speed/Accel/Decel (%), 2101 RapidDecel %,
2601 in-range settling time (s).

A program may change these DataIDs at run time (``Controller.PDb``/``PDbNum``); the motion
registry then calls :meth:`RobotLimits.reload` on the robot's limits, which rereads them in place
and drops the ``joint_limits`` memo, so the next motion uses the new values and a Move that
follows no write pays nothing extra.  Which of them need power off is decided in
``gplrt.controller.services.NEEDS_POWER_OFF``.

Profile mapping (gpl-classes §22.4, robot-models §2.4 [P]):
``v = ref_speed · min(Speed, 2704)/100 · SystemSpeed/100``, ``a = ref_accel · min(Accel, 2705)/100``,
``d = ref_accel · min(Decel, 2706)/100``, jerk ``a / AccelRamp`` and ``d / DecelRamp``.  Ruckig has
one jerk per axis, so the smaller of the two is used (a ramp of 0 means no jerk limit).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields
from typing import TypeVar

import numpy as np
from numpy.typing import NDArray

from gplrt.motion.profile import Profile

Vec = NDArray[np.float64]
_T = TypeVar("_T")

#: Settling time for InRange > 0 when the database has no DataID 2601 (s).
DEFAULT_SETTLE = 0.05

#: The DataIDs :meth:`RobotLimits.from_pdb` reads: a write to one of them reloads the limits.
LIMIT_DATA_IDS: frozenset[int] = frozenset({2700, 2701, 2702, 2703, 2704, 2705, 2706, 2101, 2601})


@dataclass(frozen=True)
class AxisLimits:
    """Per-axis limits for one planned segment (arrays of the robot's axis count).

    ``lists`` holds the same values as Python float lists (jerk: ``inf`` for no limit), the form
    Ruckig's input takes, computed once per distinct Profile so a Move converts nothing."""

    velocity: Vec
    accel: Vec
    decel: Vec
    jerk: Vec
    lists: tuple[list[float], list[float], list[float], list[float]] = field(init=False, repr=False)
    symmetric: bool = field(init=False, repr=False)  # accel == decel on every axis

    def __post_init__(self) -> None:
        conv = lambda a: [float(x) for x in a]  # noqa: E731
        object.__setattr__(self, "lists", (conv(self.velocity), conv(self.accel), conv(self.decel), conv(self.jerk)))
        object.__setattr__(self, "symmetric", bool(np.array_equal(self.accel, self.decel)))


@dataclass(frozen=True)
class PathLimits:
    """Limits of the tool along a Cartesian path: linear (mm) and rotation (deg) rates."""

    linear_velocity: float
    linear_accel: float
    linear_decel: float
    rotation_velocity: float
    rotation_accel: float
    rotation_decel: float
    accel_ramp: float
    decel_ramp: float


@dataclass(frozen=True)
class LineLimits:
    """What the 1-D plan of a Cartesian path needs of one Profile (``path_run.path_limits``):
    the speed, acceleration and deceleration limits of the tool's length, its turn and each
    joint, in that order, as Python float lists, and the two ramps.  Memoised per Profile
    values (``RobotLimits.line_limits``) so that a straight ``Move.Loc`` only divides."""

    velocity: list[float]
    accel: list[float]
    decel: list[float]
    accel_ramp: float
    decel_ramp: float
    #: The joints' part of ``velocity``, ``accel``, ``decel`` (from the third entry on), kept
    #: apart so that ``path_limits`` walks the joints' chords without an index per joint.
    joint_velocity: list[float] = field(init=False)
    joint_accel: list[float] = field(init=False)
    joint_decel: list[float] = field(init=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "joint_velocity", self.velocity[2:])
        object.__setattr__(self, "joint_accel", self.accel[2:])
        object.__setattr__(self, "joint_decel", self.decel[2:])


@dataclass(eq=False)
class RobotLimits:
    """The reference (100 %) values of one robot (``joint_limits`` results are memoised per
    Profile values: a program uses a handful of profiles for thousands of moves)."""

    joint_speed: Vec
    joint_accel: Vec
    cart_speed: tuple[float, float]
    cart_accel: tuple[float, float]
    max_speed_pct: float
    max_accel_pct: float
    max_decel_pct: float
    rapid_decel_pct: float
    settle_time: float
    _joint_cache: dict[tuple[float, ...], AxisLimits] = field(default_factory=dict, repr=False)
    _path_cache: dict[tuple[float, ...], PathLimits] = field(default_factory=dict, repr=False)
    _line_cache: dict[tuple[float, ...], LineLimits] = field(default_factory=dict, repr=False)
    _hard: tuple[Vec, Vec] | None = field(default=None, repr=False)
    #: (Profile values, SystemSpeed, result) of the last ``joint_limits`` / ``line_limits`` call:
    #: a program moves with the same unchanged Profile move after move, and ``Profile.values``
    #: is then the very same tuple, so the memo is found by identity without building a key.
    _joint_last: tuple[object, object, AxisLimits | None] = field(default=(None, None, None), repr=False)
    _line_last: tuple[object, object, LineLimits | None] = field(default=(None, None, None), repr=False)

    @classmethod
    def from_pdb(cls, pdb: object, robot: int, n: int) -> RobotLimits:
        """Read the DataIDs above; missing per-axis values repeat the last one given."""

        def nums(data_id: int, default: list[float]) -> list[float]:
            has = getattr(pdb, "has")(data_id, robot)
            return list(getattr(pdb, "get_nums")(data_id, robot)) if has else default

        def per_axis(data_id: int) -> Vec:
            vals = [v for v in nums(data_id, [100.0]) if v > 0.0] or [100.0]
            vals = (vals + [vals[-1]] * n)[:n]
            return np.array(vals, dtype=float)

        cs = nums(2701, [250.0, 180.0]) + [180.0]
        ca = nums(2703, [1000.0, 720.0]) + [720.0]
        one = lambda data_id, default: nums(data_id, [default])[0]  # noqa: E731
        return cls(
            joint_speed=per_axis(2700),
            joint_accel=per_axis(2702),
            cart_speed=(float(cs[0]), float(cs[1])),
            cart_accel=(float(ca[0]), float(ca[1])),
            max_speed_pct=float(one(2704, 100.0)),
            max_accel_pct=float(one(2705, 100.0)),
            max_decel_pct=float(one(2706, 100.0)),
            rapid_decel_pct=float(one(2101, 100.0)),
            settle_time=float(one(2601, DEFAULT_SETTLE)),
        )

    def reload(self, pdb: object, robot: int, n: int) -> None:
        """Reread the DataIDs after a parameter-database write, in place (whoever holds these
        limits sees the new values), and forget the memoised ``joint_limits``/``path_limits`` results."""
        fresh = RobotLimits.from_pdb(pdb, robot, n)
        for f in fields(self):  # every value read from the database; the memos start empty
            setattr(self, f.name, getattr(fresh, f.name))

    @property
    def max_joint_speed(self) -> Vec:
        """Each joint's hard maximum speed, 2700 × 2704 %: the fastest any Profile may ask."""
        return self.hard_limits()[0]

    @property
    def max_joint_accel(self) -> Vec:
        """Each joint's hard maximum acceleration, 2702 × the larger of 2705 % and 2706 %."""
        return self.hard_limits()[1]

    def hard_limits(self) -> tuple[Vec, Vec]:
        """(``max_joint_speed``, ``max_joint_accel``) in one call (a straight Move takes both)."""
        if self._hard is None:
            pct = max(self.max_accel_pct, self.max_decel_pct)
            self._hard = (self.joint_speed * (self.max_speed_pct / 100.0), self.joint_accel * (pct / 100.0))
        return self._hard

    # -- Profile scaling ------------------------------------------------------------------------

    def _pcts(self, prof: Profile, system_speed: float) -> tuple[float, float, float]:
        speed = min(float(prof.Speed), self.max_speed_pct) / 100.0 * system_speed / 100.0
        accel = min(float(prof.Accel), self.max_accel_pct) / 100.0
        decel = min(float(prof.Decel), self.max_decel_pct) / 100.0
        return speed, accel, decel

    def joint_limits(self, prof: Profile, system_speed: float) -> AxisLimits:
        """Joint-interpolated move limits for ``prof`` at ``Controller.SystemSpeed``."""
        values = prof._values or prof.values()
        last = self._joint_last  # (the hits stay inline: every Move.Loc asks)
        if last[0] is values and last[1] == system_speed:
            return last[2]  # type: ignore[return-value]
        key = (prof._speed, prof._accel, prof._decel, prof._accel_ramp, prof._decel_ramp, system_speed)
        lim = self._joint_cache.get(key)
        if lim is None:
            lim = _remember(self._joint_cache, key, self._joint_limits(prof, system_speed))
        self._joint_last = (values, system_speed, lim)
        return lim

    def _joint_limits(self, prof: Profile, system_speed: float) -> AxisLimits:
        speed, accel, decel = self._pcts(prof, system_speed)
        a = self.joint_accel * accel
        d = self.joint_accel * decel
        return AxisLimits(self.joint_speed * speed, a, d, jerk_of(a, d, prof.AccelRamp, prof.DecelRamp))

    def path_limits(self, prof: Profile, system_speed: float) -> PathLimits:
        """Straight-line / arc limits: 2701/2703 [1] for translation, [2] for rotation (memoised
        per Profile values like ``joint_limits``).

        ``Speed2`` > 0 replaces ``Speed`` for the rotation rate ("secondary peak speed for
        selected axes during Cartesian motions"); 0 means "not used" (same as Speed)."""
        key = (prof._speed, prof._speed2, prof._accel, prof._decel, prof._accel_ramp, prof._decel_ramp, system_speed)
        lim = self._path_cache.get(key)
        return lim if lim is not None else _remember(self._path_cache, key, self._path_limits(prof, system_speed))

    def line_limits(self, prof: Profile, system_speed: float) -> LineLimits:
        """``path_limits`` and ``joint_limits`` of ``prof`` side by side, as a line's 1-D plan
        reads them (memoised per Profile values like them)."""
        values = prof._values or prof.values()
        last = self._line_last
        if last[0] is values and last[1] == system_speed:
            return last[2]  # type: ignore[return-value]
        key = (prof._speed, prof._speed2, prof._accel, prof._decel, prof._accel_ramp, prof._decel_ramp, system_speed)
        lim = self._line_cache.get(key)
        if lim is None:
            lim = _remember(self._line_cache, key, self._line_limits(prof, system_speed))
        self._line_last = (values, system_speed, lim)
        return lim

    def _line_limits(self, prof: Profile, system_speed: float) -> LineLimits:
        cart, (vel, acc, dec, _) = self.path_limits(prof, system_speed), self.joint_limits(prof, system_speed).lists
        return LineLimits([cart.linear_velocity, cart.rotation_velocity, *vel],
                          [cart.linear_accel, cart.rotation_accel, *acc],
                          [cart.linear_decel, cart.rotation_decel, *dec], prof._accel_ramp, prof._decel_ramp)

    def _path_limits(self, prof: Profile, system_speed: float) -> PathLimits:
        speed, accel, decel = self._pcts(prof, system_speed)
        rot_speed = speed
        if float(prof.Speed2) > 0.0:
            rot_speed = min(float(prof.Speed2), self.max_speed_pct) / 100.0 * system_speed / 100.0
        return PathLimits(
            self.cart_speed[0] * speed, self.cart_accel[0] * accel, self.cart_accel[0] * decel,
            self.cart_speed[1] * rot_speed, self.cart_accel[1] * accel, self.cart_accel[1] * decel,
            float(prof.AccelRamp), float(prof.DecelRamp),
        )


#: Distinct Profiles memoised per robot before the memo starts again (a program uses a handful).
MEMO_SIZE = 256


def _remember(cache: dict[tuple[float, ...], _T], key: tuple[float, ...], value: _T) -> _T:
    """Store a memo entry (``joint_limits``/``path_limits``), emptying a memo grown past ``MEMO_SIZE``."""
    if len(cache) >= MEMO_SIZE:
        cache.clear()
    cache[key] = value
    return value


#: Ramps shorter than this (s) are treated as 0 = no jerk limit: a tenth of a millisecond is far
#: below the trajectory generator's period, so the controller cannot follow such a ramp anyway.
#: Below it Ruckig fails on short moves (a jerk of accel / 1e-6: 236 of 3,000 random joint moves
#: with ramps of 1-10 µs were refused with -1043; none from 0.1 ms up).
MIN_RAMP = 1e-4


def jerk_of(a: Vec, d: Vec, accel_ramp: float, decel_ramp: float) -> Vec:
    """Jerk = accel / ramp time; the more restrictive of the accel and decel ramps (0 s = unlimited)."""
    ja = a / accel_ramp if accel_ramp >= MIN_RAMP else np.full_like(a, math.inf)
    jd = d / decel_ramp if decel_ramp >= MIN_RAMP else np.full_like(d, math.inf)
    return np.minimum(ja, jd)

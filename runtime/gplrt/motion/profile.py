"""GPL's Profile class: how a motion moves (speed, acceleration, ramps, path type, in-position rule).

Spec: gpl-classes.md §6, gpl-dictionary.md §3, robot-models.md §2.4.

Defaults are the controller's parameter-database defaults for a new Profile (robot-models.md
§2.4; the PF400 sets under /work/shared/data/robots/ give these, the GCU default set says Speed
100 %, so the controller calls ``set_profile_defaults`` after loading its PDb): Speed 50 % (DataID
2708), Speed2 0 % = not used (2709), Accel and Decel 100 % (2710/2711), AccelRamp and DecelRamp
0.1 s (2712/2713), Straight False (GD straight.htm), InRange 0 [P: stop at the end without a
position-error check — the Dictionary gives no default; the planner treats 0 as "done when the
last set-point is issued"], Text "".

Range checks (the Dictionary names no codes; we use the controller's generic ones): NaN or an
infinite value -> -708 *Value infinite or NAN*; Speed, Accel, Decel <= 0 -> -705 *Value too
small* (a zero speed could never finish a motion); Speed2, AccelRamp, DecelRamp < 0 -> -705.
Upper caps depend on the robot (DataIDs 2704-2706, e.g. 150/300/300 % on a PF400); a Profile is not
bound to a robot, so the planner clamps with ``min(value, cap)`` when it plans a segment
(``robot-models.md`` §2.4 mapping) — it is not an error to ask for more.
"""

from __future__ import annotations

import math

from gplrt.display import html_table, short
from gplrt.lang.conversions import to_bool, to_double, to_string
from gplrt.lang.errors import VALUE_INFINITE_OR_NAN, VALUE_TOO_SMALL, GplException
from gplrt.lang.gpltypes import Boolean, Double, String


DEFAULT_SPEED = 50.0
DEFAULT_SPEED2 = 0.0
DEFAULT_ACCEL = 100.0
DEFAULT_DECEL = 100.0
DEFAULT_RAMP = 0.1
DEFAULT_INRANGE = 0.0

_defaults: dict[str, float] = {
    "_speed": DEFAULT_SPEED,
    "_speed2": DEFAULT_SPEED2,
    "_accel": DEFAULT_ACCEL,
    "_decel": DEFAULT_DECEL,
    "_accel_ramp": DEFAULT_RAMP,
    "_decel_ramp": DEFAULT_RAMP,
}


def set_profile_defaults(
    speed: float = DEFAULT_SPEED,
    speed2: float = DEFAULT_SPEED2,
    accel: float = DEFAULT_ACCEL,
    decel: float = DEFAULT_DECEL,
    accel_ramp: float = DEFAULT_RAMP,
    decel_ramp: float = DEFAULT_RAMP,
) -> None:
    """Defaults for profiles created from now on (DataIDs 2708-2713 of the loaded robot)."""
    _defaults.update(
        _speed=_checked(speed, "Speed", positive=True),
        _speed2=_checked(speed2, "Speed2", positive=False),
        _accel=_checked(accel, "Accel", positive=True),
        _decel=_checked(decel, "Decel", positive=True),
        _accel_ramp=_checked(accel_ramp, "AccelRamp", positive=False),
        _decel_ramp=_checked(decel_ramp, "DecelRamp", positive=False),
    )


def _checked(value: float, name: str, *, positive: bool) -> float:
    """``value`` as a Double under GPL's conversion rules (a numeric String is parsed, -717 on bad
    text, -782 for Nothing), refused when not finite or below the member's range."""
    v = to_double(value)
    if not math.isfinite(v):
        raise GplException(VALUE_INFINITE_OR_NAN, detail=f"Profile.{name} = {v}")
    if v < 0.0 or (positive and v == 0.0):
        bound = "> 0" if positive else ">= 0"
        raise GplException(VALUE_TOO_SMALL, detail=f"Profile.{name} = {v}, must be {bound}")
    return v


class Profile:
    """GPL ``Profile``.  ``New Profile`` (no arguments) gives the controller defaults above."""

    #: The values a motion takes from its Profile (``values``), in this order.
    FIELDS = ("_speed", "_speed2", "_accel", "_decel", "_accel_ramp", "_decel_ramp", "_straight", "_inrange", "_text")
    #: ``_values``: the tuple ``values`` returned last, None after any change (every setter
    #: clears it), so a Move with an unchanged Profile takes no snapshot and its limits are found
    #: by identity (``RobotLimits.joint_limits``).
    __slots__ = (*FIELDS, "_values")

    def __init__(self) -> None:
        d = _defaults
        self._speed = d["_speed"]
        self._speed2 = d["_speed2"]
        self._accel = d["_accel"]
        self._decel = d["_decel"]
        self._accel_ramp = d["_accel_ramp"]
        self._decel_ramp = d["_decel_ramp"]
        self._straight = False
        self._inrange = DEFAULT_INRANGE
        self._text = ""
        self._values: tuple[object, ...] | None = None

    def values(self) -> tuple[object, ...]:
        """The Profile's values (``FIELDS``) as one tuple: what a queued motion keeps of it (the
        program may change its Profile after the Move).  The same tuple object until a setter
        changes a value, which is what lets the motion layer memoise per Profile state by identity."""
        values = self._values
        if values is None:
            values = self._values = (self._speed, self._speed2, self._accel, self._decel, self._accel_ramp,
                                     self._decel_ramp, self._straight, self._inrange, self._text)
        return values

    @property
    def Speed(self) -> Double:
        """Peak speed, % of the robot's 100 % speeds (DataID 2700 joint / 2701 Cartesian)."""
        return self._speed  # type: ignore[return-value]

    @Speed.setter
    def Speed(self, value: Double) -> None:
        self._values = None
        self._speed = _checked(value, "Speed", positive=True)

    @property
    def Speed2(self) -> Double:
        """Secondary peak speed (%) for selected axes in Cartesian motions; 0 = not used."""
        return self._speed2  # type: ignore[return-value]

    @Speed2.setter
    def Speed2(self, value: Double) -> None:
        self._values = None
        self._speed2 = _checked(value, "Speed2", positive=False)

    @property
    def Accel(self) -> Double:
        """Peak acceleration, % of the robot's 100 % accelerations (DataID 2702/2703)."""
        return self._accel  # type: ignore[return-value]

    @Accel.setter
    def Accel(self, value: Double) -> None:
        self._values = None
        self._accel = _checked(value, "Accel", positive=True)

    @property
    def Decel(self) -> Double:
        """Peak deceleration, % of the robot's 100 % accelerations."""
        return self._decel  # type: ignore[return-value]

    @Decel.setter
    def Decel(self, value: Double) -> None:
        self._values = None
        self._decel = _checked(value, "Decel", positive=True)

    @property
    def AccelRamp(self) -> Double:
        """Seconds to ramp up to peak acceleration (the jerk limit; 0 = trapezoidal)."""
        return self._accel_ramp  # type: ignore[return-value]

    @AccelRamp.setter
    def AccelRamp(self, value: Double) -> None:
        self._values = None
        self._accel_ramp = _checked(value, "AccelRamp", positive=False)

    @property
    def DecelRamp(self) -> Double:
        """Seconds to ramp up to peak deceleration."""
        return self._decel_ramp  # type: ignore[return-value]

    @DecelRamp.setter
    def DecelRamp(self, value: Double) -> None:
        self._values = None
        self._decel_ramp = _checked(value, "DecelRamp", positive=False)

    @property
    def Straight(self) -> Boolean:
        """True: straight-line Cartesian path of the tool tip; False: joint-interpolated."""
        return self._straight  # type: ignore[return-value]

    @Straight.setter
    def Straight(self, value: Boolean) -> None:
        self._values = None
        self._straight = to_bool(value)  # "False" is False, as CBool reads it

    @property
    def InRange(self) -> Double:
        """< 0: blend into the next motion; 0: stop, no position check; > 0: stop within a tolerance."""
        return self._inrange  # type: ignore[return-value]

    @InRange.setter
    def InRange(self, value: Double) -> None:
        self._values = None
        v = to_double(value)
        if not math.isfinite(v):
            raise GplException(VALUE_INFINITE_OR_NAN, detail=f"Profile.InRange = {v}")
        self._inrange = v

    @property
    def Text(self) -> String:
        """Free user string."""
        return self._text  # type: ignore[return-value]

    @Text.setter
    def Text(self, value: String) -> None:
        self._values = None
        self._text = to_string(value)  # CStr rules: 2.0 is "2"

    def Clone(self) -> Profile:
        """An independent copy."""
        twin = Profile.__new__(Profile)
        for name in Profile.FIELDS:
            setattr(twin, name, getattr(self, name))
        twin._values = self._values  # (an immutable tuple of the same values)
        return twin

    # -- Python side -------------------------------------------------------------------------------

    @property
    def blends(self) -> bool:
        """True when the motion should blend into the next one (InRange < 0)."""
        return self._inrange < 0.0

    def _display_items(self) -> list[tuple[str, object]]:
        return [("Speed", self._speed), ("Speed2", self._speed2), ("Accel", self._accel), ("Decel", self._decel),
                ("AccelRamp", self._accel_ramp), ("DecelRamp", self._decel_ramp), ("Straight", self._straight),
                ("InRange", self._inrange)]

    def __repr__(self) -> str:
        return "Profile(" + ", ".join(f"{name}={short(value)}" for name, value in self._display_items()) + ")"

    def _repr_html_(self) -> str:
        items = self._display_items()
        caption = f"Profile {self._text!r}" if self._text else "Profile"
        return html_table([name for name, _ in items], [tuple(short(v) for _, v in items)], caption)

"""Named points, bases and TCPs (manual L14355-L14860, L14857-L15514): the teach classes
``TPoint``, ``TBase``, ``TTCP`` a script declares, and the parameterized objects ``Point[name]``,
``Base[name]``, ``TCP[name]`` that read them (``RobotBase`` and ``NOTOOL`` always exist).

A declaration registers its name on the current robot, so that ``ChangeBase("name")``,
``ChangeTCP("name")`` and ``Point["name"].Value`` find it.  Write-back kinds (``"D"``, ``"JD"``)
are accepted and not written back (there is no TMflow point file).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from gplrt.tm import context
from gplrt.tm.robot import config_bits, pose_to_se3, se3_to_pose
from gplrt.tm.values import Array, TMError, to_double, to_string

KINDS = ("C", "D", "J", "JD", "V")


def _values(args: list[object], name: str) -> list[float]:
    """Six values from the front of ``args`` (a float[] or six scalars), removed from it."""
    if args and isinstance(args[0], (list, tuple)):
        vals = [float(to_double(v)) for v in args.pop(0)]  # type: ignore[union-attr]
    else:
        if len(args) < 6:
            raise TMError(f"{name}: six values are needed")
        vals = [float(to_double(v)) for v in args[:6]]
        del args[:6]
    if len(vals) != 6:
        raise TMError(f"{name}: six values are needed, not {len(vals)}")
    return vals


class LiveArray(Array):
    """An attribute's array whose element writes reach the attribute: ``Point["P1"].Value[2] =
    120`` replaces the point's Z alone (L14445, L14496, L14551, L14599, L15058)."""

    __slots__ = ("_write",)

    def __init__(self, type_name: str, items: Iterable[object], write: Callable[[list[object]], None]) -> None:
        super().__init__(type_name, items)
        self._write = write

    def __setitem__(self, i, v):  # type: ignore[no-untyped-def]
        super().__setitem__(i, v)
        self._write(list(self))


def _registry(kind: str) -> dict[str, object]:
    r = context.robot()
    reg = r.__dict__.setdefault("_teach", {"point": {}, "base": {}, "tcp": {}})
    return reg[kind]  # type: ignore[no-any-return]


class TPoint:
    """``TPoint p = [kind,] float[6]|6 floats [, joints] [, base, tcp]`` (L14859-L15023)."""

    def __init__(self, name: str, *args: object) -> None:
        rest = list(args)
        self.name = name
        self.kind = str(rest.pop(0)) if rest and isinstance(rest[0], str) and rest[0] in KINDS else "C"
        first = _values(rest, "TPoint")
        joints = _values(rest, "TPoint") if rest and isinstance(rest[0], (list, tuple)) else None
        robot = context.robot()  # (a name not given, or "", is the current one, L14936, L14978)
        self.BaseName = (to_string(rest.pop(0)) if rest else "") or robot.script_base_name
        self.TCPName = (to_string(rest.pop(0)) if rest else "") or robot.script_tcp_name
        self._joint: list[float] | None = first if self.kind.startswith("J") else joints
        self._value: list[float] | None = None if self.kind.startswith("J") else first
        self._pose: list[int] | None = None  # the configuration asked for, when one was set
        _registry("point")[name] = self

    @property
    def Value(self) -> Array:
        if self._value is None:
            assert self._joint is not None
            self._value = se3_to_pose(context.robot().arm.fk_se3(self._joint))
        return LiveArray("float", self._value, lambda vals: setattr(self, "Value", vals))

    @Value.setter
    def Value(self, v: object) -> None:
        self._value, self._joint = _values([v], "Point.Value"), None

    @property
    def Joint(self) -> Array:
        if self._joint is None:
            r = context.robot()
            assert self._value is not None
            self._joint = r.arm.ik(self._value, r.current_joints(), self._pose)  # an error when unreachable (L14427)
        return LiveArray("float", self._joint, lambda vals: setattr(self, "Joint", vals))

    @property
    def Pose(self) -> Array:
        """The pose configuration ``{Config1, Config2, Config3}`` of the point's joints (L14419,
        L17206)."""
        return Array("int", context.robot().arm.config(list(self.Joint)))

    @Pose.setter
    def Pose(self, v: object) -> None:
        """Setting the configuration recomputes the joints in it (an error when unreachable)."""
        triplet = [int(to_double(x)) for x in (v if isinstance(v, (list, tuple, Array)) else [v])]  # type: ignore[union-attr]
        config_bits(triplet)
        if self._value is None:
            self._value = list(self.Value)
        self._pose, self._joint = triplet, None

    @Joint.setter
    def Joint(self, v: object) -> None:
        self._joint, self._value, self._pose = _values([v], "Point.Joint"), None, None


class TBase:
    """``TBase b = [kind,] float[6]|6 floats`` (L15065)."""

    def __init__(self, name: str, *args: object) -> None:
        rest = list(args)
        self.Type = str(rest.pop(0)) if rest and isinstance(rest[0], str) and rest[0] in KINDS else "C"
        self._value = _values(rest, "TBase")
        if name != "RobotBase":
            _registry("base")[name] = self

    @property
    def Value(self) -> Array:
        return LiveArray("float", self._value, lambda vals: setattr(self, "Value", vals))

    @Value.setter
    def Value(self, v: object) -> None:
        self._value = _values([v], "Base.Value")


class TTCP:
    """``TTCP t = [kind,] float[6]|6 floats [, mass]`` (L15278)."""

    def __init__(self, name: str, *args: object) -> None:
        rest = list(args)
        self.Type = str(rest.pop(0)) if rest and isinstance(rest[0], str) and rest[0] in KINDS else "C"
        self._value = _values(rest, "TTCP")
        self.Mass = float(to_double(rest.pop(0))) if rest else 0.0
        if name not in ("NOTOOL", "HandCamera"):
            _registry("tcp")[name] = self

    @property
    def Value(self) -> Array:
        return LiveArray("float", self._value, lambda vals: setattr(self, "Value", vals))

    @Value.setter
    def Value(self, v: object) -> None:
        self._value = _values([v], "TCP.Value")


class _Named:
    def __init__(self, kind: str, builtin: dict[str, object]) -> None:
        self.kind, self.builtin = kind, builtin

    def __getitem__(self, key: object) -> object:
        name = key[0] if isinstance(key, tuple) else key
        found = _registry(self.kind).get(str(name)) or self.builtin.get(str(name))
        if found is None:
            raise TMError(f'{self.kind.capitalize()}["{name}"] does not exist')
        return found


class _Fixed:
    """``Base["RobotBase"]``, ``TCP["NOTOOL"]``: read only, all zeros."""

    Type = "R"
    Mass = 0.0

    @property
    def Value(self) -> Array:
        return Array("float", [0.0] * 6)


Point = _Named("point", {})
Base = _Named("base", {"RobotBase": _Fixed()})
TCP = _Named("tcp", {"NOTOOL": _Fixed(), "HandCamera": _Fixed()})


def frame_of(kind: str, name: str) -> tuple[object, float] | None:
    """A declared base's or TCP's transform (and a TCP's mass), or None."""
    found = _registry(kind).get(name)
    if found is None:
        return None
    return pose_to_se3(found._value), float(getattr(found, "Mass", 0.0))  # type: ignore[attr-defined]

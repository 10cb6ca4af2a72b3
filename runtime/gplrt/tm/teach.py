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
from gplrt.tm.members import Members
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


class TPoint(Members):
    """``TPoint p = [kind,] float[6]|6 floats [, joints] [, base, tcp]`` (L14859-L15023)."""

    tm_name = "TPoint"

    def __init__(self, name: str, *args: object) -> None:
        rest = list(args)
        self.name = name
        self.kind = str(rest.pop(0)) if rest and isinstance(rest[0], str) and rest[0] in KINDS else "C"
        first = _values(rest, "TPoint")
        joints = _values(rest, "TPoint") if rest and isinstance(rest[0], (list, tuple)) else None
        robot = context.robot()  # (a name not given, or "", is the current one, L14936, L14978)
        self._base_name = (to_string(rest.pop(0)) if rest else "") or robot.script_base_name
        self._tcp_name = (to_string(rest.pop(0)) if rest else "") or robot.script_tcp_name
        self._joint: list[float] | None = first if self.kind.startswith("J") else joints
        self._value: list[float] | None = None if self.kind.startswith("J") else first
        self._pose: list[int] | None = None  # the configuration asked for, when one was set
        _registry("point")[name] = self

    @property
    def BaseName(self) -> str:
        return self._base_name

    @property
    def TCPName(self) -> str:
        return self._tcp_name

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


class TBase(Members):
    """``TBase b = [kind,] float[6]|6 floats`` (L15065)."""

    tm_name = "TBase"

    def __init__(self, name: str, *args: object) -> None:
        rest = list(args)
        self._type = str(rest.pop(0)) if rest and isinstance(rest[0], str) and rest[0] in KINDS else "C"
        self._value = _values(rest, "TBase")
        if name != "RobotBase":
            _registry("base")[name] = self

    @property
    def Type(self) -> str:
        return self._type

    @property
    def Value(self) -> Array:
        return LiveArray("float", self._value, lambda vals: setattr(self, "Value", vals))

    @Value.setter
    def Value(self, v: object) -> None:
        self._value = _values([v], "Base.Value")


class TTCP(Members):
    """``TTCP t = [kind,] float[6]|6 floats [, mass]`` (L15278).  Its kind is kept but is no member
    (the manual's TTCP has none: L15467)."""

    tm_name = "TTCP"

    def __init__(self, name: str, *args: object) -> None:
        rest = list(args)
        self._type = str(rest.pop(0)) if rest and isinstance(rest[0], str) and rest[0] in KINDS else "C"
        self._value = _values(rest, "TTCP")
        self._mass = float(to_double(rest.pop(0))) if rest else 0.0
        if name not in ("NOTOOL", "HandCamera"):
            _registry("tcp")[name] = self

    @property
    def Mass(self) -> float:
        return self._mass

    @Mass.setter
    def Mass(self, v: object) -> None:
        self._mass = float(to_double(v))

    @property
    def Value(self) -> Array:
        return LiveArray("float", self._value, lambda vals: setattr(self, "Value", vals))

    @Value.setter
    def Value(self, v: object) -> None:
        self._value = _values([v], "TCP.Value")


class _Named:
    """``Point[name]``, ``Base[name]``, ``TCP[name]``; ``item`` is the class of what they give (the
    front end checks their members against it)."""

    def __init__(self, kind: str, builtin: dict[str, object], item: type) -> None:
        self.kind, self.builtin, self.item = kind, builtin, item

    def __getitem__(self, key: object) -> object:
        name = key[0] if isinstance(key, tuple) else key
        found = _registry(self.kind).get(str(name)) or self.builtin.get(str(name))
        if found is None:
            raise TMError(f'{self.kind.capitalize()}["{name}"] does not exist')
        return found


class _FixedBase(Members):
    """``Base["RobotBase"]``: read only, all zeros, the members of a TBase (writing one is an
    invalid operation, L14481)."""

    tm_name = 'Base["RobotBase"]'
    Type = "R"

    @property
    def Value(self) -> Array:
        return Array("float", [0.0] * 6)


class _FixedTCP(Members):
    """``TCP["NOTOOL"]``, ``TCP["HandCamera"]``: read only, all zeros, the members of a TTCP
    (L14535)."""

    tm_name = "a system TCP"
    Mass = 0.0

    @property
    def Value(self) -> Array:
        return Array("float", [0.0] * 6)


Point = _Named("point", {}, TPoint)
Base = _Named("base", {"RobotBase": _FixedBase()}, TBase)
TCP = _Named("tcp", {"NOTOOL": _FixedTCP(), "HandCamera": _FixedTCP()}, TTCP)


def frame_of(kind: str, name: str) -> tuple[object, float] | None:
    """A declared base's or TCP's transform (and a TCP's mass), or None."""
    found = _registry(kind).get(name)
    if found is None:
        return None
    mass = float(found.Mass) if isinstance(found, TTCP) else 0.0
    return pose_to_se3(found._value), mass  # type: ignore[attr-defined]

"""GPL's Location class: a Cartesian pose (optionally relative to a RefFrame) or a set of axis values.

Spec: gpl-classes.md §5 and §22.1, gpl-dictionary.md §1 (Brooks GPL Dictionary pages).  Members keep
their GPL spelling (runtime/gplrt/CATALOGUE.md); Python-side helpers are snake_case.

State and speed.  The primary state of a Cartesian Location is its PosWrtRef as a *pose tuple* of
12 floats (rotation row-major + translation, see ``transforms``); Euler angles are extracted lazily
and cached.  Rarely-changed fields (Config, ZClearance, Text, RefFrame, ...) are class-level
defaults that an instance only overrides when set, so ``Mul``/``Inverse`` build their result with a
single dict copy.  This keeps ``Mul`` within ~2-3x a bare numpy ``a @ b`` (benchmarks/geometry_speed.py).

Decisions where the manuals are silent (documented per the team rules):

* ``Type``: 0 = Cartesian, 1 = Angles (NIR list, gpl-dictionary.md §1).  A Location keeps both
  its pose and its axis values; changing ``Type`` only selects which one is meaningful.
* Reading Yaw/Pitch/Roll after writing them returns what was written (wrapped to (-180, 180]):
  the written triple is cached alongside the matrix, so ``loc.Yaw = 30`` followed by
  ``loc.Pitch = 90`` builds Rz(30)·Ry(90), as a program writing the angles one by one intends.
  Poses produced by arithmetic (Mul, Inverse, Pos through frames, ...) are decomposed with the
  rule in ``transforms`` (pitch in [0, 180]; at pitch 0/180 yaw = 0 and the rotation is in roll).
  This departs on purpose from gpl-classes.md §22.1 item 2, which proposes decomposing on every
  read (so ``XYZ(0,0,0,30,0,60)`` would read yaw 0, roll 90): the issue asks that written values
  read back, the manual (D0:1996-2013) only says the pose is *stored* as a matrix and is silent on
  read-back, and the cached triple always describes exactly the stored matrix, so no computation
  can tell the difference.  Only the singular pitches 0/180 (and a written pitch outside [0, 180])
  read differently from a decomposition; tests/geometry pins both behaviours.
* ``Angle(i)``: axes are numbered 1..12 (``MAX_AXES``); other numbers -> -707 *Value
  out-of-range*, like ``Latch.Angle``.  Not -1002 *Invalid axis number*: that code reports an axis
  a *robot* lacks (``Move.OneAxis``), while a Location belongs to no robot and always has room for
  12 values.  Axes never set read 0.
* ``Mul`` copies every property but the pose from the left operand (like ``Inverse``, whose page
  says "all other properties copied"); the Mul page only fixes PosWrtRef and RefFrame.
* ``Pos`` (get) returns a new Location holding the total pose, RefFrame Nothing, other properties
  copied.
* A chain of frames that loops back on itself is GPL error -770 *Reference frame undefined data*.
* ``XYZInc`` adds to X, Y, Z of PosWrtRef, i.e. in the axes of the parent frame.
* ``Here3(p0, px, pxy)``: origin p0, +X towards px, pxy in the X-Y plane on the +Y side.
* No arithmetic operators: the manuals define none on Locations (composition is only ``Mul``,
  inversion only ``Inverse``; gpl-classes.md §5.2), so ``loc1 * loc2`` is deliberately a Python
  TypeError that the transpiler's type check reports before run time.
* A pose computed by arithmetic (Mul, Inverse, Pos through frames or pallets, XYZInc, Here3,
  Distance) that leaves the Double range is -710 *Arithmetic overflow*, as for ``*`` on Doubles
  (``gplrt.lang.operators``), and the Location is left unchanged; the manuals name no other code.
  NaN results are -710 as well (they come from overflowed intermediates: operands are finite,
  since setters and ``from_pose`` reject NaN/inf input with -708).
* ``Config`` is stored as given; the kinematics provider interprets the bits (contradictory pairs
  such as Righty|Lefty are its business, the controller's behaviour being unconfirmed).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from gplrt.geometry import transforms as tf
from gplrt.geometry._checks import boolean, finite, finite_pose, in_range, text, to_integer, valid_pose, wrong_object
from gplrt.geometry.kinematics_provider import get_kinematics_provider
from gplrt.display import fixed, html_table
from gplrt.geometry.transforms import IDENTITY, Pose, pose_mul, wrap_angle
from gplrt.lang.errors import (
    ARITHMETIC_OVERFLOW,
    FRAME_UNDEFINED_DATA,
    NOTHING_VALUE,
    NOT_ANGLES,
    NOT_CARTESIAN,
    VALUE_OUT_OF_RANGE,
    GplException,
)
from gplrt.lang.gpltypes import Boolean, Double, Integer, String

# The RefFrame class, bound here by refframe.py when it loads (it imports this module, so this
# module cannot import it); annotations below name it and get_type_hints resolves it at run time.
RefFrame: Any = None

CARTESIAN = 0
ANGLES = 1
MAX_AXES = 12
#: ZClearance value meaning "not initialized" (no clearance defined).
NO_CLEARANCE = 1.0e32
#: Frame chains deeper than this are taken to be loops (-770).
MAX_FRAME_DEPTH = 64
#: Here3 scales difference vectors longer than this before its cross product (which would overflow
#: near the square root of the Double limit, ~1e154).
_HERE3_SCALE_ABOVE = 2.0**500


class Location:
    """GPL ``Location``.  ``New Location`` takes no arguments: a Cartesian identity pose.

    Accepted constructor forms: ``Location()`` only (the manuals document no overloads).
    """

    # Class-level defaults; instances override only what they change (see module docstring).
    _type: int = CARTESIAN
    _pose: Pose = IDENTITY
    _ypr: tuple[float, float, float] | None = (0.0, 0.0, 0.0)
    _angles: tuple[float, ...] = ()
    _config: int = 0
    _zclear: float = NO_CLEARANCE
    _zworld: bool = False
    _text: str = ""
    _ref: RefFrame | None = None

    def __init__(self) -> None:
        pass

    # -- Python-side construction and access ---------------------------------------------------

    @classmethod
    def from_pose(cls, pose: Pose, ref: RefFrame | None = None) -> Location:
        """A Cartesian Location whose PosWrtRef is ``pose`` (a 12-float tuple); a NaN or infinite
        component is -708, so that Location arithmetic only ever sees finite operands."""
        loc = object.__new__(cls)
        loc._pose = valid_pose(pose, "pose")
        loc._ypr = None
        if ref is not None:
            loc._ref = ref
        return loc

    @classmethod
    def from_matrix(cls, m: NDArray[np.float64]) -> Location:
        """A Cartesian Location whose PosWrtRef is the (4, 4) homogeneous matrix ``m``."""
        return cls.from_pose(tf.matrix_to_pose(m))

    @classmethod
    def from_angles(cls, values: Any) -> Location:
        """An Angles Location holding ``values`` (axis 1 first)."""
        loc = object.__new__(cls)
        loc._type = ANGLES
        try:
            values = tuple(values)
        except TypeError:
            raise wrong_object(values, "axis values", "sequence of numbers") from None
        loc._angles = tuple(finite(v, "axis value") for v in values)
        if len(loc._angles) > MAX_AXES:
            raise GplException(VALUE_OUT_OF_RANGE, detail=f"{len(loc._angles)} axes, at most {MAX_AXES}")
        return loc

    def total_pose(self) -> Pose:
        """Total position as a pose tuple (Cartesian only): Total(RefFrame) · PosWrtRef."""
        if self._type != CARTESIAN:
            raise GplException(NOT_CARTESIAN, detail="total pose of an Angles Location")
        return self._total_pose(0)

    def _total_pose(self, depth: int) -> Pose:
        ref = self._ref
        if ref is None:
            return self._pose
        if depth > MAX_FRAME_DEPTH:
            raise GplException(FRAME_UNDEFINED_DATA, detail="reference frames form a loop")
        return finite_pose(pose_mul(ref._total_pose(depth + 1), self._pose), "Pos")

    @property
    def pose_wrt_ref(self) -> Pose:
        """PosWrtRef as a pose tuple (Python side)."""
        return self._pose

    def matrix(self) -> NDArray[np.float64]:
        """Total position as a (4, 4) homogeneous matrix (Cartesian only)."""
        return tf.pose_to_matrix(self.total_pose())

    def axis_values(self) -> tuple[float, ...]:
        """The stored axis values of an Angles Location, axis 1 first."""
        return self._angles

    def approach_location(self) -> Location | None:
        """The clearance point ``Move.Approach`` goes to, or None when ZClearance is not initialized.

        ZWorld True: the total position with its world Z replaced by ZClearance; ZWorld False: the
        total position retracted by ZClearance along the tool's -Z axis (gpl-classes.md §22.1 item 8).
        """
        if self._zclear >= NO_CLEARANCE:
            return None
        t = self.total_pose()
        if self._zworld:
            p = t[:11] + (self._zclear,)
        else:
            # No overflow check: |ZClearance| < 1e32 is far below one unit in the last place of a
            # coordinate near the Double limit, so the retraction cannot leave the range.
            p = tf.pose_translate(t, 0.0, 0.0, -self._zclear)
        res = Location.from_pose(p)  # type: ignore[arg-type]
        res._config = self._config
        return res

    def _need_cartesian(self, what: str) -> None:
        if self._type != CARTESIAN:
            raise GplException(NOT_CARTESIAN, detail=f"{what} of an Angles Location")

    def _copy(self) -> Location:
        twin = object.__new__(Location)
        twin.__dict__.update(self.__dict__)
        return twin

    def _euler(self) -> tuple[float, float, float]:
        ypr = self._ypr
        if ypr is None:
            ypr = self._ypr = tf.pose_angles(self._pose)
        return ypr

    def _set_ypr(self, yaw: float, pitch: float, roll: float) -> None:
        p = self._pose
        self._pose = tf.pose_from_xyzypr(p[9], p[10], p[11], yaw, pitch, roll)
        self._ypr = (wrap_angle(yaw), wrap_angle(pitch), wrap_angle(roll))

    # -- how it shows (gplrt.display: for reading, mm and degrees to 3 decimals) -------------------

    def _display_values(self) -> tuple[tuple[str, ...], tuple[float, ...]]:
        """Column names and values: X Y Z Yaw Pitch Roll (PosWrtRef), or the axes of Angles."""
        if self._type == ANGLES:
            return tuple(f"axis {i + 1}" for i in range(len(self._angles))), self._angles
        return ("X", "Y", "Z", "Yaw", "Pitch", "Roll"), (*self._pose[9:], *self._euler())

    def __repr__(self) -> str:
        _, values = self._display_values()
        form = "Angles" if self._type == ANGLES else "XYZ"
        frame = ", RefFrame" if self._ref is not None else ""
        return f"Location({form}({', '.join(fixed(v) for v in values)}){frame})"

    def _repr_html_(self) -> str:
        names, values = self._display_values()
        extra = [("Config", f"&H{self._config:X}")] if self._config else []
        if self._zclear < NO_CLEARANCE:
            extra.append(("ZClearance", f"{fixed(self._zclear)} ({'world Z' if self._zworld else 'tool Z'})"))
        if self._ref is not None:
            extra.append(("RefFrame", "yes: X..Roll are relative to it"))
        if self._text:
            extra.append(("Text", self._text))
        kind = "Angles" if self._type == ANGLES else "Cartesian"
        table = html_table(names, [tuple(fixed(v) for v in values)], f"Location ({kind})")
        return table + (html_table(("", ""), extra) if extra else "")

    # -- properties: type and bookkeeping ------------------------------------------------------

    @property
    def Type(self) -> Integer:
        """0 = Cartesian, 1 = Angles."""
        return self._type  # type: ignore[return-value]

    @Type.setter
    def Type(self, value: Integer) -> None:
        self._type = in_range(to_integer(value, "Type"), CARTESIAN, ANGLES, "Location.Type")

    @property
    def Config(self) -> Integer:
        """GPL_Righty (&H01) ... GPL_Single (&H1000) bits choosing the IK solution (dictionary §13.1)."""
        return self._config  # type: ignore[return-value]

    @Config.setter
    def Config(self, value: Integer) -> None:
        self._config = to_integer(value, "Config")

    @property
    def ZClearance(self) -> Double:
        """Approach clearance in mm; 1.0E+32 means none defined."""
        return self._zclear  # type: ignore[return-value]

    @ZClearance.setter
    def ZClearance(self, value: Double) -> None:
        self._zclear = finite(value, "ZClearance")

    @property
    def ZWorld(self) -> Boolean:
        """True: ZClearance is an absolute world Z; False: a retraction along the tool's -Z."""
        return self._zworld  # type: ignore[return-value]

    @ZWorld.setter
    def ZWorld(self, value: Boolean) -> None:
        self._zworld = boolean(value)

    @property
    def Text(self) -> String:
        """Free user string; GPL itself never reads it."""
        return self._text  # type: ignore[return-value]

    @Text.setter
    def Text(self, value: String) -> None:
        self._text = text(value)

    @property
    def RefFrame(self) -> RefFrame | None:
        """The frame PosWrtRef is relative to, or Nothing."""
        return self._ref

    @RefFrame.setter
    def RefFrame(self, value: RefFrame | None) -> None:
        if value is not None:
            if not isinstance(value, RefFrame):
                raise wrong_object(value, "Location.RefFrame", "RefFrame")
            self._need_cartesian("RefFrame")
        self._ref = value

    # -- properties: the Cartesian components of PosWrtRef ---------------------------------------

    @property
    def X(self) -> Double:
        """X of PosWrtRef, mm."""
        if self._type != CARTESIAN:
            self._need_cartesian("X")
        return self._pose[9]  # type: ignore[return-value]

    @X.setter
    def X(self, value: Double) -> None:
        self._need_cartesian("X")
        p = self._pose
        self._pose = p[:9] + (finite(value, "X"), p[10], p[11])  # type: ignore[assignment]

    @property
    def Y(self) -> Double:
        """Y of PosWrtRef, mm."""
        if self._type != CARTESIAN:
            self._need_cartesian("Y")
        return self._pose[10]  # type: ignore[return-value]

    @Y.setter
    def Y(self, value: Double) -> None:
        self._need_cartesian("Y")
        p = self._pose
        self._pose = p[:10] + (finite(value, "Y"), p[11])  # type: ignore[assignment]

    @property
    def Z(self) -> Double:
        """Z of PosWrtRef, mm."""
        if self._type != CARTESIAN:
            self._need_cartesian("Z")
        return self._pose[11]  # type: ignore[return-value]

    @Z.setter
    def Z(self, value: Double) -> None:
        self._need_cartesian("Z")
        p = self._pose
        self._pose = p[:11] + (finite(value, "Z"),)  # type: ignore[assignment]

    @property
    def Yaw(self) -> Double:
        """Yaw (first rotation, about Z) of PosWrtRef, degrees."""
        self._need_cartesian("Yaw")
        return self._euler()[0]  # type: ignore[return-value]

    @Yaw.setter
    def Yaw(self, value: Double) -> None:
        self._need_cartesian("Yaw")
        _, pitch, roll = self._euler()
        self._set_ypr(finite(value, "Yaw"), pitch, roll)

    @property
    def Pitch(self) -> Double:
        """Pitch (rotation about the new Y) of PosWrtRef, degrees."""
        self._need_cartesian("Pitch")
        return self._euler()[1]  # type: ignore[return-value]

    @Pitch.setter
    def Pitch(self, value: Double) -> None:
        self._need_cartesian("Pitch")
        yaw, _, roll = self._euler()
        self._set_ypr(yaw, finite(value, "Pitch"), roll)

    @property
    def Roll(self) -> Double:
        """Roll (final rotation, about the new Z) of PosWrtRef, degrees."""
        self._need_cartesian("Roll")
        return self._euler()[2]  # type: ignore[return-value]

    @Roll.setter
    def Roll(self, value: Double) -> None:
        self._need_cartesian("Roll")
        yaw, pitch, _ = self._euler()
        self._set_ypr(yaw, pitch, finite(value, "Roll"))

    # -- methods that set values ---------------------------------------------------------------

    def XYZ(
        self,
        X: Double = 0.0,  # type: ignore[assignment]
        Y: Double = 0.0,  # type: ignore[assignment]
        Z: Double = 0.0,  # type: ignore[assignment]
        Yaw: Double = 0.0,  # type: ignore[assignment]
        Pitch: Double = 0.0,  # type: ignore[assignment]
        Roll: Double = 0.0,  # type: ignore[assignment]
    ) -> None:
        """Set all six PosWrtRef components (every argument optional, default 0); makes it Cartesian."""
        yaw, pitch, roll = finite(Yaw, "Yaw"), finite(Pitch, "Pitch"), finite(Roll, "Roll")
        self._pose = tf.pose_from_xyzypr(finite(X, "X"), finite(Y, "Y"), finite(Z, "Z"), yaw, pitch, roll)
        self._ypr = (wrap_angle(yaw), wrap_angle(pitch), wrap_angle(roll))
        self._type = CARTESIAN

    def XYZInc(self, X: Double = 0.0, Y: Double = 0.0, Z: Double = 0.0) -> None:  # type: ignore[assignment]
        """Add X, Y, Z (mm) to the translation of PosWrtRef (parent-frame axes; orientation kept)."""
        self._need_cartesian("XYZInc")
        p = self._pose
        dx, dy, dz = finite(X, "X"), finite(Y, "Y"), finite(Z, "Z")
        self._pose = finite_pose(p[:9] + (p[9] + dx, p[10] + dy, p[11] + dz), "XYZInc")  # type: ignore[assignment]

    @staticmethod
    def XYZValue(
        X: Double = 0.0,  # type: ignore[assignment]
        Y: Double = 0.0,  # type: ignore[assignment]
        Z: Double = 0.0,  # type: ignore[assignment]
        Yaw: Double = 0.0,  # type: ignore[assignment]
        Pitch: Double = 0.0,  # type: ignore[assignment]
        Roll: Double = 0.0,  # type: ignore[assignment]
    ) -> Location:
        """Shared: a new Cartesian Location (no RefFrame) with the given pose."""
        loc = Location()
        loc.XYZ(X, Y, Z, Yaw, Pitch, Roll)
        return loc

    def Angle(self, Axis: Integer) -> Double:
        """One axis value (mm or degrees) of an Angles Location; axes 1..12."""
        if self._type != ANGLES:
            raise GplException(NOT_ANGLES, detail="Angle of a Cartesian Location")
        i = in_range(to_integer(Axis, "Axis"), 1, MAX_AXES, "Angle axis")
        a = self._angles
        return a[i - 1] if i <= len(a) else 0.0  # type: ignore[return-value]

    def set_Angle(self, Axis: Integer, value: Double) -> None:
        """``loc.Angle(axis) = value``."""
        if self._type != ANGLES:
            raise GplException(NOT_ANGLES, detail="Angle of a Cartesian Location")
        i = in_range(to_integer(Axis, "Axis"), 1, MAX_AXES, "Angle axis")
        a = list(self._angles)
        if len(a) < i:
            a.extend([0.0] * (i - len(a)))
        a[i - 1] = finite(value, "Angle")
        self._angles = tuple(a)

    def Angles(
        self,
        Axis1: Double = 0.0,  # type: ignore[assignment]
        Axis2: Double = 0.0,  # type: ignore[assignment]
        Axis3: Double = 0.0,  # type: ignore[assignment]
        Axis4: Double = 0.0,  # type: ignore[assignment]
        Axis5: Double = 0.0,  # type: ignore[assignment]
        Axis6: Double = 0.0,  # type: ignore[assignment]
        Axis7: Double = 0.0,  # type: ignore[assignment]
        Axis8: Double = 0.0,  # type: ignore[assignment]
        Axis9: Double = 0.0,  # type: ignore[assignment]
        Axis10: Double = 0.0,  # type: ignore[assignment]
        Axis11: Double = 0.0,  # type: ignore[assignment]
        Axis12: Double = 0.0,  # type: ignore[assignment]
    ) -> None:
        """Set every axis value at once (omitted axes 0) and make the Location an Angles one."""
        values = (Axis1, Axis2, Axis3, Axis4, Axis5, Axis6, Axis7, Axis8, Axis9, Axis10, Axis11, Axis12)
        self._angles = tuple(finite(v, "Angles") for v in values)
        self._type = ANGLES

    # -- total position and PosWrtRef ----------------------------------------------------------

    @property
    def Pos(self) -> Location:
        """Total position: through every RefFrame of the chain (Cartesian) or the axis values (Angles)."""
        res = self._copy()
        if self._type == CARTESIAN and self._ref is not None:
            res._pose = self._total_pose(0)
            res._ypr = None
            del res._ref
        return res

    @Pos.setter
    def Pos(self, value: Location) -> None:
        if not isinstance(value, Location):
            raise wrong_object(value, "Pos value", "Location")
        if self._type == CARTESIAN:
            if value._type != CARTESIAN:
                raise GplException(NOT_CARTESIAN, detail="Pos of a Cartesian Location set from an Angles one")
            target = value._total_pose(0)
            if self._ref is None:
                self._pose = target
                self._ypr = value._ypr if value._ref is None else None
            else:
                self._pose = finite_pose(tf.pose_mul(tf.pose_inv(self._ref._total_pose(1)), target), "Pos")
                self._ypr = None
        else:
            if value._type != ANGLES:
                raise GplException(NOT_ANGLES, detail="Pos of an Angles Location set from a Cartesian one")
            self._angles = value._angles

    @property
    def PosWrtRef(self) -> Location:
        """A new Cartesian Location holding only this PosWrtRef (RefFrame Nothing, ZClearance none)."""
        self._need_cartesian("PosWrtRef")
        res = object.__new__(Location)
        res._pose = self._pose
        res._ypr = self._ypr
        return res

    @PosWrtRef.setter
    def PosWrtRef(self, value: Location) -> None:
        self._need_cartesian("PosWrtRef")
        if not isinstance(value, Location):
            raise wrong_object(value, "PosWrtRef value", "Location")
        if value._type != CARTESIAN:
            raise GplException(NOT_CARTESIAN, detail="PosWrtRef set from an Angles Location")
        self._pose = value._total_pose(0)
        self._ypr = value._ypr if value._ref is None else None

    # -- arithmetic ----------------------------------------------------------------------------

    def Mul(self, Location2: Location) -> Location:
        """``self`` combined with ``Location2``: total = Total(self) · Total(Location2).

        Stored as PosWrtRef(self) · Total(Location2) with self's RefFrame (GD mul.htm).
        """
        if self._type != CARTESIAN:
            raise GplException(NOT_CARTESIAN, detail="Mul of an Angles Location")
        if not isinstance(Location2, Location):
            raise wrong_object(Location2, "Mul argument", "Location")
        if Location2._type != CARTESIAN:
            raise GplException(NOT_CARTESIAN, detail="Mul argument is an Angles Location")
        b = Location2._pose if Location2._ref is None else Location2._total_pose(0)
        res = object.__new__(Location)
        d = res.__dict__
        d.update(self.__dict__)
        d["_pose"] = finite_pose(pose_mul(self._pose, b), "Mul")
        d["_ypr"] = None
        return res

    def Inverse(self) -> Location:
        """Inverse of the total position; RefFrame Nothing, every other property copied."""
        if self._type != CARTESIAN:
            raise GplException(NOT_CARTESIAN, detail="Inverse of an Angles Location")
        res = object.__new__(Location)
        d = res.__dict__
        d.update(self.__dict__)
        a = self._pose if self._ref is None else self._total_pose(0)
        a11, a12, a13, a21, a22, a23, a31, a32, a33, x, y, z = a
        d["_pose"] = finite_pose((
            a11, a21, a31, a12, a22, a32, a13, a23, a33,
            -(a11 * x + a21 * y + a31 * z), -(a12 * x + a22 * y + a32 * z), -(a13 * x + a23 * y + a33 * z),
        ), "Inverse")  # fmt: skip
        d["_ypr"] = None
        d.pop("_ref", None)
        return res

    @staticmethod
    def Distance(Location1: Location, Location2: Location) -> Double:
        """Shared: distance in mm between the XYZ of the total positions of two Cartesian Locations."""
        for i, arg in enumerate((Location1, Location2), start=1):
            if not isinstance(arg, Location):
                raise wrong_object(arg, f"Distance argument {i}", "Location")
        a = Location1.total_pose()
        b = Location2.total_pose()
        # math.dist scales instead of squaring, so far-apart points (1e200 mm) do not overflow a
        # square that the distance itself fits; a distance beyond the range is -710.
        d = math.dist(a[9:], b[9:])
        if d == math.inf:
            raise GplException(ARITHMETIC_OVERFLOW, detail="Distance overflows a Double")
        return d  # type: ignore[return-value]

    def Normalize(self) -> None:
        """Remove numerical drift from the rotation of PosWrtRef (re-orthonormalise it).

        A pose whose angles were written (and not computed since) is rebuilt from those angles:
        that is already the drift-free rotation, and the angles keep reading back as written —
        decomposing instead would turn ``XYZ(0,0,0,45,180,30)`` into (0, 180, -15) after a
        Normalize that changed nothing.
        """
        self._need_cartesian("Normalize")
        ypr = self._ypr
        p = self._pose
        if ypr is not None:
            self._pose = tf.pose_from_xyzypr(p[9], p[10], p[11], *ypr)
        else:
            self._pose = tf.pose_orthonormalize(p)

    def Clone(self) -> Location:
        """An independent copy (the RefFrame pointer is copied, not the frame)."""
        return self._copy()

    def Here3(self, Location0: Location, LocationX: Location, LocationXY: Location) -> None:
        """Set the total position from three points: origin, a point on +X, a point in the X-Y plane."""
        for i, p in enumerate((Location0, LocationX, LocationXY), start=1):
            if not isinstance(p, Location):
                raise wrong_object(p, f"Here3 argument {i}", "Location")
        self._need_cartesian("Here3")
        o, px, pxy = (p.total_pose()[9:] for p in (Location0, LocationX, LocationXY))
        # Differences of points beyond the Double range are -710.  Differences so large that their
        # cross product would overflow (points 1e200 mm apart) are first scaled by an exact power of
        # two - the axes need only directions - and the collinearity thresholds are scaled with
        # them, so the test means what it means unscaled; norms use hypot.  Ordinary points are
        # not scaled, so their result is unchanged to the last bit.
        xv = finite_pose(tuple(px[i] - o[i] for i in range(3)), "Here3")
        v = finite_pose(tuple(pxy[i] - o[i] for i in range(3)), "Here3")
        big = max(map(abs, xv + v))
        scale = 1.0
        if big > _HERE3_SCALE_ABOVE:
            scale = 2.0 ** -math.frexp(big)[1]
            xv = tuple(c * scale for c in xv)
            v = tuple(c * scale for c in v)
        nx = math.hypot(*xv)
        zv = [xv[1] * v[2] - xv[2] * v[1], xv[2] * v[0] - xv[0] * v[2], xv[0] * v[1] - xv[1] * v[0]]
        nz = math.hypot(*zv)
        limit = 1e-9 * max(nx, 1.0) if scale == 1.0 else 1e-9 * nx * scale  # scaled: true nx > 1
        if nx < 1e-9 * scale or nz < limit:
            raise GplException(VALUE_OUT_OF_RANGE, detail="Here3 points are coincident or collinear")
        xv = [c / nx for c in xv]
        zv = [c / nz for c in zv]
        yv = [zv[1] * xv[2] - zv[2] * xv[1], zv[2] * xv[0] - zv[0] * xv[2], zv[0] * xv[1] - zv[1] * xv[0]]
        pose = (xv[0], yv[0], zv[0], xv[1], yv[1], zv[1], xv[2], yv[2], zv[2], o[0], o[1], o[2])
        self.Pos = Location.from_pose(pose)  # type: ignore[arg-type]

    # -- members that need a robot ---------------------------------------------------------------

    def Here(self) -> None:
        """Set the total position to the robot's present position (Angles: its present joints)."""
        provider = get_kinematics_provider()
        if self._type == ANGLES:
            self._angles = provider.where_angles()._angles
            return
        where = provider.where()
        self.Pos = where
        self._config = where._config

    def KineSol(self, Mode: Integer = 0, Current: Location | None = None) -> Location:  # type: ignore[assignment]
        """Angles -> Cartesian (forward kinematics) or Cartesian -> Angles (inverse, using Config).

        ``Current`` (an Angles Location) is the solution to stay near; Nothing = the robot's present
        joints.  ``Mode``'s meaning is not documented anywhere we have (gpl-dictionary.md §1,
        [unconfirmed]); it is accepted and not used.
        """
        provider = get_kinematics_provider()
        if self._type == ANGLES:
            return provider.forward(self)
        if Current is not None and not isinstance(Current, Location):
            raise wrong_object(Current, "KineSol reference", "Location")
        if Current is not None and Current._type != ANGLES:
            raise GplException(NOT_ANGLES, detail="KineSol reference must be an Angles Location")
        return provider.inverse(self, self._config, Current)

    def ConveyorLimit(self, Mode: Integer = 0) -> Double:  # type: ignore[assignment]
        """Distance (mm) of this conveyor-relative Location from the conveyor's limits.

        Mode 0: distance left before the downstream limit; Mode 1: distance travelled past the
        upstream limit (both positive inside the window).  See ``refframe.Conveyor``; the mode
        numbering is our decision (the Dictionary page was not available).
        """
        self._need_cartesian("ConveyorLimit")
        ref = self._ref
        if ref is None:
            raise GplException(NOTHING_VALUE, detail="ConveyorLimit of a Location with no RefFrame")
        return ref._conveyor_limit(self, in_range(to_integer(Mode, "Mode"), 0, 1, "ConveyorLimit mode"))

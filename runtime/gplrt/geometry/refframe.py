"""GPL's RefFrame class: basic (Type 0), pallet (Type 1) and conveyor (Type 2) reference frames.

Spec: gpl-classes.md §8, §22.1 items 7 and 9; gpl-dictionary.md §2 (Brooks pallet pages).

* Basic: the frame's pose is the total position of its ``Loc`` (which may itself have a RefFrame,
  so frames chain).
* Pallet: ``Total(Loc) · Trans((row-1)·Pitch(1), (col-1)·Pitch(2), (layer-1)·Pitch(3))`` — rows
  along Loc's X axis, columns along Y, layers along Z (D0:2445-2447).  Indices are 1-based and are
  the cell the frame designates *now*: the Dictionary's examples (PalletRowColLay(2,3,1) gives
  (110, 90) for origin (100, 50) and pitches 10/20) read the position straight after setting them.
  ``PalletNextPos`` steps in ``PalletOrder`` (the first-named index varies fastest) and wraps to
  (1,1,1) after the last cell (D0:2459-2461).
* Conveyor: the belt is modelled Python-side by a ``Conveyor`` registered per conveyor robot
  number.  Pos = nominal · Trans(belt travel, 0, 0) with belt travel = (encoder count -
  ConveyorOffset) · mm_per_count: X points along the belt (D0:2505-2509).  The count moves when
  Python sets or advances it, and, for a belt given ``counts_per_second``, with the controller's
  clock (virtual time in a simulation), so a GPL tracking loop sees the belt run.
  ``Loc`` is not used: "conveyor reference frames cannot be defined with respect to any other
  reference frame" (D0:2521-2524), so a conveyor frame whose ``Loc.RefFrame`` is set is the
  controller's -791 *Conveyor must be base RefFrame* when its position is needed (checked on use:
  a Location cannot know that it is a conveyor frame's Loc when its RefFrame is assigned).

Decisions where the manuals are silent: a new pallet has MaxIndex 1 (a single cell) and Pitch 0 in
every dimension; lowering a MaxIndex below the current index resets that index to 1; a dimension
argument outside 1..3 and an index outside 1..MaxIndex are -707 *Value out-of-range*; pallet
members on a non-pallet frame and conveyor members on a non-conveyor frame are -769; ConveyorOffset
is in encoder counts (it is "the zero position of the belt's encoder"); a conveyor robot number
with no registered Conveyor is -1001 *Undefined robot*.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from gplrt.display import fixed, html_table
from gplrt.geometry import location as _location_module
from gplrt.geometry import transforms as tf
from gplrt.geometry._checks import finite, finite_pose, in_range, not_nothing, text, to_integer, wrong_object
from gplrt.geometry.location import CARTESIAN, MAX_FRAME_DEPTH, Location
from gplrt.geometry.transforms import IDENTITY, Pose
from gplrt.lang.errors import (CONVEYOR_MUST_BE_BASE, FRAME_UNDEFINED_DATA, FRAME_WRONG_TYPE, NOT_CARTESIAN,
                               UNDEFINED_ROBOT, GplException)
from gplrt.lang.exceptions import not_available
from gplrt.lang.gpltypes import Double, Integer, String
from gplrt.session import current_session

BASIC = 0
PALLET = 1
CONVEYOR = 2

#: PalletOrder -> the dimensions (0 row, 1 column, 2 layer) from fastest to slowest (GD palletorder.htm).
PALLET_ORDERS: dict[int, tuple[int, int, int]] = {
    0: (0, 1, 2),  # row, column, layer
    1: (0, 2, 1),  # row, layer, column
    2: (1, 0, 2),  # column, row, layer
    3: (1, 2, 0),  # column, layer, row
    4: (2, 0, 1),  # layer, row, column
    5: (2, 1, 0),  # layer, column, row
}


@dataclass
class Conveyor:
    """A conveyor belt as the simulation sees it ("encoder only" robot, D0:2817-2818).

    ``nominal`` is the belt's nominal transformation in world coordinates (X along travel);
    ``upstream_limit`` and ``downstream_limit`` bound, in mm along the nominal X axis, where the
    robot may track the belt.  The encoder count is ``encoder + counts_per_second · clock()``:
    a stopped belt (``counts_per_second`` 0, the default) reads ``encoder`` and never consults a
    clock; a running one moves with ``clock`` (default: the controller's clock, virtual time in a
    simulation).  ``set_count``/``advance`` move it by hand (a setup file, a test, a latch).
    """

    nominal: Pose = IDENTITY
    mm_per_count: float = 1.0
    encoder: float = 0.0
    upstream_limit: float = -math.inf
    downstream_limit: float = math.inf
    counts_per_second: float = 0.0
    clock: Callable[[], float] | None = field(default=None, repr=False)

    def _now(self) -> float:
        if self.clock is not None:
            return self.clock()
        return current_session().now()

    def count(self) -> float:
        """The encoder count now."""
        rate = self.counts_per_second
        return self.encoder if rate == 0.0 else self.encoder + rate * self._now()

    def set_count(self, counts: float) -> None:
        """Make the encoder read ``counts`` now (a running belt goes on from there)."""
        rate = self.counts_per_second
        self.encoder = counts if rate == 0.0 else counts - rate * self._now()

    def advance(self, counts: float) -> None:
        """Move the belt by ``counts`` encoder counts."""
        self.encoder += counts


_conveyors: dict[int, Conveyor] = {}


def register_conveyor(robot: int, conveyor: Conveyor | None) -> None:
    """Make ``conveyor`` the belt of conveyor robot number ``robot`` (None removes it)."""
    if conveyor is None:
        _conveyors.pop(robot, None)
    else:
        _conveyors[robot] = conveyor


def get_conveyor(robot: int) -> Conveyor:
    """The registered belt of ``robot``, or GPL error -1001 *Undefined robot*."""
    try:
        return _conveyors[robot]
    except KeyError:
        raise GplException(UNDEFINED_ROBOT, detail=f"no conveyor registered as robot {robot}") from None


class RefFrame:
    """GPL ``RefFrame``.  ``New RefFrame`` (no arguments): a basic frame with a new identity ``Loc``."""

    def __init__(self) -> None:
        self._type: int = BASIC
        self._loc: Location | None = Location()
        self._text: str = ""
        self._max: list[int] = [1, 1, 1]
        self._pitch: list[float] = [0.0, 0.0, 0.0]
        self._index: list[int] = [1, 1, 1]
        self._order: int = 0
        self._conveyor_robot: int = 1
        self._conveyor_offset: float = 0.0

    # -- common members ------------------------------------------------------------------------

    @property
    def Type(self) -> Integer:
        """0 basic, 1 pallet, 2 conveyor."""
        return self._type  # type: ignore[return-value]

    @Type.setter
    def Type(self, value: Integer) -> None:
        self._type = in_range(to_integer(value, "Type"), BASIC, CONVEYOR, "RefFrame.Type")

    @property
    def Loc(self) -> Location | None:
        """The Location defining the frame (pallet origin); its RefFrame is the parent frame."""
        return self._loc

    @Loc.setter
    def Loc(self, value: Location | None) -> None:
        if value is not None and not isinstance(value, Location):
            raise wrong_object(value, "RefFrame.Loc", "Location")
        if value is not None and value._type != CARTESIAN:
            raise GplException(NOT_CARTESIAN, detail="RefFrame.Loc must be a Cartesian Location")
        self._loc = value

    @property
    def Text(self) -> String:
        """Free user string."""
        return self._text  # type: ignore[return-value]

    @Text.setter
    def Text(self, value: String) -> None:
        self._text = text(value)

    def Pos(self, location: Location | None = None) -> Location:
        """The frame's total (absolute) position as a new Cartesian Location.

        ``frame.Pos(location)`` is the Dictionary's form (gpl-dictionary §2, a location expressed
        in this frame, meaning unconfirmed; the manuals have only ``frame.Pos``): accepted, and
        -204 *Not implemented* until its meaning is known.

        A basic frame with no parent is exactly its Loc, so angles written into the Loc read back
        from ``frame.Pos`` too (the manual prefers ``frame.Pos`` to ``frame.Loc.Pos``, D0:2422-2427,
        so the two must agree); every other frame position is computed and decomposed.
        """
        if location is not None:
            not_available("RefFrame.Pos(location)", builtin=True)
        res = Location.from_pose(self._total_pose(0))
        if self._type == BASIC and self._loc is not None and self._loc._ref is None:
            res._ypr = self._loc._ypr
        return res

    def PosWrtRef(self, location: Location | None = None) -> Location:
        """The frame's position ignoring further frames (conveyor: the nominal transformation).

        ``frame.PosWrtRef(location)`` (gpl-dictionary §2, meaning unconfirmed) is -204, as for ``Pos``.

        A basic frame's PosWrtRef is its Loc's, written angles included (see ``Pos``).
        """
        if location is not None:
            not_available("RefFrame.PosWrtRef(location)", builtin=True)
        if self._type == CONVEYOR:
            return Location.from_pose(self._conveyor().nominal)
        loc = self._origin()
        if self._type == PALLET:
            return Location.from_pose(self._cell(loc._pose))
        res = Location.from_pose(loc._pose)
        res._ypr = loc._ypr
        return res

    def copy(self) -> RefFrame:
        """Python side (GPL documents no RefFrame.Clone): a copy sharing the same Loc object."""
        twin = RefFrame()
        twin.__dict__.update(self.__dict__)
        twin._max, twin._pitch, twin._index = list(self._max), list(self._pitch), list(self._index)
        return twin

    # -- how it shows (gplrt.display; for reading, never evaluates a conveyor's belt) ---------------

    _KINDS = {BASIC: "basic", PALLET: "pallet", CONVEYOR: "conveyor"}

    def _display_items(self) -> list[tuple[str, str]]:
        """What a person checks: the kind, the Loc (X..Roll), a pallet's cells, a conveyor's robot."""
        loc = self._loc
        items = [("Type", f"{self._type} ({self._KINDS.get(self._type, '?')})"),
                 ("Loc", "Nothing" if loc is None else repr(loc).removeprefix("Location("
                                                                             ).removesuffix(")"))]
        if self._type == PALLET:
            items.append(("PalletIndex/Max", ", ".join(f"{i}/{m}" for i, m in zip(self._index, self._max))))
            items.append(("PalletPitch", ", ".join(fixed(p) for p in self._pitch)))
            items.append(("PalletOrder", str(self._order)))
        elif self._type == CONVEYOR:
            items.append(("ConveyorRobot", str(self._conveyor_robot)))
        if self._text:
            items.append(("Text", repr(self._text)))
        return items

    def __repr__(self) -> str:
        return "RefFrame(" + ", ".join(f"{name}={value}" for name, value in self._display_items()) + ")"

    def _repr_html_(self) -> str:
        return html_table(("", ""), self._display_items(), "RefFrame")

    # -- pallet members --------------------------------------------------------------------------

    def _need_pallet(self, what: str) -> None:
        if self._type != PALLET:
            raise GplException(FRAME_WRONG_TYPE, detail=f"{what} needs a pallet frame (Type 1), this is Type {self._type}")

    @staticmethod
    def _dim(value: Integer) -> int:
        return in_range(to_integer(value, "dimension"), 1, 3, "pallet dimension (1 row, 2 column, 3 layer)") - 1

    def PalletIndex(self, Dimension: Integer) -> Integer:
        """Current index (1..PalletMaxIndex) along row (1), column (2) or layer (3)."""
        self._need_pallet("PalletIndex")
        return self._index[self._dim(Dimension)]  # type: ignore[return-value]

    def set_PalletIndex(self, Dimension: Integer, value: Integer) -> None:
        """``rf.PalletIndex(dim) = n``."""
        self._need_pallet("PalletIndex")
        d = self._dim(Dimension)
        self._index[d] = in_range(to_integer(value, "PalletIndex"), 1, self._max[d], f"PalletIndex({d + 1})")

    def PalletMaxIndex(self, Dimension: Integer) -> Integer:
        """Number of cells along row (1), column (2) or layer (3); 1 = that dimension never steps."""
        self._need_pallet("PalletMaxIndex")
        return self._max[self._dim(Dimension)]  # type: ignore[return-value]

    def set_PalletMaxIndex(self, Dimension: Integer, value: Integer) -> None:
        """``rf.PalletMaxIndex(dim) = n`` (n >= 1)."""
        self._need_pallet("PalletMaxIndex")
        d = self._dim(Dimension)
        n = in_range(to_integer(value, "PalletMaxIndex"), 1, 2**31 - 1, f"PalletMaxIndex({d + 1})")
        self._max[d] = n
        if self._index[d] > n:
            self._index[d] = 1

    def PalletPitch(self, Dimension: Integer) -> Double:
        """Spacing in mm between adjacent rows (1), columns (2) or layers (3); may be negative."""
        self._need_pallet("PalletPitch")
        return self._pitch[self._dim(Dimension)]  # type: ignore[return-value]

    def set_PalletPitch(self, Dimension: Integer, value: Double) -> None:
        """``rf.PalletPitch(dim) = mm``."""
        self._need_pallet("PalletPitch")
        self._pitch[self._dim(Dimension)] = finite(value, "PalletPitch")

    @property
    def PalletOrder(self) -> Integer:
        """Stepping order of PalletNextPos: 0 row,col,layer (default) ... 5 layer,col,row."""
        self._need_pallet("PalletOrder")
        return self._order  # type: ignore[return-value]

    @PalletOrder.setter
    def PalletOrder(self, value: Integer) -> None:
        self._need_pallet("PalletOrder")
        self._order = in_range(to_integer(value, "PalletOrder"), 0, 5, "PalletOrder")

    def PalletRowColLay(self, Row: Integer, Column: Integer, Layer: Integer) -> None:
        """Set all three indices at once (all checked before any is changed)."""
        self._need_pallet("PalletRowColLay")
        new = [
            in_range(to_integer(v, name), 1, self._max[d], f"PalletRowColLay {name}")
            for d, (v, name) in enumerate(((Row, "row"), (Column, "column"), (Layer, "layer")))
        ]
        self._index = new

    def PalletNextPos(self) -> None:
        """Step to the next cell in PalletOrder; after the last cell wrap to (1, 1, 1)."""
        self._need_pallet("PalletNextPos")
        idx = self._index
        for d in PALLET_ORDERS[self._order]:
            if idx[d] < self._max[d]:
                idx[d] += 1
                return
            idx[d] = 1

    def _cell(self, p: Pose) -> Pose:
        i, s = self._index, self._pitch
        step = (i[0] - 1) * s[0], (i[1] - 1) * s[1], (i[2] - 1) * s[2]
        return finite_pose(tf.pose_translate(p, *step), "pallet position")

    # -- conveyor members ------------------------------------------------------------------------

    def _need_conveyor(self, what: str) -> None:
        if self._type != CONVEYOR:
            raise GplException(FRAME_WRONG_TYPE, detail=f"{what} needs a conveyor frame (Type 2), this is Type {self._type}")

    @property
    def ConveyorRobot(self) -> Integer:
        """Number of the (encoder-only) robot that carries the belt's data."""
        self._need_conveyor("ConveyorRobot")
        return self._conveyor_robot  # type: ignore[return-value]

    @ConveyorRobot.setter
    def ConveyorRobot(self, value: Integer) -> None:
        self._need_conveyor("ConveyorRobot")
        self._conveyor_robot = to_integer(value, "ConveyorRobot")

    @property
    def ConveyorOffset(self) -> Double:
        """Encoder count at which the belt is at its zero position."""
        self._need_conveyor("ConveyorOffset")
        return self._conveyor_offset  # type: ignore[return-value]

    @ConveyorOffset.setter
    def ConveyorOffset(self, value: Double) -> None:
        self._need_conveyor("ConveyorOffset")
        self._conveyor_offset = finite(value, "ConveyorOffset")

    def set_encoder(self, counts: float) -> None:
        """Python side: set the encoder count of this frame's conveyor (the simulation's hook)."""
        self._need_conveyor("set_encoder")
        self._conveyor().set_count(finite(counts, "encoder"))

    def _conveyor(self) -> Conveyor:
        return get_conveyor(self._conveyor_robot)

    def _belt_travel(self) -> float:
        c = self._conveyor()
        return (c.count() - self._conveyor_offset) * c.mm_per_count

    def _conveyor_limit(self, loc: Location, mode: int) -> float:
        """Location.ConveyorLimit: find the conveyor at the base of ``loc``'s frame chain."""
        total = loc._total_pose(0)  # first: a looping chain is -770, a misplaced conveyor -791
        frame: RefFrame | None = self
        for _ in range(MAX_FRAME_DEPTH):
            if frame is None:
                break
            if frame._type == CONVEYOR:
                c = frame._conveyor()
                along = finite_pose(tf.pose_mul(tf.pose_inv(c.nominal), total), "ConveyorLimit")[9]
                return c.downstream_limit - along if mode == 0 else along - c.upstream_limit
            nxt = frame._loc
            frame = nxt._ref if nxt is not None else None
        raise GplException(FRAME_WRONG_TYPE, detail="ConveyorLimit of a Location not relative to a conveyor frame")

    # -- the total position ----------------------------------------------------------------------

    def _origin(self) -> Location:
        loc = self._loc
        not_nothing(loc, "RefFrame.Loc")
        assert loc is not None
        if loc._type != CARTESIAN:
            raise GplException(NOT_CARTESIAN, detail="RefFrame.Loc is an Angles Location")
        return loc

    def _total_pose(self, depth: int) -> Pose:
        """Absolute pose of the frame (called by Location through a chain; ``depth`` catches loops)."""
        if depth > MAX_FRAME_DEPTH:
            raise GplException(FRAME_UNDEFINED_DATA, detail="reference frames form a loop")
        t = self._type
        if t == CONVEYOR:
            loc = self._loc
            if loc is not None and loc._ref is not None:
                raise GplException(CONVEYOR_MUST_BE_BASE,
                                   detail="a conveyor frame's Loc has a RefFrame: conveyors are base frames")
            c = self._conveyor()
            return finite_pose(tf.pose_translate(c.nominal, self._belt_travel(), 0.0, 0.0), "conveyor position")
        p = self._origin()._total_pose(depth + 1)
        if t == PALLET:
            p = self._cell(p)
        return p


# Location's annotations name RefFrame, which location.py cannot import (refframe imports it);
# bind the name there so ``typing.get_type_hints`` — and so the transpiler's catalogue — resolves it.
_location_module.RefFrame = RefFrame  # type: ignore[attr-defined]

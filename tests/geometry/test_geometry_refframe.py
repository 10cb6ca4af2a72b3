"""RefFrame: basic chains, pallet indexing (every order, wrap-around), conveyor frames, errors."""

from __future__ import annotations

import itertools

import pytest

from gplrt.geometry import Conveyor, Location, RefFrame, register_conveyor, xyzypr_to_matrix
from gplrt.geometry.refframe import PALLET_ORDERS
from geomtest import conveyor_frame, in_a_frame_loop, xyz as _xyz
from gpltest import code_of as _code


# -- basic frames ------------------------------------------------------------------------------------


def test_ex15_basic_frame_moves_its_locations() -> None:
    """EX-15 (D0:2413-2416): loc1 relative to ref1; ref1.Loc.XYZ(10,20,30,0,180,20)."""
    loc1 = Location()
    ref1 = RefFrame()
    loc1.RefFrame = ref1
    ref1.Loc.XYZ(10, 20, 30, 0, 180, 20)
    assert ref1.Type == 0
    assert _xyz(loc1.Pos) == (10, 20, 30, 0, 180, 20)
    assert _xyz(loc1) == (0, 0, 0, 0, 0, 0)  # PosWrtRef unchanged
    loc1.XYZ(1, 0, 0)  # 1 mm along the frame's X (rotated by 20 deg, flipped by pitch 180)
    p = loc1.Pos
    assert (p.X, p.Y, p.Z) == pytest.approx((10 - 0.9396926207859084, 20 + 0.3420201433256687, 30), abs=1e-12)


def test_frame_chain_three_deep_pos_and_poswrtref() -> None:
    f3, f2, f1 = RefFrame(), RefFrame(), RefFrame()
    f3.Loc.XYZ(100, 0, 0, 0, 0, 90)
    f2.Loc.XYZ(10, 0, 0)
    f2.Loc.RefFrame = f3
    f1.Loc.XYZ(0, 1, 0, 0, 0, 90)
    f1.Loc.RefFrame = f2
    loc = Location()
    loc.XYZ(2, 0, 0)
    loc.RefFrame = f1
    # f3 turns +X into +Y: f2 origin (100,10,0); f1 origin (99,10,0) rotated 180; loc 2 mm along -X
    assert _xyz(f1.Pos()) == (99, 10, 0, 0, 0, 180)
    assert _xyz(f1.PosWrtRef()) == (0, 1, 0, 0, 0, 90)
    assert _xyz(loc.Pos) == (97, 10, 0, 0, 0, 180)
    # moving the root frame moves everything
    f3.Loc.X = 200
    assert loc.Pos.X == 197.0
    m = xyzypr_to_matrix(200, 0, 0, 0, 0, 90) @ xyzypr_to_matrix(10, 0, 0, 0, 0, 0)
    m = m @ xyzypr_to_matrix(0, 1, 0, 0, 0, 90) @ xyzypr_to_matrix(2, 0, 0, 0, 0, 0)
    assert loc.matrix() == pytest.approx(m, abs=1e-12)


def test_basic_frame_pos_reads_the_angles_written_into_its_loc() -> None:
    """frame.Pos / frame.PosWrtRef agree with frame.Loc.Pos / .PosWrtRef (D0:2422-2427), singular too."""
    f = RefFrame()
    f.Loc.XYZ(10, 20, 30, 30, 0, 60)
    assert _xyz(f.Pos()) == _xyz(f.Loc.Pos) == (10, 20, 30, 30, 0, 60)
    assert _xyz(f.PosWrtRef()) == _xyz(f.Loc.PosWrtRef) == (10, 20, 30, 30, 0, 60)
    parent = RefFrame()
    parent.Loc.XYZ(1, 0, 0)
    f.Loc.RefFrame = parent  # now computed: the rule of transforms (rotation in roll)
    assert _xyz(f.Pos()) == _xyz(f.Loc.Pos) == (11, 20, 30, 0, 0, 90)
    assert _xyz(f.PosWrtRef()) == (10, 20, 30, 30, 0, 60)


def test_frame_loc_must_be_cartesian_and_not_nothing() -> None:
    f = RefFrame()
    a = Location()
    a.Angles(1, 2)
    assert _code(setattr, f, "Loc", a) == -762
    f.Loc = None
    assert _code(f.Pos) == -782
    assert _code(setattr, f, "Type", 3) == -707


# -- pallet frames -------------------------------------------------------------------------------------


def _pallet(rows: int = 3, cols: int = 3, layers: int = 1) -> RefFrame:
    """The Dictionary's example pallet (origin (100,50,-80), pitches 10/20) plus a 5 mm layer pitch."""
    rf = RefFrame()
    rf.Type = 1
    rf.Loc.XYZ(100, 50, -80, 0, 0, 0)
    for d, (n, p) in enumerate(((rows, 10.0), (cols, 20.0), (layers, 5.0)), start=1):
        rf.set_PalletPitch(d, p)
        rf.set_PalletMaxIndex(d, n)
    return rf


def _follower(rf: RefFrame) -> Location:
    loc = Location()
    loc.RefFrame = rf
    return loc


def test_dictionary_pallet_examples() -> None:
    """GD palletpitch.htm, palletindex.htm, palletorder.htm."""
    rf = _pallet()
    loc1 = _follower(rf)
    rf.PalletRowColLay(2, 3, 1)
    assert (loc1.Pos.X, loc1.Pos.Y) == (110, 90)
    rf2 = _pallet()
    loc2 = _follower(rf2)
    rf2.set_PalletIndex(2, 2)
    assert (loc2.Pos.X, loc2.Pos.Y) == (100, 70)
    rf3 = _pallet()
    loc3 = _follower(rf3)
    rf3.PalletOrder = 2
    rf3.PalletRowColLay(3, 1, 1)
    rf3.PalletNextPos()
    assert [rf3.PalletIndex(d) for d in (1, 2, 3)] == [3, 2, 1]
    assert (loc3.Pos.X, loc3.Pos.Y) == (120, 70)


def test_new_pallet_defaults() -> None:
    rf = RefFrame()
    rf.Type = 1
    assert [rf.PalletIndex(d) for d in (1, 2, 3)] == [1, 1, 1]
    assert [rf.PalletMaxIndex(d) for d in (1, 2, 3)] == [1, 1, 1]
    assert rf.PalletOrder == 0
    rf.PalletNextPos()  # a single-cell pallet stays put
    assert [rf.PalletIndex(d) for d in (1, 2, 3)] == [1, 1, 1]


def test_default_order_table_row_first_with_wrap() -> None:
    """Order 0 on a 2x2x2 pallet: row varies fastest, then column, then layer; wraps to (1,1,1)."""
    rf = _pallet(2, 2, 2)
    seen = []
    for _ in range(9):
        seen.append(tuple(rf.PalletIndex(d) for d in (1, 2, 3)))
        rf.PalletNextPos()
    assert seen == [
        (1, 1, 1), (2, 1, 1), (1, 2, 1), (2, 2, 1),
        (1, 1, 2), (2, 1, 2), (1, 2, 2), (2, 2, 2),
        (1, 1, 1),
    ]  # fmt: skip


ORDER_NAMES = {0: "row,col,layer", 1: "row,layer,col", 2: "col,row,layer", 3: "col,layer,row", 4: "layer,row,col", 5: "layer,col,row"}


@pytest.mark.parametrize("order", range(6))
def test_every_order_visits_every_cell_in_order_and_wraps(order: int) -> None:
    """Expected sequence built independently: nested loops, first-named dimension innermost."""
    sizes = {"row": 3, "col": 2, "layer": 4}
    names = ORDER_NAMES[order].split(",")
    expected = []
    for slow, mid, fast in itertools.product(*(range(1, sizes[n] + 1) for n in reversed(names))):
        cell = dict(zip(reversed(names), (slow, mid, fast)))
        expected.append((cell["row"], cell["col"], cell["layer"]))
    rf = _pallet(3, 2, 4)
    rf.PalletOrder = order
    loc = _follower(rf)
    got, positions = [], []
    for _ in range(2 * len(expected)):  # two full passes: wrap-around
        got.append(tuple(rf.PalletIndex(d) for d in (1, 2, 3)))
        p = loc.Pos
        positions.append((p.X, p.Y, p.Z))
        rf.PalletNextPos()
    assert got == expected * 2
    assert positions[: len(expected)] == [(100 + (r - 1) * 10, 50 + (c - 1) * 20, -80 + (la - 1) * 5) for r, c, la in expected]
    assert PALLET_ORDERS[order] == tuple({"row": 0, "col": 1, "layer": 2}[n] for n in names)


def test_pallet_axes_follow_the_loc_orientation() -> None:
    """Rows along Loc's X, columns along Loc's Y, layers along Loc's Z (D0:2445-2447)."""
    rf = _pallet(3, 3, 3)
    rf.Loc.XYZ(0, 0, 0, 90, 0, 0)  # X -> world Y, Y -> world -X
    rf.PalletRowColLay(2, 3, 2)
    assert _xyz(rf.Pos()) == (-40, 10, 5, 0, 0, 90)
    assert _xyz(rf.PosWrtRef()) == (-40, 10, 5, 0, 0, 90)


def test_pallet_on_a_frame_and_a_location_on_the_pallet() -> None:
    base = RefFrame()
    base.Loc.XYZ(1000, 0, 0)
    rf = _pallet()
    rf.Loc.RefFrame = base
    rf.PalletRowColLay(3, 2, 1)
    loc = _follower(rf)
    loc.XYZ(0, 0, 7)
    assert (loc.Pos.X, loc.Pos.Y, loc.Pos.Z) == (1120, 70, -73)
    assert (rf.PosWrtRef().X, rf.Pos().X) == (120, 1120)


def test_negative_pitch_steps_backwards() -> None:
    rf = _pallet(3, 1, 1)
    rf.set_PalletPitch(1, -10)
    rf.PalletNextPos()
    assert rf.Pos().X == 90.0


def test_lowering_max_index_resets_the_index() -> None:
    rf = _pallet(3, 3, 1)
    rf.PalletRowColLay(3, 2, 1)
    rf.set_PalletMaxIndex(1, 2)
    assert [rf.PalletIndex(d) for d in (1, 2, 3)] == [1, 2, 1]


def test_pallet_errors() -> None:
    rf = _pallet(3, 3, 1)
    for bad in ((rf.set_PalletIndex, 1, 4), (rf.set_PalletIndex, 1, 0), (rf.set_PalletIndex, 3, 2),
                (rf.PalletIndex, 0), (rf.PalletIndex, 4), (rf.PalletPitch, 4), (rf.set_PalletMaxIndex, 2, 0),
                (rf.PalletRowColLay, 1, 4, 1), (rf.PalletRowColLay, 0, 1, 1)):  # fmt: skip
        assert _code(*bad) == -707
    assert _code(setattr, rf, "PalletOrder", 6) == -707
    rf.PalletRowColLay(2, 2, 1)
    assert _code(rf.PalletRowColLay, 3, 3, 9) == -707
    assert [rf.PalletIndex(d) for d in (1, 2, 3)] == [2, 2, 1]  # a rejected call changes nothing


def test_pallet_members_on_a_basic_frame_raise_769() -> None:
    rf = RefFrame()
    for fn in (lambda: rf.PalletIndex(1), lambda: rf.set_PalletIndex(1, 1), lambda: rf.PalletMaxIndex(1),
               lambda: rf.set_PalletPitch(1, 1.0), lambda: rf.PalletOrder, lambda: rf.PalletNextPos(),
               lambda: rf.PalletRowColLay(1, 1, 1), lambda: rf.ConveyorOffset, lambda: rf.ConveyorRobot):  # fmt: skip
        assert _code(fn) == -769


# -- conveyor frames --------------------------------------------------------------------------------


@pytest.fixture
def belt() -> Conveyor:
    c = Conveyor(
        nominal=Location.XYZValue(500, -200, 10, 90, 0, 0).pose_wrt_ref,
        mm_per_count=0.01,
        upstream_limit=-100.0,
        downstream_limit=400.0,
    )
    register_conveyor(3, c)  # conftest.py unregisters it
    return c


def _conveyor_frame() -> RefFrame:
    """A frame on the ``belt`` fixture's conveyor whose zero is 1000 counts along it."""
    rf = conveyor_frame(3)
    rf.ConveyorOffset = 1000
    return rf


def test_conveyor_frame_moves_with_the_encoder(belt: Conveyor) -> None:
    rf = _conveyor_frame()
    part = Location()
    part.XYZ(0, 5, 0)
    part.RefFrame = rf
    rf.set_encoder(1000)  # at the zero position
    assert _xyz(rf.Pos()) == (500, -200, 10, 0, 0, 90)
    assert (part.Pos.X, part.Pos.Y) == (495, -200)
    rf.set_encoder(21000)  # 200 mm along the belt's X = world +Y
    assert (part.Pos.X, part.Pos.Y) == (495, 0)
    belt.advance(5000)
    assert part.Pos.Y == 50.0
    assert _xyz(rf.PosWrtRef()) == (500, -200, 10, 0, 0, 90)  # the nominal transformation


def test_conveyor_limit(belt: Conveyor) -> None:
    rf = _conveyor_frame()
    part = Location()
    part.RefFrame = rf
    rf.set_encoder(1000 + 15000)  # 150 mm downstream of the zero position
    assert part.ConveyorLimit(0) == pytest.approx(250.0, abs=1e-9)
    assert part.ConveyorLimit(1) == pytest.approx(250.0, abs=1e-9)
    rf.set_encoder(1000 + 45000)  # 450 mm: 50 mm beyond the downstream limit
    assert part.ConveyorLimit(0) == pytest.approx(-50.0, abs=1e-9)
    # a Location on a frame that sits on the conveyor is conveyor-relative too
    tray = RefFrame()
    tray.Loc.XYZ(10, 0, 0)
    tray.Loc.RefFrame = rf
    on_tray = Location()
    on_tray.RefFrame = tray
    assert on_tray.ConveyorLimit(0) == pytest.approx(-60.0, abs=1e-9)


def test_conveyor_errors(belt: Conveyor) -> None:
    plain = Location()
    assert _code(plain.ConveyorLimit) == -782
    plain.RefFrame = RefFrame()
    assert _code(plain.ConveyorLimit) == -769
    rf = _conveyor_frame()
    rf.ConveyorRobot = 9
    assert _code(rf.Pos) == -1001
    assert _code(RefFrame().set_encoder, 5) == -769
    rf.ConveyorRobot = 3
    part = Location()
    part.RefFrame = rf
    assert _code(part.ConveyorLimit, 2) == -707


def test_a_running_belt_moves_with_its_clock() -> None:
    """counts_per_second: the encoder runs with the clock; set_encoder rebases, the belt goes on."""
    t = [10.0]
    c = Conveyor(mm_per_count=0.5, counts_per_second=200.0, clock=lambda: t[0])
    register_conveyor(5, c)
    rf = conveyor_frame(5)
    part = Location()
    part.RefFrame = rf
    rf.set_encoder(0)  # belt at its zero position at t = 10 s
    assert part.Pos.X == 0.0
    t[0] = 12.5  # 2.5 s x 200 counts/s x 0.5 mm = 250 mm
    assert part.Pos.X == 250.0
    c.advance(100)  # a hand-made jump of 50 mm on top
    assert part.Pos.X == 300.0
    rf.ConveyorOffset = 600  # the zero position is 600 counts = 300 mm downstream
    assert part.Pos.X == 0.0


def test_a_running_belt_follows_the_simulation_virtual_clock() -> None:
    """Without an explicit clock the belt runs on the controller's (virtual) time."""
    from gplrt.sim import Simulation

    c = Conveyor(mm_per_count=0.01, counts_per_second=10_000.0)  # 100 mm/s
    register_conveyor(6, c)
    with Simulation() as sim:
        rf = conveyor_frame(6)
        rf.set_encoder(0)
        start = sim.now()
        sim.run_for(1.5)
        assert sim.now() - start == pytest.approx(1.5)
        assert rf.Pos().X == pytest.approx(150.0, abs=1e-9)


def test_a_conveyor_frame_relative_to_another_frame_is_791(belt: Conveyor) -> None:
    """D0:2521-2524: conveyor frames cannot be defined relative to another frame (-791)."""
    rf = _conveyor_frame()
    part = Location()
    part.RefFrame = rf
    rf.Loc.RefFrame = RefFrame()
    assert _code(rf.Pos) == -791
    assert _code(lambda: part.Pos) == -791
    assert _code(part.ConveyorLimit) == -791
    rf.Loc.RefFrame = None
    p = rf.Pos()  # encoder 0, offset 1000: 10 mm upstream along the belt's X = world -Y
    assert (p.X, p.Y, p.Z) == pytest.approx((500.0, -210.0, 10.0), abs=1e-12)


def test_conveyor_limit_through_a_looping_chain_is_770() -> None:
    loc = in_a_frame_loop()
    assert _code(loc.ConveyorLimit) == -770

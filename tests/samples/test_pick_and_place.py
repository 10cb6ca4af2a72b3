"""samples/pick_and_place: transpiled, run in virtual time against a scripted conveyor and gripper.

The expected console text and every pose are computed here from the cell's documented geometry
(Globals.gpo header: pallet frame at (450, -120, 100) turned 30 deg about Z, pitches 45/60/25 mm,
3 x 2 x 2 cells filled rows first; pick at (250, 300, 130); clearance at world Z 250; the gripper
points along the frame's rows), never copied from a run.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gpltest import SAMPLES, Transpiled, transpile
from gplrt.controller.signals import IoMap
from gplrt.sim import Simulation

PALLET_ORIGIN = np.array([450.0, -120.0, 100.0])
PALLET_YAW = 30.0
PITCH = (45.0, 60.0, 25.0)
SHAPE = (3, 2, 2)  # rows, columns, layers
PARTS = 8
PICK = np.array([250.0, 300.0, 130.0])
CLEAR_Z = 250.0

DOUT_CLOSE, DOUT_REQUEST = 1, 2
DIN_PRESENT, DIN_CLOSED = 10001, 10002


def rz(deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def ry(deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def hand_rotation(yaw: float) -> np.ndarray:
    """GPL (yaw, 90, 180): Z-Y-Z Euler angles of a PF400 hand that points horizontally along yaw."""
    return rz(yaw) @ ry(90.0) @ rz(180.0)


def cell_order() -> list[tuple[int, int, int]]:
    """Pallet cells in PalletNextPos order: rows vary fastest, then columns, then layers."""
    return [(r, c, l) for l in range(1, SHAPE[2] + 1) for c in range(1, SHAPE[1] + 1)
            for r in range(1, SHAPE[0] + 1)]


def cell_position(row: int, col: int, layer: int) -> np.ndarray:
    offset = np.array([(row - 1) * PITCH[0], (col - 1) * PITCH[1], (layer - 1) * PITCH[2]])
    return PALLET_ORIGIN + rz(PALLET_YAW) @ offset


def scripted_io(*, gripper_works: bool = True, feeder_works: bool = True) -> IoMap:
    """The conveyor and the gripper as the cell's wiring diagram describes them."""
    io = IoMap()
    if feeder_works:
        # a part arrives 0.2 s after it is requested and is gone 0.3 s after the jaws close
        io.when_output(DOUT_REQUEST, True).set_input(DIN_PRESENT, True, after=0.2)
        io.when_output(DOUT_CLOSE, True).set_input(DIN_PRESENT, False, after=0.3)
    if gripper_works:
        io.when_output(DOUT_CLOSE, True).set_input(DIN_CLOSED, True, after=0.15)
        io.when_output(DOUT_CLOSE, False).set_input(DIN_CLOSED, False, after=0.1)
    return io


@pytest.fixture(scope="module")
def sample(tmp_path_factory: pytest.TempPathFactory) -> Transpiled:
    return transpile(SAMPLES / "pick_and_place", tmp_path_factory.mktemp("pick_and_place"))


def run(sample: Transpiled, io: IoMap) -> Simulation:
    sim = Simulation(capture=True, io=io)
    sample.package.main(sim)
    return sim


def test_transpiles_without_diagnostics(sample: Transpiled) -> None:
    sample.assert_clean()


def test_places_eight_parts_in_pallet_order_and_reports_each(sample: Transpiled) -> None:
    sim = run(sample, scripted_io())
    expected = ["palletising cell: 8 parts onto outfeed pallet"]
    for n, (r, c, l) in enumerate(cell_order()[:PARTS], start=1):
        expected.append(f"placed part {n} at row {r} column {c} layer {l}")
    expected.append("cell done: 8 parts placed, 8 requested")
    assert sim.console.output == "\n".join(expected) + "\n"
    assert sim.controller.error_log == []


def test_final_pose_is_the_depart_point_above_the_last_cell(sample: Transpiled) -> None:
    sim = run(sample, scripted_io())
    robot = sim.robots[1]
    T = robot.forward(robot.joints_at(sim.now()))
    r, c, l = cell_order()[PARTS - 1]
    expected_xyz = cell_position(r, c, l)
    expected_xyz[2] = CLEAR_Z  # ZWorld clearance replaces the world Z
    assert np.max(np.abs(T[:3, 3] - expected_xyz)) < 1e-6
    assert np.max(np.abs(T[:3, :3] - hand_rotation(PALLET_YAW))) < 1e-9


def test_gripper_closes_only_at_the_pick_and_opens_only_on_the_right_cell(sample: Transpiled) -> None:
    io = scripted_io()
    sim = run(sample, io)
    robot = sim.robots[1]
    changes = [ch for ch in io.trace if ch.kind == "DIO" and ch.signal == DOUT_CLOSE and ch.source == "gpl"]
    closes = [ch.time for ch in changes if ch.value]
    opens = [ch.time for ch in changes if not ch.value]
    assert len(closes) == PARTS and len(opens) == PARTS
    for t in closes:
        T = robot.forward(robot.joints_at(t))
        assert np.max(np.abs(T[:3, 3] - PICK)) < 1e-6
        assert np.max(np.abs(T[:3, :3] - hand_rotation(90.0))) < 1e-9
    for t, cell in zip(opens, cell_order()):
        T = robot.forward(robot.joints_at(t))
        assert np.max(np.abs(T[:3, 3] - cell_position(*cell))) < 1e-6
    # every part was requested from the conveyor, and it was present before the robot went down
    requests = [ch.time for ch in io.trace if ch.signal == DOUT_REQUEST and ch.value and ch.source == "gpl"]
    arrivals = [ch.time for ch in io.trace if ch.signal == DIN_PRESENT and ch.value]
    assert len(requests) == PARTS and len(arrivals) == PARTS
    for req, arr, close in zip(requests, arrivals, closes):
        assert math.isclose(arr - req, 0.2, abs_tol=1e-9)
        assert close > arr


def test_stuck_gripper_is_retried_once_then_stops_the_cell(sample: Transpiled) -> None:
    sim = run(sample, scripted_io(gripper_works=False))
    assert sim.console.output.splitlines() == [
        "palletising cell: 8 parts onto outfeed pallet",
        "regrip: gripper did not switch",
        "cell stopped: error -3100 gripper did not switch",
    ]


def test_missing_part_times_out_with_the_feeder_error(sample: Transpiled) -> None:
    sim = run(sample, scripted_io(feeder_works=False))
    lines = sim.console.output.splitlines()
    assert lines[-1] == "cell stopped: error -3101 no part after 5000 ms"
    assert sim.now() >= 5.0  # the 5 s timeout elapsed in controller time

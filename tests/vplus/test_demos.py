"""The corpus's V+ demos run unchanged on a simulated Viper s650 (issue 21, milestone 5).

Each demo is read in place from ``../shared/corpus/vplus/robot-sandbox`` (``$GPL_CORPUS``) and
copied beside a data file the test writes: the globals a V+ data file would load (``p1``, ``dx``,
``#safe`` ...) as ``.LOCATIONS``/``.REALS`` sections, with values the robot reaches.  The test works
out independently where the program must put the tool (the demo's own arithmetic, in numpy, with
V+'s ``TRANS(x,y,z,yaw,pitch,roll) = Trans * Rz(yaw) * Ry(pitch) * Rz(roll)``, User's Guide
L5987-6053) and checks that the robot stopped at each such pose, in order: the joints at the end
of each motion, put through the robot's kinematics, match to 1e-6.
"""

from __future__ import annotations

import math
import shutil
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np

from gpl2py.notebook import Cell
from gplrt.motion.kinematics import robot_model
from gpltest import corpus_dir
from vplusoracle import trans

ROBOT = "VIPER-S650"




def _run_demo(tmp_path: Path, demo: str, data: str, io: Callable[[Cell], None] | None = None) -> Cell:
    folder = tmp_path / "demo"
    folder.mkdir()
    src = corpus_dir() / "vplus" / "robot-sandbox" / "robot-programs" / demo
    shutil.copy(src, folder / src.name)
    (folder / "zz_data.v2").write_text(data)  # (after the demo: its first program is the start)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (the dialect warnings)
        cell = Cell.load(folder, robot=ROBOT, echo=False, cache_dir=tmp_path / "cache")
    if io is not None:
        io(cell)
    assert cell.run_main() == 0, cell.sim.console.output
    return cell


def _reached(cell: Cell) -> list[np.ndarray]:
    """The tool pose at the end of each motion the robot made, by the robot's kinematics."""
    state = cell.sim.robot(1)
    model = robot_model(ROBOT)
    poses = []
    with state.lock:
        for seg in state.queue.history:
            poses.append(model.forward(state.queue.joints_at(float(seg.end))))
    return poses


def _assert_visits_in_order(reached: list[np.ndarray], expected: list[np.ndarray]) -> None:
    i = 0
    for n, want in enumerate(expected):
        while i < len(reached) and np.abs(reached[i] - want).max() > 1e-6:
            i += 1
        assert i < len(reached), f"pose {n} of {len(expected)} never reached:\n{want.round(6)}"
        i += 1


def test_hanoi_moves_every_disc_to_the_poses_the_recursion_computes(tmp_path: Path) -> None:
    p1 = (500.0, -150.0, 250.0)
    dx, dz, n, ang = 150.0, 20.0, 3, 90.0
    data = (".LOCATIONS\n"
            f"p1      {p1[0]} {p1[1]} {p1[2]} 0 180 0\n"
            "#safe   0 -30 150 0 60 0\n"
            ".END\n"
            f".REALS\ndx {dx}\ndz {dz}\nn {n}\nang {ang}\n.END\n")
    cell = _run_demo(tmp_path, "demos/hanoi.v2", data)
    # the towers: RZ(ang):TRANS(k*dx,0,0):RZ(-ang):p1 is p1 moved by k*dx along RZ(ang)'s X axis
    towers = [np.array(p1) + k * dx * np.array([math.cos(math.radians(ang)), math.sin(math.radians(ang)), 0])
              for k in range(3)]
    tops = [towers[0][2] + dz * n, towers[1][2], towers[2][2]]  # where the next disc goes (vf.*'s Z)
    expected: list[np.ndarray] = []

    def move(src: int, dst: int) -> None:
        tops[src] -= dz
        expected.append(trans(towers[src][0], towers[src][1], tops[src], 0, 180, 0))
        expected.append(trans(towers[dst][0], towers[dst][1], tops[dst], 0, 180, 0))
        tops[dst] += dz

    def hanoi(k: int, src: int, dst: int, aux: int) -> None:
        if k == 1:
            move(src, dst)
        else:
            hanoi(k - 1, src, aux, dst)
            move(src, dst)
            hanoi(k - 1, aux, dst, src)

    hanoi(n, 0, 1, 2)  # CALL muta.discuri(vf.a, vf.b, vf.c, n): source, destination, auxiliary
    assert len(expected) == 2 * (2 ** n - 1)
    safe = robot_model(ROBOT).forward([0, -30, 150, 0, 60, 0])
    _assert_visits_in_order(_reached(cell), [safe, *expected, safe])


SAFE = "#safe   0 -30 150 0 60 0\n"


def test_pick_and_place_stacks_the_pallet_where_the_program_computes(tmp_path: Path) -> None:
    st, pal = (450.0, -200.0, 200.0), (450.0, 150.0, 200.0)
    dx, dy, dz = 40.0, 40.0, 15.0
    data = (f".LOCATIONS\nst {st[0]} {st[1]} {st[2]} 0 180 0\npal {pal[0]} {pal[1]} {pal[2]} 0 180 0\n{SAFE}.END\n"
            f".REALS\ndx {dx}\ndy {dy}\ndz {dz}\n.END\n")
    cell = _run_demo(tmp_path, "pickplace/pal.ideal.v2", data)
    nl, nc, nn = 3, 2, 2
    total = nl * nc * nn
    expected = []
    for p in range(1, total + 1):  # the program's own arithmetic (order L-C-N)
        r = total - p + 1
        i, j, k = (p - 1) // (nc * nn), ((p - 1) // nn) % nc, (p - 1) % nn
        expected.append(trans(st[0], st[1], st[2] + (r - 1) * dz, 0, 180, 0))
        expected.append(trans(pal[0] + i * dx, pal[1] + j * dy, pal[2] + k * dz, 0, 180, 0))
    assert cell.sim.console.output.splitlines()[:3] == ["0, 0, 0", "0, 0, 1", "0, 1, 0"]  # TYPE i, ", ", j ...
    safe = robot_model(ROBOT).forward([0, -30, 150, 0, 60, 0])
    _assert_visits_in_order(_reached(cell), [safe, *expected, safe])


def test_belt_demo_waits_for_the_pallet_sensor_and_places_each_part(tmp_path: Path) -> None:
    st, conv = (450.0, -200.0, 200.0), (450.0, 200.0, 200.0)
    d, h = 50.0, 10.0
    data = (f".LOCATIONS\nst {st[0]} {st[1]} {st[2]} 0 180 0\nconv {conv[0]} {conv[1]} {conv[2]} 0 180 0\n"
            f"{SAFE}.END\n.REALS\nd {d}\nh {h}\n.END\n")

    def conveyor(cell: Cell) -> None:  # the belt (output 1) brings a pallet to the sensor (input 1001)
        cell.io.when_output(1, True).set_input(10001, True, after=3.0)
        cell.io.when_output(1, False).set_input(10001, False)

    cell = _run_demo(tmp_path, "demos/belt.v2", data, conveyor)
    n = 12
    expected = []
    for i in range(1, n // 4 + 1):
        for j in range(1, 5):
            p = 4 * (i - 1) + j
            expected.append(trans(st[0], st[1], st[2] + h * (n - p), 0, 180, 0))
            expected.append(trans(conv[0], conv[1] + (j % 2) * d - d / 2, conv[2] + (j // 2) * h, 0, 180, 0))
    out = cell.sim.console.output.splitlines()
    assert out.count("Pallet detected.") == 3 and out[-1] == "Done."
    _assert_visits_in_order(_reached(cell), expected)

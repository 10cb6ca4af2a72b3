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
from pathlib import Path

import numpy as np

from gpl2py.notebook import Cell
from gplrt.motion.kinematics import robot_model
from gpltest import corpus_dir

ROBOT = "VIPER-S650"


def trans(x: float, y: float, z: float, yaw: float = 0, pitch: float = 0, roll: float = 0) -> np.ndarray:
    def rz(a: float) -> np.ndarray:
        c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
        return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])

    def ry(a: float) -> np.ndarray:
        c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
        return np.array([[c, 0, s, 0], [0, 1, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1]])

    t = np.eye(4)
    t[:3, 3] = (x, y, z)
    return t @ rz(yaw) @ ry(pitch) @ rz(roll)


def _run_demo(tmp_path: Path, demo: str, data: str) -> Cell:
    folder = tmp_path / "demo"
    folder.mkdir()
    src = corpus_dir() / "vplus" / "robot-sandbox" / "robot-programs" / demo
    shutil.copy(src, folder / src.name)
    (folder / "zz_data.v2").write_text(data)  # (after the demo: its first program is the start)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (the dialect warnings)
        cell = Cell.load(folder, robot=ROBOT, echo=False, cache_dir=tmp_path / "cache")
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

"""Robots from URDF (docs/design/robots.md): the Viper s650, Cobra s600 and the TMs, by name.

Forward kinematics against Pinocchio on the URDF directly, inverse round trips for every
configuration, the Cobra's mimic joint, limits from the URDF and the controller's error codes,
and a GPL program that moves each robot under ``gpl2py run --robot``."""

from __future__ import annotations

import itertools
import math
import re
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from gplrt.controller.pdb import default_database, model_names
from gplrt.geometry.transforms import matrix_to_xyzypr
from gplrt.lang.errors import (
    INVALID_CARTESIAN,
    JOINT_OUT_OF_RANGE,
    POSITION_TOO_CLOSE,
    POSITION_TOO_FAR,
    GplException,
)
from gplrt.motion.kinematics import (
    GPL_ABOVE,
    GPL_BELOW,
    GPL_FLIP,
    GPL_LEFTY,
    GPL_NOFLIP,
    GPL_RIGHTY,
    GPL_SINGLE,
    RobotModel,
    robot_model,
)
from gpltest import REPO, in_process, module_src, write_project

URDF_DIR = REPO / "runtime" / "gplrt" / "data" / "robots" / "urdf"
FILES = {"VIPER-S650": ("adept_viper_s650.urdf", "tool0"), "COBRA-S600": ("adept_cobra_s600.urdf", "tool0"),
         "TM5-700": ("tm5-700-nominal.urdf", "flange"), "TM5-900": ("tm5-900-nominal.urdf", "flange"),
         "TM12": ("tm12-nominal.urdf", "flange"), "TM14": ("tm14-nominal.urdf", "flange")}
SIX_AXES = ["VIPER-S650", "TM5-700", "TM5-900", "TM12", "TM14"]
ALL = [*SIX_AXES, "COBRA-S600"]
ARM_CONFIGS = [r | a | f for r, a, f in itertools.product((GPL_RIGHTY, GPL_LEFTY), (GPL_ABOVE, GPL_BELOW),
                                                          (GPL_NOFLIP, GPL_FLIP))]
N_POSES = 60


def _random_joints(model: RobotModel, rng: np.random.Generator) -> list[float]:
    """Joints uniformly inside the soft limits (a margin of 2 % of each range)."""
    return [rng.uniform(lo + 0.02 * (hi - lo), hi - 0.02 * (hi - lo)) for lo, hi in zip(model.lower_limits, model.upper_limits)]


def _pin_flange(name: str, joints: list[float]) -> np.ndarray:
    """The flange pose (mm) Pinocchio computes on the URDF itself, every joint by name (the
    Cobra's mimic joint following ``inner_joint`` as the URDF says)."""
    file, frame = FILES[name]
    model = pin.buildModelFromUrdf(str(URDF_DIR / file))
    data = model.createData()
    q = pin.neutral(model)
    names = [n for n in model.names[1:] if n != "flyover_cable_joint"]
    values = dict(zip(names, joints, strict=True))
    if "flyover_cable_joint" in model.names:
        values["flyover_cable_joint"] = values["inner_joint"]
    for jname, v in values.items():
        jid = model.getJointId(jname)
        q[model.joints[jid].idx_q] = v / 1000.0 if "prismatic" in jname else math.radians(v)
    pin.framesForwardKinematics(model, data, q)
    T = data.oMf[model.getFrameId(frame)].homogeneous
    T[:3, 3] *= 1000.0
    return T


def test_the_robots_are_in_the_catalogue() -> None:
    for name in ALL:
        assert name in model_names()
        assert robot_model(name.lower()).axis_count == (4 if name == "COBRA-S600" else 6)


@pytest.mark.parametrize("name", ALL)
def test_forward_kinematics_is_pinocchios_on_the_urdf(name: str) -> None:
    model = robot_model(name)
    rng = np.random.default_rng(21)
    for _ in range(50):
        q = _random_joints(model, rng)
        assert np.allclose(model.forward(q), _pin_flange(name, q), atol=1e-9, rtol=0)
        assert np.allclose(model.flange(q), _pin_flange(name, q), atol=1e-9, rtol=0)


def test_viper_zero_is_the_urdf_zero() -> None:
    """V+ zero: upper arm horizontal, forearm up, flange z up at (255, 0, 710) mm."""
    T = robot_model("VIPER-S650").forward([0.0] * 6)
    assert np.allclose(T[:3, 3], [255.0, 0.0, 710.0], atol=1e-9)
    assert np.allclose(T[:3, :3], np.eye(3), atol=1e-12)


def test_limits_and_speeds_come_from_the_urdf() -> None:
    viper = robot_model("VIPER-S650")
    assert viper.lower_limits[2] == pytest.approx(math.degrees(-0.5061))
    assert viper.upper_limits[2] == pytest.approx(math.degrees(4.4680))
    cobra = robot_model("COBRA-S600")
    assert [j.linear for j in cobra.joints] == [False, False, True, False]
    assert (cobra.lower_limits[2], cobra.upper_limits[2]) == (-210.0, 0.0)
    db = default_database("COBRA-S600")
    assert db.get_nums(2700) == pytest.approx([math.degrees(6.737), math.degrees(12.5664), 1100.0, math.degrees(20.944)])
    # 100 % acceleration: top speed in 0.2 s (docs/design/robots.md)
    assert db.get_nums(2702) == pytest.approx([v / 0.2 for v in db.get_nums(2700)])
    tm = default_database("TM5-900")
    assert tm.get_nums(16077) == pytest.approx([270.0, 180.0, 155.0, 180.0, 180.0, 270.0], abs=1e-9)


def test_the_cobra_has_one_actuated_joint_where_the_urdf_mimics() -> None:
    cobra = robot_model("COBRA-S600")
    assert cobra.joint_names == ["inner_joint", "outer_joint", "quill_prismatic_joint", "quill_rotation_joint"]
    q = [37.0, -80.0, -100.0, 45.0]
    values = cobra.urdf_joint_values(q)
    assert values["flyover_cable_joint"] == pytest.approx(37.0)
    # the whole URDF at that configuration: the cable link follows J1, the flange is the model's
    full = cobra.full_model
    data = full.createData()
    pin.framesForwardKinematics(full, data, cobra.full_configuration(q))
    cable = data.oMf[full.getFrameId("flyover_cable_link")]
    assert math.degrees(math.atan2(cable.rotation[1, 0], cable.rotation[0, 0])) == pytest.approx(37.0)
    flange = data.oMf[full.getFrameId("tool0")].homogeneous
    flange[:3, 3] *= 1000.0
    assert np.allclose(flange, cobra.forward(q), atol=1e-9)


def _round_trip(model: RobotModel, q: list[float], bits: int, current: list[float]) -> list[float]:
    T = model.forward(q)
    sol = model.inverse(T, bits, current)
    assert np.abs(model.forward(sol) - T).max() < 1e-9
    return sol


@pytest.mark.parametrize("name", SIX_AXES)
def test_inverse_round_trips_in_every_configuration(name: str) -> None:
    """For each of the eight configurations, poses of random joints in that configuration are
    solved back, from random current joints, into the same configuration, to 1e-9 mm."""
    model = robot_model(name)
    rng = np.random.default_rng(22)
    seen = dict.fromkeys(ARM_CONFIGS, 0)
    tries = 0
    while min(seen.values()) < N_POSES // 8 and tries < 40 * N_POSES:
        tries += 1
        q = _random_joints(model, rng)
        bits = model.config_of(q)
        if seen[bits] >= N_POSES // 8:
            continue
        seen[bits] += 1
        sol = _round_trip(model, q, bits, _random_joints(model, rng))
        assert model.config_of(sol) == bits
    assert min(seen.values()) == N_POSES // 8, seen


@pytest.mark.parametrize("name", SIX_AXES)
def test_no_bits_keep_the_current_configuration(name: str) -> None:
    model = robot_model(name)
    rng = np.random.default_rng(23)
    for _ in range(N_POSES // 2):
        q = _random_joints(model, rng)
        # current joints near the target, in its branch: the solution is the target itself
        current = [v + rng.uniform(-2.0, 2.0) for v in q]
        if model.config_of(current) != model.config_of(q):
            continue
        sol = _round_trip(model, q, 0, current)
        assert np.allclose(sol, q, atol=1e-7)


@pytest.mark.parametrize("name", ALL)
def test_the_zero_pose_solves_back_whatever_the_bits(name: str) -> None:
    """All joints 0 (where Robot.Home leaves these arms) sits on branch boundaries: the TMs
    stand straight up, with the wrist point on the edge of the J1 solutions and J5 = 0.  Its
    pose must solve back, with no bits, with the bits Where reports, and moved 10 mm down."""
    model = robot_model(name)
    zero = model.ready_joints()
    T = model.forward(zero)
    for bits in (0, model.config_of(zero)):
        _round_trip(model, zero, bits, zero)
    lower = T.copy()
    lower[2, 3] -= 10.0
    sol = model.inverse(lower, 0, zero)
    assert np.abs(model.forward(sol) - lower).max() < 1e-9


@pytest.mark.parametrize("name", ALL)
def test_tool_and_base_apply_as_on_every_robot(name: str) -> None:
    model = robot_model(name)
    tool = np.eye(4)
    tool[:3, 3] = [0.0, 0.0, 120.0]
    base = _shift(50.0, -30.0)
    model.tool, model.base = tool, base
    rng = np.random.default_rng(25)
    for _ in range(10):
        q = _random_joints(model, rng)
        assert np.allclose(model.forward(q), base @ model.flange(q) @ tool, atol=1e-9)
        _round_trip(model, q, model.config_of(q), _random_joints(model, rng))


@pytest.mark.parametrize("name", SIX_AXES)
def test_the_branches_measured_by_hand_are_the_geometric_ones(name: str) -> None:
    """The solvers measure the branches by hand (the Viper in its arm's plane, the TMs on the
    product of exponentials); they must be the geometric rule on Pinocchio's joint frames (wrist
    point, elbow, J5) of the module docstring."""
    from gplrt.motion.kinematics.urdf import _arm_measures

    model = robot_model(name)
    rng = np.random.default_rng(26)
    for _ in range(100):
        q = [math.radians(v) for v in _random_joints(model, rng)]
        assert np.allclose(model._measures(q), _arm_measures(model.joint_origins(q), q), atol=1e-12)


def test_cobra_round_trips_lefty_and_righty() -> None:
    cobra = robot_model("COBRA-S600")
    rng = np.random.default_rng(24)
    for _ in range(N_POSES):
        q = _random_joints(cobra, rng)
        bits = cobra.config_of(q)
        assert bits == (GPL_RIGHTY if q[1] >= 0 else GPL_LEFTY)
        sol = _round_trip(cobra, q, bits, _random_joints(cobra, rng))
        assert np.allclose(sol[:3], q[:3], atol=1e-7)  # one solution per branch
        assert math.remainder(sol[3] - q[3], 360.0) == pytest.approx(0.0, abs=1e-7)  # J4 up to a turn
        other = GPL_LEFTY if bits == GPL_RIGHTY else GPL_RIGHTY
        try:
            flipped = _round_trip(cobra, q, other, q)
        except GplException as exc:
            assert exc.ErrorCode == JOINT_OUT_OF_RANGE  # the mirror branch may leave the limits
        else:
            assert cobra.config_of(flipped) == other


def test_the_cobras_plain_path_is_the_general_steps_to_the_bit() -> None:
    """``UrdfModel._plain_inverse`` (the Cobra's usual case in one method) answers what the
    general steps answer, bit for bit, and leaves them every other case."""
    from gplrt.geometry.transforms import matrix_to_pose

    cobra = robot_model("COBRA-S600")
    rng = np.random.default_rng(27)
    plain = 0
    for k in range(400):
        if k == 200:  # the second half with a gripper offset as Tool
            tool = np.eye(4)
            tool[:3, 3] = [10.0, -5.0, 60.0]
            cobra.tool = tool
        q = _random_joints(cobra, rng)
        current = _random_joints(cobra, rng) if k % 2 else [v + rng.uniform(-5.0, 5.0) for v in q]
        bits = (0, GPL_RIGHTY, GPL_LEFTY, GPL_SINGLE)[k % 4]
        pose = matrix_to_pose(cobra.forward(q))
        for check in (True, False):
            fast = cobra._plain_inverse(pose, bits, current, check)
            try:
                general = cobra._general_inverse(pose, bits, current, check)
            except GplException:
                assert fast is None
                continue
            if fast is not None:
                plain += 1
                assert fast == general
    assert plain > 300  # the usual case takes the plain path
    tilted = matrix_to_pose(cobra.forward([10, 20, -50, 0]) @ _rot_x(5.0))
    assert cobra._plain_inverse(tilted, 0, [10, 20, -50, 0], True) is None


def test_viper_configuration_words_choose_the_branch() -> None:
    """One pose, every branch: each one inside the limits lands in its own bits; the others are
    refused with the controller's code (here Lefty: J1 = 180°, outside ±170°)."""
    viper = robot_model("VIPER-S650")
    q = [0.0, -90.0, 180.0, 0.0, 30.0, 0.0]
    T = viper.forward(q)
    reached = set()
    for bits in ARM_CONFIGS:
        try:
            sol = viper.inverse(T, bits, q)
        except GplException as exc:
            assert exc.ErrorCode == JOINT_OUT_OF_RANGE
            continue
        assert np.abs(viper.forward(sol) - T).max() < 1e-9
        assert viper.config_of(sol) == bits
        reached.add(bits)
    assert reached == {b for b in ARM_CONFIGS if b & GPL_RIGHTY}, reached


def test_single_puts_the_last_axis_in_half_a_turn() -> None:
    viper = robot_model("VIPER-S650")
    q = [0.0, -90.0, 180.0, 0.0, 30.0, 300.0]
    sol = viper.inverse(viper.forward(q), viper.config_of(q) | GPL_SINGLE, q)
    assert sol[5] == pytest.approx(-60.0)
    assert viper.inverse(viper.forward(q), viper.config_of(q), q)[5] == pytest.approx(300.0)


def _code(model: RobotModel, T: np.ndarray, bits: int = 0, current: list[float] | None = None) -> int:
    with pytest.raises(GplException) as info:
        model.inverse(T, bits, current)
    return info.value.ErrorCode


def test_error_codes_for_unreachable_and_out_of_range_goals() -> None:
    viper, cobra, tm = robot_model("VIPER-S650"), robot_model("COBRA-S600"), robot_model("TM5-900")
    far = np.eye(4)
    far[:3, 3] = [2000.0, 0.0, 500.0]
    assert _code(viper, far) == POSITION_TOO_FAR
    assert _code(cobra, cobra.forward([0, 0, -50, 0]) @ _shift(100.0, 0.0)) == POSITION_TOO_FAR
    assert _code(tm, far) == POSITION_TOO_FAR
    # the Cobra's flange inside |l1 - l2| = 50 mm of the J1 axis, and tilted
    near = cobra.forward([0, 0, -50, 0])
    near[:3, 3] = [10.0, 0.0, near[2, 3]]
    assert _code(cobra, near) == POSITION_TOO_CLOSE
    tilted = cobra.forward([10, 20, -50, 0]) @ _rot_x(5.0)
    assert _code(cobra, tilted) == INVALID_CARTESIAN
    # the Viper's wrist centre on its shoulder: too close
    close = np.eye(4)
    close[:3, 3] = [75.0, 0.0, 335.0 + 80.0]
    assert _code(viper, close) == POSITION_TOO_CLOSE
    # a reachable pose whose only solution in the branch asked for is outside the limits: -1012
    q = [0.0, -80.0, 200.0, 0.0, 45.0, 0.0]
    T = viper.forward(q)
    codes = {bits: _code_or_none(viper, T, bits, q) for bits in ARM_CONFIGS}
    assert codes[GPL_RIGHTY | GPL_ABOVE | GPL_NOFLIP] is None
    assert set(codes.values()) == {None, JOINT_OUT_OF_RANGE}, codes
    # ... and the wrist centre beyond reach in the Lefty branch only: -1040 for Lefty
    q = [20.0, -100.0, 150.0, 30.0, 40.0, 10.0]
    assert _code_or_none(viper, viper.forward(q), GPL_LEFTY, q) == POSITION_TOO_FAR
    with pytest.raises(GplException) as info:
        viper.check_limits([0.0, 0.0, -50.0, 0.0, 0.0, 0.0])
    assert info.value.ErrorCode == JOINT_OUT_OF_RANGE and "joint_3" in str(info.value)


def _code_or_none(model: RobotModel, T: np.ndarray, bits: int, current: list[float]) -> int | None:
    try:
        model.inverse(T, bits, current)
    except GplException as exc:
        return exc.ErrorCode
    return None


def _shift(x: float, y: float) -> np.ndarray:
    T = np.eye(4)
    T[:3, 3] = [x, y, 0.0]
    return T


def _rot_x(deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    T = np.eye(4)
    T[1:3, 1:3] = [[c, -s], [s, c]]
    return T


# -- a GPL program on each robot --------------------------------------------------------------------

#: Per robot: the joints of the first (joint) move and of the Cartesian goal, both inside the limits.
GOALS = {
    "VIPER-S650": ([10.0, -80.0, 170.0, 20.0, 30.0, 40.0], [-25.0, -60.0, 140.0, -30.0, 50.0, 10.0]),
    "COBRA-S600": ([10.0, 40.0, -50.0, 30.0], [-30.0, 70.0, -120.0, -60.0]),
    "TM5-700": ([10.0, -20.0, 80.0, -30.0, 90.0, 15.0], [-40.0, 10.0, 60.0, 20.0, 70.0, -30.0]),
    "TM5-900": ([10.0, -20.0, 80.0, -30.0, 90.0, 15.0], [-40.0, 10.0, 60.0, 20.0, 70.0, -30.0]),
    "TM12": ([10.0, -20.0, 80.0, -30.0, 90.0, 15.0], [-40.0, 10.0, 60.0, 20.0, 70.0, -30.0]),
    "TM14": ([10.0, -20.0, 80.0, -30.0, 90.0, 15.0], [-40.0, 10.0, 60.0, 20.0, 70.0, -30.0]),
}


def _program(joints: list[float], goal: tuple[float, ...]) -> str:
    n = len(joints)
    show_angles = " & \" \" & ".join(f'Format(a.Angle({i + 1}), "0.000000000")' for i in range(n))
    return module_src(f"""\
    Public Sub Show(ByVal tag As String)
        Dim w As Location
        Dim a As Location
        w = Robot.Where
        a = Robot.WhereAngles
        Console.WriteLine(tag & " " & Format(w.X, "0.000000000") & " " & Format(w.Y, "0.000000000") & " " & Format(w.Z, "0.000000000") & " " & Format(w.Yaw, "0.000000000") & " " & Format(w.Pitch, "0.000000000") & " " & Format(w.Roll, "0.000000000"))
        Console.WriteLine(tag & " " & {show_angles})
    End Sub

    Public Sub Main()
        Dim prof As New Profile
        Dim j As New Location
        Dim c As New Location
        Controller.PowerEnabled = True
        While Not Controller.PowerEnabled
            Thread.Sleep(10)
        End While
        Robot.Attached = 1
        Robot.Home
        j.Angles({", ".join(repr(v) for v in joints)})
        Move.Loc(j, prof)
        Move.WaitForEOM
        Show("joint")
        c.XYZ({", ".join(repr(v) for v in goal)})
        Move.Loc(c, prof)
        Move.WaitForEOM
        Show("cart")
        prof.Straight = True
        c.Z = c.Z - 20
        Move.Loc(c, prof)
        Move.WaitForEOM
        Show("line")
    End Sub""")


def _numbers(line: str) -> list[float]:
    return [float(v) for v in line.split()[1:]]


@pytest.mark.parametrize("name", ALL)
def test_a_gpl_program_moves_each_robot(name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``gpl2py run --robot NAME``: a joint move, a Cartesian move and a straight line; the poses
    reached are the forward kinematics of the joints reached, and the goals, to 1e-6."""
    model = robot_model(name)
    joints, goal_joints = GOALS[name]
    goal = model.forward(goal_joints)
    proj = write_project(tmp_path, {"Main.gpl": _program(joints, matrix_to_xyzypr(goal))})
    r = in_process(capsys, "run", proj, "--robot", name, "-q")
    assert r.returncode == 0, r.stdout + r.stderr
    lines = dict((ln.split()[0] + str(i % 2), ln) for i, ln in enumerate(r.stdout.splitlines()))
    assert np.allclose(_numbers(lines["joint1"]), joints, atol=1e-6)
    expect = [model.forward(joints), goal, goal.copy()]
    expect[2][2, 3] -= 20.0
    for tag, T in zip(("joint", "cart", "line"), expect, strict=True):
        xyzypr, angles = _numbers(lines[tag + "0"]), _numbers(lines[tag + "1"])
        reached = model.forward(angles)
        assert np.abs(reached[:3, 3] - T[:3, 3]).max() < 1e-6, tag
        assert np.abs(reached[:3, :3] - T[:3, :3]).max() < 1e-6, tag
        assert np.allclose(xyzypr[:3], T[:3, 3], atol=1e-6), tag
    assert re.search(r"^cart ", r.stdout, re.M)


CONFIG_PROGRAM = module_src("""\
    Public Sub Main()
        Dim prof As New Profile
        Dim c As New Location
        Dim a As Location
        Dim k As Integer
        Dim configs(1) As Integer
        Controller.PowerEnabled = True
        While Not Controller.PowerEnabled
            Thread.Sleep(10)
        End While
        Robot.Attached = 1
        Robot.Home
        configs(0) = CONFIG_A
        configs(1) = CONFIG_B
        For k = 0 To 1
            c.XYZ(GOAL)
            c.Config = configs(k)
            Move.Loc(c, prof)
            Move.WaitForEOM
            a = Robot.WhereAngles
            Console.WriteLine(CStr(Robot.Where.Config) & " " & Format(a.Angle(1), "0.000000000") & " " & Format(a.Angle(2), "0.000000000") & " " & Format(a.Angle(3), "0.000000000") & " " & Format(a.Angle(4), "0.000000000") & " " & Format(a.Angle(NLAST1), "0.000000000") & " " & Format(a.Angle(NLAST), "0.000000000"))
        Next
    End Sub""")


@pytest.mark.parametrize(("name", "joints", "configs"), [
    ("COBRA-S600", [-30.0, 70.0, -120.0, -60.0], (GPL_RIGHTY, GPL_LEFTY)),
    ("VIPER-S650", [-25.0, -60.0, 140.0, -30.0, 50.0, 10.0], (GPL_RIGHTY | GPL_ABOVE | GPL_NOFLIP,
                                                            GPL_RIGHTY | GPL_ABOVE | GPL_FLIP)),
    ("TM5-900", [-40.0, 10.0, 60.0, 20.0, 70.0, -30.0], (GPL_RIGHTY | GPL_BELOW | GPL_NOFLIP,
                                                        GPL_LEFTY | GPL_ABOVE | GPL_FLIP)),
])
def test_a_gpl_location_config_chooses_the_branch(name: str, joints: list[float], configs: tuple[int, int],
                                                  tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``Location.Config`` reaches the URDF robot's inverse: one Cartesian goal, two configurations,
    two joint solutions, each reporting its configuration and reaching the goal."""
    model = robot_model(name)
    goal = model.forward(joints)
    n = model.axis_count
    src = (CONFIG_PROGRAM.replace("GOAL", ", ".join(repr(v) for v in matrix_to_xyzypr(goal)))
           .replace("CONFIG_A", str(configs[0])).replace("CONFIG_B", str(configs[1]))
           .replace("NLAST1", str(n - 1)).replace("NLAST", str(n)))
    proj = write_project(tmp_path, {"Main.gpl": src})
    r = in_process(capsys, "run", proj, "--robot", name, "-q")
    assert r.returncode == 0, r.stdout + r.stderr
    rows = [line.split() for line in r.stdout.splitlines()]
    assert len(rows) == 2
    solutions = []
    for row, bits in zip(rows, configs, strict=True):
        assert int(row[0]) == bits
        angles = [float(v) for v in row[1:5]] + ([float(v) for v in row[5:7]] if n == 6 else [])
        assert model.config_of(angles) == bits
        assert np.abs(model.forward(angles) - goal).max() < 1e-6
        solutions.append(angles)
    assert not np.allclose(solutions[0], solutions[1], atol=1e-3)


def test_run_help_lists_the_urdf_robots(capsys: pytest.CaptureFixture[str]) -> None:
    out = in_process(capsys, "run", "--help").stdout
    for name in ALL:
        assert name in out

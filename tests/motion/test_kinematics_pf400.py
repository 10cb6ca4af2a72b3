"""PF400 family kinematics: FK against the URDFs and the closed form (robot-models.md §4), IK round
trips with Config bits, unwinding, and the controller's error codes."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from gplrt.controller.pdb import default_database
from gplrt.geometry.transforms import matrix_to_xyzypr, xyzypr_to_matrix
from gplrt.lang.errors import GplException
from gplrt.motion.kinematics import GPL_LEFTY, GPL_RIGHTY, GPL_SINGLE, Pf400Model, build_model

DATA = Path(__file__).parent / "data"
RNG_SEED = 20261121
N_ROUND_TRIP = 10_000
FLANGE_R0 = np.array([[0.0, 0.0, 1.0], [0.0, -1.0, 0.0], [1.0, 0.0, 0.0]])  # Ry(90)·Rz(180)


def _model(name: str) -> Pf400Model:
    model = build_model(default_database(name))
    assert isinstance(model, Pf400Model)
    return model


def _random_joints(model: Pf400Model, rng: np.random.Generator, n: int) -> np.ndarray:
    lo, hi = np.array(model.lower_limits), np.array(model.upper_limits)
    return rng.uniform(lo, hi, size=(n, model.axis_count))


def _closed_form(q: np.ndarray, l1: float, l2: float, tool: float, rail_angle_deg: float) -> np.ndarray:
    """§4.3 written out independently: Where = Trans(xw + g cosψ, yw + g sinψ, J1)·Rz(ψ)·Ry(90)·Rz(180)."""
    j1, j2, j3, j4 = q[0], math.radians(q[1]), math.radians(q[2]), math.radians(q[3])
    rail = q[5] if len(q) > 5 else 0.0
    a = math.radians(rail_angle_deg)
    psi = j2 + j3 + j4
    xw = l1 * math.cos(j2) + l2 * math.cos(j2 + j3) - rail * math.sin(a)
    yw = l1 * math.sin(j2) + l2 * math.sin(j2 + j3) + rail * math.cos(a)
    T = np.eye(4)
    c, s = math.cos(psi), math.sin(psi)
    T[:3, :3] = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]) @ FLANGE_R0
    T[:3, 3] = [xw + tool * c, yw + tool * s, j1]
    return T


# -- forward ------------------------------------------------------------------------------------


@pytest.mark.parametrize(("name", "l1", "l2", "rail_angle"),
                         [("PF400SX", 302, 289, 0), ("PF400SXL", 302, 289, 0), ("PF400S", 225, 210, 0),
                          ("PF3400SX", 302, 289, 0)])
def test_forward_equals_closed_form(name: str, l1: float, l2: float, rail_angle: float) -> None:
    model = _model(name)
    rng = np.random.default_rng(RNG_SEED)
    for q in _random_joints(model, rng, 2000):
        assert np.abs(model.forward(q) - _closed_form(q, l1, l2, 162.0, rail_angle)).max() < 1e-9


def test_forward_matches_pf400_urdf_with_rail_along_x() -> None:
    """PF400.urdf (AD-SDL): rail along +X, i.e. 16050[5] = −90 (§4.6); we build our model from the
    SXL database with that one number changed and compare where the two agree: J1 within the URDF's
    0.002–1.160 m, the `hand` frame turned into the GPL flange (·Ry(90)·Rz(180)) and shifted by the
    documented world offset (233.101, −19.600, 143.623) mm (§4.5)."""
    db = default_database("PF400SXL-TALL")
    db.set(16050, -90.0, index=5, key=1)
    ours = build_model(db)
    urdf = pin.buildModelFromUrdf(str(DATA / "PF400.urdf"))
    data = urdf.createData()
    hand = urdf.getFrameId("hand")
    offset = np.array([233.101, -19.600, 143.623])
    rng = np.random.default_rng(RNG_SEED)
    qs = _random_joints(ours, rng, 3000)
    qs[:, 0] = rng.uniform(2.0, 1160.0, len(qs))
    worst = 0.0
    for q in qs:
        qu = np.array([q[5] / 1000, q[0] / 1000, *np.radians(q[1:4]), 0.068, 0.068])
        pin.framesForwardKinematics(urdf, data, qu)
        M = data.oMf[hand]
        expected = np.eye(4)
        expected[:3, :3] = M.rotation @ FLANGE_R0
        expected[:3, 3] = M.translation * 1000 - offset
        worst = max(worst, float(np.abs(ours.flange(q) - expected).max()))
    assert worst < 1e-9


def test_forward_matches_pf3400sx_urdf() -> None:
    ours = _model("PF3400SX")
    urdf = pin.buildModelFromUrdf(str(DATA / "PF3400SX.urdf"))
    data = urdf.createData()
    hand = urdf.getFrameId("hand")
    offset = np.array([203.051, 0.200, 93.623])
    rng = np.random.default_rng(RNG_SEED + 1)
    for q in _random_joints(ours, rng, 3000):
        qu = np.array([q[0] / 1000, *np.radians(q[1:4]), 0.06, 0.06])
        pin.framesForwardKinematics(urdf, data, qu)
        M = data.oMf[hand]
        assert np.abs(ours.flange(q)[:3, :3] - M.rotation @ FLANGE_R0).max() < 1e-12
        assert np.abs(ours.flange(q)[:3, 3] - (M.translation * 1000 - offset)).max() < 1e-9


def test_real_arm_where_and_whereangles_agree() -> None:
    """pharmbio/robotlab wherejson (§4.7): same pose as Where and WhereAngles, rounded to 0.01."""
    model = _model("PF400SX")
    q = [569.41, -0.15, 184.78, -912.41, 126.58]
    x, y, z, yaw, pitch, roll = matrix_to_xyzypr(model.forward(q))
    assert abs(x - 174.45) < 0.006 and abs(y - -46.05) < 0.006 and z == pytest.approx(569.41)
    assert (round(yaw, 2), round(pitch, 6), round(roll, 6)) == (-7.78, 90.0, 180.0)
    assert model.config_of(q) == GPL_LEFTY
    back = model.inverse(xyzypr_to_matrix(174.45, -46.05, 569.41, -7.78, 90, 180), GPL_LEFTY,
                         [569.0, 0.0, 185.0, -900.0, 126.58])
    assert back[3] == pytest.approx(-912.41, abs=0.02) and back[2] == pytest.approx(184.78, abs=0.02)


# -- inverse ------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["PF400SX", "PF400SXL", "PF400S-SHORT", "PF400SL-TALL", "PF3400SX"])
def test_inverse_round_trip_honours_config_and_unwinds_toward_current(name: str) -> None:
    """10,000 random in-limit poses per variant: with Config = config_of(q) and current joints
    within ±170° of q on the wrist (other axes jittered), IK must give back q itself."""
    model = _model(name)
    rng = np.random.default_rng(RNG_SEED)
    qs = _random_joints(model, rng, N_ROUND_TRIP)
    current = np.clip(qs + rng.uniform(-5, 5, qs.shape), model.lower_limits, model.upper_limits)
    current[:, 3] = qs[:, 3] + rng.uniform(-170, 170, len(qs))
    if model.axis_count > 5:
        current[:, 5] = qs[:, 5]  # the rail stays where it is; IK does not move it
    worst_pose = worst_joint = 0.0
    for q, cur in zip(qs, current, strict=True):
        T = model.forward(q)
        bits = model.config_of(q)
        sol = model.inverse(T, bits, cur)
        assert model.config_of(sol) == bits
        worst_pose = max(worst_pose, float(np.abs(model.forward(sol) - T).max()))
        skip = [4]  # the gripper keeps its current value
        worst_joint = max(worst_joint, float(np.abs(np.delete(np.array(sol) - q, skip)).max()))
        assert abs(sol[4] - cur[4]) < 1e-12
    assert worst_pose < 1e-9
    assert worst_joint < 1e-9


def test_inverse_other_branch_either_solves_or_reports_joint_limit() -> None:
    model = _model("PF400SX")
    rng = np.random.default_rng(RNG_SEED + 2)
    solved = 0
    for q in _random_joints(model, rng, 2000):
        T = model.forward(q)
        other = GPL_LEFTY if model.config_of(q) == GPL_RIGHTY else GPL_RIGHTY
        try:
            sol = model.inverse(T, other, q)
        except GplException as exc:
            assert exc.ErrorCode == -1012
            continue
        solved += 1
        assert model.config_of(sol) == other
        assert np.abs(model.forward(sol) - T).max() < 1e-9
    assert solved > 500


def test_config_zero_keeps_the_current_elbow_branch() -> None:
    model = _model("PF400SX")
    T = model.forward([500, -40, 60, 30, 100])  # Lefty twin: J2 ≈ 18.6, J3 = 300, both in range
    assert model.inverse(T, 0, [500, 0, 90, 0, 100]) == pytest.approx([500, -40, 60, 30, 100], abs=1e-9)
    lefty = model.inverse(T, 0, [500, 0, 270, 0, 100])
    assert model.config_of(lefty) == GPL_LEFTY
    assert model.inverse(T, GPL_RIGHTY | GPL_LEFTY, [500, 0, 270, 0, 100]) == pytest.approx(lefty)


def test_multi_turn_wrist_unwinds_and_single_restricts_it() -> None:
    model = _model("PF400SX")
    q = [500.0, 10.0, 120.0, 30.0, 100.0]
    T = model.forward(q)
    assert model.inverse(T, GPL_RIGHTY, [500, 10, 120, 700, 100])[3] == pytest.approx(750.0)
    assert model.inverse(T, GPL_RIGHTY, [500, 10, 120, -700, 100])[3] == pytest.approx(-690.0)
    assert model.inverse(T, GPL_RIGHTY | GPL_SINGLE, [500, 10, 120, 700, 100])[3] == pytest.approx(30.0)
    # nearest equivalent beyond the ±960 stop is not chosen: 950 + 30 → the 750 one
    assert model.inverse(T, GPL_RIGHTY, [500, 10, 120, 959, 100])[3] == pytest.approx(750.0)


def test_rail_is_subtracted_along_its_direction() -> None:
    model = _model("PF400SXL")  # rail angle 0: the base moves along +Y
    q = [200.0, 20.0, 100.0, -40.0, 100.0, 250.0]
    T = model.forward(q)
    assert T[1, 3] == pytest.approx(model.forward([*q[:5], 0.0])[1, 3] + 250.0)
    assert model.inverse(T, GPL_RIGHTY, q) == pytest.approx(q, abs=1e-9)
    shifted = model.inverse(T, GPL_RIGHTY, [*q[:5], 100.0])  # other rail position: arm compensates
    assert shifted[5] == 100.0 and np.abs(model.forward(shifted) - T).max() < 1e-9


@pytest.mark.parametrize(
    ("pose", "code", "axis"),
    [
        ((300, 0, 500, 0, 45, 180), -1033, 0),  # pitch ≠ 90: impossible for a 4-DOF arm
        ((800, 0, 500, 0, 90, 180), -1040, 0),  # wrist radius 638 > l1 + l2 = 591
        ((162 + 5, 0, 500, 0, 90, 180), -1039, 0),  # wrist radius 5 mm < |l1 − l2| = 13
        ((162 + 589.5, 0, 500, 0, 90, 180), -1012, 3),  # between 587.76 (J3 = 12°) and 591
        ((300, 0, 1200, 0, 90, 180), -1012, 1),  # above the column
        ((-493.56371, -82.630104, 1157.130034, -83.036521, 90, 180), -1012, 2),  # Tcs.gpo station 1 (§5.3)
    ],
)
def test_unreachable_targets_raise_controller_codes(pose: tuple[float, ...], code: int, axis: int) -> None:
    model = _model("PF400SX")
    with pytest.raises(GplException) as exc:
        model.inverse(xyzypr_to_matrix(*pose), GPL_RIGHTY, [500, 0, 90, 0, 100])
    assert exc.value.ErrorCode == code
    if axis:
        assert exc.value.Axis == axis and exc.value.RobotError


def test_tool_and_base_enter_forward_and_inverse() -> None:
    model = _model("PF400SX")
    model.base = xyzypr_to_matrix(100, -50, 20, 30, 0, 0)
    model.tool = xyzypr_to_matrix(10, 5, 150, 0, 0, 0)
    q = [400.0, -20.0, 200.0, 100.0, 90.0]
    T = model.forward(q)
    assert np.abs(T - model.base @ model.flange(q) @ model.tool).max() < 1e-12
    assert model.inverse(T, GPL_LEFTY, q) == pytest.approx(q, abs=1e-9)


# -- whole paths in one pass ----------------------------------------------------------------------


@pytest.mark.parametrize("name", ["PF400SX", "PF400SXL", "PF400S-SHORT", "PF3400SX"])
def test_inverse_path_equals_pose_by_pose_solutions(name: str) -> None:
    """``inverse_path`` (one numpy pass over a straight line's or an arc's samples) gives the joints
    the pose-by-pose ``inverse`` gives, seeded sample after sample — rail moving along, Tool set,
    multi-turn wrist — and declines (None) exactly where pose by pose would raise or pick another turn."""
    from gplrt.motion.straight import ArcPath, LinePath, PathJoints

    model = _model(name)
    rng = np.random.default_rng(RNG_SEED + 7)
    lo, hi = np.array(model.lower_limits), np.array(model.upper_limits)
    lo, hi = np.maximum(lo, -700.0), np.minimum(hi, 700.0)
    mask = np.array([j.role == "rail" for j in model.joints])
    compared = declined = 0
    for _ in range(150):
        q0, q1 = rng.uniform(lo, hi), rng.uniform(lo, hi)
        q_end = q1  # the rail (if any) goes to q1's along the path; IK solves the arm
        T0, T1 = model.forward(q0), model.forward(q_end)
        mid = 0.5 * (T0[:3, 3] + T1[:3, 3]) + rng.uniform(-40.0, 40.0, 3)
        for path in (LinePath(T0, T1), ArcPath(T0, mid, T1)):
            def ik(T: np.ndarray, seed: np.ndarray) -> np.ndarray:
                return np.array(model.inverse(T, 0, seed.tolist()))
            try:
                one_by_one = PathJoints.sample(path, ik, q0, q_end, mask)
            except GplException:
                one_by_one = None
            if one_by_one is None:
                with pytest.raises(GplException):
                    PathJoints.sample(path, ik, q0, q_end, mask, model.inverse_path)
                continue
            batch = model.inverse_path(path.poses(one_by_one.u[1:]), np.array([
                np.where(mask, q0 + (q_end - q0) * u, q0) for u in one_by_one.u[1:]]))
            if batch is None:
                declined += 1
                continue
            compared += 1
            assert np.abs(batch - one_by_one.q[1:]).max() < 1e-9
            assert np.abs(path.poses(one_by_one.u) - np.array([path.pose(float(u)) for u in one_by_one.u])).max() < 1e-9
    assert compared > 100 and declined < compared / 10


def test_from_the_folded_posture_config_zero_takes_the_reachable_nearest_branch() -> None:
    """J3 = 180° exactly (folded, the PF400's parking posture) is in both elbow branches: Config 0
    must not refuse a target that one branch reaches (it used to take Lefty and raise -1012), and
    of two reachable solutions it takes the one nearest the current joints."""
    model = _model("PF400SX")
    folded = [250.0, 0.0, 180.0, 0.0, 80.0]
    T = xyzypr_to_matrix(300, 100, 250, 0, 90, 180)  # Lefty would need J2 beyond its limit
    sol = model.inverse(T, 0, folded)
    assert sol == pytest.approx(model.inverse(T, GPL_RIGHTY, folded), abs=1e-12)
    assert np.abs(model.forward(sol) - T).max() < 1e-9
    T = xyzypr_to_matrix(300, -100, 250, 0, 90, 180)  # and the mirror image: Lefty only
    assert model.inverse(T, 0, folded) == pytest.approx(model.inverse(T, GPL_LEFTY, folded), abs=1e-12)
    # both reachable: the nearer one wins (here J2 is -63° or +63°; from J2 = -60° Righty is nearer)
    T = xyzypr_to_matrix(400, 0, 250, 0, 90, 180)
    near_righty = model.inverse(T, 0, [250.0, -60.0, 180.0, 0.0, 80.0])
    assert near_righty == pytest.approx(model.inverse(T, GPL_RIGHTY, folded), abs=1e-9)
    near_lefty = model.inverse(T, 0, [250.0, 60.0, 180.0, 0.0, 80.0])
    assert near_lefty == pytest.approx(model.inverse(T, GPL_LEFTY, folded), abs=1e-9)
    # an exact tie keeps the branch Where reports for J3 = 180 (Lefty)
    assert model.config_of(model.inverse(T, 0, folded)) == GPL_LEFTY == model.config_of(folded)
    # away from the boundary Config 0 keeps the current branch even when the other is nearer
    with pytest.raises(GplException) as exc:
        model.inverse(xyzypr_to_matrix(300, 100, 250, 0, 90, 180), 0, [250.0, 0.0, 181.0, 0.0, 80.0])
    assert exc.value.ErrorCode == -1012


@pytest.mark.parametrize("name", ["PF400SX", "PF400SXL", "PF400S-SHORT", "PF3400SX"])
def test_the_plain_case_path_agrees_with_the_general_steps(name: str) -> None:
    """``Pf400Model.inverse_pose`` solves the common case in one method (``_plain_inverse``) and
    hands everything else to ``RobotModel.inverse_pose``'s general steps.  On random targets —
    reachable or not, every Config the PF400 reads, current joints anywhere including the folded
    branch boundary, with and without a tool offset — the two give the same joints (the solved
    axes to the bit; the gripper and rail, which the general steps take through metres and back,
    within 1e-12) or the same error code and axis, checked and unchecked."""
    from gplrt.motion.kinematics.base import RobotModel

    rng = np.random.default_rng(RNG_SEED)
    model = _model(name)
    plain = 0
    for k in range(3000):
        if k == 1500:
            model.tool = xyzypr_to_matrix(12.0, -3.0, 150.0, 0.0, 0.0, 0.0)  # a pure offset: the shortcut
        target_q, current = _random_joints(model, rng, 2)
        if k % 7 == 0:
            current[2] = 180.0  # folded: on the branch boundary
        T = model.forward(target_q)
        T[:3, 3] += rng.normal(0.0, 30.0, 3) * (k % 3 == 0)  # now and then off the joints' pose
        pose = tuple(T[:3, :3].ravel().tolist() + T[:3, 3].tolist())
        bits = int(rng.choice([0, GPL_RIGHTY, GPL_LEFTY, GPL_RIGHTY | GPL_LEFTY, GPL_SINGLE, GPL_RIGHTY | GPL_SINGLE]))
        check = bool(k % 5)
        got: list[float] | int
        want: list[float] | int
        try:
            got = model.inverse_pose(pose, bits, current.tolist(), check)
        except GplException as exc:
            got = (exc.ErrorCode, exc.Axis)
        try:
            want = RobotModel.inverse_pose(model, pose, bits, current.tolist(), check)
        except GplException as exc:
            want = (exc.ErrorCode, exc.Axis)
        if isinstance(want, tuple) or isinstance(got, tuple):
            assert got == want, (k, got, want)
            continue
        plain += model._plain_inverse(pose, bits, current.tolist(), check) is not None
        solved = [model.roles.index(r) for r in ("z", "shoulder", "elbow", "wrist") if r in model.roles]
        assert [got[i] for i in solved] == [want[i] for i in solved], (k, got, want)
        assert np.allclose(got, want, rtol=1e-12, atol=1e-12), (k, got, want)
    assert plain > 500  # the shortcut did run, a good share of the time

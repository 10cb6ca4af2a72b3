"""Six-axis articulated arm (our ARM6): FK against an independent matrix product, IK round trips
with all Config bits honoured, the DLS solver on its own, singular wrist, errors."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from gplrt.controller.pdb import default_database
from gplrt.geometry.transforms import xyzypr_to_matrix
from gplrt.lang.errors import GplException
from gplrt.motion.kinematics import (
    GPL_ABOVE,
    GPL_BELOW,
    GPL_FLIP,
    GPL_LEFTY,
    GPL_NOFLIP,
    GPL_RIGHTY,
    GPL_SINGLE,
    Articulated6Model,
    build_model,
    solve_dls,
)

RNG_SEED = 6
N_ROUND_TRIP = 10_000


def _model() -> Articulated6Model:
    model = build_model(default_database("ARM6"))
    assert isinstance(model, Articulated6Model)
    return model


def _rot(axis: str, deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    R = {"y": [[c, 0, s], [0, 1, 0], [-s, 0, c]], "z": [[c, -s, 0], [s, c, 0], [0, 0, 1]]}[axis]
    T = np.eye(4)
    T[:3, :3] = R
    return T


def _trans(x: float, y: float, z: float) -> np.ndarray:
    T = np.eye(4)
    T[:3, 3] = [x, y, z]
    return T


def _independent_fk(q: np.ndarray) -> np.ndarray:
    """Joint chain from the data README, multiplied out with plain numpy (no Pinocchio)."""
    d1, a1, a2, a3, d4, d6 = 400, 50, 350, 35, 350, 80
    return (_rot("z", q[0]) @ _trans(a1, 0, d1) @ _rot("y", q[1]) @ _trans(0, 0, a2) @ _rot("y", q[2])
            @ _trans(a3, 0, d4) @ _rot("z", q[3]) @ _rot("y", q[4]) @ _rot("z", q[5]) @ _trans(0, 0, d6)
            @ _trans(0, 0, 100))  # Tool at restart z = 100


def _random_joints(model: Articulated6Model, rng: np.random.Generator, n: int) -> np.ndarray:
    return rng.uniform(model.lower_limits, model.upper_limits, size=(n, 6))


def test_forward_equals_independent_chain() -> None:
    model = _model()
    rng = np.random.default_rng(RNG_SEED)
    for q in _random_joints(model, rng, 2000):
        assert np.abs(model.forward(q) - _independent_fk(q)).max() < 1e-9


def test_home_posture_points_straight_up() -> None:
    T = _model().forward([0] * 6)
    assert T[:3, 3] == pytest.approx([85.0, 0.0, 400 + 350 + 350 + 80 + 100])
    assert T[:3, :3] == pytest.approx(np.eye(3))


def test_inverse_round_trip_10000_with_config_and_unwinding() -> None:
    """Config = config_of(q), current = q jittered by up to ±20°: IK returns q (to 1e-8°, or only
    the pose within 1e-9 when the wrist is within 0.01° of singular, where J4/J6 split freely; the
    DLS refinement brings the pose to ~1e-12, the joints near the singular wrist to ~2e-10°)."""
    model = _model()
    rng = np.random.default_rng(RNG_SEED)
    qs = _random_joints(model, rng, N_ROUND_TRIP)
    current = np.clip(qs + rng.uniform(-20, 20, qs.shape), model.lower_limits, model.upper_limits)
    worst_pose = worst_joint = 0.0
    iterations = []
    for q, cur in zip(qs, current, strict=True):
        T = model.forward(q)
        bits = model.config_of(q)
        sol = model.inverse(T, bits, cur)
        iterations.append(model.last_iterations)
        assert model.config_of(sol) == bits
        worst_pose = max(worst_pose, float(np.abs(model.forward(sol) - T).max()))
        if abs(math.sin(math.radians(q[4]))) > math.sin(math.radians(0.01)):
            worst_joint = max(worst_joint, float(np.abs(np.array(sol) - q).max()))
    assert worst_pose < 1e-9
    assert worst_joint < 1e-8
    assert max(iterations) <= 3  # the analytic seed is already (almost) exact


def test_all_eight_branches_of_one_pose() -> None:
    model = _model()
    T = xyzypr_to_matrix(450, 120, 600, 20, 100, 30)
    solutions = {}
    for shoulder, elbow, wrist in itertools.product((GPL_RIGHTY, GPL_LEFTY), (GPL_ABOVE, GPL_BELOW),
                                                    (GPL_FLIP, GPL_NOFLIP)):
        bits = shoulder | elbow | wrist
        try:
            sol = model.inverse(T, bits, [0, 0, 0, 0, 10, 0])
        except GplException as exc:
            assert exc.ErrorCode == -1012
            continue
        assert model.config_of(sol) == bits
        assert np.abs(model.forward(sol) - T).max() < 1e-9
        solutions[bits] = sol
    # Righty with both elbows and both wrists fit inside this arm's limits
    assert {GPL_RIGHTY | e | w for e in (GPL_ABOVE, GPL_BELOW) for w in (GPL_FLIP, GPL_NOFLIP)} <= set(solutions)
    assert len({tuple(np.round(s, 6)) for s in solutions.values()}) == len(solutions)


def test_config_zero_keeps_the_current_branches() -> None:
    model = _model()
    q = np.array([30.0, 40.0, -30.0, 40.0, -50.0, 10.0])
    T = model.forward(q)
    near = q + 3.0
    assert model.inverse(T, 0, near) == pytest.approx(q, abs=1e-7)
    assert model.config_of(q) == GPL_RIGHTY | GPL_BELOW | GPL_FLIP  # φ = J3 + 5.7° < 0, J5 < 0


def test_single_and_multi_turn_wrist() -> None:
    model = _model()
    q = [10.0, 30.0, 40.0, 20.0, 60.0, 200.0]
    T = model.forward(q)
    bits = model.config_of(q)
    assert model.inverse(T, bits, q)[5] == pytest.approx(200.0)
    assert model.inverse(T, bits | GPL_SINGLE, q)[5] == pytest.approx(-160.0)
    assert model.inverse(T, bits, [*q[:5], -150.0])[5] == pytest.approx(-160.0)


def test_singular_wrist_keeps_j4_and_reaches_the_pose() -> None:
    model = _model()
    q = [20.0, 30.0, 40.0, 0.0, 0.0, 50.0]
    T = model.forward(q)
    sol = model.inverse(T, model.config_of(q), [20.0, 30.0, 40.0, 15.0, 5.0, 0.0])
    assert sol[3] == pytest.approx(15.0) and sol[5] == pytest.approx(35.0)
    assert np.abs(model.forward(sol) - T).max() < 1e-9


def test_dls_converges_from_a_perturbed_seed() -> None:
    """The numeric solver alone (no analytic seed): from 5° off it reaches machine precision."""
    model = _model()
    assert model.pin_model is not None and model.pin_data is not None
    rng = np.random.default_rng(RNG_SEED + 1)
    for q in _random_joints(model, rng, 200):
        q[4] = math.copysign(max(abs(q[4]), 20.0), q[4])  # keep away from the wrist singularity
        target = model.flange_se3(np.radians(q))
        seed = model.q_pin(np.radians(q + rng.uniform(-5, 5, 6)))
        sol, err, iters = solve_dls(model.pin_model, model.pin_data, model.flange_frame, target, seed)
        assert err < 1e-12 and iters < 20
        reached = model.flange_se3(model.q_gpl(sol))
        assert np.abs(reached.homogeneous - target.homogeneous).max() < 1e-12


@pytest.mark.parametrize(
    ("pose", "code"),
    # too far; wrist centre on the shoulder axis (closer than |a2 − √(a3² + d4²)| = 1.7 mm)
    [((2000, 0, 500, 0, 90, 0), -1040), ((50, 0, 580, 0, 0, 0), -1039)],
)
def test_unreachable_targets(pose: tuple[float, ...], code: int) -> None:
    model = _model()
    with pytest.raises(GplException) as exc:
        model.inverse(xyzypr_to_matrix(*pose), GPL_RIGHTY | GPL_ABOVE | GPL_NOFLIP)
    assert exc.value.ErrorCode == code


def test_other_branches_solve_or_report_limits_with_the_axis() -> None:
    model = _model()
    rng = np.random.default_rng(RNG_SEED + 2)
    codes: dict[int, int] = {}
    for q in _random_joints(model, rng, 500):
        T = model.forward(q)
        bits = model.config_of(q) ^ (GPL_RIGHTY | GPL_LEFTY | GPL_ABOVE | GPL_BELOW | GPL_FLIP | GPL_NOFLIP)
        try:
            sol = model.inverse(T, bits, q)
        except GplException as exc:
            codes[exc.ErrorCode] = codes.get(exc.ErrorCode, 0) + 1
            assert exc.ErrorCode in (-1012, -1039, -1040)
            if exc.ErrorCode == -1012:
                assert 1 <= exc.Axis <= 6 and exc.RobotNum == 1
            continue
        codes[0] = codes.get(0, 0) + 1
        assert model.config_of(sol) == bits
        assert np.abs(model.forward(sol) - T).max() < 1e-9
    assert codes.get(0, 0) > 50 and codes.get(-1012, 0) > 50


def test_from_the_zero_home_config_zero_takes_the_nearest_wrist_branch() -> None:
    """All-zero joints (the home posture) put J5 exactly on the Flip/NoFlip boundary: the arm is in
    both wrist branches.  A Config-0 target just across it must be reached by the nearby Flip
    solution, not by NoFlip with J4 and J6 swung round half a turn (what "keep the branch
    config_of reports" gave); away from the boundary the current branch still rules."""
    model = _model()
    q = [10.0, 20.0, 30.0, 10.0, -5.0, 20.0]
    T = model.forward(q)
    assert model.inverse(T, 0, [0.0] * 6) == pytest.approx(q, abs=1e-6)
    # a tie keeps the branch config_of reports for the current joints (NoFlip at J5 = 0)
    straight_up = model.forward([0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    assert model.config_of(model.inverse(straight_up, 0, [0.0] * 6)) == model.config_of([0.0] * 6)
    # from J5 = 1 degree (NoFlip, off the boundary) the NoFlip solution is kept
    sol = model.inverse(T, 0, [0.0, 0.0, 0.0, 0.0, 1.0, 0.0])
    assert sol[4] == pytest.approx(5.0, abs=1e-6) and np.abs(model.forward(sol) - T).max() < 1e-9
    # an explicit bit still decides
    assert model.inverse(T, GPL_NOFLIP, [0.0] * 6)[4] == pytest.approx(5.0, abs=1e-6)

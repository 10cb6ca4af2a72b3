"""XYZ-Theta gantry (module 2) and the model builder: FK per the module's axis rules, IK round
trips, theta unwinding / Single, axis masks, unknown modules, bad databases."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gplrt.controller.pdb import default_database
from gplrt.geometry.transforms import xyzypr_to_matrix
from gplrt.lang.errors import GplException
from gplrt.motion.kinematics import GPL_RIGHTY, GPL_SINGLE, GantryModel, RobotModel, build_model

RNG_SEED = 4
N_ROUND_TRIP = 10_000


def _gantry(name: str = "GANTRY4") -> GantryModel:
    model = build_model(default_database(name))
    assert isinstance(model, GantryModel)
    return model


def _expected(q: np.ndarray) -> np.ndarray:
    """Module 2 rules: axis 1 → +X, axis 2 → +Y, axis 3 positive → −Z, axis 4 positive → −yaw."""
    c, s = math.cos(math.radians(-q[3])), math.sin(math.radians(-q[3]))
    T = np.eye(4)
    T[:3, :3] = [[c, -s, 0], [s, c, 0], [0, 0, 1]]
    T[:3, 3] = [q[0], q[1], -q[2]]
    return T


@pytest.mark.parametrize("name", ["GANTRY4", "XYZT-GCU"])
def test_forward_follows_the_xyztheta_axis_rules(name: str) -> None:
    model = _gantry(name)
    rng = np.random.default_rng(RNG_SEED)
    for q in rng.uniform(model.lower_limits, model.upper_limits, size=(2000, 4)):
        assert np.abs(model.forward(q) - _expected(q)).max() < 1e-9


@pytest.mark.parametrize("name", ["GANTRY4", "XYZT-GCU"])
def test_inverse_round_trip_10000(name: str) -> None:
    model = _gantry(name)
    rng = np.random.default_rng(RNG_SEED)
    qs = rng.uniform(model.lower_limits, model.upper_limits, size=(N_ROUND_TRIP, 4))
    current = qs.copy()
    current[:, 3] += rng.uniform(-170, 170, len(qs))  # theta unwinds toward the current value
    worst_pose = worst_joint = 0.0
    for q, cur in zip(qs, current, strict=True):
        T = model.forward(q)
        sol = model.inverse(T, model.config_of(q), cur)
        assert model.config_of(sol) == 0
        worst_pose = max(worst_pose, float(np.abs(model.forward(sol) - T).max()))
        worst_joint = max(worst_joint, float(np.abs(np.array(sol) - q).max()))
    assert worst_pose < 1e-9 and worst_joint < 1e-9


def test_theta_unwinding_single_and_limits() -> None:
    model = _gantry()  # theta ±360
    T = model.forward([100, 200, 50, 30])
    assert model.inverse(T, 0, [0, 0, 0, 300])[3] == pytest.approx(30.0)  # 390 is past the stop
    assert model.inverse(T, 0, [0, 0, 0, -300])[3] == pytest.approx(-330.0)
    assert model.inverse(xyzypr_to_matrix(100, 200, -50, 0, 0, 170), GPL_SINGLE, [0, 0, 0, 300])[3] == pytest.approx(-170.0)
    assert model.inverse(xyzypr_to_matrix(100, 200, -50, 0, 0, 170), 0, [0, 0, 0, 300])[3] == pytest.approx(190.0)


@pytest.mark.parametrize(
    ("pose", "code", "axis"),
    [
        ((100, 100, -50, 0, 30, 0), -1033, 0),  # tilted tool: not a pure rotation about Z
        ((900, 100, -50, 0, 0, 0), -1012, 1),  # X beyond 800
        ((100, 100, 50, 0, 0, 0), -1012, 3),  # Z axis would have to be −50 (axis 3 positive is down)
    ],
)
def test_gantry_errors(pose: tuple[float, ...], code: int, axis: int) -> None:
    with pytest.raises(GplException) as exc:
        _gantry().inverse(xyzypr_to_matrix(*pose), 0, [0, 0, 0, 0])
    assert exc.value.ErrorCode == code
    if axis:
        assert exc.value.Axis == axis


def test_axis_mask_without_y_and_theta() -> None:
    db = default_database("GANTRY4")
    db.set(2003, 0x05, key=1)  # X and Z only: numbered J1 = X, J2 = Z
    db.set(2000, 2.0, key=1)
    model = build_model(db)
    assert model.joint_names == ["X", "Z"]
    assert model.forward([10, 20])[:3, 3] == pytest.approx([10, 0, -20])
    assert model.inverse(xyzypr_to_matrix(30, 0, -40, 0, 0, 0), 0, [0, 0]) == pytest.approx([30, 40])
    with pytest.raises(GplException) as exc:
        model.inverse(xyzypr_to_matrix(30, 5, -40, 0, 0, 0), 0, [0, 0])
    assert exc.value.ErrorCode == -1033


# -- the builder --------------------------------------------------------------------------------


def test_builder_dispatches_on_dataid_116_and_reads_tool_base_limits() -> None:
    db = default_database("ARM6")
    db.set_pdb_text("1, 2, 3, 0, 0, 90", 16051)
    model = build_model(db)
    assert model.tool == pytest.approx(xyzypr_to_matrix(1, 2, 3, 0, 0, 90))
    assert model.axis_count == 6 and model.upper_limits[5] == 360
    rail_arm = build_model(default_database("PF400SXL"))
    assert rail_arm.pin_model is not None
    # Pinocchio's limits are the PDb soft limits in SI, in tree order (the rail is the root joint)
    assert rail_arm.pin_model.upperPositionLimit == pytest.approx([0.5, 0.4015, *np.radians([93, 348, 960]), 0.134])


def test_unknown_module_moves_joints_but_refuses_cartesian() -> None:
    db = default_database("PF400SX")
    db.set(116, 99.0, index=1, key=1)
    model = build_model(db)
    assert type(model) is RobotModel and model.axis_count == 5 and model.module == 99
    model.check_limits([500, 0, 90, 0, 100])
    with pytest.raises(GplException) as exc:
        model.forward([500, 0, 90, 0, 100])
    assert exc.value.ErrorCode == -1036
    with pytest.raises(GplException) as exc:
        model.inverse(np.eye(4), GPL_RIGHTY)
    assert exc.value.ErrorCode == -1036


def test_encoder_only_robot_and_undefined_robot() -> None:
    db = default_database("XYZT-GCU")
    encoder = build_model(db, 2)  # robot02.pac: 116 entry 2 is 0, one axis, no kinematics
    assert encoder.axis_count == 1 and not encoder.has_kinematics
    with pytest.raises(GplException) as exc:
        build_model(db, 3)
    assert exc.value.ErrorCode == -1001


def test_axis_count_must_match_the_mask() -> None:
    db = default_database("PF400SX")
    db.set(2000, 6.0, key=1)
    with pytest.raises(GplException) as exc:
        build_model(db)
    assert exc.value.ErrorCode == -1516


def test_gantry_with_only_a_gripper_axis_is_refused() -> None:
    """An axis mask with the servo gripper but no X, Y, Z or theta axis describes no gantry."""
    db = default_database("GANTRY4")
    db.set(2003, 0x10, key=1)
    db.set(2000, 1.0, key=1)
    with pytest.raises(GplException) as exc:
        build_model(db)
    assert exc.value.ErrorCode == -1516
    assert "no X, Y, Z or theta axis" in str(exc.value)


def test_link_lengths_come_from_the_database() -> None:
    db = default_database("PF400SX")
    db.set_pdb_text("0, 250, 200, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0", 16050, key=1)
    model = build_model(db)
    T = model.flange([500, 0, 180 - 1e-9, 0, 100])  # folded: wrist at l1 − l2 = 50 mm
    assert T[0, 3] == pytest.approx(50.0) and T[1, 3] == pytest.approx(0.0, abs=1e-6)


def test_joint_count_mismatch_is_an_argument_error() -> None:
    with pytest.raises(GplException) as exc:
        _gantry().forward([1, 2, 3])
    assert exc.value.ErrorCode == -202


@pytest.mark.parametrize("bad", [np.eye(3), np.full((4, 4), np.nan)])
def test_malformed_targets_are_argument_errors(bad: np.ndarray) -> None:
    with pytest.raises(GplException) as exc:
        _gantry().inverse(bad, 0)
    assert exc.value.ErrorCode == -202
    with pytest.raises(GplException) as exc:
        _gantry().forward([1, 2, math.inf, 0])
    assert exc.value.ErrorCode == -202

"""The kinematics wrappers (``RobotModel.forward``/``flange``/``inverse``) give what the Pinocchio
model and the closed forms give, in GPL units, with the controller's error codes, for every model.

``forward`` reads the tool pose off a millimetre copy of the Pinocchio model with a frame at the
tool tip (base.py); these tests hold it to the SI model's flange times Base and Tool, computed the
long way, including after Tool and Base are assigned.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gplrt.controller.pdb import default_database
from gplrt.geometry.transforms import matrix_to_pose, pose_to_matrix, xyzypr_to_matrix
from gplrt.lang.errors import GplException
from gplrt.motion.kinematics import RobotModel, build_model
from gplrt.motion.kinematics import units

MODELS = ["PF400SX", "PF400SXL", "PF3400SX", "GANTRY4", "ARM6", "XYZT-GCU"]


def _samples(model: RobotModel, n: int = 200, seed: int = 3) -> list[list[float]]:
    rng = np.random.default_rng(seed)
    lower = np.maximum(model.lower_limits, -1e3)
    upper = np.minimum(model.upper_limits, 1e3)
    return [q.tolist() for q in rng.uniform(lower, upper, size=(n, model.axis_count))]


def _long_way(model: RobotModel, q: list[float]) -> np.ndarray:
    """Base · Flange · Tool through the SI Pinocchio model and numpy products."""
    si = [v / 1000.0 if j.linear else math.radians(v) for v, j in zip(q, model.joints)]
    return model.base @ units.se3_to_matrix(model.flange_se3(si)) @ model.tool


@pytest.mark.parametrize("name", MODELS)
def test_forward_and_flange_are_the_si_model_in_mm(name: str) -> None:
    model = build_model(default_database(name))
    for q in _samples(model):
        T = model.forward(q)
        assert np.abs(T - _long_way(model, q)).max() < 1e-9
        assert np.abs(model.flange(q) - model._base_inv @ T @ model._tool_inv).max() < 1e-9
        assert np.array_equal(model.forward(np.array(q)), T) and np.array_equal(model.forward(tuple(q)), T)


@pytest.mark.parametrize("name", ["PF400SX", "PF400SXL", "ARM6", "GANTRY4"])
def test_forward_follows_a_new_tool_and_base(name: str) -> None:
    model = build_model(default_database(name))
    qs = _samples(model, 50)
    model.tool = xyzypr_to_matrix(5.0, -20.0, 130.0, 10.0, 170.0, -30.0)
    model.base = xyzypr_to_matrix(100.0, 50.0, -20.0, 30.0, 0.0, 0.0)
    for q in qs:
        assert np.abs(model.forward(q) - _long_way(model, q)).max() < 1e-9
    model.tool = np.eye(4)
    model.base = np.eye(4)
    for q in qs:
        assert np.abs(model.forward(q) - model.flange(q)).max() < 1e-9


@pytest.mark.parametrize("name", MODELS)
def test_inverse_of_forward_returns_the_joints(name: str) -> None:
    model = build_model(default_database(name))
    for q in _samples(model, 100):
        T = model.forward(q)
        back = model.inverse(T, model.config_of(q), q)
        assert np.abs(np.array(back) - q).max() < 1e-7, (q, back)
        assert model.inverse_pose(matrix_to_pose(T), model.config_of(q), q) == back


@pytest.mark.parametrize("name", ["PF400SX", "GANTRY4", "ARM6"])
def test_bad_joints_and_targets_keep_their_codes(name: str) -> None:
    model = build_model(default_database(name))
    q = _samples(model, 1)[0]
    for bad in (q[:-1], [*q, 0.0], [math.nan, *q[1:]], [*q[:-1], math.inf]):
        for call in (model.forward, model.flange, model.config_of):
            with pytest.raises(GplException) as info:
                call(bad)
            assert info.value.ErrorCode == -202
    T = model.forward(q)
    for target in (T[:3], np.full((4, 4), np.nan), np.where(np.eye(4, dtype=bool), np.inf, T), "not a matrix"):
        with pytest.raises(GplException) as info:
            model.inverse(target, 0, q)  # type: ignore[arg-type]
        assert info.value.ErrorCode == -202


def test_a_robot_without_kinematics_refuses_with_1036() -> None:
    model = RobotModel("bare", 1, 99, build_model(default_database("PF400SX")).joints)
    for call in (lambda: model.forward([0.0] * 5), lambda: model.flange([0.0] * 5),
                 lambda: model.inverse(np.eye(4), 0, [0.0] * 5)):
        with pytest.raises(GplException) as info:
            call()
        assert info.value.ErrorCode == -1036


def test_matrix_to_pose_takes_what_it_took() -> None:
    T = xyzypr_to_matrix(10.0, 25.0, -40.0, 30.0, 45.0, 60.0)
    pose = matrix_to_pose(T)
    assert all(type(v) is float for v in pose)
    assert np.array_equal(pose_to_matrix(pose), T)
    assert matrix_to_pose(T[:3]) == pose == matrix_to_pose(T.tolist())
    assert matrix_to_pose(np.eye(4, dtype=int)) == matrix_to_pose(np.eye(4))
    assert all(type(v) is float for v in matrix_to_pose(np.eye(4, dtype=int)))
    for bad in (np.eye(3), np.eye(4)[None], "x", [[1, 2], [3]]):
        with pytest.raises(GplException) as info:
            matrix_to_pose(bad)  # type: ignore[arg-type]
        assert info.value.ErrorCode == -202


def test_the_gantry_closed_form_is_the_general_steps_to_the_bit() -> None:
    """``GantryModel._plain_inverse`` (the usual case in one method) gives what the general steps
    give, bit for bit on the axes it solves, and leaves them what it does not handle."""
    model = build_model(default_database("GANTRY4"))
    solved = [model._i[r] for r in ("x", "y", "z", "theta")]
    for q in _samples(model, 300, seed=11):
        pose = matrix_to_pose(model.forward(q))
        seed = [v + 1.0 for v in q]
        plain = model._plain_inverse(pose, 0, seed, True)
        general = model._general_inverse(pose, 0, seed, True)
        assert plain is not None
        assert [plain[k] for k in solved] == [general[k] for k in solved]
        assert plain == pytest.approx(general, abs=1e-12)
    q = _samples(model, 1)[0]
    T = model.forward(q)
    x = model._i["x"]
    T[0, 3] = model.upper_limits[x] + 10.0  # beyond X's soft limit: the general steps' -1012
    assert model._plain_inverse(matrix_to_pose(T), 0, q, True) is None
    with pytest.raises(GplException) as info:
        model.inverse(T, 0, q)
    assert info.value.ErrorCode == -1012 and info.value.Axis == x + 1

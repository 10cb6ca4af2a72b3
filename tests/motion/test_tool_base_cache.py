"""RobotModel caches Base⁻¹ and Tool⁻¹: a new Tool/Base takes effect at once, in-place edits are refused."""

from __future__ import annotations

import numpy as np
import pytest

from gplrt.controller.pdb import default_database
from gplrt.geometry.transforms import xyzypr_to_matrix
from gplrt.motion.kinematics import build_model


def test_inverse_follows_each_new_tool_and_base() -> None:
    model = build_model(default_database("PF400SX"))
    q = [300.0, 10.0, 90.0, -20.0, 80.0]
    for tool, base in (((10, 5, 150, 0, 0, 0), (0, 0, 0, 0, 0, 0)),
                       ((0, 0, 80, 0, 0, 0), (100, -50, 20, 30, 0, 0)),
                       ((0, 0, 0, 0, 0, 0), (-20, 40, 0, -45, 0, 0))):
        model.tool = xyzypr_to_matrix(*tool)
        model.base = xyzypr_to_matrix(*base)
        T = model.forward(q)
        assert np.allclose(T, xyzypr_to_matrix(*base) @ model.flange(q) @ xyzypr_to_matrix(*tool), atol=1e-9)
        assert model.inverse(T, 0, q) == pytest.approx(q, abs=1e-9)


def test_tool_and_base_cannot_be_edited_in_place() -> None:
    model = build_model(default_database("PF400SX"))
    with pytest.raises(ValueError):
        model.tool[2, 3] = 50.0
    with pytest.raises(ValueError):
        model.base[0, 3] = 10.0

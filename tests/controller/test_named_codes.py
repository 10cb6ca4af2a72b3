"""Codes raised by the controller services carry their names from the one table (lang/errors.py)."""

from __future__ import annotations

import pytest

from gplrt.controller.pdb import default_database
from gplrt.lang import errors
from gplrt.lang.errors import GplException


def test_unknown_robot_model_is_invalid_robot_type() -> None:
    with pytest.raises(GplException) as info:
        default_database("PF9000")
    assert info.value.ErrorCode == errors.INVALID_ROBOT_TYPE == -221
    assert info.value.Message() == "*Invalid robot type*"
    assert "PF9000" in str(info.value)  # the detail names the model for the Python traceback


def test_new_names_follow_the_controller_texts() -> None:
    assert errors.error_text(errors.INVALID_ROBOT_TYPE) == "Invalid robot type"
    assert errors.error_text(errors.KINEMATICS_NOT_INSTALLED) == "Kinematics not installed"

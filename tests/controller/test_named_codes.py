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


def test_pdb_arguments_convert_by_gpl_rules_not_python_int_or_float() -> None:
    """Controller.PDb/PDbNum from hand-written Python get GPL codes, never a bare ValueError."""
    from gpltest import code_of
    from gplrt.controller.services import Controller
    from gplrt.lang.errors import INVALID_NUMBER_FORMAT
    from gplrt.sim import Simulation

    with Simulation(capture=True):
        assert code_of(Controller.PDbNum, "x") == INVALID_NUMBER_FORMAT
        assert code_of(Controller.PDbNum, 601, "a") == INVALID_NUMBER_FORMAT
        assert code_of(Controller.set_PDbNum, 601, "fast") == INVALID_NUMBER_FORMAT
        Controller.set_PDbNum(601, "40")  # numeric text converts, as a GPL store would
        assert Controller.PDbNum(601.4) == 40.0  # CInt rounding of the DataID


@pytest.mark.parametrize(("name", "code", "text"), [
    ("CANT_DETACH_MOVING_ROBOT", -1008, "Can't detached a moving robot"),
    ("CANT_WRITE_WHEN_POWER_ON", -1522, "Cannot write value when power on"),
    ("POWER_OFF_REQUESTED", -1600, "Power off requested"),
    ("AXIS_OVER_SPEED", -3106, "Axis over-speed"),
    ("SOFT_ENVELOPE_ERROR", -3122, "Soft envelope error"),
])
def test_controller_state_and_servo_codes_are_named_in_the_one_table(name: str, code: int, text: str) -> None:
    """The codes the detach rule, the power sequencer, PDb writes and path motions raise."""
    assert getattr(errors, name) == code
    assert errors.error_text(code) == text

"""Controller's arguments convert by GPL's rules, as a transpiled call would.

Hand-written Python (a notebook, a --setup file) can pass any value: Timer/SleepTick/ErrorLog and
SystemSpeed must answer with the controller's codes (-717 bad numeric text, -782 Nothing, -710 a
NaN or infinite Integer, -707 a NaN speed), never a bare ValueError or TypeError from
int()/float(); Boolean properties read text as CBool does, so the text "False" does not enable
power.
"""

from __future__ import annotations

import math

import pytest

from gplrt.controller.services import Controller
from gplrt.lang.errors import ARITHMETIC_OVERFLOW, INVALID_NUMBER_FORMAT, NOTHING_VALUE, VALUE_OUT_OF_RANGE
from gplrt.sim import Simulation
from gpltest import code_of


@pytest.mark.parametrize(("call", "code"), [
    (lambda: Controller.Timer("now"), INVALID_NUMBER_FORMAT),
    (lambda: Controller.Timer(math.nan), ARITHMETIC_OVERFLOW),
    (lambda: Controller.SleepTick("two"), INVALID_NUMBER_FORMAT),
    (lambda: Controller.SleepTick(math.inf), ARITHMETIC_OVERFLOW),
    (lambda: Controller.ErrorLog(None), NOTHING_VALUE),
    (lambda: setattr(Controller, "SystemSpeed", "fast"), INVALID_NUMBER_FORMAT),
    (lambda: setattr(Controller, "SystemSpeed", math.nan), VALUE_OUT_OF_RANGE),
])
def test_bad_arguments_get_gpl_codes(vsim: Simulation, call: object, code: int) -> None:
    assert code_of(call) == code


def test_numeric_text_converts(vsim: Simulation) -> None:
    Controller.SystemSpeed = "50"
    assert Controller.SystemSpeed == 50.0
    t0 = Controller.Timer("1")
    Controller.SleepTick("2.6")  # CInt rounds to 3 ticks
    assert Controller.Timer(1) - t0 == pytest.approx(3 * Controller.Tick, abs=1e-12)


def test_boolean_text_reads_as_cbool(vsim: Simulation) -> None:
    Controller.PowerEnabled = "False"
    assert not Controller.PowerEnabled
    Controller.RecordButton = "False"
    assert Controller.RecordButton is False
    Controller.SoftEStop = "0"
    assert Controller.SoftEStop is False

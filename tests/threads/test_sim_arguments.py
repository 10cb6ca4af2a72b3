"""The session's Python API names a bad duration argument in a ValueError, instead of failing
deep inside the scheduler with whatever Python error the bad value happened to cause."""

from __future__ import annotations

import numpy as np
import pytest

from gplrt.sim import Simulation


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), -1.0, "abc", True])
def test_run_for_names_a_bad_duration(bad: object) -> None:
    s = Simulation(capture=True)
    with pytest.raises(ValueError, match="seconds must be a finite number of seconds >= 0"):
        s.run_for(bad)  # type: ignore[arg-type]


@pytest.mark.parametrize("bad", [float("nan"), "x", -2])
def test_call_and_run_main_name_a_bad_timeout(bad: object) -> None:
    s = Simulation(capture=True)
    ran: list[bool] = []
    with pytest.raises(ValueError, match="timeout must be"):
        s.call(lambda: ran.append(True), timeout=bad)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="timeout must be"):
        s.run_main(lambda: ran.append(True), timeout=bad)  # type: ignore[arg-type]
    assert s.run_main(lambda: None) == [] and not ran  # refused before anything started


def test_good_durations_still_run() -> None:
    s = Simulation(capture=True)
    s.run_for(np.float64(0.5))
    s.run_for(1)
    assert s.now() == pytest.approx(1.5)
    assert s.run_main(lambda: None, timeout=5) == []

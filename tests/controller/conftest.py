"""Fresh simulation sessions for the controller tests."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from gplrt.sim import Simulation, set_current


@pytest.fixture
def vsim() -> Iterator[Simulation]:
    sim = Simulation(capture=True)
    with sim:
        yield sim
    set_current(None)

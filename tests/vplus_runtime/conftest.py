"""Fixtures of the V+ runtime tests: a captured simulation, active for the test."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from gplrt.sim import Simulation


@pytest.fixture
def sim() -> Iterator[Simulation]:
    s = Simulation(capture=True)
    with s:
        yield s
    s.close()

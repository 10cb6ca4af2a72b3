"""Shared helpers for the thread tests: fresh sessions, procedures written as generated code is."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from gplrt.sim import Simulation, set_current


@pytest.fixture
def vsim() -> Iterator[Simulation]:
    """A fresh virtual-clock session with captured console, active for the test."""
    sim = Simulation(capture=True)
    with sim:
        yield sim
    set_current(None)


@pytest.fixture
def rsim() -> Iterator[Simulation]:
    """A fresh real-clock session (speed 1) with captured console."""
    sim = Simulation(clock="real", capture=True)
    with sim:
        yield sim
    set_current(None)

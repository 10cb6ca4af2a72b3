"""Geometry tests register conveyor belts (a process-wide table in ``gplrt.geometry.refframe``):
every test starts with the table as it found it and leaves it so, whatever it registered and
whether or not it failed, so no test needs its own try/finally."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from gplrt.geometry import refframe


@pytest.fixture(autouse=True)
def _restore_conveyors() -> Iterator[None]:
    saved = dict(refframe._conveyors)
    yield
    refframe._conveyors.clear()
    refframe._conveyors.update(saved)

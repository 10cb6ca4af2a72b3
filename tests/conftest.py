"""Fixtures shared by every test package.

The runtime has process-wide state a test can change: the active session (``gplrt.session``), the
Console sink the simulator installs, the kinematics provider behind ``Location.Here`` and the
table of conveyor belts RefFrames register.  Everything else (flash root, network, robots, ...)
belongs to a session.  ``_isolate_runtime_state`` starts each test with no active session and puts
everything back afterwards, so that no test depends on which tests ran before it.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

# Shared test helpers (tests/gpltest.py) import as a top-level module: test folders are not packages.
sys.path.insert(0, str(Path(__file__).resolve().parent))

from gplrt.geometry import kinematics_provider, refframe
from gplrt.lang.console import get_console_sink, set_console_sink
from gplrt.session import active_session, set_active_session
from gplrt.sim import Simulation


@pytest.hookimpl(wrapper=True)
def pytest_collection(session: pytest.Session) -> Iterator[object]:
    """Marks the collection phase for ``gpltest.shared_dir``: the shared corpus and specs may be
    looked for only while a test runs, because without them a skip at collection time ends the
    whole session ("Interrupted: 1 error during collection") instead of skipping one test."""
    os.environ["GPL2PY_TESTS_COLLECTING"] = "1"
    try:
        return (yield)
    finally:
        del os.environ["GPL2PY_TESTS_COLLECTING"]


@pytest.fixture(autouse=True)
def _isolate_runtime_state() -> Iterator[None]:
    sink = get_console_sink()
    session = active_session()
    provider = kinematics_provider._provider
    conveyors = dict(refframe._conveyors)
    set_active_session(None)
    yield
    set_console_sink(sink)
    set_active_session(session)
    kinematics_provider._provider = provider
    refframe._conveyors.clear()
    refframe._conveyors.update(conveyors)


@pytest.fixture
def vsim() -> Iterator[Simulation]:
    """A fresh virtual-clock session with captured console, active for the test."""
    sim = Simulation(capture=True)
    with sim:
        yield sim


@pytest.fixture
def rsim() -> Iterator[Simulation]:
    """A fresh real-clock session (speed 1) with captured console."""
    sim = Simulation(clock="real", capture=True)
    with sim:
        yield sim

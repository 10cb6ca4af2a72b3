"""Must-show (i) and (ii): deterministic multi-threaded output, and no lost increment under TestAndSet."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from gpltest import Transpiled, transpile
from gplrt.sim import Simulation

#: The GPL projects of these tests (here, not imported from conftest: ``from conftest import``
#: found another folder's conftest when several folders' tests ran in one session).
PROJECTS = Path(__file__).resolve().parent / "projects"

ITEMS = 40
EXPECTED_TOTAL = sum(pid * 1000 + n for pid in (1, 2) for n in range(1, ITEMS + 1))


@pytest.fixture(scope="module")
def prodcons(tmp_path_factory: pytest.TempPathFactory) -> Transpiled:
    return transpile(PROJECTS / "prodcons", tmp_path_factory.mktemp("prodcons"))


@pytest.fixture(scope="module")
def counter(tmp_path_factory: pytest.TempPathFactory) -> Transpiled:
    return transpile(PROJECTS / "counter", tmp_path_factory.mktemp("counter"))


def run_prodcons(sample: Transpiled) -> Simulation:
    sim = Simulation(capture=True)
    assert sample.package.main(sim) == 0
    return sim


def test_producer_consumer_output_is_identical_on_every_virtual_run(prodcons: Transpiled) -> None:
    outputs = [run_prodcons(prodcons).console.output.encode("latin-1") for _ in range(5)]
    assert all(out == outputs[0] for out in outputs[1:])

    lines = outputs[0].decode("latin-1").splitlines()
    items = [int(m.group(1)) for m in map(re.compile(r"^(\d+) @[\d.]+$").match, lines[:-1]) if m]
    assert len(items) == len(lines) - 1 == 2 * ITEMS  # every item consumed exactly once
    assert sorted(items) == sorted(pid * 1000 + n for pid in (1, 2) for n in range(1, ITEMS + 1))
    for pid in (1, 2):  # each producer's items come out in the order it put them in
        mine = [v for v in items if v // 1000 == pid]
        assert mine == sorted(mine)
    assert {v // 1000 for v in items[:10]} == {1, 2}  # the producers really interleave
    assert re.fullmatch(rf"total {EXPECTED_TOTAL} at [\d.]+", lines[-1])


def test_eight_threads_lose_no_increment_in_virtual_time(counter: Transpiled) -> None:
    # a slice of 5 checkpoints switches threads inside the critical section all the time
    sim = Simulation(capture=True, slice_checkpoints=5)
    assert counter.package.main(sim) == 0
    assert sim.console.output == "count 80000\nlock was contended\n"


def test_eight_threads_lose_no_increment_on_the_real_clock(counter: Transpiled) -> None:
    sim = Simulation(clock="real", capture=True)
    assert counter.package.main(sim) == 0
    assert sim.console.output.splitlines()[0] == "count 80000"

"""Conformance suite: every case under manual/ and differential/ must print exactly its .out.

Each case is transpiled with the real gpl2py and run on the simulated controller by a worker
process (``conformance_harness``); a mismatch shows the status, the diagnostics or run error, the
controller log and a unified diff of the expected and actual Console output.  A case must also end
cleanly: an unhandled GPL error or a stalled program is a failure even if the text matched, since
the manual's programs end normally.
"""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from conformance_harness import Case, Worker, discover, explain

CASES = discover()


@pytest.fixture(scope="module")
def worker() -> Iterator[Worker]:
    w = Worker()
    yield w
    w.close()


def test_suite_is_big_enough() -> None:
    """The brief: every runnable manual example, and at least 200 differential cases."""
    differential = [c for c in CASES if c.id.startswith("differential/")]
    manual = [c for c in CASES if c.id.startswith("manual/")]
    assert len(differential) >= 200, len(differential)
    assert len(manual) >= 20, len(manual)


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_case(case: Case, worker: Worker) -> None:
    result = worker.run(case)
    ok = result.status == "ok" and result.output == case.expected_output() and not result.log
    if not ok:
        pytest.fail(explain(case, result), pytrace=False)


def _first_source(case: Case) -> str:
    if case.source.is_file():
        return case.source.read_text(encoding="latin-1")
    gpr = (case.source / "Project.gpr").read_text(encoding="latin-1")
    first = next(line for line in gpr.splitlines() if line.lower().startswith("projectsource"))
    return (case.source / first.split("=", 1)[1].strip().strip('"')).read_text(encoding="latin-1")


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_case_documents_its_expectation(case: Case) -> None:
    """Every case opens with a comment saying where its expected output comes from: a manual
    citation ([000 L..]), a spec section/ambiguity (§n, AMB-n) or a documented gplrt decision."""
    head = _first_source(case).lstrip().splitlines()[0]
    assert head.startswith("'"), f"{case.id}: first line must be the provenance comment"
    comment = "\n".join(line for line in _first_source(case).splitlines() if line.lstrip().startswith("'"))
    assert any(tag in comment for tag in ("[000 L", "§", "AMB-", "gplrt", "gpl-dictionary")), case.id

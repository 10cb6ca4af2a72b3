"""The runs of a sweep in a plain loop in this process, and the rows every engine makes.

The loop (:func:`in_process`) is the reference the Dask engine (``gpl2py.sweep.cluster``) is
compared with: the same parameter set gives the same row in both, whatever order and process the
runs had (tests/sweep checks it), and the benchmark measures Dask's overhead per run against it.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import Any

from gpl2py.sweep.metrics import OUTCOME, Metric, RunRecord
from gpl2py.sweep.params import ParamSet, run_id
from gpl2py.sweep.worker import Setup, SetupSource, Shipment, install, run_one

__all__ = ["in_process", "lost_row", "row_of"]


def row_of(params: ParamSet, result: dict[str, Any]) -> dict[str, Any]:
    """A run's row: its parameters, then what it measured, then its ``run_id``."""
    return {**params, **result, "run_id": run_id(params)}


def lost_row(params: ParamSet, why: str, metrics: list[Metric]) -> dict[str, Any]:
    """The row of a run that never reported back (its worker died, every time it was tried):
    its metrics' columns are there, with no value."""
    unmeasured = {c: None for m in metrics for c in m.columns(RunRecord())}
    return row_of(params, {**dict.fromkeys(OUTCOME), "status": "lost", "error_message": why, **unmeasured})


def in_process(shipment: Shipment, setup: Setup | SetupSource | None, sets: list[ParamSet],
               metrics: list[Metric], timeout: float | None, folder: str | None = None,
               progress: Callable[[int, int], None] | None = None) -> Iterator[dict[str, Any]]:
    """Each run in turn in this process: the reference the engines are compared with."""
    project = install(shipment, folder)
    for done, params in enumerate(sets, start=1):
        yield row_of(params, run_one(project, setup, params, metrics, timeout))
        if progress is not None:
            progress(done, len(sets))

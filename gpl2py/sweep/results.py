"""The sweep's table: rows written as they arrive, so that a crash mid-sweep loses nothing.

Format (decision): while a sweep runs, its rows go to ``OUT.parts/``, a folder beside the output
``OUT`` (``results.parquet`` -> ``results.parquet.parts/``), as small Parquet files, one per
batch (the rows that arrived in about a second).  Each part is written under a temporary name
and renamed into place, so the folder only ever holds complete parts, whatever moment the sweep
(or the machine) stops at.  At the end the parts, and the rows of an earlier ``OUT`` when
resuming, are merged into ``OUT`` (written aside and renamed, too) and the folder is removed.
``--resume`` reads both ``OUT`` and any parts, and skips every parameter set already there;
without it a sweep starts afresh (the old ``OUT`` and parts are removed first).

Why not one Parquet file appended to: Parquet has no append, and a file being rewritten is lost
if the sweep dies halfway.  Why not a text log: Parquet keeps the columns' types (a count stays
an integer, a missing error code stays missing), and a part is read with the same reader as the
final table.

Rows are identified by ``run_id`` (``gpl2py.sweep.params.run_id``): merging keeps one row per
set, and the table is ordered as the parameter sets are, whatever order the runs ended in.
"""

from __future__ import annotations

import os
import shutil
import time
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from gpl2py.sweep.metrics import OUTCOME

__all__ = ["Results", "done", "frame", "parts_folder", "written"]

#: Seconds between two parts: the rows a crash can lose at most are those of the last second.
FLUSH_EVERY = 1.0


def parts_folder(output: Path) -> Path:
    """Where the rows of a sweep writing ``output`` wait to be merged."""
    return output.with_name(output.name + ".parts")


def frame(rows: Iterable[dict[str, Any]], names: list[str], order: list[str] | None = None) -> Any:
    """The rows as a pandas DataFrame: the parameters ``names`` first, then the outcome, then the
    metrics, then ``run_id``; ordered by ``order`` (run ids) when given; one row per run id."""
    import pandas as pd
    import pyarrow

    rows = list({row["run_id"]: row for row in rows}.values())
    if order is not None:
        rank = {rid: i for i, rid in enumerate(order)}
        rows.sort(key=lambda r: rank.get(r["run_id"], len(rank)))
    columns = list(names) + [c for c in OUTCOME if c not in names]
    for row in rows:
        columns += [c for c in row if c not in columns and c != "run_id"]
    columns.append("run_id")
    df = pd.DataFrame.from_records(rows, columns=columns)
    types: dict[str, Any] = {"error_code": "Int64", "error_line": "Int64"}
    for c in ("status", "error_message", "error_file", "error_thread", "stalled_threads", "run_id"):
        types[c] = object
    df = df.astype({c: t for c, t in types.items() if c in df.columns})
    # The types a Parquet file gives back (text columns differ between pandas versions): the table
    # a sweep returns is the one a later read_parquet of its output gives.
    return pyarrow.Table.from_pandas(df, preserve_index=False).to_pandas()


def written(output: Path) -> list[Path]:
    """The files that hold rows of a sweep writing ``output``: ``output`` itself and its parts."""
    parts = parts_folder(output)
    return ([output] if output.exists() else []) + (sorted(parts.glob("part-*.parquet")) if parts.is_dir() else [])


def done(output: Path) -> set[str]:
    """The run ids that have a row in ``output`` or its parts (what ``--resume`` skips)."""
    return {row["run_id"] for path in written(output) for row in _read(path)}


def _read(path: Path) -> list[dict[str, Any]]:
    import pandas as pd

    return list(pd.read_parquet(path).to_dict("records"))


class Results:
    """Rows of one sweep: kept in memory, and written to ``output`` when given (module docstring)."""

    def __init__(self, output: str | Path | None, names: list[str], order: list[str]) -> None:
        self.output = Path(output) if output is not None else None
        self.names = names
        self.order = order
        self.rows: list[dict[str, Any]] = []  # of this sweep and, resuming, of the earlier one
        self._pending: list[dict[str, Any]] = []
        self._last = time.monotonic()
        self._serial = 0

    def open(self, resume: bool) -> set[str]:
        """Prepare the output; returns the run ids already done (resuming), else an empty set."""
        if self.output is None:
            return set()
        if not resume:
            if self.output.exists():
                self.output.unlink()
            shutil.rmtree(parts_folder(self.output), ignore_errors=True)
            return set()
        found = written(self.output)
        for path in found:
            self.rows.extend(_read(path))
        self._serial = len(found)
        return {row["run_id"] for row in self.rows}

    def add(self, row: dict[str, Any]) -> None:
        """Keep ``row``; write the batch when a second has passed since the last one."""
        self.rows.append(row)
        self._pending.append(row)
        if time.monotonic() - self._last >= FLUSH_EVERY:
            self.flush()

    def flush(self) -> None:
        """Write the rows not yet written as one part (renamed into place when complete)."""
        self._last = time.monotonic()
        if self.output is None or not self._pending:
            self._pending.clear()
            return
        parts = parts_folder(self.output)
        parts.mkdir(parents=True, exist_ok=True)
        self._serial += 1
        name = f"part-{self._serial:06d}-{os.getpid()}.parquet"
        temporary = parts / (name + ".tmp")
        frame(self._pending, self.names).to_parquet(temporary, index=False)
        os.replace(temporary, parts / name)
        self._pending.clear()

    def finish(self) -> Any:
        """Merge everything into ``output`` (when given) and return the whole table."""
        self.flush()
        table = frame(self.rows, self.names, self.order)
        if self.output is not None:
            self.output.parent.mkdir(parents=True, exist_ok=True)
            temporary = self.output.with_name(self.output.name + ".tmp")
            table.to_parquet(temporary, index=False)
            os.replace(temporary, self.output)
            shutil.rmtree(parts_folder(self.output), ignore_errors=True)
        return table

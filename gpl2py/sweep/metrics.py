"""What a sweep measures in each run: columns computed from a :class:`RunRecord`.

Why metrics read a record rather than the live simulation: the record is a few plain lists (the
console lines and signal changes with their controller times, each robot's motion summary) taken
by the worker while the run happens, so a metric is a pure function of it -- the same on a Dask
worker and in a plain loop, and nothing holds the simulation (its robots, Ruckig trajectories)
once the run is over.

Every row has the outcome columns (:data:`OUTCOME`: ``status`` -- ok, error, stalled, timeout,
setup error, crashed or lost -- and the first unhandled error's code, message, GPL file and line
and thread) and, by default, :class:`EndTime`, :class:`MotionTime` and :class:`PeakJointSpeeds`.
A user adds :class:`Count` (console lines matching a pattern, or rising edges of a signal) and
:class:`EventTime` (the controller time of the first such line or edge), in Python or in the
parameter file's ``[metrics]`` table (:func:`from_table`)::

    [metrics]
    parts = { count = "^placed part" }      # console lines matching the regular expression
    requests = { count = 2 }                # rising edges of digital signal 2
    done_at = { time = "^cell done" }       # controller time of the first matching line
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Any

__all__ = ["OUTCOME", "Count", "EndTime", "EventTime", "Metric", "MotionSummary", "MotionTime", "PeakJointSpeeds",
           "RunRecord", "default_metrics", "from_table"]

#: The columns every row has, whatever the metrics: how the run ended.
OUTCOME = ("status", "error_code", "error_message", "error_file", "error_line", "error_thread", "stalled_threads")


@dataclass
class MotionSummary:
    """One robot's motion over the run: how long it moved and each joint's peak speed."""

    joints: tuple[str, ...]
    motion_time: float
    peak_speeds: tuple[float, ...]


@dataclass
class RunRecord:
    """What the worker saw of one run (module docstring); times are controller seconds."""

    end_time: float = 0.0
    console: list[tuple[float, str]] = field(default_factory=list)  # complete lines, when written
    signals: list[tuple[float, int, bool]] = field(default_factory=list)  # every digital change
    motion: dict[int, MotionSummary] = field(default_factory=dict)  # by robot number


class Metric:
    """A metric: ``columns(record)`` names its columns and values (NaN when not measured);
    ``claims(name)`` says whether a column of that name may be one of them (a parameter must not
    have that name: its column would be overwritten)."""

    def columns(self, record: RunRecord) -> dict[str, Any]:
        raise NotImplementedError

    def claims(self, name: str) -> bool:
        raise NotImplementedError


@dataclass(frozen=True)
class EndTime(Metric):
    """``end_time``: controller seconds from the start to the end of the program (or its stall)."""

    name: str = "end_time"

    def columns(self, record: RunRecord) -> dict[str, Any]:
        return {self.name: record.end_time}

    def claims(self, name: str) -> bool:
        return name == self.name


@dataclass(frozen=True)
class MotionTime(Metric):
    """``motion_time``: controller seconds during which the robot was moving (blends counted once)."""

    robot: int = 1

    def columns(self, record: RunRecord) -> dict[str, Any]:
        found = record.motion.get(self.robot)
        return {_robot_name("motion_time", self.robot): found.motion_time if found else 0.0}

    def claims(self, name: str) -> bool:
        return name == _robot_name("motion_time", self.robot)


@dataclass(frozen=True)
class PeakJointSpeeds(Metric):
    """``peak_speed_<joint>``: each joint's highest speed in the run (deg/s or mm/s), sampled at the
    trajectory generator's period.  Columns only for a robot that moved."""

    robot: int = 1

    def columns(self, record: RunRecord) -> dict[str, Any]:
        found = record.motion.get(self.robot)
        if found is None:
            return {}
        return {_robot_name(f"peak_speed_{j}", self.robot): v for j, v in zip(found.joints, found.peak_speeds)}

    def claims(self, name: str) -> bool:
        return name.startswith("peak_speed_") and (self.robot == 1 or name.endswith(f"_r{self.robot}"))


def _robot_name(column: str, robot: int) -> str:
    return column if robot == 1 else f"{column}_r{robot}"


@dataclass(frozen=True)
class _Source:
    """Console lines matching ``console`` (a regular expression), or changes of digital signal
    ``signal`` to ``value`` (its rising edges by default)."""

    name: str
    console: str | None = None
    signal: int | None = None
    value: bool = True

    def __post_init__(self) -> None:
        if (self.console is None) == (self.signal is None):
            raise ValueError(f"metric {self.name}: give a console pattern or a signal number, one of them")
        if self.console is not None:
            try:
                re.compile(self.console)
            except re.error as exc:
                raise ValueError(f"metric {self.name}: {self.console!r} is not a regular expression: {exc}") from None

    def times(self, record: RunRecord) -> list[float]:
        """The controller times of each matching line or change, in order."""
        if self.console is not None:
            pattern = re.compile(self.console)
            return [t for t, line in record.console if pattern.search(line)]
        return [t for t, n, v in record.signals if n == self.signal and v == self.value]

    def claims(self, name: str) -> bool:
        return name == self.name


@dataclass(frozen=True)
class Count(_Source, Metric):
    """How many console lines matched, or how many times the signal went to ``value``."""

    def columns(self, record: RunRecord) -> dict[str, Any]:
        return {self.name: len(self.times(record))}


@dataclass(frozen=True)
class EventTime(_Source, Metric):
    """The controller time of the first matching line or signal change (NaN if it never came)."""

    def columns(self, record: RunRecord) -> dict[str, Any]:
        found = self.times(record)
        return {self.name: found[0] if found else math.nan}


def default_metrics() -> list[Metric]:
    """What a sweep measures unless told otherwise: time to the end, motion time, peak speeds."""
    return [EndTime(), MotionTime(), PeakJointSpeeds()]


def from_table(table: dict[str, Any]) -> list[Metric]:
    """The ``[metrics]`` table of a parameter file (module docstring), after the defaults."""
    out = default_metrics()
    for name, spec in table.items():
        if not isinstance(spec, dict) or len(spec) != 1 or next(iter(spec)) not in ("count", "time"):
            raise ValueError(f"metric {name}: write {{ count = ... }} or {{ time = ... }}")
        kind, what = next(iter(spec.items()))
        if isinstance(what, bool) or not isinstance(what, (str, int)):
            raise ValueError(f"metric {name}: a console pattern (text) or a signal number, not {what!r}")
        where = {"console": what} if isinstance(what, str) else {"signal": what}
        out.append((Count if kind == "count" else EventTime)(name, **where))
    return out

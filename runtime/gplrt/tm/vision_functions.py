"""TMscript's vision functions (L17229-L17641) and ``File_CopyImage``/``File_GetImage``
(L11737-L11895) on the robot's vision backend (``gplrt.tm.vision``, ``Robot.vision``).

``Vision_DoJob(job)`` runs a job without an initial position at once; ``Vision_DoJob_PTP`` and
``Vision_DoJob_Line`` (``do_job_ptp``/``do_job_line``, which the library gives its script's
cancellation) queue a move to the job's initial position (when it has one) and the job
after it, with the motions, and return once the job has run (their result is the job's, L17280).
False when the job fails, does not exist, or (``Vision_DoJob``) has an initial position (L17247).
"""

from __future__ import annotations

import builtins
from collections.abc import Callable

from gplrt.tm import context
from gplrt.tm.motion import CARTESIAN_SPEED, line_path
from gplrt.tm.members import Members
from gplrt.tm.teach import LiveArray, TBase
from gplrt.tm.values import Array, TMError, to_bool, to_double, to_int, to_string
from gplrt.tm.vision import JobResult, Vision, copy_image

#: Acceleration time (ms) of ``Vision_DoJob_Line(job, speedPct)``, which gives none.
DEFAULT_ACCEL_MS = 200.0


def _vision() -> Vision:
    return context.robot().vision  # type: ignore[no-any-return]


def _apply(job: str, result: JobResult | None) -> bool:
    """The job's outcome as the script sees it; a passing job with a base updates ``vision_<job>``."""
    if result is None:
        return False
    if result.passed and result.base is not None:
        TBase(f"vision_{job}", "V", Array("float", result.base))
    return bool(result.passed)


def _run(job: str) -> JobResult | None:
    r = context.robot()
    return _vision().run(job, r.sim.files.root().box, r.sim.project)


def Vision_DoJob(job: object) -> bool:
    """Run a job that has no initial position (L17229)."""
    name = to_string(job)
    exists, initial = _vision().initial(name)
    if not exists or initial is not None:
        return False
    return _apply(name, _run(name))


def _queued(name: str, move: object, cancelled: Callable[[], bool]) -> bool:
    r = context.robot()
    exists, initial = _vision().initial(name)
    if not exists:
        return False
    if initial is not None:
        r.enqueue(move(r, initial))  # type: ignore[operator]
    ran, result = r.run_queued(lambda: _run(name), cancelled)
    return _apply(name, result if ran else None)  # type: ignore[arg-type]


def do_job_ptp(job: object, speed: object, accel: object, smart_pose: object = False,
               cancelled: Callable[[], bool] = lambda: False) -> bool:
    """``Vision_DoJob_PTP``: PTP to the job's initial position (queued), then the job (L17262).
    ``smart_pose``: the arm keeps its configuration either way (no teaching pose is recorded
    here).  ``cancelled``: the script's wait must end (a Listen node's priority command)."""
    to_bool(smart_pose)
    pct, ms = float(to_double(speed)), float(to_double(accel))
    return _queued(to_string(job), lambda r, pose: r.ptp_pose(pose, pct, ms), cancelled)


def do_job_line(job: object, speed: object, accel: object = None, link: object = True,
                cancelled: Callable[[], bool] = lambda: False) -> bool:
    """``Vision_DoJob_Line``: Line to the job's initial position (queued), then the job (L17319):
    ``(job, speed %)`` or ``(job, mm/s, accel ms [, link to the project speed])``."""
    to_bool(link)
    if accel is None:
        mm_s, ms = CARTESIAN_SPEED * float(to_double(speed)) / 100.0, DEFAULT_ACCEL_MS
    else:
        mm_s, ms = float(to_double(speed)), float(to_double(accel))
    return _queued(to_string(job), lambda r, pose: r.path_move(line_path(lambda: r.cartesian_target(pose)), mm_s, ms),
                   cancelled)


def Vision_IsJobAvailable(job: object) -> bool:
    """Whether the project has the job (L17401)."""
    return _vision().available(to_string(job))


def Vision_GetOutputArraySize(variable: object, row: object = None) -> int:
    """The rows (objects found) of a 2-D output, or the length of row ``row`` (L17430)."""
    rows = _vision().rows(to_string(variable))
    if row is None:
        return len(rows)
    return len(_row(rows, to_int(row), variable))


def _row(rows: list[list[str]], i: int, variable: object) -> list[str]:
    if not 0 <= i < len(rows):
        raise TMError(f"{to_string(variable)}[{i}]: Exceeded the access range (find object count: {len(rows)}, "
                      f"index: 0 .. {len(rows) - 1})")  # (the manual's words, L17549)
    return rows[i]


def Vision_GetOutputArrayValue(variable: object, row: object, col: object = None) -> object:
    """Row ``row`` of a 2-D output (``string[]``), or its element ``col`` (L17469); an error out of
    range (L17549)."""
    r = _row(_vision().rows(to_string(variable)), to_int(row), variable)
    if col is None:
        return Array("string", list(r))
    c = to_int(col)
    if not 0 <= c < len(r):
        raise TMError(f"{to_string(variable)}[{to_int(row)}, {c}]: Exceeded the access range (index: 0 .. {len(r) - 1})")
    return r[c]


def Vision_GetTriggerJobOutputCount(variable: object) -> int:
    """Results of an IO-triggered job waiting in its buffer (L17552)."""
    v = _vision()
    with v.lock:
        return len(v.triggers.get(to_string(variable), ()))


def Vision_GetTriggerJobOutputValue(variable: object) -> Array:
    """The oldest result of an IO-triggered job, taken from its buffer; ``{}`` when empty (L17572)."""
    v = _vision()
    with v.lock:
        fifo = v.triggers.get(to_string(variable))
        return Array("string", fifo.popleft() if fifo else [])


def get_image(timeout_ms: object = -1, cancelled: Callable[[], bool] = lambda: False) -> Array:
    """``File_GetImage``: the oldest ``{source, result}`` image paths (L11845), waiting up to
    ``timeout_ms`` of controller time (< 0: until one comes, 0: a look); ``{"", ""}`` when none."""
    r = context.robot()
    v = _vision()
    limit = to_int(timeout_ms)
    end = r.clock.now() + builtins.max(0, limit) / 1000.0
    with r.sched.adopted():
        while True:
            found = v.pop_image()
            if found is not None:
                return Array("string", list(found))
            if limit == 0 or (limit > 0 and r.clock.reached(end)) or cancelled():
                return Array("string", ["", ""])
            r.sched.wait(r.changed, None if limit < 0 else end)


def File_CopyImage(src: object, folder: object, *rest: object) -> bool:
    """Copy a saved vision image to the (simulated) USB drive (L11737): ``(src, dir)``,
    ``(src, dir, name)``, ``(src, dir, option)`` or ``(src, dir, name, option)``."""
    name, option = "", 0
    if len(rest) == 1 and not isinstance(rest[0], str):
        option = to_int(rest[0])
    elif rest:
        name = to_string(rest[0])
        if len(rest) > 1:
            option = to_int(rest[1])
    r = context.robot()
    return copy_image(_vision(), r.sim.files.root().box, to_string(src), to_string(folder), name, option)


class _VPoint(Members):
    """``VPoint[job]``: the initial position of a vision job (L14559): ``Value`` read and
    written (the job then starts there), ``BaseName``, ``TeachValue`` (the position it was
    registered with)."""

    BaseName = "RobotBase"

    def __init__(self, vision: Vision, job: str) -> None:
        self._vision, self._job = vision, job
        self.tm_name = f'VPoint["{job}"]'

    def _entry(self):  # type: ignore[no-untyped-def]
        entry = self._vision.jobs.get(self._job)
        if entry is None or entry.initial is None:
            raise TMError(f'VPoint["{self._job}"] does not exist')
        return entry

    @property
    def Value(self) -> Array:
        return LiveArray("float", self._entry().initial, lambda vals: setattr(self, "Value", vals))

    @Value.setter
    def Value(self, v: object) -> None:
        vals = [float(to_double(x)) for x in v] if isinstance(v, (list, tuple)) else []
        if len(vals) != 6:
            raise TMError(f'VPoint["{self._job}"].Value: six values are needed')
        self._entry().initial = vals

    @property
    def TeachValue(self) -> Array:
        entry = self._entry()
        return Array("float", entry.taught if entry.taught is not None else entry.initial)


class _VPoints:
    item = _VPoint  # (what ``VPoint[job]`` gives)

    def __getitem__(self, key: object) -> _VPoint:
        return _VPoint(_vision(), to_string(key[0] if isinstance(key, tuple) else key))


#: ``VPoint["job"]`` (L14559).
VPoint = _VPoints()

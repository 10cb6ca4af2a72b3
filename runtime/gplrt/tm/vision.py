"""TMvision on the simulated robot: a pluggable backend that the user fills (manual §12.19-§13.5,
L17229-L17641; ``File_CopyImage``/``File_GetImage``, L11737-L11895).

There is no camera.  A notebook or a test registers what a vision job finds
(``robot.vision.register("job1", passed=True, outputs={...}, source_image=b"...")``): pass or
fail, the output variables it writes (``job1_Count_Blob_1_DetectObjectX_TM``: a 2-D string array,
one row per object found), the images it saves, the initial position it starts from (a TCP pose
in the robot base, TMflow's "Start at Initial Position") and the vision base it updates
(``vision_<job>``).  Results registered several times are used in turn, the last one again.
A job that is not registered is one the project does not have: ``Vision_IsJobAvailable`` is
false and running it "fails to execute" (false, L17247).

Images are written when a job runs, in the robot's flash sandbox (``Simulation.files``, docs/security.md)
under ``Vision/<project>/<job>/<date>/source|result/<HH-mm-ss_fff>.png``; their paths
(``\\Vision\\...``) go to the 60-entry image FIFO ``File_GetImage`` pops (L11845).
``File_CopyImage`` copies such an image to the simulated USB drive (``\\USB\\<label>``, the
sandbox's ``USB/`` folder); a local folder (``.\\TextFiles``, L11760) is refused; a network
share is not simulated.
"""

from __future__ import annotations

import datetime
import re
import threading
from collections import deque
from dataclasses import dataclass, field
from typing import Any

from gplrt.io.sandbox import Sandbox
from gplrt.lang.errors import GplException
from gplrt.tm.values import TMError

#: Image paths ``File_GetImage`` keeps (L11849).
IMAGE_FIFO = 60
#: IO-trigger results kept per output variable (the manual gives no figure, L17596).
TRIGGER_FIFO = 100


@dataclass
class JobResult:
    """What one run of a vision job finds (see the module docstring)."""

    passed: bool = True
    #: Output variables: name -> a value, a string array, or a 2-D string array (rows of objects).
    outputs: dict[str, Any] = field(default_factory=dict)
    source_image: bytes | None = None
    result_image: bytes | None = None
    #: The vision base the job updates (``vision_<job>``, a pose in mm and degrees), or None.
    base: list[float] | None = None


@dataclass
class VisionJob:
    name: str
    #: The initial position (a TCP pose in the robot base), or None: the job has none.
    initial: list[float] | None = None
    results: deque[JobResult] = field(default_factory=deque)
    runs: int = 0
    #: The initial position as registered (``VPoint[job].TeachValue``; ``Value`` may move it).
    taught: list[float] | None = None


class Vision:
    """One robot's vision backend: the jobs registered, the outputs of the last runs, the image
    FIFO and the IO-trigger FIFOs."""

    def __init__(self) -> None:
        self.jobs: dict[str, VisionJob] = {}
        self.outputs: dict[str, Any] = {}
        self.images: deque[tuple[str, str]] = deque(maxlen=IMAGE_FIFO)
        self.triggers: dict[str, deque[list[str]]] = {}
        self.lock = threading.Lock()
        #: Called when images arrive (the robot wakes a ``File_GetImage`` waiting).
        self.on_change: Any = None

    # --- what the user registers ----------------------------------------------------------------
    def register(self, job: str, passed: bool = True, outputs: dict[str, Any] | None = None,
                 source_image: bytes | None = None, result_image: bytes | None = None,
                 base: list[float] | None = None, initial: list[float] | None = None) -> VisionJob:
        """Add a result of ``job`` (making the job exist); ``initial`` sets its initial position."""
        with self.lock:
            entry = self.jobs.setdefault(job, VisionJob(job))
            if initial is not None:
                entry.initial = [float(v) for v in initial]
                entry.taught = list(entry.initial)
            entry.results.append(JobResult(passed, dict(outputs or {}), source_image, result_image,
                                           None if base is None else [float(v) for v in base]))
            return entry

    def remove(self, job: str) -> None:
        with self.lock:
            self.jobs.pop(job, None)

    def trigger(self, variable: str, values: list[str]) -> None:
        """An IO-triggered job wrote ``values`` to ``variable`` (``Vision_GetTriggerJobOutput*``)."""
        with self.lock:
            fifo = self.triggers.setdefault(variable, deque(maxlen=TRIGGER_FIFO))
            fifo.append([str(v) for v in values])

    # --- running a job (the robot's side) -------------------------------------------------------
    def available(self, job: str) -> bool:
        with self.lock:
            entry = self.jobs.get(job)
            return entry is not None and bool(entry.results)

    def initial(self, job: str) -> tuple[bool, list[float] | None]:
        """(whether the job exists, its initial position)."""
        with self.lock:
            entry = self.jobs.get(job)
            return (False, None) if entry is None or not entry.results else (True, entry.initial)

    def run(self, job: str, box: Sandbox, project: str) -> JobResult | None:
        """Run ``job``: its next result (None: no such job), its outputs and images recorded."""
        with self.lock:
            entry = self.jobs.get(job)
            if entry is None or not entry.results:
                return None
            result = entry.results.popleft() if len(entry.results) > 1 else entry.results[0]
            entry.runs += 1
            self.outputs.update({k: _stored(v) for k, v in result.outputs.items()})
        paths = self._save_images(job, result, box, project)
        if paths is not None:
            with self.lock:
                self.images.append(paths)
            if self.on_change is not None:
                self.on_change()
        return result

    def _save_images(self, job: str, result: JobResult, box: Sandbox, project: str) -> tuple[str, str] | None:
        if result.source_image is None and result.result_image is None:
            return None
        now = datetime.datetime.now()
        stamp = now.strftime("%H-%M-%S_") + f"{now.microsecond // 1000:03d}.png"
        folder = ["Vision", _safe(project or "Project"), _safe(job), now.strftime("%Y%m%d")]
        out = []
        for kind, data in (("source", result.source_image), ("result", result.result_image)):
            if data is None:
                out.append("")
                continue
            parts = [*folder, kind]
            here: list[str] = []
            for name in parts:
                here.append(name)
                box.path(*here).ensure_folder()
            box.path(*parts, stamp).write_bytes(data)
            out.append("\\" + "\\".join([*parts, stamp]))
        return out[0], out[1]

    def pop_image(self) -> tuple[str, str] | None:
        with self.lock:
            return self.images.popleft() if self.images else None

    # --- the output variables -------------------------------------------------------------------
    def rows(self, variable: str) -> list[list[str]]:
        with self.lock:
            if variable not in self.outputs:
                raise TMError(f"the vision output variable {variable!r} does not exist")
            value = self.outputs[variable]
        if isinstance(value, list) and all(isinstance(r, list) for r in value):
            return value
        raise TMError(f"the vision output variable {variable!r} is not a 2-D array")


def _stored(value: Any) -> Any:
    """An output value as the job writes it: text, a string array, or rows of strings."""
    if isinstance(value, (list, tuple)):
        if all(isinstance(r, (list, tuple)) for r in value):
            return [[str(x) for x in r] for r in value]
        return [str(x) for x in value]
    return value


_UNSAFE = re.compile(r"[^A-Za-z0-9_.-]")


def _safe(name: str) -> str:
    """A folder name made of the characters a file name can always hold, never ``.``/``..``
    nor hidden (a leading dot)."""
    return _UNSAFE.sub("_", name).lstrip(".") or "_"


def copy_image(vision: Vision, box: Sandbox, src: str, dst: str, name: str, option: int) -> bool:
    """``File_CopyImage`` (see the module docstring): True when copied."""
    fail_error = bool(option & 2)

    def fail(why: str) -> bool:
        if fail_error:
            raise TMError(f"File_CopyImage: {why}")
        return False
    target = dst.replace("/", "\\")
    low = target.lower()
    if not low.startswith("\\usb\\") and not low.startswith("\\\\usb\\"):
        if low.startswith("\\\\"):
            return fail(f"{dst}: network shares are not simulated")
        return False  # a local folder: not supported (L11760; the examples answer false even with option 2)
    src_parts = [p for p in re.split(r"[\\/]+", src) if p]
    if len(src_parts) < 2 or src_parts[0].lower() != "vision" or any(p in (".", "..") for p in src_parts):
        return fail(f"{src}: not a saved vision image")
    try:
        data = box.path("Vision", *src_parts[1:]).read_bytes()
    except (OSError, GplException):
        return fail(f"{src}: the image does not exist")
    dst_parts = [p for p in re.split(r"[\\/]+", target) if p][2:]  # (below \USB\<label>)
    keep = src_parts[1:-1] if option & 1 else []
    file_name = name or src_parts[-1]
    parts = ["USB", *dst_parts, *keep]
    if any(p in (".", "..") or "\0" in p for p in [*parts, file_name]) or re.search(r"[\\/]", file_name):
        return fail(f"{dst}\\{file_name}: an invalid path")
    here: list[str] = []
    for p in parts:
        here.append(p)
        box.path(*here).ensure_folder()
    box.path(*parts, file_name).write_bytes(data)
    return True


__all__ = ["JobResult", "Vision", "VisionJob", "copy_image"]

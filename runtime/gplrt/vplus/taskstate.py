"""The state V+ keeps per task, and the safepoint where fired reactions run (used by every module).

Tasks are the core's threads (``gplrt.threads.thread.Thread``) on the session's clock, numbered
0..27 (L882-884, L1360).  A thread the layer did not start (the main program run by
``Simulation.run_main`` or ``vp.run``, a test) is task 0 [D].

REACTE (docs/design/vplus-runtime.md §7): generated code makes each statement a resumable unit,
``with vp.step(line): ...``.  When a V+ error leaves the block and the task has a REACTE program,
that program is called right there, on top of the failing frame, at program priority 254, and the
error is then suppressed, so execution goes on with the next statement: V+'s RETURNE (L5154-5160).

REACT/REACTI (L4492-4572): a signal transition is latched when the core's ``IoMap`` reports it;
the reaction program runs at the task's next safepoint (``step`` entry, ``safepoint()``, and every
wait of this layer) if its priority is above the task's program priority, else when ``lock``
lowers it.  A reaction is one-shot (spec Q5): it disarms when it fires.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from gplrt.controller.signals import SignalChange
from gplrt.motion import registry
from gplrt.motion.robot_class import Robot
from gplrt.session import current_session
from gplrt.threads.thread import Thread
from gplrt.vplus.signals import vplus_number
from gplrt.vplus.values import session_data

MAX_TASK = 27
CYCLE = 0.016  # the 16 ms major cycle (L1341-1438)
REACTE_PRIORITY = 254


class TaskEnd(BaseException):
    """HALT / STOP: the task ends here (not an error: REACTE never sees it)."""

    def __init__(self, kind: str) -> None:
        super().__init__(kind)
        self.kind = kind


@dataclass
class Reaction:
    signal: int
    program: Callable[..., Any]
    args: tuple[Any, ...]
    priority: int
    immediate: bool  # REACTI: brake as well
    fired: bool = False


@dataclass
class TaskState:
    """What V+ keeps per task: its number, program priority, traps, reactions, modal motion."""

    number: int
    priority: int = 0
    reacte: Callable[..., Any] | None = None
    in_reacte: bool = False
    last_error: int = 0
    reactions: dict[int, Reaction] = field(default_factory=dict)
    pending: list[Reaction] = field(default_factory=list)
    thread: Thread | None = None
    motion: Any = None  # gplrt.vplus.motion.MotionState, made on first motion
    luns: dict[int, Any] = field(default_factory=dict)  # gplrt.vplus.luns


def _tables() -> tuple[dict[Any, TaskState], dict[int, TaskState], threading.RLock]:
    data = session_data()
    extra = data.extra
    if "tasks" not in extra:
        with data.lock:
            if "tasks" not in extra:
                extra["tasks_by_key"] = {}
                extra["tasks"] = {}
                _install_listener()
    return extra["tasks_by_key"], extra["tasks"], data.lock


def current_task() -> TaskState:
    """The calling task's state (task 0 for a thread the layer did not start)."""
    by_key, by_number, lock = _tables()
    key = registry.thread_key()
    task = by_key.get(key)
    if task is None:
        with lock:
            task = by_key.get(key)
            if task is None:
                task = TaskState(0)
                by_key[key] = task
                by_number.setdefault(0, task)
    return task


def _sleep(seconds: float) -> None:
    current_session().scheduler.sleep(seconds)


def safepoint() -> None:
    """Run the reactions that fired, if their priority is above the program's."""
    task = current_task()
    if task.pending:
        _run_reactions(task)


def _run_reactions(task: TaskState) -> None:
    while True:
        ready = [r for r in task.pending if r.priority > task.priority]
        if not ready:
            return
        r = max(ready, key=lambda x: x.priority)
        task.pending.remove(r)
        if r.immediate:
            Robot.do_RapidDecel(1)  # REACTI also stops the robot (L4498-4500)
        saved = task.priority
        task.priority = r.priority
        try:
            r.program(*r.args)
        finally:
            task.priority = saved


def _install_listener() -> None:
    session = current_session()
    data = session_data(session)

    def on_change(change: SignalChange) -> None:
        if change.kind != "DIO":
            return
        n = vplus_number(change.signal)
        tasks: dict[Any, TaskState] = data.extra.get("tasks_by_key", {})
        for task in list(tasks.values()):
            r = task.reactions.get(n)
            if r is None:
                continue
            if (r.signal > 0) == bool(change.value):
                task.reactions.pop(n, None)  # one-shot
                task.pending.append(r)

    session.io.on_change(on_change)



"""V+ tasks by number, events, waits, timers, and the reaction instructions (REACT, REACTI, REACTE).

The per-task state and the safepoint where fired reactions run are in ``taskstate`` (every module
of the layer reaches them); see it for how REACTE and REACT work.
"""

from __future__ import annotations

import datetime
from collections.abc import Callable
from typing import Any

from gplrt.lang.errors import GplException
from gplrt.motion import registry
from gplrt.session import current_session
from gplrt.sim import current as current_sim
from gplrt.threads.thread import Thread
from gplrt.vplus.errors import ILLEGAL_VALUE, NOT_IMPLEMENTED, TASK_IN_USE, VError, from_core
from gplrt.vplus.luns import detach_all
from gplrt.vplus.operators import to_int
from gplrt.vplus.signals import core_number
from gplrt.vplus.taskstate import (
    CYCLE, MAX_TASK, REACTE_PRIORITY, Reaction, TaskEnd, TaskState, _run_reactions, _sleep, _tables,
    current_task, safepoint,
)
from gplrt.vplus.values import find_program, session_data

__all__ = ["CYCLE", "TaskEnd", "TaskState", "current_task", "safepoint", "time_"]


# -- EXECUTE / ABORT --------------------------------------------------------------------------------

def execute(task: Any, prog: Any, *args: Any, cycles: Any = 1) -> None:
    """``EXECUTE task prog(args)``: start ``prog`` as task ``task`` (L941-945)."""
    n = to_int(task)
    if not 0 <= n <= MAX_TASK:
        raise VError(ILLEGAL_VALUE, detail=f"task {n}")
    fn = find_program(prog)
    by_key, by_number, lock = _tables()
    session = current_session()
    with lock:
        old = by_number.get(n)
        if old is not None and old.thread is not None and old.thread._active:
            raise VError(TASK_IN_USE, detail=f"task {n}")
        state = TaskState(n)
        by_number[n] = state
    if old is not None:
        detach_all(old)  # a task stopped by an error kept its devices until run again (as KILL)
    count = to_int(cycles)

    def body() -> None:
        key = registry.thread_key()
        with lock:
            by_key[key] = state
        try:
            _cycles(fn, args, count)
        except GplException:
            # Stopped by an error: "most device attachments are preserved" (L7476-7480) -- the
            # task could be resumed (L915-917) -- so its files and connections stay open, and
            # are closed when the task is run again or the session stops (_release_stopped).
            raise
        except BaseException:
            detach_all(state)  # ABORT, the session stopping
            raise
        else:
            detach_all(state)  # ended normally: every device detached (L7476-7477)
        finally:
            with lock:
                by_key.pop(key, None)

    thread = Thread(body, 0.0, f"task {n}", _session=session)
    thread._start_name = getattr(fn, "vplus_name", getattr(fn, "__name__", "program"))
    state.thread = thread
    thread.Start()


def _cycles(fn: Callable[..., Any], args: tuple[Any, ...], count: int) -> None:
    """Run ``fn`` for ``count`` execution cycles (0: forever); STOP ends a cycle, HALT them all."""
    remaining = count
    while True:
        try:
            fn(*args)
        except TaskEnd as end:
            if end.kind == "STOP" and remaining != 1:
                remaining -= 1
                continue
            return
        remaining -= 1
        if remaining == 0 or count == 0:
            return


def abort(task: Any) -> None:
    """``ABORT task``: stop the task (it ends at its next scheduling point)."""
    n = to_int(task)
    _, by_number, _ = _tables()
    state = by_number.get(n)
    if state is not None and state.thread is not None and state.thread._active:
        state.thread.Abort()


def task_status(task: Any) -> float:
    """-1 while task ``task`` runs, else 0 (a small part of ``TASK()``)."""
    _, by_number, _ = _tables()
    state = by_number.get(to_int(task))
    running = state is not None and (state.thread is None or state.thread._active)
    return -1.0 if running else 0.0


def halt() -> None:
    raise TaskEnd("HALT")


def stop() -> None:
    raise TaskEnd("STOP")


def pause() -> None:
    """``PAUSE``: [D] ends the task (a simulation has no operator to PROCEED)."""
    raise TaskEnd("PAUSE")


# -- waits, events, interlocks ----------------------------------------------------------------------

def wait() -> None:
    """``WAIT``: to the next 16 ms cycle."""
    safepoint()
    _sleep(CYCLE)
    safepoint()


def wait_for(condition: Callable[[], Any]) -> None:
    """``WAIT expr``: re-test every cycle until the expression is nonzero (L1435-1438)."""
    while True:
        safepoint()
        if condition() != 0:
            return
        _sleep(CYCLE)


def release(task: Any = None) -> None:
    """``RELEASE``: let other tasks run."""
    _sleep(0.0)


def _thread_of(task: Any) -> Thread:
    n = to_int(task)
    _, by_number, _ = _tables()
    state = by_number.get(n)
    if state is None or state.thread is None:
        if n == current_task().number:
            return Thread.CurrentThread()
        raise VError(ILLEGAL_VALUE, detail=f"task {n} is not running")
    return state.thread


def set_event(task: Any, flags: Any = 1) -> None:
    """``SET.EVENT task``: set the task's event flag (L4677)."""
    _thread_of(task).SendEvent(to_int(flags) or 1)


def clear_event(task: Any = None, flags: Any = 1) -> None:
    """``CLEAR.EVENT``: clear the calling task's flag."""
    me = Thread.CurrentThread() if task is None else _thread_of(task)
    me._events &= ~(to_int(flags) or 1)


def get_event(task: Any = None) -> float:
    me = Thread.CurrentThread() if task is None else _thread_of(task)
    return float(me._events)


def wait_event(mask: Any = None, timeout: Any = None) -> float:
    """``WAIT.EVENT [mask], [timeout]``: wait for SET.EVENT or ``timeout`` seconds (L4474-4490);
    [D] the flag seen is cleared.  Returns the flags seen (0 on timeout)."""
    safepoint()
    m = 1 if mask is None else (to_int(mask) or 1)
    ms = -1 if timeout is None else max(0, int(round(float(timeout) * 1000.0)))
    if ms == 0:
        ms = 1  # (0 means "do not wait" to the core; a zero timeout still yields)
    got = Thread.WaitEvent(m, ms)
    safepoint()
    return float(got)


def tas(ref: Any, new: Any) -> float:
    """``TAS(var, new)``: the old value, ``new`` stored, atomically (L5546-5552)."""
    lock = session_data().lock
    with lock:
        old = ref.v if ref.defined else 0.0
        ref.v = new
    return float(old)


def cas(ref: Any, test: Any, new: Any) -> float:
    lock = session_data().lock
    with lock:
        old = ref.v if ref.defined else 0.0
        if old == test:
            ref.v = new
    return float(old)


# -- timers -------------------------------------------------------------------------------------------

def _timers() -> dict[int, float]:
    return session_data().extra.setdefault("timers", {})


def timer(n: Any = 1) -> float:
    """``TIMER(n)``: seconds since ``TIMER n =`` last set it (since the start when never set)."""
    now = current_session().now()
    return now - _timers().get(to_int(n), 0.0)


def timer_set(n: Any, value: Any) -> None:
    _timers()[to_int(n)] = current_session().now() - float(value)


def s_time() -> str:
    """``$TIME``: the date and time, [D] the virtual clock counted from 01-JAN-2026 00:00:00."""
    t = datetime.datetime(2026, 1, 1) + datetime.timedelta(seconds=current_session().now())
    return t.strftime("%d-%b-%Y %H:%M:%S").upper()


def time_(text: Any = None) -> float:
    """``TIME(...)`` (function): [D] seconds since the virtual clock's midnight of 01-JAN-2026 (the
    same clock as ``$TIME``); a date string argument is not interpreted yet (*Not implemented*)."""
    if text is not None:
        raise VError(NOT_IMPLEMENTED, detail="TIME of a date string")
    return current_session().now() % 86400.0


def tps() -> float:
    """``TPS``: ticks per second (the 16 ms cycle counts 62.5 ticks)."""
    return 1.0 / CYCLE


# -- REACTE -------------------------------------------------------------------------------------------

def reacte(prog: Any) -> None:
    """``REACTE prog``: arm the task's error trap (``None`` disarms)."""
    current_task().reacte = None if prog is None else find_program(prog)


def error(which: Any = -1) -> float:
    """``ERROR(...)``: [D] the code of the task's last trapped or stopping error, for any argument."""
    return float(current_task().last_error)


class step:
    """``with vp.step(line):`` one resumable V+ statement (see the module docstring)."""

    __slots__ = ("line",)

    def __init__(self, line: int = 0) -> None:
        self.line = line

    def __enter__(self) -> step:
        task = current_task()
        if task.pending:
            _run_reactions(task)
        return self

    def __exit__(self, et: Any, exc: BaseException | None, tb: Any) -> bool:
        if exc is None or not isinstance(exc, GplException):
            return False
        task = current_task()
        err = from_core(exc)
        task.last_error = err.ErrorCode
        handler = task.reacte
        if handler is None or task.in_reacte:
            if err is not exc:
                raise err from None
            return False
        saved = task.priority
        task.in_reacte, task.priority = True, REACTE_PRIORITY
        try:
            handler()
        finally:
            task.in_reacte, task.priority = False, saved
        return True


# -- REACT / REACTI -----------------------------------------------------------------------------------

def react(signal: Any, prog: Any, *args: Any, priority: Any = 1, immediate: bool = False) -> None:
    """``REACT sig, prog[(args)][, pri]`` (``immediate``: REACTI)."""
    sig = to_int(signal)
    pri = to_int(priority)
    if not 1 <= pri <= 127:
        raise VError(ILLEGAL_VALUE, detail=f"reaction priority {pri}")
    core_number(sig)  # a bad signal number is refused now
    task = current_task()
    task.reactions[abs(sig)] = Reaction(sig, find_program(prog), args, pri, immediate)


def reacti(signal: Any, prog: Any, *args: Any, priority: Any = 1) -> None:
    react(signal, prog, *args, priority=priority, immediate=True)


def ignore(signal: Any) -> None:
    task = current_task()
    task.reactions.pop(abs(to_int(signal)), None)


def lock(priority: Any) -> None:
    """``LOCK n``: the program priority; lowering it lets deferred reactions run (L4553-4558)."""
    task = current_task()
    task.priority = to_int(priority)
    safepoint()


def priority() -> float:
    return float(current_task().priority)


def run(prog: Any, *args: Any, sim: Any = None) -> list[str]:
    """Run ``prog`` as task 0 of ``sim`` (default: the current simulation) until every task ends."""
    s = sim if sim is not None else current_sim()
    fn = find_program(prog)
    return s.run_main(lambda: fn(*args), name="task 0")

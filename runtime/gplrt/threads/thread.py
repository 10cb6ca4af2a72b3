"""GPL's ``Thread`` class (gpl-dictionary §7, gpl-classes §17, D0 §17).

Decisions where the manuals are silent (documented here, tested in tests/threads):

* ``New Thread(start_procedure [, argument [, thread_name]])`` — the procedure is a String
  (``"Proc"`` or ``"Module.Proc"``, case-insensitive) or, for hand-written Python, a callable.  The
  String is resolved when the object is created, by ``gplrt.lang.procedures.find_procedure`` *as
  seen from the module that executes the New*: a bare name finds that module's own procedure,
  Public or Private, before the one Public procedure of that name elsewhere; ``"Module.Proc"``
  names exactly that module's procedure, which must be Public unless it is the caller's module
  (-729 otherwise; an unknown module is -798).  Why not Public only, as for String delegates
  (spec §9.4, whose recommendation the thread spec points to): the manual gives no rule for
  threads, module members are Private by default (D0:1679), and real programs start threads on a
  plain ``Sub Worker()`` of their own module; refusing them would break GPL code that runs on a
  controller, while allowing them cannot change a program that names a Public procedure.  The
  calling module is the ``_module`` argument when given, else the GPL module whose generated
  code executes the ``New`` (found from the caller's Python module in the procedure registry).
  The start procedure takes no parameters; it reads ``Thread.CurrentThread.Argument``.  One with
  parameters cannot be started (the thread passes none): ``New`` raises -741 *Argument mismatch*
  rather than the thread failing later with a Python TypeError.
  The thread name defaults to the procedure name (without module); starting a thread whose name
  is already used by an active thread of the same project raises -749 *Thread already exists*, so
  several threads on one procedure need explicit names (two projects in memory may each run a
  ``Main``: docs/design/console.md).
* ``Start`` on an active thread raises -750; more than ``Simulation.max_threads`` (32, D0:4584)
  active threads raises -207 *Too many*.  Start clears pending events.  The starter keeps
  running; the new thread runs at the starter's next scheduling point.
* ``Join(timeout_ms)`` — timeout in milliseconds, negative or omitted = forever, 0 = poll; returns
  True when the thread is not running (finished, aborted, failed or never started), False on
  timeout.  Joining the calling thread itself raises -750.
* ``Abort`` requests the stop and waits (up to 1 s of controller time) for the thread to unwind;
  ``Finally`` blocks run, ``Catch`` blocks do not see it.  Aborting the calling thread stops it at once.
  What the aborted thread held is freed when it ends, reference cycles included (one collection
  of Python's cyclic garbage per Abort), so its sockets close as a controller's do.
* ``Suspend``/``Resume`` are cooperative: the target parks at its next checkpoint or scheduling
  point (a sleeping target finishes its sleep first).
* ``ThreadState`` codes are undocumented; we use the five states the controller's console shows
  (``Show Thread``): 0 Idle (never started, or ended normally or by Abort), 1 Running (including
  sleeping/waiting), 2 Stopped (suspended), 3 Error (ended by an unhandled exception),
  4 Stopping (abort requested, not yet unwound) — see :class:`ThreadStateValue`.
* ``WaitEvent(mask, timeout_ms)`` follows Table 19-107 (waitevent.htm): mask 0 → returns all
  received events without clearing or waiting; timeout 0 → clears and returns the matching
  events without waiting; timeout > 0 → waits for a matching event, then clears and returns the
  matches (0 on timeout); timeout < 0 → never times out.  Mask outside 0..&HFFFF, or a timeout
  over 2147 s, raises -707.
* ``SendEvent(mask)`` ORs the mask into the target's pending events (event n = bit n−1); events
  sent before the target waits stay pending.  A mask outside 0..&HFFFF raises -707.
* An unhandled GPL exception ends only its own thread: ThreadState becomes 3, the error goes into
  ``Controller.ErrorLog`` and the simulator's console log, and joiners return.
"""

from __future__ import annotations

import gc
import inspect
import sys
import threading
import traceback
from enum import IntEnum
from types import FrameType
from typing import Any, Callable

from gplrt.lang.errors import (
    ARGUMENT_MISMATCH,
    INTERNAL_ERROR,
    INVALID_WHEN_THREAD_ACTIVE,
    THREAD_ALREADY_EXISTS,
    TOO_MANY,
    UNDEFINED_SYMBOL,
    VALUE_OUT_OF_RANGE,
    GplException,
)
from gplrt.lang.conversions import to_int32
from gplrt.lang.gpltypes import Boolean, Double, Integer, Ref, String
from gplrt.lang.procedures import find_procedure, registered_procedures
from gplrt.session import ProjectScope, Session, current_scope, current_session
from gplrt.threads.scheduler import ThreadAbort, ThreadCtx, WaitQueue, current_ctx

MAX_EVENT_MASK = 0xFFFF
MAX_WAIT_MS = 2147 * 1000
ABORT_GRACE = 1.0  # controller seconds Abort waits for the target to unwind

_TAS_LOCK = threading.Lock()


class ThreadStateValue(IntEnum):
    """Values of ``Thread.ThreadState`` (our decision; see module docstring)."""

    IDLE = 0
    RUNNING = 1
    STOPPED = 2
    ERROR = 3
    STOPPING = 4


def _resolve(procedure: str, module: str | None, given: int = 0) -> Callable[..., Any]:
    """Find ``"Proc"`` or ``"Module.Proc"`` in the generated-code registry, as seen from ``module``."""
    proc = find_procedure(procedure, module, given)  # an overloaded name: the one taking no arguments
    if proc is None:
        raise GplException(UNDEFINED_SYMBOL, detail=f"procedure {procedure!r}")
    required = _required_parameters(proc)
    if len(required) > given:  # ``given``: arguments hand-written Python passes (Simulation.start)
        raise GplException(
            ARGUMENT_MISMATCH,
            detail=f"a thread's start procedure takes no arguments; {procedure} needs {', '.join(required)}",
        )
    return proc


def _required_parameters(proc: Callable[..., Any]) -> list[str]:
    """Names of the parameters ``proc`` cannot be called without (through ``gpl_entry`` too)."""
    try:
        params = inspect.signature(proc).parameters.values()
    except (TypeError, ValueError):
        return []
    return [p.name for p in params
            if p.default is p.empty and p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]


_module_of_code: dict[tuple[str, str], str] = {}  # (package, Python module) -> GPL module


def _calling_module(frame: FrameType | None) -> str | None:
    """The GPL module whose generated code runs in ``frame`` (None for other Python code).

    Generated code registers each procedure with its package's registry; the entry whose function
    was defined in the frame's Python module tells the GPL module (the shortest qualifier: a
    Shared class procedure is registered as ``Module.Class``).
    """
    if frame is None:
        return None
    name = frame.f_globals.get("__name__")
    package = frame.f_globals.get("__package__")
    if not name or not package:
        return None
    key = (package, name)
    known = _module_of_code.get(key)
    if known is not None:
        return known
    paths = [e.path for e in registered_procedures(package) if getattr(e.func, "__module__", None) == name]
    if not paths:
        return None
    module = ".".join(min(paths, key=len))
    _module_of_code[key] = module
    return module


class _Inherit:
    """``Thread(_project=...)``'s default: the thread belongs to its creator's project."""


_INHERIT_PROJECT = _Inherit()


class _Foreign(threading.local):
    thread: "Thread | None" = None


_foreign = _Foreign()


class Thread:
    """A GPL thread object: ``Dim t As New Thread("Module.Proc", arg, "name")``."""

    def __init__(
        self,
        StartProcedure: String | Callable[..., Any] | None = None,
        Argument: Double = 0.0,  # type: ignore[assignment]
        Name: String = "",  # type: ignore[assignment]
        *,
        _session: Session | None = None,
        _args: tuple[Any, ...] = (),
        _propagate: bool = False,
        _module: str | None = None,
        _project: ProjectScope | None | _Inherit = _INHERIT_PROJECT,
    ) -> None:
        #: The session the thread runs in: the creating code's, unless given.
        self._session = _session if _session is not None else current_session()
        #: The project it belongs to (``gplrt.session.ProjectScope``): the creating thread's, unless
        #: given; None is the session's own project.
        self._project: ProjectScope | None = current_scope() if isinstance(_project, _Inherit) else _project
        self._target: Callable[..., Any] | None
        if StartProcedure is None:
            self._target, self._start_name = None, ""
        elif callable(StartProcedure):
            self._target = StartProcedure
            self._start_name = str(getattr(StartProcedure, "__gpl_name__", StartProcedure.__qualname__))
        else:
            self._start_name = str(StartProcedure)
            module = _module if _module is not None else _calling_module(sys._getframe(1))
            self._target = _resolve(self._start_name, module, len(_args))
        self._argument: Any = Argument
        self._name = str(Name) if Name else self._start_name.rpartition(".")[2]
        self._args = _args
        self._propagate = _propagate
        self._events = 0
        self._event_q = WaitQueue("event")
        self._join_q = WaitQueue("join")
        self._ctx: ThreadCtx | None = None
        self._active = False
        self._failed = False
        self._result: Any = None
        self._error: BaseException | None = None

    # -- GPL properties -------------------------------------------------------------------------------

    @property
    def Argument(self) -> Double:
        return self._argument  # type: ignore[no-any-return]

    @Argument.setter
    def Argument(self, value: Double) -> None:
        self._argument = value

    @property
    def Name(self) -> String:
        return self._name  # type: ignore[return-value]

    @property
    def Project(self) -> String:
        scope = self._project
        return (scope.name if scope is not None else str(self._session.project))  # type: ignore[return-value]

    @property
    def StartProcedure(self) -> String:
        return self._start_name  # type: ignore[return-value]

    @property
    def ThreadState(self) -> Integer:
        if not self._active:
            state = ThreadStateValue.ERROR if self._failed else ThreadStateValue.IDLE
        elif self._ctx is not None and self._ctx.abort_requested:
            state = ThreadStateValue.STOPPING
        elif self._ctx is not None and self._ctx.suspend_requested:
            state = ThreadStateValue.STOPPED
        else:
            state = ThreadStateValue.RUNNING
        return int(state)  # type: ignore[return-value]

    # -- GPL methods ----------------------------------------------------------------------------------

    def Start(self) -> None:
        """Start the procedure in its own thread (it runs at the starter's next scheduling point)."""
        if self._active:
            raise GplException(INVALID_WHEN_THREAD_ACTIVE, detail=f"thread {self._name}")
        if self._target is None:
            raise GplException(INVALID_WHEN_THREAD_ACTIVE, detail="the calling thread cannot be started")
        session = self._session
        # Checks and claim under the scheduler lock: under the real clock two threads starting
        # the same name (or the same Thread object) at once must not both pass the checks.
        with session.scheduler._lock:
            if self._active:
                raise GplException(INVALID_WHEN_THREAD_ACTIVE, detail=f"thread {self._name}")
            active = [t for t in session.threads if t._active]
            if any(t._name.lower() == self._name.lower() and t._project is self._project for t in active):
                raise GplException(THREAD_ALREADY_EXISTS, detail=f"thread {self._name}")
            if len(active) >= session.max_threads:
                raise GplException(TOO_MANY, detail=f"more than {session.max_threads} threads")
            self._events = 0
            self._failed = False
            self._error = None
            self._result = None
            self._active = True
            if self not in session.threads:
                session.threads.append(self)
            self._ctx = session.scheduler.new_ctx(self._name, owner=self)
        session.scheduler.spawn(self._ctx, self._body)

    def Join(self, timeout: Integer = -1) -> Boolean:  # type: ignore[assignment]
        """Wait for the thread to end; ``timeout`` in ms (<0 forever, 0 poll). True if it ended."""
        if not self._active:
            return True  # type: ignore[return-value]
        if self._ctx is not None and self._ctx is current_ctx():
            raise GplException(INVALID_WHEN_THREAD_ACTIVE, detail="a thread cannot join itself")
        sched = self._session.scheduler
        timeout = to_int32(timeout)
        deadline = None if timeout < 0 else sched.clock.now() + timeout / 1000.0
        if timeout == 0:
            return (not self._active)  # type: ignore[return-value]
        while self._active:
            if not sched.wait(self._join_q, deadline, until=lambda: not self._active):
                break
        return (not self._active)  # type: ignore[return-value]

    def Abort(self) -> None:
        if not self._active or self._ctx is None:
            return
        sched = self._session.scheduler
        if self._ctx is current_ctx():
            raise ThreadAbort()
        sched.request_abort(self._ctx)
        self.Join(int(ABORT_GRACE * 1000))  # type: ignore[arg-type]

    def Suspend(self) -> None:
        if not self._active or self._ctx is None:
            return
        sched = self._session.scheduler
        sched.request_suspend(self._ctx)
        if self._ctx is current_ctx():
            sched._service_requests(self._ctx)

    def Resume(self) -> None:
        if self._active and self._ctx is not None:
            self._session.scheduler.request_resume(self._ctx)

    def SendEvent(self, event_mask: Integer) -> None:
        mask = _check_mask(event_mask)
        sched = self._session.scheduler
        with sched._lock:
            self._events |= mask
        sched.notify_all(self._event_q)

    # -- Shared members -------------------------------------------------------------------------------

    @staticmethod
    def CurrentThread() -> Thread:
        ctx = current_ctx()
        if ctx is not None and isinstance(ctx.owner, Thread):
            return ctx.owner
        # A Python thread the scheduler does not run (notebook, pytest): one stand-in object per
        # Python thread and session, so its events persist between calls.
        me = _foreign.thread
        if me is None or me._session is not current_session():
            me = Thread(None, 0.0, threading.current_thread().name)  # type: ignore[arg-type]
            _foreign.thread = me
        return me

    @staticmethod
    def Sleep(milliseconds: Integer) -> None:
        """Suspend the calling thread; ``Sleep(0)`` (or negative) just yields."""
        current_session().scheduler.sleep(max(0, to_int32(milliseconds)) / 1000.0)

    @staticmethod
    def WaitEvent(event_mask: Integer, time_out: Integer) -> Integer:
        me = Thread.CurrentThread()
        mask = _check_mask(event_mask)
        time_out = to_int32(time_out)
        if time_out > MAX_WAIT_MS:
            raise GplException(VALUE_OUT_OF_RANGE, detail=f"WaitEvent timeout {time_out} ms")
        sched = me._session.scheduler
        if mask == 0:
            return me._events  # type: ignore[return-value]
        if time_out != 0:
            deadline = None if time_out < 0 else sched.clock.now() + time_out / 1000.0
            ctx = current_ctx()
            if ctx is not None:
                ctx.waiting_on = "event"
            while not me._events & mask:
                if not sched.wait(me._event_q, deadline, until=lambda: me._events & mask):
                    break
        with sched._lock:
            got = me._events & mask
            me._events &= ~got
        return got  # type: ignore[return-value]

    @staticmethod
    def TestAndSet(variable: Ref[Integer], new_value: Integer) -> Integer:
        """Atomically read ``variable``, store ``new_value``, return the old value.

        Under the virtual clock nothing else runs between the read and the write.  Under the real
        clock Python may switch threads between them, and the lock only orders TestAndSet calls
        among themselves, not against a plain store such as a spin lock's release ``lock = 0``.
        Storing only when the value changes closes that gap for the pattern programs use: a
        TestAndSet that finds the lock taken writes nothing, so it cannot overwrite the holder's
        release with a stale 1 (which left the lock taken forever).
        """
        with _TAS_LOCK:
            old = variable.get()
            if old != new_value:
                variable.set(new_value)
        return old

    @staticmethod
    def Schedule(priority: Integer = 0, period: Double = 0.0, high_priority_time: Double = 0.0, phase: Double = 0.0) -> None:  # type: ignore[assignment]
        """Accepted and ignored: a PC has no real-time priorities (gpl-classes §22.5)."""

    # -- Python side ----------------------------------------------------------------------------------

    @property
    def unhandled_error(self) -> BaseException | None:
        """The exception that ended this thread unhandled (reported in the controller's error log),
        or None — while it runs, after a normal end or an Abort.  Usually a GplException; another
        Python exception means a bug in generated or hand-written code (reported as -201)."""
        return self._error if self._failed else None

    def release_frames(self) -> None:
        """Drop the local variables of the frames the thread's error passed through (the error's
        traceback, and that of the Python fault it was made from).

        Called when the session is done with (``Simulation.close``, interpreter exit): those
        frames hold what the failing statement was using -- after a motion error, the robot with
        its planned motion, whose Ruckig trajectories nanobind reports as "leaked" if they are
        still alive when the ``ruckig`` module is torn down.  The error stays readable: its code,
        message and the file:line of each frame (``gplrt.lang.sourcemap``) do not need the locals.
        """
        seen: set[int] = set()
        exc = self._error
        while exc is not None and id(exc) not in seen:
            seen.add(id(exc))
            traceback.clear_frames(exc.__traceback__)  # (an executing frame is left as it is)
            exc = exc.__cause__ or exc.__context__

    def _body(self) -> None:
        ctx = self._ctx
        assert ctx is not None and self._target is not None
        session = self._session
        aborted = False
        try:
            session.scheduler._service_requests(ctx)  # aborted/suspended before it first ran
            self._result = self._target(*self._args)
        except ThreadAbort:
            aborted = True
        except GplException as exc:
            self._fail(exc, exc.ErrorCode, str(exc))
        except Exception as exc:  # a bug in generated or hand-written Python: still only this thread
            self._fail(exc, INTERNAL_ERROR, f"Python error {type(exc).__name__}: {exc}")
        finally:
            if aborted:
                # A controller frees a stopped thread's objects at once: its sockets close, and
                # the client of a server thread sees the connection end (TCS ``reset``).  Those
                # held in a reference cycle (a caught exception's traceback holds frames) would
                # wait for Python's cyclic collector, which runs only when allocations add up.
                gc.collect()
            for hook in list(session.thread_exit_hooks):
                try:
                    hook(self)
                except Exception as exc:  # noqa: BLE001 - a hook must not kill the scheduler
                    session.report(self._name, f"thread exit hook failed: {exc!r}")
            with session.scheduler._lock:
                self._active = False
            session.scheduler.notify_all(self._join_q)
            session.scheduler.finish(ctx)

    def _fail(self, exc: BaseException, code: int, text: str) -> None:
        if self._propagate:
            self._error = exc
            return
        self._failed = True
        self._error = exc
        self._session.report(self._name, f"unhandled error: {text}", code)

    def __repr__(self) -> str:
        return f"<GPL Thread {self._name!r} state={self.ThreadState}>"


def _check_mask(mask: int) -> int:
    mask = to_int32(mask)  # GPL's Integer conversion (-717/-710), not int()'s ValueError
    if not 0 <= mask <= MAX_EVENT_MASK:
        raise GplException(VALUE_OUT_OF_RANGE, detail=f"event mask {mask}")
    return mask

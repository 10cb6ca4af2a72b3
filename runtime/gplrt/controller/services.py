"""GPL's global ``Controller`` class: its non-motion members (gpl-classes §9, gpl-dictionary §6).

State lives in the session's ``controller`` (:class:`gplrt.controller.state.ControllerState`, one per
session) so that the motion work reads the same power state, system speed and E-stop flag.  Decisions where the manuals are
silent:

* ``Timer(select)`` — ``select`` 1: seconds since boot (the active clock); 0 (default): seconds
  since 1 Jan 1988, i.e. boot time plus ``ControllerState.time_of_day_origin`` (fixed by default
  so that virtual runs are reproducible).  Quantised to 125 µs (timer.htm).
* ``Tick`` — trajectory-generator period, 0.001 s by default.  ``SleepTick(n)`` sleeps ``n`` ticks
  (default 1) on the active clock.
* ``PowerEnabled = True`` walks ``PowerState`` through 8 (enabling amplifiers) and 10 (enabling
  servos) to 20 (ready for a program to attach a robot) over ``power_up_time`` controller seconds,
  and returns when power is on — the next statement (typically a homing) can rely on it.  It
  raises -1046 *Power not enabled* while a soft E-stop is set.  ``False`` drops to 7 at once.
  ``PowerEnabled`` reads True in every "on" state of gpl-dictionary §13.3.
* The controller has one power sequencer (``ControllerState.power_sequence``), and a
  power-up is the controller's, not a thread's: its PowerState steps are clock callbacks
  (``scheduler.call_at``), and the threads that asked for it only wait.  A ``PowerEnabled =
  True`` while a power-up runs *joins* it (as concurrent ``Robot.Home`` calls share one homing)
  rather than restarting it, and every requester returns when that power-up reaches 20 — on the
  virtual and the real clock.  Suspending or aborting a requester (the first one included) only
  stops that thread waiting; the power-up goes on for the others.  [P: the manuals are silent;
  on a controller the amplifiers come up whatever the program thread that asked does.]
* ``PowerEnabled = False`` (or ``SoftEStop = True``) while a power-up runs wins at once: power
  is off (7) and every thread waiting for that power-up raises — -1600 *Power off requested* for
  a power-off request (listed for PowerEnabled in gpl-dictionary.md), -1046 for a soft E-stop.
  A ``True`` after that starts a fresh power-up.  The power-off and each power-up step are one
  locked step each (``PowerSequence.lock``, ``gplrt.controller.state``), so a power-off can never be overtaken by a step of
  the power-up it ended (the real clock runs them on different threads).
* ``PDb`` writes of the motion DataIDs that need power off (``NEEDS_POWER_OFF``) raise -1522
  *Cannot write value when power on* while power is on or coming up.
* ``Controller.PowerEnabled(timeout) = True`` (real code, TCS ``hp 1 20``; the Dictionary shows
  only the plain form): ``timeout`` > 0 waits at most that many seconds and raises -1025
  *Timeout enabling power* if power is not on by then (the power-up goes on); 0 waits as long
  as it takes, like the plain form.  Writing DataID 241 starts a power-up and does not wait
  (``start_power_up``, gplrt.controller.live_pdb).
* ``PowerState(mode)`` — the sequencer state (``mode`` accepted, ignored: undocumented).
* ``SoftEStop = True`` drops power (state 7) and blocks power-on until set False.
* ``SystemSpeed`` — percent, 0 < v ≤ 100, else -707; the value only (motion applies it).
* ``SystemMessage(msg)`` — appended to ``ControllerState.system_messages`` and echoed to the
  console *log* channel (not the program's output).
* ``ErrorLog(entry)`` — entry 1 is the most recent; an entry past the end reads "".  Assigning
  (``Controller.ErrorLog(0) = ""``) clears the log.  Entries read ``"<code> <message> (<thread>)"``.
* ``ShowDialog(buttons, prompt, ByRef button)`` — answered by ``ControllerState.dialog_answers``
  (scripted, 1-based button positions, consumed in order) or ``ControllerState.dialog_handler``;
  with neither, it raises -204 *Not implemented* naming the prompt, rather than hanging.
* ``PDb``/``PDbNum`` — served by the session's database (``Session.database()``, a
  ``gplrt.controller.pdb.ParameterDatabase``: ``pdb_text``/``set_pdb_text``/``pdb_num``/
  ``set_pdb_num``); a session without one loads its robot model's shipped database on first use.
* ``Command(cmd)`` runs a console command on the session's console
  (``gplrt.controller.commands``, the one Telnet reaches) and returns its output, lines separated
  by LF; a command that fails raises its error (``-753 *Project not compiled*``), catchable by the
  program's ``Try``.  ``Load(path)`` loads and compiles a project (the console's ``Load`` then
  ``Compile``: "Loads a GPL project into memory and compiles it", D0:2586), ``Unload(name)``
  removes an idle one.  Compiling needs the compiler ``gpl2py run`` gives the session (-204
  without one).  docs/design/console.md has the commands and their replies.
* ``ShowDialogMCP`` — not simulated (``@not_simulated``): -204 naming the member.
"""

from __future__ import annotations

from typing import Any, overload

from gplrt.controller import clock as _clock
from gplrt.controller.commands import ConsoleCommands
from gplrt.controller.projects import ProjectTable
from gplrt.controller.pdb import ParameterDatabase
from gplrt.lang.conversions import to_bool, to_double, to_int32, to_string
from gplrt.lang.exceptions import not_simulated
from gplrt.lang.errors import (
    CANT_WRITE_WHEN_POWER_ON,
    NOT_IMPLEMENTED,
    POWER_NOT_ENABLED,
    POWER_OFF_REQUESTED,
    SOFT_ESTOP,
    TIMEOUT_ENABLING_POWER,
    VALUE_OUT_OF_RANGE,
    GplException,
    error_text,
)
from gplrt.controller.state import (
    POWER_COMING_UP_STATES,
    POWER_ENABLING_AMPS,
    POWER_ENABLING_SERVOS,
    POWER_OFF_WAITING,
    POWER_ON_STATES,
    POWER_READY,
    LogEntry,
    PowerSequence,
    PowerUp,
)
from gplrt.lang.gpltypes import Boolean, Double, Integer, Ref, String
from gplrt.motion import registry
from gplrt.session import Session, current_session
from gplrt.threads.scheduler import controller_wait, current_ctx, external_wait

__all__ = [
    "Controller", "NEEDS_POWER_OFF", "POWER_COMING_UP_STATES", "POWER_ENABLING_AMPS", "POWER_ENABLING_SERVOS",
    "POWER_OFF_WAITING", "POWER_ON_STATES", "POWER_READY", "power_off", "start_power_up",
]

#: Motion DataIDs whose write needs high power off (-1522), decided [P] since neither the GPL
#: manual nor robot-models.md says which parameters the controller locks: the 100 % reference
#: speeds and accelerations (2700 joint speed, 2701 Cartesian speed, 2702 joint accel, 2703
#: Cartesian accel) are the trajectory generator's base units — every queued motion was planned
#: in them — so they change with the amplifiers off, like the robot's configuration.  The caps
#: on Profile percentages (2704-2706), the RapidDecel % (2101) and the settling time (2601) are
#: tuning a running cell may adjust: they are writable with power on and apply to the motions
#: queued after the write (gplrt.motion.registry._pdb_written).
NEEDS_POWER_OFF: frozenset[int] = frozenset({2700, 2701, 2702, 2703})


def _thread_name() -> str:
    ctx = current_ctx()
    return ctx.name if ctx is not None else "<external>"


class _ControllerClass:
    """GPL ``Controller`` (global class: one instance; see the module docstring)."""

    # -- time ------------------------------------------------------------------------------------

    def Timer(self, select: Integer = 0) -> Double:  # type: ignore[assignment]
        sim = current_session()
        t = sim.scheduler.clock.now()
        if to_int32(select) == 0:
            t += sim.controller.time_of_day_origin
        return _clock.quantise(t)  # type: ignore[return-value]

    @property
    def Tick(self) -> Double:
        return current_session().controller.tick  # type: ignore[return-value]

    def SleepTick(self, ticks: Integer = 1) -> None:  # type: ignore[assignment]
        sim = current_session()
        sim.scheduler.sleep(max(0, to_int32(ticks)) * sim.controller.tick)

    # -- power and speed -------------------------------------------------------------------------

    @property
    def PowerEnabled(self) -> Boolean:
        return current_session().controller.power_state in POWER_ON_STATES  # type: ignore[return-value]

    @PowerEnabled.setter
    def PowerEnabled(self, value: Boolean) -> None:
        self.set_PowerEnabled(0, value)

    def set_PowerEnabled(self, timeout: Double, value: Boolean) -> None:
        """``Controller.PowerEnabled(timeout) = True``: power on, waiting at most ``timeout``
        seconds (0 or less: as long as it takes, like ``PowerEnabled = True``) for power to come
        on, else -1025 *Timeout enabling power* (TCS 3.0C1 ``hp 1 t``; docs/design/real-code.md).
        ``False`` turns power off at once whatever the timeout."""
        sim = current_session()
        if not to_bool(value):  # (text "False" is False, as CBool has it)
            power_off(sim)
            return
        wait = to_double(timeout)
        _power_up(sim, timeout=wait if wait > 0 else None)

    def PowerState(self, mode: Integer = 0) -> Integer:  # type: ignore[assignment]
        return current_session().controller.power_state  # type: ignore[return-value]

    @property
    def SoftEStop(self) -> Boolean:
        return current_session().controller.soft_estop  # type: ignore[return-value]

    @SoftEStop.setter
    def SoftEStop(self, value: Boolean) -> None:
        sim = current_session()
        state = sim.controller
        state.soft_estop = to_bool(value)
        if state.soft_estop:
            _power_off(sim, POWER_NOT_ENABLED)
            _power_dropped(sim, SOFT_ESTOP)

    @property
    def SystemSpeed(self) -> Double:
        """The speed all motions are scaled by (%); boots at the database's DataID 601."""
        s = current_session()
        s.database()  # the boot value comes from the parameter database
        return s.controller.system_speed  # type: ignore[return-value]

    @SystemSpeed.setter
    def SystemSpeed(self, value: Double) -> None:
        v = to_double(value)
        if not 0.0 < v <= 100.0:  # (NaN fails this too)
            raise GplException(VALUE_OUT_OF_RANGE, detail=f"SystemSpeed {v}")
        state = current_session().controller
        state.system_speed = v
        state.system_speed_set = True

    @property
    def RecordButton(self) -> Boolean:
        return current_session().controller.record_button  # type: ignore[return-value]

    @RecordButton.setter
    def RecordButton(self, value: Boolean) -> None:
        current_session().controller.record_button = to_bool(value)

    # -- messages and logs -----------------------------------------------------------------------

    def SystemMessage(self, message: String) -> None:
        sim = current_session()
        entry = LogEntry(sim.now(), _thread_name(), str(message))
        sim.controller.system_messages.append(entry)
        sim.console.log(f"[{entry.time:.6f}] SystemMessage: {entry.text}")

    def ErrorLog(self, entry: Integer = 1) -> String:  # type: ignore[assignment]
        log = current_session().controller.error_log
        i = to_int32(entry)
        if not 1 <= i <= len(log):
            return ""  # type: ignore[return-value]
        e = log[-i]
        return f"{e.code} {error_text(e.code)} ({e.thread})"  # type: ignore[return-value]

    def set_ErrorLog(self, entry: Integer, value: String) -> None:
        current_session().controller.error_log.clear()

    def ShowDialog(self, buttons: String, prompt: String, button: Ref[Integer]) -> None:
        state = current_session().controller
        labels = [b.strip() for b in str(buttons).split(",")]
        if state.dialog_answers:
            choice = state.dialog_answers.pop(0)
        elif state.dialog_handler is not None:
            with external_wait():
                choice = state.dialog_handler(labels, str(prompt))
        else:
            raise GplException(NOT_IMPLEMENTED, detail=f"no operator to answer the dialog {prompt!r}")
        if not 1 <= int(choice) <= len(labels):
            raise GplException(VALUE_OUT_OF_RANGE, detail=f"dialog answer {choice} for {labels}")
        button.set(int(choice))

    @not_simulated
    def ShowDialogMCP(self, button_mask: Integer, message: String, button_return: Ref[Integer]) -> None:
        """A dialog on the Manual Control Pendant (the simulation has none)."""

    def Command(self, command: String) -> String:
        """Run a console command; its output (module docstring)."""
        return ConsoleCommands(_projects()).execute(to_string(command))  # type: ignore[return-value]

    def Load(self, project_path: String) -> None:
        """Load a project folder into memory and compile it (module docstring)."""
        table = _projects()
        project = table.load(to_string(project_path))
        try:
            table.compile(project.name)
        except GplException:
            table.unload(project.name)  # a project that does not compile is not left half-loaded
            raise

    def Unload(self, project: String) -> None:
        """Remove an idle project from memory (-750 while its threads run)."""
        _projects().unload(to_string(project))

    # -- parameter database ------------------------------------------------------------------------

    def PDb(self, data_id: Integer, unit: Integer = 1, unit2: Integer = 1, array_index: Integer = 0) -> String:  # type: ignore[assignment]
        return _pdb().pdb_text(*_ints(data_id, unit, unit2, array_index))  # type: ignore[return-value]

    @overload
    def set_PDb(self, data_id: Integer, value: String) -> None: ...

    @overload
    def set_PDb(self, data_id: Integer, unit: Integer, value: String) -> None: ...

    @overload
    def set_PDb(self, data_id: Integer, unit: Integer, unit2: Integer, value: String) -> None: ...

    @overload
    def set_PDb(self, data_id: Integer, unit: Integer, unit2: Integer, array_index: Integer,
                value: String) -> None: ...

    @overload
    def set_PDb(self, data_id: Integer, unit: Integer, unit2: Integer, array_index: Integer, key: Integer,
                value: String) -> None: ...

    def set_PDb(self, data_id: Integer, *rest: Any) -> None:
        """``Controller.PDb(id[, unit[, unit2[, index[, key]]]]) = value``: the value comes last."""
        unit, unit2, index, key = _pdb_args(rest[:-1], (1, 1, 0, 0))
        data_id = _check_power_for_write(to_int32(data_id))
        _pdb().set_pdb_text(to_string(rest[-1]), data_id, unit, unit2, index, key)

    def PDbNum(self, data_id: Integer, unit: Integer = 1, unit2: Integer = 1, array_index: Integer = 1) -> Double:  # type: ignore[assignment]
        return float(_pdb().pdb_num(*_ints(data_id, unit, unit2, array_index)))  # type: ignore[return-value]

    @overload
    def set_PDbNum(self, data_id: Integer, value: Double) -> None: ...

    @overload
    def set_PDbNum(self, data_id: Integer, unit: Integer, value: Double) -> None: ...

    @overload
    def set_PDbNum(self, data_id: Integer, unit: Integer, unit2: Integer, value: Double) -> None: ...

    @overload
    def set_PDbNum(self, data_id: Integer, unit: Integer, unit2: Integer, array_index: Integer,
                   value: Double) -> None: ...

    @overload
    def set_PDbNum(self, data_id: Integer, unit: Integer, unit2: Integer, array_index: Integer, key: Integer,
                   value: Double) -> None: ...

    def set_PDbNum(self, data_id: Integer, *rest: Any) -> None:
        """``Controller.PDbNum(id[, unit[, unit2[, index[, key]]]]) = value``: the value comes last."""
        unit, unit2, index, key = _pdb_args(rest[:-1], (1, 1, 1, 0))
        data_id = _check_power_for_write(to_int32(data_id))
        _pdb().set_pdb_num(rest[-1], data_id, unit, unit2, index, key)  # converts by GPL's rules


def start_power_up(sim: Session) -> None:
    """Start a power-up (or let the one in progress go on) and return at once: DataID 241."""
    _power_up(sim, wait=False)


def power_off(sim: Session) -> None:
    """``PowerEnabled = False``: high power off now, motion stops (module docstring)."""
    _power_off(sim, POWER_OFF_REQUESTED)
    _power_dropped(sim)


def _power_up(sim: Session, *, wait: bool = True, timeout: float | None = None) -> None:
    """``PowerEnabled = True``: start a power-up or join the one in progress, and (``wait``) wait
    for it, at most ``timeout`` controller seconds when given (-1025 after that; module docstring)."""
    state = sim.controller
    seq = state.power_sequence
    with seq.lock:
        if state.power_state in POWER_ON_STATES:
            return
        if state.soft_estop:
            raise GplException(POWER_NOT_ENABLED, detail="soft E-stop is set")
        power_up = seq.current
        started = power_up is None
        if power_up is None:
            t0, step = sim.scheduler.clock.now(), state.power_up_time / 2.0
            power_up = seq.current = PowerUp(ends_at=t0 + 2 * step)
            state.power_state = POWER_ENABLING_AMPS
    if started:
        # Scheduled outside ``seq.lock``: a timer callback runs under the scheduler's lock and
        # then takes ``seq.lock``, so ``seq.lock`` is never held while taking the scheduler's.
        sim.scheduler.call_at(t0 + step, lambda: _power_step(sim, seq, power_up, POWER_ENABLING_SERVOS))
        sim.scheduler.call_at(t0 + 2 * step, lambda: _power_step(sim, seq, power_up, POWER_READY))
    if not wait:
        return
    ended = lambda: power_up.outcome is not None  # noqa: E731 - tested under the scheduler lock
    deadline = None if timeout is None else sim.scheduler.clock.now() + timeout
    with controller_wait(power_up.ends_at):
        while not ended():
            if deadline is not None and sim.scheduler.clock.reached(deadline):
                raise GplException(TIMEOUT_ENABLING_POWER, detail=f"power not on after {timeout} s")
            sim.scheduler.wait(seq.done, deadline, ended)
    if power_up.outcome:
        raise GplException(power_up.outcome, detail="the power-up was interrupted")


def _power_step(sim: Session, seq: PowerSequence, power_up: PowerUp, phase: int) -> None:
    """A timer callback of ``power_up``: PowerState moves to ``phase``; at ``POWER_READY`` the
    power-up ends and its requesters return.  A power-up that was ended meanwhile (power off,
    E-stop) is no longer ``seq.current`` and its steps do nothing."""
    with seq.lock:
        if seq.current is not power_up:
            return
        sim.controller.power_state = phase
        if phase != POWER_READY:
            return
        registry.refresh_power_state(sim)  # 21 instead of 20 when a robot is already attached
        power_up.outcome, seq.current = 0, None
    sim.scheduler.notify_all(seq.done)


def _power_off(sim: Session, code: int) -> None:
    """A power-off request or soft E-stop: PowerState 7, and the power-up in progress (if any)
    ends now — its requesters raise ``code``.  One step under ``seq.lock`` (see PowerSequence)."""
    seq = sim.controller.power_sequence
    with seq.lock:
        sim.controller.power_state = POWER_OFF_WAITING
        power_up, seq.current = seq.current, None
        if power_up is not None:
            power_up.outcome = code
    if power_up is not None:
        sim.scheduler.notify_all(seq.done)


def _power_dropped(sim: Session, code: int = POWER_NOT_ENABLED) -> None:
    """Motion stops when high power goes off (gplrt.motion.registry.power_dropped)."""
    registry.power_dropped(sim, code)


def _check_power_for_write(data_id: int) -> int:
    """-1522 *Cannot write value when power on* for a ``NEEDS_POWER_OFF`` DataID while high
    power is on or coming up (module docstring); returns ``data_id``."""
    if data_id in NEEDS_POWER_OFF:
        state = current_session().controller.power_state
        if state in POWER_ON_STATES or state in POWER_COMING_UP_STATES:
            raise GplException(CANT_WRITE_WHEN_POWER_ON, detail=f"DataID {data_id} can change only with power off")
    return data_id


def _ints(*values: Any) -> list[int]:
    """PDb arguments as Integers by GPL's rules (CInt rounding, -717 on bad text), never int()."""
    return [to_int32(v) for v in values]


def _pdb_args(given: tuple[Any, ...], defaults: tuple[int, int, int, int]) -> tuple[int, int, int, int]:
    """unit, unit2, array_index, key from the optional arguments that were given."""
    merged = _ints(*given[:4]) + list(defaults[len(given[:4]) :])
    return merged[0], merged[1], merged[2], merged[3]


def _projects() -> ProjectTable:
    """The session's project table (every ``gplrt.sim.Simulation`` has one)."""
    table = current_session().projects
    if table is None:
        raise GplException(NOT_IMPLEMENTED, detail="this session keeps no projects")
    return table


def _pdb() -> ParameterDatabase:
    """The session's parameter database (``Session.database()``).

    A real controller always has its database, and vendor code (TCS) reads it at start-up, before
    any motion: a session without one gets its robot model's shipped database here, exactly as the
    first motion would load it, so reads never depend on whether a robot has moved yet.
    """
    return current_session().database()


Controller = _ControllerClass()

"""The controller's own state, one per session: power, homing, system speed, E-stop and the logs.

``Session.controller`` is a :class:`ControllerState`.  The motion work reads the same power state,
system speed and E-stop flag as GPL's ``Controller`` class (``gplrt.controller.services``), which
says what each member does with them.

Power states are the sequencer's (gpl-dictionary §13.3): 7 off and waiting for the power request,
8 and 10 while the amplifiers and servos are enabled, 20 ready, 21 while a robot is attached, 28
while homing.  ``PowerEnabled`` reads True in every state of :data:`POWER_ON_STATES`.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field

from gplrt.threads.scheduler import WaitQueue

POWER_OFF_WAITING = 7
POWER_ENABLING_AMPS = 8
POWER_ENABLING_SERVOS = 10
POWER_READY = 20
POWER_ATTACHED = 21
POWER_HOMING = 28
POWER_ON_STATES = frozenset({9, 11, 12, *range(20, 32)})
#: "Coming up" states (gpl-dictionary §13.3): amplifiers/servos being enabled, safety diagnostics.
POWER_COMING_UP_STATES = frozenset({POWER_ENABLING_AMPS, POWER_ENABLING_SERVOS, 16})


@dataclass
class LogEntry:
    """One line of the system-message log or of the error log."""

    time: float
    thread: str
    text: str
    code: int = 0


@dataclass(eq=False)
class PowerUp:
    """One power-up in progress: the requesters who asked for it wait until ``outcome`` is set
    (0: power came on; else the code they raise — -1600 power off requested, -1046 E-stop)."""

    outcome: int | None = None
    ends_at: float = 0.0  # controller time the power-up reaches POWER_READY, unless interrupted


@dataclass(eq=False)
class PowerSequence:
    """The controller's one high-power sequencer (``gplrt.controller.services``).

    ``current`` is the power-up in progress, if any.  Every change of it, and every PowerState
    step it makes, happens under ``lock``: a power-off request and a power-up step are never
    interleaved (on the real clock either may run on any thread)."""

    lock: threading.Lock = field(default_factory=threading.Lock)
    current: PowerUp | None = None
    done: WaitQueue = field(default_factory=lambda: WaitQueue("power-up"))


@dataclass
class ControllerState:
    """The controller's non-motion state (read by motion checks: power, speed, E-stop)."""

    power_state: int = POWER_OFF_WAITING  # off, waiting for the power request (gpl-dictionary §13.3)
    power_sequence: PowerSequence = field(default_factory=PowerSequence)
    system_speed: float = 100.0  # until the parameter database loads: then its DataID 601
    system_speed_set: bool = False  # the program (or a test) set SystemSpeed itself
    soft_estop: bool = False
    record_button: bool = False
    tick: float = 0.001  # trajectory-generator period (gpl-classes §22.3 item 8)
    power_up_time: float = 0.3  # virtual seconds from the power request to "on"
    homings: int = 0  # Robot.Home calls in progress (they share PowerState 28, see Robot._home)
    power_before_homing: int = 0  # the power state the last of them restores
    time_of_day_origin: float = 1135641600.0  # Timer(0) at boot: 2024-01-01 UTC in s since 1988
    system_messages: list[LogEntry] = field(default_factory=list)
    error_log: list[LogEntry] = field(default_factory=list)
    dialog_handler: Callable[[list[str], str], int] | None = None
    dialog_answers: list[int] = field(default_factory=list)

    @property
    def power_on(self) -> bool:
        """High power is on: the one test Move and Robot make before a motion or a homing."""
        return self.power_state in POWER_ON_STATES

    def log_error(self, time: float, thread: str, text: str, code: int = 0) -> LogEntry:
        """Append an entry to the error log (``Controller.ErrorLog``) and return it."""
        entry = LogEntry(time, thread, text, code)
        self.error_log.append(entry)
        return entry

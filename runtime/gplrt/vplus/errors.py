"""V+ error codes, their ``$ERROR`` texts, and :class:`VError`, the exception of a V+ run-time error.

Why a table of its own: V+ numbers its errors differently from GPL (``-504 *Unexpected end of
file*`` is V+'s, GPL has no such code), and ``$ERROR(code)``, ``IOSTAT`` and REACTE show V+'s
numbers to the program.  ``VError`` subclasses the core's ``GplException`` so that the core's
thread machinery reports an unhandled V+ error as it reports a GPL one.

Provenance of each code (docs/design/vplus-runtime.md §9): the seeds hold no error-message
appendix (that is in the V+ Reference Guides, which we do not have); the User's Guide (seed 002)
prints twelve codes with their number and text, each cited below and checked by
tests/vplus_runtime/test_values_strings.py.  The other codes are ``UNCONFIRMED``: the number is
ours (as we believe the Reference Guide numbers them), and the text is the Guide's where a line is
cited, else ours too.  A reader with the Reference Guide should check them; this table is the one
place to correct.
"""

from __future__ import annotations

from gplrt.lang import errors as core_errors
from gplrt.lang.errors import GplException

# -- codes printed in the User's Guide ------------------------------------------------------------
END_OF_FILE = -504            # L8078, L5359-5361
DATA_ERROR = -522             # L8064
COMM_OVERRUN = -524           # L8069
NO_DATA = -526                # L8074, L7530-7535
SPEED_POT = -620              # L9795
FORCE_PROTECT = -624          # L5830 (printed "*force protect limit exceeded")
NO_HARDWARE = -666            # L12015-12019 (-666 is also *Must use Monitor #1*, L12015)
NULLING_TIMEOUT = -1003       # L5832
SOFT_ENVELOPE = -1006         # L5833
NO_ZERO_INDEX = -1011         # L12618
LOST_SYNC = -1012             # L12616
QUADRATURE = -1013            # L12617

# -- UNCONFIRMED: numbers ours; the text the Guide's where a line is cited ---------------------------
UNDEFINED_VALUE = -401            # text L4141 ("an undefined value error")
UNDEFINED_NAME = -402             # text L1224-1226
ILLEGAL_INDEX = -403              # text ours
ILLEGAL_VALUE = -404              # text ours
STRING_TOO_LONG = -405            # text ours (the 128-character limit: §3.4)
DIVIDE_BY_ZERO = -406             # text ours
TYPE_MISMATCH = -407              # text ours; the condition L4009-4011
TOO_MANY_CALLS = -410             # text L992
PROGRAM_NOT_EXECUTABLE = -311     # text L664 (a line V+ would not load, kept by gpl2py --keep-going)
TASK_IN_USE = -421                # text ours
NOT_IMPLEMENTED = -430            # text ours (what gpl2py does not simulate)
DEVICE_NOT_READY = -508           # text L7404-7406, L8480
NONEXISTENT_FILE = -513           # text L8556-8561
FILE_EXISTS = -514                # text ours
NOT_ATTACHED = -516               # text ours
ALREADY_ATTACHED = -517           # text ours
FILE_NOT_OPEN = -518              # text ours
FILE_ALREADY_OPEN = -519          # text ours
ILLEGAL_IO = -530                 # text ours
CONNECTION_CLOSED = -543          # text ours
CONNECTION_REFUSED = -544         # text ours
ROBOT_NOT_ATTACHED = -601         # text ours
NOT_PRECISION_POINT = -603        # text ours
LOCATION_OUT_OF_RANGE = -610      # text ours
JOINT_OUT_OF_RANGE = -1002        # text ours
TOO_CLOSE = -1004                 # text ours
TOO_FAR = -1005                   # text ours

# Positive IOSTAT values of a TCP server LUN (AdeptNet; docs/design/vplus.md)
CLIENT_CONNECTED = 100
CLIENT_CLOSED = 101

_TEXT: dict[int, str] = {
    END_OF_FILE: "Unexpected end of file",
    DATA_ERROR: "Data error on device",
    COMM_OVERRUN: "Communications overrun",
    NO_DATA: "No data received",
    SPEED_POT: "Speed pot or STEP not pressed",
    FORCE_PROTECT: "Force protect limit exceeded",
    NO_HARDWARE: "Device Hardware not Present",
    NULLING_TIMEOUT: "Time-out nulling errors",
    SOFT_ENVELOPE: "Soft envelope error",
    NO_ZERO_INDEX: "No zero index",
    LOST_SYNC: "Lost encoder sync",
    QUADRATURE: "Encoder quadrature error",
    UNDEFINED_VALUE: "Undefined value",
    UNDEFINED_NAME: "Undefined program or variable name",
    ILLEGAL_INDEX: "Illegal array index",
    ILLEGAL_VALUE: "Illegal value",
    STRING_TOO_LONG: "String too long",
    DIVIDE_BY_ZERO: "Divide by zero",
    TYPE_MISMATCH: "Data type mismatch",
    TOO_MANY_CALLS: "Too many subroutine calls",
    PROGRAM_NOT_EXECUTABLE: "Program not executable",
    TASK_IN_USE: "Task already in use",
    NOT_IMPLEMENTED: "Not implemented",
    DEVICE_NOT_READY: "Device not ready",
    NONEXISTENT_FILE: "Nonexistent file",
    FILE_EXISTS: "File already exists",
    NOT_ATTACHED: "Not attached to logical unit",
    ALREADY_ATTACHED: "Already attached to logical unit",
    FILE_NOT_OPEN: "File not open",
    FILE_ALREADY_OPEN: "File already open",
    ILLEGAL_IO: "Illegal I/O request",
    CONNECTION_CLOSED: "Connection closed",
    CONNECTION_REFUSED: "Connection refused",
    ROBOT_NOT_ATTACHED: "Robot not attached to this program",
    NOT_PRECISION_POINT: "Not a precision point",
    LOCATION_OUT_OF_RANGE: "Location out of range",
    JOINT_OUT_OF_RANGE: "Joint out of range",
    TOO_CLOSE: "Location too close",
    TOO_FAR: "Location too far",
}


def error_text(code: int) -> str:
    """``$ERROR(code)``: the message between asterisks, as V+ prints it."""
    text = _TEXT.get(int(code))
    return f"*{text}*" if text is not None else f"*Unknown error code {int(code)}*"


class VError(GplException):
    """A V+ run-time error: the program's REACTE handler sees ``code``, else the task stops."""

    def __init__(self, code: int, detail: str | None = None) -> None:
        super().__init__(code, detail=detail)

    def Message(self) -> str:  # noqa: N802 - the core's member name
        return error_text(self.ErrorCode)

    def __str__(self) -> str:
        text = f"{self.Message()} ({self.ErrorCode})"
        return f"{text} - {self.detail}" if self.detail else text


def unsupported(keyword: str, *args: object) -> None:
    """A tier-3 instruction or function (graphics, vision, VME, protocols: spec §2.6) reached at
    run time: V+'s *Not implemented* naming it."""
    raise VError(NOT_IMPLEMENTED, detail=f"{keyword} is not simulated")


def compile_error(code: int, diagnostic: str) -> None:
    """A line gpl2py translated despite an error (``--keep-going``, or the error ignored), reached:
    V+'s error for the fault (``gpl2py.vplus.messages.RUNTIME_CODES``), naming gpl2py's diagnostic,
    so the program's REACTE traps it as any other and an unhandled one says which line and why."""
    raise VError(int(code), detail=diagnostic)


# GPL codes the shared core raises -> the V+ code a V+ program sees (the same condition).
_FROM_CORE: dict[int, int] = {
    core_errors.NO_ROBOT_ATTACHED: ROBOT_NOT_ATTACHED,
    core_errors.VALUE_OUT_OF_RANGE: ILLEGAL_VALUE,
    core_errors.VALUE_INFINITE_OR_NAN: ILLEGAL_VALUE,
    core_errors.ARITHMETIC_OVERFLOW: ILLEGAL_VALUE,
}
_FROM_CORE.update({
    core_errors.JOINT_OUT_OF_RANGE: JOINT_OUT_OF_RANGE,
    core_errors.POSITION_TOO_CLOSE: TOO_CLOSE,
    core_errors.POSITION_TOO_FAR: TOO_FAR,
    core_errors.INVALID_CARTESIAN: LOCATION_OUT_OF_RANGE,
})


def from_core(exc: GplException) -> VError:
    """The V+ error for a core (GPL-coded) exception: a motion's joint limit becomes V+'s
    *Joint out of range*; a code without a V+ counterpart keeps the core's number and text."""
    if isinstance(exc, VError):
        return exc
    code = _FROM_CORE.get(exc.ErrorCode)
    if code is None:
        err = VError(exc.ErrorCode, detail=exc.Message() + (f" - {exc.detail}" if exc.detail else ""))
        _TEXT.setdefault(exc.ErrorCode, core_errors.error_text(exc.ErrorCode))
        return err
    return VError(code, detail=exc.detail)

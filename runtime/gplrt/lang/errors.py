"""GPL exceptions: the Exception class of GPL, which is also the Python exception that carries it.

One class plays both roles so that a ``Catch ex`` in transpiled code receives exactly the object
that was thrown (``Throw ex`` raises it, ``Catch`` stores it) and so that runtime faults (divide by
zero, bad index, robot refusals) arrive as GPL exceptions with the controller's error codes.

Message format (gpl-dictionary.md §8): ``*<text>*``, then ``: <qualifier>`` for a general exception
with a non-zero qualifier, or `` Robot <n>: <axis>`` for a robot exception, then ``: <subject>`` when
the runtime names what the error is about (a stub's missing name).  A ``detail`` string
(not part of the controller's data) may name what failed, e.g. the file that could not be opened;
it is appended after `` - `` so that Python tracebacks say what went wrong.
"""

from __future__ import annotations

import os
from collections.abc import Callable

from gplrt.lang.error_codes import ERROR_MESSAGES
from gplrt.lang.sourcemap import locate

# The one table of names for the codes the runtime raises: every module imports its codes from
# here (one name per code; names follow the controller's message texts in error_codes.py).
# General and language runtime faults.
NO_MEMORY = -200
INTERNAL_ERROR = -201
INVALID_ARGUMENT = -202
NOT_IMPLEMENTED = -204
MISSING_ARGUMENT = -205
TOO_MANY = -207
PROTECTION_ERROR = -208
READ_ONLY = -209
INVALID_ROBOT_TYPE = -221
VALUE_TOO_SMALL = -705
VALUE_OUT_OF_RANGE = -707
VALUE_INFINITE_OR_NAN = -708
DIVISION_BY_ZERO = -709
ARITHMETIC_OVERFLOW = -710
INVALID_NUMBER_FORMAT = -717
MISSING_QUOTE_MARK = -704
INVALID_SYNTAX = -712
UNKNOWN_COMMAND = -714
AMBIGUOUS_ABBREVIATION = -716
UNDEFINED_SYMBOL = -729
INVALID_DATA_TYPE = -738
ARGUMENT_MISMATCH = -741
# Projects (the console's Load, Compile, Start, Unload; Controller.Load).
COMPILATION_ERRORS = -742
INVALID_PROJECT_FILE = -743
INVALID_START_PROCEDURE = -744
PROJECT_ALREADY_EXISTS = -745
PROJECT_NOT_COMPILED = -753
THREAD_ALREADY_EXISTS = -749
INVALID_WHEN_THREAD_ACTIVE = -750
THREAD_STACK_TOO_SMALL = -755
OBJECT_NOT_INSTANTIATED = -757
NOT_CARTESIAN = -762
NOT_ANGLES = -763
ARRAY_INDEX_MISMATCH = -766
INVALID_ARRAY_INDEX = -767
FRAME_WRONG_TYPE = -769
FRAME_UNDEFINED_DATA = -770
AMBIGUOUS_PUBLIC_REFERENCE = -772
NOTHING_VALUE = -782
SHORT_STRING = -783
PROJECT_ERROR = -786
CONVEYOR_MUST_BE_BASE = -791
ZCLEARANCE_NOT_SET = -794
NO_DELEGATE_DEFINED = -796
NO_MODULE_DEFINED = -798
# XML documents.
XML_ERROR = -799
NO_XML_DOCUMENT = -800
NO_XML_NODE = -801
UNDEFINED_XML_NAME = -802
INVALID_NODE_TYPE = -803
DOCUMENTS_DO_NOT_MATCH = -804
# Devices and files.
UNDEFINED_DEVICE = -301
PORT_IN_USE = -304
NO_DEVICE_MAPPED = -309
DEVICE_FULL = -323
DEVICE_IO_ERROR = -500
UNEXPECTED_EOF = -505
FILE_NOT_FOUND = -508
CANT_OPEN_FOR_WRITE = -509
FILE_EXISTS = -510
CANT_CREATE_DIRECTORY = -511
WRITE_ERROR = -512
READ_ERROR = -513
INVALID_FILE_NAME = -516
PATH_TOO_LONG = -517
INVALID_FILE_FORMAT = -519
FILE_NOT_OPEN = -520
INVALID_FILE_TYPE = -521
NO_DATA = -523
LATCH_DATA_OVERRUN = -526
# Network and Modbus.
CONNECTION_REFUSED = -1702
NO_CONNECTION = -1703
INVALID_ADDRESS = -1704
NETWORK_TIMEOUT = -1705
ALREADY_CONNECTED = -1706
SOCKET_NOT_OPEN = -1707
CONNECTION_CLOSED = -1708
INVALID_PROTOCOL = -1709
MODBUS_EXCEPTION = -1730
MODBUS_TIMEOUT = -1731
# Robots and motion.
INVALID_ROBOT_NUMBER = -1000
UNDEFINED_ROBOT = -1001
INVALID_AXIS = -1002
ROBOT_ALREADY_ATTACHED = -1006
CANT_DETACH_MOVING_ROBOT = -1008
NO_ROBOT_ATTACHED = -1009
JOINT_OUT_OF_RANGE = -1012
TORQUE_MODE_INCORRECT = -1016
NOT_IN_POSITION_MODE = -1017
ROBOT_NOT_HOMED = -1021
TIMEOUT_ENABLING_POWER = -1025
INVALID_CARTESIAN = -1033
KINEMATICS_NOT_INSTALLED = -1036
POSITION_TOO_CLOSE = -1039
POSITION_TOO_FAR = -1040
CANT_CHANGE_CONFIG = -1042
ASYNCHRONOUS_SOFT_ERROR = -1043
SOFT_ESTOP = -1045
POWER_NOT_ENABLED = -1046
INCONSISTENT_TRIGGER_MODE = -788
# Parameter database and signals.
UNKNOWN_DATA_ID = -1501
INVALID_DATA_INDEX = -1509
INVALID_PARAMETER_ARRAY_INDEX = -1514
INVALID_DATA_FILE_FORMAT = -1515
INVALID_AXIS_COUNT = -1516
INVALID_SIGNAL_NUMBER = -1517
UNDEFINED_SIGNAL_NUMBER = -1518
OUTPUT_SIGNAL_REQUIRED = -1519
CANT_OPEN_PARAMETER_DB = -1520
CANT_WRITE_WHEN_POWER_ON = -1522
# Power sequencer.
POWER_OFF_REQUESTED = -1600
# Servo faults (a motion stopped part-way by what the servos can follow).
AXIS_OVER_SPEED = -3106
SOFT_ENVELOPE_ERROR = -3122
# Vision.
VISION_CANNOT_CONNECT = -4000
VISION_UNKNOWN_PROCESS = -4012
VISION_UNKNOWN_TOOL = -4013
VISION_INVALID_INDEX = -4014
VISION_PROPERTY_NOT_FOUND = -4017


def error_text(code: int) -> str:
    """The controller's short text for ``code``; unknown codes read ``Error <code>``."""
    return ERROR_MESSAGES.get(code, f"Error {code}")


def host_reason(exc: BaseException) -> str:
    """Why the host refused, in the host's own words, for a GPL error's ``detail``: the operating
    system's text ("No such file or directory"), else the text of its errno, else a plain phrase.

    Never Python's rendering of the exception ("[Errno 2] No such file or directory: 'x'", "'ascii'
    codec can't decode byte 0xff ..."): a GPL error keeps the controller's words (issue 20), and
    the file or address it is about is already in the detail the caller writes around this.
    """
    if isinstance(exc, UnicodeDecodeError):
        return f"not {exc.encoding.upper()} text (byte 0x{exc.object[exc.start]:02X} at offset {exc.start})"
    if isinstance(exc, OSError):
        if exc.strerror:
            return str(exc.strerror)
        if exc.errno:
            return os.strerror(exc.errno)
        if isinstance(exc, TimeoutError):
            return "timed out"
    return "the operating system refused"


def _not_installed(value: object) -> int:
    raise RuntimeError("gplrt.lang.conversions is not loaded (gplrt/__init__.py loads it)")


#: GPL's Integer conversion (``gplrt.lang.conversions.to_int32``), which converting a member value
#: needs.  The conversions raise GplException with this module's codes, so they sit above it and
#: install their Integer conversion here when they load; ``gplrt/__init__.py`` loads them with the
#: package, so it is in place before any GplException exists.
integer_conversion: Callable[[object], int] = _not_installed


def _integer(value: object) -> int:
    """GPL's Integer conversion of a member value (``ex.Qualifier = "3"``, ``= 1.5``, ``= True``).

    Python's ``int()`` would truncate 1.5 and raise a bare ValueError for "abc" or NaN; the shared
    conversion rounds half away from zero and raises the controller's codes (-717, -710).
    """
    if type(value) is int:
        return value
    return integer_conversion(value)


class GplException(Exception):
    """GPL's ``Exception`` class: ``New Exception``, ``Throw``, ``Catch ex``.

    GPL members keep their GPL spelling (``ErrorCode``, ``Message``, ...); Python-side helpers are
    snake_case.  Construct with ``GplException(code, detail=...)`` to raise a runtime fault.
    """

    def __init__(
        self,
        ErrorCode: int = 0,
        Qualifier: int = 0,
        *,
        detail: str | None = None,
        robot_num: int | None = None,
        axis: int = 0,
        subject: str | None = None,
    ) -> None:
        super().__init__()
        self._code = _integer(ErrorCode)
        self._qualifier = _integer(Qualifier)
        self._robot_error = robot_num is not None
        self._robot_num = robot_num if robot_num is not None else 0
        self._axis = _integer(axis)
        self.detail = detail
        # What the error is about, shown in Message itself (``*Not implemented*: protected source
        # not available: VendorLib.Grip``): unlike ``detail`` a GPL program that catches the
        # exception sees it, for errors whose code alone cannot tell the user what is missing.
        self.subject = subject
        # Where the fault was raised in GPL terms ("Module.gpl:12"), filled in by the runtime.
        self.gpl_location: str | None = None

    # -- GPL members -----------------------------------------------------------------------------

    @property
    def ErrorCode(self) -> int:
        return self._code

    @ErrorCode.setter
    def ErrorCode(self, value: int) -> None:
        value = _integer(value)
        if value != self._code:
            self.subject = None  # it named what the old error was about, not the new one
        self._code = value

    @property
    def Qualifier(self) -> int:
        return self._qualifier

    @Qualifier.setter
    def Qualifier(self, value: int) -> None:
        value = _integer(value)
        if not 0 <= value <= 65535:
            raise GplException(VALUE_OUT_OF_RANGE, detail=f"Qualifier {value}")
        self._qualifier = value
        self._robot_error = False

    @property
    def RobotError(self) -> bool:
        return self._robot_error

    @RobotError.setter
    def RobotError(self, value: bool) -> None:
        value = bool(value)
        if self._robot_error and not value:
            self._qualifier = 0  # switching robot -> general resets the qualifier (§8)
        self._robot_error = value

    @property
    def RobotNum(self) -> int:
        return self._robot_num

    @RobotNum.setter
    def RobotNum(self, value: int) -> None:
        self._robot_num = _integer(value)

    @property
    def Axis(self) -> int:
        return self._axis

    @Axis.setter
    def Axis(self, value: int) -> None:
        self._axis = _integer(value)

    def Message(self) -> str:
        text = f"*{error_text(self._code)}*"
        if self._robot_error:
            text += f" Robot {self._robot_num}: {self._axis}"
        elif self._qualifier:
            text += f": {self._qualifier}"
        if self.subject:
            text += f": {self.subject}"
        return text

    def Clone(self) -> GplException:
        twin = GplException(self._code, self._qualifier, detail=self.detail, subject=self.subject)
        twin._robot_error = self._robot_error
        twin._robot_num = self._robot_num
        twin._axis = self._axis
        twin.gpl_location = self.gpl_location
        return twin

    def UpdateErrorCode(self) -> None:
        """Replace a generic asynchronous code by the specific one posted since.

        The simulated controller posts its specific code together with the generic one, so the
        specific code is already in place: nothing to update.
        """

    # -- Python side ------------------------------------------------------------------------------

    def forget_location(self) -> None:
        """Drop where the exception was last raised (its ``gpl_location`` and Python traceback).

        ``Catch`` calls it (``as_gpl_exception``): the GPL object carries no location (its members
        are ErrorCode, Qualifier, RobotError, RobotNum, Axis, Message, Clone, UpdateErrorCode),
        so a ``Throw`` of a caught object -- TCS reuses one (``ex.ErrorCode = -1708: Throw ex``) --
        is reported where that Throw is.  Python would otherwise keep the first raise's frames at
        the end of the new traceback, and the report would name the first Throw's line.
        """
        self.gpl_location = None
        self.__traceback__ = None

    def __str__(self) -> str:
        text = self.Message()
        if self.detail:
            text += f" - {self.detail}"
        location = self.gpl_location
        if location is None and self.__traceback__ is not None:
            location = locate(self)  # transpiled frames name their GPL line
        if location:
            text += f" (at {location})"
        return f"GPL error {self._code}: {text}"

    def __repr__(self) -> str:
        if self.subject:
            return f"GplException({self._code}, detail={self.detail!r}, subject={self.subject!r})"
        return f"GplException({self._code}, detail={self.detail!r})"


def gpl_error(code: int, detail: str | None = None) -> GplException:
    """A new exception for ``code`` (the caller raises it): ``raise gpl_error(-709)``."""
    return GplException(code, detail=detail)

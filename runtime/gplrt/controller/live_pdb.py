"""The parameter database's live DataIDs: the controller's own state and commands, read and
written through ``Controller.PDb`` / ``PDbNum`` like any stored parameter.

A real controller answers these DataIDs from its running state; none of them is in a ``.pac``
backup.  Vendor code relies on them (TCS reads the GPL version at start-up, the power state for
``sysState``, writes 241 for ``hp 1`` and 213 for ``homeAll``; PARobot reads 3520 and the gripper's
torques), so the simulation serves them from its own state
(``gplrt.controller.pdb.LiveParameter``).  What each one is, and the decisions where the manuals
are silent (docs/design/real-code.md has the ones where real code departs from the manuals):

=======  =====================================================================================
100-102  manufacturer, controller model, hardware version (read-only text): the hardware is the
         simulation's, so 101 and 102 say so; 100 is Precise Automation, whose GPL runs here
103      software version text, ``GPL 4.2J2, Mar  6 2020, Release``: the GPL of the controller
         whose ``.pac`` files ship as the PF400SX (data/robots/README.md); 104/105/106 encode it
         as major 4, minor 2, edit 1002 (letter J = 10, times 100, plus 2): TCS computes
         ``104·10⁶ + 105·10⁴ + 106`` and compares it with 4020109 for "4.2a9" (Cmd.gpl:1677);
         107 and 108 are its date and qualifier (``Mar  6 2020``, ``Release``)
110      controller serial number: a simulated one, ``SIMULATED_SERIAL`` (a real controller's
         comes from its hardware and is in no DataID of the ``.pac`` files)
111/113  number of robots (units with DataID 2000): TCS checks robot numbers against them
121      date and time text ``MM-DD-YYYY HH:MM:SS`` on the controller clock (the form a real
         controller wrote into docs/Tcs-taught-stations-2022.gpo); writing sets the clock
136      power-on hours: whole hours the simulated controller has run (its clock since boot);
         a real controller's counter started when it was built
213      write 1: home every robot, as the web page's Home button; the writer does not wait
         (TCS sleeps 100 ms after it "in case of error"); -1046 when power is off; reads 0
230      auto-execution state: 1 while the controller runs a GPL project (any GPL thread), 0
         when it runs none [P: the state's codes are not published; with the shipped
         "Automatic execution mode" 200 = 1, a GPL project is what auto execution runs]
234      power state (``Controller.PowerState``), read-only
241      write 1: start a power-up and return at once (TCS ``hp 1``), 0: power off; reads 1
         while power is on or coming up
247      write 1: reset a latched fatal error; the simulation latches none (no hardware faults),
         so there is nothing to reset; reads 0
375      status bits: &H100000 while a robot has an asynchronous motion error not yet reported
         (TCS waits a tick for it when bits &H700000 are set)
420      local IP address (read-only text): the address the simulated controller's servers
         listen on (``Simulation(listen=...)``, ``gpl2py run --listen``); 127.0.0.1 when they
         listen on every address of the computer (0.0.0.0 is no address of a controller)
601      the system speed in % (``Controller.SystemSpeed``): the stored value is what the
         controller boots with; reading gives the present speed, writing sets it (TCS ``mspeed``)
901      write 1: save the stored DataIDs to ``/flash/config`` on the session's flash disk, one
         ``.pac`` file each as the controller keeps them (``ParameterDatabase.pac_files``), so a
         ``pc`` change survives as the TCS guide says; reads 0.  The simulation boots from the
         robot model's shipped files, not from ``/flash/config``
2800     per robot: 1 when every axis is homed, 0 when not (``Robot.Home`` sets it)
3520     per robot: the trajectory-generator state, as ``Robot.TrajState(robot)``
12304    per robot and axis: output torque in torque counts (±32768 = amplifier peak);
12331    filtered feedforward torque (the gripper's spring compensation): see
         ``gplrt.motion.servo`` for how the simulation computes both
14500    per robot: the axis the brake DataID 14002 acts on
14002    per robot: 1 releases the brake of axis 14500, 0 sets it; reads that axis's state
=======  =====================================================================================

The callbacks act on the calling code's session (``gplrt.session.current_session()``: the calling
GPL thread's own), so one database may serve several sessions, as the notebook's does.  The
session's composer installs them when it boots its database (``gplrt.sim``); this module sits above
the controller and motion modules whose state they read.
"""

from __future__ import annotations

import datetime as _dt
from collections.abc import Callable

from gplrt.controller.pdb import LiveParameter, ParameterDatabase, Value
from gplrt.controller.services import Controller, power_off, start_power_up
from gplrt.controller.state import POWER_COMING_UP_STATES, POWER_ON_STATES
from gplrt.io.sockets import ANY, LOOPBACK
from gplrt.lang.errors import CANT_OPEN_PARAMETER_DB, INVALID_ARGUMENT, INVALID_AXIS, GplException
from gplrt.motion.robot import RobotState
from gplrt.motion.robot_class import start_homing_all, traj_state
from gplrt.motion.servo import axis_torques
from gplrt.session import current_session

#: GPL 4.2J2 (data/robots/README.md): what 103-108 report.
GPL_VERSION_TEXT = "GPL 4.2J2, Mar  6 2020, Release"
GPL_VERSION = (4, 2, 1002)
#: What 100-102 and 110 report: the manufacturer whose GPL this is, and simulated hardware.
MANUFACTURER = "Precise Automation"
CONTROLLER_MODEL = "gplrt simulated controller"
HARDWARE_VERSION = "simulated (gplrt)"
SIMULATED_SERIAL = "0014FF-00000000"
#: Where DataID 901 saves the parameter database (robot-models.md §1.1).
CONFIG_FOLDER = "/flash/config"
#: Bit of DataID 375 set while a robot has an unreported asynchronous error.
STATUS_ASYNC_ERROR = 0x100000
#: The date text of DataID 121.
DATE_FORMAT = "%m-%d-%Y %H:%M:%S"
_EPOCH_1988 = _dt.datetime(1988, 1, 1)


Reader = Callable[[int, int], list[Value]]


def _const(*values: Value) -> Reader:
    return lambda unit, unit2: list(values)


def install(pdb: ParameterDatabase) -> None:
    """Register the live DataIDs on ``pdb`` (once; a database that has them keeps them)."""
    if pdb.live:
        return
    robots = pdb.robots

    def robot_count(unit: int, unit2: int) -> list[Value]:
        return [float(len(robots()))]

    _, date, qualifier = (part.strip() for part in GPL_VERSION_TEXT.split(","))
    pdb.live.update({
        100: LiveParameter("Controller manufacturer", _const(MANUFACTURER), is_string=True),
        101: LiveParameter("Controller model", _const(CONTROLLER_MODEL), is_string=True),
        102: LiveParameter("Hardware version", _const(HARDWARE_VERSION), is_string=True),
        103: LiveParameter("Software version", _const(GPL_VERSION_TEXT), is_string=True),
        104: LiveParameter("Software major version number", _const(float(GPL_VERSION[0]))),
        105: LiveParameter("Software minor version number", _const(float(GPL_VERSION[1]))),
        106: LiveParameter("Software edit number", _const(float(GPL_VERSION[2]))),
        107: LiveParameter("Software date", _const(date), is_string=True),
        108: LiveParameter("Software qualifier", _const(qualifier), is_string=True),
        110: LiveParameter("Controller serial number", _const(SIMULATED_SERIAL), is_string=True),
        111: LiveParameter("Number of robots", robot_count),
        113: LiveParameter("Number of configured robots", robot_count),
        121: LiveParameter("Date and time", _date, _set_date, is_string=True),
        136: LiveParameter("Power-on hours", _power_on_hours),
        213: LiveParameter("Home all robots", _const(0.0), _home_all),
        230: LiveParameter("Auto execution state", _auto_execution),
        234: LiveParameter("Power state", lambda u, u2: [float(current_session().controller.power_state)]),
        241: LiveParameter("Power request, do not wait", _power_requested, _request_power),
        247: LiveParameter("Reset fatal error", _const(0.0), _reset_fatal_error),
        375: LiveParameter("Controller status bits", _status_bits),
        420: LiveParameter("Local IP address", _local_ip, is_string=True),
        601: LiveParameter("System wide test speed in %", _system_speed, _set_system_speed),
        901: LiveParameter("Save parameters to flash", _const(0.0), _save_to_flash),
        2800: LiveParameter("Robot homed", _homed, units=robots),
        3520: LiveParameter("Trajectory mode", _traj_mode, units=robots),
        12304: LiveParameter("Compensator output torque, tcnt", _torques(output=True), units=robots),
        12331: LiveParameter("Filtered feedforward torque, tcnt", _torques(output=False), units=robots),
        14500: LiveParameter("Brake control axis", _brake_axis, _set_brake_axis, units=robots),
        14002: LiveParameter("Brake release", _brake_released, _set_brake, units=robots),
    })


# -- controller ---------------------------------------------------------------------------------


def _date(unit: int, unit2: int) -> list[Value]:
    sim = current_session()
    seconds = sim.controller.time_of_day_origin + sim.now()
    return [(_EPOCH_1988 + _dt.timedelta(seconds=int(seconds))).strftime(DATE_FORMAT)]


def _set_date(unit: int, unit2: int, values: list[Value]) -> None:
    try:
        when = _dt.datetime.strptime(str(values[0]).strip(), DATE_FORMAT)
    except ValueError:
        raise GplException(INVALID_ARGUMENT, detail=f"date {values[0]!r} is not MM-DD-YYYY HH:MM:SS") from None
    sim = current_session()
    sim.controller.time_of_day_origin = (when - _EPOCH_1988).total_seconds() - sim.now()


def _power_on_hours(unit: int, unit2: int) -> list[Value]:
    return [float(int(current_session().now() // 3600.0))]


def _auto_execution(unit: int, unit2: int) -> list[Value]:
    return [1.0 if current_session().scheduler.live else 0.0]


def _reset_fatal_error(unit: int, unit2: int, values: list[Value]) -> None:
    """Nothing to reset: the simulation latches no fatal error (module docstring)."""


def _local_ip(unit: int, unit2: int) -> list[Value]:
    listen = current_session().network.listen
    return [LOOPBACK if listen == ANY else listen]


def _save_to_flash(unit: int, unit2: int, values: list[Value]) -> None:
    """Write the stored DataIDs to ``/flash/config`` through the flash sandbox; a host refusal
    (a link or a file in the way, a full disk) is -1520 *Can't open parameter DB file*."""
    if not values[0]:
        return
    sim = current_session()
    try:
        folder = sim.files.resolve(CONFIG_FOLDER).file
        assert folder is not None  # (a disk path)
        folder.mkdir()
        for name, text in sim.database().pac_files().items():
            target = sim.files.resolve(f"{CONFIG_FOLDER}/{name}").file
            assert target is not None
            target.replace(text.encode("ascii", errors="replace"))
    except OSError as exc:
        raise GplException(CANT_OPEN_PARAMETER_DB, detail=f"{CONFIG_FOLDER}: {exc.strerror or exc}") from None


def _home_all(unit: int, unit2: int, values: list[Value]) -> None:
    if values[0]:
        start_homing_all(current_session())


def _power_requested(unit: int, unit2: int) -> list[Value]:
    state = current_session().controller.power_state
    return [1.0 if state in POWER_ON_STATES or state in POWER_COMING_UP_STATES else 0.0]


def _request_power(unit: int, unit2: int, values: list[Value]) -> None:
    (start_power_up if values[0] else power_off)(current_session())


def _system_speed(unit: int, unit2: int) -> list[Value]:
    return [float(current_session().controller.system_speed)]


def _set_system_speed(unit: int, unit2: int, values: list[Value]) -> None:
    Controller.SystemSpeed = values[0]  # the same value, range and error (-707) as the property


def _status_bits(unit: int, unit2: int) -> list[Value]:
    sim = current_session()
    pending = any(r.async_error or r.queue.fault is not None for r in sim.robots.values())
    return [float(STATUS_ASYNC_ERROR if pending else 0)]


# -- per robot ----------------------------------------------------------------------------------


def _robot(unit: int) -> RobotState:
    return current_session().robot(int(unit))


def _homed(unit: int, unit2: int) -> list[Value]:
    return [1.0 if _robot(unit).homed else 0.0]


def _traj_mode(unit: int, unit2: int) -> list[Value]:
    return [float(traj_state(_robot(unit)))]


def _torques(output: bool) -> Reader:
    def read(unit: int, unit2: int) -> list[Value]:
        s = current_session()
        pid, feedforward = axis_torques(s, s.robot(int(unit)), s.now())
        return [float(f + p) if output else float(f) for p, f in zip(pid, feedforward)]

    return read


def _brake_axis(unit: int, unit2: int) -> list[Value]:
    return [float(_robot(unit).brake_axis)]


def _set_brake_axis(unit: int, unit2: int, values: list[Value]) -> None:
    robot = _robot(unit)
    axis = int(float(values[0]))
    if not 1 <= axis <= robot.axis_count:
        raise GplException(INVALID_AXIS, robot_num=robot.number, axis=axis, detail=f"brake axis {axis}")
    robot.brake_axis = axis


def _brake_released(unit: int, unit2: int) -> list[Value]:
    robot = _robot(unit)
    return [1.0 if robot.brake_axis in robot.brakes_released else 0.0]


def _set_brake(unit: int, unit2: int, values: list[Value]) -> None:
    robot = _robot(unit)
    if not 1 <= robot.brake_axis <= robot.axis_count:
        raise GplException(INVALID_AXIS, robot_num=robot.number, detail="no brake axis chosen (DataID 14500)")
    if values[0]:
        robot.brakes_released.add(robot.brake_axis)
    else:
        robot.brakes_released.discard(robot.brake_axis)

"""Every command of the TCS User's Guide and of the PARobot plug-in guide, one case each, sent
through a plain TCP socket to the vendor's TCP Command Server on the simulated PF400 (issue 11).

The corpus's TCS 3.0C1 with the PARobot plug-in (``tcs-3.0C1-pa``) is copied unchanged (not one
``.gpl`` line differs) and served by a notebook ``Cell`` on the FAST clock: one TCS per robot model
for the whole module, a PF400SX for every command and a PF400SXL (the same arm on a linear rail)
for the rail's.  The only thing a user would add is there too: the taught-station file a real
PF400 cell wrote (``docs/Tcs-taught-stations-2022.gpo``) in ``/flash/data``.  TCS listens on its
fixed ports, 10100 (robot 1) and 10000 (status), so the module runs in a network namespace of its
own (``gpltest.private_network_module``).

Each case sets up the state its command needs with TCS's own commands (``hp 1 20``, ``attach 1``,
``home``, stations taught with ``locXyz``/``hereJ``/``TeachPlate``), sends the command as a
client would, and asserts the exact reply in the guide's PC-mode format.  Numbers that report
robot state are checked against the simulated robot: its joints (TCS prints three decimals,
``Functions.gpl`` ``sFormat``), and its Cartesian pose worked out by hand from the PF400's links
(DataID 16050) and tool, not by the runtime.  A command that moves the robot is followed by
``waitForEom`` and the robot's pose (to 1e-6 of the target).  A command the controller refuses in
some state is sent in that state too, and must reply with the controller's code.  Commands that
need hardware the simulated PF400 does not have (vision, a dual gripper) must give the reply TCS
gives when it is missing.

The cases run in the order below.  Their results make the table in ``docs/tcs-commands.md``:
``test_the_command_table_is_current`` fails when the committed table differs from this run's
(``GPL2PY_WRITE_TCS_TABLE=1`` writes it instead).  A case that fails because of a bug found in
another part of gpl2py is a strict expected failure naming the bug: it shows as "does not work
yet" in the table, and turns into a failure once the bug is fixed, so the mark cannot outlive it.
"""

from __future__ import annotations

import math
import os
import re
import shutil
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from gpltest import (
    REPO,
    LineClient,
    PrivateRun,
    copy_project,
    corpus_dir,
    hand_rotation,
    private_network_module,
)
from gplrt.controller.pdb import DATA_DIR
from gplrt.controller.services import POWER_ON_STATES
from gplrt.geometry import kinematics_provider, refframe
from gplrt.lang.console import get_console_sink, set_console_sink
from gplrt.lang.conversions import CStr
from gplrt.lang.error_codes import ERROR_MESSAGES
# Imported for its side effect: it installs the kinematics provider (Location.Here).  TCS's own
# threads would import it during the first case, and conftest's per-test isolation would then put
# the provider it saved before that case (none) back.
import gplrt.motion.robot_class  # noqa: F401
from gplrt.motion.registry import robot_of
from gplrt.motion.servo import gripper_of
from gplrt.motion.special import push
from gpl2py.notebook import Cell

ROBOT_PORT, STATUS_PORT = 10100, 10000  # Startup.gpl: Robot1Port, Status1Port
TIMEOUT = 30.0  # real seconds for any one reply (bounds a hang; nothing asserts a duration)
TABLE = REPO / "docs" / "tcs-commands.md"
WRITE_TABLE = "GPL2PY_WRITE_TCS_TABLE"
TAUGHT = "Tcs-taught-stations-2022.gpo"  # corpus/docs: a Tcs.gpo a working PF400 cell wrote

SX, SXL = "PF400SX", "PF400SXL"
TCS, PA, SOURCES = "TCS", "PARobot", "sources"
GUIDES = {TCS: "TCS User's Guide 3.0C1 (standard commands)",
          PA: "PARobot plug-in 3.0C1 (PARobot and SSGRIP commands)",
          SOURCES: "In the sources, not in the guides"}
WORKS, REFUSED, NOT_SIMULATED = "works", "refused", "not simulated"

# -- the PF400 by hand ------------------------------------------------------------------------------

L1, L2 = 302.0, 289.0  # shoulder->elbow, elbow->wrist in mm: DataID 16050 [2], [3] (robot-models.md)
TOOL = (0.0, 0.0, 162.0)  # the PF400SX's default tool: 162 mm out of the flange (``tool``)
SAFE = (170.0, 0.0, 180.0, -180.0, 75.5)  # PARobot's SafeLoc for a PF400 (PARobot.gpl Hook_InitCommand)
GRIP_OPEN, GRIP_CLOSE = 100.0, 75.5  # PARobot's PF400 gripper open and close positions
JOINTS_A = (300.0, 10.0, 90.0, -100.0, 90.0)  # Z mm, shoulder, elbow, wrist deg, gripper mm
JOINTS_B = (250.0, -20.0, 110.0, -80.0, 90.0)
CART_C = (400.0, 100.0, 250.0, 0.0, 90.0, 180.0)  # a pose the PF400 reaches righty (config 1)


def wrap(angle: float) -> float:
    """An angle in degrees in (-180, 180], as the controller reports yaw."""
    a = math.fmod(angle, 360.0)
    if a <= -180.0:
        a += 360.0
    elif a > 180.0:
        a -= 360.0
    return a


def pf400_pose(q: tuple[float, ...] | np.ndarray, tool: tuple[float, float, float] = TOOL,
               base: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0), rail: float = 0.0
               ) -> tuple[float, ...]:
    """X Y Z yaw pitch roll of the tool for PF400 joints ``q``, worked out by hand.

    J1 lifts the arm (Z), J2 and J3 turn the links in the horizontal plane, J4 turns the hand,
    which holds the tool horizontally: orientation (yaw, 90, 180) with yaw = J2 + J3 + J4
    (``gpltest.hand_rotation``).  ``tool`` is a translation from the flange; ``base`` is the
    ``base`` command's X Y Z and rotation about Z; ``rail`` moves the whole arm along world Y (the
    PF400SXL's rail with direction 0, DataID 16050 [5])."""
    z, j2, j3, j4 = (float(v) for v in q[:4])
    yaw = j2 + j3 + j4
    wrist = np.array([L1 * math.cos(math.radians(j2)) + L2 * math.cos(math.radians(j2 + j3)),
                      L1 * math.sin(math.radians(j2)) + L2 * math.sin(math.radians(j2 + j3)) + rail, z])
    p = wrist + hand_rotation(yaw) @ np.array(tool)
    bx, by, bz, brot = base
    c, s = math.cos(math.radians(brot)), math.sin(math.radians(brot))
    p = np.array([c * p[0] - s * p[1] + bx, s * p[0] + c * p[1] + by, p[2] + bz])
    return (float(p[0]), float(p[1]), float(p[2]), wrap(yaw + brot), 90.0, 180.0)


def pf400_config(q: tuple[float, ...] | np.ndarray) -> int:
    """GPL_Righty (1) while the elbow J3 is between 0 and 180 degrees, else GPL_Lefty (2)."""
    return 1 if 0.0 < math.fmod(float(q[2]), 360.0) % 360.0 < 180.0 else 2


# -- TCS's reply format -------------------------------------------------------------------------------


def num(value: float, frac: int = 3) -> str:
    """A number as TCS prints it: rounded half away from zero to ``frac`` decimals (Functions.gpl
    sFormat), then the controller's CStr."""
    scale = 10.0 ** frac
    return CStr(math.floor(abs(value) * scale + 0.5) / scale * (1 if value >= 0 else -1))


def nums(values: Any, frac: int = 3) -> str:
    return " ".join(num(float(v), frac) for v in values)


def error(code: int) -> str:
    """The text for a GPL error code in the table: ``-1012 *Joint out-of-range*``."""
    return f"{code} *{ERROR_MESSAGES[code]}*" if code in ERROR_MESSAGES else str(code)


# -- the session ------------------------------------------------------------------------------------


class Tcs:
    """TCS serving on a simulated robot, and a client's two connections to it (robot, status)."""

    def __init__(self, cell: Cell, model: str, flash: Path) -> None:
        self.cell, self.model, self.flash = cell, model, flash
        self.robot = connect(ROBOT_PORT)
        self.status = connect(STATUS_PORT)

    def close(self) -> None:
        self.robot.close()
        self.status.close()

    # -- talking to TCS

    def ask(self, command: str, link: LineClient | None = None) -> str:
        """Send one command line (LF-terminated, as the guide's syntax) and return the reply line."""
        return (link or self.robot).ask(command)

    def expect(self, command: str, reply: str, link: LineClient | None = None) -> str:
        got = self.ask(command, link)
        assert got == reply, f"{command!r} replied {got!r}, expected {reply!r}"
        return got

    def ok(self, *commands: str, link: LineClient | None = None) -> None:
        for command in commands:
            self.expect(command, "0", link)

    def on_status(self, command: str, reply: str) -> str:
        return self.expect(command, reply, self.status)

    def reconnect(self) -> None:
        """A new robot connection (TCS listens again half a second after one closes)."""
        self.robot.close()
        self.robot = connect(ROBOT_PORT)

    # -- the simulated controller

    @property
    def arm(self) -> Any:
        """The simulated robot 1 (``gplrt.motion.robot.RobotState``)."""
        return robot_of(self.cell.sim, 1)

    def powered(self) -> bool:
        return self.cell.sim.controller.power_state in POWER_ON_STATES

    def joints(self) -> np.ndarray:
        return np.array(self.cell.where().joints)

    def assert_joints(self, expected: Any) -> None:
        """The robot is at ``expected`` (1e-6), and ``wherej`` says so."""
        here = self.joints()
        assert here[:len(expected)] == pytest.approx(np.array(expected, dtype=float), abs=1e-6)
        self.expect("wherej", "0 " + nums(here))

    def pose(self, tool: tuple[float, float, float] = TOOL, base: tuple[float, ...] = (0.0, 0.0, 0.0, 0.0)
             ) -> tuple[float, ...]:
        """The robot's tool pose, from its joints by hand (``pf400_pose``)."""
        q = self.joints()
        rail = float(q[5]) if self.model == SXL else 0.0
        return pf400_pose(q, tool, base, rail)  # type: ignore[arg-type]

    def assert_pose(self, expected: tuple[float, ...], tool: tuple[float, float, float] = TOOL) -> None:
        """The robot's tool is at ``expected`` (1e-6 mm / deg), and ``wherec`` says so."""
        pose = self.pose(tool)
        assert pose == pytest.approx(expected, abs=1e-6)
        self.expect("wherec", f"0 {nums(pose)} {pf400_config(self.joints())}")

    def ensure(self, power: bool = True, attached: bool = True, homed: bool = True) -> None:
        """Give the robot the state a command needs, with TCS's own commands."""
        if power and not self.powered():
            self.ok("hp 1 20")
        elif not power and self.powered():
            self.ok("hp 0")
        if attached and self.arm.owner is None:
            self.ok("attach 1")
        elif not attached and self.arm.owner is not None:
            self.ok("attach 0")
        if homed and power and attached and not self.arm.homed:
            self.ok("home")

    def move_to(self, joints: tuple[float, ...], profile: int = 1) -> None:
        self.ensure()
        self.ok(f"moveJ {profile} {nums(joints)}", "waitForEom")
        self.assert_joints(joints)

    def slow_move(self, joints: tuple[float, ...]) -> None:
        """Start a long motion (profile 20 at 2 % speed) and return while the robot moves."""
        self.ensure()
        self.ok("speed 20 2", f"moveJ 20 {nums(joints)}")


def connect(port: int) -> LineClient:
    """A client connection; TCS starts listening again half a second after a connection ends."""
    end = time.monotonic() + TIMEOUT
    while True:
        try:
            return LineClient(port, TIMEOUT, newline="\n")
        except ConnectionRefusedError:
            if time.monotonic() > end:
                raise
            time.sleep(0.05)


def raw_exchange(link: LineClient, data: str, expected: str) -> None:
    """Send ``data`` as it is and read exactly the bytes of ``expected`` (Telnet mode's framing)."""
    link.send(data)
    want = expected.encode("latin-1")
    while len(link.pending) < len(want):
        chunk = link.sock.recv(4096)
        if not chunk:
            break
        link.pending += chunk
    got, link.pending = link.pending[:len(want)], link.pending[len(want):]
    assert got == want, f"{data!r} gave {got!r}, expected {want!r}"


def closed_by_server(link: LineClient) -> bool:
    """The server closed ``link``: a read gives end-of-file (a time-out raises instead)."""
    return link.pending == b"" and link.sock.recv(64) == b""


# -- the cases ------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Case:
    command: str  # as the guide spells it
    guide: str  # TCS, PA or SOURCES
    section: str  # the guide's section
    needs: str  # what the command needs on the controller
    checks: str  # what the case asserts, for the table
    verdict: str  # WORKS, REFUSED or NOT_SIMULATED
    why: str  # for REFUSED / NOT_SIMULATED: why
    robot: str
    body: Callable[[Tcs], str | None]  # returns the refusal reply for REFUSED / NOT_SIMULATED
    bug: str = ""  # a bug found elsewhere in gpl2py that makes the case fail (strict xfail)

    @property
    def id(self) -> str:
        return f"{self.robot}-{self.command}"


CASES: list[Case] = []
#: case id -> (verdict, the refusal reply) for the cases that passed, (``"fails"``, reason) else
RESULTS: dict[str, tuple[str, str]] = {}


def case(command: str, guide: str, section: str, needs: str, checks: str, verdict: str = WORKS,
         why: str = "", robot: str = SX, bug: str = "") -> Callable[[Callable[[Tcs], str | None]], Callable[[Tcs], str | None]]:
    def register(body: Callable[[Tcs], str | None]) -> Callable[[Tcs], str | None]:
        CASES.append(Case(command, guide, section, needs, checks, verdict, why, robot, body, bug))
        return body
    return register


# ---- General commands

@case("version", TCS, "General", "nothing", "the TCS version and every plug-in's, in order")
def _version(tcs: Tcs) -> None:
    from gpl2py.gpl.standins.parobot_auto_center import Version as auto_center_standin

    tcs.expect("version", "0 TCP Command Server 3.0C1 05-27-2021, Load-Save Module 3.0B2 12-04-2020, "
               "PARobot Module 3.0C1 05-27-2021, SSGrip Module 3.0A3 09-03-2015, " + auto_center_standin)


@case("nop", TCS, "General", "nothing", "replies 0")
def _nop(tcs: Tcs) -> None:
    tcs.expect("nop", "0")
    tcs.on_status("nop", "0")


@case("mode", TCS, "General", "nothing",
      "mode 1: Telnet framing (CR LF before each reply, the CMD> prompt, verbose replies); mode 0: PC mode")
def _mode(tcs: Tcs) -> None:
    tcs.expect("mode", "0 0")
    link = tcs.robot
    raw_exchange(link, "mode 1\n", "\r\nOk\r\nCMD> ")
    raw_exchange(link, "mode\n", "\r\n0 1 Telnet_Mode\r\nCMD> ")
    raw_exchange(link, "wherej\n", f"\r\nAngles = {nums(tcs.joints())}\r\nCMD> ")
    raw_exchange(link, "bogus\n", "\r\n-2805 *Unknown command*: bogus\r\nCMD> ")
    raw_exchange(link, "mode 0\n", "0\r\n")  # the reply is made after the switch back
    tcs.expect("mode", "0 0")


@case("sysState", TCS, "General", "nothing",
      "DataID 234 as the simulated controller's power state: 7 power off, 20 on, 21 robot attached")
def _sys_state(tcs: Tcs) -> None:
    tcs.ensure(power=False, attached=False)
    assert tcs.cell.sim.controller.power_state == 7
    tcs.expect("sysState", "0 7")
    tcs.on_status("sysState", "0 7")
    tcs.ok("hp 1 20")
    tcs.on_status("sysState", "0 20")
    tcs.ok("attach 1")
    tcs.on_status("sysState", "0 21")
    assert tcs.cell.sim.controller.power_state == 21


@case("hp", TCS, "General", "nothing",
      "power on without waiting, with a time-out, off; the state read back; -1025 when power is not on in time")
def _hp(tcs: Tcs) -> None:
    tcs.ensure(power=False, attached=False)
    tcs.expect("hp", "0 0")
    tcs.ok("hp 1")  # starts the power-up and replies at once
    assert not tcs.powered()
    tcs.ok("hp 1 20")  # waits for it
    assert tcs.powered()
    tcs.expect("hp", "0 1")
    tcs.ok("hp 0")
    assert not tcs.powered()
    tcs.expect("hp", "0 0")
    assert tcs.cell.sim.controller.power_up_time > 0.1
    tcs.expect("hp 1 0.1", "-1025")  # *Timeout enabling power*: the power-up takes longer
    tcs.ok("hp 1 -1")  # waits as long as it takes
    assert tcs.powered()


@case("attach", TCS, "General", "power (to move)",
      "attach / release the robot; the state read back (the robot number); -2808 from the status port")
def _attach(tcs: Tcs) -> None:
    tcs.ensure(attached=False, homed=False)
    tcs.expect("attach", "0 0")
    tcs.ok("attach 1")
    assert tcs.arm.owner is not None
    tcs.expect("attach", "0 1")  # GPL's Robot.Attached: the robot's number (the guide says -1)
    tcs.on_status("attach 1", "-2808 *Not allowed by this thread*")
    tcs.ok("attach 0")
    assert tcs.arm.owner is None
    tcs.expect("attach", "0 0")


@case("homeAll", TCS, "General", "power; robots not attached",
      "homes the unhomed robot (sysState 28 while it does, 20 after; DataID 2800 0 before, 1 after); "
      "-1046 with power off")
def _home_all(tcs: Tcs) -> None:
    tcs.ensure(power=False, attached=False, homed=False)
    assert not tcs.arm.homed  # the simulated PF400 starts unhomed
    tcs.on_status("pd 2800", "0 0")  # DataID 2800, robot homed
    tcs.on_status("homeAll", "-1046")  # *Power not enabled*
    tcs.on_status("hp 1 20", "0")
    tcs.on_status("homeAll", "0")
    for _ in range(200):
        if tcs.ask("sysState", tcs.status) == "0 20":
            break
        time.sleep(0.02)
    assert tcs.arm.homed
    tcs.on_status("sysState", "0 20")
    tcs.on_status("pd 2800", "0 1")


@case("home", TCS, "General", "power; robot attached",
      "homes the robot: DataID 2800 (robot homed) 0 before, 1 after, as a client reads it on connect "
      "and after home; -1009 not attached, -1046 power off", robot=SXL)
def _home(tcs: Tcs) -> None:
    # The first case on the PF400SXL: its robot has not been homed since the controller started.
    tcs.ensure(power=True, attached=False, homed=False)
    assert not tcs.arm.homed
    tcs.expect("pd 2800", "0 0")
    tcs.expect("home", "-1009")  # *No robot attached*
    tcs.ok("attach 1", "hp 0")
    tcs.expect("home", "-1046")  # *Power not enabled*
    tcs.expect("pd 2800", "0 0")
    tcs.ok("hp 1 20", "home")
    assert tcs.arm.homed
    tcs.expect("pd 2800", "0 1")
    tcs.on_status("pd 2800 1", "0 1")


@case("mspeed", TCS, "General", "nothing", "the system speed (DataID 601) read and set")
def _mspeed(tcs: Tcs) -> None:
    controller = tcs.cell.sim.controller
    before = controller.system_speed
    tcs.expect("mspeed", f"0 {num(before)}")
    try:
        tcs.ok("mspeed 30")
        tcs.expect("mspeed", "0 30")
        tcs.expect("pd 601", "0 30")
        assert controller.system_speed == 30  # what scales every motion
    finally:
        tcs.ok(f"mspeed {num(before)}")


@case("payload", TCS, "General", "nothing", "the payload percentage read and set")
def _payload(tcs: Tcs) -> None:
    tcs.ensure()
    tcs.expect("payload", "0 0")
    tcs.ok("payload 25")
    assert tcs.arm.payload == 25
    tcs.expect("payload", "0 25")
    tcs.ok("payload 0")


@case("pc", TCS, "General", "nothing",
      "a numeric parameter changed with 2 and 5 arguments (DataID 241 turns power on and off), "
      "a quoted string one, saved to /flash/config by DataID 901; -2801, -2800, -1501")
def _pc(tcs: Tcs) -> None:
    tcs.ensure(power=False, attached=False)
    name = tcs.ask("pd 2002").removeprefix("0 ")
    assert name == "PreciseFlex 400SX"
    tcs.ok("pc 241 1")  # DataID 241: request power, do not wait
    tcs.ok("hp 1 20")  # (waits for it)
    assert tcs.powered()
    tcs.ok("pc 241 0 0 1 0")  # DataID, unit, sub-unit, index, value: power off
    assert not tcs.powered()
    try:
        tcs.ok('pc 2002 "Test arm 1"')  # the robot's name, a string parameter
        tcs.expect("pd 2002", "0 Test arm 1")
        tcs.ok("pc 901 1")  # save to flash (the guide's pc): the name is kept in robot01.pac
        assert pac_values(tcs.flash / "flash" / "config" / "robot01.pac", 2002) == ["Test arm 1"]
    finally:
        tcs.ok(f'pc 2002 "{name}"')
    tcs.expect("pc", "-2801 *Warning No Parameters")
    tcs.expect("pc 601", "-2800 *Warning Parameter Mismatch*")
    tcs.expect("pc 99999 1", "-1501")  # *Unknown Data ID code*


@case("pd", TCS, "General", "nothing",
      "parameters of the PF400 database: robot type, axes, links, soft limits; every DataID of the "
      "DataID table below, against its .pac file or the simulated controller; -2801, -1501")
def _pd(tcs: Tcs) -> None:
    tcs.ensure()  # power on, robot attached and homed: the state the live DataIDs' checks expect
    for data_id in DATA_IDS:
        reply = tcs.ask(f"pd {data_id.number}")
        assert reply.startswith("0 ") and data_id.check(tcs, reply[2:]), (data_id.number, reply)
    tcs.expect("pd 2007", "0 400")  # robot type: PreciseFlex 400
    tcs.expect("pd 2000", "0 5")  # axes, the gripper included
    tcs.expect("pd 16050 1 0 2", f"0 {num(L1)}")  # the links the hand kinematics here use
    tcs.expect("pd 16050 1 0 3", f"0 {num(L2)}")
    tcs.expect("pd 16077 1 0 1", "0 1161.5")  # Z soft limits of the tall column
    tcs.expect("pd 16078 1 0 1", "0 1.5")
    tcs.expect("pd", "-2801 *Warning No Parameters")
    tcs.expect("pd 99999", "-1501")


# ---- DataIDs: every one real clients and the guide name, as ``pd`` reads it (the DataID table)

PF400SX_PAC = DATA_DIR / "pf400sx"  # the real PF400SX backup the simulated controller loads
PLR, GUIDE, SOURCE = "PyLabRobot", "TCS guide", "TCS"
LIVE_TESTS = "test_live_pdb.py"


def pac_values(path: Path, data_id: int) -> list[str]:
    """The values of ``data_id`` as a ``.pac`` file writes them (read here, not by gplrt): the
    record's continuation lines joined, its values split at the commas, strings unquoted."""
    text = re.sub(r",[ \t]*\n[ \t]+", ", ", path.read_text(encoding="ascii"))
    found = re.search(rf'^DI: {data_id}, 0, 0, 0, "[^"]*" = (.*)$', text, re.MULTILINE)
    assert found, f"DataID {data_id} is not in {path.name}"
    return [v.strip().strip('"') for v in found.group(1).split(",")]


@dataclass(frozen=True)
class DataId:
    number: int
    meaning: str
    reply: str  # the shape of what ``pd`` replies: a number, text, one number per axis, ...
    value: str  # where the value comes from: stored (which .pac file), live, simulated, a command
    readers: tuple[str, ...]  # who reads it: PyLabRobot's newest driver, the TCS guide, TCS itself
    check: Callable[[Tcs, str], bool]  # the reply (after "0 ") is right on the PF400SX
    tests: str = ""  # the tests besides this module's ``pd`` case that cover it


def stored(file: str, number: int, meaning: str, reply: str, *readers: str, tests: str = "") -> DataId:
    """A configuration DataID: ``pd`` replies the values of the PF400SX's ``file``, in order."""
    def check(tcs: Tcs, got: str) -> bool:
        want, parts = pac_values(PF400SX_PAC / file, number), got.split(",")
        if len(parts) != len(want):
            return False
        try:
            return [float(v) for v in parts] == [float(v) for v in want]
        except ValueError:
            return parts == want
    return DataId(number, meaning, reply, f"stored: `{file}`", readers, check, tests)


def live(number: int, meaning: str, reply: str, value: str, readers: tuple[str, ...],
         expected: str | re.Pattern[str] | Callable[[Tcs], str], tests: str = "") -> DataId:
    """A DataID the controller answers from its state: the reply is ``expected`` (text, a pattern
    it matches, or worked out from the simulated controller)."""
    def check(tcs: Tcs, got: str) -> bool:
        if isinstance(expected, re.Pattern):
            return expected.fullmatch(got) is not None
        return got == (expected if isinstance(expected, str) else expected(tcs))
    return DataId(number, meaning, reply, value, readers, check, tests)


NUMBER, TEXT, PER_AXIS = "a number", "text", "one number per axis"
LIVE, SIMULATED = "live", "live, simulated"
DATA_IDS: list[DataId] = [
    live(100, "controller manufacturer", TEXT, SIMULATED, (PLR,), "Precise Automation",
         f"{LIVE_TESTS}::test_identity_text_and_power_on_hours"),
    live(101, "controller model", TEXT, SIMULATED, (PLR,), "gplrt simulated controller",
         f"{LIVE_TESTS}::test_identity_text_and_power_on_hours"),
    live(102, "hardware version", TEXT, SIMULATED, (PLR,), "simulated (gplrt)",
         f"{LIVE_TESTS}::test_identity_text_and_power_on_hours"),
    live(103, "software version", TEXT, LIVE, (PLR,), "GPL 4.2J2, Mar  6 2020, Release",
         f"{LIVE_TESTS}::test_identity_text_and_power_on_hours"),
    live(104, "software major version", NUMBER, LIVE, (PLR, SOURCE), "4", f"{LIVE_TESTS}::test_version_robots_date_and_power_state"),
    live(105, "software minor version", NUMBER, LIVE, (PLR, SOURCE), "2", f"{LIVE_TESTS}::test_version_robots_date_and_power_state"),
    live(106, "software edit number", NUMBER, LIVE, (PLR, SOURCE), "1002", f"{LIVE_TESTS}::test_version_robots_date_and_power_state"),
    live(107, "software date", TEXT, LIVE, (PLR,), "Mar  6 2020",
         f"{LIVE_TESTS}::test_identity_text_and_power_on_hours"),
    live(108, "software qualifier", TEXT, LIVE, (PLR,), "Release",
         f"{LIVE_TESTS}::test_identity_text_and_power_on_hours"),
    stored("controller.pac", 109, "controller name", TEXT, PLR),
    live(110, "controller serial number", TEXT, SIMULATED, (PLR,), "0014FF-00000000",
         f"{LIVE_TESTS}::test_identity_text_and_power_on_hours"),
    live(111, "number of robots", NUMBER, LIVE, (SOURCE,), "1", "`selectRobot` (-1001 for robot 2)"),
    live(113, "number of configured robots", NUMBER, LIVE, (SOURCE,), "1", f"{LIVE_TESTS}::test_version_robots_date_and_power_state"),
    stored("controller.pac", 116, "robot types (kinematic module per robot: 12 = PreciseFlex 400)",
           "one number per robot (12)", PLR),
    stored("controller.pac", 117, "safety mode", NUMBER, PLR),
    live(121, "date and time", "text, MM-DD-YYYY HH:MM:SS", LIVE, (SOURCE,),
         re.compile(r"\d\d-\d\d-\d{4} \d\d:\d\d:\d\d"), f"{LIVE_TESTS}::test_version_robots_date_and_power_state"),
    live(136, "power-on hours (of the simulated controller's clock)", NUMBER, SIMULATED, (PLR,),
         re.compile(r"\d+"), f"{LIVE_TESTS}::test_identity_text_and_power_on_hours"),
    stored("controller.pac", 151, "servo network node identifiers", "text per node (16)", PLR),
    live(213, "home all robots (write 1)", NUMBER, "command; reads 0", (SOURCE,), "0",
         f"`homeAll`; {LIVE_TESTS}::test_241_starts_power_without_waiting_and_213_homes_all"),
    live(230, "auto-execution state: 1 while a GPL project runs", NUMBER, LIVE, (PLR,), "1",
         f"{LIVE_TESTS}::test_230_is_1_while_a_gpl_project_runs"),
    live(234, "power state (sysState)", NUMBER, LIVE, (PLR, GUIDE, SOURCE), "21", "`sysState`, `homeAll`"),
    live(241, "power request, do not wait (write 1 or 0)", NUMBER, LIVE, (SOURCE,), "1", "`hp`, `pc`"),
    live(247, "reset fatal error (write 1; no fatal error is simulated)", NUMBER, "command; reads 0", (PLR,),
         "0", f"{LIVE_TESTS}::test_247_resets_no_fatal_error_and_901_saves_the_database_to_flash"),
    live(375, "controller status bits (&H100000: an unreported motion error)", NUMBER, LIVE, (SOURCE,), "0",
         "`waitForEom`"),
    live(420, "local IP address: where the simulated controller listens", TEXT, SIMULATED, (PLR,), "127.0.0.1",
         f"{LIVE_TESTS}::test_420_is_the_address_the_controller_listens_on"),
    live(601, "system speed in %", NUMBER, "live (boots from `controller.pac`)", (GUIDE, SOURCE),
         lambda tcs: num(tcs.cell.sim.controller.system_speed), "`mspeed`"),
    live(901, "save the parameters to flash (write 1)", NUMBER, "command; reads 0", (GUIDE,), "0",
         f"`pc`; {LIVE_TESTS}::test_247_resets_no_fatal_error_and_901_saves_the_database_to_flash"),
    stored("robot01.pac", 2000, "number of axes", NUMBER, PLR, SOURCE),
    stored("robot01.pac", 2002, "robot name", TEXT, PLR, tests="`pc`"),
    stored("robot01.pac", 2003, "axis mask", NUMBER, PLR, SOURCE),
    stored("robot01.pac", 2004, "number of extra axes", NUMBER, PLR),
    stored("robot01.pac", 2007, "robot model (TCS's RobType)", NUMBER, GUIDE, SOURCE),
    stored("robot01.pac", 2700, "100 % joint speeds, mm or deg/s", PER_AXIS, PLR),
    stored("robot01.pac", 2701, "100 % Cartesian speeds (linear, rotation, gripper)", "three numbers", PLR),
    stored("robot01.pac", 2702, "100 % joint accelerations, mm or deg/s²", PER_AXIS, PLR),
    stored("robot01.pac", 2703, "100 % Cartesian accelerations", "three numbers", PLR),
    stored("robot01.pac", 2704, "max speed %", NUMBER, PLR),
    stored("robot01.pac", 2705, "max acceleration %", NUMBER, PLR),
    stored("robot01.pac", 2706, "max deceleration %", NUMBER, PLR),
    live(2800, "robot homed: 1 every axis homed, 0 not", NUMBER, LIVE, (PLR,), "1",
         f"`home` (0 before, 1 after), `homeAll`; {LIVE_TESTS}::test_2800_says_whether_the_robot_is_homed"),
    live(3520, "trajectory state, as Robot.TrajState", NUMBER, LIVE, (SOURCE,), "1",
         f"`MoveRail`; {LIVE_TESTS}::test_241_starts_power_without_waiting_and_213_homes_all"),
    live(12304, "output torque, torque counts", PER_AXIS, LIVE, (SOURCE,),
         re.compile(r"-?[0-9.E+-]+(,-?[0-9.E+-]+){4}"), "`GraspPlate`"),
    live(12331, "filtered feedforward torque, torque counts", PER_AXIS, LIVE, (SOURCE,),
         re.compile(r"-?[0-9.E+-]+(,-?[0-9.E+-]+){4}"), "`GraspPlate`"),
    live(14002, "brake release of the axis 14500 names (write 1 or 0)", NUMBER, LIVE, (SOURCE,),
         re.compile(r"[01]"), "`releaseBrake`, `setBrake`"),
    live(14500, "the axis 14002 acts on", NUMBER, LIVE, (SOURCE,), re.compile(r"\d"), "`releaseBrake`"),
    stored("calib01.pac", 16000, "robot serial number", TEXT, PLR),
    stored("calib01.pac", 16050, "kinematic constants: [2], [3] link lengths, [5] rail angle", "16 numbers",
           PLR, SOURCE),
    stored("calib01.pac", 16051, "tool at restart: X Y Z yaw pitch roll", "six numbers", PLR, tests="`tool`"),
    stored("calib01.pac", 16071, "payload feedforward default %", NUMBER, PLR),
    stored("calib01.pac", 16075, "joint max hard-stop limits", PER_AXIS, PLR),
    stored("calib01.pac", 16076, "joint min hard-stop limits", PER_AXIS, PLR),
    stored("calib01.pac", 16077, "joint max soft limits", PER_AXIS, PLR, tests="`MoveJ` (-1012)"),
    stored("calib01.pac", 16078, "joint min soft limits", PER_AXIS, PLR),
]


@case("reset", TCS, "General", "the status port",
      "from the status port: the robot's connection is broken, a new one is served; -2808 from the robot port")
def _reset(tcs: Tcs) -> None:
    tcs.expect("reset 1", "-2808 *Not allowed by this thread*")
    tcs.on_status("reset 1", "0")
    assert closed_by_server(tcs.robot)
    assert "Stopping robot threads 1\nStarting robot Threads 1\n" in tcs.cell.console
    tcs.reconnect()
    tcs.expect("nop", "0")
    tcs.ensure()


@case("selectRobot", TCS, "General", "nothing",
      "robot 1 on its port; the status port selects robot 1 and back to 0; -1001, -2808")
def _select_robot(tcs: Tcs) -> None:
    tcs.expect("selectRobot", "0 1")
    tcs.expect("selectRobot 2", "-1001")  # *Undefined robot*: one PF400
    tcs.expect("selectRobot 0", "-2808 *Not allowed by this thread*")
    tcs.ok("selectRobot 1")
    tcs.on_status("selectRobot", "0 0")
    tcs.on_status("selectRobot 1", "0")
    tcs.on_status("selectRobot", "0 1")
    tcs.on_status("wherej", "0 " + nums(tcs.joints()))  # robot 1's joints, read by the status thread
    tcs.on_status("selectRobot 0", "0")
    tcs.on_status("selectRobot", "0 0")


@case("sig", TCS, "General", "nothing",
      "an output set and read back on the simulated controller; an input read; -2807 setting an input")
def _sig(tcs: Tcs) -> None:
    tcs.expect("sig 13", "0 13 0")
    tcs.ok("sig 13 1")
    assert tcs.cell.output(13)
    tcs.expect("sig 13", "0 13 -1")
    tcs.ok("sig 13 0")
    assert not tcs.cell.output(13)
    tcs.cell.set_input(10001, True)
    try:
        tcs.expect("sig 10001", "0 10001 -1")
        tcs.expect("sig 10001 0", "-2807 *Warning cannot set Input states*")
    finally:
        tcs.cell.set_input(10001, False)
    tcs.expect("sig 10001", "0 10001 0")


@case("tool", TCS, "General", "robot attached (to set)",
      "the tool read and set; wherec moves with it, the joints do not; -2800")
def _tool(tcs: Tcs) -> None:
    tcs.ensure()
    tcs.expect("tool", f"0 {nums(TOOL)} 0 0 0")
    q = tcs.joints()
    try:
        tcs.ok("tool 0 0 100 0 0 0")
        tcs.expect("tool", "0 0 0 100 0 0 0")
        assert tcs.joints() == pytest.approx(q, abs=1e-9)
        tcs.assert_pose(pf400_pose(q, tool=(0.0, 0.0, 100.0)), tool=(0.0, 0.0, 100.0))
        tcs.expect("tool 1 2", "-2800 *Warning Parameter Mismatch*")
    finally:
        tcs.ok(f"tool {nums(TOOL)} 0 0 0")
    tcs.assert_pose(pf400_pose(q))


@case("base", TCS, "General", "robot attached (to set)",
      "the base read and set; wherec moves with it, the joints do not; -2800")
def _base(tcs: Tcs) -> None:
    tcs.ensure()
    tcs.expect("base", "0 0 0 0 0")
    q = tcs.joints()
    base = (10.0, 20.0, 5.0, 30.0)
    try:
        tcs.ok(f"base {nums(base)}")
        tcs.expect("base", f"0 {nums(base)}")
        assert tcs.joints() == pytest.approx(q, abs=1e-9)
        pose = pf400_pose(q, base=base)
        tcs.expect("wherec", f"0 {nums(pose)} {pf400_config(q)}")
        tcs.expect("base 1 2", "-2800 *Warning Parameter Mismatch*")
    finally:
        tcs.ok("base 0 0 0 0")
    tcs.assert_pose(pf400_pose(q))


@case("exit", TCS, "General", "nothing",
      "closes the connection without a reply; TCS serves the next one")
def _exit(tcs: Tcs) -> None:
    tcs.robot.send("exit\n")
    assert closed_by_server(tcs.robot)
    tcs.reconnect()
    tcs.expect("nop", "0")


# ---- Location commands

@case("loc", TCS, "Location", "a station",
      "an angles and a Cartesian station (a pallet's offset: PalletIndex); -2801, -2800, -2814, -2816")
def _loc(tcs: Tcs) -> None:
    tcs.ok(f"locAngles 2 {nums(JOINTS_A)}", f"locXyz 5 {nums(CART_C)}")
    tcs.expect("loc 2", f"0 1 2 {nums(JOINTS_A)}")
    tcs.expect("loc 5", f"0 0 5 {nums(CART_C)}")
    tcs.expect("loc", "-2801 *Warning No Parameters")
    tcs.expect("loc 2 5", "-2800 *Warning Parameter Mismatch*")
    tcs.expect("loc 0", "-2814 *Invalid location index*")
    tcs.expect("loc 21", "-2816 *Undefined location*")


@case("locAngles", TCS, "Location", "a station",
      "angles set and read; extra values ignored, missing ones 0; -763 reading a Cartesian station")
def _loc_angles(tcs: Tcs) -> None:
    tcs.ok(f"locAngles 3 {nums(JOINTS_B)} 7")
    tcs.expect("locAngles 3", f"0 1 3 {nums(JOINTS_B)}")
    tcs.ok("locAngles 3 250 -20")
    tcs.expect("locAngles 3", "0 1 3 250 -20 0 0 0")
    tcs.ok(f"locXyz 5 {nums(CART_C)}")
    tcs.expect("locAngles 5", "-763")  # *Location not an angles type*
    tcs.expect("locAngles 0", "-2814 *Invalid location index*")


@case("locXyz", TCS, "Location", "a station",
      "X Y Z yaw pitch roll set and read; -762 reading an angles station; -2800")
def _loc_xyz(tcs: Tcs) -> None:
    tcs.ok(f"locXyz 5 {nums(CART_C)}")
    tcs.expect("locXyz 5", f"0 0 5 {nums(CART_C)}")
    tcs.ok(f"locAngles 2 {nums(JOINTS_A)}")
    tcs.expect("locXyz 2", "-762")  # *Location not a Cartesian type*
    tcs.expect("locXyz 5 1 2", "-2800 *Warning Parameter Mismatch*")


@case("locZClearance", TCS, "Location", "a station",
      "unset (1E+32) on a new location, then set and read (moveAppro uses it)")
def _loc_zclearance(tcs: Tcs) -> None:
    tcs.ok(f"locXyz 5 {nums(CART_C)}")
    tcs.expect("locZClearance 5", "0 5 1E+32")
    tcs.ok("locZClearance 5 40")
    tcs.expect("locZClearance 5", "0 5 40")


@case("locConfig", TCS, "Location", "a station", "the configuration bits set and read")
def _loc_config(tcs: Tcs) -> None:
    tcs.ok(f"locXyz 5 {nums(CART_C)}")
    tcs.expect("locConfig 5", "0 5 0")
    tcs.ok("locConfig 5 1")
    tcs.expect("locConfig 5", "0 5 1")


@case("DestC", TCS, "Location", "robot",
      "while the robot moves: the target's pose; when it stops: where it is; -2800")
def _dest_c(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.expect("destC", f"0 {nums(pf400_pose(JOINTS_A))} {pf400_config(JOINTS_A)}")
    tcs.slow_move(JOINTS_B)
    target = f"0 {nums(pf400_pose(JOINTS_B))} {pf400_config(JOINTS_B)}"
    tcs.expect("destC", target)
    tcs.expect("destC 1", target)
    assert tcs.ask("wherec") != target  # not there yet
    tcs.expect("destC 2", "-2800 *Warning Parameter Mismatch*")
    tcs.ok("waitForEom")
    tcs.expect("destC", target)


@case("DestJ", TCS, "Location", "robot",
      "while the robot moves: the target's joints; when it stops: its joints; -2800")
def _dest_j(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.expect("destJ", f"0 {nums(JOINTS_A)}")
    tcs.slow_move(JOINTS_B)
    tcs.expect("destJ", f"0 {nums(JOINTS_B)}")
    tcs.expect("destJ 1", f"0 {nums(JOINTS_B)}")
    assert tcs.ask("wherej") != f"0 {nums(JOINTS_B)}"
    tcs.expect("destJ 2", "-2800 *Warning Parameter Mismatch*")
    tcs.ok("waitForEom")
    tcs.expect("destJ", f"0 {nums(JOINTS_B)}")


@case("HereJ", TCS, "Location", "robot; a station",
      "teaches the robot's joints into a station, which move then reaches; -2801, -2814")
def _here_j(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_B)
    tcs.ok("hereJ 4")
    tcs.expect("loc 4", f"0 1 4 {nums(JOINTS_B)}")
    tcs.move_to(JOINTS_A)
    tcs.ok("move 4 1", "waitForEom")
    tcs.assert_joints(JOINTS_B)
    tcs.expect("hereJ", "-2801 *Warning No Parameters")
    tcs.expect("hereJ 0", "-2814 *Invalid location index*")


@case("HereC", TCS, "Location", "robot; a Cartesian station",
      "teaches the robot's pose and configuration into a Cartesian station; -763 for an angles station")
def _here_c(tcs: Tcs) -> None:
    tcs.ok(f"locXyz 5 {nums(CART_C)}")
    tcs.move_to(JOINTS_B)
    tcs.ok("hereC 5")
    tcs.expect("loc 5", f"0 0 5 {nums(pf400_pose(JOINTS_B))}")
    tcs.expect("locConfig 5", f"0 5 {pf400_config(JOINTS_B)}")
    # Location.Pos, which HereC sets, needs a location of the same type (gpl-dictionary Pos)
    tcs.ok(f"locAngles 4 {nums(JOINTS_A)}")
    tcs.expect("hereC 4", "-763")  # *Location not an angles type*


@case("where", TCS, "Location", "robot", "the pose, then the joints, of the simulated robot")
def _where(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.expect("where", f"0 {nums(pf400_pose(JOINTS_A))} {nums(JOINTS_A)}")


@case("wherec", TCS, "Location", "robot", "the pose and configuration of the simulated robot")
def _where_c(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_B)
    tcs.assert_pose(pf400_pose(JOINTS_B))
    tcs.move_to(SAFE)  # the elbow at 180 degrees: lefty
    tcs.expect("wherec", f"0 {nums(pf400_pose(SAFE))} 2")


@case("wherej", TCS, "Location", "robot", "the joints of the simulated robot")
def _where_j(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.expect("wherej", f"0 {nums(JOINTS_A)}")
    tcs.assert_joints(JOINTS_A)


# ---- Profile commands

def profile_property(tcs: Tcs, command: str, default: str, value: str, slot: int) -> None:
    """``command`` reads and sets one property of profile 1, which ``profile 1`` shows in ``slot``."""
    tcs.expect(f"{command} 1", f"0 1 {default}")
    try:
        tcs.ok(f"{command} 1 {value}")
        tcs.expect(f"{command} 1", f"0 1 {value}")
        assert tcs.ask("profile 1").split()[2 + slot] == value
        tcs.expect(f"{command} 0", "-2815 *Invalid profile index*")
        tcs.expect(f"{command} 21", "-2815 *Invalid profile index*")
        tcs.expect(command, "-2801 *Warning No Parameters")
    finally:
        tcs.ok(f"{command} 1 {default}")


@case("Speed", TCS, "Profile", "nothing", "read, set, shown by profile; -2815, -2801")
def _speed(tcs: Tcs) -> None:
    profile_property(tcs, "speed", "50", "60", 0)


@case("Speed2", TCS, "Profile", "nothing", "read, set, shown by profile; -2815, -2801")
def _speed2(tcs: Tcs) -> None:
    profile_property(tcs, "speed2", "0", "40", 1)


@case("Accel", TCS, "Profile", "nothing", "read, set, shown by profile; -2815, -2801")
def _accel(tcs: Tcs) -> None:
    profile_property(tcs, "accel", "100", "70", 2)


@case("AccRamp", TCS, "Profile", "nothing", "read, set, shown by profile; -2815, -2801")
def _acc_ramp(tcs: Tcs) -> None:
    profile_property(tcs, "accRamp", "0.1", "0.25", 4)


@case("Decel", TCS, "Profile", "nothing", "read, set, shown by profile; -2815, -2801")
def _decel(tcs: Tcs) -> None:
    profile_property(tcs, "decel", "100", "80", 3)


@case("DecRamp", TCS, "Profile", "nothing", "read, set, shown by profile; -2815, -2801")
def _dec_ramp(tcs: Tcs) -> None:
    profile_property(tcs, "decRamp", "0.1", "0.3", 5)


@case("InRange", TCS, "Profile", "nothing", "read (two decimals), set, shown by profile; -2815, -2801")
def _in_range(tcs: Tcs) -> None:
    profile_property(tcs, "inRange", "10", "-1", 6)


@case("Straight", TCS, "Profile", "robot (to see it)",
      "read and set; a straight profile moves the tool along the line, a joint one does not")
def _straight(tcs: Tcs) -> None:
    tcs.expect("straight 3", "0 3 False")
    tcs.ok("straight 3 -1")
    tcs.expect("straight 3", "0 3 True")
    tcs.expect("straight 0", "-2815 *Invalid profile index*")
    start = pf400_pose(JOINTS_A)
    for profile, straight in ((3, True), (1, False)):
        tcs.move_to(JOINTS_A)
        t0 = tcs.cell.time
        tcs.ok(f"moveC {profile} {nums(CART_C)} 1", "waitForEom")
        t1 = tcs.cell.time
        tcs.assert_pose(CART_C)
        times, _, xyz = tcs.cell.sim.trace(1, 0.01)
        path = xyz[(times >= t0) & (times <= t1)]
        a, b = np.array(start[:3]), np.array(CART_C[:3])
        off_line = np.linalg.norm(np.cross(path - a, b - a), axis=1) / np.linalg.norm(b - a)
        assert len(path) > 10
        assert (off_line.max() < 0.01) == straight, off_line.max()
    tcs.ok("straight 3 0")


@case("Profile", TCS, "Profile", "nothing",
      "all eight properties read and set at once; -2800, -2801")
def _profile(tcs: Tcs) -> None:
    tcs.expect("profile 1", "0 1 50 0 100 100 0.1 0.1 10 0")
    tcs.ok("profile 2 30 0 80 80 0.2 0.2 5 -1")
    tcs.expect("profile 2", "0 2 30 0 80 80 0.2 0.2 5 -1")
    tcs.expect("straight 2", "0 2 True")
    tcs.expect("profile 2 1 2", "-2800 *Warning Parameter Mismatch*")
    tcs.expect("profile", "-2801 *Warning No Parameters")
    tcs.ok("profile 2 50 0 100 100 0.1 0.1 10 0")


# ---- Motion commands

@case("halt", TCS, "Motion", "robot moving",
      "stops a motion short of its target; power stays on")
def _halt(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.slow_move(JOINTS_B)
    time.sleep(0.2)
    tcs.ok("halt", "waitForEom")
    assert abs(tcs.joints()[0] - JOINTS_B[0]) > 1.0  # stopped well before the target
    tcs.expect("state", "0 1")
    tcs.expect("hp", "0 1")


@case("Move", TCS, "Motion", "power; robot attached, homed; a station",
      "to a Cartesian and to an angles station; -1009, -2802, -2816, -2815")
def _move(tcs: Tcs) -> None:
    tcs.ok(f"locXyz 5 {nums(CART_C)}", "locConfig 5 1", f"locAngles 2 {nums(JOINTS_A)}")
    tcs.move_to(JOINTS_B)
    tcs.ok("move 5 1", "waitForEom")
    tcs.assert_pose(CART_C)
    tcs.ok("move 2 1", "waitForEom")
    tcs.assert_joints(JOINTS_A)
    tcs.expect("move 5", "-2802 *Warning Illegal move command*")
    tcs.expect("move 21 1", "-2816 *Undefined location*")
    tcs.expect("move 5 21", "-2815 *Invalid profile index*")
    tcs.ok("attach 0")
    tcs.expect("move 5 1", "-1009")  # *No robot attached*


@case("moveAppro", TCS, "Motion", "power; robot attached, homed; a station with a ZClearance",
      "to the point ZClearance back along the tool from the station; -2802")
def _move_appro(tcs: Tcs) -> None:
    tcs.ok(f"locXyz 5 {nums(CART_C)}", "locConfig 5 1", "locZClearance 5 40")
    tcs.move_to(JOINTS_A)
    tcs.ok("moveAppro 5 1", "waitForEom")
    yaw = math.radians(CART_C[3])  # the PF400's tool points along yaw, horizontally
    tcs.assert_pose((CART_C[0] - 40 * math.cos(yaw), CART_C[1] - 40 * math.sin(yaw), *CART_C[2:]))
    tcs.expect("moveAppro 5", "-2802 *Warning Illegal move command*")


@case("MoveOneAxis", TCS, "Motion", "power; robot attached, homed",
      "one joint to its destination, the others stay; -2802, -1012")
def _move_one_axis(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.ok("moveOneAxis 1 200 1", "waitForEom")
    tcs.assert_joints((200.0, *JOINTS_A[1:]))
    tcs.expect("moveOneAxis 1 200", "-2802 *Warning Illegal move command*")
    tcs.expect("moveOneAxis 1 2000 1", "-1012")  # *Joint out-of-range*


@case("MoveC", TCS, "Motion", "power; robot attached, homed",
      "to a Cartesian pose (PF400 kinematics); -2804, -1040 out of reach")
def _move_c(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.ok(f"moveC 1 {nums(CART_C)} 1", "waitForEom")
    tcs.assert_pose(CART_C)
    tcs.expect("moveC 1 400 100", "-2804 *Warning: Invalid Cartesian coordinate values*")
    tcs.expect("moveC 1 2000 0 100 0 90 180 1", "-1040")  # *Position too far*
    tcs.assert_pose(CART_C)


@case("MoveJ", TCS, "Motion", "power; robot attached, homed",
      "to joint angles; -2803 too few, -1012 beyond a soft limit")
def _move_j(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_B)
    tcs.ok(f"moveJ 1 {nums(JOINTS_A)}", "waitForEom")
    tcs.assert_joints(JOINTS_A)
    tcs.expect("moveJ 1 300 10", "-2803 *Warning Invalid joint angles*")
    tcs.expect("moveJ 1 300 10 900 -100 90", "-1012")  # *Joint out-of-range*
    tcs.assert_joints(JOINTS_A)


@case("releaseBrake", TCS, "Motion", "robot", "releases an axis's brake (DataID 14002 reads 1)")
def _release_brake(tcs: Tcs) -> None:
    tcs.ensure()
    tcs.ok("releaseBrake 3")
    assert 3 in tcs.arm.brakes_released
    tcs.expect("pd 14002", "0 1")
    tcs.ok("setBrake 3")


@case("setBrake", TCS, "Motion", "robot", "sets a released brake again (DataID 14002 reads 0)")
def _set_brake(tcs: Tcs) -> None:
    tcs.ensure()
    tcs.ok("releaseBrake 2", "setBrake 2")
    assert 2 not in tcs.arm.brakes_released
    tcs.expect("pd 14002", "0 0")


@case("state", TCS, "Motion", "robot", "1 idle, 2 to 5 while moving, as Robot.TrajState")
def _state(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.expect("state", "0 1")
    tcs.slow_move(JOINTS_B)
    assert tcs.ask("state") in ("0 2", "0 3", "0 4", "0 5")
    tcs.ok("waitForEom")
    tcs.expect("state", "0 1")


@case("waitForEom", TCS, "Motion", "robot", "replies once the robot has stopped at its target")
def _wait_for_eom(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.slow_move(JOINTS_B)
    tcs.ok("waitForEom")
    tcs.assert_joints(JOINTS_B)
    tcs.expect("state", "0 1")


@case("zeroTorque", TCS, "Motion", "power; robot attached, homed",
      "the masked axes in torque mode (state 8), holding where they are; back to position mode; -2800")
def _zero_torque(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.ok("zeroTorque 1 3")  # axes 1 and 2
    tcs.expect("state", "0 8")
    assert tcs.arm.special.kind == "torque" and set(tcs.arm.special.torques) == {0, 1}
    tcs.assert_joints(JOINTS_A)
    tcs.ok("zeroTorque 0")
    tcs.expect("state", "0 1")
    tcs.expect("zeroTorque 1", "-2800 *Warning Parameter Mismatch*")


# ---- Vision commands: a PF400 without a vision system

NO_VISION = "a PF400 without a vision system, whose controller cannot connect to a PreciseVision server"


@case("vprocess", TCS, "Vision", "vision", "replies -4000", NOT_SIMULATED, NO_VISION)
def _vprocess(tcs: Tcs) -> str:
    return tcs.expect("vprocess find_plate", "-4000")


@case("vresultInfo", TCS, "Vision", "vision", "replies -4000; -2800 for one argument", NOT_SIMULATED, NO_VISION)
def _vresult_info(tcs: Tcs) -> str:
    tcs.expect("vresultInfo find_plate", "-2800 *Warning Parameter Mismatch*")
    return tcs.expect("vresultInfo", "-4000")


@case("vresultInspect", TCS, "Vision", "vision", "replies -4000; -2800 for one argument", NOT_SIMULATED,
      NO_VISION)
def _vresult_inspect(tcs: Tcs) -> str:
    tcs.expect("vresultInspect find_plate", "-2800 *Warning Parameter Mismatch*")
    return tcs.expect("vresultInspect", "-4000")


@case("vresultLoc", TCS, "Vision", "vision", "replies -4000; -2800 for one argument", NOT_SIMULATED, NO_VISION)
def _vresult_loc(tcs: Tcs) -> str:
    tcs.expect("vresultLoc find_plate", "-2800 *Warning Parameter Mismatch*")
    return tcs.expect("vresultLoc", "-4000")


# ---- Load-Save plug-in (the guide's appendix)

@case("LoadFile", TCS, "Load-Save", "a .gpo file",
      "the taught stations and profiles of a real PF400 cell's Tcs.gpo; -508 for a missing file")
def _load_file(tcs: Tcs) -> None:
    tcs.expect("loadFile nothere", "-508 *File not found*, file: nothere.gpo")
    tcs.ok("loadFile /flash/data/taught.gpo")
    tcs.expect("loc 1", "0 0 1 -493.564 -82.63 1157.13 -83.037 90 180")  # XYZ(-493.56371, ...) in the file
    tcs.expect("locConfig 1", "0 1 1")
    tcs.expect("loc 2", "0 1 2 0 0 0 0 0")
    tcs.expect("profile 20", "0 20 50 0 100 100 0.1 0.1 10 0")


@case("StoreFile", TCS, "Load-Save", "nothing",
      "writes the stations and profiles in the format a real controller's TCS wrote")
def _store_file(tcs: Tcs) -> None:
    tcs.ok(f"locXyz 5 {nums(CART_C)}", "locZClearance 5 40", "locConfig 5 1", "speed 3 33")
    try:
        tcs.ok("storeFile /flash/data/stored.gpo")
    finally:
        tcs.ok("speed 3 50")
    text = (tcs.flash / "flash" / "data" / "stored.gpo").read_text(encoding="latin-1")
    taught = (corpus_dir() / "docs" / TAUGHT).read_text(encoding="latin-1")
    declarations = [line for line in taught.splitlines() if line.startswith(("Module ", "  Public "))]
    assert [line for line in text.splitlines() if line.startswith(("Module ", "  Public "))] == declarations
    assert ("    '<MotionLocation>tcs_sta_loc_1,20\n"
            "    tcs_sta_loc_1(5) = New Location\n"
            "    tcs_sta_loc_1(5).Type = 0\n"
            "    tcs_sta_loc_1(5).XYZ(400,100,250,0,90,180)\n"
            "    tcs_sta_loc_1(5).ZWorld = False\n"
            "    tcs_sta_loc_1(5).ZClearance = 40\n"
            "    tcs_sta_loc_1(5).Config = 1\n"
            "    '</MotionLocation>\n") in text
    assert "    tcs_prof_1(3).Speed = 33\n" in text


# ---- PARobot commands

@case("ChangeConfig", PA, "PARobot", "power; robot attached, homed; a PF400",
      "righty to lefty and back through PARobot's configuration points, the gripper opened; -2801, -2800")
def _change_config(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)  # righty
    tcs.ok("ChangeConfig 1")
    lefty = (170.0, -20.0, 240.0, -225.0, GRIP_OPEN)  # PARobot's Lefty_j, gripper open
    tcs.assert_joints(lefty)
    tcs.expect("wherec", f"0 {nums(pf400_pose(lefty))} 2")
    tcs.ok("ChangeConfig 0")
    righty = (170.0, 10.0, 120.0, -130.0, GRIP_OPEN)  # Righty_j, gripper unchanged
    tcs.assert_joints(righty)
    tcs.expect("wherec", f"0 {nums(pf400_pose(righty))} 1")
    tcs.expect("ChangeConfig", "-2801 *Warning No Parameters")
    tcs.expect("ChangeConfig 3", "-2800 *Warning Parameter Mismatch*")


@case("ChangeConfig2", PA, "PARobot", "power; robot attached, homed; a PF400",
      "righty to lefty and back by swinging the elbow through 180 degrees, the gripper closed; -2801")
def _change_config2(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.ok("ChangeConfig2 2")
    q = tcs.joints()
    assert q[2] == pytest.approx(205.0, abs=1e-6) and q[4] == pytest.approx(GRIP_CLOSE, abs=1e-6)
    tcs.expect("wherec", f"0 {nums(pf400_pose(q))} 2")
    tcs.ok("ChangeConfig2 0")
    q = tcs.joints()
    assert q[2] == pytest.approx(155.0, abs=1e-6)
    tcs.expect("wherec", f"0 {nums(pf400_pose(q))} 1")
    tcs.expect("ChangeConfig2", "-2801 *Warning No Parameters")


@case("FreeMode", PA, "PARobot", "power; robot attached, homed",
      "an axis made free (jog mode, state 10) and moved by hand; all held again; -2800, -2801")
def _free_mode(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.ok("FreeMode 3")
    tcs.expect("state", "0 10")
    assert tcs.arm.special.free == {2}
    push(tcs.cell.sim, 1, {3: 100.0})  # the operator moves the elbow by hand
    tcs.ok("FreeMode -1")
    tcs.expect("state", "0 1")
    tcs.assert_joints((300.0, 10.0, 100.0, -100.0, 90.0))
    tcs.expect("FreeMode 9", "-2800 *Warning Parameter Mismatch*")
    tcs.expect("FreeMode", "-2801 *Warning No Parameters")


@case("GraspData", PA, "PARobot", "nothing", "plate width, finger speed, force read and set; -2800")
def _grasp_data(tcs: Tcs) -> None:
    tcs.expect("GraspData", "0 80 50 10")
    tcs.ok("GraspData 85 40 12")
    tcs.expect("GraspData", "0 85 40 12")
    tcs.expect("GraspData 1 2", "-2800 *Warning Parameter Mismatch*")
    tcs.ok("GraspData 80 50 10")


@case("GripClosePos", PA, "PARobot", "a servo gripper", "read and set; gripper 2 closes there")
def _grip_close_pos(tcs: Tcs) -> None:
    tcs.ensure()
    tcs.expect("GripClosePos", "0 75.5")
    try:
        tcs.ok("GripClosePos 78", "gripper 2")
        tcs.expect("GripClosePos", "0 78")
        assert tcs.joints()[4] == pytest.approx(78.0, abs=1e-6)
    finally:
        tcs.ok("GripClosePos 75.5")


@case("GripOpenPos", PA, "PARobot", "a servo gripper", "read and set; gripper 1 opens there")
def _grip_open_pos(tcs: Tcs) -> None:
    tcs.ensure()
    tcs.expect("GripOpenPos", "0 100")
    try:
        tcs.ok("GripOpenPos 110", "gripper 1")
        tcs.expect("GripOpenPos", "0 110")
        assert tcs.joints()[4] == pytest.approx(110.0, abs=1e-6)
    finally:
        tcs.ok("GripOpenPos 100")


@case("Gripper", PA, "PARobot", "power; robot attached, homed; a servo gripper",
      "opens and closes the servo gripper; -2800, -2801")
def _gripper(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.ok("gripper 1")
    tcs.assert_joints((*JOINTS_A[:4], GRIP_OPEN))
    tcs.ok("gripper 2")
    tcs.assert_joints((*JOINTS_A[:4], GRIP_CLOSE))
    tcs.expect("gripper 3", "-2800 *Warning Parameter Mismatch*")
    tcs.expect("gripper", "-2801 *Warning No Parameters")


@case("movetosafe", PA, "PARobot", "power; robot attached, homed; a PF400",
      "to PARobot's safe position with the gripper closed; -1009 not attached")
def _move_to_safe(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_B)
    tcs.ok("movetosafe")
    tcs.assert_joints(SAFE)
    tcs.ok("attach 0")
    tcs.expect("movetosafe", "-1009")  # *No robot attached*


def make_pallet(tcs: Tcs, station: int) -> None:
    """A 3 x 2 x 2 pallet: origin (400, 0, 200), 3 along +Y every 50 mm, 2 along +X 100 mm apart."""
    tcs.ok(f"StationType {station} 1 1 50 5 0", f"PalletOrigin {station} 400 0 200 0 90 180 1",
           f"PalletX {station} 3 400 100 200", f"PalletY {station} 2 500 0 200", f"PalletZ {station} 2 400 0 250")


@case("PalletOrigin", PA, "PARobot", "a pallet station", "the origin set and read; -2822 not a pallet")
def _pallet_origin(tcs: Tcs) -> None:
    tcs.ok("StationType 8 1 1 50 5 0", "PalletOrigin 8 400 0 200 0 90 180 1")
    tcs.expect("PalletOrigin 8", "0 8  400 0 200 0 90 180 1")
    tcs.expect("loc 8", "0 0 8 400 0 200 0 90 180")
    tcs.ok(f"locXyz 5 {nums(CART_C)}")
    tcs.expect("PalletOrigin 5", "-2822 *Not a pallet*")


@case("PalletX", PA, "PARobot", "a pallet station", "count and last point along X set and read")
def _pallet_x(tcs: Tcs) -> None:
    tcs.ok("StationType 8 1 1 50 5 0", "PalletOrigin 8 400 0 200 0 90 180 1", "PalletX 8 3 400 100 200")
    tcs.expect("PalletX 8", "0 83 400 100 200")  # TCS runs the station and the count together


@case("PalletY", PA, "PARobot", "a pallet station", "count and last point along Y set and read")
def _pallet_y(tcs: Tcs) -> None:
    tcs.ok("StationType 8 1 1 50 5 0", "PalletOrigin 8 400 0 200 0 90 180 1", "PalletX 8 3 400 100 200",
           "PalletY 8 2 500 0 200")
    tcs.expect("PalletY 8", "0 82 500 0 200")


@case("PalletZ", PA, "PARobot", "a pallet station",
      "count and layer pitch set and read (along the frame's Z, which these X and Y make point down)")
def _pallet_z(tcs: Tcs) -> None:
    make_pallet(tcs, 8)
    tcs.expect("PalletZ 8", "0 82 400 0 150")


@case("PalletIndex", PA, "PARobot", "a pallet station; robot to move there",
      "the index read and set; loc and move go to that pallet position; -2820")
def _pallet_index(tcs: Tcs) -> None:
    make_pallet(tcs, 8)
    tcs.expect("PalletIndex 8", "0 8 1 1 1")
    tcs.ok("PalletIndex 8 3 2 0")  # 0: that index unchanged
    tcs.expect("PalletIndex 8", "0 8 3 2 1")
    position = (500.0, 100.0, 200.0, 0.0, 90.0, 180.0)  # origin + 2 x 50 along +Y + 1 x 100 along +X
    tcs.expect("loc 8", f"0 0 8 {nums(position)}")
    tcs.move_to(JOINTS_A)
    tcs.ok("move 8 1", "waitForEom")
    tcs.assert_pose(position)
    tcs.expect("PalletIndex 0", "-2820 *Invalid station index*")


def teach_plate_station(tcs: Tcs, station: int) -> tuple[float, ...]:
    """Teach ``station`` with TeachPlate at JOINTS_A with the gripper open (ZClearance 40)."""
    at = (*JOINTS_A[:4], 110.0)
    tcs.move_to(at)
    tcs.ok(f"TeachPlate {station} 40")
    return pf400_pose(at)


@case("PickPlate", PA, "PARobot", "power; robot attached, homed; a Cartesian station with a ZClearance",
      "picks a plate at a horizontal station: grasped (0 -1) on the simulated plate, not (0 0) without; "
      "ends at the approach; -2803, -794; -204 with horizontal compliance (protected code)")
def _pick_plate(tcs: Tcs) -> None:
    plate = teach_plate_station(tcs, 6)
    gripper = gripper_of(tcs.cell.sim)  # plate_width: a plate between its fingers
    tcs.move_to(JOINTS_B)
    gripper.plate_width = 80.0
    try:
        tcs.expect("PickPlate 6", "0 -1")
        assert tcs.joints()[4] == pytest.approx(80.0, abs=1e-6)  # the fingers on the plate
        # lifted by z_above (5), withdrawn ZClearance (40) back along the tool
        tcs.assert_pose((plate[0] - 40.0, plate[1], plate[2] + 5.0, *plate[3:]))
    finally:
        gripper.plate_width = None  # (the fingers close on nothing)
    tcs.expect("PickPlate 6", "0 0")  # nothing between the fingers
    tcs.expect("PickPlate 6 1", "-204")  # horizontal compliance: PARobot_auto_center.gpp
    tcs.ok(f"locAngles 2 {nums(JOINTS_A)}", f"locXyz 7 {nums(CART_C)}")
    tcs.expect("PickPlate 2", "-2803 *Warning Invalid joint angles*")
    tcs.expect("PickPlate 7", "-794")  # *ZClearance property not set*


@case("PlacePlate", PA, "PARobot", "power; robot attached, homed; a Cartesian station with a ZClearance",
      "places the plate in hand at a horizontal station, opens the gripper and withdraws to the approach")
def _place_plate(tcs: Tcs) -> None:
    plate = teach_plate_station(tcs, 6)
    gripper = gripper_of(tcs.cell.sim)  # plate_width: a plate between its fingers
    tcs.move_to(JOINTS_B)
    gripper.plate_width = 80.0
    try:
        tcs.expect("PickPlate 6", "0 -1")
        tcs.ok("PlacePlate 6")
    finally:
        gripper.plate_width = None
    assert tcs.joints()[4] == pytest.approx(GRIP_OPEN, abs=1e-6)
    tcs.assert_pose((plate[0] - 40.0, *plate[1:]))


@case("TeachPlate", PA, "PARobot", "robot; a station",
      "the robot's pose becomes a Cartesian station with its ZClearance (default 50); -2852 while moving")
def _teach_plate(tcs: Tcs) -> None:
    plate = teach_plate_station(tcs, 6)
    tcs.expect("loc 6", f"0 0 6 {nums(plate)}")
    tcs.expect("StationType 6", "0 6 0 0 40 5 0")
    tcs.ok("TeachPlate 7")
    tcs.expect("locZClearance 7", "0 7 50")
    tcs.slow_move(JOINTS_B)
    tcs.expect("TeachPlate 7", "-2852 *Invalid robot state to execute command*")
    tcs.ok("waitForEom")


@case("StationType", PA, "PARobot", "a station",
      "access, pallet type, ZClearance, ZAbove, ZGrasp offset set and read; -2820, -2801")
def _station_type(tcs: Tcs) -> None:
    tcs.ok("locAngles 9 0 0 0 0 0")
    tcs.expect("StationType 9", "0 9 0 0 1E+32 5 0")
    tcs.ok("StationType 9 1 0 50 7 3")
    tcs.expect("StationType 9", "0 9 1 0 50 7 3")
    tcs.expect("loc 9", "0 0 9 0 0 0 0 0 0")  # made Cartesian
    tcs.expect("StationType 0", "-2820 *Invalid station index*")
    tcs.expect("StationType", "-2801 *Warning No Parameters")


# ---- SSGRIP commands

@case("HomeAll_IfNoPlate", PA, "SSGRIP", "a PF400 with a servo gripper",
      "fingers fully closed (no plate): power on and home, 0 -1; fingers open (a plate?): 0 0, nothing done")
def _home_all_if_no_plate(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.ok("gripper 1")
    tcs.ok("hp 0")
    tcs.expect("HomeAll_IfNoPlate", "0 0")  # the fingers are open: they might hold a plate
    assert not tcs.powered()
    tcs.ensure()
    tcs.expect("GraspPlate 80 50 10", "0 0")  # closes fully on nothing
    tcs.ok("hp 0")
    tcs.expect("HomeAll_IfNoPlate", "0 -1")
    assert tcs.powered() and tcs.arm.homed


@case("GraspPlate", PA, "SSGRIP", "power; robot attached, homed; a servo gripper",
      "closes on the simulated plate with limited force, 0 -1; on nothing, 0 0; -2800")
def _grasp_plate(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    gripper = gripper_of(tcs.cell.sim)  # plate_width: a plate between its fingers
    tcs.ok("gripper 1")
    gripper.plate_width = 80.0
    try:
        tcs.expect("GraspPlate 80 50 10", "0 -1")
        assert tcs.joints()[4] == pytest.approx(80.0, abs=1e-6)
    finally:
        gripper.plate_width = None
    tcs.ok("ReleasePlate 100 50", "waitForEom")
    tcs.expect("GraspPlate 80 50 10", "0 0")
    assert tcs.joints()[4] == pytest.approx(gripper.closed_stop, abs=1e-6)
    tcs.expect("GraspPlate 80", "-2800 *Warning Parameter Mismatch*")


@case("ReleasePlate", PA, "SSGRIP", "power; robot attached, homed; a servo gripper",
      "opens the gripper off the plate to the width given; -2800")
def _release_plate(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    gripper = gripper_of(tcs.cell.sim)  # plate_width: a plate between its fingers
    gripper.plate_width = 80.0
    try:
        tcs.ok("gripper 1")
        tcs.expect("GraspPlate 80 50 10", "0 -1")
        tcs.ok("ReleasePlate 105 50", "waitForEom")
    finally:
        gripper.plate_width = None
    assert tcs.joints()[4] == pytest.approx(105.0, abs=1e-6)
    tcs.expect("ReleasePlate 100", "-2800 *Warning Parameter Mismatch*")


@case("IsFullyClosed", PA, "SSGRIP", "a PF400 servo gripper",
      "the end-of-travel sensor: 0 -1 closed on nothing, 0 0 open or on a plate")
def _is_fully_closed(tcs: Tcs) -> None:
    tcs.move_to(JOINTS_A)
    tcs.ok("gripper 1")
    tcs.expect("IsFullyClosed", "0 0")
    tcs.expect("GraspPlate 80 50 10", "0 0")
    tcs.expect("IsFullyClosed", "0 -1")
    tcs.ok("gripper 1")


@case("SetActiveGripper", PA, "SSGRIP", "a dual gripper", "gripper 1 accepted (0), gripper 2 refused -2852",
      NOT_SIMULATED, "it needs a dual gripper, which no simulated PF400 has; on the single gripper TCS "
      "accepts gripper 1 and refuses 2")
def _set_active_gripper(tcs: Tcs) -> str:
    tcs.ensure()
    tcs.ok("SetActiveGripper 1")
    tcs.expect("SetActiveGripper 1 2", "-2800 *Warning Parameter Mismatch*")
    return tcs.expect("SetActiveGripper 2", "-2852 *Invalid robot state to execute command*")


@case("GetActiveGripper", PA, "SSGRIP", "nothing", "1 on a single gripper; -2800")
def _get_active_gripper(tcs: Tcs) -> None:
    tcs.expect("GetActiveGripper", "0 1")
    tcs.expect("GetActiveGripper 2", "-2800 *Warning Parameter Mismatch*")


# ---- In the sources only

@case("Custom", SOURCES, "Custom.gpl", "nothing", "the template command: robot, name, global, arguments")
def _custom(tcs: Tcs) -> None:
    tcs.expect("custom 1 2.5", "0 1 custom 123 2 1 2.5")


@case("HeightDetect", SOURCES, "PARobot_auto_center_intf.gpl", "protected code", "replies -204",
      NOT_SIMULATED, "its work is done by the protected PARobot_auto_center.gpp, which nobody can read")
def _height_detect(tcs: Tcs) -> str:
    tcs.ensure()
    return tcs.expect("HeightDetect", "-204")


# ---- The PF400SXL: the same arm on a linear rail (axis 6)

@case("MoveRail", PA, "PARobot", "power; robot attached, homed; a rail",
      "the rail to a station's or a given position now; or with the next pick (-2853 when not there)", robot=SXL)
def _move_rail(tcs: Tcs) -> None:
    tcs.ensure()
    tcs.ok("Rail 1 250", "MoveRail 1 1", "waitForEom")
    assert tcs.joints()[5] == pytest.approx(250.0, abs=1e-6)
    tcs.ok("MoveRail 1 1 -100", "waitForEom")
    assert tcs.joints()[5] == pytest.approx(-100.0, abs=1e-6)
    tcs.move_to((*JOINTS_A[:4], 110.0, 50.0))
    tcs.ok("TeachPlate 3 40")
    tcs.expect("Rail 3", "0 3 50")
    tcs.ok("MoveRail 3 1 0", "waitForEom")
    tcs.expect("PickPlate 3", "-2853 *Rail not at correct station*")
    tcs.ok("MoveRail 3 2")  # move the rail with the next pick
    tcs.expect("PickPlate 3", "0 0")
    assert tcs.joints()[5] == pytest.approx(50.0, abs=1e-6)


@case("Rail", PA, "PARobot", "a rail", "a station's rail position read and set; -2820, -2801", robot=SXL)
def _rail(tcs: Tcs) -> None:
    tcs.expect("Rail 4", "0 4 0")
    tcs.ok("Rail 4 250")
    tcs.expect("Rail 4", "0 4 250")
    tcs.expect("Rail 0", "-2820 *Invalid station index*")
    tcs.expect("Rail", "-2801 *Warning No Parameters")


@case("moveExtraAxis", TCS, "Motion", "power; robot attached, homed; an extra axis (the PF400SXL's rail)",
      "the rail goes there during the next Cartesian move; -2802", robot=SXL)
def _move_extra_axis(tcs: Tcs) -> None:
    tcs.move_to((*JOINTS_A, 0.0))
    tcs.ok("moveExtraAxis 120", f"moveC 1 {nums(CART_C)} 1", "waitForEom")
    assert tcs.joints()[5] == pytest.approx(120.0, abs=1e-6)
    tcs.assert_pose(CART_C)
    tcs.expect("moveExtraAxis", "-2802 *Warning Illegal move command*")


# -- running them ---------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def elsewhere(request: Any) -> PrivateRun | None:
    """This module's outcomes from its own network namespace, or None: the cases run here."""
    corpus_dir()  # no corpus: skipped here, failed under CI=true, before any namespace is made
    return private_network_module(request)


@pytest.fixture(scope="module")
def tcs(request: Any, elsewhere: PrivateRun | None, tmp_path_factory: pytest.TempPathFactory
        ) -> Iterator[Tcs | PrivateRun]:
    """TCS 3.0C1-pa, unchanged, serving on a simulated ``request.param`` robot for the module."""
    if elsewhere is not None:
        yield elsewhere
        return
    model: str = request.param
    corpus = corpus_dir()
    root = tmp_path_factory.getbasetemp() / "tcs-commands"
    project = root / "tcs-3.0C1-pa"
    if not project.exists():  # one copy (and one translation, cached) for both robots
        copy_project(corpus / "tcs-3.0C1-pa", project)
    flash = root / f"controller-{model}"
    (flash / "flash" / "data").mkdir(parents=True, exist_ok=True)
    shutil.copy(corpus / "docs" / TAUGHT, flash / "flash" / "data" / "taught.gpo")
    saved = (get_console_sink(), kinematics_provider._provider, dict(refframe._conveyors))
    try:
        cell = Cell.load(project, robot=model, clock="fast", echo=False, cache_dir=root / "cache", flash=flash)
        with cell.serve(ports=[ROBOT_PORT, STATUS_PORT], timeout=60.0) as serving:
            session = Tcs(cell, model, flash)
            try:
                yield session
            finally:
                session.close()
            assert serving.running, cell.log  # TCS serves on: it never ends by itself
        assert "unhandled" not in cell.log, cell.log
    finally:
        set_console_sink(saved[0])
        kinematics_provider._provider = saved[1]
        refframe._conveyors.clear()
        refframe._conveyors.update(saved[2])


@pytest.mark.parametrize(
    ("tcs", "case"),
    [pytest.param(c.robot, c, id=c.id, marks=[pytest.mark.xfail(strict=True, reason=f"bug: {c.bug}")] if c.bug else [])
     for c in CASES],
    indirect=["tcs"], scope="module")  # (the default for a direct argument, function, would make one TCS per case)
def test_command(tcs: Tcs | PrivateRun, case: Case, request: Any) -> None:
    if isinstance(tcs, PrivateRun):
        tcs.reproduce(request)
        return
    try:
        reply = case.body(tcs)
    except BaseException:
        RESULTS[case.id] = ("fails", case.bug or "the case fails")
        raise
    assert (reply is None) == (case.verdict == WORKS), reply
    RESULTS[case.id] = (case.verdict, reply or "")


def test_every_command_of_tcs_has_one_case() -> None:
    """The cases are exactly TCS's commands: every ``Cmd_<name>`` handler of the project (TCS
    dispatches on ``New CommandDelegate("Cmd_" & name)``, Class_command.gpl), one case each; the
    standard ones (Cmd.gpl, Load_save.gpl) from the User's Guide, PARobot.gpl's from the plug-in's."""
    project = corpus_dir() / "tcs-3.0C1-pa"
    handlers: dict[str, str] = {}
    for source in sorted(project.glob("*.gpl")):
        text = source.read_text(encoding="latin-1")
        for match in re.finditer(r"^[ \t]*Public Sub Cmd_(\w+)\s*\(", text, re.MULTILINE | re.IGNORECASE):
            handlers[match.group(1).lower()] = source.name
    guide_of = {"Cmd.gpl": TCS, "Load_save.gpl": TCS, "PARobot.gpl": PA}
    cases = {c.command.lower(): c for c in CASES}
    assert len(cases) == len(CASES), "one case per command"
    assert sorted(cases) == sorted(handlers)
    assert {name: c.guide for name, c in cases.items()} == \
        {name: guide_of.get(source, SOURCES) for name, source in handlers.items()}
    assert sum(c.guide == TCS for c in CASES) == 57  # the User's Guide's tables, with LoadFile/StoreFile
    assert sum(c.guide == PA for c in CASES) == 25  # 19 PARobot and 6 SSGRIP commands


def test_the_command_table_is_current(elsewhere: PrivateRun | None, request: Any) -> None:
    """docs/tcs-commands.md is this run's table (``GPL2PY_WRITE_TCS_TABLE=1`` writes it)."""
    if elsewhere is not None:
        elsewhere.reproduce(request)
        return
    missing = [c.id for c in CASES if c.id not in RESULTS]
    if missing:
        pytest.skip(f"the table needs every case of this module in the same run; not run: {', '.join(missing[:5])}")
    table = render_table()
    if os.environ.get(WRITE_TABLE) == "1":
        TABLE.write_text(table, encoding="utf-8")
        return
    assert TABLE.read_text(encoding="utf-8") == table, (
        f"{TABLE.relative_to(REPO)} differs from this run's results: run "
        f"{WRITE_TABLE}=1 bash scripts/test.sh {Path(__file__).relative_to(REPO)} and review the diff")


# -- the table -----------------------------------------------------------------------------------------


SECTIONS = ("General", "Location", "Profile", "Motion", "Vision", "Load-Save", "PARobot", "SSGRIP")
DOES_NOT_WORK = "does not work yet"


def result_text(c: Case) -> tuple[str, str]:
    """(category, text) of a case's result for the table."""
    verdict, detail = RESULTS[c.id]
    if verdict == "fails":
        return DOES_NOT_WORK, f"**{DOES_NOT_WORK}**: gpl2py bug: {detail}"
    if verdict == WORKS:
        return WORKS, WORKS
    reply = error(int(detail)) if re.fullmatch(r"-\d+", detail) else detail
    if verdict == REFUSED:
        return REFUSED, f"refused, `{reply}`: {c.why}"
    return NOT_SIMULATED, f"not simulated: {c.why}: `{reply}`"


def render_table() -> str:
    categories = (WORKS, REFUSED, NOT_SIMULATED, DOES_NOT_WORK)
    out = [
        "# TCS 3.0C1 commands on the simulated PF400",
        "",
        "<!-- Generated by tests/e2e_io/test_tcs_commands.py from its cases and their results; do not edit:",
        f"     {WRITE_TABLE}=1 bash scripts/test.sh tests/e2e_io/test_tcs_commands.py writes it. -->",
        "",
        "The vendor's TCP Command Server 3.0C1 with the PARobot plug-in (`tcs-3.0C1-pa` of the shared",
        "corpus), unchanged, served by gpl2py on a simulated PF400SX (the rail's commands on a PF400SXL,",
        "the same arm on a linear rail) and driven through a plain TCP socket, one test case per",
        "command. Each case sets up the state the command needs with TCS's own commands, asserts the",
        "exact replies in the guide's PC-mode format, checks the numbers that report robot state",
        "against the simulated robot (its joints, and its pose worked out by hand from the PF400's",
        "links) and, for a command that moves the robot, the pose it ends at. Where the controller",
        "refuses a command in some state, the case sends it in that state too and checks the code.",
        "",
        "* **works**: the command does what the guide says on the simulated robot.",
        "* **refused**: the controller refuses it on a PF400 without vision, with the code shown.",
        "* **not simulated**: it needs hardware the simulated robots do not have; the case checks the",
        "  reply TCS gives when that hardware is missing.",
        f"* **{DOES_NOT_WORK}**: a bug found elsewhere in gpl2py stops it (the case is a strict",
        "  expected failure naming the bug).",
        "",
        "| Guide | Commands | " + " | ".join(c[0].upper() + c[1:] for c in categories) + " |",
        "|---|---|" + "---|" * len(categories),
    ]
    works = []
    for guide in (TCS, PA):
        cases = [c for c in CASES if c.guide == guide]
        counts = [sum(result_text(c)[0] == cat for c in cases) for cat in categories]
        out.append(f"| {GUIDES[guide]} | {len(cases)} | " + " | ".join(map(str, counts)) + " |")
        works.append(f"{counts[0]} of the {len(cases)} {'standard' if guide == TCS else 'PARobot'} commands")
    out += ["", f"{works[0].capitalize()} work, and {works[1]}."]
    for guide in (TCS, PA, SOURCES):
        out += ["", f"## {GUIDES[guide]}", "",
                "| Command | Section | Needs | Result | What the case checks |",
                "|---|---|---|---|---|"]
        cases = [c for c in CASES if c.guide == guide]
        order = {name: i for i, name in enumerate(SECTIONS)}
        for c in sorted(cases, key=lambda c: (order.get(c.section, len(order)), c.command.lower())):
            robot = "" if c.robot == SX else f" (on the {c.robot})"
            cell = result_text(c)[1].replace("|", "\\|")
            out.append(f"| `{c.command}` | {c.section} | {c.needs} | {cell} | {c.checks}{robot} |")
    out += ["", "## DataIDs", "",
            "Every DataID that PyLabRobot's newest PreciseFlex driver reads (as issue 20 lists them;",
            "the pinned 0.2.2 reads none by number), that the TCS guide names, and that TCS itself",
            "reads or writes, as `pd <DataID>` replies on the PF400SX (the robot's own DataIDs for",
            "robot 1, the one TCS's robot port serves). The `pd` case checks each reply: a stored value against the",
            "PF400SX's own `.pac` file (`runtime/gplrt/data/robots/pf400sx`, a real controller's",
            "backup), a live one against the simulated controller's state (`gplrt/controller/live_pdb.py`",
            "says what each one follows). *Simulated* marks a value a physical controller takes from",
            "its hardware. Several values are separated by commas (`pd 2700` replies",
            "`0 500,360,720,720,400`).",
            "",
            "| DataID | Meaning | `pd` replies | Value | Read by | Tests |",
            "|---|---|---|---|---|---|"]
    for d in sorted(DATA_IDS, key=lambda d: d.number):
        tests = re.sub(r"(test_\w+\.py::\w+)", r"`\1`", "; ".join(filter(None, ["`pd`", d.tests])))
        out.append(f"| {d.number} | {d.meaning} | {d.reply} | {d.value} | {', '.join(d.readers)} | {tests} |")
    return "\n".join(out) + "\n"

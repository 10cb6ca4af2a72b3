"""tests/realworld/tcs_like: a vendor-style (TCS-like) GPL project, transpiled and served end to end.

The project is written the way Precise Automation's Tcp Command Server is: a Global module of
constants and shared tables, Public Classes inside modules, a location table read from /flash, a
profile table, gripper I/O with timeouts, one thread per TCP client and "<code> <message>" replies.
It is transpiled with the ``gpl2py`` command (zero diagnostics), run on the real clock sped up 10x,
and driven by Python socket clients through one scripted session.  Every reply is asserted, and so
is the pose the simulated robot ends in (read off the robot itself, not from the program's replies).
"""

from __future__ import annotations

import threading
import time
from pathlib import Path

import numpy as np
import pytest

from gpltest import LineClient, Transpiled, copy_project, free_port, shutdown_server, transpile, wait_for_console
from gplrt.sim import Simulation

HERE = Path(__file__).resolve().parent
TIMEOUT = 15.0
CRLF = "\r\n"

LOCATIONS = CRLF.join([
    "; Tcs_Like location table, written by the teach pendant",
    "' index, name, type, values",
    "1, safe, J, 300, 10, 170, 0, 100",
    "2,nest1,C,350,100,150,0,90,180",
    "  3 , nest2 , c , 350 , -100 , 160 , 90 , 90 , 180  ",
    "",
    "4, park, J, 250, -30, 200, 10, 80",
    "5, broken, X, 1, 2, 3, 4, 5",          # unknown type: loading stops here with an error
    "6, never, J, 1, 2, 3, 4, 5",
]) + CRLF


class Cell:
    """The simulated cell around the server: gripper valves wired to their sensors, with a jam switch."""

    def __init__(self, tmp: Path) -> None:
        self.port = free_port()
        src = copy_project(HERE / "tcs_like", tmp / "src" / "tcs_like",
                           {"g_port As Integer = DEFAULT_PORT": f"g_port As Integer = {self.port}"})
        self.flash = tmp / "disk"
        (self.flash / "flash" / "projects" / "Tcs_Like").mkdir(parents=True)
        (self.flash / "flash" / "projects" / "Tcs_Like" / "Locations.txt").write_bytes(LOCATIONS.encode())
        self.built: Transpiled = transpile(src, tmp / "out")
        self.sim = Simulation(clock="real", speed=10.0, capture=True, flash_root=self.flash)
        self.jammed = False
        io = self.sim.io
        io.when_output(1, True).call(lambda: self._sensor(10001, True), after=0.1).set_input(10002, False)
        io.when_output(1, False).set_input(10001, False)
        io.when_output(2, True).call(lambda: self._sensor(10002, True), after=0.1).set_input(10001, False)
        io.when_output(2, False).set_input(10002, False)
        self.runner = threading.Thread(target=self._run, daemon=True)
        self.status: int | None = None

    def _sensor(self, signal: int, value: bool) -> None:
        if not self.jammed:
            self.sim.io.set_input(signal, value)

    def _run(self) -> None:
        self.status = self.built.package.main(self.sim)

    def start(self) -> None:
        self.runner.start()
        wait_for_console(self.sim, self.runner, "TCS listening", TIMEOUT)

    def joints(self) -> np.ndarray:
        robot = self.sim.robots[1]
        return np.asarray(robot.joints_at(self.sim.now()))

    def tool(self) -> np.ndarray:
        robot = self.sim.robots[1]
        return robot.forward(robot.joints_at(self.sim.now()))


@pytest.fixture(scope="module")
def cell(tmp_path_factory: pytest.TempPathFactory):
    c = Cell(tmp_path_factory.mktemp("tcs_like"))
    c.start()
    yield c
    shutdown_server(c.port, c.runner, TIMEOUT)


def test_project_is_vendor_sized_and_transpiles_clean(cell: Cell) -> None:
    sources = sorted((HERE / "tcs_like").glob("*.gpl"))
    assert len(sources) >= 8
    assert sum(len(p.read_text().splitlines()) for p in sources) >= 1500
    assert (HERE / "tcs_like" / "Project.gpr").read_bytes().count(b"\r\n") >= 10
    cell.built.assert_clean()


def expect_error_count(replies: list[str]) -> int:
    """Replies built by StrUtil.ErrorReply: every error but the unknown-command one."""
    return sum(1 for r in replies if r.startswith("-") and not r.startswith("-1 "))


def test_scripted_session(cell: Cell) -> None:
    sim = cell.sim
    out = sim.console.output.splitlines()
    assert out[:3] == ["Tcs_Like 2.1.3 starting", "robot 1: 5 axes, model 400",
                       "/flash/projects/Tcs_Like/Locations.txt:8: *Project generated error*: 1"]
    assert out[3:6] == ["4 locations loaded, 1 errors", "2 stations", "self test passed"]

    a = LineClient(cell.port)
    sent: list[tuple[str, str]] = []

    def check(cmd: str, want: str) -> None:
        got = a.ask(cmd)
        sent.append((cmd, got))
        assert got == want, f"{cmd!r}: {got!r} != {want!r}"

    # --- general commands, bad commands -------------------------------------------------------
    check("version", "0 Tcs_Like 2.1.3")
    check("nop", "0 OK")
    check("  NOP ", "0 OK")
    check("", "0")
    check("nop extra", "-786 *Invalid argument*")
    check("frobnicate 1 2", "-1 Unknown command frobnicate")
    check("echo hello \t  world", "0 hello world")
    check("mode", "0 0")
    check("mode 1", "0 1")
    check("Mode 0", "0 0")
    # --- power and homing ---------------------------------------------------------------------
    check("hp", "0 0")
    check("home", "-1046 *Power not enabled*")
    check("movej 1 300 0 180 0 100", "-1046 *Power not enabled*")
    check("hp 1", "0 OK")
    check("hp", "0 1")
    check("movej 1 300 0 180 0 100", "-1021 *Robot not homed*")
    check("home", "0 OK")
    check("status", "0 &H5")
    # --- parameter database ---------------------------------------------------------------------
    check("pd 2000", "0 5")
    check("pd 2007 1", "0 400")
    check("pd 16077 1 1 3", "0 348")
    check("pd 16078 1 1 2", "0 -93")
    # --- joint moves, out of range, bad arguments ---------------------------------------------
    check("movej 1 300 0 180 0 100", "0 OK")
    check("wherej", "0 300.000 0.000 180.000 0.000 100.000")
    assert np.max(np.abs(cell.joints() - [300, 0, 180, 0, 100])) < 1e-9
    check("movej 1 300 0 400 0 100", "-1012 *Joint out-of-range*")
    check("wherej", "0 300.000 0.000 180.000 0.000 100.000")
    check("movej 1 300 0 180", "-786 *Invalid argument*")
    check("movej 1 300 abc 180 0 100", "-786 *Invalid argument*")
    check("movej 1 300 1e 180 0 100", "-786 *Invalid argument*")
    check("movej 9 300 0 180 0 100", "-786 *Index out of range*")
    check("movej 1.5 300 0 180 0 100", "-786 *Invalid argument*")
    # --- the location table -------------------------------------------------------------------
    check("loc 1", "0 1 safe J 300.000 10.000 170.000 0.000 100.000")
    check("loc NEST1", "0 2 nest1 C 350.000 100.000 150.000 0.000 90.000 180.000")
    check("loc 3", "0 3 nest2 C 350.000 -100.000 160.000 90.000 90.000 180.000")
    check("loc 6", "0 6 loc6 undefined")
    check("loc 21", "-786 *Index out of range*")
    check("loc 0", "-786 *Index out of range*")
    check("loc nowhere", "-786 *Location undefined*")
    check("locs", "0 4 of 20")
    check("move safe 1", "0 OK")
    check("move 6 1", "-786 *Location undefined*")
    check("move nest1 1", "0 OK")
    check("where", "0 350.000 100.000 150.000 0.000 90.000 180.000")
    assert np.max(np.abs(cell.tool()[:3, 3] - [350, 100, 150])) < 1e-6
    check("locxyz 7 2000 0 200 0 90 180", "0 7 loc7 C 2000.000 0.000 200.000 0.000 90.000 180.000")
    check("move 7 1", "-1040 *Position too far*")
    check("locangles 8 250 -120 180 0 100", "0 8 loc8 J 250.000 -120.000 180.000 0.000 100.000")
    check("move 8 1", "-1012 *Joint out-of-range*")
    check("locname 8 far_left", "0 OK")
    check("loc far_left", "0 8 far_left J 250.000 -120.000 180.000 0.000 100.000")
    check("where", "0 350.000 100.000 150.000 0.000 90.000 180.000")
    # --- profiles and system speed --------------------------------------------------------------
    check("profile 1", "0 1 80 0 100 100 0.10 0.10 0 False")
    check("profile 2", "0 2 20 0 100 100 0.10 0.10 0 True")
    check("profile 4 60 0 90 90 0.2 0.2 10 1", "0 4 60 0 90 90 0.20 0.20 10 True")
    check("profile 4 0 0 90 90 0.2 0.2 10 1", "-786 *Invalid argument*")
    check("profile 4 60 0 90 90 0.2 0.2 10 maybe", "-786 *Invalid argument*")
    check("profile 9", "-786 *Index out of range*")
    check("sysspeed", "0 100")
    check("sysspeed 50", "0 50")
    check("sysspeed 101", "-786 *Invalid argument*")
    check("sysspeed", "0 50")
    # --- gripper and I/O ------------------------------------------------------------------------
    check("gripper", "0 open")
    check("gripper close", "0 closed")
    assert sim.io.read_dio(1) and not sim.io.read_dio(2) and sim.io.read_dio(10001)
    check("status", "0 &H15")
    check("gripper open", "0 open")
    check("gripper squeeze", "-786 *Invalid argument*")
    check("dio 5 1", "0 1")
    assert sim.io.read_dio(5)
    check("dio 5", "0 1")
    check("dio 5 0", "0 0")
    assert not sim.io.read_dio(5)
    cell.jammed = True
    check("gripper close", "-786 *Gripper timeout*")
    assert not sim.io.read_dio(1) and not sim.io.read_dio(2)  # both valves off after the timeout
    cell.jammed = False
    check("gripper open", "0 open")
    # --- stations: pick and place -------------------------------------------------------------
    check("station 1", "0 1 nest1 loc=2 clear=60.0 prof=2 full visits=0")
    check("station 2", "0 2 nest2 loc=3 clear=60.0 prof=2 empty visits=0")
    check("station 3", "-786 *Index out of range*")
    check("pick 1", "0 1 nest1 loc=2 clear=60.0 prof=2 empty visits=1")
    assert sim.io.read_dio(1)  # holding the plate
    check("pick 1", "-786 *Location undefined*")
    check("place 2", "0 2 nest2 loc=3 clear=60.0 prof=2 full visits=1")
    assert not sim.io.read_dio(1) and sim.io.read_dio(2)
    check("where", "0 350.000 -100.000 220.000 90.000 90.000 180.000")
    check("moveup -30", "0 OK")
    check("where", "0 350.000 -100.000 190.000 90.000 90.000 180.000")
    check("moveup 10 9", "-786 *Index out of range*")
    # --- teaching, saving the table to /flash and loading it back ---------------------------
    check("here 9 teach1", "0 9 teach1 C 350.000 -100.000 190.000 90.000 90.000 180.000")
    joints = " ".join(f"{v:.3f}" for v in cell.joints())
    check("herej 10", f"0 10 loc10 J {joints}")
    check("here 0", "-786 *Index out of range*")
    check("savelocs", "0 8")
    table = cell.flash / "flash" / "projects" / "Tcs_Like" / "Locations.txt"
    saved = table.read_text().splitlines()
    assert saved[0] == "; Tcs_Like 2.1.3 location table"
    assert "9, teach1, C, 350.000, -100.000, 190.000, 90.000, 90.000, 180.000" in saved
    assert f"10, loc10, J, {joints.replace(' ', ', ')}" in saved
    assert len(saved) == 2 + 8 and not table.with_name("Locations.txt.tmp").exists()
    check("locname 2 renamed", "0 OK")
    check("locxyz 3 1 2 3 4 5 6", "0 3 nest2 C 1.000 2.000 3.000 4.000 5.000 6.000")
    check("reloadlocs", "0 8")
    check("loc 2", "0 2 nest1 C 350.000 100.000 150.000 0.000 90.000 180.000")
    check("loc 3", "0 3 nest2 C 350.000 -100.000 160.000 90.000 90.000 180.000")
    check("loc teach1", "0 9 teach1 C 350.000 -100.000 190.000 90.000 90.000 180.000")
    assert a.ask("help").startswith("0 nop version hp attach home mode where wherej movej")
    # --- the interlock across clients -------------------------------------------------------
    check("lock", "0 OK")
    b = LineClient(cell.port)
    try:
        assert b.ask("status") == "0 &H105"
        assert b.ask("place 1") == "-786 *Interlock busy*"   # waited 1 s for the lock
        assert b.ask("lock") == "-786 *Interlock busy*"
    finally:
        b.close()
    check("unlock", "0 OK")
    check("unlock", "-786 *Interlock busy*")
    check("sysspeed 100", "0 100")

    # --- a disconnect in the middle of a command: the command still completes -----------------
    c = LineClient(cell.port)
    c.sock.sendall(b"movej 1 320 25 170 15 90\r\n")
    c.close()
    target = np.array([320, 25, 170, 15, 90])
    deadline = time.monotonic() + TIMEOUT
    while np.max(np.abs(cell.joints() - target)) > 1e-9 and time.monotonic() < deadline:
        time.sleep(0.02)
    check("wherej", "0 320.000 25.000 170.000 15.000 90.000")
    # ... and half a line, then a disconnect: nothing runs
    d = LineClient(cell.port)
    d.sock.sendall(b"movej 1 300 0 180 0 1")
    d.close()
    time.sleep(0.3)
    check("wherej", "0 320.000 25.000 170.000 15.000 90.000")

    # --- too many clients -----------------------------------------------------------------------
    extra = [LineClient(cell.port) for _ in range(3)]   # with `a`, MAX_CLIENTS = 4 are connected
    try:
        for k in extra:
            assert k.ask("nop") == "0 OK"
        late = LineClient(cell.port)
        assert late.line() == "-1 *Too many clients*"
        assert late.sock.recv(16) == b""
        late.close()
    finally:
        for k in extra:
            k.close()

    # --- counters, then leave --------------------------------------------------------------
    replies = [r for _, r in sent]
    cmds = [cmd for cmd, _ in sent if cmd.strip()]
    # executed: the self test's 3, this session's non-empty lines, client b's 3, the dropped
    # movej, the extras' nops; parsed: those and the empty line; error replies built by
    # ErrorReply: the self test's one, this session's, client b's two
    executed = 3 + len(cmds) + 1 + 3 + 1 + 3   # (+1: help)
    errors = 1 + expect_error_count(replies) + 2
    assert a.ask("count") == f"0 {executed + 1} {executed + 2} {errors}"
    a.sock.sendall(b"quit\r\n")
    assert a.line() == "0 bye"
    assert a.sock.recv(16) == b""
    a.close()
    assert len(sent) >= 50

    z = LineClient(cell.port)
    assert z.ask("shutdown") == "0 OK"
    z.close()
    cell.runner.join(TIMEOUT)
    assert not cell.runner.is_alive()
    assert cell.status == 0
    last = sim.console.output.splitlines()[-1]
    assert last == f"TCS stopped after 8 connections, {executed + 3} commands"
    assert np.max(np.abs(cell.joints() - target)) < 1e-9
    T = cell.tool()
    assert np.all(np.isfinite(T))
    assert sim.controller.error_log == []

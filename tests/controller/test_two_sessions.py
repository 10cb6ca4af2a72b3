"""Two sessions in one process stay fully independent (issue 14, item 1).

Two Simulations with different robots, clocks, flash folders and listen addresses run their
programs at the same time, each on its own Python thread.  The programs meet at two rendezvous
(each waits, as on the outside world, for the other to have done its part), so everything one has
done by then is in place while the other looks: power, homing and the robot's state, PDb writes,
signals, files, sockets, console, procedure registry and trace of one never show in the other.
"""

from __future__ import annotations

import threading
from pathlib import Path
from typing import Any

from gplrt.controller.services import Controller
from gplrt.controller.signals import Signal
from gplrt.geometry.location import Location
from gplrt.io.files import File, StreamWriter
from gplrt.io.sockets import IPEndPoint, TcpListener, network_config
from gplrt.lang.console import Console
from gplrt.lang.procedures import register_procedure, use_procedures
from gplrt.motion.move import Move
from gplrt.motion.profile import Profile
from gplrt.motion.robot_class import Robot
from gplrt.session import current_session
from gplrt.sim import Simulation
from gplrt.threads import Thread
from gplrt.threads.scheduler import external_wait

RENDEZVOUS = 60.0  # real seconds a program waits for the other at most (a hang fails, never a pass)


def _wait(event: threading.Event) -> None:
    with external_wait():  # a wait on the outside world: the session's scheduler lets time be
        assert event.wait(RENDEZVOUS), "the other session never got there"


def _ran(package: str, seen: list[tuple[str, str]]) -> None:
    """Register ``Main.Worker`` of ``package``: it records which project's worker ran, and in
    which session."""
    def worker() -> None:
        seen.append((current_session().project, package))

    register_procedure("Main", "Worker", worker, package=package)


def test_two_sessions_running_at_once_share_nothing(tmp_path: Path) -> None:
    a = Simulation(clock="virtual", robot="PF400SX", flash_root=tmp_path / "a", capture=True, project="CellA")
    b = Simulation(clock="real", speed=20.0, robot="ARM6", flash_root=tmp_path / "b", capture=True,
                   project="CellB", listen="0.0.0.0")
    workers: list[tuple[str, str]] = []
    _ran("two_sessions_a", workers)
    _ran("two_sessions_b", workers)
    use_procedures(a, "two_sessions_a")
    use_procedures(b, "two_sessions_b")
    a_done, b_done = threading.Event(), threading.Event()
    seen_by_a: dict[str, Any] = {}
    seen_by_b: dict[str, Any] = {}

    def program_a() -> None:
        seen_by_a["session"] = current_session()
        Console.WriteLine("hello from A")
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home()
        Move.Loc(Location.from_angles([300.0, 20.0, 170.0, 30.0, 80.0]), Profile())
        Move.WaitForEOM()
        Signal.set_DIO(1, True)
        Controller.set_PDbNum(2704, 1, 40.0)
        w = StreamWriter("/flash/a.txt")
        w.WriteLine("A")
        w.Close()
        listener = TcpListener(IPEndPoint("", 0))
        listener.Start()
        seen_by_a["listen"] = network_config().listen
        seen_by_a["ports"] = current_session().network.listening_ports()
        Thread("Main.Worker").Start()
        a_done.set()
        _wait(b_done)  # B has done all of its part: none of it may show here
        seen_by_a["power after B"] = Controller.PowerState()
        seen_by_a["DIO 2"] = Signal.DIO(2)
        seen_by_a["2704"] = Controller.PDbNum(2704, 1)
        seen_by_a["files"] = sorted(File.GetFiles("/flash"))
        seen_by_a["ports after B"] = current_session().network.listening_ports()
        listener.Stop()

    def program_b() -> None:
        seen_by_b["session"] = current_session()
        _wait(a_done)  # A has powered, homed, moved, written, listened and started its worker
        seen_by_b["power"] = Controller.PowerEnabled
        seen_by_b["power state"] = Controller.PowerState()
        Robot.Attached = 1  # robot 1 of this controller is free: A's thread holds only A's
        seen_by_b["trajectory"] = Robot.TrajState()  # 0 halted: no power here
        seen_by_b["where"] = Robot.WhereAngles().axis_values()
        seen_by_b["DIO 1"] = Signal.DIO(1)
        seen_by_b["2704"] = Controller.PDbNum(2704, 1)
        seen_by_b["files"] = sorted(File.GetFiles("/flash"))
        seen_by_b["listen"] = network_config().listen
        seen_by_b["ports"] = current_session().network.listening_ports()
        Console.WriteLine("hello from B")
        Signal.set_DIO(2, True)
        Controller.set_PDbNum(2704, 1, 30.0)
        w = StreamWriter("/flash/b.txt")
        w.WriteLine("B")
        w.Close()
        worker = Thread("Main.Worker")
        worker.Start()
        worker.Join()
        b_done.set()

    errors: list[BaseException] = []

    def run(sim: Simulation, program: Any) -> None:
        try:
            assert sim.run_main(program, timeout=2 * RENDEZVOUS) == []
        except BaseException as exc:  # reported by the test's own thread
            errors.append(exc)
            a_done.set()
            b_done.set()

    threads = [threading.Thread(target=run, args=(a, program_a)), threading.Thread(target=run, args=(b, program_b))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == []
    assert a.controller.error_log == [] and b.controller.error_log == [], (a.console.log_text, b.console.log_text)

    # Each program ran in its own session, on its own clock.
    assert seen_by_a["session"] is a and seen_by_b["session"] is b
    assert a.mode == "virtual" and b.mode == "real"

    # Power, homing, robot state: A's are on, homed and moved; B saw none of it.
    assert seen_by_b["power"] is False and seen_by_b["power state"] == 7
    assert seen_by_b["trajectory"] == 0 and seen_by_a["power after B"] == 21  # A's robot attached
    assert a.controller.power_state in (20, 21) and b.controller.power_state == 7
    assert a.robots[1].homed and not b.robots[1].homed
    assert a.robots[1].axis_count == 5 and b.robots[1].axis_count == 6
    assert list(seen_by_b["where"]) == [float(v) for v in b.robots[1].queue.rest]  # never moved
    assert a.robots[1].queue.final_joints().tolist() == [300.0, 20.0, 170.0, 30.0, 80.0]

    # PDb writes.
    assert seen_by_b["2704"] != 40.0 and seen_by_a["2704"] == 40.0
    assert a.database().get_num(2704, 1) == 40.0 and b.database().get_num(2704, 1) == 30.0
    assert a.robots[1].limits.max_speed_pct == 40.0 and b.robots[1].limits.max_speed_pct == 30.0

    # Signals.
    assert seen_by_b["DIO 1"] is False and seen_by_a["DIO 2"] is False
    assert [c.signal for c in a.io.output_trace()] == [1] and [c.signal for c in b.io.output_trace()] == [2]

    # Files: each session's disks are its own folder.
    assert seen_by_b["files"] == [] and seen_by_a["files"] == ["a.txt"]
    assert (tmp_path / "a" / "flash" / "a.txt").exists() and not (tmp_path / "a" / "flash" / "b.txt").exists()
    assert (tmp_path / "b" / "flash" / "b.txt").exists() and not (tmp_path / "b" / "flash" / "a.txt").exists()

    # Sockets: where servers may listen, and who listens.
    assert seen_by_a["listen"] == "127.0.0.1" and seen_by_b["listen"] == "0.0.0.0"
    assert len(seen_by_a["ports"]) == 1 and seen_by_a["ports"] == seen_by_a["ports after B"]
    assert seen_by_b["ports"] == set()

    # Console.
    assert a.console.output == "hello from A\n" and b.console.output == "hello from B\n"

    # Procedure registry: "Main.Worker" is each session's own project's.
    assert sorted(workers) == [("CellA", "two_sessions_a"), ("CellB", "two_sessions_b")]
    assert a.procedures is not b.procedures

    # Trace: A's robot moved, B's never did.
    trace_a, trace_b = a.trace(1), b.trace(1)
    assert trace_a.joints.shape[1] == 5 and len(trace_a.times) > 2
    assert trace_b.joints.shape[1] == 6 and len(trace_b.times) == 1
    a.close()
    b.close()

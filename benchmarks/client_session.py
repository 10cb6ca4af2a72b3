"""A client session against a GPL server on the fast clock: wall time against simulated motion time.

The server runs in this process as a notebook ``Cell`` (``Cell.serve``) on ``clock="fast"``;
the client makes MOVES moves, each waiting for the end of the motion, then the script prints
the wall time the moves took, the motion time the simulated robot ran for (the durations of
the segments queued meanwhile, read off robot 1) and their ratio.  Two servers:

* ``--server tcs`` (default): the vendor's TCP Command Server with the PARobot plug-in, from
  the corpus (``$GPL_CORPUS`` or ``../shared/corpus``), driven by PyLabRobot's
  ``PreciseFlex400Backend``: ``move_j`` then ``waitForEom`` per move (``--as-written`` uses
  ``get_joint_position`` instead, as samples/pylabrobot/arm_session.py does: it adds the 0.2 s
  PyLabRobot sleeps after every ``waitForEom``).  TCS listens on its fixed ports 10100 and
  10000; on a shared machine give it a network of its own:
  ``unshare --net sh -c 'ip link set lo up && python benchmarks/client_session.py'``.
* ``--server sample``: samples/tcp_command_server on a free port, with a plain line client
  ("move pick", "move place"), which needs no corpus.

    python benchmarks/client_session.py [--server tcs|sample] [--moves 50] [--speed 50] [--clock virtual] [--runs 5]

It prints the median wall time of ``--runs`` sessions and their spread (the machine is shared and
noisy; the motion time is the same in every run).

``--clock virtual`` runs the same session on the paced virtual clock, for comparison: there the
wall time is about the motion time.

It also prints the CPU time the process spent in the session (the server's threads and the
client share it).  After each session the reference workload R (``_reference``) runs (for a
quarter of the session's time, at least once), and the times and the factor are printed once more
normalised by R of the same turn: the times in R, the factor in seconds of simulated motion per R,
once for the wall clock and once for CPU time.
The CPU ones are the figures to compare between machines: load stretches the wall time of a
session of short requests less than R's (``WAITING``).
"""

from __future__ import annotations

import argparse
import asyncio
import os
import shutil
import socket
import statistics
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from _reference import HOW_TO_COMPARE, Reference, per_r, times_r

from gpl2py.notebook import Cell

#: Why the CPU figures are the ones to compare (docs/design/performance.md, "The reference workload R").
WAITING = ("A session is many short requests: its threads sleep and wake at each, and a loaded machine's "
           "scheduler favours a thread that wakes over one that has run for a while, as R has, so load "
           "stretches the session's wall time less than R's: of this benchmark, compare the CPU figures in R.")

REPO = Path(__file__).resolve().parents[1]
POSES = [(300.0, 10.0, 90.0, -100.0, 90.0), (250.0, -20.0, 110.0, -80.0, 90.0)]


def motion_time(cell: Cell, since: float) -> float:
    """Controller seconds robot 1 spent in the segments queued at or after ``since``."""
    return sum(seg.end - seg.t0 for seg in cell.sim.robots[1].queue.history if seg.t0 >= since)


@dataclass
class Session:
    """What one session took: ``wall`` and ``cpu`` seconds (the process's CPU time: the server's
    threads and the client, which share it) for ``motion`` seconds of simulated motion."""

    wall: float
    cpu: float
    motion: float


class _Stopwatch:
    """Wall-clock and CPU seconds since it was made."""

    def __init__(self) -> None:
        self.wall, self.cpu = time.perf_counter(), time.process_time()

    def session(self, motion: float) -> Session:
        return Session(time.perf_counter() - self.wall, time.process_time() - self.cpu, motion)


async def tcs_moves(cell: Cell, moves: int, speed: float, as_written: bool) -> Session:
    from pylabrobot.arms.precise_flex import PreciseFlex400Backend
    from pylabrobot.arms.precise_flex.joints import PFAxis

    arm = PreciseFlex400Backend("127.0.0.1", 10100)
    await arm.setup()
    await arm.set_speed(speed)
    since, watch = cell.time, _Stopwatch()
    for i in range(moves):
        await arm.move_j(1, dict(zip(PFAxis, POSES[i % 2])))
        if as_written:
            await arm.get_joint_position()
        else:
            await arm.send_command("waitForEom")
    done = watch.session(motion_time(cell, since))
    await arm.stop()
    return done


def run_tcs(moves: int, speed: float, as_written: bool, work: Path, clock: str) -> Session:
    corpus = Path(os.environ.get("GPL_CORPUS") or REPO.parent / "shared" / "corpus") / "tcs-3.0C1-pa"
    project = shutil.copytree(corpus, work / "tcs-3.0C1-pa")
    cell = Cell.load(project, robot="PF400SX", clock=clock, echo=False, cache_dir=work / "cache")
    with cell.serve(ports=[10100, 10000], timeout=120.0):
        return asyncio.run(tcs_moves(cell, moves, speed, as_written))


def run_sample(moves: int, speed: float, work: Path, clock: str) -> Session:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    project = shutil.copytree(REPO / "samples" / "tcp_command_server", work / "tcp_command_server")
    startup = project / "Startup.gpl"
    startup.write_text(startup.read_text().replace("SERVER_PORT As Integer = 10100",
                                                   f"SERVER_PORT As Integer = {port}"))
    cell = Cell.load(project, clock=clock, echo=False, cache_dir=work / "cache")
    with cell.serve(ports=[port], timeout=120.0), socket.create_connection(("127.0.0.1", port), timeout=60) as conn:
        lines = conn.makefile("r", encoding="latin-1", newline="\r\n")

        def ask(text: str) -> str:
            conn.sendall(text.encode() + b"\n")
            reply = lines.readline().strip()
            assert reply.startswith("0 "), (text, reply)
            return reply

        for request in ("power on", "home", f"speed {speed:g}"):
            ask(request)
        since, watch = cell.time, _Stopwatch()
        for i in range(moves):
            ask("move pick" if i % 2 == 0 else "move place")
        done = watch.session(motion_time(cell, since))
        ask("shutdown")
    return done


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--server", choices=("tcs", "sample"), default="tcs")
    parser.add_argument("--moves", type=int, default=50)
    parser.add_argument("--speed", type=float, default=50.0, help="profile speed in percent (default 50)")
    parser.add_argument("--clock", choices=("fast", "virtual"), default="fast",
                        help="virtual: the paced clock, for comparison (wall time ~ motion time)")
    parser.add_argument("--as-written", action="store_true",
                        help="tcs: wait with get_joint_position (PyLabRobot sleeps 0.2 s after each)")
    parser.add_argument("--runs", type=int, default=5, help="sessions to run (each a fresh server; default 5)")
    args = parser.parse_args()
    sessions: list[Session] = []
    ref = Reference()
    ref.run(record=False)
    for _ in range(args.runs):
        with tempfile.TemporaryDirectory() as tmp:
            if args.server == "tcs":
                sessions.append(run_tcs(args.moves, args.speed, args.as_written, Path(tmp), args.clock))
            else:
                sessions.append(run_sample(args.moves, args.speed, Path(tmp), args.clock))
        ref.run(match=sessions[-1].wall)
    motion = sessions[-1].motion
    walls, cpus = [s.wall for s in sessions], [s.cpu for s in sessions]
    median = statistics.median(walls)
    print(f"{args.server}, {args.clock} clock: {args.moves} moves at {args.speed:g} % speed, each waited for: "
          f"{motion:.1f} s of simulated motion; wall time over {args.runs} sessions: median {median:.3f} s "
          f"(spread {min(walls):.3f}-{max(walls):.3f} s): {motion / median:.1f}x faster than the robot "
          f"({motion / max(walls):.1f}-{motion / min(walls):.1f}x)")
    print(f"CPU time of the process (server and client): median {statistics.median(cpus):.3f} s "
          f"(spread {min(cpus):.3f}-{max(cpus):.3f} s)")
    print("normalised by R of the same turn:")
    for what, times, refs in (("wall", walls, ref.wall), ("CPU ", cpus, ref.cpu)):
        in_r = per_r(times, refs)
        per_ref = times_r([motion / t for t in times], refs)
        print(f"  {what} time {statistics.median(in_r):.2f} R (spread {min(in_r):.2f}-{max(in_r):.2f}): "
              f"{statistics.median(per_ref):.2f} s of simulated motion per R (spread "
              f"{min(per_ref):.2f}-{max(per_ref):.2f})")
    print(ref.line())
    print(HOW_TO_COMPARE)
    print(WAITING)

if __name__ == "__main__":
    main()

"""The Listen node: a TCP server on port 5890 that runs the TMscript clients send (manual §14,
L17642-L18305; spec §2.3).

Every ``$TMSCT,len,ID,SCRIPT`` is translated **at run time by the TMscript front end**
(``gpl2py.tmscript.pipeline.translate_packet``: the same lexer, parser, checks and lowering as
``gpl2py translate``) and run in arrival order by one executor; motion and I/O calls queue on the
robot and return, ``QueueTag(n, 1)`` waits.  The reply follows the run (L17813): ``OK``,
``OK;l;l`` naming lines with warnings, ``ERROR;l;l`` naming the bad lines of a script that does not
compile (sent at once, nothing run).  Variables declared by a packet live until the node is left
(L17838).  ``$TMSTA`` 00 and 01 are answered at once, 01 is also pushed when a tag completes, and
``ListenSend`` pushes 90-99.  The priority commands ``ScriptExit(0|1)`` and
``StopAndClearBuffer(0|1|2)`` act on receipt, ahead of the queue (L18127).  After ``ScriptExit()``
the node is left: a ``$TMSCT`` then draws ``CPERR F1``.

A run-time error in a script (a division by zero, an unreachable point) would stop a real robot's
project; the simulated node replies ``ERROR;<line>`` for that script and keeps serving, so a client
under test sees which line failed (docs/design/tmscript.md).
"""

from __future__ import annotations

import re
import sys
import threading
from collections import deque
from dataclasses import dataclass, field
from collections.abc import Callable
from types import TracebackType
from typing import Any

import gplrt.tm as tm
from gplrt.tm import context
from gplrt.tm.motion import Robot, start_thread
from gplrt.threads.scheduler import WaitQueue
from gplrt.tm.packets import encode
from gplrt.tm.server import Conn, Server
from gplrt.tm.slave import EthernetSlave
from gplrt.tm.values import TMError

PORT = 5890
_PRIORITY = re.compile(r"^\s*(ScriptExit|StopAndClearBuffer)\s*\(\s*(\d+)\s*\)\s*$")
_ID = re.compile(r"^[A-Za-z0-9]+$")


class ScriptAborted(Exception):
    """The running script was abandoned (``StopAndClearBuffer(1|2)``, ``ScriptExit(0|1)``)."""


class _Exit(Exception):
    """``ScriptExit()`` ran: the rest of the packet is not executed (L17690)."""


class Vars:
    """The node's variables (``v.name`` in a packet's Python)."""


@dataclass
class _Job:
    conn: Conn
    ident: str
    script: str
    pushes: list[bytes] = field(default_factory=list)  # tag pushes held until the reply is sent


#: The TMscript front end as the node calls it on each script: ``translate(script, known, name)``
#: -> a packet with ``errors``, ``warnings`` (diagnostics), ``python`` (the text defining
#: ``script(vars)``), ``declared`` and ``lines`` (Python line -> script line).  The runtime never
#: imports the transpiler (tests/controller/test_import_graph.py): whoever starts a node hands it
#: ``gpl2py.tmscript.pipeline.translate_packet`` (``gpl2py run --listen-node``,
#: ``gpl2py.tmscript.serve``), the same front end that translates script projects.
Translate = Callable[[str, dict[str, object], str], Any]


class ListenNode:
    """A Listen node on ``robot`` that translates each script with ``translate`` (:data:`Translate`);
    ``serve()`` opens the port (0: any free port, see ``port``).

    Its threads -- the accept loop, one per connection, the script executor -- are threads of
    the robot's scheduler (``robot.sim``), its sockets ``gplrt.io.sockets``' (``gplrt.tm.server``):
    the node runs on the same clock as the robot's motions (docs/design/tmscript.md).  ``lock``
    guards the node's state and is never held across a wait or a send (either may hand the
    scheduler's token to another thread); waits go through the scheduler (``changed``)."""

    def __init__(self, robot: Robot, translate: Translate, host: str = "127.0.0.1", port: int = PORT,
                 message: str = "Listen1") -> None:
        self.robot, self.host, self.message = robot, host, message
        self.translate = translate
        self.active = False
        self.vars = Vars()
        self.known: dict[str, object] = {}
        self.jobs: deque[_Job] = deque()
        self.lock = threading.RLock()
        self.sched = robot.sched
        self.changed = WaitQueue("tm-listen")
        self.abort = False
        self.running: _Job | None = None
        self.tag_owner: dict[int, Conn] = {}
        self.exited = threading.Event()
        self.result: str | None = None  # "pass" / "fail" once left
        self._owner: Conn | None = None
        robot.on_tag = self._tag_done
        robot.on_error = self._project_error
        self._server: Server | None = None
        self._requested_port = port
        self.port = port

    @property
    def conns(self) -> list[Conn]:
        return self._server.conns if self._server is not None else []

    def _notify(self) -> None:
        self.sched.notify_all(self.changed)
        self.robot._notify()  # (a script waiting on the robot notices an abort)

    # --- life -----------------------------------------------------------------------------------
    def serve(self, enter: bool = True) -> ListenNode:
        """Start listening (in the background); ``enter``: the flow is in the node now."""
        self._server = Server(self.robot.sim, self.host, self._requested_port, self._serve_conn, "tm-listen")
        self.port = self._server.port
        start_thread(self.sched, "tm-listen-executor", self._execute)
        self.robot.drive()
        if enter:
            self.enter()
        return self

    def enter(self) -> None:
        """The flow enters the node: greet every connected client (``$TMSCT,n,0,Listen1``, L17795)."""
        self.robot.restart()
        with self.lock:
            self.active = True
            self.result = None
            self.exited.clear()
        frame = encode("TMSCT", f"0,{self.message}".encode())
        with self.sched.adopted():
            for c in list(self.conns):
                c.send(frame)

    def close(self) -> None:
        if self._server is not None:
            self._server.close()
            self._server = None
            self.robot.undrive()

    def cancelled(self) -> bool:
        """Whether the running script must stop (checked by the library's waits)."""
        if self.abort:
            raise ScriptAborted
        return False

    def script_exit(self) -> None:
        raise _Exit

    def push(self, header: bytes, data: bytes) -> None:
        """Send a frame to every client (``ListenSend``)."""
        frame = encode(header, data)
        for c in list(self.conns):
            c.send(frame)

    def _tag_done(self, tag: int) -> None:
        """Push ``$TMSTA 01,NN,true`` to the connection that queued the tag -- after the reply of
        the script that queued it, as in the manual's exchanges (L18262-L18269): on the fast
        clock a motion can end before its script has been answered."""
        conn = self.tag_owner.get(tag)
        if conn is None:
            return
        frame = encode("TMSTA", f"01,{tag:02d},true".encode())
        with self.lock:
            job = self.running
            if job is not None and job.conn is conn:
                job.pushes.append(frame)
                return
            conn.queue(frame)  # (in order with a reply queued just before, see _execute)
        conn.flush()

    def _project_error(self, exc: TMError) -> None:
        """A motion stopped the project by error (``Robot._stop_by_error``): the flow leaves the
        node, the running script is stopped, the scripts waiting are not run (they are answered
        ``CPERR F1``, as every later one: no external script mode now, L18121)."""
        with self.lock:
            if not self.active:
                return
            if self.running is not None:
                self.abort = True
            dropped = list(self.jobs)
            self.jobs.clear()
        self._notify()
        for job in dropped:
            job.conn.send(encode("CPERR", b"F1"))
        self._leave("fail")

    # --- connections ----------------------------------------------------------------------------
    def _serve_conn(self, conn: Conn) -> None:
        for frame in conn.frames():
            if frame.error:
                conn.send(encode("CPERR", f"{frame.error:02X}".encode()))
            elif frame.header == b"TMSTA":
                self._status(conn, frame.data)
            elif frame.header == b"TMSCT":
                self._script(conn, frame.data)
            else:  # CPERR / TMSVR sent to the Listen port
                conn.send(encode("CPERR", b"03"))

    def _status(self, conn: Conn, data: bytes) -> None:
        text = data.decode("utf-8", "replace")
        parts = text.split(",")
        sub = parts[0]
        if sub == "00":  # (also "00," as some clients send it)
            reply = f"00,true,{self.message}" if self.active else "00,false,"
        elif sub == "01" and len(parts) >= 2 and parts[1].strip().isdigit():
            tag = int(parts[1])
            state = self.robot.tag_status(tag) if 1 <= tag <= 15 else None
            word = "none" if state is None else ("true" if state else "false")
            reply = f"01,{parts[1].strip()},{word}"
        else:
            conn.send(encode("CPERR", b"04"))
            return
        conn.send(encode("TMSTA", reply.encode()))

    def _script(self, conn: Conn, data: bytes) -> None:
        text = data.decode("utf-8", "replace")
        ident, comma, script = text.partition(",")
        if not comma or not _ID.match(ident):
            conn.send(encode("CPERR", b"04"))
            return
        if not self.active:
            conn.send(encode("CPERR", b"F1"))
            return
        prio = self._priority(script)
        if prio is not None:
            self._run_priority(conn, ident, *prio)
            return
        with self.lock:
            self.jobs.append(_Job(conn, ident, script))
        self._notify()

    @staticmethod
    def _priority(script: str) -> tuple[str, int] | None:
        """The one priority command a packet carries (ScriptExit before StopAndClearBuffer, the
        first of each, L18196), or None."""
        found = [(m.group(1), int(m.group(2))) for line in script.splitlines()
                 if (m := _PRIORITY.match(line)) is not None]
        exits = [f for f in found if f[0] == "ScriptExit" and f[1] in (0, 1)]
        stops = [f for f in found if f[0] == "StopAndClearBuffer" and f[1] in (0, 1, 2)]
        return exits[0] if exits else stops[0] if stops else None

    def _run_priority(self, conn: Conn, ident: str, name: str, mode: int) -> None:
        dropped: list[_Job] = []
        with self.lock:
            if name == "ScriptExit" or mode >= 1:
                if self.running is not None:
                    self.abort = True
                elif self.jobs:  # the current script has not started yet: it is the one abandoned
                    dropped.append(self.jobs.popleft())
            if name == "ScriptExit" or mode == 2:
                self.jobs.clear()
        self._notify()
        for job in dropped:
            job.conn.send(encode("TMSCT", f"{job.ident},OK".encode()))
        self.robot.stop_and_clear()
        self.sched.wait(self.changed, self.robot.clock.now() + 5.0,
                        until=lambda: self.running is None or not self.abort)
        if name == "ScriptExit":  # (left before the reply, as a queued ScriptExit())
            self._leave("pass" if mode == 1 else "fail")
        conn.send(encode("TMSCT", f"{ident},OK".encode()))

    def _leave(self, result: str) -> None:
        with self.lock:
            self.active = False
            self.result = result
            self.vars = Vars()
            self.known = {}
        self.exited.set()

    # --- the script executor --------------------------------------------------------------------
    def _execute(self) -> None:
        """The script executor, a thread of the robot's scheduler: one script at a time."""
        while True:
            self.sched.wait(self.changed, None, until=lambda: bool(self.jobs))
            with self.lock:
                if not self.jobs:
                    continue
                job = self.jobs.popleft()
                self.running = job
                self.abort = False
            try:
                reply, leave = self._run_job(job)
            except Exception:  # a fault of the simulator itself: the script fails, the node goes on
                reply, leave = "ERROR;1", False
            if leave:
                # The node is left once the queue is done, before the reply: the client's next
                # script, sent when it reads the reply, must find the node left (CPERR F1).
                self.robot.wait_idle()
                if self.robot.fault is None:  # (else the error has left the node already)
                    self._leave("pass")
            with self.lock:
                for frame in [encode("TMSCT", f"{job.ident},{reply}".encode()), *job.pushes]:
                    job.conn.queue(frame)
                job.pushes = []
                self.running = None
                self.abort = False
            job.conn.flush()
            self._notify()

    def _run_job(self, job: _Job) -> tuple[str, bool]:
        packet = self.translate(job.script, self.known, f"TMSCT {job.ident}")
        if packet.errors:
            lines = sorted({d.span.line for d in packet.errors if d.span is not None} or {1})
            return "ERROR;" + ";".join(map(str, lines)), False
        warn = sorted({d.span.line for d in packet.warnings if d.span is not None})
        ok = "OK" + "".join(f";{n}" for n in warn)
        filename = f"<TMSCT {job.ident}>"
        namespace: dict[str, object] = {"tm": tm}
        try:
            exec(compile(packet.python, filename, "exec"), namespace)  # noqa: S102 (the front end's own output)
        except SyntaxError:
            return "ERROR;1", False
        self.known.update(packet.declared)
        context.set_node(self)
        self._owner = job.conn
        try:
            namespace["script"](self.vars)  # type: ignore[operator]
        except _Exit:
            return ok, True
        except ScriptAborted as exc:
            if self.robot.fault is not None:  # stopped by the project's error, not by a command
                return f"ERROR;{_script_line(exc.__traceback__, filename, packet.lines)}", False
            return ok, False
        except (TMError, ArithmeticError, ValueError, TypeError, IndexError, KeyError, AttributeError) as exc:
            return f"ERROR;{_script_line(exc.__traceback__, filename, packet.lines)}", False
        return ok, False


def _script_line(tb: TracebackType | None, filename: str, lines: list[int]) -> int:
    """The script line of the innermost frame of the packet's code in a traceback."""
    found = 0
    while tb is not None:
        if tb.tb_frame.f_code.co_filename == filename and 0 < tb.tb_lineno <= len(lines):
            found = lines[tb.tb_lineno - 1] or found
        tb = tb.tb_next
    return found or 1


def serve(translate: Translate, robot: str = "TM5-900", host: str = "127.0.0.1", port: int = PORT,
          svr_port: int = 5891, speed: float = float("inf"),
          clock: str | None = None) -> tuple[ListenNode, EthernetSlave]:
    """A simulated TM robot in a Listen node (what ``gpl2py run --robot TM5-900 --listen-node``
    starts; a notebook calls ``gpl2py.tmscript.serve``, which gives the front end):
    ``(node, slave)``, serving in the background until ``node.close()`` and ``slave.close()``.
    Port 0 takes a free port (``node.port``); ``clock``/``speed`` as ``context.use_robot``."""
    r = context.use_robot(robot, speed, clock)
    node = ListenNode(r, translate, host, port).serve()
    slave = EthernetSlave(r, host, svr_port).serve()
    return node, slave


def main(translate: Translate, robot_name: str = "TM5-900", host: str = "127.0.0.1", port: int = PORT,
         svr_port: int = 5891, speed: float = float("inf"), clock: str | None = None) -> int:
    """``gpl2py run --robot TM5-900 --listen-node``: serve until interrupted."""
    robot = context.use_robot(robot_name, speed, clock)
    node = ListenNode(robot, translate, host, port).serve()
    context.set_node(node)
    slave = EthernetSlave(robot, host, svr_port).serve()
    print(f"{robot_name} Listen node on {host}:{node.port}, Ethernet Slave on {host}:{slave.port}", file=sys.stderr, flush=True)
    try:
        threading.Event().wait()
    except KeyboardInterrupt:
        pass
    finally:
        node.close()
        slave.close()
        robot.close()
    return 0

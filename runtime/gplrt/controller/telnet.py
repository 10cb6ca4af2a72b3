"""The controller's console over Telnet (``gpl2py run --console PORT``).

A controller serves its command console on the Telnet port; labs use it to load and start the
project they deployed by FTP.  This server reads one command a line and answers with what
:class:`gplrt.controller.commands.ConsoleCommands` returns, then the prompt ``GPL: ``.  A failed
command answers ``<code> *<message>*`` (``-745 *Project already exists*``), then the detail, if
any, on the next line.  ``exit`` (or ``quit``) closes the connection.

It speaks plain text over TCP, which a Telnet client, ``nc`` and a socket all understand: the
Telnet option negotiation a client may send (``IAC`` sequences) is read and dropped, and nothing
is negotiated back — the client stays in its default line mode, which is what a console wants.

Everything that arrives is untrusted (docs/security.md, "Console and FTP"): a line is at most
``MAX_LINE`` bytes (a longer one is answered -712 *Invalid syntax* and dropped up to its end),
at most ``MAX_CLIENTS`` connections are served at once (the next is told so and closed), and a
command can do nothing the console's commands cannot.  The server listens on loopback unless the
session's network was opened (``--listen``), like the program's own servers
(``gplrt.io.sockets``).
"""

from __future__ import annotations

import socket
import socketserver
import threading
from typing import TYPE_CHECKING

from gplrt.controller.commands import ConsoleCommands
from gplrt.lang.errors import INVALID_SYNTAX, TOO_MANY, GplException, error_text

if TYPE_CHECKING:
    from gplrt.controller.projects import ProjectTable

__all__ = ["MAX_CLIENTS", "MAX_LINE", "PROMPT", "ConsoleServer", "reply_lines"]

PROMPT = "GPL: "
MAX_LINE = 1024
MAX_CLIENTS = 8
_EXIT = {"exit", "quit", "logout"}
_IAC, _SB, _SE = 255, 250, 240


def reply_lines(commands: ConsoleCommands, line: str) -> list[str]:
    """The console's answer to ``line``: the command's output lines, or the error's."""
    try:
        out = commands.execute(line)
    except GplException as exc:
        lines = [f"{exc.ErrorCode} {exc.Message()}"]
        if exc.detail:
            lines.extend(str(exc.detail).splitlines())
        return lines
    return out.splitlines() if out else []


class _TelnetFilter:
    """Drops Telnet commands (``IAC ...``) from the byte stream, across reads."""

    def __init__(self) -> None:
        self._state = 0  # 0 data, 1 after IAC, 2 option byte, 3 in SB, 4 IAC in SB

    def feed(self, data: bytes) -> bytes:
        out = bytearray()
        for b in data:
            s = self._state
            if s == 0:
                if b == _IAC:
                    self._state = 1
                else:
                    out.append(b)
            elif s == 1:
                if b == _IAC:
                    out.append(b)  # IAC IAC: a data byte 255
                    self._state = 0
                elif b == _SB:
                    self._state = 3
                elif 251 <= b <= 254:  # WILL, WONT, DO, DONT: one option byte follows
                    self._state = 2
                else:
                    self._state = 0
            elif s == 2:
                self._state = 0
            elif s == 3:
                self._state = 4 if b == _IAC else 3
            else:
                self._state = 0 if b == _SE else 3
        return bytes(out)


class _Handler(socketserver.BaseRequestHandler):
    server: _Server

    def handle(self) -> None:
        sock: socket.socket = self.request
        if not self.server.admit():
            sock.sendall(f"{TOO_MANY} *{error_text(TOO_MANY)}*: at most {MAX_CLIENTS} console connections\r\n".encode())
            return
        try:
            self._session(sock)
        except OSError:
            pass  # the client went away
        finally:
            self.server.leave()

    def _session(self, sock: socket.socket) -> None:
        commands = ConsoleCommands(self.server.projects)
        telnet = _TelnetFilter()
        pending = bytearray()
        dropping = False  # inside a line that was too long
        sock.sendall(f"gplrt simulated controller console\r\n{PROMPT}".encode())
        while True:
            data = sock.recv(4096)
            if not data:
                return
            pending += telnet.feed(data)
            while True:
                end = pending.find(b"\n")
                if end < 0:
                    if len(pending) > MAX_LINE:
                        dropping = True
                        pending.clear()
                    break
                raw, pending = bytes(pending[:end]), pending[end + 1:]
                if dropping or len(raw) > MAX_LINE:
                    dropping = False
                    lines = [f"{INVALID_SYNTAX} *{error_text(INVALID_SYNTAX)}*", f"a command line is at most {MAX_LINE} bytes"]
                else:
                    line = raw.decode("latin-1").strip("\r\0 \t")
                    if line.lower() in _EXIT:
                        return
                    lines = reply_lines(commands, line)
                text = "".join(f"{line}\r\n" for line in lines) + PROMPT
                sock.sendall(text.encode("latin-1", errors="replace"))


class _Server(socketserver.ThreadingTCPServer):
    daemon_threads = True
    allow_reuse_address = True

    def __init__(self, address: tuple[str, int], projects: ProjectTable) -> None:
        self.projects = projects
        self._clients = 0
        self._lock = threading.Lock()
        super().__init__(address, _Handler)

    def admit(self) -> bool:
        with self._lock:
            if self._clients >= MAX_CLIENTS:
                return False
            self._clients += 1
            return True

    def leave(self) -> None:
        with self._lock:
            self._clients -= 1


class ConsoleServer:
    """The Telnet console of one session's project table, served from a background thread."""

    def __init__(self, projects: ProjectTable, port: int, host: str) -> None:
        self._server = _Server((host, port), projects)
        self._thread = threading.Thread(target=self._server.serve_forever, kwargs={"poll_interval": 0.2},
                                        name="gplrt-console", daemon=True)

    @property
    def address(self) -> tuple[str, int]:
        """Where it listens (the port the system chose for port 0)."""
        host, port = self._server.server_address[:2]
        return str(host), int(port)

    def start(self) -> ConsoleServer:
        self._thread.start()
        return self

    def close(self) -> None:
        """Stop listening (connections being served end with the process: daemon threads)."""
        self._server.shutdown()
        self._server.server_close()

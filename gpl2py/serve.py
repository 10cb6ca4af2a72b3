"""``gpl2py run --console [PORT] --ftp [PORT]``: the simulated controller's Telnet console and FTP.

With either option the run is a controller that stays on: the project given is started from the
project table like any project the console loads (``gplrt.controller.projects``), and the run
goes on after its threads end — a client may upload, load and start another project at any
time — until Ctrl-C (status 130, every GPL thread stopped first).  While the console or FTP is
open, virtual time keeps to real time (the outside world is involved, as with an open socket:
docs/design/clock.md), and a program that waits for something only a client can bring is not a
stall.  docs/design/console.md has the decisions.

Both listen on loopback unless ``--listen ADDRESS`` opens the network, on high ports by default
(23 and 21 need privileges); port 0 takes a free port, and the note printed on stderr says which:
``note: console (Telnet) listening on 127.0.0.1:2323``.
"""

from __future__ import annotations

import argparse
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, TextIO

__all__ = ["DEFAULT_CONSOLE_PORT", "DEFAULT_FTP_PORT", "Services", "add_options", "keep_running", "wanted"]

DEFAULT_CONSOLE_PORT = 2323
DEFAULT_FTP_PORT = 2121
#: Real seconds between two looks at a run that has no thread left (it goes on anyway).
_IDLE_POLL = 0.2


def _port(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a port number: {text!r}") from None
    if not 0 <= value <= 65535:
        raise argparse.ArgumentTypeError(f"a port is 0 to 65535 (0: any free port), not {value}")
    return value


def add_options(parser: argparse.ArgumentParser) -> None:
    """``--console [PORT]`` and ``--ftp [PORT]`` of ``gpl2py run``."""
    parser.add_argument("--console", metavar="PORT", type=_port, nargs="?", const=DEFAULT_CONSOLE_PORT, default=None,
                        help="serve the controller's command console over Telnet on PORT (default "
                        f"{DEFAULT_CONSOLE_PORT}; 0: any free port): Load, Compile, Start, Stop, Unload, "
                        "Show Thread, Dir ... The run then goes on until Ctrl-C")
    parser.add_argument("--ftp", metavar="PORT", type=_port, nargs="?", const=DEFAULT_FTP_PORT, default=None,
                        help=f"serve the controller's disks (/flash, /NVRAM ...) by FTP on PORT (default {DEFAULT_FTP_PORT}; "
                        "0: any free port; needs pyftpdlib: pip install 'gpl2py[ftp]'). The run then goes on until Ctrl-C")


def wanted(args: argparse.Namespace) -> bool:
    return getattr(args, "console", None) is not None or getattr(args, "ftp", None) is not None


@dataclass
class Services:
    """The console and FTP servers of one run, and the real-time pace they hold."""

    closers: list[Callable[[], None]] = field(default_factory=list)

    @classmethod
    def start(cls, sim: Any, args: argparse.Namespace, stderr: TextIO) -> Services:
        """Start what ``args`` asks for on ``sim``'s project table and disks; says where each
        listens on ``stderr``.  An OSError (the port is taken) stops the ones started already."""
        services = cls()
        try:
            if args.console is not None:
                from gplrt.controller.telnet import ConsoleServer

                console = ConsoleServer(sim.projects, args.console, sim.listen).start()
                services.closers.append(console.close)
                host, port = console.address
                stderr.write(f"note: console (Telnet) listening on {host}:{port}\n")
            if args.ftp is not None:
                from gplrt.io.ftp import FtpService

                ftp = FtpService(sim.files, args.ftp, sim.listen).start()
                services.closers.append(ftp.close)
                host, port = ftp.address
                stderr.write(f"note: FTP listening on {host}:{port} (the controller's disks)\n")
        except BaseException:
            services.close()
            raise
        stderr.flush()
        services.closers.append(sim.scheduler.hold_real_time())
        return services

    def close(self) -> None:
        for close in reversed(self.closers):
            close()
        self.closers.clear()


def keep_running(project: str) -> Callable[[Any], None]:
    """What ``gpl2py run`` runs instead of the package's ``main`` while it serves: start the
    project from the table, then drive the scheduler until interrupted (module docstring)."""

    def main(sim: Any) -> None:
        sim.activate()
        if project:
            sim.projects.start(project)
        idle = threading.Event()
        while True:
            if sim.scheduler.wait_until_quiet(None, _IDLE_POLL) or sim.scheduler.is_stalled():
                idle.wait(_IDLE_POLL)  # nothing to drive now; a console command may start more

    return main

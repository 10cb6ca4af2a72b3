"""The ``gpl2py`` command's entry point: a Ctrl-C at any moment ends it with status 130, no traceback.

Why a module of its own: ``gpl2py.cli`` imports the transpiler and, for ``run``, the simulator
(numpy, Pinocchio, Ruckig) — about 0.1 s in which a Ctrl-C raised KeyboardInterrupt inside an
import, before ``cli.main`` could catch anything, and Python printed a traceback.  This module
imports only the standard library's ``os``, ``signal`` and ``sys``, so the handler stands before the
first slow import.  ``cli.main`` keeps its own handling for the command itself (``gpl2py run``
stops every GPL thread first, see ``gpl2py.run``).

After the command has returned, Python still runs its cleanup (atexit handlers such as the
temporary flash folder's removal, the wait for threads), where a Ctrl-C would print
"Exception ignored in atexit callback" and a traceback: from then on a Ctrl-C ends the process at
once, with status 130.  A SIGINT that was ignored when gpl2py started stays ignored (POSIX
background jobs, ``nohup``).
"""

from __future__ import annotations

import os
import signal
import sys
from types import FrameType

EXIT_INTERRUPTED = 130


def main() -> int:
    """Run the ``gpl2py`` command line (``gpl2py.cli.main``) and return its exit status."""
    status = EXIT_INTERRUPTED
    try:
        from gpl2py.cli import main as cli_main

        status = cli_main()
    except KeyboardInterrupt:
        _end_on_interrupt()  # first, so that a second Ctrl-C cannot interrupt the message
        _say("gpl2py: interrupted\n")
    finally:
        _end_on_interrupt()
    return status


def _end_on_interrupt() -> None:
    """From now on SIGINT ends the process at once with 130 (unless it is ignored)."""
    if signal.getsignal(signal.SIGINT) is not signal.SIG_IGN:
        signal.signal(signal.SIGINT, _end_now)


def _end_now(signum: int, frame: FrameType | None) -> None:
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a closed pipe or stream: nothing more can be said
            pass
    os._exit(EXIT_INTERRUPTED)


def _say(text: str) -> None:
    try:
        sys.stderr.write(text)
        sys.stderr.flush()
    except (OSError, ValueError):
        pass

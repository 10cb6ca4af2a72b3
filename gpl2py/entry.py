"""The ``gpl2py`` command's entry point: a Ctrl-C at any moment ends it with status 130, SIGTERM
with 143, no traceback.

Why a module of its own: ``gpl2py.cli`` imports the transpiler and, for ``run``, the simulator
(numpy, Pinocchio, Ruckig) — about 0.1 s in which a Ctrl-C raised KeyboardInterrupt inside an
import, before ``cli.main`` could catch anything, and Python printed a traceback.  This module
imports only the standard library's ``os``, ``signal`` and ``sys``, and ``gpl2py.interrupts``
(which imports nothing), so the handler stands before the first slow import.  ``cli.main`` keeps
its own handling for the command itself (``gpl2py run`` stops every GPL thread first, see
``gpl2py.run``).

After the command has returned, Python still runs its cleanup (atexit handlers such as the
temporary flash folder's removal, the wait for threads), where a Ctrl-C would print
"Exception ignored in atexit callback" and a traceback: from then on a Ctrl-C ends the process at
once, with status 130.  A SIGINT that was ignored when gpl2py started stays ignored (POSIX
background jobs, ``nohup``).

SIGTERM (what ``docker stop``, systemd, ``kill`` and CI time-outs send) is treated as Ctrl-C is:
its handler raises ``gpl2py.interrupts.Terminated``, a KeyboardInterrupt, so every place that
stops cleanly on Ctrl-C does so on SIGTERM too -- ``gpl2py run`` stops the GPL threads, closes
their servers and removes the temporary flash folder at exit -- and the status is 143 (128 +
SIGTERM), the word "terminated".  Python's default for SIGTERM was to die at once, leaving the flash folder behind.
"""

from __future__ import annotations

import os
import signal
import sys
from types import FrameType

from gpl2py.interrupts import EXIT_INTERRUPTED, EXIT_TERMINATED, Terminated, stop_status


def main() -> int:
    """Run the ``gpl2py`` command line (``gpl2py.cli.main``) and return its exit status."""
    _terminate_as_interrupt()
    status = EXIT_INTERRUPTED
    try:
        from gpl2py.cli import main as cli_main

        status = cli_main()
    except KeyboardInterrupt as interrupt:
        _end_on_interrupt()  # first, so that a second Ctrl-C cannot interrupt the message
        status, word = stop_status(interrupt)
        _say(f"gpl2py: {word}\n")
    finally:
        _end_on_interrupt()
    return status


def _terminate_as_interrupt() -> None:
    """From now on SIGTERM raises :class:`Terminated` (unless it is ignored)."""
    if signal.getsignal(signal.SIGTERM) is not signal.SIG_IGN:
        signal.signal(signal.SIGTERM, _raise_terminated)


def _raise_terminated(signum: int, frame: FrameType | None) -> None:
    raise Terminated


def _end_on_interrupt() -> None:
    """From now on SIGINT ends the process at once with 130, SIGTERM with 143 (unless ignored)."""
    if signal.getsignal(signal.SIGINT) is not signal.SIG_IGN:
        signal.signal(signal.SIGINT, _end_now)
    if signal.getsignal(signal.SIGTERM) is not signal.SIG_IGN:
        signal.signal(signal.SIGTERM, _end_now)


def _end_now(signum: int, frame: FrameType | None) -> None:
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a closed pipe or stream: nothing more can be said
            pass
    os._exit(EXIT_TERMINATED if signum == signal.SIGTERM else EXIT_INTERRUPTED)


def _say(text: str) -> None:
    try:
        sys.stderr.write(text)
        sys.stderr.flush()
    except (OSError, ValueError):
        pass

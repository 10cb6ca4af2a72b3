"""What stops gpl2py from outside: Ctrl-C (SIGINT) and SIGTERM, with the status and word of each.

``gpl2py.entry`` makes SIGTERM raise :class:`Terminated`, a KeyboardInterrupt, so that every place
that stops cleanly on Ctrl-C (``gpl2py.cli``, ``gpl2py run``'s stop of the GPL threads) stops the
same way on SIGTERM; :func:`stop_status` then tells the two apart for the exit status and message.
A module of its own, importing nothing, so that the entry point (which must stay light) and the
commands share it without importing one another.
"""

from __future__ import annotations

EXIT_INTERRUPTED = 130  # 128 + SIGINT
EXIT_TERMINATED = 143  # 128 + SIGTERM, as a shell reports a program SIGTERM ended


class Terminated(KeyboardInterrupt):
    """SIGTERM arrived (``kill``, ``docker stop``, systemd, a CI time-out): raised in the main
    thread where Ctrl-C's KeyboardInterrupt would be."""


def stop_status(interrupt: KeyboardInterrupt) -> tuple[int, str]:
    """The exit status and the word for what stopped gpl2py: (130, "interrupted") for Ctrl-C,
    (143, "terminated") for SIGTERM."""
    if isinstance(interrupt, Terminated):
        return EXIT_TERMINATED, "terminated"
    return EXIT_INTERRUPTED, "interrupted"

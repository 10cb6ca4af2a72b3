"""The GPL ``Console`` class: diagnostic text output (spec gpl-language.md §14.7).

``Console.Write(x)`` and ``Console.WriteLine(x)`` are Shared and take one number, Boolean or
String, rendered with the CStr rules (AMB-22); WriteLine appends a line feed [000 L3971-3976].
The manuals document no input member (no ReadLine), so there is none.

Output goes to a replaceable *sink*: a callable taking a str (default: write to ``sys.stdout`` at
call time, so pytest's capture and redirections work).  The simulator and tests install their own
with ``set_console_sink``.  Each call hands the sink one complete piece of text under a lock, so
lines written by concurrent GPL threads never interleave inside a line.
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Callable
from typing import Any

from gplrt.lang.conversions import to_string

__all__ = ["Console", "set_console_sink", "get_console_sink", "capture_console"]

Sink = Callable[[str], Any]


def _stdout_sink(text: str) -> None:
    sys.stdout.write(text)
    sys.stdout.flush()


_sink: Sink = _stdout_sink
_lock = threading.Lock()


def set_console_sink(sink: Sink | None) -> Sink:
    """Install ``sink`` (``None`` restores stdout); returns the previous sink."""
    global _sink
    with _lock:
        previous = _sink
        _sink = sink if sink is not None else _stdout_sink
    return previous


def get_console_sink() -> Sink:
    return _sink


class capture_console:
    """Context manager collecting console output: ``with capture_console() as out: ...``;
    ``out.text`` is everything written, ``out.lines`` the complete lines."""

    def __init__(self) -> None:
        self._parts: list[str] = []
        self._previous: Sink | None = None

    def __enter__(self) -> capture_console:
        self._previous = set_console_sink(self._parts.append)
        return self

    def __exit__(self, *exc: object) -> None:
        set_console_sink(self._previous)

    @property
    def text(self) -> str:
        return "".join(self._parts)

    @property
    def lines(self) -> list[str]:
        return self.text.split("\n")[:-1]


class _Console:
    """GPL ``Console`` (a global class: one instance, Shared members)."""

    __slots__ = ()

    @staticmethod
    def Write(value: Any = "") -> None:
        """Write ``value`` (CStr rules) without a line end."""
        text = value if type(value) is str else to_string(value)
        with _lock:
            _sink(text)

    @staticmethod
    def WriteLine(value: Any = "") -> None:
        """Write ``value`` (CStr rules) followed by a line feed, as one piece."""
        text = value if type(value) is str else to_string(value)
        with _lock:
            _sink(text + "\n")


Console = _Console()

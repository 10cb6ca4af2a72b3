"""A one-line progress bar on stderr while a large project is translated.

Shown only when it helps and cannot hurt: stderr is a terminal (never in logs, pipes or CI), the
user did not ask for ``--quiet`` or ``--json``, and the project has at least ``MIN_FILES`` source
files (small projects finish before a bar could be read).  The bar redraws in place with ``\\r``
and erases itself when done, so the diagnostics and the summary that follow start on a clean line.
"""

from __future__ import annotations

import time
from typing import TextIO

from gpl2py.formats import is_terminal

MIN_FILES = 8
_WIDTH = 28
_MIN_INTERVAL = 0.05  # s between redraws: a fast run must not spend its time drawing


def wants_progress(stream: TextIO, quiet: bool, as_json: bool) -> bool:
    """Whether a bar may be drawn on ``stream`` at all (TTY, not --quiet, not --json)."""
    if quiet or as_json:
        return False
    return is_terminal(stream)


class ProgressBar:
    """``bar(phase, done, total)`` is the callback ``gpl2py.transpile.transpile`` accepts."""

    def __init__(self, stream: TextIO, enabled: bool, min_files: int = MIN_FILES) -> None:
        self.stream = stream
        self.enabled = enabled
        self.min_files = min_files
        self._last = 0.0
        self._drawn = False

    def __call__(self, phase: str, done: int, total: int) -> None:
        if not self.enabled or total < self.min_files:
            return
        now = time.monotonic()
        if done < total and now - self._last < _MIN_INTERVAL:
            return
        self._last = now
        filled = _WIDTH * done // max(total, 1)
        bar = "#" * filled + "-" * (_WIDTH - filled)
        self.stream.write(f"\r{phase:<10} [{bar}] {done}/{total}")
        self.stream.flush()
        self._drawn = True

    def close(self) -> None:
        """Erase the bar (if one was drawn) so that the next output starts at column 1."""
        if self._drawn:
            self.stream.write("\r\x1b[K")
            self.stream.flush()
            self._drawn = False

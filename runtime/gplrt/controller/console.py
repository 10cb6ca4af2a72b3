"""Where one session's console output and the controller's log lines go (``Session.console``).

GPL's ``Console`` class (``gplrt.lang.console``) writes to one process-wide sink; the simulator
installs a sink that hands each piece of text to the console of the session the writing thread
belongs to (``gplrt.sim``), so two sessions side by side never take each other's output.
"""

from __future__ import annotations

import io as _io
import sys
import threading
from typing import TextIO


class ConsoleSink:
    """Where the program's console output and the controller's log lines go.

    ``write`` carries program output (``Console.WriteLine``); ``log`` carries controller reports
    (unhandled thread errors, system messages).  With ``capture=True`` both are kept in memory
    (``output``, ``log_text``) instead of being printed — tests compare them byte for byte.
    """

    def __init__(self, capture: bool = False, stream: TextIO | None = None, log_stream: TextIO | None = None) -> None:
        self.capture = capture
        self._out: TextIO = _io.StringIO() if capture else (stream or sys.stdout)
        self._log: TextIO = _io.StringIO() if capture else (log_stream or sys.stderr)
        self._lock = threading.Lock()
        #: Set when a stream was closed by its reader (``gpl2py run | head``): the console output
        #: is then dropped, never an error of the GPL program that wrote it, and ``gpl2py run``
        #: ends the run quietly.
        self.closed = threading.Event()

    def write(self, text: str) -> None:
        self._put(self._out, text)

    def log(self, line: str) -> None:
        self._put(self._log, line + "\n")

    def _put(self, stream: TextIO, text: str) -> None:
        with self._lock:
            if self.closed.is_set():
                return
            try:
                stream.write(text)
                if not self.capture:
                    stream.flush()
            except (BrokenPipeError, ValueError):  # the reader went away / the stream was closed
                self.closed.set()

    @property
    def output(self) -> str:
        return self._out.getvalue() if isinstance(self._out, _io.StringIO) else ""

    @property
    def log_text(self) -> str:
        return self._log.getvalue() if isinstance(self._log, _io.StringIO) else ""

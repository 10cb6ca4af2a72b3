"""TYPE and PROMPT on the session's console (L7093-7139, L7233-7240).

TYPE writes its items and a line end unless ``/S``; output is gated by the MESSAGES switch
(L5886-5887).  PROMPT reads a line from the session's input (``set_prompt_input``) into a string or
real variable, by default from the process's standard input (``gpl2py run`` at a terminal), waiting
as a thread waits on the outside world (the virtual clock does not race ahead meanwhile); [D] at the
end of the input it is *Unexpected end of file* (-504), what V+ reports for Ctrl-Z at a PROMPT.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import Any

from gplrt.lang.console import Console
from gplrt.threads.scheduler import external_wait
from gplrt.vplus.errors import END_OF_FILE, VError
from gplrt.vplus.strings import render, val
from gplrt.vplus.system import switch
from gplrt.vplus.taskstate import safepoint
from gplrt.vplus.values import session_data


def type_(*items: Any) -> None:
    text, end = render(items)
    if switch("MESSAGES"):
        Console.Write(text + ("\n" if end else ""))
    safepoint()


def set_prompt_input(source: Callable[[], str | None] | list[str]) -> None:
    """Where PROMPT reads from in this session: a function returning a line (None at the end) or
    a list of lines consumed in order."""
    if isinstance(source, list):
        lines = list(source)
        source = lambda: lines.pop(0) if lines else None  # noqa: E731
    session_data().extra["prompt_input"] = source


def _stdin_line() -> str | None:
    """A line of standard input without its line end; None at its end (or when there is none)."""
    try:
        with external_wait():
            line = sys.stdin.readline()
    except (OSError, ValueError, AttributeError):  # no usable stdin (closed, captured by a test)
        return None
    return line.rstrip("\r\n") if line else None


def prompt(text: str, ref: Any) -> None:
    """``PROMPT "text", var``."""
    Console.Write(text)
    source = session_data().extra.get("prompt_input")
    line = source() if source is not None else _stdin_line()
    if line is None:
        raise VError(END_OF_FILE, detail="PROMPT: no input")
    if source is not None:
        Console.Write(line + "\n")  # (what a user types at a terminal is on the screen already)
    name = getattr(ref, "name", "")
    if name.startswith("$") or (ref.defined and isinstance(ref.v, str)):
        ref.v = line
    else:
        ref.v = val(line)

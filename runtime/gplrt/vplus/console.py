"""TYPE and PROMPT on the session's console (L7093-7139, L7233-7240).

TYPE writes its items and a line end unless ``/S``; output is gated by the MESSAGES switch
(L5886-5887).  PROMPT reads a line from the session's input (``set_prompt_input``) into a string or
real variable; [D] with no input available it is *Unexpected end of file* (-504), what V+ reports
for Ctrl-Z at a PROMPT.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from gplrt.lang.console import Console
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


def prompt(text: str, ref: Any) -> None:
    """``PROMPT "text", var``."""
    Console.Write(text)
    source = session_data().extra.get("prompt_input")
    line = source() if source is not None else None
    if line is None:
        raise VError(END_OF_FILE, detail="PROMPT: no input")
    Console.Write(line + "\n")
    name = getattr(ref, "name", "")
    if name.startswith("$") or (ref.defined and isinstance(ref.v, str)):
        ref.v = line
    else:
        ref.v = val(line)

"""Every diagnostic gpl2py can emit: its stable code, severity and wording (mypy's message_registry).

Codes are stable: once released, a code keeps its meaning.  Ranges belong to layers so that a
newcomer can tell from the number where a message comes from:

* ``GPL1000``-``GPL1099`` lexer              * ``GPL1100``-``GPL1399`` parser
* ``GPL1400``-``GPL1499`` project loading    * ``GPL2000``-``GPL2999`` semantic analysis
* ``GPL3000``-``GPL3499`` lowering / output  * ``GPL3500``-``GPL3999`` stubs for missing code
* ``GPL9000``-``GPL9999`` internal errors and command-line usage

``docs/diagnostics.md`` is generated from this module (``python -m gpl2py.messages``); a test keeps
the two in step.  Templates use ``str.format`` fields.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from gpl2py.diagnostics import Severity

_REGISTRY: dict[str, Message] = {}


@dataclass(frozen=True, slots=True)
class Message:
    code: str
    severity_name: str  # "error" | "warning" | "note"
    template: str
    doc: str = ""

    @property
    def severity(self) -> Severity:
        from gpl2py.diagnostics import Severity

        return Severity(self.severity_name)

    def format(self, **args: object) -> str:
        return self.template.format(**args) if args else self.template


def _error(code: str, template: str, doc: str = "") -> Message:
    return _register(Message(code, "error", template, doc))


def _warning(code: str, template: str, doc: str = "") -> Message:
    return _register(Message(code, "warning", template, doc))


def _register(message: Message) -> Message:
    if message.code in _REGISTRY:
        raise AssertionError(f"duplicate diagnostic code {message.code}")
    _REGISTRY[message.code] = message
    return message


def all_messages() -> list[Message]:
    return sorted(_REGISTRY.values(), key=lambda m: m.code)


# --- lexer (GPL1000-GPL1099) -------------------------------------------------------------------

# --- parser (GPL1100-GPL1399) ------------------------------------------------------------------

# --- project loading (GPL1400-GPL1499) ---------------------------------------------------------

# --- semantic analysis (GPL2000-GPL2999) -------------------------------------------------------

# --- lowering and output (GPL3000-GPL3499) -----------------------------------------------------

# --- stubs for missing code (GPL3500-GPL3999) --------------------------------------------------

# --- internal and usage (GPL9000-GPL9999) ------------------------------------------------------

INTERNAL_ERROR = _error(
    "GPL9000",
    "internal error in gpl2py while processing this input: {detail}",
    "A bug in gpl2py, never in your program. Please report it with the input that caused it.",
)


def markdown() -> str:
    """The text of docs/diagnostics.md."""
    out = [
        "# gpl2py diagnostics",
        "",
        "Generated from `gpl2py/messages.py` by `python -m gpl2py.messages > docs/diagnostics.md`;",
        "do not edit by hand. Codes are stable. Each diagnostic prints as",
        "`path:line:col: severity GPLnnnn: message`, followed by the source line and a caret.",
        "",
        "| Code | Severity | Message | Notes |",
        "|---|---|---|---|",
    ]
    for m in all_messages():
        text = m.template.replace("|", "\\|")
        doc = m.doc.replace("|", "\\|")
        out.append(f"| {m.code} | {m.severity_name} | {text} | {doc} |")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    sys.stdout.write(markdown())

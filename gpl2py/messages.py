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

PATH_NOT_FOUND = _error(
    "GPL1400",
    "no such file or folder: {path}",
    "The path given to gpl2py does not exist.",
)
NOT_A_PROJECT = _error(
    "GPL1401",
    "not a GPL project or source file: {path}",
    "gpl2py reads a project folder, a Project.gpr file, or a single .gpl/.gpo source file.",
)
NO_SOURCES = _error(
    "GPL1402",
    "no GPL source files (.gpl, .gpo) in {path}",
    "A folder without Project.gpr is read as every .gpl/.gpo file in it; this one has none.",
)
CANNOT_READ = _error(
    "GPL1403",
    "cannot read {path}: {reason}",
    "The operating system refused to read the file (permissions, a folder where a file was expected, ...).",
)
BINARY_FILE = _error(
    "GPL1404",
    "{path} is not a text file: {what}",
    "GPL sources are ASCII text. NUL bytes, UTF-16 encoding or mostly control characters mean the file "
    "is binary or was saved in the wrong encoding; re-save it as ASCII.",
)
SOURCE_NOT_FOUND = _error(
    "GPL1405",
    "source file {name} named in Project.gpr not found in {folder}",
    "Every ProjectSource line must name a file in the project folder (names are matched "
    "case-insensitively, as on the controller).",
)
PROTECTED_SKIPPED = _warning(
    "GPL1406",
    "skipping vendor-protected file {name}: protected (.gpp) sources cannot be read or translated",
    "A .gpp file (or any file starting with '#Protected|) is encrypted vendor code. The rest of the "
    "project is still translated; calls into the protected code will not resolve.",
)
GPR_BAD_LINE = _error(
    "GPL1407",
    "cannot understand this Project.gpr line; expected KEY=\"value\"",
    "Project.gpr holds one KEY=\"value\" per line between ProjectBegin and ProjectEnd; lines "
    "starting with ' are comments.",
)
GPR_UNKNOWN_KEY = _warning(
    "GPL1408",
    "unknown Project.gpr key {key}; kept but not used",
    "gpl2py understands ProjectName, ProjectStart and ProjectSource. Other keys are kept in "
    "Project.extra_keys so later tools can read them.",
)
GPR_MISSING_BEGIN = _error(
    "GPL1409",
    "Project.gpr does not start with ProjectBegin",
    "The first line that is not a ' comment must be ProjectBegin.",
)
GPR_MISSING_END = _error(
    "GPL1410",
    "Project.gpr has no ProjectEnd",
    "The file is probably truncated; the lines read so far are used.",
)
GPR_TEXT_AFTER_END = _warning(
    "GPL1411",
    "text after ProjectEnd is ignored",
    "",
)
GPR_DUPLICATE_KEY = _warning(
    "GPL1412",
    "{key} given more than once; the first value {value} is used",
    "ProjectName and ProjectStart may appear once.",
)
GPR_DUPLICATE_SOURCE = _warning(
    "GPL1413",
    "source file {name} is listed more than once; later entries are ignored",
    "Each module is loaded once, at its first position in the ProjectSource order.",
)
GPR_NO_START = _warning(
    "GPL1414",
    "Project.gpr has no ProjectStart; the project has no start procedure",
    "The project can be checked and imported, but not run on its own.",
)
GPR_NO_SOURCES = _error(
    "GPL1415",
    "Project.gpr lists no ProjectSource files",
    "",
)
GPR_BAD_SOURCE_NAME = _error(
    "GPL1416",
    "source file name {name} must be a plain file name inside the project folder",
    "ProjectSource names a file in the project folder; absolute paths and '..' are not allowed.",
)
GPR_BAD_EXTENSION = _error(
    "GPL1417",
    "source file {name} is not a GPL source (.gpl, .gpo or .gpp)",
    "",
)
AMBIGUOUS_FILE_NAME = _warning(
    "GPL1418",
    "{name} matches several files that differ only in case ({candidates}); using {chosen}",
    "The controller's file system is case-insensitive, so only one of these files could exist there.",
)
GPR_EMPTY_VALUE = _error(
    "GPL1419",
    "{key} has an empty value",
    "",
)

# --- semantic analysis (GPL2000-GPL2999) -------------------------------------------------------

# --- lowering and output (GPL3000-GPL3499) -----------------------------------------------------

# --- stubs for missing code (GPL3500-GPL3999) --------------------------------------------------

# --- internal and usage (GPL9000-GPL9999) ------------------------------------------------------

INTERNAL_ERROR = _error(
    "GPL9000",
    "internal error in gpl2py while processing this input: {detail}",
    "A bug in gpl2py, never in your program. Please report it with the input that caused it.",
)
USAGE_ERROR = _error(
    "GPL9001",
    "{detail}",
    "The command line is wrong (unknown command or option, missing argument). Run gpl2py --help. "
    "Exit status 2.",
)
DUMP_AST_NEEDS_FILE = _error(
    "GPL9002",
    "dump-ast takes one .gpl or .gpo source file, not {path}",
    "To check a whole project use gpl2py check. Exit status 2.",
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

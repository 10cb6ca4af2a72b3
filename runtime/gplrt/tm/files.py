"""TMscript's file functions (manual §7, L9907-L12366; spec §3.10) on the runtime's file sandbox.

Paths (L9909-L9951): a bare name is in ``.\\TextFiles``; ``.\\TextFiles``, ``.\\XmlFiles`` and
``.\\TMcraft`` (and their sub-folders) are the local folders; an absolute path (``C:\\...``,
``\\TextFiles\\...``), a ``..`` and any other folder are invalid -- a script error for the
functions that read or write, false or -1 for the queries (``File_Exists``, ``File_Length``).
The robot's USB drive, network shares and FTP are not simulated (a script error naming them).

The folders live in the robot's session's flash sandbox (``Simulation.files``, the same
``gplrt.io.sandbox`` GPL's file classes use: no link is followed, only regular files are opened,
docs/security.md), as ``TextFiles/``, ``XmlFiles/``, ``TMcraft/`` below its root.  Names match
case-insensitively, as on the robot's Windows (the manual reads ``SampleFile1.txt`` as
``sampleFile1.txt``, L9990).  Files are at most 10 MB (L9951).  Text is UTF-8; a line written
ends with CR LF (the robot's Windows newline; the manual's files read back with ``0x0D 0x0A``,
L9989).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from gplrt.io.sandbox import Sandbox, SandboxPath
from gplrt.lang.errors import GplException
from gplrt.tm import context
from gplrt.tm.conversions import GetBytes, write_span
from gplrt.tm.strings import GetAllTokens, GetToken
from gplrt.tm.values import Array, TMError, format_value, to_int, to_string

#: The local folders a path may name (L9911), by their lower-case name.
FOLDERS = {"textfiles": "TextFiles", "xmlfiles": "XmlFiles", "tmcraft": "TMcraft"}
#: The largest file read or written (L9951).
MAX_SIZE = 10 * 1024 * 1024
NEWLINE = "\r\n"
_DRIVE = re.compile(r"^[A-Za-z]:")


class _Invalid(Exception):
    """A path the robot refuses (absolute, ``..``, outside the local folders)."""


def _parts(path: object) -> tuple[str, ...]:
    """The folder and names of ``path`` below the sandbox root (``_Invalid`` if refused)."""
    text = to_string(path)
    low = text.lower()
    if low.startswith(("\\usb\\", "\\\\", "ftp://")):
        raise TMError(f"{text}: the USB drive, network shares and FTP are not simulated")
    if not text or _DRIVE.match(text) or text.startswith(("\\", "/")):
        raise _Invalid(f"{text}: an absolute path is void (L9928)")
    names = re.split(r"[\\/]", text)
    if len(names) == 1:  # a bare name: .\TextFiles (L9915)
        names = [".", "TextFiles", *names]
    if names[0] != "." or len(names) < 3:
        raise _Invalid(f"{text}: files are in the local folders TextFiles, XmlFiles or TMcraft (L9911)")
    folder = FOLDERS.get(names[1].lower())
    rest = names[2:]
    if folder is None or any(n in ("", ".", "..") or "\0" in n for n in rest):
        raise _Invalid(f"{text}: files are in the local folders TextFiles, XmlFiles or TMcraft (L9920)")
    return (folder, *rest)


def _box() -> Sandbox:
    return context.robot().sim.files.root().box


def _find(parts: tuple[str, ...]) -> SandboxPath:
    """The sandbox entry of ``parts``, each name matched case-insensitively to what exists (as
    given where nothing matches: a file about to be made)."""
    box = _box()
    found: list[str] = [parts[0]]
    box.path(parts[0]).ensure_folder()
    for name in parts[1:]:
        try:
            here = box.path(*found).entries()
        except OSError:
            here = []
        match = next((n for n, _ in here if n == name), None) or \
            next((n for n, _ in here if n.lower() == name.lower()), name)
        found.append(match)
    return box.path(*found)


def _file(path: object, what: str) -> SandboxPath:
    """The entry of a path a reading or writing function uses (a script error if refused)."""
    try:
        return _find(_parts(path))
    except _Invalid as exc:
        raise TMError(f"{what}: {exc}") from None


def _read(path: object, what: str) -> bytes:
    entry = _file(path, what)
    try:
        if entry.file_size() > MAX_SIZE:
            raise TMError(f"{what}: {to_string(path)} is larger than 10 MB (L9951)")
        return entry.read_bytes()
    except (OSError, GplException) as exc:
        raise TMError(f"{what}: {to_string(path)}: the file does not exist or cannot be read ({exc})") from None


def _text(data: bytes) -> str:
    return data.decode("utf-8-sig", errors="replace")


def _lines(text: str) -> list[str]:
    """The lines of a file's text: an empty file is one empty line ({""}, L10140); a final
    newline ends the last line, it does not start another."""
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    return lines[:-1] if len(lines) > 1 and lines[-1] == "" else lines


def File_ReadBytes(path: object) -> Array:
    """The whole file as ``byte[]`` (L9954)."""
    return Array("byte", _read(path, "File_ReadBytes"))


def File_ReadText(path: object) -> str:
    """The whole file as text (L10013)."""
    return _text(_read(path, "File_ReadText"))


def File_ReadLines(path: object, first: object = None, count: object = 0) -> Array:
    """The lines (L10054): from line ``first`` (1-based; <= 0 or past the end: ``{}``), ``count``
    of them (<= 0: to the end)."""
    lines = _lines(_text(_read(path, "File_ReadLines")))
    if first is None:
        return Array("string", lines)
    start, n = to_int(first), to_int(count)
    if not 1 <= start <= len(lines):
        return Array("string", [])
    chosen = lines[start - 1:] if n <= 0 else lines[start - 1:start - 1 + n]
    return Array("string", chosen)


@dataclass
class _Cursor:
    """``File_NextLine``'s place: the last file read and the next line's index."""

    key: tuple[str, ...] | None = None
    path: object = None
    lines: list[str] = field(default_factory=list)
    at: int = 0

    @property
    def eof(self) -> bool:
        return self.key is None or self.at >= len(self.lines)


def _cursor() -> _Cursor:
    robot = context.robot()
    cur = getattr(robot, "_file_cursor", None)
    if cur is None:
        cur = robot._file_cursor = _Cursor()  # type: ignore[attr-defined]
    return cur  # type: ignore[no-any-return]


def _open_cursor(path: object) -> _Cursor:
    cur = _cursor()
    parts = _parts_or_error(path, "File_NextLine")
    cur.key = tuple(p.lower() for p in parts)
    cur.path = path
    cur.lines = _lines(_text(_read(path, "File_NextLine")))
    cur.at = 0
    return cur


def _parts_or_error(path: object, what: str) -> tuple[str, ...]:
    try:
        return _parts(path)
    except _Invalid as exc:
        raise TMError(f"{what}: {exc}") from None


def File_NextLine(*args: object) -> object:
    """The next line of the last file read (L10149): ``()`` continues; ``(path)`` continues on
    the same file, starts another at its first line; ``(path, true)`` reopens.  ``""`` at the
    end.  With an int mode (L10256): ``{line}`` or ``{}`` at the end; 0 continue, 1 reopen and
    read, 2 open without reading (``{}``)."""
    mode: int | None = None
    path: object = None
    reopen = False
    rest = list(args)
    if rest and isinstance(rest[0], str):
        path = rest.pop(0)
    if rest:
        if isinstance(rest[0], bool):
            reopen = bool(rest[0])
        else:
            mode = to_int(rest[0])
    if mode is not None and mode not in (0, 1, 2):
        raise TMError(f"File_NextLine: mode {mode} is not 0, 1 or 2 (L10283)")
    cur = _cursor()
    if path is not None:
        key = tuple(p.lower() for p in _parts_or_error(path, "File_NextLine"))
        if reopen or mode in (1, 2) or key != cur.key:
            cur = _open_cursor(path)
    elif mode in (1, 2) and cur.key is not None:  # (the last file, reopened: syntax 5, L10283)
        cur = _open_cursor(cur.path)
    if mode == 2:
        return Array("string", [])
    if cur.eof:
        return Array("string", []) if mode is not None else ""
    line = cur.lines[cur.at]
    cur.at += 1
    return Array("string", [line]) if mode is not None else line


def File_NextEOF() -> bool:
    """Whether ``File_NextLine`` has reached the end of its file, or has no file (L10367)."""
    return _cursor().eof


def _write(path: object, data: bytes, append: object, what: str) -> bool:
    entry = _file(path, what)
    try:
        size = entry.file_size() if to_int(append) == 1 and entry.lstat() is not None else 0
        if size + len(data) > MAX_SIZE:
            return False
        for depth in range(2, len(entry.parts)):  # (sub-folders are made as needed)
            entry.box.path(*entry.parts[:depth]).mkdir()
        with entry.open("a" if to_int(append) == 1 else "w") as stream:
            stream.write(data)
    except (OSError, GplException):
        return False
    return True


def File_WriteBytes(path: object, value: object, append: object = 0, start: object = 0, length: object = 0) -> bool:
    """``value`` as bytes (little-endian numbers, UTF-8 text, L10410); ``append`` 1 appends."""
    data = bytes(GetBytes(write_span(value, start, length)))
    return _write(path, data, append, "File_WriteBytes")


def File_WriteText(path: object, value: object, append: object = 0, start: object = 0, length: object = 0) -> bool:
    """``value``'s text form (arrays ``{a,b}``), no newline (L10772)."""
    return _write(path, format_value(write_span(value, start, length)).encode("utf-8"), append, "File_WriteText")


def File_WriteLine(path: object, value: object, append: object = 0, start: object = 0, length: object = 0) -> bool:
    """``value``'s text form and a newline (L11074)."""
    text = format_value(write_span(value, start, length)) + NEWLINE
    return _write(path, text.encode("utf-8"), append, "File_WriteLine")


def File_WriteLines(path: object, value: object, append: object = 0, start: object = 0, length: object = 0) -> bool:
    """Each element of an array on a line of its own (a single value: one line, L11329)."""
    part = write_span(value, start, length)
    items = part if isinstance(part, (list, tuple)) else [part]
    text = "".join(format_value(v) + NEWLINE for v in items)
    return _write(path, text.encode("utf-8"), append, "File_WriteLines")


def File_Exists(path: object) -> bool:
    """Whether the file exists (an invalid path: false, L11547)."""
    try:
        entry = _find(_parts(path))
    except (_Invalid, TMError, OSError, GplException):
        return False
    found = entry.lstat()
    return found is not None and not _is_folder(entry)


def _is_folder(entry: SandboxPath) -> bool:
    try:
        entry.entries()
    except (OSError, GplException):
        return False
    return True


def File_Length(path: object) -> int:
    """The size in bytes; -1 missing or invalid, -2 too large (L11579)."""
    try:
        size = _find(_parts(path)).file_size()
    except (_Invalid, TMError, OSError, GplException):
        return -1
    return -2 if size > MAX_SIZE else int(size)


def File_Delete(*paths: object) -> bool:
    """Delete files (also a ``string[]`` of them); true also when one is missing, false when one
    cannot be deleted (L11613)."""
    names = list(paths[0]) if len(paths) == 1 and isinstance(paths[0], (list, tuple)) else list(paths)
    ok = True
    for p in names:
        entry = _file(p, "File_Delete")
        if entry.lstat() is None:
            continue
        try:
            entry.unlink()
        except (OSError, GplException):
            ok = False
    return ok


def File_Copy(src: object, folder: object, name: object = "") -> bool:
    """Copy ``src`` into the local folder ``folder`` as ``name`` (default: its own name),
    overwriting (L11677)."""
    data = _read(src, "File_Copy")
    target = to_string(name) or re.split(r"[\\/]", to_string(src))[-1]
    where = to_string(folder).rstrip("\\/")
    return _write(f"{where}\\{target}", data, 0, "File_Copy")


def File_Replace(path: object, old: object, new: object) -> bool:
    """Replace every ``old`` by ``new`` in the file (L11896); false when it cannot be read."""
    try:
        text = _text(_read(path, "File_Replace"))
    except TMError:
        return False
    return _write(path, text.replace(to_string(old), to_string(new)).encode("utf-8"), 0, "File_Replace")


def File_GetToken(path: object, prefix: object, suffix: object, n: object = 1, mode: object = 0) -> str:
    """``GetToken`` over the file's text (L11968)."""
    return GetToken(_text(_read(path, "File_GetToken")), prefix, suffix, n, mode)


def File_GetAllTokens(path: object, prefix: object, suffix: object, mode: object = 0) -> Array:
    """``GetAllTokens`` over the file's text (L12259)."""
    return GetAllTokens(_text(_read(path, "File_GetAllTokens")), prefix, suffix, mode)


__all__ = [
    "File_Copy", "File_Delete", "File_GetAllTokens", "File_Exists", "File_GetToken", "File_Length", "File_NextEOF", "File_NextLine",
    "File_ReadBytes", "File_ReadLines", "File_ReadText", "File_Replace", "File_WriteBytes", "File_WriteLine",
    "File_WriteLines", "File_WriteText",
]

"""Project loading: a path on disk -> the ordered set of GPL sources to compile.

Three kinds of input are accepted, mirroring how code reaches a PreciseFlex controller:

* a **project folder** holding ``Project.gpr`` (or the ``Project.gpr`` file itself): the sources are
  the ``ProjectSource`` lines, in order, because module initialisation follows that order;
* a **folder without Project.gpr**: every ``.gpl``/``.gpo`` file in it, sorted case-insensitively by
  name so that the result does not depend on the file system's listing order;
* a **single** ``.gpl``/``.gpo`` **file**.

``.gpo`` files are ordinary GPL (a global module of Location and Profile objects). ``.gpp`` files are
vendor-protected (``'#Protected|`` followed by binary) and are skipped with a warning naming them.

Nothing here raises on bad input: problems are diagnostics in the caller's sink, positioned at the
``Project.gpr`` line that caused them where there is one.  File bytes are decoded leniently (UTF-8 if
valid, latin-1 otherwise) so that a stray non-ASCII character reaches the lexer, which reports it
with its exact position, instead of failing here.

Decisions where the manuals are silent (gpl-language.md §12.3 recommends the format):

* keys are case-insensitive, blank lines and ``'`` comment lines are ignored anywhere, ``KEY = "v"``
  with spaces and an unquoted value are tolerated;
* ``ProjectName``/``ProjectStart`` given twice: the first wins, with a warning;
* a byte-order mark at the start and Ctrl-Z end-of-file markers at the end (old DOS editors) are
  not part of the text, in Project.gpr as in the sources (the lexer skips them there);
* a missing ``ProjectStart`` is a warning (the project can still be checked), ``start`` is ``None``;
* file names are resolved case-insensitively (the controller's flash file system is); if several
  files differ only in case, an exact match wins, otherwise the first in sorted order, with a warning;
* ``load_project`` returns ``None`` only when nothing at all could be read (the path does not exist
  or is not a project); a project with some bad files is still returned so that every problem is
  reported in one run.
"""

from __future__ import annotations

import os
import re
import stat
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

from gpl2py import messages as msg
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.source import LINE_BREAK, Position, SourceFile, Span

PROJECT_FILE = "Project.gpr"
SOURCE_SUFFIXES = (".gpl", ".gpo")
PROTECTED_SUFFIX = ".gpp"
PROTECTED_MAGIC = b"'#Protected|"

#: How much gpl2py reads from one file by default (Project.gpr included); all sources of a
#: project together may be PROJECT_FACTOR times that (docs/security.md, "Input size").
DEFAULT_MAX_SOURCE_MB = 8
PROJECT_FACTOR = 4
MAX_SOURCE_ENV = "GPL2PY_MAX_SOURCE_MB"
#: Project.gpr holds a few lines (the TCS's: 20); one of a megabyte names tens of thousands of files.
MAX_PROJECT_FILE = 2**20


@dataclass(frozen=True)
class Limits:
    """The most bytes gpl2py reads from one file and from all of a project's sources."""

    source: int = DEFAULT_MAX_SOURCE_MB * 2**20
    project: int = PROJECT_FACTOR * DEFAULT_MAX_SOURCE_MB * 2**20

    @classmethod
    def of_mb(cls, mb: float) -> Limits:
        size = max(1, int(mb * 2**20))
        return cls(size, PROJECT_FACTOR * size)

    @classmethod
    def from_env(cls) -> Limits:
        """The limits ``GPL2PY_MAX_SOURCE_MB`` sets (megabytes per file), else the defaults; a
        value that is not a positive number is ignored."""
        text = os.environ.get(MAX_SOURCE_ENV, "")
        try:
            mb = float(text)
        except ValueError:
            return cls()
        return cls.of_mb(mb) if mb > 0 and mb == mb and mb != float("inf") else cls()


_KNOWN_KEYS = {"projectname", "projectstart", "projectsource"}
_KEY_VALUE = re.compile(r'^\s*([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(?:"([^"]*)"|([^"\s].*?))?\s*$')


@dataclass
class Project:
    """What a transpiler needs to know about one GPL project.

    ``start`` is the start procedure as written in Project.gpr (``"Main"`` or ``"Module.Main"``), or
    ``None`` when there is none (a folder or single file, or a Project.gpr without ProjectStart).
    ``extra_keys`` keeps unknown Project.gpr entries as ``(key, value)`` in file order.
    """

    name: str
    start: str | None
    root: Path
    sources: list[SourceFile] = field(default_factory=list)
    protected: list[Path] = field(default_factory=list)
    extra_keys: list[tuple[str, str]] = field(default_factory=list)
    project_file: SourceFile | None = None
    start_span: Span | None = None  # the ProjectStart value in Project.gpr, for diagnostics
    limits: Limits = field(default_factory=Limits)
    bytes_read: int = 0  # of the sources, against limits.project
    listings: dict[Path, dict[str, list[Path]]] = field(default_factory=dict, repr=False)  # while loading
    real_root: Path | None = field(default=None, repr=False)  # root resolved, while loading

    def source(self, path: str) -> SourceFile | None:
        """The loaded file whose diagnostic path is ``path`` (Project.gpr included)."""
        for src in self.files():
            if src.path == path:
                return src
        return None

    def files(self) -> list[SourceFile]:
        """Project.gpr (if any) and every source, for rendering diagnostics with excerpts."""
        head = [self.project_file] if self.project_file is not None else []
        return head + self.sources


def load_project(path: str | os.PathLike[str], sink: DiagnosticSink, limits: Limits | None = None) -> Project | None:
    """Load the project at ``path`` (folder, Project.gpr, or one .gpl/.gpo file); never raises.

    A library caller may hand over anything: a value that is no path at all (None, a number, bytes)
    is GPL1401 naming it, not a TypeError from ``pathlib``.  ``limits`` (default: from the
    environment, :meth:`Limits.from_env`) caps what is read."""
    limits = limits if limits is not None else Limits.from_env()
    try:
        p = Path(path)
    except TypeError:
        sink.report(msg.NOT_A_PROJECT, None, path=f"{path!r} (of type {type(path).__name__}, not a path)"[:200])
        return None
    try:
        exists, is_dir = p.exists(), p.is_dir()
    except OSError as exc:  # e.g. ENAMETOOLONG: the OS refuses the path itself, not just the file
        sink.report(msg.CANNOT_READ, None, path=str(p)[:200], reason=exc.strerror or str(exc))
        return None
    if not exists:
        sink.report(msg.PATH_NOT_FOUND, None, path=str(p))
        return None
    if is_dir:
        gpr = _find_case_insensitive(p, PROJECT_FILE)
        if gpr is not None and gpr.is_file():
            if not _inside(p, gpr, str(gpr), None, sink):
                return None
            return _load_gpr(gpr, sink, limits)
        return _load_folder(p, sink, limits)
    if p.name.lower() == PROJECT_FILE.lower():
        return _load_gpr(p, sink, limits)
    suffix = p.suffix.lower()
    if suffix in SOURCE_SUFFIXES or suffix == PROTECTED_SUFFIX:
        project = Project(name=p.stem, start=None, root=p.parent, limits=limits)
        _add_source(project, p, str(p), None, sink)
        return project
    sink.report(msg.NOT_A_PROJECT, None, path=str(p))
    return None


def swap_texts(project: Project, texts: Mapping[str, str]) -> None:
    """Each source of ``project`` whose absolute path ``texts`` names gets that text in place of
    the file's (an editor's unsaved buffer: the language server, docs/design/frontends.md)."""
    for src in project.sources:
        text = texts.get(os.path.abspath(src.path))
        if text is not None:
            src.text, src._lines = text, None


def load_sources(path: str | os.PathLike[str], sink: DiagnosticSink, limits: Limits | None,
                 suffixes: tuple[str, ...]) -> Project | None:
    """A project of another front end (docs/design/frontends.md): one file, or every file of a
    folder with one of ``suffixes`` (sorted case-insensitively by name; none is not reported
    here, the caller says what it looked for), read with GPL's safety
    (size limits, no links out of the folder, lenient decoding); never raises."""
    limits = limits if limits is not None else Limits.from_env()
    try:
        p = Path(path)
        exists, is_dir = p.exists(), p.is_dir()
    except (TypeError, OSError) as exc:
        sink.report(msg.NOT_A_PROJECT, None, path=f"{path!r} ({exc})"[:200])
        return None
    if not exists:
        sink.report(msg.PATH_NOT_FOUND, None, path=str(p))
        return None
    if not is_dir:
        project = Project(name=p.stem, start=None, root=p.parent, limits=limits)
        _add_source(project, p, str(p), None, sink)
        return project
    project = Project(name=_folder_name(p), start=None, root=p, limits=limits)
    try:
        entries = sorted(p.iterdir(), key=lambda e: (e.name.lower(), e.name))
    except OSError as exc:
        sink.report(msg.CANNOT_READ, None, path=str(p), reason=exc.strerror or str(exc))
        return project
    candidates = [e for e in entries if e.suffix.lower() in suffixes and not e.is_dir()]
    real = _resolved(p)
    for entry in candidates:
        if _inside(p, entry, str(entry), None, sink, real):
            _add_source(project, entry, str(entry), None, sink)
    return project  # (no sources: the front end says so in its own words)


# --- the three input kinds ----------------------------------------------------------------------


def _load_folder(folder: Path, sink: DiagnosticSink, limits: Limits) -> Project:
    project = Project(name=_folder_name(folder), start=None, root=folder, limits=limits)
    try:
        entries = sorted(folder.iterdir(), key=lambda e: (e.name.lower(), e.name))
    except OSError as exc:
        sink.report(msg.CANNOT_READ, None, path=str(folder), reason=exc.strerror or str(exc))
        return project
    candidates = [
        e for e in entries
        if e.suffix.lower() in SOURCE_SUFFIXES + (PROTECTED_SUFFIX,) and not e.is_dir()
    ]
    real = _resolved(folder)
    for entry in candidates:
        if _inside(folder, entry, str(entry), None, sink, real):
            _add_source(project, entry, str(entry), None, sink)
    if not candidates:
        sink.report(msg.NO_SOURCES, None, path=str(folder))
    return project


def _load_gpr(gpr: Path, sink: DiagnosticSink, limits: Limits) -> Project | None:
    folder = gpr.parent
    text = _read_text(gpr, str(gpr), None, sink, min(limits.source, MAX_PROJECT_FILE))
    if text is None:
        return None
    gpr_file = SourceFile(str(gpr), text)
    project = Project(name=_folder_name(folder), start=None, root=folder, project_file=gpr_file,
                      limits=limits)
    entries = _parse_gpr(gpr_file, sink)

    seen_scalar: dict[str, str] = {}
    seen_sources: set[str] = set()
    source_count = 0
    for entry in entries:
        key = entry.key.lower()
        if key not in _KNOWN_KEYS:
            sink.report(msg.GPR_UNKNOWN_KEY, entry.key_span, key=entry.key)
            project.extra_keys.append((entry.key, entry.value))
            continue
        if not entry.value:
            sink.report(msg.GPR_EMPTY_VALUE, entry.key_span, key=entry.key)
            continue
        if key == "projectsource":
            source_count += 1
            folded = entry.value.replace("\\", "/").lower()
            if folded in seen_sources:
                sink.report(msg.GPR_DUPLICATE_SOURCE, entry.value_span, name=entry.value)
                continue
            seen_sources.add(folded)
            _add_listed_source(project, entry, sink)
        elif key in seen_scalar:
            sink.report(msg.GPR_DUPLICATE_KEY, entry.key_span, key=entry.key, value=seen_scalar[key])
        else:
            seen_scalar[key] = entry.value
            if key == "projectname":
                project.name = entry.value
            else:
                project.start = entry.value
                project.start_span = entry.value_span

    whole_file = Span(Position(gpr_file.path, 1, 1), 1, 1)
    if "projectstart" not in seen_scalar:
        sink.report(msg.GPR_NO_START, whole_file)
    if source_count == 0:
        sink.report(msg.GPR_NO_SOURCES, whole_file)
    project.listings.clear()
    project.real_root = None
    return project


def _add_listed_source(project: Project, entry: _GprEntry, sink: DiagnosticSink) -> None:
    """Resolve one ProjectSource value against the project folder and load it."""
    name = entry.value.replace("\\", "/")
    parts = [part for part in name.split("/") if part not in ("", ".")]
    if name.startswith("/") or re.match(r"^[A-Za-z]:", name) or ".." in parts or not parts:
        sink.report(msg.GPR_BAD_SOURCE_NAME, entry.value_span, name=entry.value)
        return
    suffix = Path(parts[-1]).suffix.lower()
    if suffix not in SOURCE_SUFFIXES and suffix != PROTECTED_SUFFIX:
        sink.report(msg.GPR_BAD_EXTENSION, entry.value_span, name=entry.value)
        return
    current = project.root
    for part in parts:
        found = _find_case_insensitive(current, part, sink, entry.value_span, project.listings)
        if found is None:
            sink.report(
                msg.SOURCE_NOT_FOUND, entry.value_span, name=entry.value, folder=str(project.root)
            )
            return
        current = found
    if project.real_root is None:  # (resolved once for every listed source)
        project.real_root = _resolved(project.root)
    if _inside(project.root, current, entry.value, entry.value_span, sink, project.real_root):
        _add_source(project, current, str(current), entry.value_span, sink)


def _add_source(
    project: Project, path: Path, shown: str, cause: Span | None, sink: DiagnosticSink
) -> None:
    """Read one source file into the project, or record it as protected, or report why not."""
    where = cause or _file_start(shown)
    if path.suffix.lower() == PROTECTED_SUFFIX:
        sink.report(msg.PROTECTED_SKIPPED, where, name=shown)
        project.protected.append(path)
        return
    limits = project.limits
    if project.bytes_read > limits.project:
        return  # the total was passed at an earlier file (reported there)
    room = limits.project - project.bytes_read
    if room < limits.source:  # what is left of the project's total is the tighter limit
        data = _read_bytes(path, shown, cause, sink, room, project_limit=limits.project)
    else:
        data = _read_bytes(path, shown, cause, sink, limits.source)
    if data is TOO_LARGE and room < limits.source:
        project.bytes_read = limits.project + 1  # no later file is read
    if not isinstance(data, bytes):
        return
    project.bytes_read += len(data)
    if data.startswith(PROTECTED_MAGIC):
        sink.report(msg.PROTECTED_SKIPPED, where, name=shown)
        project.protected.append(path)
        return
    text = _decode(data, shown, sink)
    if text is not None:
        project.sources.append(SourceFile(shown, text))


# --- Project.gpr syntax -------------------------------------------------------------------------


@dataclass(frozen=True)
class _GprEntry:
    key: str
    value: str
    key_span: Span
    value_span: Span


def _parse_gpr(gpr: SourceFile, sink: DiagnosticSink) -> list[_GprEntry]:
    """The KEY="value" lines between ProjectBegin and ProjectEnd, reporting malformed lines."""
    entries: list[_GprEntry] = []
    state = "before"  # -> "inside" at ProjectBegin -> "after" at ProjectEnd
    last_line = 1
    text = gpr.text.rstrip("\x1a")  # a DOS end-of-file marker (Ctrl-Z) is not text after ProjectEnd
    # Lines as SourceFile and the lexer count them: splitlines would also break at U+0085 (a
    # Windows-1252 '…' read as latin-1), U+2028 and form feeds, shifting every later line number.
    lines = LINE_BREAK.split(text)
    if lines and lines[-1] == "":
        lines.pop()  # the terminator of the last line does not start another
    for number, raw in enumerate(lines, start=1):
        line = raw.strip()
        last_line = number
        if not line or line.startswith("'"):
            continue
        indent = len(raw) - len(raw.lstrip())
        word_span = Span(Position(gpr.path, number, indent + 1), number, indent + 1 + len(line))
        lowered = line.lower()
        if state == "after":
            sink.report(msg.GPR_TEXT_AFTER_END, word_span)
            break
        if lowered == "projectbegin":
            state = "inside"
            continue
        if lowered == "projectend":
            state = "after"
            continue
        if state == "before":
            sink.report(msg.GPR_MISSING_BEGIN, word_span)
            state = "inside"  # carry on: the remaining lines are still useful
        match = _KEY_VALUE.match(raw)
        if match is None:
            sink.report(msg.GPR_BAD_LINE, word_span)
            continue
        key = match.group(1)
        value = match.group(2) if match.group(2) is not None else (match.group(3) or "")
        key_span = Span(Position(gpr.path, number, match.start(1) + 1), number, match.end(1) + 1)
        value_group = 2 if match.group(2) is not None else 3
        if match.group(value_group) is not None:
            start, end = match.start(value_group) + 1, match.end(value_group) + 1
            value_span = Span(Position(gpr.path, number, start), number, end)
        else:
            value_span = key_span
        entries.append(_GprEntry(key, value, key_span, value_span))
    if state != "after":
        sink.report(msg.GPR_MISSING_END, Span(Position(gpr.path, last_line, 1), last_line, 1))
    return entries


# --- files and bytes ----------------------------------------------------------------------------


def _find_case_insensitive(
    folder: Path, name: str, sink: DiagnosticSink | None = None, cause: Span | None = None,
    listings: dict[Path, dict[str, list[Path]]] | None = None,
) -> Path | None:
    """The entry of ``folder`` called ``name`` ignoring case, as the controller would find it.

    ``listings`` caches each folder's entries by lower-cased name for the loading of one
    project: a Project.gpr with thousands of ProjectSource lines lists its folder once, not once
    per line."""
    exact = folder / name
    listing = listings.get(folder) if listings is not None else None
    if listing is None:
        try:
            listing = {}
            for e in folder.iterdir():
                listing.setdefault(e.name.lower(), []).append(e)
        except OSError:
            return exact if exact.exists() else None
        if listings is not None:
            listings[folder] = listing
    matches = sorted(listing.get(name.lower(), []))
    if not matches:
        return None
    chosen = exact if exact in matches else matches[0]
    if len(matches) > 1 and sink is not None:
        sink.report(
            msg.AMBIGUOUS_FILE_NAME,
            cause,
            name=name,
            candidates=", ".join(m.name for m in matches),
            chosen=chosen.name,
        )
    return chosen


def _resolved(folder: Path) -> Path | None:
    """``folder`` resolved, or None when it cannot be (then :func:`_inside` reports why)."""
    try:
        return folder.resolve()
    except (OSError, RuntimeError):
        return None


def _inside(root: Path, path: Path, shown: str, cause: Span | None, sink: DiagnosticSink,
            real_root: Path | None = None) -> bool:
    """Whether ``path``, a file the project names, really lies in the project folder ``root``
    (``real_root``: ``root`` resolved, when the caller has it); a link may point anywhere.
    Reported when it does not."""
    try:
        target = path.resolve()
        inside = target.is_relative_to(real_root or root.resolve())
    except (OSError, RuntimeError) as exc:  # a loop of links, a path the OS refuses
        sink.report(msg.CANNOT_READ, cause or _file_start(str(path)), path=shown,
                    reason=getattr(exc, "strerror", None) or str(exc))
        return False
    if not inside:
        sink.report(msg.SOURCE_OUTSIDE_PROJECT, cause or _file_start(str(path)), path=shown, target=str(target))
    return inside


_KINDS = ((stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"), (stat.S_ISFIFO, "a pipe"),
          (stat.S_ISSOCK, "a socket"))
_OPEN_FLAGS = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_BINARY", 0)


class _TooLarge:
    """What :func:`_read_bytes` returns for a file over its limit (reported)."""


TOO_LARGE = _TooLarge()


def _read_bytes(path: Path, shown: str, cause: Span | None, sink: DiagnosticSink, limit: int,
                project_limit: int | None = None) -> bytes | _TooLarge | None:
    """The bytes of ``path`` if it is a regular file of at most ``limit`` bytes, else ``None``
    (or :data:`TOO_LARGE`) with a diagnostic at ``cause`` (the Project.gpr entry) or at the
    file itself.

    ``project_limit`` is given when ``limit`` is what is left of the project's total, so that
    is what a file too large is told.  The file is examined before it is opened and again once
    open (it may have been swapped meanwhile), and opened without blocking: a pipe or a device
    never makes gpl2py wait or read forever."""
    where = cause or _file_start(shown)
    try:
        before = os.stat(path)
        if not _regular(before, shown, where, sink):
            return None
        if before.st_size > limit:
            _too_large(shown, where, sink, before.st_size, limit, project_limit)
            return TOO_LARGE
        fd = os.open(path, _OPEN_FLAGS)
        try:
            if not _regular(os.fstat(fd), shown, where, sink):
                return None
            chunks: list[bytes] = []
            got = 0
            while got <= limit:
                piece = os.read(fd, min(1 << 20, limit + 1 - got))
                if not piece:
                    break
                chunks.append(piece)
                got += len(piece)
        finally:
            os.close(fd)
    except OSError as exc:
        sink.report(msg.CANNOT_READ, where, path=shown, reason=exc.strerror or str(exc))
        return None
    if got > limit:  # it grew after it was examined
        _too_large(shown, where, sink, got, limit, project_limit)
        return TOO_LARGE
    return b"".join(chunks)


def _regular(st: os.stat_result, shown: str, where: Span, sink: DiagnosticSink) -> bool:
    if stat.S_ISREG(st.st_mode):
        return True
    if stat.S_ISDIR(st.st_mode):
        sink.report(msg.CANNOT_READ, where, path=shown, reason="it is a folder, not a file")
        return False
    what = next((name for test, name in _KINDS if test(st.st_mode)), "not a file")
    sink.report(msg.SOURCE_NOT_REGULAR, where, path=shown, what=what)
    return False


def _too_large(shown: str, where: Span, sink: DiagnosticSink, size: int, limit: int,
               project_limit: int | None) -> None:
    if project_limit is not None:
        sink.report(msg.PROJECT_TOO_LARGE, where, path=shown, limit=_size_text(project_limit))
    else:
        sink.report(msg.SOURCE_TOO_LARGE, where, path=shown, size=_size_text(size), limit=_size_text(limit))


def _size_text(size: int) -> str:
    """``8.0 MB``, ``175.8 kB`` or ``900 bytes``."""
    if size >= 2**20:
        return f"{size / 2**20:.1f} MB"
    return f"{size / 2**10:.1f} kB" if size >= 2**10 else f"{size} bytes"


def _read_text(path: Path, shown: str, cause: Span | None, sink: DiagnosticSink, limit: int) -> str | None:
    data = _read_bytes(path, shown, cause, sink, limit)
    return _decode(data, shown, sink) if isinstance(data, bytes) else None


_TEXT_CONTROLS = {0x09, 0x0A, 0x0C, 0x0D, 0x1A}  # tab, LF, FF, CR, DOS end-of-file
_CONTROL_BYTES = bytes(b for b in range(0x20) if b not in _TEXT_CONTROLS)


def _decode(data: bytes, shown: str, sink: DiagnosticSink) -> str | None:
    """Bytes -> text, or ``None`` with a diagnostic if the bytes are not a text file.

    Non-ASCII is not an error here: GPL forbids it only in names and literals, which the lexer
    knows about, so it is passed on (as UTF-8 when the bytes are valid UTF-8, else as latin-1).
    """
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        sink.report(msg.BINARY_FILE, _file_start(shown), path=shown, what="it is encoded as UTF-16")
        return None
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    nul = data.find(b"\x00")
    if nul >= 0:
        sink.report(msg.BINARY_FILE, _byte_span(shown, data, nul), path=shown, what="it contains NUL bytes")
        return None
    sample = data[:8192]
    controls = len(sample) - len(sample.translate(None, _CONTROL_BYTES))  # count them in C
    if sample and controls * 10 > len(sample):
        first = min(i for i in (sample.find(bytes([c])) for c in _CONTROL_BYTES) if i >= 0)
        sink.report(
            msg.BINARY_FILE,
            _byte_span(shown, data, first),
            path=shown,
            what="it is mostly control characters",
        )
        return None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return data.decode("latin-1")


def _file_start(shown: str) -> Span:
    return Span(Position(shown, 1, 1), 1, 2)


def _byte_span(shown: str, data: bytes, offset: int) -> Span:
    """The line:col of byte ``offset``, counting bytes as characters (the file is not text)."""
    line = data.count(b"\n", 0, offset) + 1
    col = offset - (data.rfind(b"\n", 0, offset) + 1) + 1
    return Span(Position(shown, line, col), line, col + 1)


# --- the project's own files ----------------------------------------------------------------------

#: A controller file name is at most this long and never starts with ``.``; a project folder is
#: no place for files over DATA_FILE_MAX_BYTES.  The runtime installs by the same rules
#: (``gplrt.io.flashroot.MAX_NAME``, ``gplrt.io.project_files.MAX_FILE_BYTES``).
CONTROLLER_MAX_NAME = 43
DATA_FILE_MAX_BYTES = 16 * 2**20
_DATA_DIR_FLAGS = os.O_RDONLY | os.O_DIRECTORY | getattr(os, "O_CLOEXEC", 0)
_DATA_FILE_FLAGS = os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0) \
    | getattr(os, "O_CLOEXEC", 0)


def read_data_files(folder: str | os.PathLike[str]) -> dict[str, bytes]:
    """The files a controller's project folder holds once ``folder`` is downloaded, by name:
    every regular file directly in it with one hard link, a name the controller accepts and at
    most :data:`DATA_FILE_MAX_BYTES` bytes, each read through the folder's descriptor without
    following a link (checked before the open and again on the open file).  Links, hard-linked
    files (their data may be a file outside), folders, FIFOs and devices are skipped.

    These are the files ``gplrt.io.project_files.read_project_files`` installs at run time; this
    copy keeps the translation from importing the runtime's I/O stack, and
    ``tests/frontend/test_project_data_files.py`` holds the two to the same answer."""
    try:
        dir_fd = os.open(folder, _DATA_DIR_FLAGS)
    except OSError:
        return {}
    try:
        with os.scandir(dir_fd) as found:
            names = sorted(e.name for e in found if e.is_file(follow_symlinks=False))
        out: dict[str, bytes] = {}
        for name in names:
            if name.startswith(".") or len(name) > CONTROLLER_MAX_NAME:
                continue
            data = _read_data_file(dir_fd, name)
            if data is not None:
                out[name] = data
        return out
    finally:
        os.close(dir_fd)


def _read_data_file(dir_fd: int, name: str) -> bytes | None:
    def acceptable(st: os.stat_result) -> bool:
        return stat.S_ISREG(st.st_mode) and st.st_nlink == 1 and st.st_size <= DATA_FILE_MAX_BYTES

    try:
        before = os.stat(name, dir_fd=dir_fd, follow_symlinks=False)
        if not acceptable(before):
            return None
        fd = os.open(name, _DATA_FILE_FLAGS, dir_fd=dir_fd)
        with os.fdopen(fd, "rb") as stream:
            after = os.fstat(fd)
            if not acceptable(after) or (after.st_dev, after.st_ino) != (before.st_dev, before.st_ino):
                return None  # swapped between the check and the open
            # read(n) allocates n bytes first: ask for the size the file has, then (if it grew
            # meanwhile) for the rest up to the limit, not for the limit every time
            data = stream.read(after.st_size + 1)
            if len(data) > after.st_size:
                data += stream.read(DATA_FILE_MAX_BYTES + 1 - len(data))
    except OSError:
        return None
    return data if len(data) <= DATA_FILE_MAX_BYTES else None


def _folder_name(folder: Path) -> str:
    return folder.resolve().name or str(folder)

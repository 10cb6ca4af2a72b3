"""The transpile cache behind ``gpl2py run`` and ``gpl2py.notebook.Cell.load``.

Running a project should not re-translate it when nothing changed, so translations are kept in a
cache folder, one entry per *key*:

    key = SHA-256 of ( gpl2py version
                     + fingerprint of gpl2py's own code and of the runtime catalogue it reads
                     + options that change the output (e.g. keep_going)
                     + for every project file (Project.gpr and each source, in project order):
                       the name shown in diagnostics and the file's contents )

The fingerprint of gpl2py's code is there for people who work on gpl2py itself (an editable
install does not change ``__version__`` when the lowering changes).  It hashes each ``.py`` file's
name, size and modification time rather than its bytes: an edit always changes the time, and a
``stat`` of ~100 files costs about a millisecond where reading them costs ~100 ms, which would be
most of a cached run's start-up.  The shown file names are in the key because the stored
diagnostics quote them.

Where (decision): a user cache folder, not the project folder, so that a GPL project folder stays
exactly what the controller sees (it may be read-only, on a share, or copied to ``/flash``):

1. ``--cache-dir DIR`` / ``cache_dir=`` when given,
2. else ``$GPL2PY_CACHE_DIR``,
3. else ``$XDG_CACHE_HOME/gpl2py``, else ``~/.cache/gpl2py``.

An entry is a folder ``<root>/<key[:24]>/`` holding the generated package ``<package>/`` and
``entry.json`` (key, package name, diagnostics, counts).  It is built in a temporary folder and
renamed into place, so a reader never sees half an entry and two concurrent runs cannot corrupt
each other.  Entries are never modified; deleting the cache folder is always safe.  After each
store the oldest entries beyond ``MAX_ENTRIES`` are removed, so the folder cannot grow without end.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from gpl2py import __version__
from gpl2py.diagnostics import Diagnostic, Severity
from gpl2py.project import Project
from gpl2py.source import Position, Span

ENTRY_FILE = "entry.json"
ENTRY_FORMAT = 1
_KEY_CHARS = 24
MAX_ENTRIES = 64


def default_cache_root() -> Path:
    """The cache folder used when no ``--cache-dir`` is given (see module docstring)."""
    explicit = os.environ.get("GPL2PY_CACHE_DIR")
    if explicit:
        return Path(explicit)
    xdg = os.environ.get("XDG_CACHE_HOME")
    base = Path(xdg) if xdg else Path.home() / ".cache"
    return base / "gpl2py"


def _tool_fingerprint() -> str:
    """Hash of the names, sizes and times of gpl2py's and gplrt's Python files (see module docstring)."""
    import gpl2py
    import gplrt

    h = hashlib.sha256()
    for pkg in (gpl2py, gplrt):
        root = Path(pkg.__file__).resolve().parent
        for path in sorted(root.rglob("*.py")):
            try:
                st = path.stat()
            except OSError:
                continue
            h.update(f"{path.relative_to(root)}\0{st.st_size}\0{st.st_mtime_ns}\0".encode())
    return h.hexdigest()


_FINGERPRINT: str | None = None


def tool_fingerprint() -> str:
    global _FINGERPRINT
    if _FINGERPRINT is None:
        _FINGERPRINT = _tool_fingerprint()
    return _FINGERPRINT


def cache_key(project: Project, options: dict[str, object]) -> str:
    """The key of a project's translation (see module docstring)."""
    h = hashlib.sha256()
    h.update(f"gpl2py {__version__}\0".encode())
    h.update(tool_fingerprint().encode())
    h.update(json.dumps(options, sort_keys=True).encode())
    for f in project.files():
        h.update(b"\0file\0" + f.path.encode("utf-8", "surrogateescape") + b"\0")
        h.update(f.text.encode("utf-8", "surrogateescape"))
    return h.hexdigest()


@dataclass
class Entry:
    """One cached translation: ``folder / package`` is the importable package."""

    folder: Path
    key: str
    package: str
    diagnostics: list[Diagnostic] = field(default_factory=list)
    files: int = 0
    lines: int = 0

    @property
    def package_dir(self) -> Path:
        return self.folder / self.package


def _diag_to_dict(d: Diagnostic) -> dict[str, object]:
    span = None
    if d.span is not None:
        span = [d.span.start.file, d.span.start.line, d.span.start.col, d.span.end_line, d.span.end_col]
    return {"severity": d.severity.value, "code": d.code, "message": d.message, "span": span}


def _diag_from_dict(data: dict[str, object]) -> Diagnostic:
    raw = data.get("span")
    span = None
    if isinstance(raw, list) and len(raw) == 5:
        span = Span(Position(str(raw[0]), int(raw[1]), int(raw[2])), int(raw[3]), int(raw[4]))
    return Diagnostic(Severity(str(data["severity"])), str(data["code"]), str(data["message"]), span)


class Cache:
    """A cache folder (see module docstring)."""

    def __init__(self, root: str | os.PathLike[str] | None = None) -> None:
        self.root = Path(root) if root is not None else default_cache_root()

    def folder_for(self, key: str) -> Path:
        return self.root / key[:_KEY_CHARS]

    def lookup(self, key: str) -> Entry | None:
        """The entry for ``key``, or None when there is none (or it is unreadable)."""
        folder = self.folder_for(key)
        try:
            data = json.loads((folder / ENTRY_FILE).read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None
        if data.get("format") != ENTRY_FORMAT or data.get("key") != key:
            return None
        entry = Entry(
            folder=folder,
            key=key,
            package=str(data["package"]),
            diagnostics=[_diag_from_dict(d) for d in data.get("diagnostics", [])],
            files=int(data.get("files", 0)),
            lines=int(data.get("lines", 0)),
        )
        if not (entry.package_dir / "__init__.py").is_file():
            return None
        return entry

    def store(self, key: str, package: str, files: dict[str, str], diagnostics: list[Diagnostic],
              counts: tuple[int, int]) -> Entry:
        """Write a new entry atomically; returns it (an entry a concurrent run stored first wins).

        ``files`` maps paths relative to the entry folder (``<package>/module.py``) to their text;
        ``counts`` is (source files, source lines).  Raises OSError when the cache is not writable.
        """
        self.root.mkdir(parents=True, exist_ok=True)
        target = self.folder_for(key)
        tmp = Path(tempfile.mkdtemp(prefix=".tmp-", dir=self.root))
        try:
            for rel, text in sorted(files.items()):
                path = tmp / rel
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_text(text, encoding="utf-8", newline="\n")
            meta = {
                "format": ENTRY_FORMAT,
                "key": key,
                "gpl2py": __version__,
                "package": package,
                "files": counts[0],
                "lines": counts[1],
                "diagnostics": [_diag_to_dict(d) for d in diagnostics],
            }
            (tmp / ENTRY_FILE).write_text(json.dumps(meta, indent=1), encoding="utf-8")
            try:
                os.replace(tmp, target)
            except OSError:
                if self.lookup(key) is None:  # not a lost race: a stale or broken entry
                    shutil.rmtree(target, ignore_errors=True)
                    os.replace(tmp, target)
        finally:
            if tmp.exists():
                shutil.rmtree(tmp, ignore_errors=True)
        entry = self.lookup(key)
        if entry is None:
            raise OSError(f"cache entry {target} could not be read back")
        self.prune(keep=MAX_ENTRIES, protect=target)
        return entry

    def prune(self, keep: int = MAX_ENTRIES, protect: Path | None = None) -> list[Path]:
        """Remove the least recently written entries beyond ``keep``; returns the removed folders."""
        entries = []
        for folder in self.root.iterdir():
            stamp = folder / ENTRY_FILE
            if folder.name.startswith(".") or folder == protect or not stamp.is_file():
                continue
            try:
                entries.append((stamp.stat().st_mtime_ns, folder))
            except OSError:
                continue
        entries.sort(reverse=True)
        removed = [folder for _, folder in entries[max(keep - (protect is not None), 0):]]
        for folder in removed:
            shutil.rmtree(folder, ignore_errors=True)
        return removed

"""Host file operations confined to one folder: no link is followed, no shared file is opened.

Why: GPL programs, the file names they use, their project files and the flash folder's contents are
untrusted (docs/security.md, "Files").  Checking a path and then opening it (``Path.resolve``, a
prefix test, then ``open``) leaves holes: ``open`` follows whatever the last name is at the moment
it runs (a link planted after the check, a link at a temporary file's name), a hard link is an
ordinary file to every check yet its data lives elsewhere, and a FIFO blocks the opening thread.
Here the check *is* the open:

* the root is opened once (:class:`Sandbox` keeps its directory descriptor), so renaming or
  replacing the root folder during a run cannot redirect a later operation;
* every path is walked from that descriptor one name at a time (``openat`` with
  ``O_DIRECTORY | O_NOFOLLOW``): a symbolic link anywhere — to a file or a folder, dangling, a
  loop, the device folder itself — is refused;
* only regular files with one hard link are opened: checked before opening (``fstatat``, so a FIFO
  or a device node is never opened), opened with ``O_NOFOLLOW | O_NONBLOCK``, and checked again on
  the descriptor (same inode); a file is emptied only after that check (``ftruncate``, never
  ``O_TRUNC``), so a refused file is left untouched;
* temporary files are created exclusively (``O_EXCL``) in the target's folder and renamed over the
  target by descriptor (``renameat``): a link waiting at the temporary's name is removed, never
  written through, and the rename replaces a link at the target instead of following it.

Refusals are GPL exceptions with the controller's codes, the same for every operation: a link (or a
file with several hard links) -> -208 *Protection error*; a FIFO, socket or device -> -521 *Invalid
file type*.  What else the host reports (missing, not a folder, disk full) stays an ``OSError``:
the caller knows which file error its operation gives (-508, -509, -512 ...).

Left open, by design: a process of the same user that moves a folder out of the sandbox while an
operation is inside it (it already has the access it would gain), and mounts (they need root).
POSIX only (Linux, macOS): ``openat``, ``O_NOFOLLOW`` and ``dir_fd`` are what this module is made of.
"""

from __future__ import annotations

import errno
import os
import shutil
import stat
import weakref
from collections.abc import Sequence
from dataclasses import dataclass
from enum import Enum
from pathlib import Path
from typing import BinaryIO, Literal

from gplrt.lang.errors import INVALID_FILE_TYPE, PROTECTION_ERROR, GplException


_DIR_FLAGS = os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC
_FILE_FLAGS = os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC
_OPEN_FLAGS = {
    "r": os.O_RDONLY,
    "w": os.O_WRONLY | os.O_CREAT,  # emptied by ftruncate once the file is known to be ours
    "a": os.O_WRONLY | os.O_CREAT | os.O_APPEND,
    "x": os.O_WRONLY | os.O_CREAT | os.O_EXCL,
}
_PY_MODES = {"r": "rb", "w": "wb", "a": "ab", "x": "wb"}
Mode = Literal["r", "w", "a", "x"]


class Kind(Enum):
    """What a folder entry is, read without following links (a listing shows files and folders)."""

    FILE = "file"
    FOLDER = "folder"
    OTHER = "other"  # a link, FIFO, socket or device: never listed, never opened


class Sandbox:
    """One host folder, reached only through the descriptor opened when the sandbox is made.

    ``root`` is the caller's own choice (a command-line option, a notebook argument) and may itself
    be reached through links; only what lies below it is untrusted.  The descriptor is closed when
    the sandbox is garbage-collected or :meth:`close` is called; files opened through it stay open.
    """

    def __init__(self, root: Path) -> None:
        self.root = root
        self.fd = os.open(root, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
        self._closer = weakref.finalize(self, os.close, self.fd)

    def path(self, *parts: str) -> SandboxPath:
        """The entry ``root/parts...``; each part is one plain name (no ``/``, not ``..``)."""
        for part in parts:
            if not part or part in (".", "..") or "/" in part or "\0" in part:
                raise ValueError(f"not a plain file name: {part!r}")
        if not parts:
            raise ValueError("a sandbox path names at least one entry below the root")
        return SandboxPath(self, parts)

    def entries(self) -> list[tuple[str, Kind]]:
        """Names and kinds directly in the root, unsorted (links and special files: ``OTHER``)."""
        with os.scandir(self.fd) as found:  # CPython reads a copy of the descriptor, rewound after
            return [(e.name, _kind(e)) for e in found]

    def close(self) -> None:
        self._closer()


@dataclass(frozen=True, slots=True)
class SandboxPath:
    """An entry below a :class:`Sandbox` root; every operation walks to it afresh, link-free."""

    box: Sandbox
    parts: tuple[str, ...]

    @property
    def name(self) -> str:
        return self.parts[-1]

    @property
    def host(self) -> Path:
        """The host path, for messages only: opening it would follow links."""
        return self.box.root.joinpath(*self.parts)

    @property
    def is_top(self) -> bool:
        """A folder directly below the root (the controller's device folders)."""
        return len(self.parts) == 1

    # -- queries ---------------------------------------------------------------------------------

    def lstat(self) -> os.stat_result | None:
        """The entry's own status (a link is not followed), or None when nothing is there."""
        try:
            folder = self._walk(self.parts[:-1])
        except (FileNotFoundError, NotADirectoryError):
            return None
        try:
            return _lstat(folder, self.name)
        finally:
            os.close(folder)

    def file_size(self) -> int:
        """Size of a regular file that may be opened (the checks of :meth:`open`)."""
        folder = self._walk(self.parts[:-1])
        try:
            found = _lstat(folder, self.name)
            if found is None:
                raise FileNotFoundError(errno.ENOENT, "No such file", str(self.host))
            _check_file(found, self)
            return found.st_size
        finally:
            os.close(folder)

    def entries(self) -> list[tuple[str, Kind]]:
        """Names and kinds in this folder, unsorted; links and special files are ``OTHER``."""
        folder = self._walk(self.parts)
        try:
            with os.scandir(folder) as found:
                return [(e.name, _kind(e)) for e in found]
        finally:
            os.close(folder)

    # -- files -----------------------------------------------------------------------------------

    def open(self, mode: Mode = "r") -> BinaryIO:
        """Open a regular file with one link: ``r`` read, ``w`` create or empty, ``a`` append,
        ``x`` create a new file (FileExistsError if the name is taken)."""
        folder = self._walk(self.parts[:-1])
        try:
            fd = _open_file(folder, self, mode)
        finally:
            os.close(folder)
        return os.fdopen(fd, _PY_MODES[mode])  # type: ignore[return-value]

    def read_bytes(self) -> bytes:
        with self.open("r") as stream:
            return stream.read()

    def write_bytes(self, data: bytes) -> None:
        with self.open("w") as stream:
            stream.write(data)

    def replace(self, data: bytes) -> None:
        """Write ``data`` to a new temporary ``.<name>.new`` and rename it over this name, so a
        reader sees the old file or the new one, never half of it (NVRAM records, installs)."""
        folder = self._walk(self.parts[:-1])
        try:
            temp = "." + self.name + ".new"  # a leading dot: never a controller file name
            fd = _create_temp(folder, temp)
            try:
                with os.fdopen(fd, "wb") as stream:
                    stream.write(data)
                os.rename(temp, self.name, src_dir_fd=folder, dst_dir_fd=folder)
            except BaseException:
                _forget(folder, temp)
                raise
        finally:
            os.close(folder)

    def unlink(self) -> None:
        """Delete a file that :meth:`open` would open (a link or special file is refused)."""
        folder = self._walk(self.parts[:-1])
        try:
            found = _lstat(folder, self.name)
            if found is None:
                raise FileNotFoundError(errno.ENOENT, "No such file", str(self.host))
            _check_file(found, self)
            os.unlink(self.name, dir_fd=folder)
        finally:
            os.close(folder)

    def rename_to(self, target: SandboxPath) -> None:
        """Rename this file or folder to ``target`` (same sandbox), both walked link-free: a link
        here is refused (-208), never moved; a link waiting at ``target`` is replaced, as
        ``renameat`` does, never followed (the FTP server's RNFR/RNTO)."""
        if target.box is not self.box:
            raise ValueError("a rename stays in one sandbox")
        source = self._walk(self.parts[:-1])
        try:
            found = _lstat(source, self.name)
            if found is None:
                raise FileNotFoundError(errno.ENOENT, "No such file", str(self.host))
            if not stat.S_ISDIR(found.st_mode):
                _check_file(found, self)
            destination = target._walk(target.parts[:-1])
            try:
                os.rename(self.name, target.name, src_dir_fd=source, dst_dir_fd=destination)
            finally:
                os.close(destination)
        finally:
            os.close(source)

    # -- folders ---------------------------------------------------------------------------------

    def mkdir(self) -> None:
        """Create this folder and any missing parents; an existing folder is fine."""
        os.close(self._walk(self.parts, create=True))

    def rmdir(self) -> None:
        """Delete this (empty) folder; a link is refused, not removed."""
        folder = self._walk(self.parts[:-1])
        try:
            found = _lstat(folder, self.name)
            if found is not None and stat.S_ISLNK(found.st_mode):
                raise _link_refused(self)
            os.rmdir(self.name, dir_fd=folder)
        finally:
            os.close(folder)

    def ensure_folder(self) -> None:
        """Create the folder if nothing has the name; whatever else is there is left alone (and
        refused when used)."""
        if self.lstat() is None:
            try:
                self.mkdir()
            except FileExistsError:
                pass

    def recreate_folder(self) -> None:
        """Remove whatever has this name (a folder with its contents, a link, a file) and make an
        empty folder: ``shutil.rmtree`` by descriptor never follows a link out."""
        folder = self._walk(self.parts[:-1])
        try:
            found = _lstat(folder, self.name)
            if found is not None and stat.S_ISDIR(found.st_mode):
                shutil.rmtree(self.name, dir_fd=folder)
            elif found is not None:
                os.unlink(self.name, dir_fd=folder)
            os.mkdir(self.name, dir_fd=folder)
        finally:
            os.close(folder)

    # -- the walk --------------------------------------------------------------------------------

    def _walk(self, names: Sequence[str], *, create: bool = False) -> int:
        """A new descriptor of the folder ``names`` below the root (the caller closes it).

        Each name is opened relative to the previous folder with ``O_NOFOLLOW``; ``create`` makes
        missing folders on the way."""
        fd = os.dup(self.box.fd)
        try:
            for name in names:
                child = _open_folder(fd, name, self, create)
                os.close(fd)
                fd = child
        except BaseException:
            os.close(fd)
            raise
        return fd


def _open_folder(parent: int, name: str, where: SandboxPath, create: bool) -> int:
    try:
        return os.open(name, _DIR_FLAGS, dir_fd=parent)
    except FileNotFoundError:
        if not create:
            raise
    except OSError as exc:
        if exc.errno in (errno.ELOOP, errno.ENOTDIR, errno.EMLINK):
            found = _lstat(parent, name)
            if found is not None and stat.S_ISLNK(found.st_mode):
                raise _link_refused(where) from None
            if create:
                raise FileExistsError(errno.EEXIST, "A file is in the way", str(where.host)) from None
        raise
    try:
        os.mkdir(name, dir_fd=parent)
    except FileExistsError:
        pass  # made meanwhile by someone else: the open below checks what it is
    return _open_folder(parent, name, where, False)


def _open_file(folder: int, where: SandboxPath, mode: Mode) -> int:
    """Open ``where``'s name in ``folder`` for ``mode`` after and before checking it (module doc)."""
    name = where.name
    before = _lstat(folder, name)
    if before is not None:
        if mode == "x":
            raise FileExistsError(errno.EEXIST, "File exists", str(where.host))
        _check_file(before, where)
    elif mode == "r":
        raise FileNotFoundError(errno.ENOENT, "No such file", str(where.host))
    try:
        fd = os.open(name, _OPEN_FLAGS[mode] | _FILE_FLAGS, 0o666, dir_fd=folder)
    except OSError as exc:
        if exc.errno in (errno.ELOOP, errno.EMLINK):
            raise _link_refused(where) from None  # a link put there since the check
        if exc.errno == errno.ENXIO:
            raise _not_a_file(where) from None  # a FIFO without a reader, a socket
        raise
    try:
        after = os.fstat(fd)
        _check_file(after, where)
        if before is not None and (after.st_dev, after.st_ino) != (before.st_dev, before.st_ino):
            raise _link_refused(where)  # the name was swapped between the check and the open
        if mode == "w":
            os.ftruncate(fd, 0)
    except BaseException:
        os.close(fd)
        raise
    return fd


def _create_temp(folder: int, temp: str) -> int:
    """A new, empty temporary file; whatever had its name (a stale temporary, a planted link) is
    removed first, never opened."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | _FILE_FLAGS
    try:
        return os.open(temp, flags, 0o666, dir_fd=folder)
    except FileExistsError:
        try:
            os.unlink(temp, dir_fd=folder)
        except IsADirectoryError:  # EISDIR would read as "the file is a folder": it is not
            raise FileExistsError(errno.EEXIST, "A folder has the temporary file's name", temp) from None
        return os.open(temp, flags, 0o666, dir_fd=folder)


def _forget(folder: int, temp: str) -> None:
    try:
        os.unlink(temp, dir_fd=folder)
    except OSError:
        pass


def _lstat(folder: int, name: str) -> os.stat_result | None:
    try:
        return os.stat(name, dir_fd=folder, follow_symlinks=False)
    except FileNotFoundError:
        return None


def _check_file(found: os.stat_result, where: SandboxPath) -> None:
    """Only a regular file with one hard link may be read, written or deleted."""
    mode = found.st_mode
    if stat.S_ISREG(mode):
        if found.st_nlink > 1:
            raise GplException(
                PROTECTION_ERROR,
                detail=f"{where.host.name}: a file with {found.st_nlink} hard links may be shared with a file "
                "outside the controller's disks",
            )
        return
    if stat.S_ISDIR(mode):
        raise IsADirectoryError(errno.EISDIR, "Is a directory", str(where.host))
    if stat.S_ISLNK(mode):
        raise _link_refused(where)
    raise _not_a_file(where)


def _kind(entry: os.DirEntry[str]) -> Kind:
    if entry.is_file(follow_symlinks=False):
        return Kind.FILE
    if entry.is_dir(follow_symlinks=False):
        return Kind.FOLDER
    return Kind.OTHER


def _link_refused(where: SandboxPath) -> GplException:
    return GplException(
        PROTECTION_ERROR,
        detail=f"{'/'.join(where.parts)}: a symbolic link in the controller's disks is never followed",
    )


def _not_a_file(where: SandboxPath) -> GplException:
    return GplException(INVALID_FILE_TYPE, detail=f"{'/'.join(where.parts)} is not a regular file")

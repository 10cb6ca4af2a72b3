"""The controller's FTP server (``gpl2py run --ftp PORT``): its disks, and nothing else.

Labs deploy a project by FTP into ``/flash/projects/<name>/`` (TCS User's Guide §2) and read
``/NVRAM`` files the same way (D1 "FTP Access": "the /NVRAM folder shows up in the top-level FTP
directory").  The protocol is pyftpdlib's (a maintained, complete FTP server: passive and active
data connections, LIST/MLSD, resumable downloads); this module gives it a file system
(:class:`ControllerFS`) that is the session's disks seen through the same rules as the GPL
program's own file access (``gplrt.io.flashroot``, ``gplrt.io.sandbox``; docs/security.md):

* the FTP root ``/`` lists the controller's devices (``flash``, the ``flash2``..``flash8`` that
  exist, ``ROMDISK``, ``NVRAM``); every path below is a controller path, checked by
  ``FlashRoot.resolve`` (no ``..`` past the root — the client's path is normalised first — no
  name with a leading dot, at most 43 characters a name and 255 a path, printable ASCII) and then
  walked from the root's descriptor without following a link;
* a link, a hard-linked file, a FIFO or a device below the root is never listed, opened, deleted
  or renamed (-208, -521), whoever put it there;
* an upload is written through the sandbox (no link followed, no file with several links
  written), at most ``MAX_FILE_BYTES`` a file (the limit of a project's own files) and
  ``FLASH_BYTES`` for everything on a disk device, at most ``MAX_ENTRIES`` files and folders on
  it; an upload that would pass a limit is refused or cut, and what it wrote is removed;
* ``/NVRAM`` is read-only here (its files are records; a GPL program writes them);
* no ``SITE CHMOD``, no ``MFMT``, no ``STOU``, no ``REST`` before an upload.

Replies to a refusal carry the controller's code: ``550 -208 *Protection error*``.  Any user
name and password log in (a controller's FTP asks for them, and a test client sends anonymous):
reaching the port is the permission, which is why it listens on loopback unless ``--listen``.
"""

from __future__ import annotations

import errno
import functools
import io
import logging
import os
import stat as _stat
import threading
import time
from collections.abc import Callable
from typing import Any, BinaryIO

from pyftpdlib.authorizers import DummyAuthorizer
from pyftpdlib.filesystems import AbstractedFS, FilesystemError
from pyftpdlib.handlers import FTPHandler
from pyftpdlib.servers import FTPServer

from gplrt.io import nvram
from gplrt.io.flashroot import DISK_DEVICES, ControllerPath, DeviceKind, Disks
from gplrt.io.project_files import MAX_FILE_BYTES
from gplrt.io.sandbox import Kind, SandboxPath
from gplrt.lang.errors import DEVICE_FULL, READ_ONLY, TOO_MANY, UNDEFINED_DEVICE, GplException

__all__ = ["FLASH_BYTES", "MAX_ENTRIES", "ControllerFS", "FtpService"]

#: What all of a disk device's files may hold, added up [P: a PreciseFlex user flash disk is tens
#: of megabytes (DataID 123); this bounds what FTP can make the host store].
FLASH_BYTES = 64 * 1024 * 1024
#: Files and folders a disk device may hold before uploads and new folders are refused.
MAX_ENTRIES = 10_000
#: Connections served at once (further ones are told so and closed by pyftpdlib).
MAX_CLIENTS = 8
_PERMS = "elradfmw"  # no M (chmod) or T (set the time)

logging.getLogger("pyftpdlib").addHandler(logging.NullHandler())
logging.getLogger("pyftpdlib").propagate = False


def _refused(exc: GplException) -> FilesystemError:
    """pyftpdlib answers ``550 <text>``: the text is the controller's code and message."""
    text = f"{exc.ErrorCode} {exc.Message()}"
    return FilesystemError(f"{text} - {exc.detail}" if exc.detail else text)


def _gpl_refusals(method: Callable[..., Any]) -> Callable[..., Any]:
    """Any refusal of the sandbox below the method (a link on the way, -208) reaches pyftpdlib as
    the FilesystemError it answers with ``550``, never as an internal error."""

    @functools.wraps(method)
    def checked(*args: Any, **kwargs: Any) -> Any:
        try:
            return method(*args, **kwargs)
        except GplException as exc:
            raise _refused(exc) from None

    return checked


class _Quota:
    """What uploads in progress may still write, shared by one server's connections."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.in_flight = 0


class _LimitedWriter(io.RawIOBase):
    """An upload's file: writes past ``allowed`` bytes fail with ENOSPC/EFBIG (pyftpdlib then
    ends the transfer with ``426``), and the file is removed as it is closed."""

    def __init__(self, file: BinaryIO, name: str, allowed: int, quota: _Quota, full: int,
                 discard: Callable[[], None]) -> None:
        super().__init__()
        self._file = file
        self.name = name
        self._allowed = allowed
        self._written = 0
        self._quota = quota
        self._full = full  # errno for passing the limit
        self._discard = discard  # removes the file: it passed a limit
        self._over = False

    def writable(self) -> bool:
        return True

    def write(self, data: Any) -> int:
        if self._written + len(data) > self._allowed:
            self._over = True
            raise OSError(self._full, "-323 *Device full*" if self._full == errno.ENOSPC
                          else f"a file on the controller is at most {MAX_FILE_BYTES} bytes")
        self._written += len(data)
        return self._file.write(data)

    def close(self) -> None:
        if not self.closed:
            with self._quota.lock:
                self._quota.in_flight -= self._allowed
            self._file.close()
            if self._over:  # removed before pyftpdlib answers, so the client never sees it
                try:
                    self._discard()
                except (OSError, GplException):
                    pass
        super().close()


class ControllerFS(AbstractedFS):
    """pyftpdlib's view of the files: the session's disks (module docstring).

    pyftpdlib hands every method an "fs path", which here is the normalised controller path
    itself (``ftp2fs`` of the base class with the root ``/``); ``/`` is the list of devices.
    """

    def __init__(self, root: str, cmd_channel: Any) -> None:
        super().__init__("/", cmd_channel)
        self.disks: Disks = cmd_channel.disks
        self.quota: _Quota = cmd_channel.quota

    # -- paths ----------------------------------------------------------------------------------

    def _where(self, path: str) -> ControllerPath:
        try:
            where = self.disks.root().resolve(path)
        except GplException as exc:
            raise _refused(exc) from None
        if where.file is None:
            raise _refused(GplException(UNDEFINED_DEVICE, detail=f"{path} is a serial device"))
        return where

    def _file(self, path: str) -> SandboxPath:
        file = self._where(path).file
        assert file is not None
        return file

    def validpath(self, path: str) -> bool:
        """Inside the disks: ``/`` or a path on a device (a host path like ``/etc`` is not)."""
        if path == "/":
            return True
        try:
            self.disks.root().resolve(path)
        except GplException as exc:
            return exc.ErrorCode != UNDEFINED_DEVICE
        return True

    def realpath(self, path: str) -> str:
        return path  # nothing on the disks is a link

    def _devices(self) -> list[str]:
        """The device folders at the FTP root: the flash sub-partitions only when they exist."""
        box = self.disks.root().box
        present = {name for name, kind in box.entries() if kind is Kind.FOLDER}
        return [d for d in DISK_DEVICES.values() if d in present and (not d.startswith("flash") or d == "flash"
                                                                      or any(box.path(d).entries()))]

    # -- queries ----------------------------------------------------------------------------------

    @_gpl_refusals
    def lstat(self, path: str) -> os.stat_result:
        if path == "/":
            now = time.time()
            return os.stat_result((_stat.S_IFDIR | 0o755, 0, 0, 2, 0, 0, 0, now, now, now))
        file = self._file(path)
        try:
            found = file.lstat()
        except GplException as exc:
            raise _refused(exc) from None
        if found is None:
            raise FileNotFoundError(errno.ENOENT, "No such file or folder", path)
        if not (_stat.S_ISDIR(found.st_mode) or (_stat.S_ISREG(found.st_mode) and found.st_nlink == 1)):
            # a link, a file with several links, a FIFO or a device: as if not there
            raise FileNotFoundError(errno.ENOENT, "No such file or folder", path)
        return found

    stat = lstat

    def isfile(self, path: str) -> bool:
        try:
            return _stat.S_ISREG(self.lstat(path).st_mode)
        except (OSError, FilesystemError):
            return False

    def isdir(self, path: str) -> bool:
        try:
            return _stat.S_ISDIR(self.lstat(path).st_mode)
        except (OSError, FilesystemError):
            return False

    def islink(self, path: str) -> bool:
        return False

    def lexists(self, path: str) -> bool:
        try:
            self.lstat(path)
        except (OSError, FilesystemError):
            return False
        return True

    def getsize(self, path: str) -> int:
        return self.lstat(path).st_size

    def getmtime(self, path: str) -> float:
        return self.lstat(path).st_mtime

    @_gpl_refusals
    def listdir(self, path: str) -> list[str]:
        if path == "/":
            return self._devices()
        folder = self._file(path)
        try:
            entries = folder.entries()
        except GplException as exc:
            raise _refused(exc) from None
        shown = []
        for name, kind in entries:
            if kind is Kind.OTHER or name.startswith("."):
                continue
            if kind is Kind.FILE:  # a file with several hard links may be one outside: not shown
                found = SandboxPath(folder.box, (*folder.parts, name)).lstat()
                if found is None or found.st_nlink != 1:
                    continue
            shown.append(name)
        return sorted(shown)

    listdirinfo = listdir

    @_gpl_refusals
    def chdir(self, path: str) -> None:
        if not self.isdir(path):
            raise FilesystemError(f"not a folder: {path}")
        self.cwd = path

    def readlink(self, path: str) -> str:
        raise FilesystemError("the controller's disks have no links")

    def get_user_by_uid(self, uid: int) -> str:
        return "controller"

    def get_group_by_gid(self, gid: int) -> str:
        return "controller"

    # -- changes ------------------------------------------------------------------------------------

    def _writable(self, path: str) -> ControllerPath:
        where = self._where(path)
        if where.kind is DeviceKind.NVRAM:
            raise _refused(GplException(READ_ONLY, detail="/NVRAM files are written by the program, not FTP"))
        if where.file is not None and where.file.is_top:
            raise _refused(GplException(READ_ONLY, detail=f"/{where.device} is a device"))
        return where

    @_gpl_refusals
    def open(self, filename: str, mode: str) -> Any:
        if "r" in mode and "+" not in mode:
            return self._open_read(filename)
        if mode not in ("wb", "ab"):
            raise FilesystemError("an upload cannot resume (REST) on the controller")
        where = self._writable(filename)
        assert where.file is not None
        allowed, full = self._reserve(where, mode == "ab")
        try:
            stream = where.file.open("a" if mode == "ab" else "w")
        except GplException as exc:
            self._release(allowed)
            raise _refused(exc) from None
        except BaseException:
            self._release(allowed)
            raise
        return _LimitedWriter(stream, filename, allowed, self.quota, full, where.file.unlink)

    def _open_read(self, filename: str) -> Any:
        where = self._where(filename)
        assert where.file is not None
        try:
            if where.kind is DeviceKind.NVRAM:
                data = io.BytesIO(nvram.read_data(where.file))
                data.name = filename  # type: ignore[attr-defined]
                return data
            return where.file.open("r")
        except GplException as exc:
            raise _refused(exc) from None

    def _reserve(self, where: ControllerPath, append: bool) -> tuple[int, int]:
        """How many bytes this upload may write (file and device limits, less what the uploads in
        progress reserved), reserved until its file is closed; and the errno for passing it."""
        assert where.file is not None
        used, entries = _usage(where.file.box.path(where.file.parts[0]))
        old = where.file.lstat()
        has = old.st_size if old is not None and _stat.S_ISREG(old.st_mode) else 0
        if old is None and entries >= MAX_ENTRIES:
            raise _refused(GplException(TOO_MANY, detail=f"/{where.device} holds {MAX_ENTRIES} files and folders"))
        with self.quota.lock:
            room = FLASH_BYTES - (used - has) - self.quota.in_flight - (has if append else 0)
            per_file = MAX_FILE_BYTES - (has if append else 0)
            allowed = max(0, min(room, per_file))
            if allowed <= 0 and room <= 0:
                raise _refused(GplException(DEVICE_FULL, detail=f"/{where.device} is full"))
            self.quota.in_flight += allowed
        return allowed, errno.ENOSPC if room < per_file else errno.EFBIG

    def _release(self, allowed: int) -> None:
        with self.quota.lock:
            self.quota.in_flight -= allowed

    def mkstemp(self, suffix: str = "", prefix: str = "", dir: str | None = None, mode: str = "wb") -> Any:
        raise FilesystemError("STOU is not supported: name the file")

    @_gpl_refusals
    def mkdir(self, path: str) -> None:
        where = self._writable(path)
        assert where.file is not None
        if where.file.lstat() is not None:
            raise FileExistsError(errno.EEXIST, "File exists", path)
        _used, entries = _usage(where.file.box.path(where.file.parts[0]))
        if entries >= MAX_ENTRIES:
            raise _refused(GplException(TOO_MANY, detail=f"/{where.device} holds {MAX_ENTRIES} files and folders"))
        try:
            where.file.mkdir()
        except GplException as exc:
            raise _refused(exc) from None

    @_gpl_refusals
    def rmdir(self, path: str) -> None:
        where = self._writable(path)
        assert where.file is not None
        try:
            where.file.rmdir()
        except GplException as exc:
            raise _refused(exc) from None

    @_gpl_refusals
    def remove(self, path: str) -> None:
        where = self._writable(path)
        assert where.file is not None
        try:
            where.file.unlink()
        except GplException as exc:
            raise _refused(exc) from None

    @_gpl_refusals
    def rename(self, src: str, dst: str) -> None:
        source, target = self._writable(src), self._writable(dst)
        assert source.file is not None and target.file is not None
        try:
            source.file.rename_to(target.file)
        except GplException as exc:
            raise _refused(exc) from None

    def chmod(self, path: str, mode: int) -> None:
        raise FilesystemError("the controller's files have no modes")

    def utime(self, path: str, timeval: float) -> None:
        raise FilesystemError("the controller's files keep their own times")


def _usage(device: SandboxPath) -> tuple[int, int]:
    """Bytes in regular files, and entries, below a device folder (links and the like are not
    counted: nothing can read them).  Stops counting at ``MAX_ENTRIES``."""
    total = count = 0
    folders = [device]
    while folders and count < MAX_ENTRIES:
        folder = folders.pop()
        try:
            entries = folder.entries()
        except (OSError, GplException):
            continue
        for name, kind in entries:
            count += 1
            entry = SandboxPath(folder.box, (*folder.parts, name))
            if kind is Kind.FOLDER:
                folders.append(entry)
            elif kind is Kind.FILE:
                found = entry.lstat()
                total += found.st_size if found is not None else 0
    return total, count


class _AnyUser(DummyAuthorizer):
    """Every user name and password logs in, with the same rights (module docstring)."""

    def validate_authentication(self, username: str, password: str, handler: Any) -> None:
        return None

    def has_user(self, username: str) -> bool:
        return True

    def get_home_dir(self, username: str) -> str:
        return "/"

    def get_perms(self, username: str) -> str:
        return _PERMS

    def has_perm(self, username: str, perm: str, path: str | None = None) -> bool:
        return perm in _PERMS

    def get_msg_login(self, username: str) -> str:
        return "Logged in to the simulated controller's disks."

    def get_msg_quit(self, username: str) -> str:
        return "Goodbye."


class _Handler(FTPHandler):
    abstracted_fs = ControllerFS
    authorizer = _AnyUser()
    banner = "gplrt simulated controller FTP"
    use_sendfile = False  # files are read through the sandbox's descriptors, never by name
    permit_foreign_addresses = False  # data connections go back to the client only (no FXP)
    disks: Disks
    quota: _Quota

    def on_incomplete_file_received(self, file: str) -> None:
        """An upload cut short (a limit, the client went away): what it wrote is removed."""
        try:
            self.fs.remove(file)
        except (OSError, FilesystemError):
            pass


class FtpService:
    """One session's FTP server, served from a background thread."""

    def __init__(self, disks: Disks, port: int, host: str) -> None:
        handler = type("ControllerFtpHandler", (_Handler,), {"disks": disks, "quota": _Quota()})
        self._server = FTPServer((host, port), handler)
        self._server.max_cons = MAX_CLIENTS + 1  # pyftpdlib counts its listening socket too
        self._server.max_cons_per_ip = MAX_CLIENTS
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._serve, name="gplrt-ftp", daemon=True)

    @property
    def address(self) -> tuple[str, int]:
        host, port = self._server.address[:2]
        return str(host), int(port)

    def start(self) -> FtpService:
        self._thread.start()
        return self

    def _serve(self) -> None:
        try:
            while not self._stop.is_set():
                self._server.serve_forever(timeout=0.2, blocking=False, handle_exit=False)
        finally:
            self._server.close_all()

    def close(self) -> None:
        self._stop.set()
        self._thread.join(2.0)

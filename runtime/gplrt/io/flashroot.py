"""Controller paths (``/flash/...``, ``/ROMDISK/...``, ``/NVRAM/...``) mapped into a sandbox folder.

The simulated controller's disks live under one host folder, :attr:`FlashRoot.root`:

    /flash/a/b.txt      -> <root>/flash/a/b.txt       (permanent user flash disk)
    /flash2 .. /flash8  -> <root>/flash2 ..            (optional sub-partitions, D0:3812-3813)
    /ROMDISK/x          -> <root>/ROMDISK/x            (RAM disk, cleared when a session starts)
    /NVRAM/file1        -> <root>/NVRAM/file1          (record store, see ``nvram.py``)

``/dev/comN`` is not a file: :func:`classify` reports it as a serial device for ``serial.py``.

Device names are matched case-insensitively (``/ROMDISK`` and ``/romdisk``); file and folder names
are case-sensitive, as on the controller (D0:3620-3624).

Each session has its own disks (:class:`Disks`, ``Session.files``): its flash root, and the folder
its relative names resolve in.  A relative name (``Tcs.gpo``) is relative to the running project's
folder, as on a controller: ``/flash/projects/<project>/`` once the project's files are installed
there (``gplrt.io.project_files``, :meth:`Disks.set_working_folder`); without a running project it
is -301.

Refusals, each with the controller code that fits best (the manual names none for this case):

* a component ``..`` or ``.`` or any name with a leading ``.``, an empty name, a name longer than
  43 characters, or a non-printable character -> **-516 Invalid file name** (D0:3620-3624 forbids
  leading dots, so ``..`` is simply an invalid name on the controller too);
* a path that is not absolute, or whose first component is not a controller device (a host path
  such as ``/etc/passwd`` or ``C:\\x``) -> **-301 Undefined device**;
* a path longer than 255 characters -> **-517 File path too long** (limit chosen by us);
* a symbolic link anywhere on the way (also one that stays inside), or a file with more than one
  hard link -> **-208 Protection error**; a FIFO, socket or device -> **-521 Invalid file type**.
  These are checked when the file is used, by :mod:`gplrt.io.sandbox` (every operation walks from
  the root's descriptor without following links), not here: a check here would be out of date by
  the time the file is opened.

Everything that puts files into the controller's disks goes through :class:`FlashRoot` and the
:class:`~gplrt.io.sandbox.SandboxPath` of a :class:`ControllerPath`, including the copy of a
project's own files into ``/flash/projects/<project>/`` (``gplrt.io.project_files``).
"""

from __future__ import annotations

import tempfile
import threading
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path

from gplrt.io.sandbox import Sandbox, SandboxPath
from gplrt.lang.errors import (
    INVALID_FILE_NAME,
    PATH_TOO_LONG,
    UNDEFINED_DEVICE,
    GplException,
)
from gplrt.session import current_scope, current_session


MAX_NAME = 43
MAX_PATH = 255

#: Disk devices, by lower-case name, with the folder used under the root.
DISK_DEVICES: dict[str, str] = {
    "flash": "flash",
    **{f"flash{n}": f"flash{n}" for n in range(2, 9)},
    "romdisk": "ROMDISK",
    "nvram": "NVRAM",
}


class DeviceKind(Enum):
    DISK = "disk"
    NVRAM = "nvram"
    SERIAL = "serial"


@dataclass(frozen=True)
class ControllerPath:
    """A checked controller path: its device, where it lives in the sandbox, the original text."""

    text: str
    kind: DeviceKind
    device: str  # "flash", "ROMDISK", "NVRAM", or the serial name "com1"
    file: SandboxPath | None  # None for serial devices; every host operation goes through it


@dataclass
class FlashRoot:
    """The sandbox folder holding the simulated controller's disks."""

    root: Path
    box: Sandbox = field(init=False, repr=False)

    def __post_init__(self) -> None:
        self.root = Path(self.root).resolve()
        self.root.mkdir(parents=True, exist_ok=True)
        self.box = Sandbox(self.root)
        for folder in DISK_DEVICES.values():
            # A device folder that is a link or a file is left as it is: using it is refused.
            self.box.path(folder).ensure_folder()

    def clear_romdisk(self) -> None:
        """Empty ``/ROMDISK`` — the RAM disk is lost on every controller restart (D0:3806-3810).

        Whatever has the name is removed without following links (a link planted there is
        removed, its target untouched), then an empty folder is made."""
        self.box.path("ROMDISK").recreate_folder()

    def resolve(self, path: str, working_folder: str | None = None) -> ControllerPath:
        """Check ``path`` and map it onto the sandbox (or onto a serial device); a relative
        ``path`` is relative to the controller folder ``working_folder`` (None: -301)."""
        if not isinstance(path, str):
            raise GplException(INVALID_FILE_NAME, detail=f"path {path!r} is not a String")
        if len(path) > MAX_PATH:
            raise GplException(PATH_TOO_LONG, detail=f"{len(path)} characters: {path[:40]}...")
        if not path.startswith("/"):
            working = working_folder
            if working is None or path == "":
                raise GplException(UNDEFINED_DEVICE, detail=f"{path!r}: a path starts with /device")
            path = f"{working}/{path}"
            if len(path) > MAX_PATH:
                raise GplException(PATH_TOO_LONG, detail=f"{len(path)} characters: {path[:40]}...")
        parts = path.split("/")[1:]
        device = parts[0]
        names = [p for p in parts[1:] if p != ""]  # tolerate "//" and a trailing "/"
        low = device.lower()
        if low == "dev" and names and _is_serial(names[0]):
            if len(names) != 1:
                raise GplException(INVALID_FILE_NAME, detail=path)
            return ControllerPath(path, DeviceKind.SERIAL, names[0].lower(), None)
        if low not in DISK_DEVICES:
            raise GplException(UNDEFINED_DEVICE, detail=f"{path!r}: no device /{device} on the controller")
        for name in names:
            _check_name(name, path)
        kind = DeviceKind.NVRAM if low == "nvram" else DeviceKind.DISK
        # Links are refused when the file is used (sandbox.py), not here: see the module docstring.
        return ControllerPath(path, kind, DISK_DEVICES[low], self.box.path(DISK_DEVICES[low], *names))


def _is_serial(name: str) -> bool:
    return name.lower().startswith("com") and len(name) > 3


def _check_name(name: str, path: str) -> None:
    if name.startswith("."):
        raise GplException(INVALID_FILE_NAME, detail=f"{path!r}: name {name!r} starts with '.'")
    if len(name) > MAX_NAME:
        raise GplException(INVALID_FILE_NAME, detail=f"{path!r}: name longer than {MAX_NAME} characters")
    if any(not (32 <= ord(c) < 127) or c == "\\" for c in name):
        raise GplException(INVALID_FILE_NAME, detail=f"{path!r}: name {name!r} has a non-printable character")


class Disks:
    """One session's disks (``Session.files``): its flash root and the folder relative names
    resolve in.

    ``root_folder`` is the host folder standing in for the controller's disks; without one, a
    temporary folder is made on first use and removed with the session (or at exit).  Every file
    operation of the session's program maps its paths here (:func:`resolve`).
    """

    def __init__(self, root_folder: Path | str | None = None) -> None:
        self.root_folder = Path(root_folder) if root_folder is not None else None
        #: The running project's folder (a controller path) relative names resolve in; None: no
        #: project, relative names are -301.
        self.working_folder: str | None = None
        self._flash: FlashRoot | None = None
        self._temporary: tempfile.TemporaryDirectory[str] | None = None
        self._lock = threading.Lock()

    def root(self) -> FlashRoot:
        """The flash root, made on first use."""
        with self._lock:
            if self._flash is None:
                if self.root_folder is None:
                    self._temporary = tempfile.TemporaryDirectory(prefix="gplrt-flash-")
                    self.root_folder = Path(self._temporary.name)
                self._flash = FlashRoot(self.root_folder)
            return self._flash

    def set_root(self, root: Path | str, *, clear_romdisk: bool = True) -> FlashRoot:
        """Use ``root`` as the disks from now on; ``clear_romdisk``: the RAM disk starts empty, as
        when a controller starts."""
        flash = FlashRoot(Path(root))
        if clear_romdisk:
            flash.clear_romdisk()
        with self._lock:
            self.root_folder, self._flash = flash.root, flash
        return flash

    def set_working_folder(self, folder: str | None) -> None:
        """Resolve relative names against the controller folder ``folder`` (None: refuse them)."""
        self.working_folder = folder.rstrip("/") if folder else None

    def resolve(self, path: str) -> ControllerPath:
        """Check and map a controller path onto these disks."""
        return self.root().resolve(path, self.working_folder)


# -- the calling code's session (gplrt.session) ------------------------------------------------------


def set_working_folder(folder: str | None) -> None:
    """Resolve the current session's relative names against ``folder`` (None: refuse them)."""
    current_session().files.set_working_folder(folder)


def get_working_folder() -> str | None:
    return current_session().files.working_folder


def set_flash_root(root: Path | str, *, clear_romdisk: bool = True) -> FlashRoot:
    """Use ``root`` as the current session's disks from now on (``Simulation(flash_root=...)``
    chooses it when the session is made)."""
    return current_session().files.set_root(root, clear_romdisk=clear_romdisk)


def get_flash_root() -> FlashRoot:
    """The current session's flash root (by default a temporary folder that lives with it)."""
    return current_session().files.root()


def resolve(path: str) -> ControllerPath:
    """Check and map a controller path against the current session's disks; a relative name is
    relative to the calling thread's project folder (``gplrt.session.ProjectScope``: a project the
    console loaded), else to the session's working folder."""
    files = current_session().files
    scope = current_scope()
    if scope is not None:
        return files.root().resolve(path, scope.folder)
    return files.resolve(path)

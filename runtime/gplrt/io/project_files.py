"""The running project's own files on the simulated controller's flash disk.

On a controller a project lives in its folder ``/flash/projects/<project>/``: its sources, its
``Project.gpr`` and whatever data files came with it (TCS's ``Tcs.gpo``), and a relative file name
in the program (``New StreamReader("Tcs.gpo")``) is relative to that folder.
:func:`install_project` puts a project folder's files there and makes that folder the one
relative names resolve against (``gplrt.io.flashroot.Disks.set_working_folder``).  ``gpl2py run``,
``Cell.load`` and ``python -m <package>`` call it before the project starts.

The project folder is untrusted input, read and written under the rules of the flash sandbox
(``gplrt.io.sandbox``, docs/security.md "Files"): only regular files directly in it, with one hard
link, each read through the folder's descriptor without following a link, are installed; links,
hard-linked files (their data may be a file outside), folders, FIFOs, devices, names the
controller would refuse (a leading ``.``, more than 43 characters) and files over
``MAX_FILE_BYTES`` are skipped.  Each file is written by temporary and rename through the flash
sandbox, so a link or hard link waiting at its name in ``/flash`` is replaced, never written
through, and a ``/flash/projects`` that is a link installs nothing; an existing copy is replaced:
installing is the controller's "download the project".
"""

from __future__ import annotations

import os
from pathlib import Path

from gplrt.io import flashroot
from gplrt.io.sandbox import Kind, Sandbox, SandboxPath
from gplrt.lang.errors import FILE_NOT_FOUND, TOO_MANY, GplException
from gplrt.session import current_session

#: Files larger than this are not installed (a project folder is no place for bulk data).
MAX_FILE_BYTES = 16 * 1024 * 1024
#: All of a project's files loaded into memory by the console (``read_controller_folder``).
MAX_PROJECT_BYTES = 4 * MAX_FILE_BYTES
PROJECTS = "/flash/projects"


def read_project_files(folder: str | os.PathLike[str]) -> dict[str, bytes]:
    """The regular files directly in ``folder`` (module docstring: what is skipped), by name."""
    try:
        box = Sandbox(Path(folder))
    except OSError:
        return {}
    try:
        out: dict[str, bytes] = {}
        for name, kind in sorted(box.entries()):
            if kind is not Kind.FILE or name.startswith(".") or len(name) > flashroot.MAX_NAME:
                continue
            data = _read_regular(box.path(name))
            if data is not None:
                out[name] = data
        return out
    finally:
        box.close()


def _read_regular(file: SandboxPath) -> bytes | None:
    """The file's bytes, or None: a link, several hard links, not regular, too big, unreadable."""
    try:
        with file.open("r") as stream:
            size = os.fstat(stream.fileno()).st_size
            if size > MAX_FILE_BYTES:
                return None
            # read(n) allocates n bytes first: ask for the size the file has, then (if it grew
            # meanwhile) for the rest up to the limit, not for the limit every time
            data = stream.read(size + 1)
            if len(data) > size:
                data += stream.read(MAX_FILE_BYTES + 1 - len(data))
    except (OSError, GplException):
        return None
    return data if len(data) <= MAX_FILE_BYTES else None


def read_controller_folder(disks: flashroot.Disks, folder: str) -> dict[str, bytes]:
    """The regular files directly in the controller folder ``folder`` (``/flash/projects/X``), by
    name: what the console's ``Load`` puts in memory.

    The folder is reached through the flash sandbox like every file of the program (no link
    followed, on the way or at a file), and the same files are skipped as when a project is
    installed (module docstring).  A folder that is not there is -508 *File not found*; a link on
    the way -208; more than ``MAX_PROJECT_BYTES`` in all is -207 *Too many*."""
    where = disks.root().resolve(folder)
    if where.file is None or where.kind is not flashroot.DeviceKind.DISK:
        raise GplException(FILE_NOT_FOUND, detail=f"{folder} is not a folder on a disk")
    try:
        entries = where.file.entries()
    except (FileNotFoundError, NotADirectoryError):
        raise GplException(FILE_NOT_FOUND, detail=f"no folder {folder}") from None
    except OSError as exc:
        raise GplException(FILE_NOT_FOUND, detail=f"{folder}: {exc.strerror or exc}") from None
    out: dict[str, bytes] = {}
    total = 0
    for name, kind in sorted(entries):
        if kind is not Kind.FILE or name.startswith(".") or len(name) > flashroot.MAX_NAME:
            continue
        data = _read_regular(SandboxPath(where.file.box, (*where.file.parts, name)))
        if data is None:
            continue
        total += len(data)
        if total > MAX_PROJECT_BYTES:
            raise GplException(TOO_MANY, detail=f"{folder} holds more than {MAX_PROJECT_BYTES} bytes of files")
        out[name] = data
    return out


def project_folder(name: str) -> str | None:
    """``/flash/projects/<name>``, or None when the controller could not hold that name."""
    if not name or name.startswith(".") or len(name) > flashroot.MAX_NAME or "/" in name:
        return None
    return f"{PROJECTS}/{name}"


def install_project(files: dict[str, bytes], name: str, disks: flashroot.Disks | None = None) -> str | None:
    """Write ``files`` into the project folder of ``name`` on ``disks`` (default: the current
    session's) and make it their working folder; returns the folder, or None when ``name``
    cannot be a controller folder."""
    if disks is None:
        disks = current_session().files
    folder = project_folder(name)
    if folder is None:
        return None
    try:
        base = disks.resolve(folder)
        assert base.file is not None
        base.file.mkdir()
    except (OSError, GplException):
        return None  # a link or a file in the way (-208 / not a folder): nothing is written
    for file, data in sorted(files.items()):
        try:
            target = disks.resolve(f"{folder}/{file}")
            assert target.file is not None
            target.file.replace(data)
        except (OSError, GplException):
            continue  # a name the controller refuses, a folder in the way
    disks.set_working_folder(folder)
    return folder


def install_project_folder(folder: str | os.PathLike[str], name: str,
                           disks: flashroot.Disks | None = None) -> str | None:
    """:func:`install_project` of the files of a host project folder."""
    return install_project(read_project_files(folder), name, disks)

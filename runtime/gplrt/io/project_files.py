"""The running project's own files on the simulated controller's flash disk.

On a controller a project lives in its folder ``/flash/projects/<project>/``: its sources, its
``Project.gpr`` and whatever data files came with it (TCS's ``Tcs.gpo``), and a relative file name
in the program (``New StreamReader("Tcs.gpo")``) is relative to that folder.
:func:`install_project` puts a project folder's files there and makes that folder the one
relative names resolve against (``gplrt.io.flashroot.set_working_folder``).  ``gpl2py run``,
``Cell.load`` and ``python -m <package>`` call it before the project starts.

The project folder is untrusted input: only regular files directly in it are installed, each
opened without following a symbolic link (``O_NOFOLLOW``) and checked to be a regular file on
the open descriptor; links, folders, devices and names the controller would refuse (a leading
``.``, more than 43 characters) are skipped, as are files over ``MAX_FILE_BYTES``.  Each file is
written through the flash sandbox (``flashroot.resolve``), whose rules apply as to any GPL write,
and an existing copy is replaced: installing is the controller's "download the project".
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from gplrt.io import flashroot
from gplrt.lang.errors import GplException

#: Files larger than this are not installed (a project folder is no place for bulk data).
MAX_FILE_BYTES = 16 * 1024 * 1024
PROJECTS = "/flash/projects"


def read_project_files(folder: str | os.PathLike[str]) -> dict[str, bytes]:
    """The regular files directly in ``folder`` (module docstring: what is skipped), by name."""
    root = Path(folder)
    out: dict[str, bytes] = {}
    try:
        names = sorted(os.listdir(root))
    except OSError:
        return out
    for name in names:
        if name.startswith(".") or len(name) > flashroot.MAX_NAME:
            continue
        data = _read_regular(root / name)
        if data is not None:
            out[name] = data
    return out


def _read_regular(path: Path) -> bytes | None:
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0))
    except OSError:
        return None  # a link (ELOOP), gone, or unreadable
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode) or info.st_size > MAX_FILE_BYTES:
            return None
        chunks = []
        while chunk := os.read(fd, 1 << 20):
            chunks.append(chunk)
        return b"".join(chunks)
    except OSError:
        return None
    finally:
        os.close(fd)


def project_folder(name: str) -> str | None:
    """``/flash/projects/<name>``, or None when the controller could not hold that name."""
    if not name or name.startswith(".") or len(name) > flashroot.MAX_NAME or "/" in name:
        return None
    return f"{PROJECTS}/{name}"


def install_project(files: dict[str, bytes], name: str) -> str | None:
    """Write ``files`` into the project folder of ``name`` on the current flash root and make it
    the working folder; returns the folder, or None when ``name`` cannot be a controller folder."""
    folder = project_folder(name)
    if folder is None:
        return None
    base = flashroot.resolve(folder)
    assert base.host is not None
    base.host.mkdir(parents=True, exist_ok=True)
    for file, data in sorted(files.items()):
        try:
            target = flashroot.resolve(f"{folder}/{file}")
        except GplException:
            continue  # a name the controller refuses
        assert target.host is not None
        _write_no_follow(target.host, data)
    flashroot.set_working_folder(folder)
    return folder


def install_project_folder(folder: str | os.PathLike[str], name: str) -> str | None:
    """:func:`install_project` of the files of a host project folder."""
    return install_project(read_project_files(folder), name)


def _write_no_follow(host: Path, data: bytes) -> None:
    flags = os.O_WRONLY | os.O_CREAT | os.O_TRUNC | getattr(os, "O_NOFOLLOW", 0)
    try:
        fd = os.open(host, flags, 0o644)
    except OSError:
        return  # a link or a folder in the way: left alone
    try:
        view = memoryview(data)
        while view:
            view = view[os.write(fd, view):]
    finally:
        os.close(fd)

"""Issue 12, item 10: the controller's disks are a sandbox whatever the flash folder holds.

Each test plants something in the flash folder (a symbolic link to a file, to a folder, a loop, a
dangling one, a hard link, a FIFO, a link at the NVRAM's temporary name, a device folder that is a
link, a root folder replaced during the run), lets GPL's file API use it, and checks what a user
would: the GPL error code (never a Python exception or -201) and that the file outside the sandbox
is exactly as it was.
"""

from __future__ import annotations

import os
import shutil
import threading
from collections.abc import Callable
from pathlib import Path

import pytest

from gplrt.io import sandbox
from gplrt.io.files import File, StreamReader, StreamWriter
from gplrt.io.flashroot import FlashRoot, set_flash_root
from gplrt.io.xmldoc import XmlDoc
from gplrt.lang.errors import GplException

SECRET = b"outside the sandbox: must never change\n"


def code_of(call: Callable[[], object]) -> int:
    with pytest.raises(GplException) as exc:
        call()
    return exc.value.ErrorCode


def write(path: str, text: str = "PWNED", append: bool = False) -> None:
    w = StreamWriter(path, append)
    w.Write(text)
    w.Close()


def read(path: str) -> str:
    r = StreamReader(path)
    try:
        text = ""
        while r.Peek() >= 0:
            text += chr(r.Read())
        return text
    finally:
        r.Close()


@pytest.fixture
def outside(flash: FlashRoot) -> Path:
    """A folder next to the sandbox root, holding one file the tests try to reach."""
    folder = flash.root.parent / "outside"
    folder.mkdir()
    (folder / "secret").write_bytes(SECRET)
    return folder


def untouched(outside: Path, *, extra: tuple[str, ...] = ()) -> None:
    assert (outside / "secret").read_bytes() == SECRET
    assert sorted(p.name for p in outside.iterdir()) == sorted(("secret", *extra))


# --- hard links -----------------------------------------------------------------------------------


def test_a_hard_link_to_an_outside_file_is_neither_read_nor_written(flash: FlashRoot, outside: Path) -> None:
    os.link(outside / "secret", flash.root / "flash" / "hl")
    assert code_of(lambda: StreamReader("/flash/hl")) == -208
    assert code_of(lambda: write("/flash/hl")) == -208
    assert code_of(lambda: write("/flash/hl", append=True)) == -208
    assert code_of(lambda: File.ComputeCRC("/flash/hl")) == -208
    assert code_of(lambda: File.Length("/flash/hl")) == -208
    assert code_of(lambda: XmlDoc.LoadFile("/flash/hl")) == -208
    assert code_of(lambda: XmlDoc("a").SaveFile("/flash/hl")) == -208
    write("/flash/src", "copied")
    assert code_of(lambda: File.Copy("/flash/src", "/flash/hl", True)) == -208
    assert code_of(lambda: File.Copy("/flash/hl", "/flash/copy")) == -208
    assert code_of(lambda: File.DeleteFile("/flash/hl")) == -208
    untouched(outside)
    assert not (flash.root / "flash" / "copy").exists()


def test_a_hard_linked_nvram_file_is_refused(flash: FlashRoot, outside: Path) -> None:
    os.link(outside / "secret", flash.root / "NVRAM" / "file3")
    assert code_of(lambda: StreamReader("/NVRAM/file3")) == -208
    assert code_of(lambda: write("/NVRAM/file3", append=True)) == -208
    untouched(outside)


# --- symbolic links -------------------------------------------------------------------------------


def test_a_symlink_loop_is_a_file_error_not_an_internal_error(flash: FlashRoot) -> None:
    os.symlink("loop", flash.root / "flash" / "loop")
    os.symlink("b", flash.root / "flash" / "a")
    os.symlink("a", flash.root / "flash" / "b")
    for path in ("/flash/loop", "/flash/a", "/flash/loop/inside"):
        assert code_of(lambda: StreamReader(path)) == -208
        assert code_of(lambda: write(path)) == -208
        assert code_of(lambda: XmlDoc.LoadFile(path)) == -208
    assert code_of(lambda: File.GetFiles("/flash/loop")) == -208
    assert code_of(lambda: File.CreateDirectory("/flash/loop/sub")) == -208
    assert code_of(lambda: File.DeleteFile("/flash/loop")) == -208
    assert code_of(lambda: File.DeleteDirectory("/flash/loop")) == -208
    assert os.path.islink(flash.root / "flash" / "loop")


def test_a_dangling_symlink_creates_nothing_outside(flash: FlashRoot, outside: Path) -> None:
    os.symlink(outside / "created", flash.root / "flash" / "dangling")
    assert code_of(lambda: write("/flash/dangling")) == -208
    assert code_of(lambda: XmlDoc("a").SaveFile("/flash/dangling")) == -208
    write("/flash/src")
    assert code_of(lambda: File.Copy("/flash/src", "/flash/dangling", True)) == -208
    untouched(outside)


def test_a_symlink_to_an_outside_file_is_refused_by_every_member(flash: FlashRoot, outside: Path) -> None:
    os.symlink(outside / "secret", flash.root / "flash" / "link")
    assert code_of(lambda: read("/flash/link")) == -208
    assert code_of(lambda: write("/flash/link")) == -208
    assert code_of(lambda: File.Length("/flash/link")) == -208
    assert code_of(lambda: File.ComputeLength("/flash/link")) == -208
    assert code_of(lambda: File.DeleteFile("/flash/link")) == -208
    assert list(File.GetFiles("/flash")) == []  # a link is not a file of the controller
    untouched(outside)


def test_a_symlink_that_stays_inside_is_refused_too(flash: FlashRoot) -> None:
    """Decision: no link is followed, wherever it points (a controller's flash has none)."""
    write("/flash/real", "data")
    os.symlink("real", flash.root / "flash" / "alias")
    os.mkdir(flash.root / "flash" / "dir")
    os.symlink("dir", flash.root / "flash" / "dirlink")
    assert code_of(lambda: read("/flash/alias")) == -208
    assert code_of(lambda: write("/flash/dirlink/new")) == -208
    assert list(File.GetDirectories("/flash")) == ["dir"]
    assert list(File.GetFiles("/flash")) == ["real"]
    assert not (flash.root / "flash" / "dir" / "new").exists()


def test_a_link_to_an_outside_folder_is_not_listed_or_entered(flash: FlashRoot, outside: Path) -> None:
    os.symlink(outside, flash.root / "flash" / "out")
    assert list(File.GetDirectories("/flash")) == []
    assert code_of(lambda: File.GetFiles("/flash/out")) == -208
    assert code_of(lambda: File.DeleteFile("/flash/out/secret")) == -208
    assert code_of(lambda: File.CreateDirectory("/flash/out/sub")) == -208
    assert code_of(lambda: File.DeleteDirectory("/flash/out")) == -208
    untouched(outside)


# --- the NVRAM's temporary file -------------------------------------------------------------------


def test_nvram_writes_never_follow_a_link_at_the_temporary_name(flash: FlashRoot, outside: Path) -> None:
    temp = flash.root / "NVRAM" / ".file1.new"
    os.symlink(outside / "secret", temp)
    write("/NVRAM/file1", "record")
    untouched(outside)
    assert read("/NVRAM/file1") == "record"
    assert not os.path.lexists(temp)
    os.symlink(outside / "planted", temp)  # dangling: the old code created the outside file
    write("/NVRAM/file1", "again", append=True)
    untouched(outside)
    assert read("/NVRAM/file1") == "recordagain"


def test_a_folder_at_the_nvram_temporary_name_is_a_write_error(flash: FlashRoot) -> None:
    (flash.root / "NVRAM" / ".file2.new").mkdir()
    assert code_of(lambda: write("/NVRAM/file2")) == -509


# --- device folders and the root ------------------------------------------------------------------


def test_a_romdisk_that_is_a_link_does_not_move_the_device_outside(flash: FlashRoot, outside: Path) -> None:
    romdisk = flash.root / "ROMDISK"
    shutil.rmtree(romdisk)
    os.symlink(outside, romdisk)
    assert code_of(lambda: write("/ROMDISK/planted")) == -208
    assert code_of(lambda: read("/ROMDISK/secret")) == -208
    assert code_of(lambda: File.GetFiles("/ROMDISK")) == -208
    untouched(outside)
    # A session start clears the RAM disk: the link goes, its target stays as it was.
    again = set_flash_root(flash.root)
    untouched(outside)
    assert romdisk.is_dir() and not romdisk.is_symlink()
    write("/ROMDISK/inside", "ok")
    assert (again.root / "ROMDISK" / "inside").read_bytes() == b"ok"


def test_a_flash_device_folder_that_is_a_link_is_refused(tmp_path: Path) -> None:
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "secret").write_bytes(SECRET)
    (tmp_path / "root").mkdir()
    os.symlink(outside, tmp_path / "root" / "flash")
    set_flash_root(tmp_path / "root")
    assert code_of(lambda: read("/flash/secret")) == -208
    assert code_of(lambda: write("/flash/new")) == -208
    assert code_of(lambda: File.CreateDirectory("/flash/sub")) == -208
    untouched(outside)


def test_the_root_replaced_during_a_run_keeps_the_original_folder(flash: FlashRoot, outside: Path) -> None:
    write("/flash/before", "1")
    moved = flash.root.parent / "moved"
    flash.root.rename(moved)
    os.symlink(outside, flash.root)  # the root's old name now leads outside
    write("/flash/after", "2")
    assert (moved / "flash" / "after").read_bytes() == b"2"
    assert read("/flash/before") == "1"
    untouched(outside)


# --- special files --------------------------------------------------------------------------------


def _ends(call: Callable[[], object]) -> object:
    """What ``call`` raised or returned; fails if it is still blocked after 10 s (a FIFO open)."""
    result: list[object] = []
    worker = threading.Thread(target=lambda: result.append(_outcome(call)), daemon=True)
    worker.start()
    worker.join(10.0)
    assert result, "the call blocked"
    return result[0]


def _outcome(call: Callable[[], object]) -> object:
    try:
        return call()
    except GplException as exc:
        return exc.ErrorCode
    except BaseException as exc:  # noqa: BLE001 - reported to the test as a wrong outcome
        return exc


def test_a_fifo_is_not_a_file_and_never_blocks(flash: FlashRoot) -> None:
    fifo = flash.root / "flash" / "fifo"
    os.mkfifo(fifo)
    assert _ends(lambda: StreamReader("/flash/fifo")) == -521
    assert _ends(lambda: write("/flash/fifo")) == -521
    assert _ends(lambda: XmlDoc.LoadFile("/flash/fifo")) == -521
    assert _ends(lambda: File.ComputeCRC("/flash/fifo")) == -521
    assert list(File.GetFiles("/flash")) == []


def test_a_device_node_and_a_unix_socket_are_not_files(flash: FlashRoot) -> None:
    import socket
    import stat

    node = flash.root / "flash" / "null"
    try:
        os.mknod(node, stat.S_IFCHR | 0o666, os.makedev(1, 3))  # /dev/null's numbers
    except (PermissionError, OSError) as exc:
        pytest.skip(f"cannot make a device node here ({exc}): needs root")
    assert code_of(lambda: StreamReader("/flash/null")) == -521
    assert code_of(lambda: write("/flash/null")) == -521
    assert code_of(lambda: File.DeleteFile("/flash/null")) == -521
    server = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        server.bind(str(flash.root / "flash" / "sock"))
        assert _ends(lambda: StreamReader("/flash/sock")) == -521
        assert _ends(lambda: write("/flash/sock")) == -521
    finally:
        server.close()


# --- other ways in that were already held: kept so that they stay held ----------------------------


def test_file_copy_onto_itself_leaves_the_file_whole(flash: FlashRoot) -> None:
    write("/flash/same", "keep me")
    assert code_of(lambda: File.Copy("/flash/same", "/flash/same", True)) == -512
    assert read("/flash/same") == "keep me"


def test_xml_never_reads_an_external_entity_or_dtd(flash: FlashRoot, outside: Path) -> None:
    (flash.root / "flash" / "x.xml").write_text(
        f'<?xml version="1.0"?><!DOCTYPE x SYSTEM "file://{outside}/secret" '
        f'[<!ENTITY e SYSTEM "file://{outside}/secret">]><x>&e;</x>')
    doc = XmlDoc.LoadFile("/flash/x.xml")
    assert "outside the sandbox" not in doc.SaveString()


def test_clearing_the_romdisk_removes_links_in_it_not_their_targets(flash: FlashRoot, outside: Path) -> None:
    os.symlink(outside, flash.root / "ROMDISK" / "dir")
    os.symlink(outside / "secret", flash.root / "ROMDISK" / "file")
    set_flash_root(flash.root)
    assert list((flash.root / "ROMDISK").iterdir()) == []
    untouched(outside)


# --- a name swapped between the check and the open ------------------------------------------------


@pytest.mark.parametrize("swap", ["symlink", "hardlink"])
def test_a_name_swapped_after_the_check_is_refused_untouched(
    flash: FlashRoot, outside: Path, monkeypatch: pytest.MonkeyPatch, swap: str
) -> None:
    """A race: the file is a plain file when it is checked and a link when it is opened."""
    target = flash.root / "flash" / "data"
    target.write_bytes(b"plain")
    real_open = os.open
    swapped: list[str] = []

    def open_after_swap(name, flags, *args, **kwargs):  # type: ignore[no-untyped-def]
        if name == "data" and not swapped:
            swapped.append(name)
            target.unlink()
            if swap == "symlink":
                os.symlink(outside / "secret", target)
            else:
                os.link(outside / "secret", target)
        return real_open(name, flags, *args, **kwargs)

    monkeypatch.setattr(sandbox.os, "open", open_after_swap)
    assert code_of(lambda: write("/flash/data")) == -208
    assert swapped
    untouched(outside)


# --- through a transpiled program -----------------------------------------------------------------


def test_a_gpl_catch_sees_the_protection_error(tmp_path: Path) -> None:
    from gpl2py.diagnostics import DiagnosticSink
    from gpl2py.run import import_package
    from gpl2py.transpile import transpile, write_package
    from gplrt.sim import Simulation

    project = tmp_path / "proj"
    project.mkdir()
    (project / "Main.gpl").write_text(
        "Module Main\n"
        "    Public Sub Main()\n"
        "        Dim w As StreamWriter\n"
        "        Try\n"
        "            w = New StreamWriter(\"/flash/hl\")\n"
        "            w.WriteLine(\"PWNED\")\n"
        "            w.Close()\n"
        "            Console.WriteLine(\"written\")\n"
        "        Catch ex As Exception\n"
        "            Console.WriteLine(\"refused \" & CStr(ex.ErrorCode))\n"
        "        End Try\n"
        "    End Sub\n"
        "End Module\n"
    )
    sink = DiagnosticSink()
    out = transpile(project, sink)
    assert out is not None, [d.render() for d in sink.sorted()]
    assert write_package(out, tmp_path / "out", sink), sink
    package = import_package(tmp_path / "out" / out.package, "_sandbox_links_e2e")
    disks = tmp_path / "disks"
    (disks / "flash").mkdir(parents=True)
    secret = tmp_path / "secret"
    secret.write_bytes(SECRET)
    os.link(secret, disks / "flash" / "hl")
    sim = Simulation(capture=True, flash_root=disks)
    assert package.main(sim) == 0
    assert sim.console.output.splitlines() == ["refused -208"]
    assert secret.read_bytes() == SECRET


# --- installing a project's own files into /flash/projects/<project>/ -----------------------------


def test_installed_project_files_are_read_like_any_file(flash: FlashRoot, tmp_path: Path) -> None:
    from gplrt.io.project_files import install_project_folder

    project = tmp_path / "project"
    project.mkdir()
    (project / "Locations.txt").write_bytes(b"table")
    assert install_project_folder(project, "Cell") == "/flash/projects/Cell"
    assert read("/flash/projects/Cell/Locations.txt") == "table"
    assert read("Locations.txt") == "table"  # relative names resolve in the project's folder


def test_a_project_cannot_smuggle_an_outside_file_into_flash(flash: FlashRoot, outside: Path, tmp_path: Path) -> None:
    from gplrt.io.project_files import install_project_folder

    project = tmp_path / "project"
    project.mkdir()
    os.symlink(outside / "secret", project / "Stolen.txt")
    os.link(outside / "secret", project / "Shared.txt")
    (project / "ok.txt").write_bytes(b"ok")
    install_project_folder(project, "Cell")
    installed = flash.root / "flash" / "projects" / "Cell"
    assert sorted(p.name for p in installed.iterdir()) == ["ok.txt"]
    untouched(outside)


def test_installing_never_writes_through_a_link_in_flash(flash: FlashRoot, outside: Path, tmp_path: Path) -> None:
    from gplrt.io.project_files import install_project_folder

    project = tmp_path / "project"
    project.mkdir()
    (project / "hl.txt").write_bytes(b"project data")
    (project / "sym.txt").write_bytes(b"project data")
    installed = flash.root / "flash" / "projects" / "Cell"
    installed.mkdir(parents=True)
    os.link(outside / "secret", installed / "hl.txt")
    os.symlink(outside / "planted", installed / "sym.txt")
    install_project_folder(project, "Cell")
    untouched(outside)  # the hard link was replaced, not truncated and overwritten
    assert read("/flash/projects/Cell/hl.txt") == "project data"
    assert read("/flash/projects/Cell/sym.txt") == "project data"


def test_installing_into_a_projects_folder_that_is_a_link_writes_nothing(
    flash: FlashRoot, outside: Path, tmp_path: Path
) -> None:
    from gplrt.io.project_files import install_project_folder

    project = tmp_path / "project"
    project.mkdir()
    (project / "data.txt").write_bytes(b"project data")
    os.symlink(outside, flash.root / "flash" / "projects")
    assert install_project_folder(project, "Cell") is None
    untouched(outside)

"""The translation packs the same project files the runtime installs.

``gpl2py.project.read_data_files`` (what ``translate`` writes to ``<package>/_project_files/``,
without importing the runtime's I/O stack) and ``gplrt.io.project_files.read_project_files`` (what
``gpl2py run``, ``Cell.load`` and ``python -m`` install on the controller) must agree on every kind
of entry a hostile project folder can hold."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from gpl2py import project
from gplrt.io import flashroot, project_files


def _hostile_folder(root: Path) -> Path:
    folder = root / "proj"
    folder.mkdir()
    (folder / "Main.gpl").write_text("Module Main\nEnd Module\n")
    (folder / "Tcs.gpo").write_bytes(b"\x00\x01 binary data")
    (folder / "empty.txt").write_bytes(b"")
    (folder / ".hidden").write_text("a name the controller refuses")
    (folder / ("n" * 43)).write_text("the longest name the controller takes")
    (folder / ("n" * 44)).write_text("one character too long")
    (folder / "sub").mkdir()
    (folder / "sub" / "inner.txt").write_text("not directly in the folder")
    (root / "secret.txt").write_text("host secret")
    os.symlink(root / "secret.txt", folder / "link.txt")
    os.symlink(root, folder / "linkdir")
    os.symlink(folder / "missing", folder / "dangling.txt")
    (root / "shared.txt").write_text("data that lives outside too")
    os.link(root / "shared.txt", folder / "hardlink.txt")
    os.mkfifo(folder / "pipe")
    return folder


def test_limits_are_the_runtimes() -> None:
    assert project.CONTROLLER_MAX_NAME == flashroot.MAX_NAME
    assert project.DATA_FILE_MAX_BYTES == project_files.MAX_FILE_BYTES


def test_translation_and_runtime_read_the_same_files(tmp_path: Path) -> None:
    folder = _hostile_folder(tmp_path)
    ours = project.read_data_files(folder)
    assert ours == project_files.read_project_files(folder)
    assert sorted(ours) == ["Main.gpl", "Tcs.gpo", "empty.txt", "n" * 43]
    assert ours["Tcs.gpo"] == b"\x00\x01 binary data"


def test_a_file_over_the_limit_is_left_out_by_both(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "big.bin").write_bytes(b"x" * 101)
    (tmp_path / "small.bin").write_bytes(b"x" * 100)
    monkeypatch.setattr(project, "DATA_FILE_MAX_BYTES", 100)
    monkeypatch.setattr(project_files, "MAX_FILE_BYTES", 100)
    assert project.read_data_files(tmp_path) == project_files.read_project_files(tmp_path) == {"small.bin": b"x" * 100}


def test_a_folder_that_cannot_be_read_gives_nothing(tmp_path: Path) -> None:
    assert project.read_data_files(tmp_path / "missing") == project_files.read_project_files(tmp_path / "missing") == {}
    (tmp_path / "file").write_text("not a folder")
    assert project.read_data_files(tmp_path / "file") == {}

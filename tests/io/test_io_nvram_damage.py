"""A damaged NVRAM host file: a cut-off last record is the in-flight write a power failure loses;
anything else that is not an NVRAM file is -519 *Invalid file format*.

D0:4004-4007 and 4068-4073: records are written atomically, "the data actively being written may
be lost" but existing records never are, and "by searching for the final record in a file, you can
always find the latest entry, even after a power failure".  So a file whose last record is cut
short reads as its complete records (the partial one dropped, not returned as data), the loss is
reported in the controller's error log, and the file is repaired so that later writes follow the
last complete record.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from gplrt.io.files import StreamReader, StreamWriter
from gplrt.io.flashroot import FlashRoot
from gplrt.io.nvram import MAGIC
from gplrt.lang.errors import INVALID_FILE_FORMAT, GplException
from gplrt.sim import Simulation


@pytest.fixture
def sim(flash: FlashRoot) -> Iterator[Simulation]:
    """A session whose error log the test reads, on the test's own flash root (a session's disks
    are its own: ``Simulation(flash_root=...)``)."""
    with Simulation(capture=True, flash_root=flash.root) as session:
        yield session


def _write_records(path: str, count: int) -> None:
    w = StreamWriter(path, True)
    for n in range(1, count + 1):
        w.WriteLine(f"Record {n}")  # one record of 10 bytes (AutoFlush on /NVRAM)
    w.Close()


def _lines(path: str) -> list[str]:
    r = StreamReader(path)
    lines = []
    while r.Peek() >= 0:
        lines.append(r.ReadLine())
    r.Close()
    return lines


def _host(flash: FlashRoot, name: str) -> Path:
    return flash.root / "NVRAM" / name


def _read_code(path: str) -> int:
    with pytest.raises(GplException) as info:
        StreamReader(path)
    return info.value.ErrorCode


@pytest.mark.parametrize("cut", [1, 5, 10])  # inside the data, just after the length byte
def test_a_cut_off_last_record_is_lost_and_the_complete_ones_read(flash: FlashRoot, sim: Simulation, cut: int) -> None:
    _write_records("/NVRAM/file2", 3)
    host = _host(flash, "file2")
    host.write_bytes(host.read_bytes()[:-cut])
    assert _lines("/NVRAM/file2") == ["Record 1", "Record 2"]
    log = sim.controller.error_log
    assert [e.code for e in log] == [INVALID_FILE_FORMAT]
    assert "file2" in log[0].text and "record" in log[0].text


def test_the_damaged_file_is_repaired_once_and_writes_follow_the_last_complete_record(
    flash: FlashRoot, sim: Simulation
) -> None:
    _write_records("/NVRAM/file2", 3)
    host = _host(flash, "file2")
    host.write_bytes(host.read_bytes()[:-4])
    assert _lines("/NVRAM/file2") == ["Record 1", "Record 2"]
    assert _lines("/NVRAM/file2") == ["Record 1", "Record 2"]  # reported once: repaired
    assert len(sim.controller.error_log) == 1
    w = StreamWriter("/NVRAM/file2", True)
    w.WriteLine("Record 4")
    w.Close()
    assert _lines("/NVRAM/file2") == ["Record 1", "Record 2", "Record 4"]
    assert len(sim.controller.error_log) == 1


def test_a_cut_off_record_found_when_opening_for_append_is_dropped_too(flash: FlashRoot, sim: Simulation) -> None:
    _write_records("/NVRAM/file5 -size 64", 2)
    host = _host(flash, "file5")
    host.write_bytes(host.read_bytes()[:-3])
    w = StreamWriter("/NVRAM/file5", True)
    w.WriteLine("Record 3")
    w.Close()
    assert _lines("/NVRAM/file5") == ["Record 1", "Record 3"]
    assert [e.code for e in sim.controller.error_log] == [INVALID_FILE_FORMAT]


def test_an_intact_file_reports_nothing(flash: FlashRoot, sim: Simulation) -> None:
    _write_records("/NVRAM/file2", 3)
    assert _lines("/NVRAM/file2") == ["Record 1", "Record 2", "Record 3"]
    assert sim.controller.error_log == []


def _header(size: int, wrap: bool = False) -> bytes:
    return MAGIC + size.to_bytes(2, "big") + bytes([wrap])


@pytest.mark.parametrize(
    "raw",
    [
        pytest.param(MAGIC + b"\x04", id="header cut short"),
        pytest.param(b"GPLXX" + b"\x04\x00\x00", id="not an NVRAM file"),
        pytest.param(_header(3), id="size below 4"),
        pytest.param(_header(7873), id="size above 7872"),
        pytest.param(_header(16) + b"\x0a" + b"Record 1\r\n" + b"\x04" + b"abcd", id="records beyond the size"),
        pytest.param(MAGIC + (64).to_bytes(2, "big") + b"\x02", id="wrap flag not 0 or 1"),
    ],
)
def test_a_file_no_controller_could_have_written_is_519(
    flash: FlashRoot, sim: Simulation, raw: bytes
) -> None:
    host = _host(flash, "file7")
    host.parent.mkdir(parents=True, exist_ok=True)
    host.write_bytes(raw)
    assert _read_code("/NVRAM/file7") == INVALID_FILE_FORMAT
    with pytest.raises(GplException) as info:
        StreamWriter("/NVRAM/file7", True)
    assert info.value.ErrorCode == INVALID_FILE_FORMAT
    assert host.read_bytes() == raw  # not "repaired" into something else

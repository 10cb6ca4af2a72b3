"""File, StreamReader, StreamWriter: round trips, line handling, buffering, NVRAM, errors."""

from __future__ import annotations

import gc
import os

import pytest

from gplrt.io.files import File, StreamReader, StreamWriter
from gplrt.io.flashroot import FlashRoot
from gplrt.lang.errors import GplException


def code_of(excinfo: pytest.ExceptionInfo[GplException]) -> int:
    return excinfo.value.ErrorCode


def test_ex24_write_then_read_lines(flash: FlashRoot) -> None:
    # EX-24: ten WriteLine calls, then read back while Peek() >= 0.
    o = StreamWriter("/ROMDISK/filetest")
    for ii in range(1, 11):
        o.WriteLine("Line " + str(ii))
    o.Close()
    assert (flash.root / "ROMDISK" / "filetest").read_bytes() == b"".join(
        b"Line %d\r\n" % i for i in range(1, 11)
    )
    i = StreamReader("/ROMDISK/filetest")
    lines = []
    while i.Peek() >= 0:
        lines.append(i.ReadLine())
    i.Close()
    assert lines == [f"Line {n}" for n in range(1, 11)]


def test_readline_accepts_lf_cr_and_crlf_and_partial_last_line(flash: FlashRoot) -> None:
    (flash.root / "flash" / "mixed").write_bytes(b"a\nb\rc\r\n\nlast")
    r = StreamReader("/flash/mixed")
    assert [r.ReadLine() for _ in range(5)] == ["a", "b", "c", "", "last"]
    assert r.Peek() == -1 and r.Read() == -1
    with pytest.raises(GplException) as exc:
        r.ReadLine()
    assert code_of(exc) == -505


def test_peek_does_not_consume_and_read_returns_bytes(flash: FlashRoot) -> None:
    (flash.root / "flash" / "bin").write_bytes(bytes([0, 200, 255]))
    r = StreamReader("/flash/bin")
    assert r.Peek() == 0 and r.Peek() == 0
    assert [r.Read(), r.Read(), r.Read(), r.Read()] == [0, 200, 255, -1]


def test_strings_are_bytes_latin1_round_trip(flash: FlashRoot) -> None:
    text = "".join(chr(c) for c in range(256))
    w = StreamWriter("/flash/all")
    w.Write(text)
    w.Close()
    assert (flash.root / "flash" / "all").read_bytes() == bytes(range(256))
    r = StreamReader("/flash/all")
    assert "".join(chr(r.Read()) for _ in range(256)) == text
    with pytest.raises(GplException) as exc:
        StreamWriter("/flash/wide").Write("\u20ac")
    assert code_of(exc) == -202


def test_buffering_autoflush_flush_and_close(flash: FlashRoot) -> None:
    host = flash.root / "flash" / "buf"
    w = StreamWriter("/flash/buf")
    assert w.AutoFlush is False
    w.Write("abc")
    assert host.read_bytes() == b""  # buffered until Flush/Close
    w.Flush()
    assert host.read_bytes() == b"abc"
    w.AutoFlush = True
    w.Write(12)
    w.Write(2.5)
    assert host.read_bytes() == b"abc122.5"
    w.NewLine = "\r"
    w.WriteLine("x")
    w.Close()
    w.Close()  # harmless
    assert host.read_bytes() == b"abc122.5x\r"


def test_append_mode_and_overwrite(flash: FlashRoot) -> None:
    for append, text in ((False, "one"), (True, "two"), (True, "three")):
        w = StreamWriter("/flash/log.txt", append)
        w.WriteLine(text)
        w.Close()
    assert (flash.root / "flash" / "log.txt").read_bytes() == b"one\r\ntwo\r\nthree\r\n"
    w = StreamWriter("/flash/log.txt")
    w.Close()
    assert (flash.root / "flash" / "log.txt").read_bytes() == b""


def test_closed_streams_raise_file_not_open(flash: FlashRoot) -> None:
    w = StreamWriter("/flash/x")
    w.Close()
    with pytest.raises(GplException) as exc:
        w.Write("late")
    assert code_of(exc) == -520
    r = StreamReader("/flash/x")
    r.Close()
    for call in (r.Read, r.Peek, r.ReadLine):
        with pytest.raises(GplException) as exc:
            call()
        assert code_of(exc) == -520


def test_missing_file_and_missing_folder(flash: FlashRoot) -> None:
    with pytest.raises(GplException) as exc:
        StreamReader("/flash/nope.txt")
    assert code_of(exc) == -508
    with pytest.raises(GplException) as exc:
        StreamWriter("/flash/no_dir/file")
    assert code_of(exc) == -509


@pytest.mark.parametrize(
    ("path", "code"),
    [
        ("/flash/../../etc/passwd", -516),
        ("/flash/sub/..", -516),
        ("/flash/.hidden", -516),
        ("/etc/passwd", -301),
        ("relative/file", -301),
        ("C:\\windows", -301),
        ("/flash/" + "n" * 44, -516),
        ("/flash/" + "d/" * 130 + "f", -517),
    ],
)
def test_sandbox_refuses_escaping_paths(flash: FlashRoot, path: str, code: int) -> None:
    with pytest.raises(GplException) as exc:
        StreamWriter(path)
    assert code_of(exc) == code
    with pytest.raises(GplException) as exc:
        StreamReader(path)
    assert code_of(exc) == code


def test_sandbox_refuses_symlink_out(flash: FlashRoot, tmp_path: os.PathLike[str]) -> None:
    outside = flash.root.parent / "outside"
    outside.mkdir()
    (outside / "secret").write_text("s")
    os.symlink(outside, flash.root / "flash" / "link")
    os.symlink(outside / "secret", flash.root / "flash" / "filelink")
    for path in ("/flash/link/secret", "/flash/filelink"):
        with pytest.raises(GplException) as exc:
            StreamReader(path)
        assert code_of(exc) == -208
    with pytest.raises(GplException) as exc:
        StreamWriter("/flash/link/new")
    assert code_of(exc) == -208
    assert not (outside / "new").exists()


def test_device_names_case_insensitive_file_names_case_sensitive(flash: FlashRoot) -> None:
    w = StreamWriter("/romdisk/Data")
    w.Write("D")
    w.Close()
    assert StreamReader("/ROMDISK/Data").Read() == ord("D")
    with pytest.raises(GplException) as exc:
        StreamReader("/ROMDISK/data")
    assert code_of(exc) == -508


def test_file_shared_members(flash: FlashRoot) -> None:
    File.CreateDirectory("/flash/a/b/c")
    assert list(File.GetDirectories("/flash/a")) == ["b"]
    w = StreamWriter("/flash/a/f1")
    w.Write("hello")
    w.Close()
    assert File.Length("/flash/a/f1") == 5 == File.ComputeLength("/flash/a/f1")
    assert File.ComputeCRC("/flash/a/f1") == 0x3610A686  # CRC-32 of "hello"
    File.Copy("/flash/a/f1", "/flash/a/f2")
    with pytest.raises(GplException) as exc:
        File.Copy("/flash/a/f1", "/flash/a/f2")
    assert code_of(exc) == -510
    File.Copy("/flash/a/f1", "/flash/a/f2", True)
    StreamWriter("/flash/a/z.tmp").Close()
    assert list(File.GetFiles("/flash/a")) == ["f1", "f2", "z.tmp"]
    File.DeleteFile("/flash/a/z.tmp")
    with pytest.raises(GplException) as exc:
        File.DeleteDirectory("/flash/a/b")
    assert code_of(exc) == -202  # not empty
    File.DeleteDirectory("/flash/a/b/c")
    File.DeleteFile("/flash/a/f2")
    assert list(File.GetFiles("/flash/a")) == ["f1"]
    with pytest.raises(GplException) as exc:
        File.DeleteFile("/flash/a/f2")
    assert code_of(exc) == -508
    with pytest.raises(GplException) as exc:
        File.GetFiles("/flash/missing")
    assert code_of(exc) == -508


def test_crc_is_signed_integer(flash: FlashRoot) -> None:
    (flash.root / "flash" / "z").write_bytes(b"The quick brown fox jumps over the lazy dog")
    assert File.ComputeCRC("/flash/z") == 0x414FA339  # positive
    (flash.root / "flash" / "n").write_bytes(b"123456789")
    assert File.ComputeCRC("/flash/n") == 0xCBF43926 - (1 << 32)


def test_romdisk_cleared_when_a_session_starts(flash: FlashRoot) -> None:
    from gplrt.io.flashroot import set_flash_root

    StreamWriter("/ROMDISK/tmp").Close()
    StreamWriter("/flash/keep").Close()
    again = set_flash_root(flash.root)
    assert not (again.root / "ROMDISK" / "tmp").exists()
    assert (again.root / "flash" / "keep").exists()


def test_ex27_nvram_non_circular_file_fails_at_record_6(flash: FlashRoot) -> None:
    tfile = StreamWriter("/NVRAM/file2 -size 64", True)
    failed_at = None
    for ii in range(1, 101):
        try:
            tfile.WriteLine("Record " + str(ii))
        except GplException as exc:
            assert exc.ErrorCode == -323
            failed_at = ii
            break
    tfile.Close()
    assert failed_at == 6
    r = StreamReader("/NVRAM/file2")
    lines = []
    while r.Peek() >= 0:
        lines.append(r.ReadLine())
    assert lines == [f"Record {n}" for n in range(1, 6)]


def test_ex28_nvram_circular_file_keeps_last_records(flash: FlashRoot) -> None:
    tfile = StreamWriter("/NVRAM/file3 -size 64 -wrap", True)
    for ii in range(1, 101):
        tfile.WriteLine("Record " + str(ii))
    tfile.Close()
    r = StreamReader("/NVRAM/file3")
    lines = []
    while r.Peek() >= 0:
        lines.append(r.ReadLine())
    assert lines == [f"Record {n}" for n in range(96, 101)]
    # The size is fixed until the file is deleted: re-opening without -size keeps 64 bytes.
    again = StreamWriter("/NVRAM/file3", False)
    again.WriteLine("x" * 60)  # 62 + 1 + 1 = 64 fits exactly
    with pytest.raises(GplException) as exc:
        StreamWriter("/NVRAM/file3", True).WriteLine("y" * 61)  # 63 + 1 + 1 > 64
    assert exc.value.ErrorCode == -323


def test_nvram_names_and_sizes(flash: FlashRoot) -> None:
    with pytest.raises(GplException) as exc:
        StreamWriter("/NVRAM/file17")
    assert exc.value.ErrorCode == -516
    with pytest.raises(GplException) as exc:
        StreamWriter("/NVRAM/file1 -size 3")
    assert exc.value.ErrorCode == -707
    w = StreamWriter("/NVRAM/file1 -size 7500 -wrap")  # EX-29's error-log spec
    w.Write("abc")
    w.Close()
    assert File.Length("/NVRAM/file1") == 3
    assert list(File.GetFiles("/NVRAM")) == ["file1"]


def test_a_writer_freed_without_close_keeps_its_buffered_lines(flash: FlashRoot) -> None:
    """GPL code often lets a local StreamWriter go at the end of its procedure without Close;
    the controller closes the stream with its last reference.  The lines must not be lost in our
    4 KB buffer (before: the file stayed empty)."""

    def log_line(text: str) -> None:  # a GPL Sub with a local writer and no Close
        sw = StreamWriter("/flash/log.txt", True)
        sw.WriteLine(text)

    log_line("first")
    log_line("second")
    gc.collect()
    assert (flash.root / "flash" / "log.txt").read_bytes() == b"first\r\nsecond\r\n"

"""TMscript's file functions (manual §7, L9907-L12366) against the manual's own examples, in the
robot's file sandbox: each script runs as a Listen-node packet would (translated at run time)."""

from __future__ import annotations

import pytest
from tmpacket import packet_values, run_packet

from gplrt.tm import context
from gplrt.tm.values import TMError

SAMPLES = {
    "SampleFile1.txt": b"1Hello World!\r\n1Hello TM Robot!",
    "SampleFile2.txt": b"2Hello World!\r\n2Hello TM Robot!\r\n2Hi TM Robot!",
    "SampleFile3.txt": b"",
    "SampleFile4.txt": b"4Hello World!\r\n\r\n4Hello TM Robot!",
    "SampleFile5.txt": b"5Hello World!\r\n5Hello TM Robot!\r\n5Hi TM Robot!",
}


@pytest.fixture
def robot():  # type: ignore[no-untyped-def]
    r = context.use_robot("TM5-900")
    box = r.sim.files.root().box
    box.path("TextFiles").mkdir()
    for name, data in SAMPLES.items():
        box.path("TextFiles", name).write_bytes(data)
    return r






def host_bytes(robot, name: str) -> bytes:  # type: ignore[no-untyped-def]
    return robot.sim.files.root().box.path("TextFiles", name).read_bytes()


def test_read_bytes_and_text_l9954_l10013(robot) -> None:  # type: ignore[no-untyped-def]
    got = packet_values('byte[] b1 = File_ReadBytes("sampleFile1.txt")\n'
                 'byte[] b2 = File_ReadBytes(".\\TextFiles\\SampleFile1.txt")\n'
                 'string s1 = File_ReadText("sampleFile1.txt")', "b1", "b2", "s1")
    want = "{" + ",".join(str(b) for b in SAMPLES["SampleFile1.txt"]) + "}"
    assert got[:2] == [want, want]
    assert got[2] == "1Hello World!\r\n1Hello TM Robot!"
    for bad in ('"C:\\SampleFile1.txt"', '".\\SampleFile1.txt"', '"SampleFileXX.txt"',
                '".\\TextFiles\\..\\..\\folder"', '"\\TextFiles\\SampleFile1.txt"'):
        with pytest.raises(TMError):
            run_packet(f"byte[] b = File_ReadBytes({bad})")


def test_read_lines_l10054(robot) -> None:  # type: ignore[no-untyped-def]
    got = packet_values('string[] a = File_ReadLines("SampleFile2.txt")\nstring[] b = File_ReadLines("SampleFile2.txt", 1, 2)\n'
                 'string[] c = File_ReadLines("SampleFile2.txt", 2, 2)\nstring[] d = File_ReadLines("SampleFile2.txt", 3, 2)\n'
                 'string[] e = File_ReadLines("SampleFile2.txt", 0)\nstring[] f = File_ReadLines("SampleFile2.txt", 4)\n'
                 'string[] g = File_ReadLines("SampleFile2.txt", 3, 0)\nstring[] h = File_ReadLines("SampleFile3.txt")\n'
                 "int n = Length(h)", *"abcdefghn")
    assert got == ["{2Hello World!,2Hello TM Robot!,2Hi TM Robot!}", "{2Hello World!,2Hello TM Robot!}",
                   "{2Hello TM Robot!,2Hi TM Robot!}", "{2Hi TM Robot!}", "{}", "{}", "{2Hi TM Robot!}", "{}", "1"]
    assert run_packet('string[] h = File_ReadLines("SampleFile3.txt")').h == [""]  # L10140: {""}


def test_next_line_and_eof_l10149_l10367(robot) -> None:  # type: ignore[no-untyped-def]
    calls = ['File_NextLine()', 'File_NextLine("SampleFile4.txt")', 'File_NextLine("SampleFile4.txt")',
             'File_NextLine("SampleFile5.txt")', 'File_NextLine("SampleFile4.txt")', 'File_NextLine("SampleFile4.txt")',
             'File_NextLine("SampleFile4.txt")', 'File_NextLine("SampleFile4.txt")', 'File_NextLine("SampleFile4.txt", true)',
             'File_NextLine("SampleFile4.txt", true)', 'File_NextLine("SampleFile4.txt", false)', "File_NextLine()"]
    script = "\n".join(f"string s{i} = {c}" for i, c in enumerate(calls)) + "\nbool eof = File_NextEOF()"
    v = run_packet(script)
    assert [getattr(v, f"s{i}") for i in range(len(calls))] == [
        "", "4Hello World!", "", "5Hello World!", "4Hello World!", "", "4Hello TM Robot!", "", "4Hello World!",
        "4Hello World!", "", "4Hello TM Robot!"]
    assert v.eof is True
    v = run_packet('string[] a = File_NextLine("SampleFile4.txt", 1)\nstring[] b = File_NextLine("SampleFile4.txt", 0)\n'
            'string[] c = File_NextLine(0)\nstring[] d = File_NextLine(0)\nstring[] e = File_NextLine(2)\n'
            'bool at_end = File_NextEOF()\nstring[] f = File_NextLine(0)')
    assert (v.a, v.b, v.c, v.d, v.e, v.at_end, v.f) == (["4Hello World!"], [""], ["4Hello TM Robot!"], [], [], False,
                                                        ["4Hello World!"])


def test_write_bytes_l10410(robot) -> None:  # type: ignore[no-untyped-def]
    decl = ("byte[] bb1 = {0x00, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08}\n"
            "byte[] bb2 = {0x30, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37, 0x38}\nbyte[] bb3 = {}\n")
    assert run_packet(decl + 'bool f = File_WriteBytes("writebytes.txt", bb1)').f is True
    assert host_bytes(robot, "writebytes.txt") == bytes(range(9))
    run_packet(decl + 'File_WriteBytes("writebytes.txt", bb2)')
    assert host_bytes(robot, "writebytes.txt") == b"012345678"
    run_packet(decl + 'File_WriteBytes("writebytes.txt", bb3)')
    assert host_bytes(robot, "writebytes.txt") == b""
    run_packet(decl + 'File_WriteBytes("writebytes.txt", bb1, 1)\nFile_WriteBytes("writebytes.txt", bb2, 1)')
    assert host_bytes(robot, "writebytes.txt") == bytes(range(9)) + b"012345678"
    run_packet(decl + 'File_WriteBytes("writebytes.txt", bb1, 1, 3)')
    assert host_bytes(robot, "writebytes.txt") == bytes(range(9)) + b"012345678" + bytes(range(3, 9))
    # numbers little endian, text UTF-8 (L10425)
    run_packet('int[] n = {1, 256}\nFile_WriteBytes("n.bin", n)\nFile_WriteBytes("n.bin", "達", 1)')
    assert host_bytes(robot, "n.bin") == b"\x01\x00\x00\x00\x00\x01\x00\x00" + "達".encode()


def test_write_text_line_lines_l10772_l11074_l11329(robot) -> None:  # type: ignore[no-untyped-def]
    run_packet('string s1 = "Hi TM Robot"\nstring s2 = "達明機器人"\nFile_WriteLine("writeline.txt", s2)\n'
        'File_WriteLine("writeline.txt", s1)\nFile_WriteLine("writeline.txt", s2, 1)\nFile_WriteLine("writeline.txt", s1, 1, 3)')
    assert host_bytes(robot, "writeline.txt").decode() == "Hi TM Robot\r\n達明機器人\r\nTM Robot\r\n"
    run_packet('string[] ss1 = {"Hi TM Robot", "達明機器人"}\nFile_WriteLines("writelines.txt", ss1)\n'
        'File_WriteText("writetext.txt", ss1)\nint[] n2 = {100, 200}\nFile_WriteLines("writelines2.txt", n2)')
    assert host_bytes(robot, "writelines.txt").decode() == "Hi TM Robot\r\n達明機器人\r\n"
    assert host_bytes(robot, "writetext.txt").decode() == "{Hi TM Robot,達明機器人}"
    assert host_bytes(robot, "writelines2.txt") == b"100\r\n200\r\n"
    v = run_packet('string[] back = File_ReadLines("writelines.txt")')
    assert v.back == ["Hi TM Robot", "達明機器人"]


def test_exists_length_delete_copy_replace(robot) -> None:  # type: ignore[no-untyped-def]
    v = run_packet('bool e1 = File_Exists("SampleFile1.txt")\nbool e2 = File_Exists("nope.txt")\n'
            'bool e3 = File_Exists("C:\\SampleFile1.txt")\nint l1 = File_Length("SampleFile1.txt")\n'
            'int l2 = File_Length("nope.txt")\nint l3 = File_Length("..\\x")\n'
            'bool c = File_Copy("SampleFile1.txt", ".\\XmlFiles\\sub", "copy.txt")\n'
            'string copied = File_ReadText(".\\XmlFiles\\sub\\copy.txt")\n'
            'bool r = File_Replace("SampleFile2.txt", "Hello", "Bye")\nstring[] lines = File_ReadLines("SampleFile2.txt")\n'
            'bool d1 = File_Delete("SampleFile1.txt")\nbool d2 = File_Delete("SampleFile1.txt")\nbool e4 = File_Exists("SampleFile1.txt")')
    assert (v.e1, v.e2, v.e3, v.l1, v.l2, v.l3) == (True, False, False, 31, -1, -1)
    assert v.c is True and v.copied == "1Hello World!\r\n1Hello TM Robot!"
    assert v.r is True and v.lines == ["2Bye World!", "2Bye TM Robot!", "2Hi TM Robot!"]
    assert (v.d1, v.d2, v.e4) == (True, True, False)
    v = run_packet('string[] t = File_GetAllTokens("SampleFile5.txt", "5", newline, 1)\n'
                   'string g = File_GetToken("SampleFile5.txt", "5", newline, 2, 1)')
    assert (v.t, v.g) == (["Hello World!", "Hello TM Robot!"], "Hello TM Robot!")


def test_the_files_stay_in_the_sandbox(robot, tmp_path) -> None:  # type: ignore[no-untyped-def]
    """A link planted in TextFiles is refused, never followed (docs/security.md)."""
    outside = tmp_path / "secret.txt"
    outside.write_text("secret")
    root = robot.sim.files.root().box.root
    (root / "TextFiles" / "link.txt").symlink_to(outside)
    with pytest.raises(TMError):
        run_packet('string s = File_ReadText("link.txt")')
    v = run_packet('bool w = File_WriteText("link.txt", "overwritten")')
    assert v.w is False and outside.read_text() == "secret"

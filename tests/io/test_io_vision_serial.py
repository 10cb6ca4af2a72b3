"""Vision without and with a simulated server; serial ports: unmapped, loop-back, pseudo-terminal."""

from __future__ import annotations

import os
import threading
import time
from collections.abc import Iterator

import pytest

from gplrt.io.files import StreamReader, StreamWriter
from gplrt.io.flashroot import FlashRoot
from gplrt.io.serial import LoopbackPort, PtyPort, configure_serial
from gplrt.io.vision import ScriptedVisionServer, Vision, VisionToolResult, VisResult, set_vision_server
from gplrt.lang.errors import GplException


@pytest.fixture
def no_vision() -> Iterator[None]:
    set_vision_server(None)
    yield
    set_vision_server(None)


def test_vision_without_server_names_what_is_missing(no_vision: None) -> None:
    vis = Vision()  # creating the object does not communicate
    assert vis.Status == 0
    for call in (lambda: vis.Process("Main"), lambda: vis.ResultCount("part1"), lambda: vis.Result("part1", 1)):
        with pytest.raises(GplException) as exc:
            call()
        assert exc.value.ErrorCode == -4000
        assert "no vision server configured in the simulator" in str(exc.value)


def test_vision_ex30_flow_with_scripted_server(no_vision: None) -> None:
    pose = object()  # stands in for the Location the simulation supplies
    server = ScriptedVisionServer()
    server.add_process(
        "Main",
        {
            "part1": [VisionToolResult(loc=pose, info=[1.5, 2.5], info_string="ok", inspect_passed=True)],
            "empty": [],
        },
    )
    set_vision_server(server)
    vis = Vision()
    v_result = VisResult()
    assert v_result.Loc is None and v_result.Type == 0
    vis.Process("Main")
    assert (vis.Status, vis.ErrorCode) == (3, 0)
    assert vis.ResultCount("part1") == 1 and vis.ResultCount("empty") == 0
    v_result = vis.Result("part1", 1)
    assert v_result.Loc is pose and v_result.InfoCount == 2 and v_result.Info(1) == 2.5
    assert v_result.InfoString == "ok" and v_result.InspectPassed is True
    for call, code in (
        (lambda: vis.Result("part1", 2), -4014),
        (lambda: vis.ResultCount("nope"), -4013),
        (lambda: v_result.Info(2), -4014),
    ):
        with pytest.raises(GplException) as exc:
            call()
        assert exc.value.ErrorCode == code
    with pytest.raises(GplException) as exc:
        vis.Process("Other")
    assert exc.value.ErrorCode == -4012 and vis.Status == 2 and vis.ErrorCode == -4012
    vis.set_ToolProperty("part1", "Threshold", "40")
    assert vis.ToolProperty("part1", "Threshold") == "40"
    assert server.runs == ["Main", "Other"]


@pytest.fixture
def com1() -> Iterator[LoopbackPort]:
    port = LoopbackPort()
    configure_serial("com1", port)
    yield port
    configure_serial("com1", None)


def test_unmapped_serial_port(flash: FlashRoot) -> None:
    configure_serial("com2", None)
    for opener in (StreamReader, StreamWriter):
        with pytest.raises(GplException) as exc:
            opener("/dev/com2")
        assert exc.value.ErrorCode == -309
        assert "/dev/com2" in str(exc.value)


def test_ex25_serial_loopback(flash: FlashRoot, com1: LoopbackPort) -> None:
    o = StreamWriter("/dev/com1")
    i = StreamReader("/dev/com1")
    assert o.AutoFlush is True  # serial ports default to AutoFlush (D0:3908-3911)
    o.NewLine = chr(13)
    assert i.Peek() == -1  # nothing typed yet: Peek does not block
    o.WriteLine("Hi")
    assert [i.Read(), i.Read(), i.Read()] == [ord("H"), ord("i"), 13]
    o.Write(chr(27))  # ESC ends EX-25's loop
    c = i.Read()
    ss = chr(c) if c >= 0x20 else "^" + chr(c + 0x40)
    assert (c, ss) == (27, "^[")
    o.Write("line one\r\nline two\n")
    assert i.ReadLine() == "line one" and i.ReadLine() == "line two"
    i.Close()
    o.Close()


def test_serial_read_waits_for_data_from_another_thread(flash: FlashRoot, com1: LoopbackPort) -> None:
    i = StreamReader("/dev/com1")
    threading.Timer(0.05, lambda: com1.write(b"Z")).start()
    start = time.monotonic()
    assert i.Read() == ord("Z")
    assert time.monotonic() - start >= 0.04


def test_serial_pseudo_terminal(flash: FlashRoot) -> None:
    pty = PtyPort()
    configure_serial("com3", pty)
    try:
        outside = os.open(pty.device_path, os.O_RDWR | os.O_NOCTTY)
        o = StreamWriter("/dev/com3")
        o.WriteLine("ping")
        got = b""
        deadline = time.monotonic() + 5
        while len(got) < 6 and time.monotonic() < deadline:
            got += os.read(outside, 100)
        assert got == b"ping\r\n"
        os.write(outside, b"pong\r")
        i = StreamReader("/dev/com3")
        assert i.ReadLine() == "pong"
        os.close(outside)
    finally:
        configure_serial("com3", None)
        pty.close()

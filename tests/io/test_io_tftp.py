"""EX-21 (TFTP write over UDP, reading the file with StreamReader.Read) against a small TFTP server."""

from __future__ import annotations

import socket
import threading

from gplrt.io.files import StreamReader, StreamWriter
from gplrt.io.flashroot import FlashRoot
from gplrt.io.sockets import IPEndPoint, UdpClient


def tftp_server(listen: socket.socket, received: bytearray) -> None:
    """Accept one write request; answer from a new port (the TFTP transfer ID) like real servers."""
    listen.settimeout(5)
    request, client = listen.recvfrom(1500)
    assert request[:2] == b"\x00\x02"
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as xfer:
        xfer.bind(("127.0.0.1", 0))
        xfer.settimeout(5)
        xfer.sendto(b"\x00\x04\x00\x00", client)  # ACK block 0
        while True:
            packet, _ = xfer.recvfrom(1500)
            assert packet[:2] == b"\x00\x03"
            received += packet[4:]
            xfer.sendto(b"\x00\x04" + packet[2:4], client)
            if len(packet) - 4 < 512:
                return


def test_ex21_tftp_write(flash: FlashRoot, cell: type) -> None:
    content = bytes((i * 7 + 3) % 256 for i in range(1200))  # three blocks: 512, 512, 176
    w = StreamWriter("/flash/testfile.txt")
    w.Write(content.decode("latin-1"))
    w.Close()

    listen = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    listen.bind(("127.0.0.1", 0))
    received = bytearray()
    server = threading.Thread(target=tftp_server, args=(listen, received), daemon=True)
    server.start()

    console: list[str] = []
    # --- EX-21 TftpWrite, statement by statement -------------------------------------------
    file = "testfile.txt"
    srv_ep = IPEndPoint("127.0.0.1", listen.getsockname()[1])
    rem_ep, ep = cell(None), cell(None)
    inp = cell("")
    in_file = StreamReader("/flash/" + file)
    uc = UdpClient()
    us = uc.Client()
    us.ReceiveTimeout = 5000
    out = chr(0) + chr(2) + file + chr(0) + "octet" + chr(0)
    us.SendTo(out, 0, srv_ep)
    us.ReceiveFrom(inp, 1500, rem_ep)
    op = ord(inp.get()[0]) * 256 + ord(inp.get()[1])
    console.append("Open response: " + str(op))
    assert op == 4
    block = 1
    while True:
        out = ""
        for _ in range(512):
            c = in_file.Read()
            if c < 0:
                break
            out += chr(c)
        out = chr(0) + chr(3) + chr(block // 256) + chr(block % 256) + out
        us.SendTo(out, 0, rem_ep.get())
        us.ReceiveFrom(inp, 1500, ep)
        if ep.get().IPAddress != rem_ep.get().IPAddress or ep.get().Port != rem_ep.get().Port:
            console.append("Address mismatch")
            break
        ack = ord(inp.get()[2]) * 256 + ord(inp.get()[3])
        if ack != block:
            console.append("Ack block mismatch")
        block += 1
        if c < 0:
            break
    console.append("Transfer complete")
    us.Close()
    in_file.Close()
    # ------------------------------------------------------------------------------------------
    server.join(5)
    listen.close()
    assert console == ["Open response: 4", "Transfer complete"]
    assert bytes(received) == content
    assert rem_ep.get().Port != srv_ep.Port  # the reply came from the server's transfer port

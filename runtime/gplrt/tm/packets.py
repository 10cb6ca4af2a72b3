"""The TM packet frame (manual L17711-L17773): ``$HEADER,LENGTH,DATA,*CS\\r\\n``.

LENGTH is the UTF-8 byte count of DATA in decimal, ``0x`` hex or ``0b`` binary; CS is the XOR of
every byte between ``$`` and ``*`` as two hex digits.  We send upper-case hex, as the manual does,
and accept either case (clients differ).  :func:`split` cuts a byte stream into frames and says,
for a bad one, which CPERR code it earns: 01 packet, 02 checksum, 03 header.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

HEADERS = (b"TMSCT", b"TMSTA", b"CPERR", b"TMSVR")


def checksum(body: bytes) -> int:
    cs = 0
    for b in body:
        cs ^= b
    return cs


def encode(header: str | bytes, data: bytes) -> bytes:
    """One frame (``data`` already UTF-8)."""
    h = header.encode() if isinstance(header, str) else header
    body = h + b"," + str(len(data)).encode() + b"," + data + b","
    return b"$" + body + b"*" + f"{checksum(body):02X}".encode() + b"\r\n"


@dataclass
class Frame:
    header: bytes
    data: bytes
    error: int = 0  # 0 good, else the CPERR code


def _length(text: bytes) -> int | None:
    try:
        t = text.decode("ascii").strip()
        low = t.lower()
        n = int(low[2:], 16) if low.startswith("0x") else int(low[2:], 2) if low.startswith("0b") else int(t, 10)
    except (UnicodeDecodeError, ValueError):
        return None
    return n if 0 <= n < 2**31 else None


_END = re.compile(rb",\*[0-9A-Fa-f]{2}\r\n")


def _drop_bad(buf: bytearray, frm: int, header: bytes, out: list[Frame], at_end: bool) -> bool:
    """Drop a malformed frame up to the next ``,*CS\r\n`` (when ``at_end``: only if the buffer
    ends there, else more data may still come); whether one was dropped."""
    m = _END.search(buf, frm)
    if m is None or (at_end and m.end() != len(buf)):
        return False
    # a well-formed frame inside what is dropped (a client's packet after garbage) is kept
    k = buf.rfind(b"$", 1, m.start())
    while k > 0:
        if _whole(bytes(buf[k:m.end()])):
            del buf[:k]
            out.append(Frame(header, b"", 1))
            return True
        k = buf.rfind(b"$", 1, k)
    del buf[:m.end()]
    out.append(Frame(header, b"", 1))
    return True


def _whole(frame: bytes) -> bool:
    """Whether ``frame`` (from ``$`` to ``\r\n``) is one frame whose length and checksum agree."""
    c1 = frame.find(b",")
    c2 = frame.find(b",", c1 + 1) if c1 > 0 else -1
    n = _length(frame[c1 + 1:c2]) if c2 > 0 else None
    if n is None or len(frame) != c2 + 1 + n + 6:
        return False
    try:
        return int(frame[-4:-2], 16) == checksum(frame[1:-5])
    except ValueError:
        return False


def split(buf: bytearray) -> list[Frame]:
    """The complete frames at the start of ``buf`` (removed from it); an incomplete one stays."""
    out: list[Frame] = []
    while True:
        start = buf.find(b"$")
        if start < 0:
            buf.clear()
            return out
        del buf[:start]
        c1 = buf.find(b",")
        c2 = buf.find(b",", c1 + 1) if c1 >= 0 else -1
        if c2 < 0:
            if not _drop_bad(buf, 0, b"", out, at_end=False):
                return out
            continue
        header = bytes(buf[1:c1])
        n = _length(bytes(buf[c1 + 1:c2]))
        if n is None:  # a negative or unreadable length: a packet error (L18093)
            if not _drop_bad(buf, c2, header, out, at_end=False):
                return out
            continue
        tail = c2 + 1 + n
        if len(buf) < tail + 6:  # more to come, or a length longer than the data
            if not _drop_bad(buf, c2, header, out, at_end=True):
                return out
            continue
        if buf[tail:tail + 2] != b",*" or buf[tail + 4:tail + 6] != b"\r\n":
            if not _drop_bad(buf, c2, header, out, at_end=False):
                return out
            continue
        body = bytes(buf[1:tail + 1])
        cs_text = bytes(buf[tail + 2:tail + 4])
        data = bytes(buf[c2 + 1:tail])
        del buf[:tail + 6]
        try:
            cs = int(cs_text, 16)
        except ValueError:
            cs = -1
        if cs != checksum(body):
            out.append(Frame(header, data, 2))
        elif header not in HEADERS:
            out.append(Frame(header, data, 3))
        else:
            out.append(Frame(header, data))

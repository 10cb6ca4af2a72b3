"""Values to bytes and back (manual L2066-L3283, L4589-L5548): little endian unless a parameter
says otherwise; float/double IEEE-754; strings UTF-8; bool 1/0 (L883-L941)."""

from __future__ import annotations

import struct

import numpy as np

from gplrt.tm.values import F32, F64, Array, TMError, to_int


def _scalar_bytes(v: object, big: bool) -> bytes:
    order = ">" if big else "<"
    if isinstance(v, bool):
        return b"\x01" if v else b"\x00"
    if isinstance(v, str):
        return v.encode("utf-8")
    if isinstance(v, (int, np.integer)):
        n = int(v)
        if 0 <= n <= 255:
            return bytes([n])
        return struct.pack(order + "i", to_int(n))
    if type(v) is F64:
        return struct.pack(order + "d", float(v))
    if isinstance(v, (float, np.floating)):
        return struct.pack(order + "f", float(F32(v)))
    raise TMError(f"GetBytes: cannot convert {v!r}")


def GetBytes(value: object, option: object = 0, fmt: object = None) -> Array:
    """``value`` as bytes (L4869): ``option`` 1 = big endian for numbers; an ``int[]``'s elements
    are 4 bytes each, a ``byte[]``'s one; ``GetBytes(int, endian, fmt)`` (L5021)."""
    if fmt is not None and not isinstance(value, (list, tuple)):
        return GetBytes3(value, option, fmt)
    big = to_int(option) == 1
    if isinstance(value, Array):
        if value.type == "byte":
            return Array("byte", value)
        if value.type == "int":
            return Array("byte", b"".join(struct.pack((">" if big else "<") + "i", v) for v in value))
        if value.type == "string" and big:
            return Array("byte", b"\x00\x00".join(str(v).encode("utf-8") for v in value))
        return Array("byte", b"".join(_scalar_bytes(v, big) for v in value))
    if isinstance(value, (list, tuple)):
        return Array("byte", b"".join(_scalar_bytes(v, big) for v in value))
    return Array("byte", _scalar_bytes(value, big))


def _bytes(b: object, name: str) -> bytes:
    if not isinstance(b, (list, tuple)):
        raise TMError(f"{name}: a byte[] is needed")
    return bytes(int(x) & 0xFF for x in b)  # type: ignore[call-overload]


def _take(b: object, n: int, endian: object, name: str) -> bytes:
    """The first ``n`` bytes of ``b``, zero-padded, in little-endian order (L2068)."""
    raw = _bytes(b, name)[:n].ljust(n, b"\x00")
    return raw[::-1] if to_int(endian) == 1 else raw


def Byte_ToInt16(b: object, endian: object = 0, unsigned: object = 0) -> int:
    """The first two bytes as an int16 (or unsigned with ``unsigned`` = 1) (L2068)."""
    v = int.from_bytes(_take(b, 2, endian, "Byte_ToInt16"), "little", signed=to_int(unsigned) != 1)
    return v


def Byte_ToInt32(b: object, endian: object = 0) -> int:
    return int.from_bytes(_take(b, 4, endian, "Byte_ToInt32"), "little", signed=True)


def Byte_ToFloat(b: object, endian: object = 0) -> F32:
    return F32(struct.unpack("<f", _take(b, 4, endian, "Byte_ToFloat"))[0])


def Byte_ToDouble(b: object, endian: object = 0) -> F64:
    return F64(struct.unpack("<d", _take(b, 8, endian, "Byte_ToDouble"))[0])


def Byte_ToString(b: object, encoding: object = 0) -> str:
    """0 UTF-8 up to the first 0x00, 1 hex text, 2 ASCII (L2573)."""
    raw = _bytes(b, "Byte_ToString")
    enc = to_int(encoding)
    if enc == 1:
        return raw.hex().upper()
    raw = raw.split(b"\x00", 1)[0]
    if enc == 2:
        return "".join(chr(c) if c < 128 else "?" for c in raw)
    return raw.decode("utf-8", "replace")


def String_ToByte(s: object, encoding: object = 0) -> Array:
    """0 UTF-8, 1 hex text (up to the first non-hex digit, an odd count padded), 2 ASCII (L3224)."""
    text = str(s)
    enc = to_int(encoding)
    if enc == 1:
        digits = ""
        for c in text:
            if c not in "0123456789abcdefABCDEF":
                break
            digits += c
        if len(digits) % 2:
            digits += "0"
        return Array("byte", bytes.fromhex(digits))
    if enc == 2:
        return Array("byte", bytes(ord(c) if ord(c) < 128 else 0x3F for c in text))
    return Array("byte", text.encode("utf-8"))


def Byte_Concat(*args: object) -> Array:
    """The variadic form (L2871-L2906): byte arrays and byte values joined; an argument of another
    type (a string, an int beyond a byte) is ignored, as the manual's examples show."""
    out = bytearray()
    for a in args:
        if isinstance(a, str) or isinstance(a, bool):
            continue
        if isinstance(a, (list, tuple)):
            out += bytes(int(x) & 0xFF for x in a)  # type: ignore[call-overload]
        elif isinstance(a, (int, np.integer)) and 0 <= int(a) <= 255:
            out.append(int(a))
    return Array("byte", out)


def GetBytes3(value: object, endian: object, fmt: object) -> Array:
    """``GetBytes(int, endian, fmt)``: fmt 0 int32, 1 int16 when the value fits, 2 int16 (L5021)."""
    v, big, f = to_int(value), to_int(endian) == 1, to_int(fmt)
    four = struct.pack(">i" if big else "<i", v)
    if f == 0 or (f == 1 and not -32768 <= v <= 65535):
        return Array("byte", four)
    return Array("byte", four[2:] if big else four[:2])


# --- checksums (L6868-L7446) --------------------------------------------------------------------
def _span(b: object, start: object, n: object, name: str) -> bytes | None:
    raw = _bytes(b, name)
    st, m = to_int(start), to_int(n)
    if not 0 <= st < len(raw):
        return None
    return raw[st:] if m < 0 else raw[st:st + m]


def XOR8(b: object, start: object = 0, n: object = -1) -> int:
    """XOR of the bytes (L6868); an invalid start gives 0."""
    data = _span(b, start, n, "XOR8")
    out = 0
    for x in data or b"":
        out ^= x
    return out


def SUM8(b: object, start: object = 0, n: object = -1) -> int:
    return sum(_span(b, start, n, "SUM8") or b"") & 0xFF


def SUM16(b: object, start: object = 0, n: object = -1) -> Array:
    return Array("byte", (sum(_span(b, start, n, "SUM16") or b"") & 0xFFFF).to_bytes(2, "big"))


def SUM32(b: object, start: object = 0, n: object = -1) -> Array:
    return Array("byte", (sum(_span(b, start, n, "SUM32") or b"") & 0xFFFFFFFF).to_bytes(4, "big"))


def _crc_reflected(data: bytes, init: int, poly: int) -> int:
    crc = init
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ poly if crc & 1 else crc >> 1
    return crc & 0xFFFF


def _crc_forward(data: bytes, init: int, poly: int) -> int:
    crc = init
    for byte in data:
        crc ^= byte << 8
        for _ in range(8):
            crc = ((crc << 1) ^ poly) if crc & 0x8000 else crc << 1
            crc &= 0xFFFF
    return crc


def _crc_sick(data: bytes) -> int:
    crc, prev = 0, 0
    for byte in data:
        if crc & 0x8000:
            crc = ((crc << 1) & 0xFFFF) ^ 0x8005
        else:
            crc = (crc << 1) & 0xFFFF
        crc ^= byte | (prev << 8)
        prev = byte
    return crc


_CRC16 = {0: (0x0000, "r", 0xA001), 1: (0xFFFF, "r", 0xA001), 2: (0x0000, "sick", 0x8005),
          3: (0x1D0F, "f", 0x1021), 4: (0xFFFF, "f", 0x1021), 5: (0x0000, "f", 0x1021),
          6: (0x0000, "r", 0x8408),
          # Schunk gripper: the manual's table (L7230) gives init 0xFFFF and polynomial 0x1021.  It
          # writes reflected algorithms with their reflected polynomial (0xA001, 0x8408) and forward
          # ones with the normal form (0x1021 for 3-5), so 0x1021 is forward: CRC-16/CCITT-FALSE,
          # the same computation as 4 (docs/design/tmscript.md).
          7: (0xFFFF, "f", 0x1021)}


def CRC16(*args: object) -> Array:
    """``CRC16([alg,] bytes [, start [, n]])``, big endian (L7203); an invalid start gives the
    initial value; algorithms 0-7 (``_CRC16``)."""
    rest = list(args)
    alg = to_int(rest.pop(0)) if not isinstance(rest[0], (list, tuple)) else 0
    b = rest.pop(0)
    start = rest.pop(0) if rest else 0
    n = rest.pop(0) if rest else -1
    if alg not in _CRC16:
        raise TMError(f"CRC16: algorithm {alg} is not one of 0-7 (L7212)")
    init, kind, poly = _CRC16[alg]
    data = _span(b, start, n, "CRC16")
    if data is None:
        crc = init
    elif kind == "r":
        crc = _crc_reflected(data, init, poly)
    elif kind == "f":
        crc = _crc_forward(data, init, poly)
    else:
        crc = _crc_sick(data)
    return Array("byte", crc.to_bytes(2, "big"))


def CRC32(b: object, start: object = 0, n: object = -1) -> Array:
    import zlib

    data = _span(b, start, n, "CRC32")
    return Array("byte", (zlib.crc32(data) if data is not None else 0).to_bytes(4, "big"))


def write_span(value: object, start: object, length: object) -> object:
    """The part of a string or an array a write takes (``File_Write*``, ``socket_send``, L10410,
    L14149): ``start`` outside it is 0, ``length`` <= 0 to the end; other values whole."""
    if not isinstance(value, (str, list, tuple)):
        return value
    st, n = to_int(start), to_int(length)
    if not 0 <= st < len(value):
        st = 0
    whole = value if isinstance(value, str) else list(value)  # (an Array takes no slice)
    part = whole[st:] if n <= 0 else whole[st:st + n]
    return Array(value.type, part) if isinstance(value, Array) else part


def ValueReverse(value: object, fmt: object = 0) -> object:
    """The value with its bytes in reverse order (L4589): an int as int32 (``fmt`` 0), as int16
    when it fits one (1), or its low 16 bits as int16 (2); a float's 4 bytes, a double's 8; a
    string's characters; an array element by element."""
    if isinstance(value, (list, tuple)):
        kind = getattr(value, "type", None) or "double"
        return Array(kind, [ValueReverse(v, fmt) for v in value])
    if isinstance(value, str):
        return value[::-1]
    if isinstance(value, (bool, np.bool_)):
        raise TMError("ValueReverse: a bool has no bytes to reverse")
    if isinstance(value, (int, np.integer)):
        n, f = to_int(value), to_int(fmt)
        if f == 2 or (f == 1 and -32768 <= n <= 32767):
            return struct.unpack("<h", struct.pack(">H", n & 0xFFFF))[0]
        return struct.unpack("<i", struct.pack(">i", n))[0]
    if isinstance(value, np.float64):
        return F64(struct.unpack("<d", struct.pack(">d", float(value)))[0])
    return F32(struct.unpack("<f", struct.pack(">f", float(F32(value))))[0])

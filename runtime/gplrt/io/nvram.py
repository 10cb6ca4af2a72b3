"""The ``/NVRAM`` record store (D0:3992-4158), with the controller's exact space accounting.

NVRAM files are sequences of atomic **records** of at most 255 bytes.  A file's capacity is fixed
when it is created (``-size n``, 4 <= n <= 7872, default 1024) and is charged **1 byte per file
plus 1 byte per record** on top of the data (D0:4068-4083).  A full file raises -323 *Device full*
unless it was created with ``-wrap``, in which case the oldest records are dropped until the new one
fits.  EX-27 and EX-28 are the test oracles: ``WriteLine("Record n")`` with the default
``AutoFlush = True`` writes one record of 10-11 bytes including CR-LF.

Damage (the manual describes none; decided from its power-fail model, D0:4004-4007, 4068-4073):
records are written atomically, "the data actively being written may be lost" and the complete
records never are.  So a host file whose last record is cut short (a copy interrupted, a disk that
filled) is read as that model reads it: its complete records, the partial one dropped rather than
returned as data.  The loss is posted to the controller's error log (-519, ``_report_lost_record``)
and the host file is rewritten without it, so the report comes once and later writes follow the
last complete record.  Anything no controller could have written is -519 *Invalid file format*.

Host format (private to this module): ``b"GPLNV"``, size (2 bytes, big-endian), wrap flag
(1 byte), then each record as one length byte followed by its data.  Only file names ``file1`` ..
``file16`` exist (D0:4037-4040).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from gplrt.io.sandbox import SandboxPath
from gplrt.lang.errors import (
    DEVICE_FULL,
    INVALID_ARGUMENT,
    INVALID_FILE_FORMAT,
    INVALID_FILE_NAME,
    VALUE_OUT_OF_RANGE,
    GplException,
)
from gplrt.session import current_session
from gplrt.threads.scheduler import current_ctx


MAGIC = b"GPLNV"
MIN_SIZE, MAX_SIZE, DEFAULT_SIZE = 4, 7872, 1024
MAX_RECORD = 255
_NAME = re.compile(r"file([1-9]|1[0-6])")


@dataclass(frozen=True)
class NvramSwitches:
    """``-size n`` and ``-wrap`` parsed from the text after an NVRAM path."""

    size: int | None = None
    wrap: bool = False


def split_switches(path: str) -> tuple[str, NvramSwitches]:
    """``"/NVRAM/file2 -size 64 -wrap"`` -> ``("/NVRAM/file2", NvramSwitches(64, True))``."""
    words = path.split()
    if not words:
        return path, NvramSwitches()
    size: int | None = None
    wrap = False
    rest = words[1:]
    i = 0
    while i < len(rest):
        word = rest[i].lower()
        if word == "-wrap":
            wrap = True
        elif word == "-size" and i + 1 < len(rest) and rest[i + 1].isdigit():
            size = int(rest[i + 1])
            i += 1
        else:
            raise GplException(INVALID_ARGUMENT, detail=f"{path!r}: unknown NVRAM switch {rest[i]!r}")
        i += 1
    if size is not None and not MIN_SIZE <= size <= MAX_SIZE:
        raise GplException(VALUE_OUT_OF_RANGE, detail=f"NVRAM -size {size}: must be {MIN_SIZE}..{MAX_SIZE}")
    return words[0], NvramSwitches(size, wrap)


def check_name(file: SandboxPath) -> None:
    """Only ``file1`` .. ``file16`` exist on the NVRAM device (no folders in it)."""
    if len(file.parts) != 2 or file.parts[0] != "NVRAM" or not _NAME.fullmatch(file.name):
        raise GplException(INVALID_FILE_NAME, detail=f"NVRAM files are file1..file16, not {'/'.join(file.parts[1:])!r}")


@dataclass
class NvramFile:
    """One NVRAM file: capacity, wrap mode and its records."""

    size: int = DEFAULT_SIZE
    wrap: bool = False
    records: list[bytes] = field(default_factory=list)

    @property
    def used(self) -> int:
        return 1 + sum(len(r) + 1 for r in self.records)

    def append(self, data: bytes) -> None:
        """Store ``data`` as records (split at 255 bytes), each atomic."""
        for start in range(0, len(data), MAX_RECORD):
            self._append_record(data[start : start + MAX_RECORD])

    def _append_record(self, record: bytes) -> None:
        need = len(record) + 1
        if 1 + need > self.size:
            raise GplException(DEVICE_FULL, detail=f"record of {len(record)} bytes exceeds the NVRAM file")
        if self.used + need > self.size:
            if not self.wrap:
                raise GplException(DEVICE_FULL, detail=f"NVRAM file of {self.size} bytes is full")
            while self.used + need > self.size:
                self.records.pop(0)
        self.records.append(record)

    def data(self) -> bytes:
        return b"".join(self.records)

    # -- host storage ---------------------------------------------------------------------------

    @classmethod
    def load(cls, host: SandboxPath) -> NvramFile:
        """Read the host file; a cut-off last record is dropped and reported (module docstring).

        Anything else a controller could not have written (a bad or short header, a size outside
        4..7872, a wrap flag other than 0/1, records beyond the size) is -519 *Invalid file format*
        and the host file is left as it is.
        """
        raw = host.read_bytes()
        header = len(MAGIC) + 3
        if not raw.startswith(MAGIC) or len(raw) < header:
            raise GplException(INVALID_FILE_FORMAT, detail=f"{host.name} is not an NVRAM file")
        size = int.from_bytes(raw[len(MAGIC) : len(MAGIC) + 2], "big")
        wrap_flag = raw[header - 1]
        if not MIN_SIZE <= size <= MAX_SIZE or wrap_flag > 1:
            raise GplException(INVALID_FILE_FORMAT, detail=f"{host.name}: damaged NVRAM header")
        nv = cls(size, bool(wrap_flag))
        pos = header
        while pos < len(raw):
            length = raw[pos]
            if pos + 1 + length > len(raw):
                nv._check_capacity(host)
                _report_lost_record(host, length, len(raw) - pos - 1)
                nv.save(host)  # repaired: the next write follows the last complete record
                return nv
            nv.records.append(raw[pos + 1 : pos + 1 + length])
            pos += 1 + length
        nv._check_capacity(host)
        return nv

    def _check_capacity(self, host: SandboxPath) -> None:
        if self.used > self.size:
            raise GplException(
                INVALID_FILE_FORMAT, detail=f"{host.name}: {self.used} bytes of records in a file of {self.size}"
            )

    def save(self, host: SandboxPath) -> None:
        out = bytearray(MAGIC)
        out += self.size.to_bytes(2, "big")
        out.append(1 if self.wrap else 0)
        for record in self.records:
            out.append(len(record))
            out += record
        # Atomic, like the controller's record writes: a new temporary ".fileN.new", created
        # exclusively (a link planted at that name is removed, never written through), renamed
        # over the file (sandbox.py).
        host.replace(bytes(out))


def _report_lost_record(host: SandboxPath, length: int, present: int) -> None:
    """Post the lost record to the controller's error log (and its console log).

    -519 *Invalid file format* is the code: the manual names none for this (it only promises that
    complete records survive), and -519 is what the rest of this module raises for a damaged file.
    The reading or writing program itself gets its complete records and no exception, as after a
    power failure on a controller.
    """
    ctx = current_ctx()
    text = (
        f"NVRAM {host.name}: last record cut off ({present} of {length} bytes), "
        "lost as a write interrupted by a power failure; the complete records are kept"
    )
    current_session().report(ctx.name if ctx is not None else "<external>", text, INVALID_FILE_FORMAT)


def open_for_write(host: SandboxPath, switches: NvramSwitches, append: bool) -> NvramFile:
    """The NVRAM file to write: existing (size fixed until deleted) or created with the switches."""
    check_name(host)
    try:
        nv = NvramFile.load(host)
    except FileNotFoundError:
        nv = NvramFile(switches.size or DEFAULT_SIZE, switches.wrap)
    else:
        if not append:
            nv.records.clear()
        if switches.wrap:
            nv.wrap = True
    nv.save(host)
    return nv


def read_data(host: SandboxPath) -> bytes:
    """All bytes of an NVRAM file, records concatenated (what a StreamReader sees)."""
    check_name(host)
    return NvramFile.load(host).data()

"""GPL file I/O: the ``File`` class (Shared members), ``StreamReader`` and ``StreamWriter``.

Paths are controller paths (``/flash/...``, ``/ROMDISK/...``, ``/NVRAM/file1``, ``/dev/com1``),
checked and mapped into the sandbox by :mod:`gplrt.io.flashroot`; serial devices route to
:mod:`gplrt.io.serial`, NVRAM files to :mod:`gplrt.io.nvram`.  Streams carry 8-bit bytes, one per
GPL character (D0:3653-3660).

Decisions where the manual is silent (D0 §14, gpl-classes.md §14):

* ``Read``/``Peek`` return -1 at end of file (EX-21, EX-24); on a serial port ``Peek`` returns -1
  while no byte has arrived and ``Read`` waits for one.
* ``ReadLine`` strips the terminator (LF, CR or CR-LF); at end of file with nothing left to read it
  raises -505 *Unexpected end of file* rather than returning "" forever (programs test ``Peek``).
* ``WriteLine`` appends ``NewLine`` (default CR-LF, D0:3827) and counts as one write (one NVRAM
  record).  Output is buffered (4 KB) unless ``AutoFlush``; defaults: False for files, True for
  serial ports and /NVRAM (D0:3822-3824, 3908-3911, 4076-4078).  ``Close`` flushes.
* Using a closed stream raises -520 *File not open*; ``Close`` twice is harmless.  A StreamWriter
  freed without ``Close`` (its object went out of scope) writes its buffered output and closes.
* ``File.Copy(src, dst, overwrite=False)``: like VB.NET, an existing destination is refused with
  -510 *File already exists* unless ``overwrite`` is True.
* ``File.ComputeCRC`` returns the CRC-32 (zlib polynomial) of the file as a signed Integer; the
  controller's CRC algorithm is not documented.

Error codes: missing file -508, cannot open for write -509, not a file / not a directory -521,
directory not empty -202 (no closer code exists), read failure -513, write failure -512.
"""

from __future__ import annotations

import errno
import io
import os
import shutil
import stat
import threading
import weakref
import zlib
from typing import BinaryIO

from gplrt.io import nvram
from gplrt.io._arrays import make_array
from gplrt.io._codec import as_text, from_bytes, to_bytes
from gplrt.io.flashroot import (
    ControllerPath,
    DeviceKind,
    FlashRoot,
    get_flash_root,
    resolve,
    set_flash_root,
)
from gplrt.io.sandbox import Kind, SandboxPath
from gplrt.io.serial import SerialPort, open_port
from gplrt.lang.errors import (
    CANT_CREATE_DIRECTORY,
    CANT_OPEN_FOR_WRITE,
    FILE_EXISTS,
    FILE_NOT_FOUND,
    FILE_NOT_OPEN,
    INVALID_ARGUMENT,
    INVALID_FILE_TYPE,
    READ_ERROR,
    UNEXPECTED_EOF,
    WRITE_ERROR,
    GplException,
    host_reason,
)
from gplrt.lang.gpltypes import Boolean, Integer, String

__all__ = ["File", "StreamReader", "StreamWriter", "FlashRoot", "set_flash_root", "get_flash_root"]


BUFFER_SIZE = 4096
CR, LF = 13, 10


def _open_path(path: str) -> ControllerPath:
    """Resolve a controller path, splitting NVRAM switches off first."""
    return resolve(path)


def _disk_path(path: str) -> ControllerPath:
    """A path on a disk or NVRAM device (not a serial port)."""
    cp = resolve(path)
    if cp.file is None:
        raise GplException(INVALID_FILE_TYPE, detail=f"{path!r} is a device, not a file")
    return cp


def _file_error(exc: OSError, text: str, code: int) -> GplException:
    """The GPL error for a host error on ``text``: missing -> -508, a folder -> -521, else ``code``.

    Links, several hard links and special files never get here: the sandbox refuses them itself
    with -208 / -521 (gplrt.io.sandbox)."""
    if isinstance(exc, FileNotFoundError | NotADirectoryError):
        return GplException(FILE_NOT_FOUND, detail=text)
    if isinstance(exc, IsADirectoryError):
        return GplException(INVALID_FILE_TYPE, detail=f"{text!r} is a directory")
    return GplException(code, detail=f"{text}: {host_reason(exc)}")


def _same_file(a: os.stat_result, b: os.stat_result) -> bool:
    return (a.st_dev, a.st_ino) == (b.st_dev, b.st_ino)


def _file_bytes(cp: ControllerPath) -> bytes:
    """Every data byte of a disk or NVRAM file (NVRAM: its records, concatenated)."""
    assert cp.file is not None
    try:
        if cp.kind is DeviceKind.NVRAM:
            return nvram.read_data(cp.file)
        return cp.file.read_bytes()
    except OSError as exc:
        raise _file_error(exc, cp.text, READ_ERROR) from None


class File:
    """GPL ``File``: Shared members that manage whole files and directories (D0:3675-3707)."""

    @staticmethod
    def ComputeCRC(path: String) -> Integer:
        """CRC-32 of the file's bytes, as a signed 32-bit Integer (read through the file)."""
        crc = zlib.crc32(_file_bytes(_disk_path(path)))
        return Integer(crc - (1 << 32) if crc >= 1 << 31 else crc)

    @staticmethod
    def ComputeLength(path: String) -> Integer:
        """Length in bytes, found by reading the whole file."""
        return Integer(len(_file_bytes(_disk_path(path))))

    @staticmethod
    def Length(path: String) -> Integer:
        """Length in bytes from the directory entry (NVRAM: the data bytes of its records)."""
        cp = _disk_path(path)
        if cp.kind is DeviceKind.NVRAM:
            return Integer(len(_file_bytes(cp)))
        assert cp.file is not None
        try:
            return Integer(cp.file.file_size())
        except OSError as exc:
            raise _file_error(exc, path, READ_ERROR) from None

    @staticmethod
    def Copy(source_file: String, destination_file: String, overwrite: Boolean = Boolean(False)) -> None:
        """Copy one file; an existing destination needs ``overwrite = True``."""
        src = _disk_path(source_file)
        dst = resolve(destination_file)
        if dst.file is None or dst.kind is not DeviceKind.DISK or src.kind is not DeviceKind.DISK:
            raise GplException(INVALID_FILE_TYPE, detail="File.Copy copies disk files only")
        assert src.file is not None
        try:
            reader = src.file.open("r")
        except OSError as exc:
            raise _file_error(exc, source_file, READ_ERROR) from None
        with reader:
            there = dst.file.lstat()
            if there is not None and stat.S_ISDIR(there.st_mode):
                raise GplException(INVALID_FILE_TYPE, detail=f"{destination_file!r} is a directory")
            if there is not None and not overwrite:
                raise GplException(FILE_EXISTS, detail=destination_file)
            if there is not None and _same_file(there, os.fstat(reader.fileno())):
                # Opening the destination for writing would empty the source: leave it as it is.
                raise GplException(WRITE_ERROR, detail=f"{source_file!r} and {destination_file!r} are the same file")
            try:
                with dst.file.open("w") as writer:
                    shutil.copyfileobj(reader, writer)
            except (FileNotFoundError, NotADirectoryError):
                raise GplException(FILE_NOT_FOUND, detail=f"no folder for {destination_file!r}") from None
            except OSError as exc:
                raise _file_error(exc, destination_file, WRITE_ERROR) from None

    @staticmethod
    def CreateDirectory(path: String) -> None:
        """Create a directory and any missing parents; an existing directory is fine."""
        cp = resolve(path)
        if cp.file is None or cp.kind is not DeviceKind.DISK:
            raise GplException(CANT_CREATE_DIRECTORY, detail=f"{path!r}: not on a disk device")
        try:
            cp.file.mkdir()
        except (FileExistsError, NotADirectoryError):
            raise GplException(CANT_CREATE_DIRECTORY, detail=f"{path!r}: a file is in the way") from None
        except OSError as exc:
            raise GplException(CANT_CREATE_DIRECTORY, detail=f"{path}: {host_reason(exc)}") from None

    @staticmethod
    def DeleteDirectory(path: String) -> None:
        """Delete one empty directory."""
        cp = resolve(path)
        found = cp.file.lstat() if cp.file is not None else None
        if cp.file is None or found is None:
            raise GplException(FILE_NOT_FOUND, detail=path)
        if cp.file.is_top or not (stat.S_ISDIR(found.st_mode) or stat.S_ISLNK(found.st_mode)):
            raise GplException(INVALID_FILE_TYPE, detail=f"{path!r} is not a deletable directory")
        try:
            cp.file.rmdir()  # a link is refused (-208), not removed
        except OSError as exc:
            if exc.errno in (errno.ENOTEMPTY, errno.EEXIST):
                raise GplException(INVALID_ARGUMENT, detail=f"directory {path!r} is not empty") from None
            raise _file_error(exc, path, WRITE_ERROR) from None

    @staticmethod
    def DeleteFile(path: String) -> None:
        """Delete one file."""
        cp = _disk_path(path)
        assert cp.file is not None
        try:
            cp.file.unlink()
        except OSError as exc:
            raise _file_error(exc, path, WRITE_ERROR) from None

    @staticmethod
    def GetDirectories(path: String) -> list[String]:
        """Names (not paths) of the sub-directories of ``path``, sorted, as a String array."""
        return make_array(File._listing(path, Kind.FOLDER), String)

    @staticmethod
    def GetFiles(path: String) -> list[String]:
        """Names (not paths) of the files in ``path``, sorted, as a String array."""
        return make_array(File._listing(path, Kind.FILE), String)

    @staticmethod
    def _listing(path: str, kind: Kind) -> list[str]:
        """Sorted names of one kind; links and special files are neither files nor folders here."""
        entries = folder_entries(resolve(path), path)
        # No controller name starts with "." (the NVRAM's temporary files do).
        return sorted(name for name, found in entries if found is kind and not name.startswith("."))


def folder_entries(cp: ControllerPath, path: str) -> list[tuple[str, Kind]]:
    """The names and kinds in the controller folder ``cp`` (``path`` as the program wrote it),
    unsorted, with the controller's codes for what cannot be listed: a device or a file -521, a
    missing folder -508 (the console's ``Dir`` lists through it too)."""
    if cp.file is None:
        raise GplException(INVALID_FILE_TYPE, detail=f"{path!r} is a device")
    try:
        return cp.file.entries()
    except NotADirectoryError:
        raise GplException(INVALID_FILE_TYPE, detail=f"{path!r} is not a directory") from None
    except OSError as exc:
        raise _file_error(exc, path, READ_ERROR) from None


class _SerialSource:
    """Reader side of a serial port: Peek never blocks, Read waits for a byte."""

    def __init__(self, port: SerialPort) -> None:
        self.port = port

    def peek(self) -> int:
        return self.port.peek()

    def read(self) -> int:
        return self.port.read(None)

    def close(self) -> None:
        pass


class _FileSource:
    """Reader side of a file: Peek/Read return -1 at end of file."""

    def __init__(self, stream: BinaryIO) -> None:
        self.stream = io.BufferedReader(stream) if not isinstance(stream, io.BufferedReader) else stream

    def peek(self) -> int:
        head = self.stream.peek(1)[:1]
        return head[0] if head else -1

    def read(self) -> int:
        byte = self.stream.read(1)
        return byte[0] if byte else -1

    def close(self) -> None:
        self.stream.close()


class StreamReader:
    """``New StreamReader(path)``: read a file, an NVRAM file or a serial port byte by byte."""

    def __init__(self, path: String) -> None:
        self._lock = threading.RLock()
        self._path = path
        cp = _open_path(path)
        self._source: _SerialSource | _FileSource | None
        if cp.kind is DeviceKind.SERIAL:
            self._source = _SerialSource(open_port(cp.device))
            return
        if cp.kind is DeviceKind.NVRAM:
            path_only, _ = nvram.split_switches(path)
            cp = _disk_path(path_only)
            self._source = _FileSource(io.BytesIO(_file_bytes(cp)))  # type: ignore[arg-type]
            return
        assert cp.file is not None
        try:
            self._source = _FileSource(cp.file.open("r"))
        except OSError as exc:
            raise _file_error(exc, path, READ_ERROR) from None

    def _open(self) -> _SerialSource | _FileSource:
        if self._source is None:
            raise GplException(FILE_NOT_OPEN, detail=f"StreamReader {self._path!r} is closed")
        return self._source

    def Close(self) -> None:
        with self._lock:
            if self._source is not None:
                self._source.close()
                self._source = None

    def Peek(self) -> Integer:
        """The next byte (0-255) without removing it; -1 at end of file or no serial data yet."""
        with self._lock:
            return Integer(self._open().peek())

    def Read(self) -> Integer:
        """The next byte (0-255), removed; -1 at end of file."""
        with self._lock:
            return Integer(self._open().read())

    def ReadLine(self) -> String:
        """One line without its terminator (LF, CR or CR-LF); -505 when nothing is left."""
        with self._lock:
            source = self._open()
            if isinstance(source, _FileSource) and source.peek() < 0:
                raise GplException(UNEXPECTED_EOF, detail=f"ReadLine at end of {self._path!r}")
            line = bytearray()
            while True:
                byte = source.read()
                if byte < 0 or byte == LF:
                    break
                if byte == CR:
                    if source.peek() == LF:
                        source.read()
                    break
                line.append(byte)
            return String(from_bytes(bytes(line)))


class _FileSink:
    def __init__(self, stream: BinaryIO) -> None:
        self.stream = stream

    def write(self, data: bytes) -> None:
        self.stream.write(data)
        self.stream.flush()

    def close(self) -> None:
        self.stream.close()


class _NvramSink:
    def __init__(self, file: SandboxPath, nv: nvram.NvramFile) -> None:
        self.file, self.nv = file, nv

    def write(self, data: bytes) -> None:
        try:
            self.nv.append(data)
        finally:
            self.nv.save(self.file)  # records written before a -323 stay written

    def close(self) -> None:
        pass


class _SerialSink:
    def __init__(self, port: SerialPort) -> None:
        self.port = port

    def write(self, data: bytes) -> None:
        self.port.write(data)

    def close(self) -> None:
        pass


def _open_sink(path: str, append: bool) -> tuple[_FileSink | _NvramSink | _SerialSink, bool]:
    """The device a StreamWriter writes to, and its AutoFlush default (module docstring)."""
    path_only, switches = (
        nvram.split_switches(path) if path.lower().startswith("/nvram") else (path, None)
    )
    cp = _open_path(path_only)
    if cp.kind is DeviceKind.SERIAL:
        return _SerialSink(open_port(cp.device)), True
    assert cp.file is not None
    try:
        if cp.kind is DeviceKind.NVRAM:
            nv = nvram.open_for_write(cp.file, switches or nvram.NvramSwitches(), append)
            return _NvramSink(cp.file, nv), True
        return _FileSink(cp.file.open("a" if append else "w")), False
    except IsADirectoryError:
        raise GplException(INVALID_FILE_TYPE, detail=f"{path!r} is a directory") from None
    except (FileNotFoundError, NotADirectoryError):
        raise GplException(CANT_OPEN_FOR_WRITE, detail=f"no folder for {path!r}") from None
    except OSError as exc:
        raise GplException(CANT_OPEN_FOR_WRITE, detail=f"{path}: {host_reason(exc)}") from None


def _flush_on_free(buffer: bytearray, sink: _FileSink | _NvramSink | _SerialSink) -> None:
    """Finalizer of a StreamWriter freed without Close: write what it buffered, then close.

    Runs inside garbage collection, where an exception cannot reach the program: a write error
    here is dropped (the program had already let the writer go)."""
    try:
        if buffer:
            sink.write(bytes(buffer))
            buffer.clear()
    except (OSError, GplException):
        pass
    finally:
        sink.close()


class StreamWriter:
    """``New StreamWriter(path [, append])``: write a file, an NVRAM file or a serial port.

    ``append = True`` adds to an existing file; otherwise the file is created or overwritten.
    NVRAM paths may carry ``-size n`` and ``-wrap`` (D0:4044-4061).
    """

    def __init__(self, path: String, append: Boolean = Boolean(False)) -> None:
        self._lock = threading.RLock()
        self._path = path
        self._buffer = bytearray()
        self._newline = "\r\n"
        self._sink: _FileSink | _NvramSink | _SerialSink | None
        self._sink, self._autoflush = _open_sink(path, bool(append))
        # A writer freed without Close (a local StreamWriter at the end of its procedure, as GPL
        # code often leaves it) still writes what it buffered and closes the file, as a controller
        # closes a stream with its last reference; without this its last lines were lost.
        self._freed = weakref.finalize(self, _flush_on_free, self._buffer, self._sink)

    def _open(self) -> _FileSink | _NvramSink | _SerialSink:
        if self._sink is None:
            raise GplException(FILE_NOT_OPEN, detail=f"StreamWriter {self._path!r} is closed")
        return self._sink

    @property
    def AutoFlush(self) -> Boolean:
        return Boolean(self._autoflush)

    @AutoFlush.setter
    def AutoFlush(self, value: Boolean) -> None:
        with self._lock:
            self._autoflush = bool(value)
            if self._autoflush:
                self._flush()

    @property
    def NewLine(self) -> String:
        return String(self._newline)

    @NewLine.setter
    def NewLine(self, value: String) -> None:
        self._newline = str(value)

    def Write(self, value: String) -> None:
        """Write a String (or a number, as CStr prints it) with no terminator."""
        self._emit(as_text(value))

    def WriteLine(self, value: String = String("")) -> None:
        """Write a String or number followed by ``NewLine``, as one write."""
        self._emit(as_text(value) + self._newline)

    def Flush(self) -> None:
        """Write buffered output to the device now."""
        with self._lock:
            self._open()
            self._flush()

    def Close(self) -> None:
        """Flush and close; closing a closed writer does nothing."""
        with self._lock:
            if self._sink is None:
                return
            self._freed.detach()
            try:
                self._flush()
            finally:
                self._sink.close()
                self._sink = None

    def _emit(self, text: str) -> None:
        data = to_bytes(text)
        with self._lock:
            self._open()
            self._buffer += data
            if self._autoflush or len(self._buffer) >= BUFFER_SIZE:
                self._flush()

    def _flush(self) -> None:
        if not self._buffer or self._sink is None:
            return
        data = bytes(self._buffer)
        self._buffer.clear()  # in place: the free-time finalizer holds this same buffer
        try:
            self._sink.write(data)
        except OSError as exc:
            raise GplException(WRITE_ERROR, detail=f"{self._path}: {host_reason(exc)}") from None

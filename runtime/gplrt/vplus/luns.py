"""V+ logical units: ATTACH/DETACH, FOPEN*/FCLOSE, READ/WRITE/GETC and IOSTAT (L7384-7866).

I/O never raises: each operation stores its status on the LUN, read back with ``IOSTAT(lun)``
(1 ok, 0 pending, negative = error code; L7410-7443); GETC returns an error code as its value.
LUNs are per task (L7452-7454) and detached when the task ends (L7476-7489).

Devices, on the core's I/O:

* ``"DISK"``: files in the session's sandboxed flash disk, through ``gplrt.io.files`` (a V+ unit
  prefix ``A:``/``C:``/``D:`` is dropped, ``\\`` becomes ``/``, a relative name is under ``/flash``).  Records end in CR/LF; READ strips
  it; at the end of the file -504.
* ``"TCP"``: a server (``FOPEN (lun, 16) "/LOCAL_PORT p /CLIENTS k"``) or a client
  (``FOPEN (lun) "/REMOTE_IP a /REMOTE_PORT p"``) over ``gplrt.io.sockets`` (loopback unless the
  run allows more, docs/security.md).  A server accepts its client when the program first reads;
  the connection arrives as a **connect notice** of four bytes (the client's handle, a 32-bit
  integer most significant byte first) ahead of the client's data, which READ consumes whole
  (returning "" with IOSTAT 100) and GETC byte by byte; when the client closes, READ returns ""
  with IOSTAT 101 and GETC returns -504, and the next read waits for the next client.  A server
  that only writes takes a waiting client at its next WRITE (without waiting for one).
  docs/design/vplus.md ("the four bytes GETC reads after a client connects") gives the reasons.
  [D] ``/CLIENTS k`` is accepted; clients are served one after another.
"""

from __future__ import annotations

import fnmatch
import re
import struct
from dataclasses import dataclass, field
from typing import Any

from gplrt.io.files import File, StreamReader, StreamWriter
from gplrt.io.sockets import IPEndPoint, Socket, TcpClient, TcpListener
from gplrt.lang.byref import Box
from gplrt.lang.errors import GplException
from gplrt.vplus import errors as E
from gplrt.vplus.operators import to_int
from gplrt.vplus.motion import attach_robot, detach_robot
from gplrt.vplus.strings import render, val
from gplrt.session import current_session
from gplrt.vplus.taskstate import _tables, current_task, safepoint
from gplrt.vplus.values import MAX_STRING, session_data

FREE_LUNS = range(5, 32)  # [D] where ATTACH mode 4 looks for a free LUN
RECORD_MAX = 512


@dataclass
class Lun:
    number: int
    device: str
    status: int = 1
    last_length: int = 0
    reader: StreamReader | None = None
    writer: StreamWriter | None = None
    listener: TcpListener | None = None
    sock: Socket | None = None
    inbuf: bytearray = field(default_factory=bytearray)
    handles: int = 0
    buffer_size: int = 1024
    notice: int = 0  # bytes of the connect notice still unread
    directory: list[str] | None = None  # FOPEND: the directory records still to READ


def _task() -> Any:
    return current_task()


def _lun(lun: Any) -> Lun | None:
    return _task().luns.get(to_int(lun.v if hasattr(lun, "v") else lun))


def _set(lun: Lun, status: int) -> int:
    lun.status = status
    return status


def iostat(lun: Any, mode: Any = 0) -> float:
    """``IOSTAT(lun[, n])``: the last operation's status; n = 2 the last record's length."""
    entry = _lun(lun)
    if entry is None:
        return float(E.NOT_ATTACHED)
    if to_int(mode) == 2:
        return float(entry.last_length)
    return float(entry.status)


def attach(lun: Any, mode: Any = 0, device: str = "") -> None:
    """``ATTACH (lun, mode) "device"``: mode 4 picks a free LUN and stores it in ``lun``'s cell."""
    task = _task()
    m = to_int(mode)
    dev = device.strip().upper() or "DISK"
    if m & 4:
        number = next((n for n in FREE_LUNS if n not in task.luns), None)
        if number is None:
            raise E.VError(E.DEVICE_NOT_READY, detail="no free logical unit")
        lun.v = number
    else:
        number = to_int(lun.v if hasattr(lun, "v") else lun)
    if number == 0:
        attach_robot()
        return
    if number in task.luns:
        task.luns[number].status = E.ALREADY_ATTACHED
        return
    entry = Lun(number, dev)
    _release_at_stop()
    if dev not in ("DISK", "TCP") and not dev.startswith("NFS"):
        entry.status = E.DEVICE_NOT_READY  # serial lines, graphics, the pendant: not simulated
    task.luns[number] = entry


def detach(lun: Any = 0) -> None:
    number = to_int(lun.v if hasattr(lun, "v") else lun)
    if number == 0:
        detach_robot()
        return
    entry = _task().luns.pop(number, None)
    if entry is not None:
        _close(entry)


def detach_all(task: Any) -> None:
    """Every LUN of a task that ends normally (L7476-7477), is run again or is aborted."""
    for entry in list(task.luns.values()):
        _close(entry)
    task.luns.clear()


def _release_at_stop() -> None:
    """Once per session: when it stops, close the devices that tasks stopped by an error kept
    attached (L7476-7480: "most device attachments are preserved"; see ``tasks.execute``)."""
    _, tasks, lock = _tables()
    extra = session_data().extra
    with lock:
        if extra.get("luns_released_at_stop"):
            return
        extra["luns_released_at_stop"] = True

    def release() -> None:
        for task in list(tasks.values()):
            detach_all(task)

    current_session().stop_hooks.append(release)


def _close(entry: Lun) -> None:
    entry.directory = None
    for thing in (entry.reader, entry.writer, entry.sock, entry.listener):
        if thing is not None:
            try:
                thing.Close()
            except GplException:
                pass
    entry.reader = entry.writer = entry.sock = entry.listener = None
    entry.inbuf.clear()


def _attached(lun: Any) -> Lun:
    entry = _lun(lun)
    if entry is None:
        raise _NotAttached
    return entry


class _NotAttached(Exception):
    pass


def _file_name(name: str) -> str:
    name = name.strip().replace("\\", "/")
    if re.match(r"^[A-Za-z]:", name):
        name = name[2:]
    # the V+ disk is the controller's flash disk: a bare name lives at its root
    return name if name.startswith("/") else "/flash/" + name


def _exists(name: str) -> bool:
    try:
        File.Length(name)
        return True
    except GplException:
        return False


def _disk_open(lun: Any, name: str, kind: str) -> None:
    try:
        entry = _attached(lun)
    except _NotAttached:
        return
    if entry.reader or entry.writer:
        _set(entry, E.FILE_ALREADY_OPEN)
        return
    path = _file_name(name)
    try:
        if kind == "R":
            if not _exists(path):
                _set(entry, E.NONEXISTENT_FILE)
                return
            entry.reader = StreamReader(path)
        elif kind == "W":
            if _exists(path):
                _set(entry, E.FILE_EXISTS)
                return
            entry.writer = StreamWriter(path, False)
        else:
            entry.writer = StreamWriter(path, True)
    except GplException as exc:
        _set(entry, E.from_core(exc).ErrorCode)
        return
    _set(entry, 1)


def fopenr(lun: Any, name: str) -> None:
    _disk_open(lun, name, "R")


def fopenw(lun: Any, name: str) -> None:
    _disk_open(lun, name, "W")


def fopena(lun: Any, name: str) -> None:
    _disk_open(lun, name, "A")


def fopend(lun: Any, spec: str = "") -> None:
    """``FOPEND (lun) "path"``: open a directory; each READ then returns one record in the DOS
    layout of L7936-7993 (name, extension, size in 512-byte sectors, attributes, date, time).
    [D] A ``*``/``?`` pattern in the last part selects names; the date and time fields are blank,
    as the Guide says they are when the system date was never set (L7991-7993)."""
    try:
        entry = _attached(lun)
    except _NotAttached:
        return
    path = _file_name(spec or "")
    folder, _, pattern = path.rpartition("/")
    if not any(c in pattern for c in "*?"):
        folder, pattern = path.rstrip("/"), "*"
    folder = folder or "/flash"
    try:
        files = [str(n) for n in File.GetFiles(folder)]
        dirs = [str(n) for n in File.GetDirectories(folder)]
    except GplException:
        _set(entry, E.NONEXISTENT_FILE)
        return
    records = []
    for name, is_dir in sorted([(n, False) for n in files] + [(n, True) for n in dirs]):
        stem, _, ext = name.partition(".")
        if not fnmatch.fnmatch(f"{stem}.{ext}".upper(), pattern.upper()) and not fnmatch.fnmatch(name.upper(), pattern.upper()):
            continue  # (as in DOS, *.* also matches a name without an extension)
        sectors = 0 if is_dir else (int(File.Length(f"{folder}/{name}")) + 511) // 512
        records.append(f"{stem[:8]:<8}.{ext[:3]:<3}{sectors:>8} {'D' if is_dir else '':<7}{'':9} {'':8}")
    entry.directory = records
    _set(entry, 1)


def fdelete(lun: Any, name: str) -> None:
    try:
        entry = _attached(lun)
    except _NotAttached:
        return
    try:
        File.DeleteFile(_file_name(name))
        _set(entry, 1)
    except GplException:
        _set(entry, E.NONEXISTENT_FILE)


_OPTION = re.compile(r"/([A-Za-z_]+)\s*([^/\s]*)")


def fopen(lun: Any, text: str, mode: Any = 0) -> None:
    """``FOPEN (lun, mode) "options"``: a TCP server (mode 16) or client on a TCP LUN."""
    try:
        entry = _attached(lun)
    except _NotAttached:
        return
    if entry.device != "TCP":
        _set(entry, E.ILLEGAL_IO)  # graphics windows are not simulated
        return
    options = {k.upper(): v for k, v in _OPTION.findall(text)}
    try:
        entry.buffer_size = max(1, int(options.get("BUFFER_SIZE", "1024") or 1024))
        if to_int(mode) & 16 or "LOCAL_PORT" in options:
            listener = TcpListener(IPEndPoint("", int(options["LOCAL_PORT"])))
            listener.Start()
            entry.listener = listener
        else:
            address = options.get("REMOTE_IP") or options.get("ADDRESS") or options.get("NODE") or "127.0.0.1"
            port = int(options.get("REMOTE_PORT") or options.get("PORT") or 0)
            client = TcpClient()
            client.Connect(IPEndPoint(address, port))
            entry.sock = client.Client()
    except (KeyError, ValueError):
        _set(entry, E.ILLEGAL_VALUE)
        return
    except GplException as exc:
        code = exc.ErrorCode
        _set(entry, E.CONNECTION_REFUSED if code == -1702 else E.DEVICE_NOT_READY if code == -304
             else E.from_core(exc).ErrorCode)
        return
    _set(entry, 1)


def fclose(lun: Any) -> None:
    try:
        entry = _attached(lun)
    except _NotAttached:
        return
    _close(entry)
    _set(entry, 1)


# -- reading -----------------------------------------------------------------------------------------

def _fill(entry: Lun, wait: bool) -> int:
    """Make sure ``entry.inbuf`` holds a byte: 1 when it does, else a status (-526 no data without
    waiting, -504 the client closed)."""
    if entry.inbuf:
        return 1
    if entry.listener is not None and entry.sock is None:
        if not wait and not entry.listener.Pending():
            return E.NO_DATA
        _accept(entry)
        return 1
    sock = entry.sock
    if sock is None:
        return E.FILE_NOT_OPEN
    if not wait and sock.Available == 0:
        return E.NO_DATA
    box = Box("")
    n = sock.Receive(box, entry.buffer_size)
    if n == 0:
        sock.Close()
        entry.sock = None
        if entry.listener is None:
            return E.END_OF_FILE
        entry.status = E.CLIENT_CLOSED
        return E.CLIENT_CLOSED
    entry.inbuf += str(box.value).encode("latin-1")
    return 1


def _accept(entry: Lun) -> None:
    assert entry.listener is not None
    entry.sock = entry.listener.AcceptSocket()
    entry.handles += 1
    entry.inbuf += struct.pack(">i", entry.handles)  # the connect notice
    entry.notice = 4


def getc(lun: Any, mode: Any = 0) -> float:
    """``GETC(lun[, mode])``: the next byte (mode bit 1: do not wait, -526 when none)."""
    safepoint()
    try:
        entry = _attached(lun)
    except _NotAttached:
        return float(E.NOT_ATTACHED)
    wait = not (to_int(mode) & 1)
    if entry.reader is not None:
        b = int(entry.reader.Read())
        return float(_set(entry, E.END_OF_FILE)) if b < 0 else float(b)
    try:
        got = _fill(entry, wait)
    except GplException as exc:
        return float(_set(entry, E.from_core(exc).ErrorCode))
    if got == E.CLIENT_CLOSED:
        _set(entry, E.CLIENT_CLOSED)
        return float(E.END_OF_FILE)
    if got != 1:
        return float(_set(entry, got))
    byte = entry.inbuf.pop(0)
    if entry.notice:
        entry.notice -= 1
        entry.status = E.CLIENT_CONNECTED
    else:
        entry.status = 1
    return float(byte)


def read(lun: Any, *refs: Any, mode: Any = 0) -> None:
    """``READ (lun) var``: one record into a string variable (CR/LF stripped), or numbers."""
    safepoint()
    try:
        entry = _attached(lun)
    except _NotAttached:
        return
    wait = not (to_int(mode) & 1)
    if entry.directory is not None:
        if not entry.directory:
            _set(entry, E.END_OF_FILE)
            return
        _store(entry, refs, entry.directory.pop(0))
        return
    if entry.reader is not None:
        try:
            line = str(entry.reader.ReadLine())
        except GplException:
            _set(entry, E.END_OF_FILE)
            return
        _store(entry, refs, line)
        return
    try:
        got = _fill(entry, wait)
    except GplException as exc:
        _set(entry, E.from_core(exc).ErrorCode)
        return
    if got == E.CLIENT_CLOSED:
        _store(entry, refs, "", status=E.CLIENT_CLOSED)
        return
    if got != 1:
        _set(entry, got)
        return
    if entry.notice:
        del entry.inbuf[:entry.notice]  # the connect notice, consumed whole
        entry.notice = 0
        _store(entry, refs, "", status=E.CLIENT_CONNECTED)
        return
    end = entry.inbuf.find(b"\n")
    if end < 0:
        data, entry.inbuf[:] = bytes(entry.inbuf[:RECORD_MAX]), entry.inbuf[RECORD_MAX:]
    else:
        data, entry.inbuf[:] = bytes(entry.inbuf[:end + 1]), entry.inbuf[end + 1:]
    _store(entry, refs, data.decode("latin-1").rstrip("\r\n"))


def _store(entry: Lun, refs: tuple[Any, ...], line: str, status: int = 1) -> None:
    """A record into READ's variables: a string variable takes the whole record; real variables
    take the record's numbers in order (separated by spaces or commas) [D: the Guide shows only
    string READs; the corpus reads ``READ (lun) x, y`` from a text file]."""
    entry.last_length = len(line)
    if refs:
        first = refs[0]
        if getattr(first, "name", "").startswith("$") or (first.defined and isinstance(first.v, str)):
            first.v = line[:MAX_STRING]
        else:
            fields = [f for f in re.split(r"[\s,]+", line.strip()) if f]
            for k, ref in enumerate(refs):
                ref.v = val(fields[k]) if k < len(fields) else 0.0
    _set(entry, status)


# -- writing -----------------------------------------------------------------------------------------

def write(lun: Any, *items: Any) -> None:
    """``WRITE (lun) items``: a record (CR/LF appended unless /S)."""
    safepoint()
    try:
        entry = _attached(lun)
    except _NotAttached:
        return
    text, end = render(items, newline="\r\n")
    data = text + ("\r\n" if end else "")
    try:
        if entry.writer is not None:
            entry.writer.Write(data)
            _set(entry, 1)
            return
        if entry.listener is not None and entry.sock is None:
            _accept_pending(entry)
        if entry.sock is None:
            _set(entry, E.CONNECTION_CLOSED if entry.device == "TCP" else E.FILE_NOT_OPEN)
            return
        entry.sock.Send(data)
    except GplException as exc:
        if entry.listener is not None and entry.sock is not None:
            entry.sock.Close()  # the client left: the server waits for the next one
            entry.sock = None
        _set(entry, E.CONNECTION_CLOSED if exc.ErrorCode == -1708 else E.from_core(exc).ErrorCode)
        return
    _set(entry, 1)


def _accept_pending(entry: Lun) -> None:
    """A server LUN takes a client that is waiting, without waiting itself (WRITE to a server that
    never reads, like ros.v2's feedback server, serves whoever connects)."""
    assert entry.listener is not None
    if entry.listener.Pending():
        _accept(entry)

"""What TMscript's communication devices share: the name a device is known by, its Received
Buffer and the reads from it, and its end (``Socket``, ``SerialPort``, ``ModbusTCP``,
``ModbusRTU``: manual §8, §9, §15).

* A device is named after its variable (``SerialPort spd = "COM2", 115200`` is ``"spd"``) and
  the functions address it by that name as a string, case-insensitively; each class has its own
  table of names on the robot (``robot._<kind>_devices``), so ``com_read("x")`` never finds a
  Socket ``x``.
* **Received Buffer** (L12494-L12498, L13484): once open, a reader fills it in the background;
  when full the oldest bytes go.  The reads (``com_read``, ``socket_read`` and their ``_string``
  forms, 9 overloads each, L12500-L13192, L13505-L14148) take from it: everything; a count
  (bytes, or characters for the ``_string`` forms, L13067); a prefix and a suffix, or a suffix
  alone, with a fetch option and a read time in controller time.
* **End**: a device declared in a block is closed and forgotten when the block is left, also by
  an error (L1320, L1335-L1345): the lowering writes the rest of the block as ``with
  tm.Socket(...) as bbb:`` and ``__exit__`` is :meth:`Device.release`.  Every device still open
  is closed when the project stops (L12494: "closes the opened Serial Port and clears the
  receiving buffer"), by ``Robot.close_devices``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from gplrt.tm import context
from gplrt.tm.values import TMError, to_int, to_string

#: The Received Buffer's capacity in bytes (the manual gives none; the oldest bytes go first).
BUFFER_SIZE = 1024 * 1024


class Device:
    """A named device of the current robot.  ``kind`` names its class's table (``socket``,
    ``serial``, ``modbus``); subclasses implement :meth:`close`."""

    kind = "device"

    def __init__(self, name: str) -> None:
        self.name = name
        self.robot = context.robot()
        self.buffer = bytearray()
        registry(self.robot, self.kind)[name.lower()] = self

    # -- the block that declared it (L1320) --------------------------------------------------
    def __enter__(self) -> Any:
        return self

    def __exit__(self, *exc: object) -> None:
        self.release()

    def release(self) -> None:
        """The variable goes out of scope: close the device and forget its name (unless a later
        declaration of the same name took it)."""
        try:
            self.close()
        finally:
            table = registry(self.robot, self.kind)
            if table.get(self.name.lower()) is self:
                del table[self.name.lower()]

    def close(self) -> bool:  # pragma: no cover (each class closes its own link)
        raise NotImplementedError

    # -- the Received Buffer ----------------------------------------------------------------------
    def received(self, data: bytes) -> None:
        """The reader got ``data``: into the buffer, the oldest bytes dropped past its size."""
        self.buffer += data
        if len(self.buffer) > BUFFER_SIZE:
            del self.buffer[:len(self.buffer) - BUFFER_SIZE]
        self.robot._notify()

    def wait(self, ready: Callable[[], bool], ms: int) -> None:
        """Wait up to ``ms`` of controller time for ``ready()`` (new data wakes the wait)."""
        if ms <= 0:
            return
        robot = self.robot
        end = robot.clock.now() + ms / 1000.0
        with robot.sched.adopted():
            while not ready() and not robot.clock.reached(end):
                robot.sched.wait(robot.changed, end)


def registry(robot: object, kind: str) -> dict[str, Any]:
    """The robot's table of ``kind`` devices by lower-case name (``robot._devices[kind]``, also
    ``robot._<kind>_devices``); ``Robot.close_devices`` closes them all."""
    tables = getattr(robot, "_devices", None)
    if tables is None:
        tables = {}
        setattr(robot, "_devices", tables)
    found = tables.get(kind)
    if found is None:
        found = tables[kind] = {}
        setattr(robot, f"_{kind}_devices", found)
    return found  # type: ignore[no-any-return]


def find(kind: str, name: object) -> Any:
    """The current robot's ``kind`` device called ``name`` (spaces around it ignored), or None."""
    return registry(context.robot(), kind).get(to_string(name).strip().lower())


# -- reads from the Received Buffer ---------------------------------------------------------------

def _condition(x: object) -> bytes:
    """A prefix or suffix condition: ``string`` (UTF-8) or ``byte[]``."""
    return to_string(x).encode("utf-8") if isinstance(x, str) else bytes(int(b) & 0xFF for b in x)  # type: ignore[attr-defined]


def _is_condition(x: object) -> bool:
    return isinstance(x, (str, list, tuple, bytes))


def _chars(data: bytearray, n: int) -> int | None:
    """The byte length of the first ``n`` UTF-8 characters of ``data``, or None when fewer are
    there whole (a ``_string`` read counts characters, L13067: 4 of ``TM達明...`` is 8 bytes)."""
    pos = 0
    for _ in range(n):
        if pos >= len(data):
            return None
        lead = data[pos]
        size = 1 if lead < 0xC0 else 2 if lead < 0xE0 else 3 if lead < 0xF0 else 4
        if pos + size > len(data):
            return None
        pos += size
    return pos


def take(dev: Device, args: tuple[object, ...], what: str, chars: bool = False) -> bytes:
    """What a read takes from ``dev``'s Received Buffer, by the overload ``args`` make
    (L12500-L12849): ``()`` all; ``(n [, ms])`` ``n`` bytes (characters when ``chars``) or
    nothing until that many are there, ``n <= 0`` all; ``(prefix, suffix [, option [, ms]])`` and
    ``(suffix [, option [, ms]])`` the first match (option 0/1 anywhere, 2/3 at the start; 1/3
    without the prefix and suffix), the bytes before it dropped.  ``ms`` > 0 waits that long in
    controller time for the read to be satisfied."""
    buf = dev.buffer
    if not args:
        data = bytes(buf)
        buf.clear()
        return data
    if not _is_condition(args[0]):
        n = to_int(args[0])
        ms = to_int(args[1]) if len(args) > 1 else 0
        if n <= 0:
            dev.wait(lambda: bool(buf), ms)
            data = bytes(buf)
            buf.clear()
            return data
        size: Callable[[], int | None] = (lambda: _chars(buf, n)) if chars else (lambda: n if len(buf) >= n else None)
        dev.wait(lambda: size() is not None, ms)
        end = size()
        if end is None:
            return b""
        data = bytes(buf[:end])
        del buf[:end]
        return data
    if len(args) > 1 and _is_condition(args[1]):
        prefix, suffix, rest = _condition(args[0]), _condition(args[1]), args[2:]
    else:
        prefix, suffix, rest = b"", _condition(args[0]), args[1:]
    if len(rest) > 2:
        raise TMError(f"{what}: too many arguments for a prefix/suffix read")
    option = to_int(rest[0]) if rest else 0
    ms = to_int(rest[1]) if len(rest) > 1 else 0
    if option not in (0, 1, 2, 3):
        raise TMError(f"{what}: fetch option {option} is not 0-3")
    found: list[tuple[int, int]] = []

    def match() -> bool:
        span = _match(bytes(buf), prefix, suffix, option >= 2)
        if span is not None:
            found.append(span)
        return span is not None
    dev.wait(match, ms)
    if not found and not match():
        return b""
    start, end = found[-1]
    data = bytes(buf[start:end])
    del buf[:end]
    if option in (1, 3):
        data = data[len(prefix):len(data) - len(suffix)]
    return data


def _match(data: bytes, prefix: bytes, suffix: bytes, at_start: bool) -> tuple[int, int] | None:
    """(start, end) of the first ``prefix``...``suffix`` in ``data``, or None."""
    if not prefix and not suffix:
        return (0, len(data)) if data else None
    start = data.find(prefix) if prefix else 0
    if start < 0 or (at_start and start != 0):
        return None
    if not suffix:
        return start, len(data)
    end = data.find(suffix, start + len(prefix))
    return None if end < 0 else (start, end + len(suffix))


def text(data: bytes) -> str:
    """A ``_string`` read's bytes as UTF-8 text."""
    return data.decode("utf-8", errors="replace")


__all__ = ["BUFFER_SIZE", "Device", "find", "registry", "take", "text"]

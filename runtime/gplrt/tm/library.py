"""The TMscript built-in functions (spec §3), under their TMscript names: generated code calls
``tm.PTP(...)``, ``tm.String_Substring(...)``.  Each cites its manual section.

Motion functions queue a command and return ``true`` at once (L15519); their target forms are the
manual's: a ``float[]`` or the scalars spelled out (techmanpy sends the scalars).  A failure the
manual calls an error raises :class:`TMError` (the project stops by error).
"""

from __future__ import annotations

import builtins
import math
import random as _random
import re
import struct
import threading
from collections.abc import Callable, Sequence

import numpy as np

from gplrt.threads.scheduler import checkpoint
from gplrt.tm import context
from gplrt.tm.packets import encode
from gplrt.tm.slave import table
from gplrt.tm.motion import CARTESIAN_SPEED, Command, arc_path, line_path, start_thread
from gplrt.tm.robot import config_bits, pose_to_se3, se3_to_pose
from gplrt.tm.teach import Base, Point, TBase, TCP, TPoint, TTCP, frame_of  # noqa: F401 (TMscript's names)
from gplrt.tm.values import F32, F64, Array, TMError, format_value, to_double, to_float, to_int, to_string, truth


# --- script control (L7707-L8032) ---------------------------------------------------------------
def Display(*args: object) -> bool:
    """Show text on the dashboard (L7950): ``(text)``, ``(title, text)``, ``(bg, fg, title, text)``;
    printed as ``text``, or ``[title] text`` when there is a title (colours are not shown)."""
    text = to_string(args[-1])
    if len(args) in (2, 4):
        text = f"[{to_string(args[-2])}] {text}"
    cb = context.display_callback()
    if cb is not None:
        cb(text)
    else:
        print(text, flush=True)
    return True


class ThreadStopped(Exception):
    """``ThreadExit(id)`` asked this thread to stop: raised at its next wait (L1967-L1999)."""


def _cancelled() -> bool:
    """Whether a wait must end now: the Listen node abandons the script (raises), or this
    thread was asked to stop by ``ThreadExit`` (raises :class:`ThreadStopped`)."""
    entry = _threads.get(getattr(_local, "id", 0))
    if entry is not None and entry[1] == 1:
        raise ThreadStopped
    n = context.node()
    return bool(n is not None and n.cancelled())


#: Controller seconds between two looks at a ``WaitFor`` condition (the controller's cycle is
#: shorter; a condition on I/O or variables set by other threads is seen within this).
WAITFOR_POLL = 0.01


def tick() -> None:
    """A loop's turn in a Listen-node script: a scheduling point of the shared scheduler (the
    connections' threads get their turn), and the end of the script when a priority command
    abandons it (``StopAndClearBuffer(1|2)``, ``ScriptExit(0|1)``, L18127) or its thread was
    stopped."""
    checkpoint()
    _cancelled()


def Sleep(ms: object) -> bool:
    """Wait ``ms`` of the robot's (controller) time (L7926); false when interrupted."""
    r = context.robot()
    end = r.clock.now() + builtins.max(0, to_int(ms)) / 1000.0
    with r.sched.adopted():
        while not r.clock.reached(end):
            if _cancelled():
                return False
            r.sched.wait(r.changed, end)
    return True


def WaitFor(cond: object, ms: object = None) -> bool:
    """``WaitFor(cond, ms)``: until the deferred ``cond`` holds (true) or ``ms`` passes (false, ms < 0
    waits forever); ``WaitFor(ms)`` sleeps (L7865-L7900)."""
    if ms is None:
        return Sleep(cond)
    assert callable(cond)
    limit = to_int(ms)
    r = context.robot()
    end = r.clock.now() + builtins.max(0, limit) / 1000.0
    with r.sched.adopted():
        while not truth(cond()):
            if _cancelled() or (limit >= 0 and r.clock.reached(end)):
                return False
            poll = r.clock.now() + WAITFOR_POLL
            r.sched.wait(r.changed, poll if limit < 0 else builtins.min(poll, end))
    return True


def Pause() -> bool:
    context.robot().pause(True)
    return True


def Resume() -> bool:
    context.robot().pause(False)
    return True


class ProjectExit(Exception):
    """``Exit()``: the project stops (``code`` > 0 closestop, < 0 errorstop, L7709)."""

    def __init__(self, code: int) -> None:
        super().__init__(code)
        self.code = code


def Exit(*args: object) -> bool:
    wait, code = True, 0
    for a in args:
        if isinstance(a, bool):
            wait = a
        else:
            code = to_int(a)
    if wait:
        context.robot().wait_idle(_cancelled)
    raise ProjectExit(code)


# --- threads (L1815-L2064) ----------------------------------------------------------------------
_threads: dict[int, list[object]] = {}  # id -> [thread, state]
_local = threading.local()


def ThreadRun(stmt: Callable[[], object], non_pausable: object = False) -> int:
    tid = builtins.max(_threads, default=0) + 1
    entry: list[object] = [None, 0]

    def body() -> None:
        _local.id = tid
        try:
            stmt()
        except ThreadStopped:
            pass
        finally:
            entry[1] = 2
    entry[0] = f"tm-thread-{tid}"
    _threads[tid] = entry
    # a thread of the shared scheduler, as GPL threads and V+ tasks are
    start_thread(context.robot().sched, f"tm-thread-{tid}", body)
    return tid


def ThreadID() -> int:
    """The current thread's id (L1867); the first thread that asks (``main``) gets one as well."""
    tid = getattr(_local, "id", None)
    if tid is None:
        tid = builtins.max(_threads, default=0) + 1
        _threads[tid] = [threading.current_thread(), 0]
        _local.id = tid
    return int(tid)


def ThreadState(tid: object = None) -> int:
    """-1 no such thread, 0 running, 1 asked to stop, 2 stopped (L1931)."""
    entry = _threads.get(ThreadID() if tid is None else to_int(tid))
    return -1 if entry is None else int(entry[1])  # type: ignore[call-overload]


def ThreadExit(tid: object = None) -> int:
    entry = _threads.get(ThreadID() if tid is None else to_int(tid))
    if entry is None:
        return -1
    if entry[1] == 0:
        entry[1] = 1
    return 0


# --- motion queue (L15515-L15705) ---------------------------------------------------------------
def QueueTag(tag: object, wait: object = 0) -> bool:
    """Put tag 1..15 into the motion queue; ``wait`` = 1 blocks until it is reached (L15521)."""
    n = to_int(tag)
    if not 1 <= n <= 15:
        raise TMError(f"QueueTag: tag {n} is not between 1 and 15")
    r = context.robot()
    node = context.node()
    if node is not None:
        node.tag_owner[n] = getattr(node, "_owner", None)
    r.enqueue(Command("tag", tag=n))
    if to_int(wait) == 1:
        r.wait_tag(n, -1, _cancelled)
    return True


def WaitQueueTag(tag: object, timeout: object = -1) -> int:
    """1 done, 0 not done by the timeout, -1 not among the last four tags (L15562)."""
    return context.robot().wait_tag(to_int(tag), to_int(timeout), _cancelled)


def StopAndClearBuffer(mode: object = 0) -> bool:
    """Stop the robot and clear the motion queue (L15683); in a Listen node, modes 1 and 2 are
    priority commands the node handles itself (L18127)."""
    context.robot().stop_and_clear()
    return True


def _split(args: Sequence[object], n_points: int) -> tuple[list[list[float]], list[object]]:
    """The target(s) (a float[] each, or six scalars each) and the arguments after them."""
    points: list[list[float]] = []
    rest = list(args)
    for _ in range(n_points):
        if rest and isinstance(rest[0], (list, tuple, np.ndarray)):
            pt = [float(to_double(x)) for x in rest.pop(0)]  # type: ignore[union-attr]
        else:
            if len(rest) < 6:
                raise TMError("a point needs six values")
            pt = [float(to_double(x)) for x in rest[:6]]
            rest = rest[6:]
        if len(pt) != 6:
            raise TMError(f"a point has 6 values, not {len(pt)}")
        points.append(pt)
    return points, rest


def _fmt(fmt: object, allowed: tuple[str, ...], name: str) -> str:
    f = to_string(fmt)
    if f not in allowed:
        raise TMError(f"{name}: the format {f!r} is not one of {', '.join(allowed)}")
    return f


def _line_speed(fmt: str, speed: object) -> float:
    """mm/s of a path motion: ``P`` % of the Cartesian top speed, ``A``/``D`` mm/s (L15972)."""
    v = float(to_double(speed))
    return CARTESIAN_SPEED * v / 100.0 if fmt[1] == "P" else v


def _blend(cmd: Command, f: str, value: object) -> Command:
    """``cmd`` blending into the next motion by ``value``: % for a format ending in ``P``, a
    radius in mm for ``R`` (L15747, L15990; docs/design/tmscript.md says how a blend is made)."""
    v = float(to_double(value))
    if v < 0 or (f[-1] == "P" and v > 100):
        raise TMError(f"the blending value {v:g} is out of range ({'0-100 %' if f[-1] == 'P' else '>= 0 mm'})")
    cmd.blend = (f[-1], v) if v > 0 else None
    return cmd


def PTP(fmt: object, *args: object) -> bool:
    """Joint-interpolated move to a joint (``JPP``) or Cartesian (``CPP``) target (L15706)."""
    f = _fmt(fmt, ("JPP", "CPP"), "PTP")
    (target,), rest = _split(args, 1)
    if len(rest) < 4:
        raise TMError("PTP: speed, acceleration time, blending and precise positioning are needed")
    speed, accel = rest[0], rest[1]
    config = _pose_config(rest[4:])
    if config is not None and f != "CPP":
        raise TMError('PTP: a pose configuration goes only with "CPP" (L15773)')
    r = context.robot()
    cmd = r.joint_move(target, float(to_double(speed)), float(to_double(accel))) if f == "JPP" \
        else r.ptp_pose(target, float(to_double(speed)), float(to_double(accel)), config)
    return r.enqueue(_blend(cmd, f, rest[2]))


def _pose_config(extra: Sequence[object]) -> list[int] | None:
    """The ``int[3] pose`` (or three ints) after PTP's precise-positioning flag, or None."""
    if not extra:
        return None
    vals = list(extra[0]) if len(extra) == 1 and isinstance(extra[0], (list, tuple, np.ndarray)) else list(extra)  # type: ignore[arg-type]
    if len(vals) != 3:
        raise TMError(f"PTP: the pose configuration has 3 values, not {len(vals)}")
    triplet = [int(to_int(v)) for v in vals]
    config_bits(triplet)  # (a value outside {0|1, 2|3, 4|5} is refused when queued)
    return triplet


def Line(fmt: object, *args: object) -> bool:
    """Straight line of the TCP to a pose in the current base (L15954)."""
    f = _fmt(fmt, ("CPP", "CPR", "CAP", "CAR", "CDP", "CDR"), "Line")
    (target,), rest = _split(args, 1)
    if len(rest) < 4:
        raise TMError("Line: speed, acceleration time, blending and precise positioning are needed")
    r = context.robot()
    goal = lambda: r.cartesian_target(target)  # noqa: E731 (in the base in effect when it starts)
    return r.enqueue(_blend(r.path_move(line_path(goal), _line_speed(f, rest[0]), float(to_double(rest[1]))), f, rest[2]))


def Circle(fmt: object, *args: object) -> bool:
    """Arc through ``via`` to ``end`` (L16073); arc angle ≠ 0 sweeps it at constant orientation."""
    f = _fmt(fmt, ("CPP", "CAP", "CDP"), "Circle")
    (via, end), rest = _split(args, 2)
    if len(rest) < 5:
        raise TMError("Circle: speed, acceleration time, blending, arc angle and precise positioning are needed")
    r = context.robot()
    path = arc_path(lambda: (r.cartesian_target(via), r.cartesian_target(end)), float(to_double(rest[3])))
    return r.enqueue(_blend(r.path_move(path, _line_speed(f, rest[0]), float(to_double(rest[1]))), f, rest[2]))


def PLine(fmt: object, *args: object) -> bool:
    """A path motion at constant TCP speed (L16200; the manual does not describe its path: ours is
    a straight line for ``C`` targets, joint-interpolated for ``J`` targets)."""
    f = _fmt(fmt, ("CAP", "CDP", "JAP", "JDP"), "PLine")
    (target,), rest = _split(args, 1)
    if len(rest) < 3:
        raise TMError("PLine: speed, acceleration time and blending are needed")
    r = context.robot()
    if f[0] == "J":
        r._check_joints(target)
        goal = r.arm.fk_se3(target)
    else:
        goal = lambda: r.cartesian_target(target)  # noqa: E731
    return r.enqueue(_blend(r.path_move(line_path(goal), float(to_double(rest[0])), float(to_double(rest[1]))), f, rest[2]))


def _relative(f: str, offset: list[float]) -> Callable[[list[float]], list[float]]:
    """The absolute target of a relative motion, from the joints it starts at (L16320)."""
    r = context.robot()

    def target(start: list[float]) -> list[float]:
        if f[0] == "J":
            return [a + b for a, b in zip(start, offset)]
        tcp = r.base.inverse() * r.arm.fk_se3(start) * r.tcp
        d = pose_to_se3(offset)
        if f[0] == "T":
            return se3_to_pose(tcp * d)
        return se3_to_pose(_world_delta(tcp, d))
    return target


def _world_delta(p: object, d: object) -> object:
    """(P + Pd, Rd·R): an offset expressed in the base (manual L9578)."""
    import pinocchio as pin
    assert isinstance(p, pin.SE3) and isinstance(d, pin.SE3)
    return pin.SE3(d.rotation @ p.rotation, p.translation + d.translation)


def _queue_relative(kind: str, f: str, offset: list[float], speed: float, accel: float,
                    blend: object = 0) -> bool:
    r = context.robot()
    target = _relative(f, offset)

    def plan(start: list[float], v0: list[float] | None = None, a0: list[float] | None = None):  # type: ignore[no-untyped-def]
        goal = target(start)
        if kind == "ptp":
            cmd = r.joint_move(goal, speed, accel) if f[0] == "J" else r.ptp_pose(goal, speed, accel)
        elif f[0] == "J":
            cmd = r.path_move(line_path(r.arm.fk_se3(goal)), speed, accel)
        else:
            cmd = r.path_move(line_path(r.cartesian_target(goal)), speed, accel)
        assert cmd.plan is not None
        return cmd.plan(start, v0, a0) if v0 is not None else cmd.plan(start)
    return r.enqueue(_blend(Command("move", plan=plan, from_motion=kind == "ptp"), f, blend))


def Move_PTP(fmt: object, *args: object) -> bool:
    """Relative PTP: ``C`` offset in the current base, ``T`` in the tool, ``J`` joint offsets (L16300)."""
    f = _fmt(fmt, ("CPP", "TPP", "JPP"), "Move_PTP")
    (offset,), rest = _split(args, 1)
    return _queue_relative("ptp", f, offset, float(to_double(rest[0])), float(to_double(rest[1])),
                           rest[2] if len(rest) > 2 else 0)


def Move_Line(fmt: object, *args: object) -> bool:
    """Relative straight line (L16430)."""
    allowed = tuple(a + b + c for a in "CT" for b in "PAD" for c in "PR")
    f = _fmt(fmt, allowed, "Move_Line")
    (offset,), rest = _split(args, 1)
    return _queue_relative("line", f, offset, _line_speed(f, rest[0]), float(to_double(rest[1])),
                           rest[2] if len(rest) > 2 else 0)


def Move_PLine(fmt: object, *args: object) -> bool:
    """Relative PLine (L16598)."""
    f = _fmt(fmt, ("CAP", "CDP", "TAP", "TDP", "JAP", "JDP"), "Move_PLine")
    (offset,), rest = _split(args, 1)
    return _queue_relative("line", f, offset, float(to_double(rest[0])), float(to_double(rest[1])),
                           rest[2] if len(rest) > 2 else 0)


def ChangeBase(*args: object) -> bool:
    """Set the base of the following motions (queued, L16706): ``"RobotBase"`` or a pose."""
    r = context.robot()
    if len(args) in (1, 2) and isinstance(args[0], str):
        name = args[0]
        declared = frame_of("base", name)
        if name != "RobotBase" and declared is None:
            raise TMError(f"ChangeBase: no base named {name!r}")
        frame, label = (pose_to_se3([0] * 6) if declared is None else declared[0]), name
    else:
        (pose,), _ = _split(args, 1)
        frame, label = pose_to_se3(pose), ""

    def run() -> None:
        r.base, r.base_name = frame, label
    r.script_base_name = label
    return r.enqueue(Command("call", run=run))


def ChangeTCP(*args: object) -> bool:
    """Set the TCP of the following motions (queued, L16814): ``"NOTOOL"`` or a pose [, mass ...]."""
    r = context.robot()
    mass = 0.0
    if isinstance(args[0], str):
        declared = frame_of("tcp", args[0])
        if args[0] != "NOTOOL" and declared is None:
            raise TMError(f"ChangeTCP: no TCP named {args[0]!r}")
        frame, label = (pose_to_se3([0] * 6), "NOTOOL") if declared is None else (declared[0], args[0])
        if declared is not None:
            mass = declared[1]
    else:
        (pose,), rest = _split(args, 1)
        frame, label = pose_to_se3(pose), ""
        if rest:
            mass = float(to_double(rest[0]))

    def run() -> None:
        r.tcp, r.tcp_name, r.tool_mass = frame, label, mass
    r.script_tcp_name = label
    return r.enqueue(Command("call", run=run))


def ChangeLoad(kg: object) -> bool:
    """The payload of the following motions (queued, L17007)."""
    r = context.robot()
    value = float(to_double(kg))

    def run() -> None:
        r.load = value
    return r.enqueue(Command("call", run=run))


_pvt: dict[str, object] = {"mode": None}


def PVTEnter(mode: object = 0) -> bool:
    """Enter PVT streaming (L17033): 0 joint, 1 Cartesian."""
    _pvt["mode"] = to_int(mode)
    return True


def PVTPoint(*args: object) -> bool:
    """A knot: position, velocity, duration (s) (L17100).  Simulated as a move that ends at the
    position at rest in at least the duration (the knot's velocity is not matched)."""
    if _pvt["mode"] is None:
        raise TMError("PVTPoint outside PVTEnter/PVTExit")
    (pos, _vel), rest = _split(args, 2)
    seconds = float(to_double(rest[0])) if rest else 0.0
    r = context.robot()
    if _pvt["mode"] == 0:
        cmd = r.joint_move(pos, 100.0, builtins.max(1.0, seconds * 1000.0 / 2))
    else:
        cmd = r.path_move(line_path(lambda: r.cartesian_target(pos)), CARTESIAN_SPEED, builtins.max(1.0, seconds * 1000.0 / 2))
    return r.enqueue(cmd)


def PVTExit() -> bool:
    _pvt["mode"] = None
    return True


def PVTPause() -> bool:
    return Pause()


def PVTResume() -> bool:
    return Resume()


# --- Listen node (L7447-L7706, L17642-L18305) ---------------------------------------------------
def ScriptExit(mode: object = None) -> bool:
    """Leave the Listen node once the queue is done (L17676); outside one, false."""
    n = context.node()
    if n is None:
        return False
    n.script_exit()
    return True


def ListenPacket(*args: object) -> str:
    """``$HDR,len,data,*CS\\r\\n`` (L7447); the header defaults to TMSCT."""
    header, data = ("TMSCT", args[0]) if len(args) == 1 else (args[0], args[1])
    return encode(to_string(header) or "TMSCT", to_string(data).encode("utf-8")).decode("utf-8", "replace")


def ListenSend(*args: object) -> int:
    """Push ``$TMSTA,<90..99>,<value>`` to the Listen node's clients (L7507): 0, -1 no server, -2 bad SubCmd."""
    if len(args) == 3:
        args = args[1:]
    sub, value = to_int(args[0]), args[1]
    if not 90 <= sub <= 99:
        return -2
    n = context.node()
    if n is None:
        return -1
    if isinstance(value, str) or not isinstance(value, (list, tuple)):
        payload = to_string(value).encode("utf-8")
    else:
        payload = bytes(GetBytes(value))
    n.push(b"TMSTA", f"{sub},".encode() + payload)
    return 0


# --- Ethernet Slave (L19694-L20556) -------------------------------------------------------------
def svr_read(item: object) -> object:
    return table().read(to_string(item))


def svr_write(item: object, value: object) -> bool:
    return table().write(to_string(item), value) == 0


# --- math in degrees (L8033-L9400): the float forms compute in binary32 -------------------------
def _same(x: object, v: float) -> object:
    return F64(v) if type(x) is F64 else F32(v)


def _unary(fn: Callable[[float], float], x: object) -> object:
    v = float(to_double(x))
    return _same(x, fn(v))


def abs(x: object) -> object:  # noqa: A001 (TMscript's name)
    if isinstance(x, int) and not isinstance(x, bool):
        return to_int(-x if x < 0 else x)
    return _same(x, math.fabs(float(to_double(x))))


def sqrt(x: object) -> object:
    v = float(to_double(x))
    if v < 0:
        raise TMError("sqrt of a negative number")
    return _same(x, math.sqrt(v))


def pow(b: object, e: object) -> object:  # noqa: A001
    r = math.pow(float(to_double(b)), float(to_double(e)))
    if isinstance(b, int) and not isinstance(b, bool):
        return to_int(r)
    return _same(b, r)


def ceil(x: object) -> object:
    return _unary(math.ceil, x)


def floor(x: object) -> object:
    return _unary(math.floor, x)


def round(x: object, digits: object = 0) -> object:  # noqa: A001
    d = to_int(digits)
    d = d if 0 <= d <= 15 else 0
    v = float(to_double(x))
    q = 10.0 ** d
    r = math.floor(math.fabs(v) * q + 0.5) / q  # midpoint away from zero (round(-0.567) = -1, L8340)
    return _same(x, math.copysign(r, v))


def random(*args: object) -> object:
    if not args:
        return F32(_random.random())
    lo, hi = (0, to_int(args[0])) if len(args) == 1 else (to_int(args[0]), to_int(args[1]))
    if hi <= lo:
        return lo if len(args) == 2 else 0
    return _random.randrange(lo, hi)


def _flat(args: Sequence[object]) -> list[object]:
    out: list[object] = []
    for a in args:
        out.extend(a if isinstance(a, (list, tuple)) else [a])
    return out


def sum(*args: object) -> object:  # noqa: A001
    vals = _flat(args)
    if all(isinstance(v, int) and not isinstance(v, bool) for v in vals):
        return to_int(math.fsum(vals))  # type: ignore[arg-type]
    return F64(math.fsum(float(to_double(v)) for v in vals))


def average(*args: object) -> object:
    vals = _flat(args)
    return F64(math.fsum(float(to_double(v)) for v in vals) / len(vals))


def min(*args: object) -> object:  # noqa: A001
    vals = _flat(args)
    m = vals[0]
    for v in vals[1:]:
        if float(to_double(v)) < float(to_double(m)):
            m = v
    return m


def max(*args: object) -> object:  # noqa: A001
    vals = _flat(args)
    m = vals[0]
    for v in vals[1:]:
        if float(to_double(v)) > float(to_double(m)):
            m = v
    return m


def d2r(x: object) -> object:
    return _unary(math.radians, x)


def r2d(x: object) -> object:
    return _unary(math.degrees, x)


def _trig(fn: Callable[[float], float], x: object) -> object:
    if type(x) is F64:
        return F64(fn(math.radians(float(x))))
    return F32(fn(float(np.radians(to_float(x)))))


def sin(x: object) -> object:
    return _trig(math.sin, x)


def cos(x: object) -> object:
    return _trig(math.cos, x)


def tan(x: object) -> object:
    return _trig(math.tan, x)


def _atrig(fn: Callable[[float], float], x: object) -> object:
    v = float(to_double(x))
    if type(x) is F64:
        return F64(math.degrees(fn(v)))
    return F32(np.degrees(F32(fn(float(to_float(x))))))


def asin(x: object) -> object:
    return _atrig(math.asin, x)


def acos(x: object) -> object:
    return _atrig(math.acos, x)


def atan(x: object) -> object:
    return _atrig(math.atan, x)


def atan2(y: object, x: object) -> object:
    v = math.degrees(math.atan2(float(to_double(y)), float(to_double(x))))
    return F64(v) if type(y) is F64 or type(x) is F64 else F32(v)


def log(x: object, base: object = None) -> object:
    v = float(to_double(x))
    if v <= 0:
        raise TMError("log of a number that is not positive")
    r = math.log(v) if base is None else math.log(v, float(to_double(base)))
    return _same(x, r)


def log10(x: object) -> object:
    return log(x, 10.0)


def norm2(v: object) -> object:
    return F32(math.sqrt(math.fsum(float(to_double(x)) ** 2 for x in v)))  # type: ignore[attr-defined]


def dist(a: object, b: object) -> object:
    """Distance of the XYZ parts of two poses (L9363)."""
    return F32(math.dist([float(x) for x in a[:3]], [float(x) for x in b[:3]]))  # type: ignore[index]


def Length(x: object) -> int:
    """Bytes of a scalar, characters of a string, elements of an array (L6694)."""
    if isinstance(x, str):
        return len(x)
    if isinstance(x, (list, tuple)):
        return len(x)
    if isinstance(x, bool):
        return 1
    if isinstance(x, int):
        return 1 if 0 <= x <= 255 else 4
    return 8 if type(x) is F64 else 4


def Ctrl(x: object) -> str:
    """Control characters (L6771-L6840): an int's big-endian bytes, a string's escapes, bytes."""
    if isinstance(x, str):
        table = {"0": "\0", "a": "\a", "b": "\b", "t": "\t", "r": "\r", "v": "\v", "f": "\f", "n": "\n"}
        out, i = [], 0
        while i < len(x):
            if x[i] == "\\" and i + 1 < len(x) and x[i + 1] in table:
                out.append(table[x[i + 1]])
                i += 2
            else:
                out.append(x[i])
                i += 1
        return "".join(out)
    if isinstance(x, (list, tuple)):
        return "".join(chr(int(b)) for b in x)
    v = to_int(x) & 0xFFFFFFFF
    return "".join(chr(b) for b in v.to_bytes(4, "big") if b)


def GetNowStamp(*args: object) -> object:
    """Project run time in ms (L6471)."""
    ms = int(context.robot().clock.now() * 1000)
    if args and isinstance(args[0], bool):
        return F64(ms)
    if args:
        return to_int(ms - to_int(args[0]))
    return to_int(ms)


def GetString(x: object, *args: object, as_byte: bool = False) -> str:
    """The text form of a value (L5111-L5560): ``(v [, base [, fmt]])``, ``(v, sep [, base [,
    fmt]])``, ``(v, indexFormat, sep [, base [, fmt]])``.  ``base`` 16 or 2 shows a number's bit
    pattern (byte 8 bits, int 32, float 32, double 64), ``fmt`` 0 pads and prefixes ``0x``/``0b``,
    1 pads, 2 prefixes, 3 neither; for a ``string[]`` ``base`` is the quoting (0/10 when needed,
    1 always, other never).  An array is ``{a,b}``, or joined by ``sep`` without braces, each
    element after ``indexFormat`` with its index (``"[0]="``).  ``as_byte``: the front end's mark
    of a ``byte`` scalar (a byte and an int are both Python ints at run time)."""
    rest = list(args)
    index = sep = None
    if rest and isinstance(rest[0], str):
        if len(rest) >= 2 and isinstance(rest[1], str):
            index, sep, rest = rest[0], rest[1], rest[2:]
        else:
            sep, rest = rest[0], rest[1:]
    base = to_int(rest[0]) if rest else 10
    fmt = to_int(rest[1]) if len(rest) > 1 else 0
    if not isinstance(x, (list, tuple)):
        return _radix_text(x, base, fmt, as_byte)
    kind = getattr(x, "type", None)
    if kind == "string":
        items = [_quoted(to_string(v), base, sep or ",") for v in x]
    else:
        items = [_radix_text(v, base, fmt, kind == "byte") for v in x]
    if index is not None:
        items = [_index_text(index, i) + t for i, t in enumerate(items)]
    return "{" + ",".join(items) + "}" if sep is None else sep.join(items)


def _radix_text(v: object, base: int, fmt: int, is_byte: bool) -> str:
    """A number's text in ``base`` 16 or 2 (its bit pattern), else its ordinary text."""
    if base not in (16, 2) or isinstance(v, (bool, np.bool_, str)):
        return format_value(v)
    if isinstance(v, (int, np.integer)):
        bits, pattern = (8, int(v) & 0xFF) if is_byte else (32, int(v) & 0xFFFFFFFF)
    elif isinstance(v, np.float64):
        bits, pattern = 64, int.from_bytes(struct.pack(">d", float(v)), "big")
    elif isinstance(v, (float, np.floating)):
        bits, pattern = 32, int.from_bytes(struct.pack(">f", float(F32(v))), "big")
    else:
        return format_value(v)
    width = bits // 4 if base == 16 else bits
    digits = format(pattern, "X" if base == 16 else "b")
    if fmt in (0, 1):
        digits = digits.rjust(width, "0")
    return ("0x" if base == 16 else "0b") + digits if fmt in (0, 2) else digits


def _quoted(text: str, mode: int, sep: str) -> str:
    """A ``string[]`` element: in standard string form (``"a""b"``) always (mode 1), when it holds
    a quote or the separator (0 or 10), else as it is (L5140)."""
    if mode == 1 or (mode in (0, 10) and ('"' in text or sep in text)):
        return '"' + text.replace('"', '""') + '"'
    return text


def _index_text(pattern: str, i: int) -> str:
    """An element's index in a numeric format string: the first run of ``0``/``#`` placeholders
    stands for the index, zero-padded to the number of ``0`` (``"[0]="`` -> ``"[3]="``, L5449)."""
    found = re.search(r"[0#]+", pattern)
    if found is None:
        return pattern
    text = str(i).rjust(found.group().count("0"), "0")
    return pattern[:found.start()] + text + pattern[found.end():]


# --- the utility families, in modules of their own ---------------------------------------------
from gplrt.tm.conversions import (  # noqa: E402
    CRC16, CRC32, SUM8, SUM16, SUM32, XOR8, Byte_Concat, Byte_ToDouble, Byte_ToFloat, Byte_ToInt16, Byte_ToInt32,
    Byte_ToString, GetBytes, String_ToByte, ValueReverse,
)
from gplrt.tm.manager import lookup, var_sync  # noqa: E402
from gplrt.tm.vision_functions import (  # noqa: E402,F401 (TMscript's names)
    File_CopyImage, Vision_DoJob, Vision_GetOutputArraySize, Vision_GetOutputArrayValue,
    Vision_GetTriggerJobOutputCount, Vision_GetTriggerJobOutputValue, Vision_IsJobAvailable, VPoint, do_job_line,
    do_job_ptp, get_image,
)
from gplrt.tm.files import (  # noqa: E402
    File_Copy, File_Delete, File_Exists, File_GetAllTokens, File_GetToken, File_Length, File_NextEOF, File_NextLine,
    File_ReadBytes, File_ReadLines, File_ReadText, File_Replace, File_WriteBytes, File_WriteLine, File_WriteLines,
    File_WriteText,
)
from gplrt.tm.modbus import (  # noqa: E402
    ModbusRTU, ModbusTCP, modbus_close, modbus_open, modbus_read, modbus_read_double, modbus_read_float, modbus_read_int16,
    modbus_read_int32, modbus_read_string, modbus_write,
)
from gplrt.tm.posemath import (  # noqa: E402
    applytrans, changeref, intercoord, interpoint, inversetrans, points2coord, trans,
)
from gplrt.tm.serial import (  # noqa: E402
    SerialPort, com_close, com_open, com_read, com_read_string, com_write, com_writeline,
)
from gplrt.tm.sockets import (  # noqa: E402
    Socket, socket_close, socket_open, socket_read, socket_read_string, socket_send, socket_sendline,
)
from gplrt.tm.strings import (  # noqa: E402
    Array_Append, Array_Equals, Array_IndexOf, Array_Insert, Array_LastIndexOf, Array_Remove, Array_Reverse,
    Array_Sort, Array_SubElements, GetAllTokens, GetToken, String_IndexOf, String_LastIndexOf, String_Replace,
    String_Split, String_Substring, String_ToInteger, String_ToLower, String_ToUpper, String_Trim,
)


def String_ToFloat(s: object, base: object = 10) -> object:
    """Decimal text, or hex/binary text taken as the bit pattern of a binary32 (L3013)."""
    if isinstance(s, list):
        return Array("float", [String_ToFloat(x, base) for x in s])
    text = to_string(s).strip()
    low = text.lower()
    b = to_int(base)
    if b in (16, 2) or low.startswith(("0x", "0b")):
        bits = String_ToInteger(text, 16 if (b == 16 or low.startswith("0x")) else 2)
        return F32(struct.unpack("<f", struct.pack("<I", int(bits) & 0xFFFFFFFF))[0])  # type: ignore[call-overload]
    try:
        return to_float(text)
    except TMError:
        return F32(0)


def String_ToDouble(s: object, base: object = 10) -> object:
    if isinstance(s, list):
        return Array("double", [String_ToDouble(x, base) for x in s])
    try:
        return to_double(to_string(s).strip())
    except TMError:
        return F64(0)


def GetVarValue(name: object, scope: dict[str, object] | None = None) -> object:
    """The value of the variable named at run time (L6650) among those visible at the call
    (``scope``, given by the front end) or the Listen node's; an error if there is none."""
    key = to_string(name).strip()
    found, value = lookup(key, scope, context.node())
    if not found:
        raise TMError(f"GetVarValue: the variable {key!r} does not exist")
    return value


def VarSync(*args: object, scope: dict[str, object] | None = None) -> int:
    """Send variables to the robot's TMmanager (L7626): ``gplrt.tm.manager.var_sync``."""
    return var_sync(args, scope, context.robot(), context.node(), Sleep)


def Vision_DoJob_PTP(job: object, speed: object, accel: object, smart_pose: object = False) -> bool:
    """``gplrt.tm.vision_functions.do_job_ptp`` (L17262), ended by a priority command."""
    return do_job_ptp(job, speed, accel, smart_pose, _cancelled)


def Vision_DoJob_Line(job: object, speed: object, accel: object = None, link: object = True) -> bool:
    """``gplrt.tm.vision_functions.do_job_line`` (L17319), ended by a priority command."""
    return do_job_line(job, speed, accel, link, _cancelled)


def File_GetImage(timeout_ms: object = -1) -> Array:
    """``gplrt.tm.vision_functions.get_image`` (L11845), ended by a priority command."""
    return get_image(timeout_ms, _cancelled)


_NOW_TOKENS = ("yyyy", "yy", "MMMM", "MMM", "MM", "M", "dddd", "ddd", "dd", "d", "HH", "H", "hh", "h", "mm", "m",
               "ss", "s", "ffff", "fff", "ff", "f", "tt", "t")


def GetNow(fmt: object = "MM/dd/yyyy HH:mm:ss") -> str:
    """The local time with .NET-style specifiers (L6389)."""
    import datetime

    now = datetime.datetime.now()
    f = to_string(fmt)
    out, i = [], 0
    values = {
        "yyyy": f"{now.year:04d}", "yy": f"{now.year % 100:02d}", "MMMM": now.strftime("%B"), "MMM": now.strftime("%b"),
        "MM": f"{now.month:02d}", "M": str(now.month), "dddd": now.strftime("%A"), "ddd": now.strftime("%a"),
        "dd": f"{now.day:02d}", "d": str(now.day), "HH": f"{now.hour:02d}", "H": str(now.hour),
        "hh": f"{(now.hour % 12) or 12:02d}", "h": str((now.hour % 12) or 12), "mm": f"{now.minute:02d}",
        "m": str(now.minute), "ss": f"{now.second:02d}", "s": str(now.second), "tt": "AM" if now.hour < 12 else "PM",
        "t": "A" if now.hour < 12 else "P",
    }
    for k in range(1, 5):
        values["f" * k] = f"{now.microsecond:06d}"[:k]
    while i < len(f):
        tok = next((t for t in _NOW_TOKENS if f.startswith(t, i)), None)
        if tok is None:
            out.append(f[i])
            i += 1
        else:
            out.append(values[tok])
            i += len(tok)
    return "".join(out)

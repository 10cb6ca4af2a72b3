"""The V+ runtime layer: the API generated V+ code calls (docs/design/vplus-runtime.md).

Generated code does ``from gplrt import vplus as vp``.  This package holds only what is V+'s
alone; geometry, motion, threads, sockets and files are the shared core's.  Nothing on the GPL
path imports it.
"""

from gplrt.vplus import errors
from gplrt.vplus.errors import UNDEFINED_VALUE, VError, compile_error, error_text, unsupported
from gplrt.vplus.values import (
    G, Cell, ElementRef, Ref, VArray, calls, defined, find_program, last, local_store, program, byval,
)
from gplrt.vplus.operators import (
    FALSE, PI, TRUE, abs_, add, and_, atan2, band, bmask, bor, bxor, com, cos, cubrt, div, eq, fract,
    ge, gt, int_, le, lt, max_, min_, mod, mul, ne, neg, not_, or_, outside, random, sign, sin, sqr,
    sqrt, sub, tan, to_int, truth, xor_,
)
from gplrt.vplus.strings import (
    Fmt, asc, dblb, fltb, fmt, intb, len_, lngb, pos, val, s_chr, s_dblb, s_decode, s_encode, s_error,
    s_fltb, s_intb, s_lngb, s_mid, s_transb, s_truncate, transb,
)
from gplrt.vplus.transforms import (
    compose, decompose, distance, dx, dy, dz, frame, identical, inverse, normal, null, p_ppoint, rx,
    ry, rz, scale, shift, trans,
)
from gplrt.vplus.system import disable, enable, parameter, parameter_set, switch, switch_set
from gplrt.vplus.tasks import (
    abort, cas, clear_event, error, execute, get_event, halt, ignore, lock, pause, priority, react,
    reacte, reacti, release, run, s_time, safepoint, time_, set_event, step, stop, tas, task_status, timer,
    timer_set, tps, wait, wait_event, wait_for,
)
from gplrt.vplus.signals import bits, bits_set, reset, sig, sig_ins, signal
from gplrt.vplus.console import prompt, set_prompt_input, type_
from gplrt.vplus.luns import (
    attach, detach, fclose, fdelete, fopen, fopena, fopend, fopenr, fopenw, getc, iostat, read, write,
)
from gplrt.vplus.motion import (
    HAND_SIGNALS, above, accel, accel_value, below, config_value, duration_value, select_value, flip, lefty, noflip, righty, appro, appros, base, base_value, brake, break_, close, closei, config, cp,
    delay, depart, departs, dest, drive, duration, hand, here, here_into, inrange, modifier, move,
    movest, movet, moves, open_, openi, p_pdest, p_phere, ready, relax, relaxi, select_robot, speed, speed_value,
    tool, tool_value,
)

__all__ = [name for name in dir() if not name.startswith("_")]

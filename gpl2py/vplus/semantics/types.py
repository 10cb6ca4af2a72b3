"""V+ data types and what the functions and instructions say about their operands (spec §3.1, §2.5).

A V+ variable has one type, fixed when it is created.  The sigil says it for strings (``$``),
precision points (``#``) and belts (``%``); an unprefixed name is a real or a transformation, told
apart only by use, across every program (:mod:`gpl2py.vplus.semantics.check` infers it).
"""

from __future__ import annotations

import enum


class T(enum.Enum):
    """A V+ data type."""

    REAL = "a real"
    TRANS = "a transformation"
    PPOINT = "a precision point"
    STRING = "a string"
    BELT = "a belt"
    UNKNOWN = "unknown"

    @property
    def is_location(self) -> bool:
        return self in (T.TRANS, T.PPOINT)


def of_sigil(sigil: str) -> T | None:
    """The type a sigil fixes, or None for an unprefixed name (real or transformation)."""
    return {"$": T.STRING, "#": T.PPOINT, "%": T.BELT}.get(sigil)


R, L, S, P, B, U = T.REAL, T.TRANS, T.STRING, T.PPOINT, T.BELT, T.UNKNOWN

#: Function -> (result type, argument types; the last one repeats).  ``U`` leaves an argument to
#: its own type (DEFINED, $ENCODE's items).  Spec §2.5 and the User's Guide chapters it cites.
FUNCTIONS: dict[str, tuple[T, tuple[T, ...]]] = {
    # numeric
    "ABS": (R, (R,)), "ATAN2": (R, (R, R)), "COS": (R, (R,)), "SIN": (R, (R,)), "TAN": (R, (R,)),
    "SQRT": (R, (R,)), "SQR": (R, (R,)), "CUBRT": (R, (R,)), "FRACT": (R, (R,)), "INT": (R, (R,)),
    "SIGN": (R, (R,)), "MAX": (R, (R,)), "MIN": (R, (R,)), "OUTSIDE": (R, (R, R, R)), "PI": (R, ()),
    "RANDOM": (R, ()), "BCD": (R, (R,)), "DCB": (R, (R,)), "BMASK": (R, (R,)), "TRUE": (R, ()), "FALSE": (R, ()), "ON": (R, ()), "OFF": (R, ()),
    # strings
    "ASC": (R, (S, R)), "$CHR": (S, (R,)), "LEN": (R, (S,)), "$MID": (S, (S, R, R)), "POS": (R, (S, S, R)),
    "VAL": (R, (S,)), "$ERROR": (S, (R,)), "$ENCODE": (S, (U,)), "$DECODE": (S, (S, S, R)),
    "$LNGB": (S, (R,)), "$INTB": (S, (R,)), "$FLTB": (S, (R,)), "$DBLB": (S, (R,)), "LNGB": (R, (S, R)),
    "INTB": (R, (S, R)), "FLTB": (R, (S, R)), "DBLB": (R, (S, R)), "$TRANSB": (S, (L,)), "$TRUNCATE": (S, (S,)),
    "$UNPACK": (S, (S, R, R)), "$TIME": (S, (R,)), "$ID": (S, ()), "$DEFAULT": (S, ()),
    # system
    "DEFINED": (R, (U,)), "ERROR": (R, (R, R)), "FREE": (R, ()), "GET.EVENT": (R, (R,)), "ID": (R, ()),
    "LAST": (R, (U,)), "PARAMETER": (R, (U,)), "PRIORITY": (R, ()), "SELECT": (R, (U,)), "STATUS": (R, (S,)),
    "SWITCH": (R, (U,)), "TAS": (R, (R, R)), "CAS": (R, (R, R, R)), "TASK": (R, (R, R)), "TIME": (R, (S,)),
    "TIMER": (R, (R,)), "TPS": (R, ()), "SIG": (R, (R,)), "SIG.INS": (R, (R,)), "BITS": (R, (R, R)),
    "IOSTAT": (R, (R, R)), "GETC": (R, (R, R)), "PENDANT": (R, (R,)), "AIO.IN": (R, (R,)), "AIO.INS": (R, (R,)),
    "DEVICE": (R, (R,)), "STATE": (R, (R,)), "HAND": (R, ()), "CONFIG": (R, (R,)),
    # motion
    "ACCEL": (R, (R,)), "SPEED": (R, (R,)), "DURATION": (R, (R,)), "DISTANCE": (R, (L, L)),
    "DX": (R, (L,)), "DY": (R, (L,)), "DZ": (R, (L,)), "IDENTICAL": (R, (L, L)), "INRANGE": (R, (L,)),
    "LATCHED": (R, (R,)),
    # transformation-valued
    "HERE": (L, ()), "DEST": (L, ()), "BASE": (L, ()), "TOOL": (L, ()), "NULL": (L, ()), "LATCH": (L, ()),
    "INVERSE": (L, (L,)), "NORMAL": (L, (L,)), "RX": (L, (R,)), "RY": (L, (R,)), "RZ": (L, (R,)),
    "TRANS": (L, (R,)), "SHIFT": (L, (L,)), "SCALE": (L, (L,)), "FRAME": (L, (L, L, L, L)),
    # precision-point-valued (the sandbox also calls #PPOINT without its sigil)
    "#PPOINT": (P, (R,)), "PPOINT": (P, (R,)), "#PHERE": (P, ()), "#PDEST": (P, ()), "#PLATCH": (P, ()),
    # belts
    "BELT": (R, (B, R)), "BSTATUS": (R, ()), "WINDOW": (R, (L, R, R)),
}

#: Motion instructions whose first value is a location; the others are reals (spec §2.4).
LOCATION_FIRST = frozenset("MOVE MOVES APPRO APPROS MOVET MOVEST MOVEF MOVESF TOOL".split())
#: Instructions whose every value is real (signal numbers, times, speeds ...).
REAL_VALUES = frozenset("""
DEPART DEPARTS DRIVE DELAY SPEED DURATION SIGNAL WAIT WAIT.EVENT SET.EVENT CLEAR.EVENT RELEASE LOCK ABORT
IGNORE RUNSIG TIMER CYCLE.END BASE OPEN OPENI CLOSE CLOSEI RELAX RELAXI
""".split())

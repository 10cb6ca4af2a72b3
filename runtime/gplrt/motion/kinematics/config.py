"""GPL configuration bits (``Location.Config``) and the angle choices they drive.

Values from gpl-dictionary.md §13.1.  Which bits mean what on each robot is documented in the
module that solves it (pf400.py, articulated.py, gantry.py).  Two rules are shared:

* **Contradictory or missing bits** (Righty+Lefty, neither, ...) mean "no preference": the
  solver keeps the branch the robot is in now (gpl-classes.md §22.1 item 11 [P]: "Config = 0
  means no preference → solution nearest the current joints"; robot-models.md §4.4 step 6).
* **Multi-turn joints** are unwound toward the current joint value: of all ``angle + k·360°``
  inside the soft limits, the nearest to the current value wins (GPL manual, Location.Config:
  "wrists with >360° travel are resolved automatically to the nearest solution").  With
  ``GPL_Single`` the last (wrist/theta) axis is instead put in (−180°, 180°].
"""

from __future__ import annotations

import math
from typing import Final

from gplrt.lang import constants

# The bit values come from the one table of GPL predefined constants (what programs see as
# GPL_Righty ...); the upper-case names are the Python spelling used across the kinematics.
GPL_RIGHTY: Final = constants.GPL_Righty
GPL_LEFTY: Final = constants.GPL_Lefty
GPL_ABOVE: Final = constants.GPL_Above
GPL_BELOW: Final = constants.GPL_Below
GPL_FLIP: Final = constants.GPL_Flip
GPL_NOFLIP: Final = constants.GPL_NoFlip
GPL_SINGLE: Final = constants.GPL_Single

TWO_PI = 2.0 * math.pi
#: Slack (rad or m) when testing a value against a limit, so that a solution computed exactly at
#: a soft stop is not refused because of rounding.
LIMIT_SLACK = 1e-12


def preference(bits: int, yes: int, no: int) -> bool | None:
    """True if only ``yes`` is set, False if only ``no`` is set, None otherwise (no preference)."""
    has_yes, has_no = bool(bits & yes), bool(bits & no)
    if has_yes == has_no:
        return None
    return has_yes


def wrap_pi(angle: float) -> float:
    """Angle (rad) wrapped into (−π, π]."""
    a = math.remainder(angle, TWO_PI)
    return math.pi if a == -math.pi else a


def unwind(angle: float, current: float, lower: float, upper: float) -> float:
    """The ``angle + k·2π`` inside [lower, upper] nearest ``current`` (all rad).

    If no equivalent lies inside the limits, the one nearest the limits is returned so that the
    caller's limit check reports the axis (-1012)."""
    k_near = round((current - angle) / TWO_PI)
    near = angle + k_near * TWO_PI
    if abs(near - current) < math.pi and lower - LIMIT_SLACK <= near <= upper + LIMIT_SLACK:
        return near  # strictly the turn nearest ``current`` (no tie), and within the limits
    best: float | None = None
    for k in (k_near - 1, k_near, k_near + 1):
        cand = angle + k * TWO_PI
        if lower - LIMIT_SLACK <= cand <= upper + LIMIT_SLACK and (best is None or abs(cand - current) < abs(best - current)):
            best = cand
    if best is not None:
        return best
    # Limits farther than a turn from the current value: search the whole range.
    if math.isfinite(lower) and math.isfinite(upper):
        k_lo = math.ceil((lower - LIMIT_SLACK - angle) / TWO_PI)
        k_hi = math.floor((upper + LIMIT_SLACK - angle) / TWO_PI)
        if k_lo <= k_hi:
            ks = range(k_lo, k_hi + 1)
            return min((angle + k * TWO_PI for k in ks), key=lambda c: abs(c - current))
    mid = (lower + upper) / 2 if math.isfinite(lower) and math.isfinite(upper) else current
    return angle + round((mid - angle) / TWO_PI) * TWO_PI

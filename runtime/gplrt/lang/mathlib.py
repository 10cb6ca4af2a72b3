"""The GPL ``Math`` class and the numeric functions outside it (spec gpl-language.md §14.2-14.3,
gpl-dictionary.md §10.3).

* ``Math`` is a global class (no instances in GPL), exported as the single instance of
  ``_Math`` per CATALOGUE.md rule 6; every method is a staticmethod, ``E`` and ``PI`` are
  read-only properties (so the catalogue sees them as Double members).
* **Trig works in radians** (AMB-14, resolved by the spec from vendor code that writes
  ``Math.Cos(theta - Math.PI / 2.0)`` and converts Atan2 results with ``180.0 * ... / Math.PI``).
  Location angles elsewhere in gplrt stay in degrees.
* Results are Doubles [000 L1007-1012]; arguments go through the number conversion (Booleans
  -1/0, Strings parsed).
* Domain errors (``Sqrt(-1)``, ``Log(0)``, ``Acos(2)``) are **-707 Value out-of-range** (the
  dictionary's inferred code; the spec recommends an exception over NaN, consistent with 1/0);
  a result beyond the Double range (``Exp(1000)``, ``Cosh(1000)``) is **-710**.
* The rounding functions (``Floor``, ``Ceiling``, ``Fix``, ``Int``) of an infinite or NaN value
  are **-708 Value infinite or NaN**: the value has no integer part, and the controller's text
  names exactly that fault.  So are ``Sin``, ``Cos`` and ``Tan`` of an infinity, which has no
  angle (Python's math module would raise a bare ValueError there).
* The manuals list no ``Math.Round`` (nor Truncate/IEEERemainder), so there is none: a program
  using it would not run on a controller either.  ``Fix`` (toward zero) and ``Int`` (floor) are
  the documented rounding functions.
* ``Rnd(seed)`` follows the dictionary's description (VB semantics): no argument or a positive
  seed -> the next value in [0, 1); 0 -> the previous value again; a negative seed restarts a
  deterministic sequence from that seed (the same value for the same seed).
"""

from __future__ import annotations

import math
import random
import threading
from typing import Any

from gplrt.lang.conversions import to_double
from gplrt.lang.errors import ARITHMETIC_OVERFLOW, VALUE_INFINITE_OR_NAN, VALUE_OUT_OF_RANGE, GplException
from gplrt.lang.gpltypes import Double
from gplrt.lang.operators import power

__all__ = ["Math", "Fix", "Int", "Rnd", "rnd_seed"]


def _f(x: Any) -> float:
    return x if type(x) is float else to_double(x)


def _domain(name: str, x: float) -> GplException:
    return GplException(VALUE_OUT_OF_RANGE, detail=f"Math.{name}({x}) is undefined")


def _whole(name: str, rounding: Any, value: Any) -> float:
    """``rounding`` (math.floor, ceil or trunc) of ``value`` as a Double; -708 if not finite."""
    x = _f(value)
    if not math.isfinite(x):
        raise GplException(VALUE_INFINITE_OR_NAN, detail=f"{name}({x}) has no integer part")
    return float(rounding(x))


def _no_angle(name: str, x: float) -> GplException:
    """Sin/Cos/Tan of an infinity (module docstring); the callers keep math's call inline."""
    return GplException(VALUE_INFINITE_OR_NAN, detail=f"Math.{name}({x}) has no angle")


def _overflow(name: str, x: float) -> GplException:
    return GplException(ARITHMETIC_OVERFLOW, detail=f"Math.{name}({x}) overflows a Double")


class _Math:
    """GPL ``Math``: Shared numeric methods and constants (angles in radians)."""

    __slots__ = ()

    @property
    def E(self) -> Double:
        """``Math.E``: the natural logarithmic base (a read-only property of the global class)."""
        return math.e  # type: ignore[return-value]

    @property
    def PI(self) -> Double:
        """``Math.PI``."""
        return math.pi  # type: ignore[return-value]

    @staticmethod
    def Abs(value: Double) -> Double:
        return abs(_f(value))  # type: ignore[return-value]

    @staticmethod
    def Acos(cosine: Double) -> Double:
        x = _f(cosine)
        if not -1.0 <= x <= 1.0:
            raise _domain("Acos", x)
        return math.acos(x)  # type: ignore[return-value]

    @staticmethod
    def Asin(sine: Double) -> Double:
        x = _f(sine)
        if not -1.0 <= x <= 1.0:
            raise _domain("Asin", x)
        return math.asin(x)  # type: ignore[return-value]

    @staticmethod
    def Atan(tangent: Double) -> Double:
        return math.atan(_f(tangent))  # type: ignore[return-value]

    @staticmethod
    def Atan2(sine_factor: Double, cosine_factor: Double) -> Double:
        """Angle of (cosine_factor, sine_factor): ``atan2(y, x)``; (0, 0) gives 0 as in C."""
        return math.atan2(_f(sine_factor), _f(cosine_factor))  # type: ignore[return-value]

    @staticmethod
    def Ceiling(value: Double) -> Double:
        return _whole("Math.Ceiling", math.ceil, value)  # type: ignore[return-value]

    @staticmethod
    def Cos(angle: Double) -> Double:
        x = _f(angle)
        try:
            return math.cos(x)  # type: ignore[return-value]
        except ValueError:
            raise _no_angle("Cos", x) from None

    @staticmethod
    def Cosh(angle: Double) -> Double:
        x = _f(angle)
        try:
            return math.cosh(x)  # type: ignore[return-value]
        except OverflowError:
            raise _overflow("Cosh", x) from None

    @staticmethod
    def Exp(exponent: Double) -> Double:
        x = _f(exponent)
        try:
            return math.exp(x)  # type: ignore[return-value]
        except OverflowError:
            raise _overflow("Exp", x) from None

    @staticmethod
    def Floor(value: Double) -> Double:
        return _whole("Math.Floor", math.floor, value)  # type: ignore[return-value]

    @staticmethod
    def Log(value: Double) -> Double:
        """Natural logarithm; value <= 0 is -707."""
        x = _f(value)
        if not x > 0.0:
            raise _domain("Log", x)
        return math.log(x)  # type: ignore[return-value]

    @staticmethod
    def Log10(value: Double) -> Double:
        x = _f(value)
        if not x > 0.0:
            raise _domain("Log10", x)
        return math.log10(x)  # type: ignore[return-value]

    @staticmethod
    def Max(value_1: Double, value_2: Double) -> Double:
        a, b = _f(value_1), _f(value_2)
        return a if a >= b else b  # type: ignore[return-value]

    @staticmethod
    def Min(value_1: Double, value_2: Double) -> Double:
        a, b = _f(value_1), _f(value_2)
        return a if a <= b else b  # type: ignore[return-value]

    @staticmethod
    def Pow(base: Double, exponent: Double) -> Double:
        """Same rules as the ``^`` operator (negative base needs an integral power)."""
        return power(base, exponent)  # type: ignore[return-value]

    @staticmethod
    def Sign(value: Double) -> Double:
        """-1, 0 or 1 (the spec's recommendation)."""
        x = _f(value)
        return float((x > 0.0) - (x < 0.0))  # type: ignore[return-value]

    @staticmethod
    def Sin(angle: Double) -> Double:
        x = _f(angle)
        try:
            return math.sin(x)  # type: ignore[return-value]
        except ValueError:
            raise _no_angle("Sin", x) from None

    @staticmethod
    def Sinh(angle: Double) -> Double:
        x = _f(angle)
        try:
            return math.sinh(x)  # type: ignore[return-value]
        except OverflowError:
            raise _overflow("Sinh", x) from None

    @staticmethod
    def Sqrt(value: Double) -> Double:
        """Square root; a negative value is -707."""
        x = _f(value)
        if x < 0.0:
            raise _domain("Sqrt", x)
        return math.sqrt(x)  # type: ignore[return-value]

    @staticmethod
    def Tan(angle: Double) -> Double:
        x = _f(angle)
        try:
            return math.tan(x)  # type: ignore[return-value]
        except ValueError:
            raise _no_angle("Tan", x) from None

    @staticmethod
    def Tanh(angle: Double) -> Double:
        return math.tanh(_f(angle))  # type: ignore[return-value]


Math = _Math()


def Fix(number: Double) -> Double:
    """Integer part, truncating toward zero (``Fix(-2.7)`` = -2)."""
    return _whole("Fix", math.trunc, number)  # type: ignore[return-value]


def Int(number: Double) -> Double:
    """Integer part, truncating toward minus infinity (``Int(-2.7)`` = -3)."""
    return _whole("Int", math.floor, number)  # type: ignore[return-value]


_rng = random.Random(0x47504C)
_last = 0.0
_rng_lock = threading.Lock()


def rnd_seed(seed: int) -> None:
    """Restart the Rnd sequence (tests and simulation sessions, for reproducible runs)."""
    global _last
    with _rng_lock:
        _rng.seed(seed)
        _last = 0.0


def Rnd(seed: Double | None = None) -> Double:
    """Pseudo-random Double in [0, 1) (see module docstring for the seed rules)."""
    global _last
    with _rng_lock:
        if seed is None:
            _last = _rng.random()
            return _last  # type: ignore[return-value]
        s = _f(seed)
        if s < 0.0:
            _rng.seed(s)
            _last = _rng.random()
        elif s > 0.0:
            _last = _rng.random()
        return _last  # type: ignore[return-value]

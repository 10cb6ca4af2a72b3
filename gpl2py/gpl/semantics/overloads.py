"""Choosing among overloaded procedures and constructors (spec §8.3; docs/design/real-code.md).

GPL documents several ``Sub New`` with different argument lists and recommends choosing "by
argument count first, then by type compatibility, and report an error if the call is ambiguous";
real modules overload ordinary procedures the same way.  The rule, for procedures and ``New``
alike:

1. the candidates are the overloads whose parameter count admits the arguments (Optional
   parameters may be left out);
2. each argument costs what converting it to its parameter's type costs (:func:`conversion_cost`:
   nothing for the same type, a little for a widening number conversion, more for a narrowing
   one, most for a number <-> String conversion; impossible for an object of another class);
3. the overload with the smallest total wins; two with the same smallest total are ambiguous.

An argument whose type is unknown (a stub's value, or an expression already reported as wrong)
matches every parameter at no cost; when that leaves several overloads, the checker takes the
first declared without a diagnostic (the mistake was reported already, or the stub's type is
known only to the protected code).
"""

from __future__ import annotations

from collections.abc import Sequence

from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.symbols import ProcSym

# What a conversion costs (smaller is a better match).  Widening numbers cost their distance in
# the Byte < Short < Integer < Single < Double order (so Integer prefers Single to Double, as VB
# does); narrowing (and anything from or to Boolean) costs more than any widening; String <->
# number more still.
_NARROWING = 10
_TEXT = 20


def conversion_cost(src: t.GplType, dst: t.GplType) -> int | None:
    """What passing a ``src`` value to a ``dst`` parameter costs, or None if it cannot be passed."""
    if t.permissive(src) or t.permissive(dst) or src == dst:
        return 0
    if src is t.NOTHING:
        return 1 if dst.is_reference else None
    if isinstance(src, t.PrimitiveType) and isinstance(dst, t.PrimitiveType):
        if src is t.STRING or dst is t.STRING:
            return _TEXT
        distance = t.numeric_rank(dst) - t.numeric_rank(src)
        if distance > 0 and src is not t.BOOLEAN:
            return distance
        return _NARROWING + abs(distance)
    if isinstance(src, t.ArrayType) and isinstance(dst, t.ArrayType):
        ok = src.rank == dst.rank and t.ERROR in (src.element, dst.element)
        return 1 if ok else None
    return None


def best_overloads(candidates: Sequence[ProcSym], arg_types: Sequence[t.GplType]) -> list[ProcSym]:
    """The overloads that fit ``arg_types`` best (several when the call is ambiguous, none when
    no overload takes these arguments), in declaration order."""
    n = len(arg_types)
    scored: list[tuple[int, ProcSym]] = []
    for p in candidates:
        if not p.min_args <= n <= len(p.params):
            continue
        total = 0
        for a, param in zip(arg_types, p.params):
            cost = conversion_cost(a, param.type)
            if cost is None:
                break
            total += cost
        else:
            scored.append((total, p))
    if not scored:
        return []
    best = min(cost for cost, _ in scored)
    return [p for cost, p in scored if cost == best]


def signature_text(p: ProcSym) -> str:
    """``Log(String, Integer)``: how a message names one overload."""
    return f"{p.name}({', '.join(str(v.type) for v in p.params)})"


__all__ = ["conversion_cost", "best_overloads", "signature_text"]

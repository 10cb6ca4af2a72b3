"""GPL delegates: call templates bound to a procedure (spec gpl-language.md §9.4).

* ``New D(AddressOf f)`` -> ``D(f)``; ``New D(AddressOf obj.m)`` -> ``D(obj.m)``: the Python bound
  method keeps the object ``obj`` referenced when the delegate was made [000 L1647-1651].
* ``New D("Module.Proc")`` -> ``D.from_name("Module.Proc", module="Caller")`` (or ``D("...")``):
  the String is resolved **when New runs** with ``find_procedure`` (Public module procedures or
  Public Shared class procedures [000 L1653-1666]); lookup failures raise its codes (-729, -772,
  -798).  If the delegate class declares ``param_count``, a procedure with a different number of
  parameters is **-741 Argument mismatch** (the recommendation for the UNSPECIFIED run-time
  signature mismatch).
* Invoking a delegate calls its target: ``d(3)``.  A delegate variable that is ``Nothing`` cannot be
  called: ``invoke(d, *args)`` raises **-796 No delegate defined** for it (and
  ``as_gpl_exception`` maps Python's "NoneType is not callable" to the same code).

A GPL ``Delegate Function T(...)`` statement becomes a subclass (``class T(Delegate):
param_count = 1``) or ``delegate_type("T", 1)``.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import Any, ClassVar

from gplrt.lang.errors import (
    ARGUMENT_MISMATCH,
    NO_DELEGATE_DEFINED,
    GplException,
)
from gplrt.lang.procedures import find_procedure


__all__ = ["Delegate", "delegate_type", "invoke", "NO_DELEGATE_DEFINED", "ARGUMENT_MISMATCH"]


def _positional_count(func: Callable[..., Any]) -> int | None:
    """Number of positional parameters, or None when it cannot be known (``*args``, builtins)."""
    try:
        sig = inspect.signature(func)
    except (TypeError, ValueError):
        return None
    count = 0
    for p in sig.parameters.values():
        if p.kind is p.VAR_POSITIONAL:
            return None
        if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD):
            count += 1
    return count


class Delegate:
    """A delegate object: holds a callable target and calls it when invoked."""

    __slots__ = ("_target",)

    #: Number of parameters of the GPL template, or None to accept any procedure.
    param_count: ClassVar[int | None] = None

    def __init__(self, target: Callable[..., Any] | str, *, module: str | None = None) -> None:
        if isinstance(target, str):
            # an overloaded name: the overload taking the template's parameter count
            target = find_procedure(target, module, type(self).param_count)
            self._check_signature(target)
        elif target is None or not callable(target):
            raise GplException(NO_DELEGATE_DEFINED, detail=f"no procedure to bind: {target!r}")
        self._target = target

    @classmethod
    def from_name(cls, name: str, module: str | None = None) -> Delegate:
        """``New D("Module.Proc")``: resolve the String now, as seen from ``module``."""
        return cls(name, module=module)

    def _check_signature(self, func: Callable[..., Any]) -> None:
        expected = type(self).param_count
        if expected is None:
            return
        actual = _positional_count(func)
        if actual is not None and actual != expected:
            raise GplException(
                ARGUMENT_MISMATCH,
                detail=f"{type(self).__name__} takes {expected} arguments, the procedure {actual}",
            )

    @property
    def target(self) -> Callable[..., Any]:
        """The bound procedure (Python side)."""
        return self._target

    def __call__(self, *args: Any) -> Any:
        return self._target(*args)

    def __repr__(self) -> str:
        name = getattr(self._target, "__qualname__", repr(self._target))
        return f"{type(self).__name__}({name})"


def delegate_type(name: str, param_count: int | None = None) -> type[Delegate]:
    """A new delegate class for a GPL ``Delegate`` statement."""
    return type(name, (Delegate,), {"__slots__": (), "param_count": param_count})


def invoke(delegate: Delegate | None, *args: Any) -> Any:
    """Call ``delegate``; ``Nothing`` is -796 No delegate defined."""
    if delegate is None:
        raise GplException(NO_DELEGATE_DEFINED, detail="the delegate is Nothing")
    return delegate(*args)

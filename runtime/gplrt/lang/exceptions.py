"""Lowering helpers for Try/Catch: every fault reaches a ``Catch`` as a GPL exception.

GPL's Catch catches every run-time error, each with its controller error code (spec
gpl-language.md §11.1).  The runtime raises ``GplException`` itself wherever it can; this module
maps the Python faults that may still escape (from plain Python emitted for typed code, or from
hand-written Python) to the best-matching controller code (gpl-dictionary.md §14):

==============================================  ======  ===================================
Python fault                                    code    controller text
==============================================  ======  ===================================
ZeroDivisionError (``x / 0`` in plain code)      -709    Division by 0
OverflowError (``2.0 ** 5000``, int -> float)    -710    Arithmetic overflow
RecursionError                                   -755    Thread stack too small
IndexError (a list used as an array)             -767    Invalid array index
``None(...)`` -- calling a Nothing delegate      -796    No delegate defined
AttributeError/TypeError on ``None``             -757    Object not instantiated
``raise None`` (``Throw ex`` with ex Nothing)    -757    Object not instantiated
ValueError "math domain error" (Sqrt(-1) ...)    -707    Value out-of-range
ValueError "could not convert string to float"   -717    Invalid number format
ValueError "cannot convert float NaN ..."        -708    Value infinite or NAN
MemoryError                                      -200    No memory available
anything else                                    -201    System internal consistency error
==============================================  ======  ===================================

Why -757 (and not -782 *Object value is Nothing*) for using a Nothing object: the typical GPL
fault is a variable declared without ``New`` (``Dim loc As Location`` then ``loc.X = 1``), which is
an object that was never instantiated; -782 is kept for places that receive Nothing as a *value*
where an object is required (e.g. ``CStr(Nothing)``).

What the GPL error says (decision, issue 20): a Python fault that maps to a controller code *is* that
GPL fault, so its error says only what the controller would -- ``*Invalid array index*`` at the GPL
line, never ``- IndexError: list assignment index out of range`` (the user wrote GPL, and Python's
words about lists or ``'NoneType'`` name nothing they can find in it).  Only -201, the catch-all for
a fault no GPL error describes (a bug in a hand-written stub, or in gpl2py), keeps the Python text as
its ``detail``: that report is about Python code, and its author needs the text to find the bug.

Only ``Exception`` subclasses are converted: ``KeyboardInterrupt``, ``SystemExit``,
``GeneratorExit`` and the thread machinery's own ``BaseException`` signals (thread abort) are
re-raised unchanged by ``as_gpl_exception`` so that a GPL Catch never swallows them.  The original
Python exception is kept as ``__cause__`` of the GplException for debugging.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any, NoReturn, TypeVar

from gplrt.lang.errors import (
    ARITHMETIC_OVERFLOW,
    DIVISION_BY_ZERO,
    INTERNAL_ERROR,
    INVALID_ARRAY_INDEX,
    INVALID_NUMBER_FORMAT,
    NO_DELEGATE_DEFINED,
    NO_MEMORY,
    NOT_IMPLEMENTED,
    OBJECT_NOT_INSTANTIATED,
    THREAD_STACK_TOO_SMALL,
    VALUE_INFINITE_OR_NAN,
    VALUE_OUT_OF_RANGE,
    GplException,
)
from gplrt.lang.sourcemap import locate


__all__ = ["ExitTry", "as_gpl_exception", "compile_error", "gpl_code_for", "gpl_entry", "not_available",
           "not_simulated"]


def gpl_code_for(exc: BaseException) -> int:
    """The controller error code for a Python fault (table in the module docstring)."""
    if isinstance(exc, GplException):
        return exc.ErrorCode
    if isinstance(exc, ZeroDivisionError):
        return DIVISION_BY_ZERO
    if isinstance(exc, OverflowError):
        return ARITHMETIC_OVERFLOW
    if isinstance(exc, RecursionError):
        return THREAD_STACK_TOO_SMALL
    if isinstance(exc, IndexError):
        return INVALID_ARRAY_INDEX
    if isinstance(exc, MemoryError):
        return NO_MEMORY
    text = str(exc)
    if isinstance(exc, (AttributeError, TypeError)) and "NoneType" in text:
        if "not callable" in text:
            return NO_DELEGATE_DEFINED
        return OBJECT_NOT_INSTANTIATED
    if isinstance(exc, TypeError) and "exceptions must derive from BaseException" in text:
        return OBJECT_NOT_INSTANTIATED  # Throw of an Exception variable that is Nothing
    if isinstance(exc, ValueError):
        if "convert string to float" in text or "invalid literal" in text:
            return INVALID_NUMBER_FORMAT
        if "NaN" in text:
            return VALUE_INFINITE_OR_NAN
        if "domain" in text:
            return VALUE_OUT_OF_RANGE
        return VALUE_OUT_OF_RANGE
    return INTERNAL_ERROR


class ExitTry(BaseException):
    """GPL's ``Exit Try``: generated code raises it and the Try statement's own first ``except``
    clause ends it, so Finally runs and leaving loops nested in the Try body needs no flags
    (docs/design/lowering.md).  A BaseException, so no GPL Catch could ever receive it."""


def as_gpl_exception(exc: BaseException) -> GplException:
    """The GplException a ``Catch`` receives for ``exc``.

    A GplException is returned as is (``Catch ex`` gets exactly the thrown object), without the
    place it was thrown from (:meth:`GplException.forget_location`): thrown again, it is reported
    at that Throw, as the controller does (docs/design/real-code.md, "A reused Exception object").  Other
    ``Exception``s become a new GplException with the code from ``gpl_code_for`` and the original
    as ``__cause__``; only -201 (no GPL error describes the fault) has the Python message as
    ``detail`` (module docstring).  Non-``Exception`` BaseExceptions are
    re-raised (see module docstring).  Lowering: ``except BaseException as _e:
    ex = as_gpl_exception(_e)``.
    """
    if isinstance(exc, GplException):
        exc.forget_location()  # caught: a later Throw of it is reported where that Throw is
        return exc
    if not isinstance(exc, Exception):
        raise exc
    code = gpl_code_for(exc)
    gex = GplException(code, detail=f"{type(exc).__name__}: {exc}" if code == INTERNAL_ERROR else None)
    gex.__cause__ = exc
    return gex


def gpl_entry(func: Callable[..., Any]) -> Callable[..., Any]:
    """Wrap a GPL procedure that is started by name (a thread's start procedure, a delegate made
    from a String, ProjectStart) so that a Python fault escaping plain generated code -- an
    IndexError, an AttributeError on Nothing -- leaves it as the GplException a Catch would have
    received, with the controller's code and the GPL file:line where it happened.  The thread
    machinery then reports "-757 *Object not instantiated* (at Main.gpl:12)" instead of an
    internal Python error.  Direct calls between generated procedures do not go through this.
    """

    @functools.wraps(func)
    def entry(*args: Any) -> Any:
        try:
            return func(*args)
        except GplException:
            raise
        except Exception as exc:
            gex = as_gpl_exception(exc)
            gex.gpl_location = locate(exc)
            raise gex from exc

    entry.__gpl_procedure__ = func  # type: ignore[attr-defined]
    return entry


def not_available(name: str, builtin: bool = False) -> NoReturn:
    """What a stub does when the program uses it (gpl2py, README "Porting your own project").

    A name defined only in a protected (.gpp) source, or a built-in member the simulated controller
    lacks, raises -204 *Not implemented*: the code exists on a controller but cannot run here.
    (-729 *Undefined symbol* would claim the name does not exist, which is not true.)  The
    exception's subject names what is missing, in ``Message`` itself, so a program that catches it
    and an unhandled-error report both read "*Not implemented*: protected source not available:
    VendorLib.Grip" (the controller's ``*text*: ...`` form; a bare "*Not implemented*" would leave
    the user guessing which of many stubs was hit).
    """
    what = "not available in the simulated controller" if builtin else "protected source not available"
    raise GplException(NOT_IMPLEMENTED, subject=f"{what}: {name}")


def compile_error(code: int, diagnostic: str) -> NoReturn:
    """What code translated despite an error does when the program reaches it (gpl2py's
    ``--keep-going``, or the error ignored: docs/design/lowering.md, "Code that keeps an error").

    The controller would not have compiled the line; gpl2py translated the rest of the project, and
    the line raises the error the controller's compiler names for the fault (-729 *Undefined
    symbol* for an undeclared name: ``gpl2py.messages.RUNTIME_CODES``), so the program's own
    Try/Catch sees an ordinary GPL error.  The subject is gpl2py's diagnostic ("GPL2001: 'x' is not
    declared"), in ``Message`` as for a stub, so an unhandled-error report says which line of the
    source was kept with its error and why.
    """
    raise GplException(code, subject=diagnostic)


def gpl_member_name(qualname: str) -> str:
    """``Move.Trigger`` from a runtime method's ``__qualname__`` (``_MoveClass.Trigger``): the
    global classes are private classes named ``_<GPL name>Class`` (or ``_<GPL name>``)."""
    owner, _, member = qualname.rpartition(".")
    owner = owner.lstrip("_")
    if owner.endswith("Class") and len(owner) > len("Class"):
        owner = owner[: -len("Class")]
    return f"{owner}.{member}" if owner else member


_F = TypeVar("_F", bound=Callable[..., Any])


def not_simulated(func: _F) -> _F:
    """Mark a built-in member that the simulated controller does not implement.

    The member keeps its real GPL signature (the transpiler reads it, so a wrong argument count is
    a translation error, ``runtime/gplrt/CATALOGUE.md``) and raises -204 *Not implemented* when a
    program calls it, which a GPL ``Catch`` sees like any other error.  The body of a decorated
    method is never run: to implement the member, delete the decorator and write the body.
    """
    name = gpl_member_name(func.__qualname__)

    @functools.wraps(func)
    def raiser(*args: Any, **kwargs: Any) -> NoReturn:
        not_available(name, builtin=True)

    raiser.__gpl_not_simulated__ = True  # type: ignore[attr-defined]
    return raiser  # type: ignore[return-value]

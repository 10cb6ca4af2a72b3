"""TMscript members on the runtime's classes: which names a script may use after a dot, and the
script's error, not Python's ``AttributeError``, for any other.

The convention (gplrt/CATALOGUE.md's for GPL): a TMscript member keeps the manual's spelling and
starts with an upper-case letter (``Value``, ``MOI``, ``GetValue``); anything else on a runtime
class of the TM layer is snake_case or starts with ``_``.  A member is a property (read and
written when it has a setter, read only otherwise), a class constant (read only) or a method.
The front end's table of implemented members is generated from these classes
(``python -m gpl2py.tmscript.semantics.members_gen``), so the checks and the runtime cannot
disagree; a member a script names that is not here is a compile-time error.
"""

from __future__ import annotations

import functools

from gplrt.tm.values import TMError


@functools.cache
def surface(cls: type) -> dict[str, str]:
    """``cls``'s TMscript members: name -> ``"R"``, ``"RW"`` or ``"method"``."""
    out: dict[str, str] = {}
    for klass in reversed(cls.__mro__):
        for name, value in vars(klass).items():
            if not name[:1].isupper():
                continue
            if isinstance(value, property):
                out[name] = "RW" if value.fset is not None else "R"
            elif callable(value) or isinstance(value, (staticmethod, classmethod)):
                out[name] = "method"
            else:
                out[name] = "R"
    return out


class Members:
    """A runtime object a script reaches with a dot (``tcp1.Mass``, ``Robot[0].Joint``).  The
    checks accept only the members of :func:`surface`; this guards what they cannot see (which
    object ``Base[name]`` gives is known at run time): an unknown member is the script's error,
    and writing a read-only one is the manual's "invalid operation", ignored (L14433, L14481)."""

    #: How the script's error names the object (``TTCP``, ``Robot[0]``).
    tm_name = "object"

    def __getattr__(self, name: str) -> object:  # (only called when Python found nothing)
        if not name[:1].isupper():
            raise AttributeError(name)
        raise TMError(f"{self.tm_name} has no member {name}")

    def __setattr__(self, name: str, value: object) -> None:
        if not name[:1].isupper():
            object.__setattr__(self, name, value)  # (the runtime's own state)
            return
        mode = surface(type(self)).get(name)
        if mode == "RW":
            object.__setattr__(self, name, value)
        elif mode != "R":
            raise TMError(f"{self.tm_name} has no member {name} to assign")

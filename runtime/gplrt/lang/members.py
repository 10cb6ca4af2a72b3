"""Members of values whose type the transpiler could not know (docs/security.md, "Member access").

GPL is statically typed: every ``obj.Name`` names a member of a known class, and generated code
reads it as a plain attribute.  The one exception is a value that came out of protected code -- a
stub's result, or whatever the program stored in a variable of a protected module.  Its class is
unknown at translation time, so ``obj.Name`` is lowered to ``get_member(obj, "Name")`` (and
``obj.Name = v`` to ``set_member(obj, "Name", v)``), and only here is a GPL name turned into a
Python attribute.  What it may reach:

* an instance of a class transpiled from GPL: the Public members listed in its ``_gpl_members_``
  table (GPL name, lower case -> Python name), which lowering writes into every class of a project
  that has such accesses;
* an object of the runtime (``gplrt``: Location, Exception, a socket ...): its GPL members, which
  are exactly its attributes whose name starts with an upper-case letter (runtime/gplrt/CATALOGUE.md);
* an object of a user stub (``gpl2py --stubs``: Python the user wrote for the protected code) or of
  one of gpl2py's shipped stand-ins: its public attributes (names not starting with ``_``);
* nothing else: Python's own objects (numbers, strings, functions, modules, frames) have no GPL
  members, and no name starting with ``_`` is ever looked up, so ``X.__class__`` or
  ``X.__reduce_ex__(2)`` from untrusted GPL cannot reach the interpreter's internals.

GPL names are case-insensitive, so the lookup is too.  A name the object does not have is error
-729 *Undefined symbol*; a Nothing object is -757 *Object not instantiated*, as for a known type.
"""

from __future__ import annotations

from typing import Any

from gplrt.lang.errors import OBJECT_NOT_INSTANTIATED, READ_ONLY, UNDEFINED_SYMBOL, GplException

# Per class: GPL name (lower case) -> Python attribute.  Classes are few and live as long as the
# process; the tables are small.
_TABLES: dict[type, dict[str, str]] = {}

# generated package modules that hold --stubs files and shipped stand-ins (gpl2py/gpl/lower/user_stubs.py)
_STUB_MODULE_PREFIXES = ("_user_", "_standin_")


def _is_user_stub(cls: type) -> bool:
    module = getattr(cls, "__module__", "") or ""
    return module.rpartition(".")[2].startswith(_STUB_MODULE_PREFIXES)


def _is_runtime(cls: type) -> bool:
    module = getattr(cls, "__module__", "") or ""
    return module == "gplrt" or module.startswith("gplrt.")


def _class_table(cls: type) -> dict[str, str]:
    table = _TABLES.get(cls)
    if table is None:
        explicit = getattr(cls, "_gpl_members_", None)
        if isinstance(explicit, dict):
            table = {str(k).lower(): str(v) for k, v in explicit.items()}
        elif _is_runtime(cls):
            table = {n.lower(): n for n in sorted(dir(cls)) if n[:1].isascii() and n[:1].isupper()}
        else:
            table = {}
        _TABLES[cls] = table
    return table


def _attribute(obj: Any, name: str) -> str:
    """The Python attribute that GPL member ``name`` of ``obj`` names, or a GPL error."""
    if obj is None:
        raise GplException(OBJECT_NOT_INSTANTIATED, detail=f"member {name} of Nothing")
    key = name.lower()
    if not key.startswith("_"):
        cls = type(obj)
        found = _class_table(cls).get(key)
        if found is not None:
            return found
        if _is_user_stub(cls):
            for attr in sorted(dir(obj)):
                if attr.lower() == key:
                    return attr
    raise GplException(UNDEFINED_SYMBOL, detail=f"{type(obj).__name__} has no member {name}")


def get_member(obj: Any, name: str) -> Any:
    """``obj.Name`` for a value of unknown type (see the module doc)."""
    return getattr(obj, _attribute(obj, name))


def set_member(obj: Any, name: str, value: Any) -> None:
    """``obj.Name = value`` for a value of unknown type (see the module doc)."""
    attr = _attribute(obj, name)
    try:
        setattr(obj, attr, value)
    except AttributeError as exc:  # a property without a setter
        raise GplException(READ_ONLY, detail=f"member {name}") from exc


__all__ = ["get_member", "set_member"]

"""Where each stub lives in the generated package, and its Python name (see semantics/stubs.py).

``Module.Name`` of an unknown module -> ``<module>.py`` (a stub module named like the GPL module,
snake_case, so ``VendorLib.Grip(1)`` reads ``vendor_lib.Grip(1)``); a bare protected name and an
unknown built-in member -> ``_stubs.py`` (``Foo``; ``Controller_SomethingUnknown``).
"""

from __future__ import annotations

from gpl2py.gpl.lower.names import py_ident
from gpl2py.gpl.semantics.stubs import Stub

STUBS_MODULE = "_stubs"


def stub_module_name(stub: Stub, stub_module_py: dict[str, str]) -> str:
    """The generated module that defines ``stub``."""
    if stub.module is not None:
        return stub_module_py[stub.module.lower()]
    return STUBS_MODULE


#: What every stub module defines besides its stubs (lower/stubs.py): no stub may take these.
STUBS_MODULE_NAMES = frozenset({"not_available", "_VARIABLES", "_reset", "__getattr__", "__all__"})


def stub_attr_base(stub: Stub) -> str:
    """The name the stub prefers in its module (``ProjectNames`` makes it unique there)."""
    if stub.builtin is not None:
        return py_ident(f"{stub.builtin}_{stub.member}")
    return py_ident(stub.member)


__all__ = ["STUBS_MODULE", "STUBS_MODULE_NAMES", "stub_attr_base", "stub_module_name"]

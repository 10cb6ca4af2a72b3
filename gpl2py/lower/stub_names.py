"""Where each stub lives in the generated package, and its Python name (see semantics/stubs.py).

``Module.Name`` of an unknown module -> ``<module>.py`` (a stub module named like the GPL module,
snake_case, so ``VendorLib.Grip(1)`` reads ``vendor_lib.Grip(1)``); a bare protected name and an
unknown built-in member -> ``_stubs.py`` (``Foo``; ``Controller_SomethingUnknown``).
"""

from __future__ import annotations

from gpl2py.lower.names import py_ident
from gpl2py.semantics.stubs import Stub

STUBS_MODULE = "_stubs"


def stub_module_name(stub: Stub, stub_module_py: dict[str, str]) -> str:
    """The generated module that defines ``stub``."""
    if stub.module is not None:
        return stub_module_py[stub.module.lower()]
    return STUBS_MODULE


def stub_attr(stub: Stub) -> str:
    """The stub's attribute name in its module."""
    if stub.builtin is not None:
        return py_ident(f"{stub.builtin}_{stub.member}")
    return py_ident(stub.member)


__all__ = ["STUBS_MODULE", "stub_attr", "stub_module_name"]

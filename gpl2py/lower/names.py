"""Python names for GPL names (docs/design/lowering.md, "Names").

GPL names keep their declared spelling.  A GPL name that is a Python keyword or builtin (or
``self``, which methods use) gets a trailing underscore; a GPL name starting with ``_`` becomes
``_u_...`` because every name gpl2py invents starts with ``_`` (``_result``, ``_g1``, ``_sel2``),
so invented names can never collide with program names.
"""

from __future__ import annotations

import builtins
import keyword
import re

_RESERVED = frozenset(keyword.kwlist) | frozenset(keyword.softkwlist) | frozenset(dir(builtins)) | {"self", "cls"}


def py_ident(name: str) -> str:
    """The Python identifier for a GPL identifier."""
    if name.startswith("_"):
        return "_u" + name
    if name in _RESERVED:
        return name + "_"
    return name


def snake_case(name: str) -> str:
    """``CmdParse`` -> ``cmd_parse``, ``TCPServer`` -> ``tcp_server``, ``my_Mod`` -> ``my_mod``."""
    s = re.sub(r"([A-Z]+)([A-Z][a-z])", r"\1_\2", name)
    s = re.sub(r"([a-z0-9])([A-Z])", r"\1_\2", s)
    s = re.sub(r"[^0-9A-Za-z_]", "_", s).lower().strip("_") or "module"
    if s[0].isdigit():
        s = "m_" + s
    if keyword.iskeyword(s) or s in dir(builtins):
        s += "_"
    return s


def py_float(value: float) -> str:
    """A Python float literal that round-trips (``1.0``, ``0.1``, ``1e+300``)."""
    text = repr(float(value))
    if text == "inf":
        return "float(\"inf\")"
    return text

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

from gpl2py.lower.text import py_string

_RESERVED = frozenset(keyword.kwlist) | frozenset(keyword.softkwlist) | frozenset(dir(builtins)) | {"self", "cls"}


def py_ident(name: str) -> str:
    """The Python identifier for a GPL identifier."""
    if name.startswith("_"):
        return "_u" + name
    if name in _RESERVED:
        return name + "_"
    return name


def overload_names(name: str, signatures: list[list[str]]) -> list[str]:
    """Python names for the overloads of procedure ``name``, one per parameter list (the names
    of its parameter types), in declaration order: ``Log_1``/``Log_2`` when the parameter counts
    tell them apart, else the types (``Scale_Integer``/``Scale_String``, ``Scale_0`` for none).
    Readable at a call site, stable when a further overload is added with a new count; the
    caller makes them unique against the other names in scope."""
    base = py_ident(name) if name.startswith("_") else name  # a suffix never leaves a keyword
    counts = [len(sig) for sig in signatures]
    if len(set(counts)) == len(counts):
        return [f"{base}_{n}" for n in counts]
    return [f"{base}_{'_'.join(_type_word(w) for w in sig) or '0'}" for sig in signatures]


def _type_word(type_name: str) -> str:
    """``Integer`` -> ``Integer``, ``Double(,)`` -> ``DoubleArray``, ``Mod.Cls`` -> ``Cls``."""
    word = type_name.rsplit(".", 1)[-1]
    if "(" in word:
        word = word[: word.index("(")] + "Array"
    return re.sub(r"[^0-9A-Za-z]", "", word) or "Any"


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


def py_literal(value: object) -> str:
    """The Python literal for a folded GPL constant (Boolean, whole number, Double, String)."""
    if isinstance(value, bool):
        return "True" if value else "False"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return py_float(value)
    if isinstance(value, str):
        return py_string(value)
    raise TypeError(f"not a GPL constant value: {value!r}")


def py_float(value: float) -> str:
    """A Python float literal that round-trips (``1.0``, ``0.1``, ``1e+300``)."""
    text = repr(float(value))
    if text == "inf":
        return "float(\"inf\")"
    return text

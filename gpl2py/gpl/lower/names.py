"""Python names for GPL names (docs/design/lowering.md, "Names"; docs/security.md, "Names").

The one place that decides what a GPL name becomes in Python, and which Python names GPL code may
never take.  The scope tables that hand out names within one namespace (a package, a module's
globals, a stub module) are in ``lower/context.py`` and use these rules.

* :func:`py_ident` maps a GPL identifier to a Python one, **one-to-one**: GPL names keep their
  declared spelling; one that Python or generated code uses bare (a keyword, a builtin, ``self``,
  ``cls``, ``sys``) -- or is such a name followed by underscores -- gets one more trailing
  underscore (``list`` -> ``list_``, ``list_`` -> ``list__``), so two GPL names never meet in one
  Python name; a GPL name starting with ``_`` becomes ``_u...`` because every name gpl2py invents
  starts with ``_`` (``_result``, ``_g1``, ``_sel2``), so invented names can never collide with
  program names.
* :data:`RUNTIME_IMPORTS` lists every name generated code imports from the runtime (and ``math``);
  ``ModuleContext.helper`` refuses any other, so :data:`RUNTIME_NAMES`, the names a module or stub
  file must not take, is complete by construction.
* :func:`package_name` keeps a project's package from hiding a module the runtime imports.
"""

from __future__ import annotations

import builtins
import keyword
import re
import sys
from collections.abc import Iterable

from gpl2py.pywriter.text import py_string

#: Names generated code uses bare besides the runtime's: Python's keywords and builtins, the method
#: receivers, and ``sys`` (``_this = sys.modules[__name__]``).  A GPL name in this set gets ``_``.
PYTHON_NAMES = (frozenset(keyword.kwlist) | frozenset(keyword.softkwlist) | frozenset(dir(builtins))
                | {"self", "cls", "sys"})

#: Every name a generated module imports, by module (``from <module> import <name>``).  Built-in
#: classes and functions come from ``gplrt.builtins`` under their catalogue names
#: (``gpl2py.gpl.semantics.catalogue``), which :func:`runtime_names` adds.
RUNTIME_IMPORTS: dict[str, frozenset[str]] = {
    "gplrt.lang.arrays": frozenset({"GplArray", "redim", "redim_preserve"}),
    "gplrt.lang.byref": frozenset({"AttrRef", "Box", "ItemRef"}),
    "gplrt.lang.conversions": frozenset({
        "bool_num", "chk_double", "chk_int16", "chk_int32", "chk_uint8", "to_bool", "to_double",
        "to_int16", "to_int32", "to_number", "to_single", "to_string", "to_string_single", "to_uint8",
    }),
    "gplrt.lang.delegates": frozenset({"delegate_type"}),
    "gplrt.lang.exceptions": frozenset({"ExitTry", "as_gpl_exception", "compile_error", "gpl_entry",
                                        "not_available"}),
    "gplrt.lang.gpltypes": frozenset({"Ref"}),
    "gplrt.lang.members": frozenset({"get_member", "set_member"}),
    "gplrt.lang.operators": frozenset({
        "add", "and_", "div", "eq", "ge", "gt", "idiv", "is_nothing", "le", "lt", "mod", "mul", "ne",
        "neg", "not_", "or_", "power", "shl", "shr", "sub", "xor",
    }),
    "gplrt.lang.procedures": frozenset({"register_procedure", "use_procedures"}),
    "gplrt.lang.sourcemap": frozenset({"register_package"}),
    "gplrt.sim": frozenset({"Simulation", "current"}),
    "gplrt.threads": frozenset({"checkpoint", "paced", "paced_range"}),
    "math": frozenset({"atan", "atan2", "cos", "sin", "sqrt", "tan"}),
}

#: What a package's ``__init__.py`` defines besides its imports (lower/package.py), and the
#: modules every package has: no GPL module file may be called like one of them.
PACKAGE_NAMES = frozenset({"init", "main", "PROJECT", "__init__", "__main__"})

#: File names Windows refuses whatever the extension: a module or package never gets one, so a
#: translation can be copied to any controller PC.
DEVICE_NAMES = frozenset({"con", "prn", "aux", "nul", *(f"com{i}" for i in range(1, 10)),
                          *(f"lpt{i}" for i in range(1, 10))})

#: Top-level modules a generated package must not hide when ``python -m <package>`` runs from the
#: output folder (it is first on ``sys.path`` there): the standard library and the runtime's own.
TOP_LEVEL_MODULES = frozenset(sys.stdlib_module_names) | {
    "gplrt", "gpl2py", "numpy", "pinocchio", "pin", "ruckig", "matplotlib", "scipy", "hppfcl", "coal",
    "eigenpy", "libcst", "pytest", "hypothesis", "pymodbus", "pyflakes", "pycodestyle",
}


def runtime_names(extra: Iterable[str] = ()) -> frozenset[str]:
    """Every name generated code may import bare: :data:`RUNTIME_IMPORTS` plus ``extra`` (the
    catalogue's built-in names, which the caller reads)."""
    out: set[str] = set(extra)
    for names in RUNTIME_IMPORTS.values():
        out |= names
    return frozenset(out)


RUNTIME_NAMES = runtime_names()


def py_ident(name: str) -> str:
    """The Python identifier for a GPL identifier; distinct GPL names give distinct identifiers."""
    if name.startswith("_"):
        return "_u" + name
    if name.rstrip("_") in PYTHON_NAMES:
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


#: The longest module or package name made from input (file systems refuse names over 255 bytes,
#: and snake_case makes a name longer); a longer one is cut and keeps a hash of the whole.
MAX_FILE_NAME = 64


def module_base(name: str) -> str:
    """The file name (without ``.py``) a GPL module prefers: snake_case, never a name of the
    package's own (``init``, ``main``), a runtime import (``chk_int32``, ``current``), ``sys``
    or a Windows device name.  The project's scope table (lower/context.py) makes it unique."""
    base = _short(snake_case(name), name)
    if base.rstrip("_") in _NOT_MODULE_NAMES:
        base += "_mod"
    return base


_NOT_MODULE_NAMES = PACKAGE_NAMES | RUNTIME_NAMES | DEVICE_NAMES | {"sys"}


def package_name(project_name: str) -> str:
    """The package a project becomes: its name in snake_case (``gpl_project`` when it has none),
    never the name of a standard or runtime module nor a Windows device name, at most
    :data:`MAX_FILE_NAME` characters."""
    base = _short(snake_case(project_name), project_name) if project_name else "gpl_project"
    if base.rstrip("_") in TOP_LEVEL_MODULES | DEVICE_NAMES:
        base += "_gpl"
    return base


def _short(name: str, whole: str) -> str:
    """``name`` cut to :data:`MAX_FILE_NAME` characters with a hash of ``whole`` at the end, so
    that two long names stay two names."""
    if len(name) <= MAX_FILE_NAME:
        return name
    import hashlib  # (here: rarely needed, and 2 ms of check's start-up)

    digest = hashlib.sha1(whole.encode("utf-8", "surrogatepass")).hexdigest()[:8]
    return f"{name[:MAX_FILE_NAME - 9].rstrip('_')}_{digest}"


def snake_case(name: str) -> str:
    """``CmdParse`` -> ``cmd_parse``, ``TCPServer`` -> ``tcp_server``, ``my_Mod`` -> ``my_mod``."""
    s = re.sub(r"([A-Z]+)([A-Z][a-z])", r"\1_\2", name)
    s = re.sub(r"([a-z0-9])([A-Z])", r"\1_\2", s)
    s = re.sub(r"[^0-9A-Za-z_]", "_", s).lower().strip("_") or "module"
    if s[0].isdigit():
        s = "m_" + s
    if keyword.iskeyword(s) or s in _BUILTINS:
        s += "_"
    return s


_BUILTINS = frozenset(dir(builtins))


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

"""The catalogue of GPL built-ins: the one list of what GPL programs can name without declaring.

Generated code imports from here (``from gplrt.builtins import Location, Move``) and the
transpiler's semantic pass introspects the same tables (``gpl2py.semantics.catalogue``), so the
runtime and the transpiler cannot drift apart.  See ``gplrt/CATALOGUE.md`` for the conventions the
entries follow.

Each table maps the GPL spelling to the Python name exported by this module:

* ``CLASSES``   classes programs instantiate or declare variables of (``Dim l As Location``);
* ``GLOBAL_CLASSES`` classes with only Shared members, exported as one instance (``Move.Loc(...)``);
* ``FUNCTIONS`` functions called without a class prefix (``CInt``, ``Chr``, ``Format``);
* ``CONSTANTS`` predefined constants (``GPL_Righty``, ``GPL_CR``);
* ``TYPE_MEMBERS`` member catalogues of value types (``"String"`` -> the class whose staticmethods
  implement ``s.Length``, ``s.Substring(...)``; the string is the first argument).
"""

from __future__ import annotations

from gplrt.lang.errors import GplException

CLASSES: dict[str, str] = {
    "Exception": "GplException",
}

GLOBAL_CLASSES: dict[str, str] = {}

FUNCTIONS: dict[str, str] = {}

CONSTANTS: dict[str, str] = {}

TYPE_MEMBERS: dict[str, str] = {}

__all__ = ["GplException"]

"""Python names for V+ names, kept recognisable: ``ros.rev.bytes`` -> ``ros_rev_bytes``,
``$msg`` -> ``s_msg``, ``#safe`` -> ``p_safe``, ``%b1`` -> ``b_b1``, a Python keyword or builtin
gets a trailing ``_`` (``in`` -> ``in_``), and names that would collide in one function are told
apart by a number (:class:`Names`).  The runtime's own names follow the same rule
(docs/design/vplus-runtime.md): ``$CHR`` is ``vp.s_chr``, ``WAIT.EVENT`` ``vp.wait_event``.
"""

from __future__ import annotations

import builtins
import keyword
import re

_SIGIL = {"$": "s_", "#": "p_", "%": "b_", "": ""}
_TAKEN = frozenset(keyword.kwlist) | frozenset(keyword.softkwlist) | frozenset(dir(builtins)) | {"vp"}


def py_name(sigil: str, name: str) -> str:
    """A V+ name as a Python identifier (before collisions are resolved)."""
    base = _SIGIL.get(sigil, "") + re.sub(r"[^0-9A-Za-z_]", "_", name.lower())
    return base + "_" if base in _TAKEN else base


def runtime_name(word: str) -> str:
    """The runtime function of a V+ keyword or function: ``$CHR`` -> ``s_chr``, ``ABS`` -> ``abs_``."""
    sigil = word[0] if word[:1] in "$#%" else ""
    return py_name(sigil, word[len(sigil):])


class Names:
    """The Python names of one scope: each V+ symbol gets one, unique in the scope and distinct
    from ``reserved`` (the functions the scope calls, the module's own names)."""

    def __init__(self, reserved: set[str] | frozenset[str] = frozenset()) -> None:
        self.used: set[str] = set(reserved)
        self.of: dict[object, str] = {}

    def name(self, key: object, sigil: str, vname: str, suffix: str = "") -> str:
        found = self.of.get(key)
        if found is not None:
            return found
        base = py_name(sigil, vname) + suffix
        name, n = base, 2
        while name in self.used:
            name, n = f"{base}_{n}", n + 1
        self.used.add(name)
        self.of[key] = name
        return name

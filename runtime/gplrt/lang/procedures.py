"""The procedure registry: GPL procedures looked up by name at run time.

Threads and String-named delegates name their procedure in a String (``New Thread("Worker")``,
``New D("Module.Proc")``, spec gpl-language.md §9.4, §13), so generated code registers every
procedure when its module is imported::

    register_procedure("Station", "PickPart", PickPart, public=True)

and the runtime resolves names with ``find_procedure``.  The rules (§6.4, [000 L1653-1683]):

* Names are **case-insensitive** (§1.7).
* ``"Module.Proc"`` (or ``"Class.Proc"`` / ``"Module.Class.Proc"`` for a Shared procedure of a
  class, registered with the dotted ``module_name`` ``"Module.Class"``) names one procedure.
* A bare ``"Proc"`` resolves first to the procedure of that name in the **caller's module**
  (``module=``; Private allowed), then to the **single Public module-level procedure** of that name
  in all modules ("if item_name is unambiguous within all loaded modules, the module_name may be
  omitted").
* Errors (GplException): two Public candidates -> **-772 Ambiguous Public reference**; an unknown
  module or class qualifier -> **-798 No module defined**; no such procedure, or only Private
  ones in other modules -> **-729 Undefined symbol**.

Registration replaces an earlier entry for the same qualified name, so re-importing a module (a
new simulation session) is harmless; ``clear_procedures`` empties the registry for tests.

**Overloads.**  Real GPL declares several procedures of one name in a module or class, told apart
by their parameter lists.  Generated code registers each with its index (``overload=k``), so all
of them stay registered under the one GPL name.  A lookup that finds several overloads of the
name in one module picks the one whose parameter count admits the arguments the caller will pass
(``nargs``: none for a thread's start procedure, the template's count for a delegate): exactly
one must, else **-741 Argument mismatch** (none) or **-772 Ambiguous** (several, or the caller
does not say how many arguments it passes).  A lone procedure is returned as before and its
caller checks its parameters (threads and delegates raise -741 themselves).

**One registry per generated package.**  Two projects loaded in one process (two notebook Cells)
may both have a ``Main.Worker``; with one process-wide table, a thread started by name would find
the project loaded last.  So generated code registers into its package's own
:class:`ProcedureRegistry` (``register_procedure(..., package=__package__)``), the package's
``init()`` makes that registry the session's (``use_procedures(sim, package)``: it becomes
``Session.procedures``), and ``find_procedure`` looks names up in the registry of the calling
code's session (``gplrt.session.current_session()``, the session of the calling GPL thread),
falling back to the default, process-wide registry that hand-written Python registers into (no
``package``), which is also the registry of a session no package has initialised.  Direct calls
between procedures never touch a registry, so this costs nothing per call; a lookup by name costs
one dictionary access more.
"""

from __future__ import annotations

import inspect
import math
import threading
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from gplrt.lang.errors import (
    AMBIGUOUS_PUBLIC_REFERENCE,
    ARGUMENT_MISMATCH,
    NO_MODULE_DEFINED,
    UNDEFINED_SYMBOL,
    GplException,
)
from gplrt.session import current_scope, current_session

if TYPE_CHECKING:
    from gplrt.session import Session


__all__ = [
    "ProcedureEntry",
    "ProcedureRegistry",
    "registry_for",
    "default_registry",
    "use_procedures",
    "register_procedure",
    "find_procedure",
    "find_procedure_entry",
    "choose_overload",
    "clear_procedures",
    "registered_procedures",
    "UNDEFINED_SYMBOL",
    "AMBIGUOUS_PUBLIC_REFERENCE",
    "NO_MODULE_DEFINED",
]


@dataclass(frozen=True, slots=True)
class ProcedureEntry:
    """One registered procedure: ``path`` is the lower-cased qualifier (``("station",)`` or
    ``("station", "gripper")``), ``qualified_name`` the declared spelling ``"Station.PickPart"``."""

    path: tuple[str, ...]
    name: str
    qualified_name: str
    func: Callable[..., Any]
    public: bool
    overload: int = 0

    def accepts(self, nargs: int) -> bool:
        """Whether ``func`` can be called with ``nargs`` positional arguments."""
        low, high = _arity(self.func)
        return low <= nargs <= high


class ProcedureRegistry:
    """The procedures of one project (or the default registry of hand-written Python)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._by_name: dict[str, list[ProcedureEntry]] = {}
        self._qualifiers: set[str] = set()

    def register(self, module_name: str, proc_name: str, func: Callable[..., Any], public: bool,
                 overload: int = 0) -> None:
        path = tuple(part.lower() for part in module_name.split("."))
        entry = ProcedureEntry(path, proc_name, f"{module_name}.{proc_name}", func, public, overload)
        key = proc_name.lower()
        with self._lock:
            entries = [e for e in self._by_name.get(key, ()) if (e.path, e.overload) != (path, overload)]
            entries.append(entry)
            self._by_name[key] = entries
            self._qualifiers.update(path)

    def clear(self) -> None:
        with self._lock:
            self._by_name.clear()
            self._qualifiers.clear()

    def entries(self) -> list[ProcedureEntry]:
        """All entries, sorted by qualified name."""
        with self._lock:
            return sorted((e for es in self._by_name.values() for e in es), key=lambda e: e.qualified_name.lower())

    def find(self, name: str, module: str | None = None, nargs: int | None = None) -> ProcedureEntry:
        """The entry for ``name`` as seen from ``module`` (rules in the module docstring);
        ``nargs``: how many arguments the caller passes, which chooses among overloads."""
        parts = [p.strip().lower() for p in name.strip().split(".")]
        if not parts or not all(parts):
            raise GplException(UNDEFINED_SYMBOL, detail=f"invalid procedure name {name!r}")
        proc, qual = parts[-1], tuple(parts[:-1])
        caller = tuple(p.lower() for p in module.split(".")) if module else None
        candidates = self._by_name.get(proc, [])

        if not qual:
            if caller is not None:
                own = [e for e in candidates if e.path == caller]
                if own:
                    return choose_overload(own, nargs, name)
            public = [e for e in candidates if e.public and len(e.path) == 1]
            if len({e.path for e in public}) == 1:
                return choose_overload(public, nargs, name)
            if len(public) > 1:
                where = ", ".join(sorted({e.qualified_name for e in public}))
                raise GplException(AMBIGUOUS_PUBLIC_REFERENCE, detail=f"{name!r} could be {where}")
            private = [e.qualified_name for e in candidates]
            hint = f" (Private: {', '.join(sorted(private))})" if private else ""
            raise GplException(UNDEFINED_SYMBOL, detail=f"no Public procedure {name!r}{hint}")

        matches = [e for e in candidates if e.path[-len(qual):] == qual]
        if not matches:
            if not all(q in self._qualifiers for q in qual):
                raise GplException(NO_MODULE_DEFINED, detail=f"no module or class {'.'.join(qual)!r} for {name!r}")
            raise GplException(UNDEFINED_SYMBOL, detail=f"no procedure {name!r}")
        allowed = [e for e in matches if e.public or (caller is not None and e.path[: len(caller)] == caller)]
        if len({e.path for e in allowed}) == 1:
            return choose_overload(allowed, nargs, name)
        if not allowed:
            raise GplException(UNDEFINED_SYMBOL, detail=f"{matches[0].qualified_name} is Private")
        where = ", ".join(sorted({e.qualified_name for e in allowed}))
        raise GplException(AMBIGUOUS_PUBLIC_REFERENCE, detail=f"{name!r} could be {where}")

    def __len__(self) -> int:
        return sum(len(es) for es in self._by_name.values())


def choose_overload(entries: list[ProcedureEntry], nargs: int | None, name: str) -> ProcedureEntry:
    """The one entry of ``entries`` (the overloads of one procedure) a caller passing ``nargs``
    arguments means (module docstring, "Overloads"); ``name`` is for the error's text."""
    if len(entries) == 1:
        return entries[0]
    fits = entries if nargs is None else [e for e in entries if e.accepts(nargs)]
    if len(fits) == 1:
        return fits[0]
    if not fits:
        raise GplException(ARGUMENT_MISMATCH, detail=f"no overload of {name!r} takes {nargs} argument(s)")
    how = "" if nargs is None else f" with {nargs} argument(s)"
    raise GplException(AMBIGUOUS_PUBLIC_REFERENCE,
                       detail=f"{name!r} has {len(fits)} overloads that can be called{how}")


def _arity(func: Callable[..., Any]) -> tuple[int, float]:
    """(required, maximum) positional arguments of ``func`` (through ``gpl_entry``'s wrapper)."""
    try:
        params = inspect.signature(func).parameters.values()
    except (TypeError, ValueError):
        return 0, math.inf
    low, high = 0, 0.0
    for p in params:
        if p.kind is p.VAR_POSITIONAL:
            high = math.inf
        elif p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD):
            high += 1
            low += p.default is p.empty
    return low, high


_default = ProcedureRegistry()
_packages: dict[str, ProcedureRegistry] = {}
_packages_lock = threading.Lock()


def registry_for(package: str | None) -> ProcedureRegistry:
    """The registry of generated package ``package`` (created on first use); the default,
    process-wide registry for ``None``."""
    if not package:
        return _default
    reg = _packages.get(package)
    if reg is None:
        with _packages_lock:
            reg = _packages.setdefault(package, ProcedureRegistry())
    return reg


def default_registry() -> ProcedureRegistry:
    """The process-wide registry of hand-written Python (a new session's, until a package's
    ``init()`` gives it its own)."""
    return _default


def use_procedures(sim: Session, package: str) -> None:
    """Make ``package``'s registry the one that names resolve in for ``sim`` (its ``init()``); on a
    thread of a project the console loaded (``gplrt.session.ProjectScope``), for that project only,
    so that the projects in one controller's memory never resolve in each other's registry."""
    scope = current_scope()
    if scope is not None:
        scope.procedures = registry_for(package)
    else:
        sim.procedures = registry_for(package)


def register_procedure(
    module_name: str, proc_name: str, func: Callable[..., Any], *, public: bool = True,
    overload: int = 0, package: str | None = None,
) -> Callable[..., Any]:
    """Register ``func`` as ``module_name.proc_name``; returns ``func`` (usable as a decorator
    helper).  ``public`` is the GPL access level (module members are Private by default in GPL,
    but the lowering always passes it explicitly).  ``package``: the generated package whose
    registry receives it (generated code passes ``__package__``); None: the default registry."""
    registry_for(package).register(module_name, proc_name, func, public, overload)
    return func


def clear_procedures() -> None:
    """Forget every registration of the default registry (tests, or a fresh session)."""
    _default.clear()


def registered_procedures(package: str | None = None) -> list[ProcedureEntry]:
    """All entries of ``package``'s registry (default: the process-wide one), sorted by qualified
    name (diagnostics and tooling)."""
    return registry_for(package).entries()


def find_procedure_entry(name: str, module: str | None = None, nargs: int | None = None) -> ProcedureEntry:
    """Like ``find_procedure`` but returns the registry entry (name, access, qualifier)."""
    scope = current_scope()
    active = scope.procedures if scope is not None and scope.procedures is not None else current_session().procedures
    if active is _default:
        return _default.find(name, module, nargs)
    try:
        return active.find(name, module, nargs)
    except GplException as exc:
        if exc.ErrorCode in (UNDEFINED_SYMBOL, NO_MODULE_DEFINED) and len(_default):
            try:  # hand-written Python registered next to the project
                return _default.find(name, module, nargs)
            except GplException:
                pass
        raise


def find_procedure(name: str, module: str | None = None, nargs: int | None = None) -> Callable[..., Any]:
    """The procedure called ``name`` (``"Proc"`` or ``"Module.Proc"``), looked up as seen from
    procedures of ``module`` (``None``: from outside any module), in the registry of the running
    simulation's project; ``nargs`` (the arguments the caller will pass) chooses among
    overloads.  Raises GplException -729, -741, -772 or -798 as described in the module
    docstring."""
    return find_procedure_entry(name, module, nargs).func

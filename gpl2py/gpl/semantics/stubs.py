"""Stubs: names the readable sources use but do not define (issue "Porting real projects", part 1).

Real projects are never clean.  Two kinds of names cannot be resolved, and both become *stubs*,
stand-ins that the generated package defines and that raise GPL error -204 *Not implemented* only
if the program actually uses them, so the other 99 % of the project runs:

* **protected names** — in a project with vendor-protected ``.gpp`` files (skipped by the loader),
  a name declared nowhere readable is assumed to live in the protected code: ``Foo(1)``,
  ``SomeModule.Proc(x)``, ``SomeModule.var``, ``New VendorThing``, ``Dim v As VendorThing``.
  Decision: in a project *without* protected files an unknown name stays error GPL2001 (a typo is far
  likelier than missing code there).
* **unknown built-in members** — ``Controller.SomethingUnknown(...)``, ``Robot.NoSuchMember``: always
  a warning and a stub (the member may exist on a newer controller, or is not simulated).

Each stub is reported once (GPL3501 / GPL3502, errors with ``--strict``).  Types are unknown, so a
stub's value has the permissive type ANY: it accepts every use, and the lowering converts it at run
time wherever a typed value is needed.

How a protected name is used decides what its stub is (convention, documented in README "Porting"):
used with parentheses or as a statement -> a *procedure* (``Foo(1)`` may also be an array element in
the protected code; a user stub may implement it as a function of the subscripts); used only as a
value or assignment target without parentheses -> a *variable*; named as a type or with ``New`` ->
a *class*.  The qualifier of an unknown ``Module.Name`` is a *stub module*.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from gpl2py import messages as M
from gpl2py.diagnostics import Diagnostic, DiagnosticSink, Severity
from gpl2py.source import Span


@dataclass(eq=False)
class Stub:
    """One stand-in.  ``name`` is the GPL name as first written (``SomeModule.Proc``, ``Foo``,
    ``Controller.SomethingUnknown``); ``module`` the unknown module's name for ``Module.Name``;
    ``builtin`` the built-in class for an unknown built-in member (``shared``: reached through the
    class, not an object)."""

    name: str
    member: str
    module: str | None = None
    builtin: str | None = None
    shared: bool = False
    span: Span | None = None
    called: bool = False
    created: bool = False  # New X / As X: a class
    assigned: bool = False

    @property
    def kind(self) -> str:
        """``procedure``, ``variable``, ``class`` or ``member`` (of a built-in class)."""
        if self.builtin is not None:
            return "member"
        if self.created:
            return "class"
        return "procedure" if self.called else "variable"


@dataclass
class StubTable:
    """Every stub of a project, keyed by lower-cased GPL name; reports each one once."""

    sink: DiagnosticSink
    protected: bool = False  # the project has protected files: unknown names become stubs
    strict: bool = False  # report stubs as errors
    stubs: dict[str, Stub] = field(default_factory=dict)
    modules: dict[str, str] = field(default_factory=dict)  # lower -> declared spelling
    # Who implements a stub, if anyone: "the stand-in vendorlib.py" (a --stubs file or one gpl2py
    # ships); None when the generated stub raises -204.  The warning says which.
    provider: Callable[[Stub], str | None] | None = None
    # how many times a stub was looked up or made: whether checking a part of the project touched
    # the table, which then depends on the order everything was checked in (semantics/warm.py)
    uses: int = 0

    def _consequence(self, stub: Stub) -> str:
        """What becomes of the stub, as the warning (or, with ``strict``, the error) says it."""
        found = self.provider(stub) if self.provider is not None else None
        if found is not None:
            return (M.STUB_IMPLEMENTED_STRICT if self.strict else M.STUB_IMPLEMENTED).format(provider=found)
        return M.STUB_STRICT if self.strict else M.STUB_RAISES

    def _report(self, message: M.Message, span: Span | None, **args: object) -> None:
        if self.strict:
            text = message.format(**args)
            self.sink.add(Diagnostic(Severity.ERROR, message.code, text, span))
        else:
            self.sink.report(message, span, **args)

    def protected_name(self, name: str, span: Span | None, module: str | None = None) -> Stub:
        """The stub for ``name`` (or ``module.name``) from protected code."""
        self.uses += 1
        if module is not None:
            module = self.modules.setdefault(module.lower(), module)
        full = f"{module}.{name}" if module else name
        key = full.lower()
        stub = self.stubs.get(key)
        if stub is None:
            stub = Stub(full, name, module=module, span=span)
            self.stubs[key] = stub
            self._report(M.STUB_PROTECTED, span, name=full, consequence=self._consequence(stub))
        return stub

    def builtin_member(self, owner: str, member: str, span: Span | None, shared: bool) -> Stub:
        """The stub for a member that the runtime's built-in class ``owner`` lacks."""
        self.uses += 1
        full = f"{owner}.{member}"
        key = full.lower()
        stub = self.stubs.get(key)
        if stub is None:
            stub = Stub(full, member, builtin=owner, shared=shared, span=span)
            self.stubs[key] = stub
            self._report(M.STUB_BUILTIN_MEMBER, span, owner=owner, member=member,
                         consequence=self._consequence(stub))
        return stub

    def ordered(self) -> list[Stub]:
        return sorted(self.stubs.values(), key=lambda s: s.name.lower())


__all__ = ["Stub", "StubTable"]

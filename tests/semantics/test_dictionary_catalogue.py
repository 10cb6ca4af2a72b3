"""Every member of the GPL Dictionary is in the catalogue the transpiler reads, with its signature.

``tests/gpldictionary.py`` reads the member tables of ``shared/spec/gpl-dictionary.md``; each
member becomes one test that holds the runtime's catalogue (``gplrt.builtins`` as
``gpl2py.gpl.semantics.catalogue`` reads it) against it: the member exists on its class, is Shared
when the Dictionary says so, can be read and assigned as listed, and accepts every argument count
the Dictionary's signature allows.  The catalogue may accept more (real code calls some members
with arguments the Dictionary does not list; docs/design/real-code.md), never less.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from gpldictionary import DictMember, read_dictionary
from gpltest import find_shared, spec_dir

from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.catalogue import BuiltinClass, Catalogue, Member, load_catalogue


def _dictionary() -> list[DictMember | None]:
    """One parameter per member of the Dictionary; without the spec one None, whose test skips
    (fails under CI) naming ``GPL_SPEC``: collection itself must never need the spec."""
    spec = find_shared("spec", "GPL_SPEC")
    return [None] if spec is None else list(read_dictionary(spec / "gpl-dictionary.md"))


MEMBERS = _dictionary()


def _covers(accepted: tuple[int, int], listed: tuple[int, int] | None) -> bool:
    return listed is None or (accepted[0] <= listed[0] and accepted[1] >= listed[1])


def _owner(cat: Catalogue, name: str) -> BuiltinClass | None:
    return cat.lookup_class(name) or cat.type_members.get(name.lower())


def test_the_dictionary_is_read() -> None:
    """The reader finds every table (a format change must not pass by finding nothing)."""
    members = read_dictionary(spec_dir() / "gpl-dictionary.md")
    owners = {m.owner for m in members if m.kind == "member"}
    assert len(members) >= 330, len(members)
    assert owners >= {"Location", "RefFrame", "Profile", "Move", "Robot", "Controller", "Thread",
                      "Exception", "Signal", "Latch", "String", "Math", "Array", "Console", "File",
                      "StreamReader", "StreamWriter", "IPEndPoint", "Socket", "TcpClient", "UdpClient",
                      "TcpListener", "Modbus", "Vision", "VisResult", "XmlDoc", "XmlNode"}
    trigger = next(m for m in members if m.label == "Move.Trigger")
    assert trigger.shared and trigger.read_args == (3, 3)
    pdb = next(m for m in members if m.label == "Controller.PDb")
    assert pdb.get and pdb.set and pdb.read_args == (1, 4) and pdb.set_args == (1, 5)


def _member_problems(cat: Catalogue, dm: DictMember) -> list[str]:
    b = _owner(cat, dm.owner)
    if b is None:
        return [f"class {dm.owner} is not in the catalogue"]
    m: Member | None = b.member(dm.name)
    if m is None:
        return [f"{dm.label} is not in the catalogue"]
    problems = []
    shared = m.shared or b.is_global
    if dm.shared != shared:
        problems.append(f"Shared is {shared}, the Dictionary says {dm.shared}")
    if dm.get and m.result is t.VOID:
        problems.append("cannot be read (no result)")
    if not _covers((m.min_args, m.max_args), dm.read_args):
        problems.append(f"takes {m.min_args}..{m.max_args} arguments, the Dictionary {dm.read_args}")
    if dm.set and not m.settable:
        problems.append("cannot be assigned")
    elif dm.set and not _covers((m.set_min_args, m.set_max_args), dm.set_args):
        problems.append(f"is assigned with {m.set_min_args}..{m.set_max_args} arguments, "
                        f"the Dictionary {dm.set_args}")
    return problems


def _problems(cat: Catalogue, dm: DictMember) -> list[str]:
    if dm.kind == "constant":
        c = cat.lookup_constant(dm.name)
        return [] if c is not None and c.value == dm.value else [f"constant {dm.name} = {dm.value} missing"]
    if dm.kind == "function":
        f = cat.lookup_function(dm.name)
        if f is None:
            return [f"function {dm.name} is not in the catalogue"]
        lo = sum(1 for p in f.params if not p.optional)
        return [] if _covers((lo, len(f.params)), dm.read_args) else [
            f"takes {lo}..{len(f.params)} arguments, the Dictionary {dm.read_args}"]
    if dm.kind == "ctor":
        b = cat.lookup_class(dm.owner)
        if b is None or b.is_global or b.constructor is None:
            return [f"New {dm.owner} is not in the catalogue"]
        lo = sum(1 for p in b.constructor if not p.optional)
        return [] if _covers((lo, len(b.constructor)), dm.read_args) else [
            f"New takes {lo}..{len(b.constructor)} arguments, the Dictionary {dm.read_args}"]
    return _member_problems(cat, dm)


@pytest.mark.parametrize("dm", MEMBERS, ids=[f"{m.label}@{m.line}" if m else "no-spec" for m in MEMBERS])
def test_dictionary_member_is_in_the_catalogue(dm: DictMember | None) -> None:
    if dm is None:
        spec_dir()  # skips, naming GPL_SPEC
        return
    problems = _problems(load_catalogue(), dm)
    assert not problems, f"gpl-dictionary.md:{dm.line} {dm.label}: " + "; ".join(problems)

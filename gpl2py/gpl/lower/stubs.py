"""The generated stub modules (see semantics/stubs.py for when a stub is made).

``_stubs.py`` holds bare protected names and unknown built-in members; one ``<module>.py`` per
unknown module holds its members.  A stub raises GPL error -204 *Not implemented* (Catch sees
``ErrorCode = -204``) only when used: procedure and member stubs when called, class stubs when
created, variable stubs when read before the program stored a value (module ``__getattr__``).
Code -204 rather than -729 *Undefined symbol*: the name is defined, in code that exists on the
controller, but the simulation cannot run it.  A user implementation (``--stubs DIR``) is imported
in place of the stand-in.
"""

from __future__ import annotations

from gpl2py.gpl.lower.stub_names import STUBS_MODULE, stub_module_name
from gpl2py.pywriter.text import escape, py_string
from gpl2py.gpl.lower.user_stubs import UserFile, UserStubs
from gpl2py.gpl.semantics.stubs import Stub, StubTable


def stub_files(table: StubTable, stub_module_py: dict[str, str], stub_attr_py: dict[Stub, str], package: str,
               user: UserStubs | None) -> tuple[dict[str, str], list[dict[str, object]]]:
    """The stub modules and user files (package-relative paths -> text) and the PROJECT["stubs"]
    records (name, kind, provided).  ``stub_module_py`` and ``stub_attr_py`` are the names
    ``ProjectNames`` gave the stub modules and the stubs."""
    by_module: dict[str, list[Stub]] = {}
    for stub in table.ordered():
        by_module.setdefault(stub_module_name(stub, stub_module_py), []).append(stub)
    files: dict[str, str] = {}
    records: list[dict[str, object]] = []
    used_files: dict[str, UserFile] = {}
    for module, stubs in sorted(by_module.items()):
        text, recs = _module_text(module, stubs, stub_attr_py, user, used_files)
        files[f"{package}/{module}.py"] = text
        records.extend(recs)
    for name, uf in sorted(used_files.items()):
        files[f"{package}/{name}.py"] = uf.text
    records.sort(key=lambda r: str(r["name"]).lower())
    return files, records


def _module_text(module: str, stubs: list[Stub], attrs: dict[Stub, str], user: UserStubs | None,
                 used_files: dict[str, UserFile]) -> tuple[str, list[dict[str, object]]]:
    if module == STUBS_MODULE:
        doc = ("Stubs for names the program uses but gpl2py could not translate: names defined in\n"
               "protected (.gpp) files, and members of built-in classes that the simulated controller lacks.")
    else:
        gpl = stubs[0].module or module
        doc = (f"Stubs for Module {escape(gpl, 'docstring')}: its source is protected (.gpp),\n"
               "gpl2py could not translate it.")
    head = [
        f'"""{doc}',
        "",
        "Each stand-in raises GPL error -204 (Not implemented) only when the program uses it. Supply a",
        "Python implementation with gpl2py --stubs DIR (README, \"Porting your own project\").",
        '"""',
        "",
    ]
    imports: list[str] = []
    defs: list[str] = []
    variables: list[tuple[str, str]] = []
    records: list[dict[str, object]] = []
    needs_helper = False
    supplied: set[str] = set()
    shipped: set[str] = set()

    def user_has(stub: Stub) -> bool:
        return user is not None and user.find(stub) is not None

    for stub in stubs:
        attr = attrs[stub]
        found = user.find(stub) if user is not None else None
        records.append({"name": stub.name, "kind": stub.kind, "provided": found is not None,
                        "standin": found is not None and found[0].shipped})
        if found is not None:
            uf, spelled = found
            used_files[uf.package_module] = uf
            (shipped if uf.shipped else supplied).add(uf.path.name)
            alias = spelled if spelled == attr else f"{spelled} as {attr}"
            imports.append(f"from .{uf.package_module} import {alias}")
        else:
            needs_helper = True
            defs.extend(_stand_in(stub, attr))
        if stub.builtin is not None and stub.assigned:
            setter = user.find(stub, setter=True) if user is not None else None
            if setter is not None:
                uf, spelled = setter
                used_files[uf.package_module] = uf
                (shipped if uf.shipped else supplied).add(uf.path.name)
                imports.append(f"from .{uf.package_module} import {spelled} as set_{attr}")
            else:
                needs_helper = True
                defs.extend(["", "", f"def set_{attr}(*args: object) -> None:",
                             f'    """Assigning {escape(stub.name, "docstring")}: not simulated, raises -204."""',
                             f"    not_available({py_string(stub.name)}, builtin=True)"])
        if stub.kind == "variable" and found is None:
            variables.append((attr, stub.name))
    lines = list(head)
    if needs_helper:
        lines.append("from gplrt.lang.exceptions import not_available")
    if imports:
        if needs_helper:
            lines.append("")
        if supplied:
            lines.append("# supplied with --stubs: " + ", ".join(sorted(supplied)))
        if shipped:
            lines.append("# gpl2py's own stand-ins (gpl2py/gpl/standins): " + ", ".join(sorted(shipped)))
        lines.extend(sorted(imports))
    exported = sorted({attrs[st] for st in stubs if st.kind != "variable" or user_has(st)}
                      | {f"set_{attrs[st]}" for st in stubs if st.builtin is not None and st.assigned})
    lines += ["", "__all__ = [" + ", ".join(py_string(n) for n in exported) + "]"]
    lines.extend(defs)
    if variables:
        entries = ", ".join(f"{py_string(a)}: {py_string(n)}" for a, n in variables)
        lines += [
            "", "",
            "# variables of the protected code: reading one before the program stores it raises -204",
            f"_VARIABLES = {{{entries}}}",
            "", "",
            "def __getattr__(name: str) -> object:",
            "    if name in _VARIABLES:",
            "        not_available(_VARIABLES[name])",
            "    raise AttributeError(name)",
        ]
    lines += [
        "", "",
        "def _reset() -> None:",
        '    """A new session forgets the values the program stored in stub variables."""',
    ]
    if variables:
        lines += ["    for name in _VARIABLES:", "        globals().pop(name, None)"]
    else:
        lines.append("    return")
    return "\n".join(lines) + "\n", records


def _stand_in(stub: Stub, attr: str) -> list[str]:
    name = py_string(stub.name)
    if stub.kind == "variable":
        return []
    if stub.kind == "class":
        return ["", "", f"class {attr}:",
                f'    """{escape(stub.name, "docstring")} (protected source): creating one raises -204."""',
                "",
                "    def __init__(self, *args: object) -> None:",
                f"        not_available({name})"]
    if stub.kind == "member":
        how = "" if stub.shared else " (the object comes first)"
        return ["", "", f"def {attr}(*args: object) -> object:",
                f'    """{escape(stub.name, "docstring")}{how}: not in the simulated controller, raises -204."""',
                f"    return not_available({name}, builtin=True)"]
    return ["", "", f"def {attr}(*args: object) -> object:",
            f'    """{escape(stub.name, "docstring")} (protected source): raises -204."""',
            f"    return not_available({name})"]


__all__ = ["stub_files"]

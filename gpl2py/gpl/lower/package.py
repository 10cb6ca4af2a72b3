"""The package entry of a generated project: ``__init__.py`` and ``__main__.py`` (§12.2, §12.3).

Importing the package starts nothing.  ``init()`` initialises every module (variables, then each
module's ``Init``) once per simulation session; ``main()`` runs ``init()`` and ProjectStart on the
main GPL thread of a simulation.  A notebook does ``sim.call(pkg.init)`` and then calls any Public
procedure with ``sim.call(pkg.module.Proc, args...)``.
"""

from __future__ import annotations

from collections.abc import Callable

from gpl2py import __version__
from gpl2py.gpl.lower.names import py_ident
from gpl2py.pywriter.text import escape, py_string
from gpl2py.gpl.semantics.check import Model
from gpl2py.gpl.semantics.symbols import ClassSym, ModuleSym, ProcSym


def package_init(model: Model, project_name: str, start_text: str | None, modules: list[ModuleSym],
                 extra: list[ModuleSym], stubs: list[dict[str, object]] | None = None,
                 stub_modules: list[str] | None = None,
                 proc_name: Callable[[ProcSym], str] | None = None,
                 entries: dict[str, frozenset[str]] | None = None) -> str:
    """``stubs``: the PROJECT["stubs"] records (name, kind, provided by the user); ``stub_modules``:
    the generated stub modules, reset with the others for a new session; ``proc_name``: the
    Python name of a procedure (``ProjectNames.proc_name``: an overloaded Init or start
    procedure has a name of its own); ``entries``: which of ``_reset``/``_init`` each module
    (by Python name) defines (``lower_module``; by default both)."""
    if proc_name is None:
        def proc_name(p: ProcSym) -> str:
            return py_ident(p.name)
    all_mods = modules + extra
    start_name = "None"
    if model.start is not None and model.start.module is not None:
        start_name = py_string(f"{model.start.module.name}.{model.start.name}")
    stub_modules = sorted(stub_modules or [])
    imported = sorted([m.py_name for m in all_mods] + stub_modules)
    start = model.start
    has_start = start is not None and start.module is not None
    lines = [
        f'"""GPL project {escape(project_name, "docstring")}, transpiled by gpl2py {escape(__version__, "docstring")}.',
        "",
        "Importing this package starts nothing.  ``main()`` runs the project (ProjectStart) on a simulated",
        "controller; ``init()`` initialises the modules (variables in ProjectSource order, then each",
        "module's Init) once per simulation session, so a notebook can call any Public procedure after it.",
        '"""',
        "",
        *(["from gplrt.lang.exceptions import gpl_entry"] if has_start else []),
        "from gplrt.lang.procedures import use_procedures",
        "from gplrt.lang.sourcemap import register_package",
        "from gplrt.sim import Simulation, current" if has_start else "from gplrt.sim import current",
        "",
    ]
    if all_mods or stub_modules:
        text = f"from . import {', '.join(imported)}"
        lines.extend([text, ""] if len(text) <= 99 else ["from . import (", *(f"    {n}," for n in imported), ")", ""])
        # every module is imported for the procedures it registers (Thread("Proc"), delegates by
        # name), also one that init() has nothing to call in: the package's public names say so
        exported = [py_string(n) for n in ["PROJECT", *imported, "init", "main"]]
        text = f"__all__ = [{', '.join(exported)}]"
        lines.extend([text, ""] if len(text) <= 99 else ["__all__ = [", *(f"    {n}," for n in exported), "]", ""])
    lines += [
        "PROJECT = {",
        f"    \"name\": {py_string(project_name)},",
        f"    \"gpl2py\": {py_string(__version__)},  # the gpl2py that made this package",
        f"    \"start\": {py_string(start_text) if start_text else start_name},",
        *_modules_lines([py_string(m.name) for m in modules]),
        *_stub_lines(stubs or []),
        "}",
        "",
        "_session = None",
        "",
        "",
        "def init() -> None:",
        '    """Initialise every module once for the current simulation session (§12.2, AMB-16)."""',
        "    global _session",
        "    sim = current()",
        "    if _session is sim:",
        "        return",
        "    _session = sim",
        "    use_procedures(sim, __name__)  # Thread(\"Proc\") and delegates resolve in this project",
    ]
    for name in stub_modules:
        lines.append(f"    {name}._reset()")
    def defines(m: ModuleSym, entry: str) -> bool:
        return entries is None or entry in entries.get(m.py_name, ())

    lines += [f"    {m.py_name}._reset()" for m in extra + modules if defines(m, "_reset")]
    lines += [f"    {m.py_name}._init()" for m in extra + modules if defines(m, "_init")]
    for m in extra + modules:
        # the Shared Sub Init of each class (real code relies on it: docs/design/real-code.md),
        # before its module's Init, which may use the class
        for c in _classes(m):
            p = c.init_proc
            if p is not None:
                path = ".".join(py_ident(n) for n in c.path)
                lines.append(f"    {m.py_name}.{path}.{proc_name(p)}()")
        if m in modules and m.init_proc is not None:
            lines.append(f"    {m.py_name}.{proc_name(m.init_proc)}()")
    # without a start procedure there is no Simulation import to annotate with
    sim_type = "Simulation | None" if has_start else "object"
    lines += [
        "",
        "",
        f"def main(sim: {sim_type} = None) -> int:",
        '    """Run ProjectStart on the main GPL thread; 1 if any thread ended with an unhandled error."""',
    ]
    if not has_start:
        # no start procedure: say so before any thread starts (``python -m`` prints it, status 1)
        lines.append(f"    raise SystemExit({py_string(_NO_START.format(project=project_name))})")
    else:
        assert start is not None and start.module is not None
        thread = start.name
        lines += [
            "    if sim is None:",
            f"        sim = Simulation(project={py_string(project_name)})",
            "",
            "    def _start() -> None:",
            "        init()",
            f"        {start.module.py_name}.{proc_name(start)}()",
            "",
            f"    _start.__gpl_name__ = {py_string(thread)}  # type: ignore[attr-defined]",
            f"    sim.run_main(gpl_entry(_start), name={py_string(thread)})",
            "    return 1 if sim.controller.error_log else 0",
        ]
    lines += [
        "",
        "",
        "register_package(__file__)",
    ]
    return "\n".join(lines) + "\n"


def _classes(m: ModuleSym) -> list[ClassSym]:
    """The classes of module ``m`` and the classes nested in them, in declaration order."""
    out: list[ClassSym] = []
    for member in m.members.values():
        if isinstance(member, ClassSym):
            out.extend(member.classes())
    return out


_NO_START = ("GPL project {project} has no start procedure: Project.gpr names no ProjectStart and the "
             "project has no single Public Sub Main; call its procedures from Python instead")


def _modules_lines(names: list[str]) -> list[str]:
    """PROJECT["modules"] in ProjectSource order: one line when it fits PEP 8's 99 columns, else
    one name per line."""
    one = f'    "modules": [{", ".join(names)}],'
    if len(one) <= 99:
        return [one]
    return ['    "modules": [', *(f"        {n}," for n in names), "    ],"]


def _stub_lines(stubs: list[dict[str, object]]) -> list[str]:
    """PROJECT["stubs"]: one record per stub; ``gpl2py run`` prints them in a note."""
    if not stubs:
        return ['    "stubs": [],']
    out = ['    "stubs": [']
    for r in stubs:
        fields = [f'"name": {py_string(str(r["name"]))}', f'"kind": {py_string(str(r["kind"]))}',
                  f'"provided": {bool(r["provided"])}', f'"standin": {bool(r.get("standin"))}']
        line = f"        {{{', '.join(fields)}}},"
        if len(line) <= 99:
            out.append(line)
        else:  # one field a line
            out.extend(["        {", *(f"            {f}," for f in fields), "        },"])
    out.append("    ],")
    return out


def package_main() -> str:
    """``python -m``: the project's own files (``_project_files/``, written next to the modules by
    ``gpl2py PROJECT -o OUT``) go to its controller folder first, as ``gpl2py run`` does."""
    return (
        '"""``python -m <package>``: run the project on a simulated controller."""\n'
        "\n"
        "from pathlib import Path\n"
        "\n"
        "from gplrt.sim import Simulation\n"
        "\n"
        "from . import PROJECT, main\n"
        "\n"
        'sim = Simulation(project=PROJECT["name"])\n'
        'sim.install_project_files(Path(__file__).parent / "_project_files")\n'
        "raise SystemExit(main(sim))\n"
    )

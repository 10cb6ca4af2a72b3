"""The package entry of a generated project: ``__init__.py`` and ``__main__.py`` (§12.2, §12.3).

Importing the package starts nothing.  ``init()`` initialises every module (variables, then each
module's ``Init``) once per simulation session; ``main()`` runs ``init()`` and ProjectStart on the
main GPL thread of a simulation.  A notebook does ``sim.call(pkg.init)`` and then calls any Public
procedure with ``sim.call(pkg.module.Proc, args...)``.
"""

from __future__ import annotations

from gpl2py.lower.names import py_ident, py_string
from gpl2py.semantics.check import Model
from gpl2py.semantics.symbols import ModuleSym


def package_init(model: Model, project_name: str, start_text: str | None, modules: list[ModuleSym],
                 extra: list[ModuleSym]) -> str:
    all_mods = modules + extra
    names = ", ".join(sorted(m.py_name for m in all_mods))
    start = model.start
    lines = [
        f'"""GPL project {project_name}, transpiled by gpl2py.',
        "",
        "Importing this package starts nothing.  ``main()`` runs the project (ProjectStart) on a simulated",
        "controller; ``init()`` initialises the modules (variables in ProjectSource order, then each",
        "module's Init) once per simulation session, so a notebook can call any Public procedure after it.",
        '"""',
        "",
        "from gplrt.lang.exceptions import gpl_entry",
        "from gplrt.lang.sourcemap import register_package",
        "from gplrt.sim import Simulation, current",
        "",
    ]
    if all_mods:
        lines.append(f"from . import {names}")
        lines.append("")
    lines += [
        "PROJECT = {",
        f"    \"name\": {py_string(project_name)},",
        f"    \"start\": {py_string(start_text) if start_text else 'None'},",
        f"    \"modules\": [{', '.join(py_string(m.name) for m in modules)}],",
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
    ]
    for m in extra + modules:
        lines.append(f"    {m.py_name}._reset()")
    for m in extra + modules:
        lines.append(f"    {m.py_name}._init()")
    for m in modules:
        if m.init_proc is not None:
            lines.append(f"    {m.py_name}.{py_ident(m.init_proc.name)}()")
    lines += [
        "",
        "",
        "def main(sim: Simulation | None = None) -> int:",
        '    """Run ProjectStart on the main GPL thread; 1 if any thread ended with an unhandled error."""',
        "    if sim is None:",
        f"        sim = Simulation(project={py_string(project_name)})",
        "",
        "    def _start() -> None:",
        "        init()",
    ]
    if start is not None and start.module is not None:
        lines.append(f"        {start.module.py_name}.{py_ident(start.name)}()")
    else:
        lines.append("        raise SystemExit(\"this project has no ProjectStart procedure\")")
    thread = start.name if start is not None else "Main"
    lines += [
        "",
        f"    _start.__gpl_name__ = {py_string(thread)}  # type: ignore[attr-defined]",
        f"    sim.run_main(gpl_entry(_start), name={py_string(thread)})",
        "    return 1 if sim.controller.error_log else 0",
        "",
        "",
        "register_package(__file__)",
    ]
    return "\n".join(lines) + "\n"


def package_main() -> str:
    return (
        '"""``python -m <package>``: run the project on a simulated controller."""\n'
        "\n"
        "from . import main\n"
        "\n"
        "raise SystemExit(main())\n"
    )

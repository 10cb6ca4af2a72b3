"""A V+ project -> the generated package: one Python module per V+ file, ``__init__.py`` and
``__main__.py``, and the source map.

Each module holds its file's programs (:mod:`gpl2py.vplus.lower.program`) and ``_data()``, which
loads the file's data sections into the session's globals as V+'s LOAD does.  The package's
``main(sim)`` runs the start program as task 0 (``--start``, else the first program of the first
file) after ``init()`` has loaded every file's data, once per session; ``PROJECT`` names the
language and the start program, as a GPL package's does.
"""

from __future__ import annotations

from pathlib import Path

from gpl2py import __version__
from gpl2py.diagnostics import DiagnosticSink, contained
from gpl2py.output import Output
from gpl2py.project import Project
from gpl2py.pywriter.emit import Writer
from gpl2py.pywriter.sourcemap import runs_json, sourcemap_json
from gpl2py.pywriter.text import escape, py_string
from gpl2py.vplus.lower.expressions import number
from gpl2py.vplus.lower.names import Names, py_name
from gpl2py.vplus.lower.program import ProgramLowerer, _has_goto
from gpl2py.vplus.semantics.check import Model, ProgramInfo
from gpl2py.vplus.syntax import ast as A

_GOTO_CLASS = [
    "class _GoTo(Exception):",
    '    """A V+ GOTO to a step label (the program\'s dispatch loop catches it and goes on there)."""',
    "",
    "    def __init__(self, label: int) -> None:",
    "        super().__init__(label)",
    "        self.label = label",
]


def lower_project(project: Project, modules: list[A.Module], model: Model, sink: DiagnosticSink,
                  keep_modules: bool = True) -> Output:
    """The generated files of an analysed V+ project."""
    package = "vp_" + py_name("", project.name) if not project.name[:1].isalpha() else py_name("", project.name)
    out = Output(package, project=project)
    mod_names = Names(_PACKAGE_NAMES)
    module_of: dict[str, str] = {}
    for mod in modules:
        module_of[mod.path] = mod_names.name(mod.path, "", _module_stem(Path(mod.path).stem))
    program_module: dict[str, str] = {}  # program key -> its module
    function: dict[str, str] = {}  # program key -> its function's name
    fn_names: dict[str, Names] = {m: Names({"vp", "_data", "_GoTo"}) for m in module_of.values()}
    for key, info in model.programs.items():
        m = module_of[info.path]
        program_module[key] = m
        function[key] = fn_names[m].name(key, "", info.program.name)
    smap: dict[str, tuple[str, str]] = {}
    reactions = _reactions(model)
    for mod in modules:
        m = module_of[mod.path]
        with contained(sink, _file_span(mod.path)):
            text, gmap = _module_text(mod, m, model, program_module, function, sink, reactions)
            if keep_modules:
                out.files[f"{package}/{m}.py"] = text
                smap[f"{m}.py"] = (mod.path, runs_json(gmap))
    out.files[f"{package}/__init__.py"] = _package_init(project, model, module_of, program_module, function)
    out.files[f"{package}/__main__.py"] = _package_main()
    out.files[f"{package}/_sourcemap.json"] = sourcemap_json(smap)
    return out


#: The names of the package's ``__init__`` and its files, which no module of a V+ file may take:
#: a file ``__init__.v2`` or ``__main__.pg`` overwrote the package's own, and ``current.v2`` hid
#: the function ``init()`` calls.
_PACKAGE_NAMES = frozenset({"vp", "main", "init", "PROJECT", "__init__", "__main__", "_sourcemap", "register_package",
                            "Simulation", "current", "start_program", "_session"})


def _module_stem(stem: str) -> str:
    """The name a V+ file's module is made from: its stem, with ``m_`` before one that would
    make no module name (``1st.v2``) or a dunder (``__main__.pg``, ``__builtins__.v2``)."""
    base = py_name("", stem.replace(".", "_") or "module")
    return "m_" + stem if base[:1].isdigit() or base.startswith("__") else stem.replace(".", "_") or "module"


def _file_span(path: str):  # type: ignore[no-untyped-def]
    from gpl2py.source import make_span

    return make_span(path, 1, 1, 1, 1)


def _module_text(mod: A.Module, m: str, model: Model, program_module: dict[str, str], function: dict[str, str],
                 sink: DiagnosticSink, reactions: frozenset[str]) -> tuple[str, list[int]]:
    w = Writer()
    mine = [info for info in model.programs.values() if info.path == mod.path]
    others = sorted({program_module[k] for info in mine for k in _called(info) if program_module.get(k, m) != m})
    w.line(f'"""V+ file {escape(Path(mod.path).name, "docstring")}, transpiled by gpl2py {escape(__version__, "docstring")}."""', 0)
    w.blank()
    w.line("from __future__ import annotations", 0)
    w.blank()
    w.line("from gplrt import vplus as vp", 0)
    if others:
        w.line(f"from . import {', '.join(others)}", 0)
    if mod.comments:  # (the comments outside every program)
        w.blank(2)
        w.comments(mod.comments)
    if any(_has_goto(info.program.body) for info in mine):
        w.blank(2)
        for ln in _GOTO_CLASS:
            w.line(ln, 0)
    calls = {k: (function[k] if program_module[k] == m else f"{program_module[k]}.{function[k]}") for k in function}
    for info in mine:
        w.blank(2)
        with contained(sink, info.program.span):
            w.extend(ProgramLowerer(model, info, calls, sink, reactions).lower())
    w.blank(2)
    _data_function(w, mod, model)
    return w.render()


def _reactions(model: Model) -> frozenset[str]:
    """Which of REACT, REACTI and REACTE the project uses (the lowering adds what they need)."""
    from gpl2py.vplus.semantics.check import blocks

    found: set[str] = set()

    def walk(body: list[A.Stmt]) -> None:
        for s in body:
            if isinstance(s, A.React):
                found.add(s.word)
            for b in blocks(s):
                walk(b)
    for info in model.programs.values():
        walk(info.program.body)
    return frozenset(found)


def _called(info: ProgramInfo) -> set[str]:
    """The programs ``info`` calls, executes or arms as reactions (their V+ keys)."""
    from gpl2py.vplus.semantics.check import blocks

    found: set[str] = set()

    def walk(body: list[A.Stmt]) -> None:
        for s in body:
            if isinstance(s, A.CallStmt) and s.dynamic is None:
                found.add(A.key("", s.name))
            elif isinstance(s, A.Execute | A.React) and s.program:
                found.add(A.key("", s.program))
            for b in blocks(s):
                walk(b)
    walk(info.program.body)
    return found


def _data_function(w: Writer, mod: A.Module, model: Model) -> None:
    """``_data()``: the file's .LOCATIONS, .REALS, .DOUBLES and .STRINGS values into the globals."""
    w.line("def _data() -> None:", 0)
    w.indent()
    w.line('"""The data sections of this file, loaded into the session\'s globals (V+ LOAD)."""')
    for section in mod.data:
        for d in section.data:
            w.gpl_line = d.span.line
            if section.kind == "STRINGS":
                value = py_string(d.text or "")
            elif section.kind == "LOCATIONS" and d.var.sigil == "#":
                value = f"vp.p_ppoint({', '.join(number(v) for v in d.values)})"
            elif section.kind == "LOCATIONS":
                value = f"vp.trans({', '.join(number(v) for v in d.values)})"
            else:
                value = number(d.values[0])
            name = py_string(d.var.shown)
            if d.var.index is not None:
                index = ", ".join(number(i.value) if isinstance(i, A.Num) else "0" for i in d.var.index)
                w.line(f"vp.G.array({name})[{index}] = {value}")
            else:
                w.line(f"vp.G[{name}].v = {value}")
    w.gpl_line = 0
    w.line("return")
    w.dedent()


def _package_init(project: Project, model: Model, module_of: dict[str, str], program_module: dict[str, str],
                  function: dict[str, str]) -> str:
    start = model.start
    start_key = start.program.key if start is not None else None
    mods = list(module_of.values())
    lines = [
        f'"""V+ project {escape(project.name, "docstring")}, transpiled by gpl2py {escape(__version__, "docstring")}.',
        "",
        "Importing this package starts nothing.  ``main()`` runs the start program as V+ task 0 on a",
        "simulated controller; ``init()`` loads every file's data sections once per simulation session.",
        '"""',
        "",
        "from gplrt import vplus as vp",
        "from gplrt.lang.sourcemap import register_package",
        "from gplrt.sim import Simulation, current",
        "",
        f"from . import {', '.join(mods)}" if mods else "",
        "",
        f"__all__ = [{', '.join(py_string(n) for n in ['PROJECT', *mods, 'init', 'main', 'start_program'])}]",
        "",
        "PROJECT = {",
        f"    \"name\": {py_string(project.name)},",
        "    \"language\": \"vplus\",",
        f"    \"gpl2py\": {py_string(__version__)},  # the gpl2py that made this package",
        f"    \"start\": {py_string(start.program.name) if start is not None else 'None'},",
        f"    \"modules\": [{', '.join(py_string(m) for m in mods)}],",
        "}",
        "",
        "_session = None",
        "",
        "",
        "def init() -> None:",
        '    """Load every file\'s data sections once for the current simulation session."""',
        "    global _session",
        "    sim = current()",
        "    if _session is sim:",
        "        return",
        "    _session = sim",
        *[f"    {m}._data()" for m in mods],
        "",
        "",
        "def main(sim: Simulation | None = None) -> int:",
        '    """Run the start program as task 0; 1 if a task ended with an unhandled error."""',
    ]
    if start_key is None:
        lines.append(f"    raise SystemExit({py_string(f'V+ project {project.name} has no program to run')})")
    else:
        lines += [
            "    if sim is None:",
            f"        sim = Simulation(project={py_string(project.name)})",
            "",
            "    def _start() -> None:",
            "        init()",
            "        start_program()",
            "",
            "    vp.run(_start, sim=sim)",
            "    return 1 if sim.controller.error_log else 0",
            "",
            "",
            "def start_program() -> None:",
            f'    """The start program, {escape(start.program.name, "docstring")}, as V+ task 0 runs it (EXECUTE of the main program)."""',
            f"    {program_module[start_key]}.{function[start_key]}()",
        ]
    lines += ["", "", "register_package(__file__)"]
    return "\n".join(lines) + "\n"


def _package_main() -> str:
    return (
        '"""``python -m <package>``: run the V+ project on a simulated controller."""\n'
        "\n"
        "from gplrt.sim import Simulation\n"
        "\n"
        "from . import PROJECT, main\n"
        "\n"
        'raise SystemExit(main(Simulation(project=PROJECT["name"])))\n'
    )

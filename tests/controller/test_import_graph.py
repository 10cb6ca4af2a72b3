"""gplrt's modules import one another in one direction only (issue 14, item 1), and gplrt and gpl2py
import each other in one direction only (issue 13, item 2).

The graph is built from the import statements of every module of ``runtime/gplrt`` (``ast``), all
of them, including imports inside functions:

* ``import a.b.c`` and ``from a.b import c`` are edges to the gplrt module they load (``a.b.c``
  when it is a module, else ``a.b``), relative imports resolved;
* importing a module also runs the ``__init__`` of each package it is in, so an import of
  ``gplrt.threads.scheduler`` from outside ``gplrt.threads`` is also an edge to ``gplrt.threads``
  (a module inside a package is loaded after its package, so that edge is not drawn for it);
* an import under ``if TYPE_CHECKING:`` is not an edge: it names types for annotations and never
  runs (``from __future__ import annotations`` keeps the annotations unevaluated);
* ``importlib.import_module("a.b")`` with a constant name is an import too.

Rules checked: the graph has no cycle; no gplrt module imports gplrt inside a function (with an
acyclic graph there is no reason to, and such an import is how a cycle hides); gplrt imports
nothing from gpl2py, not even the notebook's runtime half (the loader that translates is
``gpl2py.notebook``); gpl2py's own graph has no cycle either; and gpl2py imports gplrt only
where it runs programs or shares GPL's semantics with the runtime (:data:`GPL2PY_USES_GPLRT`).
"""

from __future__ import annotations

import ast
from dataclasses import dataclass, field
from pathlib import Path

import gpl2py
import gplrt

RUNTIME = Path(gplrt.__file__).resolve().parent
TRANSPILER = Path(gpl2py.__file__).resolve().parent
#: The gpl2py modules that may import gplrt, and why (issue 13, item 2: "only where it runs programs").
GPL2PY_USES_GPLRT = {
    "gpl2py.run": "runs a translated program on a Simulation",
    "gpl2py.notebook": "the notebook loader: translates, then runs on a Simulation",
    "gpl2py.cli": "run's configuration: checks [tool.gpl2py] robot against the runtime's models",
    "gpl2py.cache": "the cache key includes the runtime's files (a translation is made for them)",
    "gpl2py.gpl.semantics.consts": "folds a Const with gplrt.lang's own operators, as the program would",
    "gpl2py.deploy": "the compiler of the simulated controller's console: translates, imports, hands gplrt a Program",
    "gpl2py.serve": "run --console/--ftp: starts the runtime's Telnet and FTP servers on the run's Simulation",
    "gpl2py.tmscript.node": "run --listen-node: starts the runtime's TM Listen node with the TMscript front end",
    "gpl2py.tmscript.semantics.members_gen": "writes members_data.py from the runtime's TM classes (a developer's "
                                             "command; the checks read the data module, not gplrt)",
    "gpl2py.sweep.worker": "sweep: runs one parameter set on a Simulation, on a Dask worker or in the loop",
}


@dataclass
class Graph:
    modules: dict[str, Path]
    edges: dict[str, set[str]] = field(default_factory=dict)
    #: (module, line, imported name) of every import inside a function
    in_functions: list[tuple[str, int, str]] = field(default_factory=list)
    #: (module, line, imported name) of every import of the other package (``build_graph``'s ``other``)
    foreign: list[tuple[str, int, str]] = field(default_factory=list)


def _module_names(root: Path, package: str) -> dict[str, Path]:
    names = {}
    for path in sorted(root.rglob("*.py")):
        parts = [package, *path.relative_to(root).with_suffix("").parts]
        if parts[-1] == "__init__":
            parts.pop()
        names[".".join(parts)] = path
    return names


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _imported_by_call(node: ast.AST) -> str | None:
    """``"a.b"`` for ``importlib.import_module("a.b")`` (or ``import_module("a.b")``), else None."""
    if not isinstance(node, ast.Call) or not node.args:
        return None
    func = node.func
    name = func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""
    first = node.args[0]
    if name == "import_module" and isinstance(first, ast.Constant) and isinstance(first.value, str):
        return first.value
    return None


def build_graph(root: Path, package: str, other: str = "gpl2py") -> Graph:
    """The import graph of the package ``package`` whose folder is ``root`` (module docstring);
    imports of the package ``other`` are listed in ``foreign``."""
    graph = Graph(_module_names(root, package))
    modules = graph.modules

    def target(name: str) -> str | None:
        while name and name not in modules:
            name = name.rpartition(".")[0]
        return name or None

    for module, path in modules.items():
        own_package = module if path.name == "__init__.py" else module.rpartition(".")[0]
        found: set[str] = set()

        def visit(node: ast.AST, in_function: bool) -> None:
            for child in ast.iter_child_nodes(node):
                if isinstance(child, ast.If) and _is_type_checking(child.test):
                    for branch in child.orelse:
                        visit(branch, in_function)
                    continue
                names: list[str] = []
                called = _imported_by_call(child)
                if called is not None:
                    names = [called]
                elif isinstance(child, ast.Import):
                    names = [alias.name for alias in child.names]
                elif isinstance(child, ast.ImportFrom):
                    if child.level:
                        base = own_package.split(".")[: len(own_package.split(".")) - (child.level - 1)]
                        source = ".".join(base + ([child.module] if child.module else []))
                    else:
                        source = child.module or ""
                    names = [f"{source}.{alias.name}" if f"{source}.{alias.name}" in modules else source
                             for alias in child.names]
                for name in names:
                    if name.split(".")[0] == other:
                        graph.foreign.append((module, getattr(child, "lineno", 0), name))
                    hit = target(name) if name.split(".")[0] == package else None
                    if hit is not None:
                        found.add(hit)
                        if in_function:
                            graph.in_functions.append((module, getattr(child, "lineno", 0), name))
                visit(child, in_function or isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)))

        visit(ast.parse(path.read_text(encoding="utf-8"), str(path)), False)
        for hit in list(found):  # the packages the imported module is in run their __init__ first
            parts = hit.split(".")
            for k in range(2, len(parts)):
                outer = ".".join(parts[:k])
                if outer in modules and not (module == outer or module.startswith(outer + ".")):
                    found.add(outer)
        found.discard(module)
        graph.edges[module] = found
    return graph


def find_cycle(edges: dict[str, set[str]]) -> list[str] | None:
    """One cycle of the graph as the modules along it (first == last), or None."""
    WHITE, GREY, BLACK = 0, 1, 2
    colour = dict.fromkeys(edges, WHITE)
    stack: list[str] = []

    def dfs(node: str) -> list[str] | None:
        colour[node] = GREY
        stack.append(node)
        for nxt in sorted(edges.get(node, ())):
            if colour.get(nxt, BLACK) == GREY:
                return stack[stack.index(nxt):] + [nxt]
            if colour.get(nxt) == WHITE:
                cycle = dfs(nxt)
                if cycle is not None:
                    return cycle
        stack.pop()
        colour[node] = BLACK
        return None

    for start in sorted(edges):
        if colour[start] == WHITE:
            cycle = dfs(start)
            if cycle is not None:
                return cycle
    return None


def test_gplrt_imports_form_no_cycle() -> None:
    graph = build_graph(RUNTIME, "gplrt")
    assert len(graph.modules) > 70  # the whole runtime was read
    assert "gplrt.session" in graph.edges["gplrt.motion.move"]  # and its imports were found
    cycle = find_cycle(graph.edges)
    assert cycle is None, "import cycle: " + " -> ".join(cycle or [])


def test_no_gplrt_module_imports_gplrt_inside_a_function() -> None:
    graph = build_graph(RUNTIME, "gplrt")
    assert graph.in_functions == [], "\n".join(f"{m}:{line}: import of {name} inside a function"
                                               for m, line, name in graph.in_functions)


def test_gplrt_imports_nothing_from_gpl2py() -> None:
    graph = build_graph(RUNTIME, "gplrt")
    assert "gplrt.notebook" in graph.modules  # the notebook's runtime half was read too
    found = [f"{m}:{line}: imports {name}" for m, line, name in graph.foreign]
    assert found == [], "\n".join(found)


def test_gpl2py_imports_form_no_cycle() -> None:
    graph = build_graph(TRANSPILER, "gpl2py", other="gplrt")
    assert len(graph.modules) > 30 and "gpl2py.run" in graph.edges["gpl2py.notebook"]
    cycle = find_cycle(graph.edges)
    assert cycle is None, "import cycle: " + " -> ".join(cycle or [])


def test_gpl2py_imports_gplrt_only_where_it_runs_programs() -> None:
    graph = build_graph(TRANSPILER, "gpl2py", other="gplrt")
    users = {m for m, _, _ in graph.foreign}
    assert "gpl2py.notebook" in users and "gpl2py.gpl.semantics.consts" in users  # (import_module calls too)
    unexpected = [f"{m}:{line}: imports {name}" for m, line, name in graph.foreign if m not in GPL2PY_USES_GPLRT]
    assert unexpected == [], "\n".join(unexpected)


def _package(root: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        path = root / "pkg" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return root / "pkg"


def test_the_graph_sees_a_cycle_hidden_in_a_function(tmp_path: Path) -> None:
    """The checks can fail: a cycle made by an import inside a function, or through a package's
    ``__init__``, is found; one closed only by a TYPE_CHECKING import is not a cycle."""
    hidden = _package(tmp_path / "a", {
        "__init__.py": "",
        "low.py": "def f():\n    from pkg import high\n    return high\n",
        "high.py": "from pkg.low import f\n",
    })
    graph = build_graph(hidden, "pkg")
    assert find_cycle(graph.edges) in (["pkg.high", "pkg.low", "pkg.high"], ["pkg.low", "pkg.high", "pkg.low"])
    assert graph.in_functions == [("pkg.low", 2, "pkg.high")]

    through_init = _package(tmp_path / "b", {
        "__init__.py": "",
        "sub/__init__.py": "from pkg.sub.thing import X\n",
        "sub/thing.py": "from pkg.base import Y\nX = 1\n",
        "base.py": "from pkg.sub.clock import Z\nY = 2\n",
        "sub/clock.py": "Z = 3\n",
    })
    cycle = find_cycle(build_graph(through_init, "pkg").edges)
    assert cycle is not None and "pkg.sub" in cycle and "pkg.base" in cycle

    by_name = _package(tmp_path / "d", {
        "__init__.py": "",
        "low.py": "import importlib\nhigh = importlib.import_module('pkg.high')\n",
        "high.py": "from pkg import low\n",
    })
    assert find_cycle(build_graph(by_name, "pkg").edges) is not None

    typing_only = _package(tmp_path / "c", {
        "__init__.py": "",
        "low.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from pkg.high import H\n",
        "high.py": "from pkg import low\nH = 1\n",
    })
    assert find_cycle(build_graph(typing_only, "pkg").edges) is None

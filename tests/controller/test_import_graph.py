"""gplrt's modules import one another in one direction only (issue 14, item 1).

The graph is built from the import statements of every module of ``runtime/gplrt`` (``ast``), all
of them, including imports inside functions:

* ``import a.b.c`` and ``from a.b import c`` are edges to the gplrt module they load (``a.b.c``
  when it is a module, else ``a.b``), relative imports resolved;
* importing a module also runs the ``__init__`` of each package it is in, so an import of
  ``gplrt.threads.scheduler`` from outside ``gplrt.threads`` is also an edge to ``gplrt.threads``
  (a module inside a package is loaded after its package, so that edge is not drawn for it);
* an import under ``if TYPE_CHECKING:`` is not an edge: it names types for annotations and never
  runs (``from __future__ import annotations`` keeps the annotations unevaluated).

Rules checked: the graph has no cycle; no gplrt module imports gplrt inside a function (with an
acyclic graph there is no reason to, and such an import is how a cycle hides); gplrt imports
nothing from gpl2py, except ``gplrt.notebook``, which translates projects with ``gpl2py.run``
(that straddling module is the subject of another issue; it must still not close a cycle inside
gplrt, which the first rule checks for it too).
"""

from __future__ import annotations

import ast
from dataclasses import dataclass, field
from pathlib import Path

import gplrt

RUNTIME = Path(gplrt.__file__).resolve().parent
#: The one module allowed to import gpl2py (see the module docstring).
STRADDLES_GPL2PY = "gplrt.notebook"


@dataclass
class Graph:
    modules: dict[str, Path]
    edges: dict[str, set[str]] = field(default_factory=dict)
    #: (module, line, imported name) of every import inside a function
    in_functions: list[tuple[str, int, str]] = field(default_factory=list)
    #: (module, line, imported name) of every import of gpl2py
    gpl2py: list[tuple[str, int, str]] = field(default_factory=list)


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


def build_graph(root: Path, package: str) -> Graph:
    """The import graph of the package ``package`` whose folder is ``root`` (module docstring)."""
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
                    for other in child.orelse:
                        visit(other, in_function)
                    continue
                names: list[str] = []
                if isinstance(child, ast.Import):
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
                    if name.split(".")[0] == "gpl2py":
                        graph.gpl2py.append((module, child.lineno, name))
                    hit = target(name) if name.split(".")[0] == package else None
                    if hit is not None:
                        found.add(hit)
                        if in_function:
                            graph.in_functions.append((module, child.lineno, name))
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


def test_gplrt_imports_nothing_from_gpl2py_but_the_notebook() -> None:
    graph = build_graph(RUNTIME, "gplrt")
    assert {m for m, _, _ in graph.gpl2py} == {STRADDLES_GPL2PY}  # the notebook does: see above
    others = [f"{m}:{line}: imports {name}" for m, line, name in graph.gpl2py if m != STRADDLES_GPL2PY]
    assert others == [], "\n".join(others)


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

    typing_only = _package(tmp_path / "c", {
        "__init__.py": "",
        "low.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from pkg.high import H\n",
        "high.py": "from pkg import low\nH = 1\n",
    })
    assert find_cycle(build_graph(typing_only, "pkg").edges) is None

"""Issue 12, item 9: translating a source takes at most 30 times its size in memory.

The measure is docs/security.md's ("Input size"): the tracemalloc peak of the whole translation
in-process -- load, parse, semantic analysis, lowering, the package's files -- after the catalogue
and the runtime it imports are loaded, divided by the size of the parsed sources.  The input is
~1 MB of the dense code ``benchmarks/transpile_speed.py`` generates (an expression every few
characters: the worst case per byte; real code, with comments and long lines, takes less).
``benchmarks/memory.py`` measures the same on 8 MB, in a fresh process, with ``ru_maxrss`` too.
Memory is measured, not time: the test asserts nothing about how long it takes.
"""

from __future__ import annotations

import gc
import importlib.util
import tracemalloc
from pathlib import Path

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.semantics.catalogue import load_catalogue
from gpl2py.transpile import transpile

ROOT = Path(__file__).resolve().parents[2]
LIMIT = 30.0  # times the source
SOURCE_BYTES = 1_000_000


def _generate(lines: int) -> dict[str, str]:
    spec = importlib.util.spec_from_file_location("transpile_speed", ROOT / "benchmarks" / "transpile_speed.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.generate(lines)  # type: ignore[no-any-return]


def _dense_project(folder: Path) -> int:
    files = _generate(SOURCE_BYTES * 10 // 278)  # ~27.8 bytes a line
    folder.mkdir()
    gpr = ["ProjectBegin", 'ProjectName="Dense"', 'ProjectStart="Mod0.Run"']
    for name, text in files.items():
        (folder / name).write_text(text, encoding="ascii")
        gpr.append(f'ProjectSource="{name}"')
    (folder / "Project.gpr").write_text("\n".join(gpr + ["ProjectEnd"]) + "\n")
    return sum(len(text) for text in files.values())


def test_translating_dense_code_takes_at_most_30_times_the_source(tmp_path: Path) -> None:
    size = _dense_project(tmp_path / "Dense")
    assert 0.9 * SOURCE_BYTES < size < 1.1 * SOURCE_BYTES
    load_catalogue()  # the runtime the catalogue imports is the interpreter's, not the source's
    gc.collect()
    sink = DiagnosticSink()
    tracemalloc.start()
    try:
        output = transpile(tmp_path / "Dense", sink)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert output is not None and not sink.has_errors(), [d.header() for d in sink.sorted()[:5]]
    assert peak / size <= LIMIT, f"peak {peak / 2**20:.1f} MB for {size / 2**20:.2f} MB of source: " \
                                 f"{peak / size:.1f}x (limit {LIMIT:.0f}x)"

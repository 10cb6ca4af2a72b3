"""Issue 12, item 9 and issue 20, item 3: translating a source takes at most 30 times its size in
memory, whatever kind of token or shape it is made of.

The measure is docs/security.md's ("Input size"): the tracemalloc peak of the whole translation
in-process -- load, parse, semantic analysis, lowering, the package's files -- after the catalogue
and the runtime it imports are loaded, divided by the size of the parsed sources.  The input is
~1 MB of the dense code ``benchmarks/transpile_speed.py`` generates (an expression every few
characters: the worst case per byte; real code, with comments and long lines, takes less).
``benchmarks/memory.py`` measures the same on 8 MB, in a fresh process, with ``ru_maxrss`` too,
and on the one-statement shapes of the tests below (``SHAPES``), with their CPU time per MB.
Memory is measured, not time: the tests assert nothing about how long anything takes.
"""

from __future__ import annotations

import gc
import importlib.util
import tracemalloc
from pathlib import Path
from typing import Any

import pytest

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.lower.expressions import LONG_CHAIN
from gpl2py.pywriter.wrap import wrap
from gpl2py.gpl.semantics.catalogue import load_catalogue
from gpl2py.transpile import Output, transpile

ROOT = Path(__file__).resolve().parents[2]
LIMIT = 30.0  # times the source
SOURCE_BYTES = 1_000_000


def _benchmark(name: str) -> Any:
    spec = importlib.util.spec_from_file_location(name, ROOT / "benchmarks" / f"{name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _generate(lines: int) -> dict[str, str]:
    return _benchmark("transpile_speed").generate(lines)  # type: ignore[no-any-return]


def _peak(project: Path, sink: DiagnosticSink) -> tuple[Output | None, int]:
    """The translation of ``project`` and the tracemalloc peak it took (the catalogue loaded first:
    the runtime it imports is the interpreter's, not the source's)."""
    load_catalogue()
    gc.collect()
    tracemalloc.start()
    try:
        output = transpile(project, sink)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    return output, peak


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
    sink = DiagnosticSink()
    output, peak = _peak(tmp_path / "Dense", sink)
    assert output is not None and not sink.has_errors(), [d.header() for d in sink.sorted()[:5]]
    assert peak / size <= LIMIT, f"peak {peak / 2**20:.1f} MB for {size / 2**20:.2f} MB of source: " \
                                 f"{peak / size:.1f}x (limit {LIMIT:.0f}x)"


SHAPES = _benchmark("memory").SHAPES


@pytest.mark.parametrize("shape", ["string", "comment", "ident", "number"])
def test_one_long_token_takes_at_most_30_times_the_source(shape: str, tmp_path: Path) -> None:
    """A file that is one long string literal, comment, identifier or Real literal (issue 20: a
    7 MB string took 2.16 GB, matched by a regular expression that kept state per character)."""
    size = _benchmark("memory").shape_project(tmp_path / "P", SOURCE_BYTES / 1e6, shape)
    sink = DiagnosticSink()
    output, peak = _peak(tmp_path / "P", sink)
    errors = [d.code for d in sink.errors]
    assert errors == (["GPL1009"] if shape == "ident" else []), errors  # (a name of 128 characters at most)
    assert output is not None or errors
    assert peak / size <= LIMIT, f"{shape}: peak {peak / 2**20:.1f} MB for {size / 2**20:.2f} MB of source: " \
                                 f"{peak / size:.1f}x (limit {LIMIT:.0f}x)"



def test_breaking_a_long_generated_line_keeps_its_tokens_small() -> None:
    """A GPL expression of many terms is one Python line of steps (ExprLowerer.chunked) that
    ``wrap`` breaks: it kept the line's tokens, which cost 199 bytes per character of the line
    (tokenize's records, and a second list of the top-level ones), then 93; 22.7 times the line
    at the peak with them in arrays (io.StringIO's copy of the line at four bytes a character, a
    string per piece of every step at once); 5.6 now, the steps tokenized one at a time."""
    steps = ["_chain1 := 1" + " + 1" * LONG_CHAIN]
    steps += ["_chain1 := _chain1" + " + 1" * LONG_CHAIN] * 99
    line = "d = (" + ", ".join(steps) + ")[-1]"
    gc.collect()
    tracemalloc.start()
    try:
        lines = wrap(2, line)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert len(lines) == 502 and max(4 * indent + len(text) for indent, text in lines) <= 99
    assert peak / len(line) <= 10, f"peak {peak / len(line):.1f}x the line"


#: The one-statement shapes of issue 20 that held an object per operand or name, and their size
#: here (MB: 25,000 terms; 26,000 names).  ``1+1+...`` is a Chain (28x), the Dim's declarators a
#: CompactDeclarators and its locals a LocalRun (was 113x, then 54x: docs/security.md, "Input size").
LONG_STATEMENTS = {"sum": 0.05, "dim": 0.2}
#: ``gpl2py PROJECT -o OUT`` on ``1+1+...``: 330x before the line's tokens went into arrays, ~185x
#: after; 28x as a Chain, with the generated line tokenized step by step
SUM_GUARD = LIMIT


def _traced_check(shape: str, tmp_path: Path, command: str = "check") -> float:
    """The tracemalloc peak of ``gpl2py check`` (or ``command``) on ``shape``, as a multiple of its
    source, measured in a fresh interpreter as ``benchmarks/memory.py`` measures it (after a run
    on a tiny project, so imports and caches are not counted)."""
    memory = _benchmark("memory")
    memory.tiny_project(tmp_path / "tiny")
    size = memory.shape_project(tmp_path / "P", LONG_STATEMENTS[shape], shape)
    return memory.traced_bytes(command, tmp_path / "P", tmp_path / "tiny", tmp_path / "out") / size  # type: ignore[no-any-return]


def test_a_long_sum_breaks_its_generated_line_in_compact_arrays(tmp_path: Path) -> None:
    """``1+1+...`` translated and written: breaking the generated line keeps its tokens in compact
    arrays, a step at a time (wrap's records per token were 186 times the GPL source: 330x in all,
    then ~185x, the syntax tree's 135x and the lowering; the tree is a Chain now)."""
    ratio = _traced_check("sum", tmp_path, "translate")
    assert ratio <= SUM_GUARD, f"sum: peak {ratio:.1f}x the source"


#: ``gpl2py check`` of ``Dim v0, v1, ...``: 113x while the lowering made sets of every local's name
#: and the analysis a dict entry and a record per declarator; 54x without them
DIM_GUARD = 60.0


def test_a_long_dim_makes_no_table_of_its_names_beside_its_symbols(tmp_path: Path) -> None:
    """A Dim of 26,000 names nothing uses: the lowering asks about a local's Python name instead
    of making sets of them all, the analysis finds a declarator's variable by its name, keeps no
    record for a name declared first in the procedure's own block, and a VarSym is 96 bytes."""
    ratio = _traced_check("dim", tmp_path)
    assert ratio <= DIM_GUARD, f"dim: peak {ratio:.1f}x the source"


@pytest.mark.parametrize("shape", [
    "sum",  # a Chain: operators in a byte each, literal operands as values (was 186x the source)
    "dim",  # names and positions in arrays, a symbol only for a name used (was 113x, then 54x)
])
def test_one_long_statement_takes_at_most_30_times_the_source(shape: str, tmp_path: Path) -> None:
    ratio = _traced_check(shape, tmp_path)
    assert ratio <= LIMIT, f"{shape}: peak {ratio:.1f}x the source (limit {LIMIT:.0f}x)"

"""Issue 20, item 3: checking and translating take time in proportion to the source, whatever shape
it has: one ``Dim`` of 66,666 names did not finish in 60 s (lowering searched the declarators once
per declarator), one expression of a million terms took 63 s.

Time is not asserted (the machine is shared); work is: the number of lines of gpl2py's own code
executed (``sys.settrace`` line events) while ``gpl2py check`` or translate runs on the shape at
two sizes.  Linear work doubles with the size (a little less: some of it does not depend on the
source); a search per declarator made it triple.  Work done in C (the lexer's regular expression)
is not counted: it is linear by construction (``benchmarks/memory.py`` times the shapes).
"""

from __future__ import annotations

import contextlib
import importlib.util
import io
import sys
from pathlib import Path
from types import FrameType
from typing import Any

import pytest

import gpl2py
from gpl2py.cli import main

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = str(Path(gpl2py.__file__).parent)


def _shape_project(folder: Path, size: int, shape: str) -> None:
    spec = importlib.util.spec_from_file_location("memory", ROOT / "benchmarks" / "memory.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    module.shape_project(folder, size / 1e6, shape)


def _lines_executed(argv: list[str]) -> int:
    """How many lines of gpl2py's code ``gpl2py argv`` executes (after one run that imports
    what the command needs and reads the catalogue)."""
    count = 0

    def call(frame: FrameType, event: str, arg: Any) -> Any:
        return line if frame.f_code.co_filename.startswith(PACKAGE) else None

    def line(frame: FrameType, event: str, arg: Any) -> Any:
        nonlocal count
        if event == "line":
            count += 1
        return line

    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        assert main(argv) == 0
        sys.settrace(call)
        try:
            status = main(argv)
        finally:
            sys.settrace(None)
    assert status == 0
    return count


@pytest.mark.parametrize("command", ["check", "translate"])
@pytest.mark.parametrize("shape,size", [("dim", 5_000), ("sum", 5_000)])
def test_work_grows_in_proportion_to_the_source(shape: str, size: int, command: str, tmp_path: Path) -> None:
    work = []
    for n in (size, 2 * size):
        folder = tmp_path / f"{shape}{n}"
        _shape_project(folder, n, shape)
        argv = ["check", str(folder)] if command == "check" else [str(folder), "-o", str(tmp_path / "out"), "--quiet"]
        work.append(_lines_executed(argv))
    assert work[1] / work[0] <= 2.2, f"{shape}: {work[0]:,} lines executed, {work[1]:,} for twice the source"

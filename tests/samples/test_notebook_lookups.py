"""gpl2py.notebook's name lookups on a shipped sample: a bad name is a GPL error with the
controller's code, whatever the notebook user typed (docs/notebook.md)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from gpl2py.notebook import Cell
from gpltest import SAMPLES, code_of


@pytest.fixture(scope="module")
def cell(tmp_path_factory: pytest.TempPathFactory) -> Cell:
    cache: Path = tmp_path_factory.mktemp("cache")
    return Cell.load(SAMPLES / "pick_and_place", cache_dir=cache, echo=False)


def test_good_names_are_found(cell: Cell) -> None:
    assert cell.procedure("cell.main") is cell.procedure("Main")
    assert cell.module("Cell").__name__.endswith(".cell")


@pytest.mark.parametrize(
    ("lookup", "name", "code"),
    [
        ("procedure", None, -782),
        ("procedure", 3, -202),
        ("procedure", "Nope", -729),
        ("module", None, -782),
        ("module", "Nope", -798),
        ("get", None, -782),
        ("get", "NoModuleGiven", -798),  # a variable must say its module
        ("get", "Nope.x", -798),
        ("get", "Cell.no_such_variable", -729),
    ],
)
def test_bad_names_are_gpl_errors(cell: Cell, lookup: str, name: Any, code: int) -> None:
    assert code_of(getattr(cell, lookup), name) == code

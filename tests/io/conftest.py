"""Shared fixtures for the I/O tests: a sandboxed flash root and ByRef cells."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from gplrt.io.flashroot import FlashRoot, set_flash_root


class Cell:
    """A ByRef argument as generated code passes it (``get``/``set``)."""

    def __init__(self, value: Any = None) -> None:
        self.value = value

    def get(self) -> Any:
        return self.value

    def set(self, value: Any) -> None:
        self.value = value


@pytest.fixture
def cell() -> type[Cell]:
    """The ByRef cell class (test modules are not a package, so they receive it as a fixture)."""
    return Cell


@pytest.fixture
def flash(tmp_path: Path) -> FlashRoot:
    """A fresh controller disk tree for one test."""
    return set_flash_root(tmp_path / "controller")

"""Shared fixtures for the I/O tests: a sandboxed flash root and ByRef cells."""

from __future__ import annotations

from pathlib import Path

import pytest

from gplrt.io.flashroot import FlashRoot, set_flash_root
from gplrt.lang.byref import Box


@pytest.fixture
def cell() -> type[Box]:
    """The runtime's ByRef box, as generated code passes a local ByRef (``get``/``set``)."""
    return Box


@pytest.fixture
def flash(tmp_path: Path) -> FlashRoot:
    """A fresh controller disk tree for one test."""
    return set_flash_root(tmp_path / "controller")

"""Every tooling test gets a private translation cache (see tooling_util)."""

from __future__ import annotations

from pathlib import Path

import pytest


@pytest.fixture(autouse=True)
def private_cache(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch) -> Path:
    cache = tmp_path_factory.mktemp("gpl2py-cache")
    monkeypatch.setenv("GPL2PY_CACHE_DIR", str(cache))
    return cache

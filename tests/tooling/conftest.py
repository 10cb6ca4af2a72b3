"""Every tooling test gets a private translation cache (``GPL2PY_CACHE_DIR`` in a temporary
folder), so no test sees entries another test made and the user's cache is never touched."""

from __future__ import annotations

from pathlib import Path

import pytest


@pytest.fixture(autouse=True)
def private_cache(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch) -> Path:
    cache = tmp_path_factory.mktemp("gpl2py-cache")
    monkeypatch.setenv("GPL2PY_CACHE_DIR", str(cache))
    return cache

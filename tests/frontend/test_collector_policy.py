"""``gpl2py check`` runs under the collector policy of translate (issue 13, item 3).

Both pause the cyclic garbage collector from loading the project to the end of lowering
(``gpl2py.transpile.collector_paused``: with it on, allocating the trees triggers collections that
walk everything built so far, again and again) and turn it back on afterwards."""

from __future__ import annotations

import gc
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

import gpl2py.cli as cli
import gpl2py.gpl.semantics.check as check_module
import gpl2py.gpl.pipeline as pipeline_module
import gpl2py.transpile as transpile_module
from gpl2py.diagnostics import DiagnosticSink

MAIN = """Module Main
    Public Sub Main()
        Console.WriteLine("hello")
    End Sub
End Module
"""


def _record(monkeypatch: pytest.MonkeyPatch) -> dict[str, list[bool]]:
    """Wrap every phase where it is looked up; each call records whether the collector was on."""
    seen: dict[str, list[bool]] = {}

    def wrap(owner: Any, name: str) -> None:
        real: Callable[..., Any] = getattr(owner, name)

        def recording(*args: Any, **kwargs: Any) -> Any:
            seen.setdefault(name, []).append(gc.isenabled())
            return real(*args, **kwargs)

        monkeypatch.setattr(owner, name, recording)

    wrap(cli, "load_project")
    wrap(cli, "_parse")
    wrap(pipeline_module, "load_project")
    wrap(pipeline_module, "parse")
    wrap(check_module, "analyze")
    wrap(pipeline_module, "analyze")
    wrap(pipeline_module, "lower")
    return seen


def _project(tmp_path: Path) -> Path:
    (tmp_path / "Main.gpl").write_text(MAIN)
    (tmp_path / "Project.gpr").write_text('ProjectBegin\nProjectName="P"\nProjectStart="Main.Main"\n'
                                          'ProjectSource="Main.gpl"\nProjectEnd\n')
    return tmp_path


@pytest.fixture
def collector_on() -> Any:
    was = gc.isenabled()
    gc.enable()
    yield
    if not was:
        gc.disable()


def test_check_pauses_the_collector_from_loading_to_lowering(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str],
        collector_on: None) -> None:
    seen = _record(monkeypatch)
    assert cli.main(["check", str(_project(tmp_path))]) == 0
    # (check is translate's own pipeline, without keeping the text: gpl2py.transpile)
    assert seen == {"load_project": [False], "parse": [False], "analyze": [False], "lower": [False]}
    assert gc.isenabled()


def test_translate_pauses_it_the_same_way(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                          collector_on: None) -> None:
    seen = _record(monkeypatch)
    assert transpile_module.transpile(_project(tmp_path), DiagnosticSink()) is not None
    assert seen == {"load_project": [False], "parse": [False], "analyze": [False], "lower": [False]}
    assert gc.isenabled()

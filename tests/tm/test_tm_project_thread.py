"""A script project's ``main`` runs on the thread that calls the project's ``run()`` (issue 22,
item 5): a notebook user's breakpoints, Ctrl-C and ``Display`` callbacks reach it there; its waits
for the robot adopt that thread for their duration (docs/design/tmscript.md).  This was already so;
the test keeps it."""

from __future__ import annotations

import importlib.util
from pathlib import Path

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.output import write_package
from gpl2py.transpile import transpile
from gplrt.tm import context


def test_a_script_projects_main_runs_on_the_callers_thread(tmp_path: Path) -> None:
    import threading

    seen: list[object] = []
    src = 'main\n{\n    Display("a")\n    PTP("JPP",10,0,90,0,90,0,50,200,0,false)\n    QueueTag(1, 1)\n    Display("b")\n}\n'
    (tmp_path / "p.tms").write_text(src)
    sink = DiagnosticSink()
    out = transpile(tmp_path / "p.tms", sink)
    assert out is not None
    write_package(out, tmp_path / "out", sink)
    spec = importlib.util.spec_from_file_location("tm_thread_proj", tmp_path / "out" / out.package / f"{out.package}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    robot = context.use_robot("TM5-900")
    context.set_display(lambda text: seen.append((text, threading.current_thread())))
    try:
        assert module.run() == 0
    finally:
        context.set_display(None)
    assert seen == [("a", threading.current_thread()), ("b", threading.current_thread())]
    assert robot.joints[0] == 10.0

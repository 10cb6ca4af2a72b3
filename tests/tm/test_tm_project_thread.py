"""A script project's ``main`` runs on the thread that calls the project's ``run()`` (issue 22,
item 5): a notebook user's breakpoints, Ctrl-C and ``Display`` callbacks reach it there; its waits
for the robot adopt that thread for their duration (docs/design/tmscript.md).  This was already so;
the test keeps it."""

from __future__ import annotations

from pathlib import Path

from tmpacket import run_project

from gplrt.tm import context


def test_a_script_projects_main_runs_on_the_callers_thread(tmp_path: Path) -> None:
    import threading

    seen: list[object] = []
    src = tmp_path / "p.tms"
    src.write_text('main\n{\n    Display("a")\n    PTP("JPP",10,0,90,0,90,0,50,200,0,false)\n    QueueTag(1, 1)\n'
                   '    Display("b")\n}\n')
    status, _ = run_project(src, tmp_path / "out", display=lambda text: seen.append((text, threading.current_thread())))
    assert status == 0
    assert seen == [("a", threading.current_thread()), ("b", threading.current_thread())]
    assert context.robot().joints[0] == 10.0

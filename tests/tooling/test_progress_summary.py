"""The translate command's closing summary, its --json summary, and the progress bar's TTY rule."""

from __future__ import annotations

import io
import json
import os
import pty
import re
import subprocess
import sys
from pathlib import Path

from gpl2py.progress import MIN_FILES, ProgressBar, wants_progress
from gpltest import REPO, gpl2py, module_src, write_project


def _many_files(root: Path, count: int = MIN_FILES + 2) -> tuple[Path, int]:
    sources = {}
    for i in range(count):
        body = f"    Public Function F{i}(ByVal n As Integer) As Integer\n        Return n + {i}\n    End Function"
        if i == 0:
            body += "\n    Public Sub Main()\n        Console.WriteLine(F1(1))\n    End Sub"
        sources[f"M{i:02}.gpl"] = module_src(body, f"M{i:02}")
    proj = Path(write_project(root, sources, start="M00.Main", name="Many"))
    return proj, sum(len(t.splitlines()) for t in sources.values())


def test_summary_counts_files_lines_warnings_errors_and_time(tmp_path: Path) -> None:
    proj, lines = _many_files(tmp_path)
    r = gpl2py(str(proj), "-o", str(tmp_path / "out"))
    assert r.returncode == 0, r.stderr
    last = r.stderr.splitlines()[-1]
    m = re.fullmatch(rf"transpiled {MIN_FILES + 2} files \({lines} lines\) in (\d+\.\d\d) s: 0 errors, 0 warnings", last)
    assert m, last
    assert "\r" not in r.stderr  # stderr is a pipe: no progress bar


def test_json_summary_for_translate(tmp_path: Path) -> None:
    proj, lines = _many_files(tmp_path)
    r = gpl2py(str(proj), "-o", str(tmp_path / "out"), "--json")
    assert r.returncode == 0 and r.stderr == ""
    summary = json.loads(r.stdout)["summary"]
    assert summary["files"] == MIN_FILES + 2 and summary["lines"] == lines
    assert summary["errors"] == 0 and summary["warnings"] == 0 and summary["seconds"] > 0


def _run_with_tty_stderr(args: list[str]) -> tuple[int, str]:
    """Run gpl2py with stderr on a pseudo-terminal; returns (status, everything written to it)."""
    master, slave = pty.openpty()
    try:
        proc = subprocess.Popen([sys.executable, "-m", "gpl2py", *args], stdout=subprocess.PIPE,
                                stderr=slave, cwd=REPO, env=os.environ.copy())
        os.close(slave)
        chunks = []
        while True:
            try:
                data = os.read(master, 4096)
            except OSError:  # EIO: the child closed the terminal
                break
            if not data:
                break
            chunks.append(data)
        proc.wait(timeout=120)
    finally:
        os.close(master)
    return proc.returncode, b"".join(chunks).decode(errors="replace")


def test_progress_bar_is_drawn_on_a_terminal_and_erased(tmp_path: Path) -> None:
    proj, _ = _many_files(tmp_path)
    status, text = _run_with_tty_stderr([str(proj), "-o", str(tmp_path / "out")])
    assert status == 0, text
    assert f"{MIN_FILES + 2}/{MIN_FILES + 2}" in text and "\r" in text and "#" in text
    assert "\x1b[K" in text  # erased before the summary
    assert text.rstrip().splitlines()[-1].split("\x1b[K")[-1].startswith("transpiled ")


def test_no_progress_bar_with_quiet_or_json_even_on_a_terminal(tmp_path: Path) -> None:
    proj, _ = _many_files(tmp_path)
    status, text = _run_with_tty_stderr([str(proj), "-o", str(tmp_path / "out"), "--quiet"])
    assert status == 0 and text == ""
    status, text = _run_with_tty_stderr([str(proj), "-o", str(tmp_path / "out2"), "--json"])
    assert status == 0 and text == ""


def test_no_progress_bar_for_small_projects() -> None:
    stream = io.StringIO()
    bar = ProgressBar(stream, enabled=True)
    for i in range(MIN_FILES - 1):
        bar("parsing", i + 1, MIN_FILES - 1)
    bar.close()
    assert stream.getvalue() == ""
    assert not wants_progress(io.StringIO(), quiet=False, as_json=False)  # not a terminal

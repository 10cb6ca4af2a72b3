"""Issue 12, items 8, 9 and 11: what a project may make gpl2py read, and where it says so.

A ProjectSource that is a device, a pipe or a link out of the project folder is refused with a
diagnostic instead of being read (``/dev/zero`` grew memory without end, a FIFO hung forever);
a source over the size limit is refused (configurable); a bad ProjectStart points at its line.
"""

from __future__ import annotations

import os
import threading
from pathlib import Path

import pytest

from gpl2py.cli import main as cli_main
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.project import Limits, Project, load_project
from gpl2py.transpile import transpile

MAIN = "Module Main\n    Public Sub Main()\n        Console.WriteLine(\"hi\")\n    End Sub\nEnd Module\n"

posix_only = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="FIFOs and /dev/zero are POSIX")


def project(folder: Path, sources: list[str], start: str = "Main") -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    lines = ["ProjectBegin", 'ProjectName="H"', f'ProjectStart="{start}"',
             *(f'ProjectSource="{s}"' for s in sources), "ProjectEnd"]
    (folder / "Project.gpr").write_text("\n".join(lines) + "\n")
    if not (folder / "Main.gpl").exists():
        (folder / "Main.gpl").write_text(MAIN)
    return folder


def load_bounded(path: Path, limits: Limits | None = None) -> tuple[Project | None, DiagnosticSink]:
    """load_project in a thread: a loader that blocks on a pipe fails the test instead of hanging."""
    sink = DiagnosticSink()
    result: list[Project | None] = []
    worker = threading.Thread(target=lambda: result.append(load_project(path, sink, limits)), daemon=True)
    worker.start()
    worker.join(60)
    assert not worker.is_alive(), "load_project blocked"
    return result[0], sink


def where(sink: DiagnosticSink) -> list[tuple[str, str, int, int]]:
    """(code, file name, line, col) of every diagnostic; each must have a position."""
    out = []
    for d in sink:
        assert d.span is not None, d.header()
        out.append((d.code, Path(d.span.file).name, d.span.line, d.span.col))
    return out


@posix_only
def test_a_fifo_source_is_refused_not_waited_for(tmp_path: Path) -> None:
    proj = project(tmp_path / "P", ["Main.gpl", "Pipe.gpl"])
    os.mkfifo(proj / "Pipe.gpl")
    loaded, sink = load_bounded(proj)
    assert loaded is not None and [s.path for s in loaded.sources] == [str(proj / "Main.gpl")]
    assert where(sink) == [("GPL1420", "Project.gpr", 5, 16)]
    assert "a pipe" in sink.errors[0].message
    # named on the command line, or found in a folder without Project.gpr: the same answer
    _, sink = load_bounded(proj / "Pipe.gpl")
    assert where(sink) == [("GPL1420", "Pipe.gpl", 1, 1)]
    (proj / "Project.gpr").unlink()
    _, sink = load_bounded(proj)
    assert where(sink) == [("GPL1420", "Pipe.gpl", 1, 1)]


@posix_only
def test_a_link_to_a_device_inside_the_project_is_refused(tmp_path: Path) -> None:
    # a link to /dev/zero read without end; inside the folder it is still not a regular file
    if not Path("/dev/zero").exists():
        pytest.skip("no /dev/zero")
    proj = project(tmp_path / "P", ["Main.gpl", "Zero.gpl"])
    os.symlink("/dev/zero", proj / "Zero.gpl")
    loaded, sink = load_bounded(proj)
    assert [d.code for d in sink] == ["GPL1423"]  # a link out of the folder
    _, sink = load_bounded(proj / "Zero.gpl")  # the user names it: not confined, still not a file
    assert where(sink) == [("GPL1420", "Zero.gpl", 1, 1)] and "character device" in sink.errors[0].message


def test_a_link_out_of_the_project_is_refused_and_one_inside_is_read(tmp_path: Path) -> None:
    secret = tmp_path / "secret.txt"
    secret.write_text("password = hunter2\n")
    proj = project(tmp_path / "P", ["Main.gpl", "Leak.gpl", "Lib/Shared.gpl"])
    (proj / "Lib").mkdir()
    (proj / "Real.gpl").write_text("Module Shared\n    Public Sub Help()\n    End Sub\nEnd Module\n")
    try:
        os.symlink(secret, proj / "Leak.gpl")
        os.symlink(proj / "Real.gpl", proj / "Lib" / "Shared.gpl")
    except (OSError, NotImplementedError):
        pytest.skip("no symbolic links here")
    loaded, sink = load_bounded(proj)
    assert where(sink) == [("GPL1423", "Project.gpr", 5, 16)]
    assert loaded is not None and len(loaded.sources) == 2  # Main.gpl and the link inside
    rendered = "\n".join(d.render() for d in sink)
    assert "hunter2" not in rendered


def test_a_source_over_the_limit_is_refused(tmp_path: Path) -> None:
    proj = project(tmp_path / "P", ["Main.gpl", "Big.gpl"])
    (proj / "Big.gpl").write_text("' filler\n" * 20_000)  # 180 kB
    loaded, sink = load_bounded(proj, Limits.of_mb(0.1))
    assert where(sink) == [("GPL1421", "Project.gpr", 5, 16)]
    assert "Big.gpl is 175.8 kB, more than the 102.4 kB gpl2py reads from one file" in sink.errors[0].message
    assert loaded is not None and len(loaded.sources) == 1
    loaded, sink = load_bounded(proj, Limits.of_mb(1))
    assert list(sink) == [] and loaded is not None and len(loaded.sources) == 2


def test_the_project_total_is_four_files(tmp_path: Path) -> None:
    names = [f"M{i}.gpl" for i in range(6)]
    proj = project(tmp_path / "P", names)
    for n in names:
        (proj / n).write_text(f"Module {n[:-4]}\n" + "' filler\n" * 3_000 + "End Module\n")  # 27 kB each
    loaded, sink = load_bounded(proj, Limits.of_mb(0.03))  # 31 kB a file, 126 kB the project
    assert where(sink) == [("GPL1422", "Project.gpr", 8, 16)]  # the fifth file passes the total
    assert loaded is not None and [Path(s.path).name for s in loaded.sources] == names[:4]


def test_the_limit_is_configurable_from_the_command_line_and_the_environment(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    proj = project(tmp_path / "P", ["Main.gpl"])
    monkeypatch.delenv("GPL2PY_MAX_SOURCE_MB", raising=False)
    assert cli_main(["check", str(proj), "--max-source-mb", "0.00005"]) == 1
    assert "error GPL1421" in capsys.readouterr().err
    monkeypatch.setenv("GPL2PY_MAX_SOURCE_MB", "0.00005")
    assert cli_main(["translate", str(proj), "-o", str(tmp_path / "out")]) == 1
    assert "error GPL1421" in capsys.readouterr().err and not (tmp_path / "out" / "h").exists()
    assert cli_main(["check", str(proj), "--max-source-mb", "2"]) == 0  # the option wins
    monkeypatch.setenv("GPL2PY_MAX_SOURCE_MB", "nonsense")  # ignored: the default applies
    assert cli_main(["check", str(proj)]) == 0
    capsys.readouterr()
    assert cli_main(["check", str(proj), "--max-source-mb", "-1"]) == 2


def test_a_bad_project_start_points_at_its_project_gpr_line(tmp_path: Path) -> None:
    # GPL2019 had no file:line:col
    proj = project(tmp_path / "P", ["Main.gpl"], start="Nowhere")
    sink = DiagnosticSink()
    assert transpile(proj, sink) is None
    assert where(sink) == [("GPL2019", "Project.gpr", 3, 15)]
    proj = project(tmp_path / "Q", ["Main.gpl"], start="Main.Missing")
    sink = DiagnosticSink()
    assert transpile(proj, sink) is None
    assert where(sink) == [("GPL2019", "Project.gpr", 3, 15)]


def test_a_long_project_gpr_lists_its_folder_once(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # every ProjectSource line listed the folder again: 30,000 lines over 5,000 files took 94 s
    names = [f"Missing{i}.gpl" for i in range(2_000)]
    proj = project(tmp_path / "P", ["Main.gpl", *names])
    for i in range(200):
        (proj / f"other{i}.txt").write_text("")
    listed: list[Path] = []
    real_iterdir = Path.iterdir

    def iterdir(self: Path):  # type: ignore[no-untyped-def]
        listed.append(self)
        return real_iterdir(self)

    monkeypatch.setattr(Path, "iterdir", iterdir)
    loaded, sink = load_bounded(proj)
    assert loaded is not None and len(loaded.sources) == 1
    assert [d.code for d in sink] == ["GPL1405"] * 2_000
    assert len(listed) <= 2, len(listed)  # Project.gpr's lookup and the ProjectSource names
    assert (proj / "Project.gpr").stat().st_size < 2**20
    (proj / "Project.gpr").write_text("ProjectBegin\n" + "' comment\n" * 120_000 + "ProjectEnd\n")
    _, sink = load_bounded(proj)  # 1.2 MB: a Project.gpr over a megabyte is refused
    assert [(d.code, Path(d.span.file).name) for d in sink if d.span] == [("GPL1421", "Project.gpr")]


def test_a_file_name_cannot_break_a_diagnostic_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # a folder called "a\nb" split the diagnostic in two lines: a name can forge a line of output
    folder = tmp_path / "a\nb: error GPL0000: forged\u202e"
    folder.mkdir()
    (folder / "Main.gpl").write_text("Module Main\n    Public Sub Main()\n        x = 1\n    End Sub\nEnd Module\n")
    assert cli_main(["check", str(folder)]) == 1
    err = capsys.readouterr().err
    first = err.splitlines()[0]
    assert first.endswith("Main.gpl:3:9: error GPL2001: 'x' is not declared"), first
    assert "a\\x0ab: error GPL0000: forged\\u202e" in first
    assert not any(line.startswith("b: error") for line in err.splitlines())


def test_a_diagnostic_on_a_long_line_quotes_a_window_of_it(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # issue 20: the warning on a 7 MB string literal reprinted the whole line, and a caret under
    # all of it (14.7 MB of output); an error far along the line reprinted it too
    folder = tmp_path / "P"
    folder.mkdir()
    line = '        Console.WriteLine("' + "a" * 1_000_000 + '" & nothere & "' + "b" * 1_000_000 + '" & nor)'
    (folder / "Main.gpl").write_text(f"Module Main\n    Public Sub Main()\n{line}\n    End Sub\nEnd Module\n")
    assert cli_main(["check", str(folder)]) == 1
    err = capsys.readouterr().err.split("\n")
    assert sum(map(len, err)) < 4_000, sum(map(len, err))
    first, middle, last = err[0:3], err[3:6], err[9:12]  # (err[6:9]: the second string)
    assert first[0].endswith("Main.gpl:3:27: warning GPL1003: string literal is 1000000 characters long; "
                             "the manual limits string literals to 128")
    assert first[1] == "    " + line[:200] + "..."  # from the start of the line: the column is near it
    assert first[2] == "    " + " " * 26 + "^" * 177  # under the string, to the window's end
    col = line.index("nothere") + 1
    assert middle[0].endswith(f"Main.gpl:3:{col}: error GPL2001: 'nothere' is not declared")
    assert middle[1] == "    ..." + line[col - 61:col + 139] + "..."  # 60 characters before the column
    assert middle[2] == "    " + " " * 63 + "^" * 7  # under 'nothere'
    assert last[0].endswith(f"Main.gpl:3:{line.index('nor)') + 1}: error GPL2001: 'nor' is not declared")
    assert last[1] == "    ..." + line[-200:]  # the last 200 characters: the column is near the end
    assert last[2].index("^") == last[1].index("nor)") and last[2].endswith(" ^^^")


def test_a_message_quotes_at_most_200_characters_of_a_token(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # a Real literal of a million digits is out of range: the message quoted all of them
    folder = tmp_path / "P"
    folder.mkdir()
    number = "1" + "0" * 1_000_000 + ".5"
    (folder / "Main.gpl").write_text(f"Module Main\n    Public Sub Main()\n        Console.WriteLine({number})\n"
                                     "    End Sub\nEnd Module\n")
    assert cli_main(["check", str(folder)]) == 1
    header = capsys.readouterr().err.split("\n")[0]
    # (the lexer cuts a long literal itself and says how long it is: GPL1007 of issue 20 item 2)
    assert header.endswith(f"error GPL1007: numeric literal {number[:20]}... ({len(number)} characters) "
                           "is out of range")

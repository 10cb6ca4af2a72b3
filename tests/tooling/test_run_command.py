"""``gpl2py run``: cache reuse, options, exit statuses, error reports, JSON, Ctrl-C."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from gpltest import FOREGROUND, REPO, gpl2py, in_process, module_src, write_project

TICKER = module_src("""\
    Function Inner(ByVal d As Integer) As Integer
        Return 10 \\ d
    End Function
    Public Sub Main()
        Dim i As Integer
        For i = 1 To 3
            Console.WriteLine("tick " & CStr(i))
            Thread.Sleep(500)
        Next
        Console.WriteLine(Inner(DIVISOR))
    End Sub""").replace("Module Main\n", "Module Main\n    Public Const DIVISOR As Integer = 5\n")


def _entries(cache: Path) -> list[Path]:
    return sorted(p for p in cache.iterdir() if not p.name.startswith("."))


def test_second_run_reuses_the_cache_and_a_changed_source_translates_again(tmp_path: Path,
                                                                            private_cache: Path) -> None:
    proj = Path(write_project(tmp_path, {"Main.gpl": TICKER}, name="Ticker"))
    first = gpl2py("run", str(proj))
    assert first.returncode == 0, first.stderr
    assert "tick 3" in first.stdout and first.stdout.endswith("2\n")
    [entry] = _entries(private_cache)
    stamps = {p: p.stat().st_mtime_ns for p in entry.rglob("*")}
    assert (entry / "ticker" / "__init__.py") in stamps

    second = gpl2py("run", str(proj))
    assert second.returncode == 0, second.stderr
    assert second.stdout == first.stdout
    assert "from the cache" in second.stderr and "from the cache" not in first.stderr
    assert _entries(private_cache) == [entry]
    assert {p: p.stat().st_mtime_ns for p in entry.rglob("*")} == stamps  # nothing rewritten

    (proj / "Main.gpl").write_text(TICKER.replace("DIVISOR As Integer = 5", "DIVISOR As Integer = 2"))
    third = gpl2py("run", str(proj))
    assert third.returncode == 0, third.stderr
    assert third.stdout.endswith("\n5\n") and "from the cache" not in third.stderr
    assert len(_entries(private_cache)) == 2


def test_cache_dir_option_and_rebuild(tmp_path: Path, private_cache: Path) -> None:
    proj = write_project(tmp_path, {"Main.gpl": TICKER}, name="Ticker")
    mine = tmp_path / "my-cache"
    r = gpl2py("run", str(proj), "--cache-dir", str(mine), "-q")
    assert r.returncode == 0, r.stderr
    assert len(_entries(mine)) == 1 and not _entries(private_cache)
    r = gpl2py("run", str(proj), "--cache-dir", str(mine), "--rebuild")
    assert r.returncode == 0 and "from the cache" not in r.stderr and "transpiled 1 file" in r.stderr


def test_console_streams_to_stdout_and_summary_goes_to_stderr(tmp_path: Path) -> None:
    proj = write_project(tmp_path, {"Main.gpl": TICKER}, name="Ticker")
    r = gpl2py("run", str(proj))
    assert r.stdout == "tick 1\ntick 2\ntick 3\n2\n"
    lines = r.stderr.splitlines()
    assert lines[0] == f"transpiled 1 file ({len(TICKER.splitlines())} lines) " + lines[0].split(") ", 1)[1]
    assert lines[0].endswith(": 0 errors, 0 warnings")
    assert lines[-1].startswith("program ended after 1.500 s of controller time (virtual clock")
    assert lines[-1].endswith(": 0 unhandled errors")
    quiet = gpl2py("run", str(proj), "--quiet")
    assert quiet.stdout == r.stdout and quiet.stderr == ""


def test_unhandled_gpl_error_names_code_message_file_and_line(tmp_path: Path) -> None:
    proj = Path(write_project(tmp_path, {"Main.gpl": TICKER.replace("= 5", "= 0")}, name="Ticker"))
    r = gpl2py("run", str(proj))
    assert r.returncode == 3
    assert f"{proj / 'Main.gpl'}:4: error -709 in thread Main: *Division by 0*" in r.stderr
    assert "Traceback" not in r.stderr
    assert r.stderr.splitlines()[-1].endswith(": 1 unhandled error")


def test_json_output_carries_diagnostics_console_and_errors(tmp_path: Path) -> None:
    long_text = "x" * 130  # a literal longer than a controller accepts: warning GPL1003
    src = TICKER.replace("= 5", "= 0").replace("Dim i As Integer", f'Dim i As Integer\n        Dim s As String = "{long_text}"')
    proj = Path(write_project(tmp_path, {"Main.gpl": src}, name="Ticker"))
    r = gpl2py("run", str(proj), "--json")
    assert r.returncode == 3 and r.stderr == ""
    doc = json.loads(r.stdout)
    assert doc["summary"]["files"] == 1 and doc["summary"]["lines"] == len(src.splitlines())
    assert doc["summary"]["errors"] == 0 and doc["summary"]["cached"] is False
    assert doc["summary"]["warnings"] == 1
    assert [(d["code"], d["line"]) for d in doc["diagnostics"]] == [("GPL1003", 8)]
    run = doc["run"]
    assert run["status"] == 3 and run["controller_time"] == 1.5
    assert run["console"] == "tick 1\ntick 2\ntick 3\n"
    [err] = run["errors"]
    assert err["code"] == -709 and err["thread"] == "Main" and err["line"] == 4
    assert err["file"] == str(proj / "Main.gpl") and err["message"].startswith("*Division by 0*")
    again = json.loads(gpl2py("run", str(proj), "--json").stdout)
    assert again["summary"]["cached"] is True and again["diagnostics"] == doc["diagnostics"]  # replayed


def test_source_errors_run_nothing(tmp_path: Path) -> None:
    proj = write_project(tmp_path, {"Main.gpl": module_src("    Public Sub Main()\n        x = 1\n    End Sub")})
    r = gpl2py("run", str(proj))
    assert r.returncode == 1
    assert "Main.gpl:3:9: error GPL2001" in r.stderr and r.stdout == ""
    lines = r.stderr.splitlines()
    assert lines[1:3] == ["            x = 1", "            ^"]  # the offending line, as `check` shows it
    assert lines[-1] == "checked 1 file: 1 error, 0 warnings"  # the files were read, not 0


def test_stalled_program_exits_4_and_names_the_waiting_threads(tmp_path: Path) -> None:
    src = module_src("""\
    Public Sub Main()
        Console.WriteLine("waiting for an event nobody sends")
        Thread.WaitEvent(1, -1)
    End Sub""")
    proj = write_project(tmp_path, {"Main.gpl": src})
    r = gpl2py("run", str(proj))
    assert r.returncode == 4, r.stderr
    assert "stalled, threads still waiting: Main" in r.stderr


def test_usage_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    proj = write_project(tmp_path, {"Main.gpl": TICKER})
    r = in_process(capsys, "run", str(proj), "--robot", "R2D2")
    assert r.returncode == 2 and "invalid choice: 'R2D2'" in r.stderr
    assert in_process(capsys, "run", str(proj), "--clock", "sundial").returncode == 2
    assert in_process(capsys, "run", str(proj), "--speed", "0").returncode == 2
    r = in_process(capsys, "run", str(proj), "--clock", "real", "--speed", "inf")
    assert r.returncode == 2 and "--speed: must be a finite number: 'inf'" in r.stderr, r.stderr
    no_start = tmp_path / "nostart"
    no_start.mkdir()
    # no Project.gpr and no Public Sub Main (with one, it would start: tests/e2e/test_start_main.py)
    (no_start / "Main.gpl").write_text(TICKER.replace("Sub Main()", "Sub Other()"))
    r = in_process(capsys, "run", str(no_start))
    assert r.returncode == 2 and "ProjectStart" in r.stderr and r.stdout == ""


def test_bad_flash_or_plot_is_a_usage_error_before_the_program_runs(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    proj = write_project(tmp_path, {"Main.gpl": TICKER})
    a_file = tmp_path / "disks.txt"
    a_file.write_text("not a folder")
    r = in_process(capsys, "run", str(proj), "--flash", str(a_file), "-q")
    assert r.returncode == 2 and r.stdout == "", r.stderr  # nothing ran: no "tick 1"
    assert f"error GPL9001: --flash {a_file}: not a folder" in r.stderr and "GPL9000" not in r.stderr
    r = in_process(capsys, "run", str(proj), "--plot", str(tmp_path / "cell.pnj"), "-q")
    assert r.returncode == 2 and r.stdout == "", r.stderr
    assert "error GPL9001: --plot" in r.stderr and "cannot save a .pnj image" in r.stderr
    assert "png" in r.stderr and "GPL9000" not in r.stderr


def test_plot_that_cannot_be_written_is_reported_and_the_run_keeps_its_status(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    proj = write_project(tmp_path, {"Main.gpl": WHERE})  # Robot.Where: robot 1 exists, so a plot is due
    blocker = tmp_path / "plots"
    blocker.write_text("a file where the plot's folder should be")
    r = in_process(capsys, "run", str(proj), "--plot", str(blocker / "cell.png"), "-q")
    assert r.returncode == 0, r.stderr
    assert f"error GPL3004: cannot write {blocker / 'cell.png'}" in r.stderr and "GPL9000" not in r.stderr
    r = in_process(capsys, "run", str(proj), "--plot", str(blocker / "cell.png"), "--json")
    doc = json.loads(r.stdout)
    assert doc["run"]["plot"] is None
    assert [d["code"] for d in doc["diagnostics"] if d["severity"] == "error"] == ["GPL3004"]


def test_help_explains_options_and_exit_statuses(capsys: pytest.CaptureFixture[str]) -> None:
    r = in_process(capsys, "run", "--help")
    assert r.returncode == 0
    for text in ("--robot", "PF400SX", "ARM6", "--clock", "--speed", "--flash", "--setup", "--plot",
                 "--cache-dir", "130", "stalled", "unhandled error"):
        assert text in r.stdout, text
    top = in_process(capsys, "--help").stdout
    assert "run" in top and "130" in top


WHERE = module_src("""\
    Public Sub Main()
        Dim here As Location
        here = Robot.Where
        Console.WriteLine(Format(here.X, "0.000") & " " & Format(here.Y, "0.000") & " " & Format(here.Z, "0.000"))
    End Sub""")


@pytest.mark.parametrize("model", ["PF400SX", "ARM6"])
def test_robot_option_chooses_the_model(tmp_path: Path, model: str) -> None:
    from gplrt.motion.registry import robot_of
    from gplrt.sim import Simulation

    proj = write_project(tmp_path, {"Main.gpl": WHERE})
    r = gpl2py("run", str(proj), "--robot", model.lower(), "-q")
    assert r.returncode == 0, r.stderr
    state = robot_of(Simulation(robot=model), 1)
    x, y, z = state.forward(state.queue.rest)[:3, 3]
    assert r.stdout == f"{x:.3f} {y:.3f} {z:.3f}\n"


def test_real_clock_with_speed_and_flash_folder(tmp_path: Path) -> None:
    src = module_src("""\
    Public Sub Main()
        Dim f As New StreamWriter("/flash/data/out.txt")
        Thread.Sleep(2000)
        f.WriteLine("slept")
        f.Close()
    End Sub""")
    proj = write_project(tmp_path, {"Main.gpl": src})
    flash = tmp_path / "disks"
    (flash / "flash" / "data").mkdir(parents=True)
    t0 = time.monotonic()
    r = gpl2py("run", str(proj), "--clock", "real", "--speed", "10", "--flash", str(flash), "--json")
    wall = time.monotonic() - t0
    assert r.returncode == 0, r.stdout + r.stderr
    assert (flash / "flash" / "data" / "out.txt").read_text().strip() == "slept"
    assert json.loads(r.stdout)["run"]["controller_time"] >= 2.0
    assert wall < 60  # 2 s of controller time at 10x is 0.2 s of waiting, plus start-up


def test_speed_scales_real_time(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """--speed 100: 20 s of controller time pass in a fifth of a wall second, not in 20 s."""
    src = module_src("""\
    Public Sub Main()
        Dim t0 As Double
        t0 = Controller.Timer(1)
        Thread.Sleep(20000)
        Console.WriteLine(Format(Controller.Timer(1) - t0, "0.0"))
    End Sub""")
    proj = write_project(tmp_path, {"Main.gpl": src})
    assert in_process(capsys, "run", str(proj), "-q").returncode == 0  # translated: only the run is timed
    t0 = time.monotonic()
    r = in_process(capsys, "run", str(proj), "--clock", "real", "--speed", "100", "--json")
    wall = time.monotonic() - t0
    assert r.returncode == 0, r.stdout
    run = json.loads(r.stdout)["run"]
    # Sleep never ends early; it may end late by the scheduling delay, which --speed 100 multiplies
    # (2 ms of wall-clock jitter on a loaded machine reads as 0.2 s), so only the floor is exact.
    assert float(run["console"]) >= 20.0 and run["controller_time"] >= 20.0
    assert wall < 8.0  # at speed 1 this run takes 20 s


def test_setup_file_and_plot(tmp_path: Path) -> None:
    png = tmp_path / "cell.png"
    r = gpl2py("run", str(REPO / "samples/pick_and_place"), "--setup",
               str(REPO / "samples/notebook/cell_io.py"), "--plot", str(png))
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines()[-1] == "cell done: 8 parts placed, 8 requested"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000
    assert f"plot saved to {png}" in r.stderr


LOOP = module_src("""\
    Public Sub Worker()
        While True
            Thread.Sleep(20)
        End While
    End Sub
    Public Sub Main()
        Dim t As New Thread("Worker")
        t.Start()
        Console.WriteLine("started")
        While True
            Thread.Sleep(50)
        End While
    End Sub""")




@pytest.mark.parametrize("clock", ["real", "virtual"])
def test_ctrl_c_stops_every_thread_and_exits_130(tmp_path: Path, clock: str) -> None:
    proj = write_project(tmp_path, {"Main.gpl": LOOP})
    # -X faulthandler: if the run ever hangs after Ctrl-C, SIGABRT makes it print every thread's
    # stack, and the failure shows where it was stuck.
    proc = subprocess.Popen([sys.executable, "-X", "faulthandler", "-c", FOREGROUND, "run", str(proj),
                             "--clock", clock],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=REPO)
    try:
        assert proc.stdout is not None
        assert proc.stdout.readline() == "started\n"
        time.sleep(0.3)
        proc.send_signal(signal.SIGINT)
        try:
            out, err = proc.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            proc.send_signal(signal.SIGABRT)
            out, err = proc.communicate(timeout=30)
            pytest.fail(f"still running 30 s after Ctrl-C; its threads were at:\n{err}")
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 130, err
    assert "Traceback" not in err and "KeyboardInterrupt" not in err
    assert err.splitlines()[-1] == "gpl2py: interrupted; stopped 2 GPL threads"


@pytest.mark.parametrize("clock", ["real", "virtual"])
def test_ctrl_c_at_any_moment_of_the_run_stops_it(tmp_path: Path, clock: str) -> None:
    """Ctrl-C lands wherever the main thread is; each time every GPL thread stops within the grace."""
    # as in a terminal's foreground (see FOREGROUND): interrupt_main does nothing to an ignored SIGINT
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        _press_ctrl_c_during_runs(tmp_path, clock)
    finally:
        signal.signal(signal.SIGINT, previous)


def _press_ctrl_c_during_runs(tmp_path: Path, clock: str) -> None:
    import _thread
    import random
    import threading

    from gpl2py.diagnostics import DiagnosticSink
    from gpl2py.run import build, execute, import_built
    from gplrt.sim import Simulation

    built = build(write_project(tmp_path, {"Main.gpl": LOOP}), DiagnosticSink(), cache_dir=tmp_path / "c")
    assert built is not None
    package = import_built(built)
    rng = random.Random(7)
    for _ in range(4):
        sim = Simulation(clock=clock, capture=True)
        delay = rng.uniform(0.0, 0.2)

        def press_ctrl_c() -> None:
            for _ in range(1000):  # once both threads run (Main prints "started" after Worker starts)
                if "started" in sim.console.output:
                    break
                time.sleep(0.01)
            time.sleep(delay)
            _thread.interrupt_main()

        presser = threading.Thread(target=press_ctrl_c, daemon=True)
        presser.start()
        report = execute(package, sim)
        presser.join(5)
        assert report.interrupted and report.status == 130, (clock, delay)
        assert (report.stopped, report.still_alive) == (2, []), (clock, delay)
        assert all(c.phase == "done" for c in sim.scheduler.live), (clock, delay)


# The installed `gpl2py` script is `from <module> import <function>; sys.exit(<function>())` for the
# console-script entry point in the package metadata: run exactly that, after a prelude (as in a
# terminal's foreground, see FOREGROUND) that delivers a real SIGINT at one chosen moment, so the
# moment is the same on every machine however fast it starts.
ENTRY_POINT = ("import importlib.metadata as md; "
               "ep = next(e for e in md.entry_points(group='console_scripts') if e.name == 'gpl2py'); "
               "sys.exit(ep.load()())")
CTRL_C_ON_IMPORT = """
import os, signal, sys
signal.signal(signal.SIGINT, signal.default_int_handler)
class CtrlC:
    def find_spec(self, name, path=None, target=None):
        if name == {module!r}:
            sys.meta_path.remove(self)
            os.kill(os.getpid(), signal.SIGINT)  # lands inside this import
        return None
sys.meta_path.insert(0, CtrlC())
"""
CTRL_C_AT_EXIT = """
import atexit, os, signal, sys, time
signal.signal(signal.SIGINT, signal.default_int_handler)
def press():
    os.kill(os.getpid(), signal.SIGINT)  # while Python cleans up after the command has ended
    time.sleep(2)
atexit.register(press)
"""


@pytest.mark.parametrize("module", ["gpl2py.cli", "gpl2py.run", "gplrt.controller.pdb", "numpy"])
def test_ctrl_c_while_gpl2py_starts_exits_130_without_a_traceback(tmp_path: Path, module: str) -> None:
    """Issue 12 item 11: the first 0.1 s of `gpl2py run` are imports (the CLI, then the simulator)."""
    proj = write_project(tmp_path, {"Main.gpl": LOOP})
    code = CTRL_C_ON_IMPORT.format(module=module) + ENTRY_POINT
    r = subprocess.run([sys.executable, "-c", code, "run", proj], capture_output=True, text=True,
                       cwd=REPO, timeout=120)
    assert r.returncode == 130, r.stderr
    assert "Traceback" not in r.stderr and "KeyboardInterrupt" not in r.stderr, r.stderr
    assert r.stderr.splitlines()[-1] == "gpl2py: interrupted"
    assert "started" not in r.stdout


def test_ctrl_c_while_gpl2py_cleans_up_exits_130_without_a_traceback(tmp_path: Path) -> None:
    proj = write_project(tmp_path, {"Main.gpl": module_src('''    Public Sub Main()
        Console.WriteLine("done")
    End Sub''')})
    r = subprocess.run([sys.executable, "-c", CTRL_C_AT_EXIT + ENTRY_POINT, "run", proj, "-q"],
                       capture_output=True, text=True, cwd=REPO, timeout=120)
    assert r.stdout == "done\n"
    assert r.returncode == 130, r.stderr
    assert "Traceback" not in r.stderr and "KeyboardInterrupt" not in r.stderr, r.stderr


def test_cache_keeps_a_bounded_number_of_entries(tmp_path: Path) -> None:
    from gpl2py.cache import Cache

    cache = Cache(tmp_path / "c")
    for i in range(5):
        cache.store(str(i) * 64, "pkg", {"pkg/__init__.py": f"# {i}\n"}, [], (1, 1))
        os.utime(cache.folder_for(str(i) * 64) / "entry.json", ns=(i * 10**9, i * 10**9))
    removed = cache.prune(keep=2)
    assert sorted(p.name for p in removed) == sorted(cache.folder_for(str(i) * 64).name for i in range(3))
    assert cache.lookup("4" * 64) is not None and cache.lookup("0" * 64) is None


def test_setup_file_problems_are_command_line_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    proj = write_project(tmp_path, {"Main.gpl": TICKER})
    no_func = tmp_path / "nofunc.py"
    no_func.write_text("X = 1\n")
    failing = tmp_path / "failing.py"
    failing.write_text("def setup(sim):\n    sim.io.set_input(5, True)\n")  # 5 is an output
    broken = tmp_path / "broken.py"
    broken.write_text("RATIO = 1 / 0\n\ndef setup(sim):\n    pass\n")  # fails while it is imported
    cases = [(in_process(capsys, "run", str(proj), "--setup", str(tmp_path / "nope.py")), "nope.py: no such file"),
             (in_process(capsys, "run", str(proj), "--setup", str(tmp_path)), "a folder, not a Python file"),
             (in_process(capsys, "run", str(proj), "--setup", os.devnull), f"{os.devnull}: not a regular file"),
             (in_process(capsys, "run", str(proj), "--setup", str(no_func)), "setup(sim)"),
             (in_process(capsys, "run", str(proj), "--setup", str(failing)), "GplException"),
             (in_process(capsys, "run", str(proj), "--setup", str(broken)),
              "broken.py: importing it raised ZeroDivisionError: division by zero")]
    for r, text in cases:
        assert r.returncode == 2, r.stderr
        assert text in r.stderr and "Traceback" not in r.stderr and r.stdout == ""


def test_setup_error_after_warnings_prints_each_line_once(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = TICKER.replace("Dim i As Integer", f'Dim i As Integer\n        Dim s As String = "{"y" * 130}"')
    proj = write_project(tmp_path, {"Main.gpl": src})
    bad = tmp_path / "bad.py"
    bad.write_text("X = 1\n")
    r = in_process(capsys, "run", str(proj), "--setup", str(bad))
    assert r.returncode == 2
    assert r.stderr.count("GPL1003") == 1 and r.stderr.count("GPL9001") == 1
    assert r.stderr.count("transpiled 1 file") == 1


def test_plot_of_a_program_without_motion_says_so(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    proj = write_project(tmp_path, {"Main.gpl": TICKER})
    png = tmp_path / "none.png"
    r = in_process(capsys, "run", str(proj), "--plot", str(png))
    assert r.returncode == 0 and not png.exists()
    assert r.stderr.splitlines()[-1].endswith("; no plot: robot 1 was never used")


def test_cache_key_covers_sources_names_options_and_the_tools(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from gpl2py import cache
    from gpl2py.diagnostics import DiagnosticSink
    from gpl2py.project import load_project

    proj = Path(write_project(tmp_path, {"Main.gpl": TICKER}))
    project = load_project(proj, DiagnosticSink())
    assert project is not None
    base = cache.cache_key(project, {"keep_going": False})
    assert cache.cache_key(project, {"keep_going": False}) == base
    assert cache.cache_key(project, {"keep_going": True}) != base
    monkeypatch.setattr(cache, "_FINGERPRINT", "an edited gpl2py")
    assert cache.cache_key(project, {"keep_going": False}) != base
    monkeypatch.undo()
    (proj / "Main.gpl").write_text(TICKER + "\n")
    changed = load_project(proj, DiagnosticSink())
    assert changed is not None and cache.cache_key(changed, {"keep_going": False}) != base


def test_a_server_run_ends_cleanly_with_nothing_but_its_own_output(tmp_path: Path) -> None:
    """samples/cell_server under `gpl2py run`, driven by a client until it shuts down: exit 0, and
    stderr holds the summaries and where the server listened only (no interpreter-exit noise such
    as nanobind's "leaked" lines, which a scheduler timer still pending at exit used to cause:
    gplrt.sim.Simulation.close)."""
    from gpltest import SAMPLES, LineClient, copy_project, free_port

    port = free_port()
    proj = copy_project(SAMPLES / "cell_server", tmp_path / "cell_server",
                        {"SERVER_PORT As Integer = 10200": f"SERVER_PORT As Integer = {port}"})
    proc = subprocess.Popen([sys.executable, "-m", "gpl2py", "run", str(proj)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, cwd=REPO)
    try:
        assert proc.stdout is not None
        assert proc.stdout.readline() == f"cell server listening on port {port}\n"
        client = LineClient(port)
        try:
            assert client.ask("move 400 50 200") == "OK moved to 400.000 50.000 200.000"
            assert client.ask("shutdown") == "OK shutting down"
        finally:
            client.close()
        out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 0, err
    assert out == "cell server stopped after 1 connections\n"
    lines = err.splitlines()
    assert len(lines) == 3, err
    assert lines[0].startswith("transpiled 5 files (") and lines[0].endswith(": 0 errors, 0 warnings")
    assert lines[1] == f"note: listening on 127.0.0.1:{port} (thread listener)"
    assert lines[2].startswith("program ended after ") and lines[2].endswith(": 0 unhandled errors")


def test_plot_without_matplotlib_names_the_extra(tmp_path: Path) -> None:
    """--plot without matplotlib (an optional dependency) was internal error GPL9000 with an
    ImportError in it; it is one line naming the extra to install, status 2, before the run."""
    fake = tmp_path / "no_matplotlib" / "matplotlib"
    fake.mkdir(parents=True)
    (fake / "__init__.py").write_text("raise ModuleNotFoundError(\"No module named 'matplotlib'\", name='matplotlib')\n")
    proj = Path(write_project(tmp_path, {"Main.gpl": TICKER}, name="NoPlot"))
    r = gpl2py("run", str(proj), "--plot", str(tmp_path / "cell.png"), "--quiet",
               env={"PYTHONPATH": str(fake.parent)})
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr == "error GPL9001: --plot needs matplotlib, which is not installed: pip install 'gpl2py[plot]'\n"


SHUTTLE = module_src("""\
    Public Sub Main()
        Dim prof As New Profile
        Dim a As New Location
        Dim b As New Location
        Dim i As Integer
        a.Angles(300, 10, 90, -100, 100)
        b.Angles(250, 0, 100, -90, 100)
        Controller.PowerEnabled = True
        Robot.Attached = 1
        Robot.Home
        For i = 1 To 60
            If i Mod 2 = 0 Then
                Move.Loc(a, prof)
            Else
                Move.Loc(b, prof)
            End If
        Next
        Move.WaitForEOM
        Console.WriteLine("done")
    End Sub""")


def test_history_option_bounds_what_the_plot_shows_and_says_so(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("matplotlib")
    from gpl2py.run import DEFAULT_HISTORY
    from gplrt.motion.queue import DEFAULT_HISTORY as RUNTIME_DEFAULT

    assert DEFAULT_HISTORY == RUNTIME_DEFAULT  # the help's figure is the runtime's
    proj = write_project(tmp_path, {"Main.gpl": SHUTTLE})
    png = tmp_path / "cell.png"
    r = in_process(capsys, "run", str(proj), "--history", "10", "--plot", str(png))
    assert r.returncode == 0 and r.stdout == "done\n", r.stderr
    assert f"plot saved to {png} (the last 10 motions; " in r.stderr
    assert "earlier ones dropped (--history all keeps them)" in r.stderr
    r = in_process(capsys, "run", str(proj), "--history", "all", "--plot", str(png))
    assert r.returncode == 0 and f"plot saved to {png}" in r.stderr, r.stderr
    assert "dropped" not in r.stderr
    for bad in ("0", "many"):
        r = in_process(capsys, "run", str(proj), "--history", bad)
        assert r.returncode == 2 and r.stdout == "" and "--history" in r.stderr, r.stderr

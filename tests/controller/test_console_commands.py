"""The controller's console: its commands, their replies and codes, and Controller.Command/Load/Unload.

Projects are deployed to the simulated flash (as FTP would), loaded, compiled by the compiler
``gpl2py run`` gives the session (gpl2py.deploy), started, stopped and unloaded; each project in
memory keeps its own procedures, relative files and thread names (docs/design/console.md).
"""

from __future__ import annotations

import time
from pathlib import Path

import pytest
from gpltest import module_src, run_gpl

from gpl2py.deploy import compiler
from gpl2py.run import build, import_built
from gplrt.controller.commands import ConsoleCommands
from gplrt.lang.errors import GplException
from gplrt.sim import Simulation

def gpr(name: str, start: str, sources: list[str]) -> str:
    """A Project.gpr as GDE writes it (no ProjectStart line when ``start`` is empty)."""
    lines = ["ProjectBegin", f'ProjectName="{name}"', *([f'ProjectStart="{start}"'] if start else []),
             *(f'ProjectSource="{f}"' for f in sources), "ProjectEnd"]
    return "\n".join(lines) + "\n"


def deploy(sim: Simulation, name: str, sources: dict[str, str], start: str = "Work.Main",
           extra: dict[str, bytes] | None = None) -> None:
    """Write a project into /flash/projects/<name>/ on ``sim``'s disks, as an FTP upload does."""
    files = {"Project.gpr": gpr(name, start, list(sources)).encode(),
             **{f: t.encode() for f, t in sources.items()}, **(extra or {})}
    for file, data in files.items():
        where = sim.files.root().resolve(f"/flash/projects/{name}/{file}")
        assert where.file is not None
        where.file.box.path(*where.file.parts[:-1]).mkdir()
        where.file.replace(data)


WORKER = module_src("""\
    Public Sub Main()
        Dim t As New Thread("Worker")
        t.Start()
        While True
            Thread.Sleep(10)
        End While
    End Sub
    Public Sub Worker()
        Dim r As New StreamReader("data.txt")
        Console.WriteLine("other worker in " & Thread.CurrentThread.Project & ": " & r.ReadLine())
        r.Close()
    End Sub""", "Work")


def test_controller_command_loads_starts_shows_stops_and_unloads_another_project(tmp_path: Path) -> None:
    """Controller.Command reaches the console; the project it starts resolves "Worker" in its own
    registry and "data.txt" in its own folder, though the running project has a Worker too."""
    main = module_src("""\
    Public Sub Worker()
        Console.WriteLine("main worker in " & Thread.CurrentThread.Project)
    End Sub
    Public Sub Main()
        Dim t As New Thread("Worker")
        Controller.Load("/flash/projects/Other")
        Console.WriteLine("[" & Controller.Command("Start Other") & "]")
        Thread.Sleep(100)
        Console.WriteLine(Controller.Command("show thread"))
        t.Start()
        t.Join(-1)
        Controller.Command("Stop Other")
        Console.WriteLine(Controller.Command("sh th"))
        Controller.Unload("Other")
        Try
            Controller.Command("Start Other")
        Catch ex As Exception
            Console.WriteLine("start after unload: " & CStr(ex.ErrorCode) & " " & ex.Message)
        End Try
    End Sub""")

    def setup(sim: Simulation) -> None:
        sim.projects.compiler = compiler(build, import_built, tmp_path / "cache")
        deploy(sim, "Other", {"Work.gpl": WORKER}, extra={"data.txt": b"other data\r\n"})

    result = run_gpl(tmp_path, {"Main.gpl": main}, setup=setup)
    out = result.output.splitlines()
    assert out[0] == "[]"  # Start succeeds silently, as the console does
    assert "other worker in Other: other data" in out
    table = out[out.index("other worker in Other: other data") + 1:]
    assert table[0].split() == ["Project", "Thread", "State"]
    rows = [line.split() for line in table[1:4]]
    assert [result.sim.project, "Main", "Running"] in rows
    assert ["Other", "Main", "Running"] in rows
    assert ["Other", "Worker", "Idle"] in rows  # it ended
    assert f"main worker in {result.sim.project}" in out
    after_stop = out[out.index(f"main worker in {result.sim.project}") + 1:]
    assert ["Other", "Main", "Idle"] in [line.split() for line in after_stop]
    assert out[-1] == "start after unload: -729 *Undefined symbol*"
    assert result.log == ""  # no thread ended with an unhandled error


@pytest.fixture
def console(tmp_path: Path) -> ConsoleCommands:
    sim = Simulation(capture=True, compiler=compiler(build, import_built, tmp_path / "cache"))
    sim.activate()
    yield ConsoleCommands(sim.projects)
    sim.close(1.0)


def code(console: ConsoleCommands, line: str) -> int:
    with pytest.raises(GplException) as info:
        console.execute(line)
    return info.value.ErrorCode


def test_console_errors_carry_the_controller_codes(console: ConsoleCommands) -> None:
    sim = console.session
    deploy(sim, "Cell", {"Work.gpl": WORKER})
    deploy(sim, "Broken", {"Work.gpl": module_src("Public Sub Main()\n    x = \nEnd Sub", "Work")})
    deploy(sim, "NoStart", {"Work.gpl": module_src("Public Sub Helper()\nEnd Sub", "Work")}, start="")
    gpr = sim.files.root().resolve("/flash/projects/Cell/Project.gpr").file
    assert gpr is not None
    no_gpr = sim.files.root().resolve("/flash/projects/Loose/Main.gpl").file
    assert no_gpr is not None
    no_gpr.box.path(*no_gpr.parts[:-1]).mkdir()
    no_gpr.replace(b"Module Main\nEnd Module\n")

    assert code(console, "frobnicate") == -714  # Unknown command
    assert code(console, "s Cell") == -716  # Ambiguous abbreviation: Start, Stop, Show
    assert code(console, "load") == -205  # Missing argument
    assert code(console, "load a b") == -202  # Invalid argument
    assert code(console, 'load "/flash/projects/Cell') == -704  # Missing quote mark
    assert code(console, "load /flash/projects/Nothing") == -508  # File not found
    assert code(console, "load /etc") == -301  # Undefined device: no host path
    assert code(console, "load /flash/projects/../../etc") == -516  # Invalid file name
    assert code(console, "load Loose") == -743  # Invalid project file: no Project.gpr
    assert code(console, "start Cell") == -729  # Undefined symbol: not in memory
    assert console.execute("Load /flash/projects/Cell") == ""
    assert code(console, "load Cell") == -745  # Project already exists
    assert code(console, "start Cell") == -753  # Project not compiled
    assert console.execute("compile Cell") == ""
    console.execute("start -event Cell")
    assert code(console, "start Cell") == -750  # Invalid when thread active
    assert code(console, "unload Cell") == -750
    assert code(console, "compile Cell") == -750
    console.execute("stop Cell")
    assert console.execute("unload cell") == ""
    console.execute("load Broken")
    with pytest.raises(GplException) as info:
        console.execute("compile Broken")
    assert info.value.ErrorCode == -742  # Compilation errors, naming the file on the controller
    assert "/flash/projects/Broken/Work.gpl:3:9: error GPL1101" in str(info.value.detail)
    console.execute("load NoStart")
    console.execute("compile NoStart")
    assert code(console, "start NoStart") == -744  # Invalid start procedure
    assert code(console, "stop Nothing") == -729
    assert code(console, "stop -all Cell") == -202
    assert code(console, "show memory") == -714


def test_show_dir_and_del(console: ConsoleCommands) -> None:
    sim = console.session
    deploy(sim, "Cell", {"Work.gpl": WORKER}, extra={"data.txt": b"12345"})
    console.execute("load Cell")
    assert console.execute("show project").splitlines()[1].split() == ["Cell", "Loaded", "/flash/projects/Cell"]
    console.execute("compile Cell")
    assert console.execute("show project").splitlines()[1].split()[:2] == ["Cell", "Compiled"]
    listing = console.execute("dir -stat /flash/projects/Cell").splitlines()
    assert listing[0] == "Directory of /flash/projects/Cell"
    assert [line.split() for line in listing[1:-1]] == [  # sorted regardless of case
        ["5", "data.txt"], [str(len(gpr("Cell", "Work.Main", ["Work.gpl"]))), "Project.gpr"],
        [str(len(WORKER)), "Work.gpl"]]
    assert listing[-1] == "3 files, " + str(sum(int(line.split()[0]) for line in listing[1:-1])) + " bytes"
    assert console.execute("dir /flash/projects").splitlines()[1].split() == ["<DIR>", "Cell"]
    assert console.execute("del /flash/projects/Cell/data.txt") == ""
    assert "data.txt" not in console.execute("dir /flash/projects/Cell")
    assert code(console, "del /flash/projects/Cell/data.txt") == -508
    assert "Load path" in console.execute("help")


def test_stop_from_the_console_ends_every_thread_of_the_project(console: ConsoleCommands) -> None:
    sim = console.session
    deploy(sim, "Cell", {"Work.gpl": WORKER}, extra={"data.txt": b"x"})
    console.execute("load Cell")
    console.execute("compile Cell")
    console.execute("start Cell")
    deadline = time.monotonic() + 10
    while "Running" not in console.execute("show project") and time.monotonic() < deadline:
        time.sleep(0.01)
    assert console.execute("stop -all") == ""
    rows = [line.split() for line in console.execute("show thread").splitlines()[1:]]
    assert rows and all(row[-1] == "Idle" for row in rows)
    assert console.execute("unload -all") == ""
    assert console.execute("show project").splitlines()[1:] == []


def test_without_a_compiler_compile_is_not_implemented(tmp_path: Path) -> None:
    with Simulation(capture=True) as sim:
        deploy(sim, "Cell", {"Work.gpl": WORKER})
        console = ConsoleCommands(sim.projects)
        console.execute("load Cell")
        assert code(console, "compile Cell") == -204

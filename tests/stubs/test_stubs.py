"""Protected sources and stubs (issue "Porting real projects end to end", part 1).

A project whose vendor library is protected (.gpp) transpiles with one warning per missing name,
runs, and each stub raises -204 only when the program uses it; --strict refuses it; --stubs DIR
supplies implementations; unknown built-in members become warnings and stubs everywhere.
"""

from __future__ import annotations

import itertools
from pathlib import Path
from types import ModuleType

import pytest

from gpl2py.cli import main as cli_main
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.run import import_package
from gpl2py.transpile import transpile
from gplrt.sim import Simulation

_serial = itertools.count()

MAIN = """Module Main
    Public Mode As Integer

    Public Sub Start()
        Dim n As Integer
        Dim g As VendorThing
        Console.WriteLine("start")
        If Mode = 1 Then
            n = VendorLib.Grip(3) + 1
            Console.WriteLine("grip " & CStr(n))
        End If
        If Mode = 2 Then
            Try
                VendorLib.Release
                Console.WriteLine("not reached")
            Catch ex As Exception
                Console.WriteLine("caught " & CStr(ex.ErrorCode))
                Console.WriteLine(ex.Message)
            End Try
        End If
        If Mode = 3 Then
            VendorLib.Release
        End If
        If Mode = 4 Then
            Home(1)
            g = New VendorThing(2)
            Console.WriteLine("speed " & CStr(VendorLib.Speed))
        End If
        VendorLib.Speed = 40
        Console.WriteLine("speed " & CStr(VendorLib.Speed + 2))
        Console.WriteLine("done")
    End Sub
End Module
"""


def _project(root: Path, main: str = MAIN, protected: bool = True, name: str = "VendorCell",
             start: str = "Main.Start") -> Path:
    proj = root / name
    proj.mkdir(parents=True)
    (proj / "Main.gpl").write_text(main)
    lines = ["ProjectBegin", f'ProjectName="{name}"', f'ProjectStart="{start}"', 'ProjectSource="Main.gpl"']
    if protected:
        (proj / "VendorLib.gpp").write_bytes(b"'#Protected|\x00\x93\xfa\x01binary vendor code\xff")
        lines.append('ProjectSource="VendorLib.gpp"')
    lines.append("ProjectEnd")
    (proj / "Project.gpr").write_text("\n".join(lines) + "\n")
    return proj


def _translate(proj: Path, out: Path, *options: str) -> tuple[int, str]:
    import contextlib
    import io

    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        status = cli_main([str(proj), "-o", str(out), *options])
    return status, err.getvalue()


def _import(folder: Path) -> ModuleType:
    return import_package(folder, f"_stubtest_{folder.name}_{next(_serial)}")


def _run(pkg: ModuleType, mode: int) -> tuple[str, int, Simulation]:
    sim = Simulation(capture=True, project="VendorCell")

    def setup() -> None:
        pkg.init()
        pkg.main_mod.Mode = mode

    sim.call(setup)
    status = pkg.main(sim)
    return sim.console.output, status, sim


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> tuple[ModuleType, str, Path]:
    root = tmp_path_factory.mktemp("stubs")
    status, err = _translate(_project(root), root / "out")
    assert status == 0, err
    folder = root / "out" / "vendor_cell"
    return _import(folder), err, folder


def test_protected_calls_are_warned_once_each(built: tuple[ModuleType, str, Path]) -> None:
    _, err, _ = built
    assert " error GPL" not in err
    for name in ("VendorLib.Grip", "VendorLib.Release", "VendorLib.Speed", "Home", "VendorThing"):
        assert err.count(f"warning GPL3501: '{name}' is not declared") == 1, (name, err)
    assert "GPL1406" in err  # the loader's own warning about the skipped file
    assert "0 errors, 6 warnings" in err


def test_path_that_never_calls_a_stub_completes(built: tuple[ModuleType, str, Path]) -> None:
    pkg, _, _ = built
    output, status, sim = _run(pkg, 0)
    assert status == 0
    assert output == "start\nspeed 42\ndone\n"  # a stub variable holds what the program stored
    assert not sim.controller.error_log


def test_called_stub_raises_minus_204_catchable(built: tuple[ModuleType, str, Path]) -> None:
    pkg, _, _ = built
    output, status, _ = _run(pkg, 2)
    assert status == 0
    # the caught exception's Message names the missing procedure (not a bare "*Not implemented*")
    assert output == ("start\ncaught -204\n*Not implemented*: protected source not available: VendorLib.Release\n"
                      "speed 42\ndone\n")


def test_unhandled_stub_error_names_the_missing_procedure(built: tuple[ModuleType, str, Path]) -> None:
    pkg, _, _ = built
    output, status, sim = _run(pkg, 3)
    assert status == 1
    assert output == "start\n"
    log = sim.console.log_text
    assert "-204" in log and "protected source not available: VendorLib.Release" in log, log


def test_project_records_its_stubs(built: tuple[ModuleType, str, Path]) -> None:
    pkg, _, folder = built
    stubs = {s["name"]: (s["kind"], s["provided"]) for s in pkg.PROJECT["stubs"]}
    assert stubs == {
        "Home": ("procedure", False),
        "VendorLib.Grip": ("procedure", False),
        "VendorLib.Release": ("procedure", False),
        "VendorLib.Speed": ("variable", False),
        "VendorThing": ("class", False),
    }
    # readable generated code: the module of the protected library is a module of stubs
    main = (folder / "main_mod.py").read_text()
    assert "vendor_lib.Grip(3)" in main and "vendor_lib.Release()" in main
    assert "_stubs.VendorThing(2)" in main and "_stubs.Home(1)" in main


def test_reading_a_stub_variable_before_any_store_raises(built: tuple[ModuleType, str, Path]) -> None:
    pkg, _, _ = built
    output, status, sim = _run(pkg, 4)
    assert status == 1 and output == "start\n"
    assert "protected source not available: Home" in sim.console.log_text


def test_strict_fails_with_exit_status_1(tmp_path: Path) -> None:
    status, err = _translate(_project(tmp_path), tmp_path / "out", "--strict")
    assert status == 1
    assert "error GPL3501: 'VendorLib.Grip'" in err
    assert not (tmp_path / "out" / "vendor_cell").exists()


def test_unknown_name_without_protected_files_stays_an_error(tmp_path: Path) -> None:
    status, err = _translate(_project(tmp_path, protected=False), tmp_path / "out")
    assert status == 1
    assert "error GPL2001: 'Home' is not declared" in err
    assert "GPL3501" not in err


@pytest.mark.parametrize("start", ["VendorLib.Boot", "Boot"])
def test_start_procedure_in_a_protected_file_says_so(tmp_path: Path, start: str) -> None:
    status, err = _translate(_project(tmp_path, start=start), tmp_path / "out")
    assert status == 1
    assert (f"error GPL2034: the start procedure '{start}' is not in the readable sources: it is "
            "presumably in a protected (.gpp) source, whose code is not available") in err, err
    assert "GPL2019" not in err


def test_start_procedure_missing_without_protected_files_stays_gpl2019(tmp_path: Path) -> None:
    status, err = _translate(_project(tmp_path, MAIN.replace("Home(1)", ""), protected=False, start="Boot"),
                             tmp_path / "out")
    assert status == 1
    assert "error GPL2019: the start procedure 'Boot' is not a Sub of this project" in err, err
    assert "GPL2034" not in err


def test_readable_start_with_parameters_stays_gpl2019_in_a_protected_project(tmp_path: Path) -> None:
    main = MAIN.replace("End Module", "    Public Sub Boot(ByVal n As Integer)\n    End Sub\nEnd Module")
    status, err = _translate(_project(tmp_path, main, start="Boot"), tmp_path / "out")
    assert status == 1
    assert "error GPL2019: the start procedure 'Boot'" in err and "GPL2034" not in err, err


def test_user_stubs_replace_the_generated_ones(tmp_path: Path) -> None:
    stubs = tmp_path / "mystubs"
    stubs.mkdir()
    (stubs / "vendorlib.py").write_text(
        '"""The vendor gripper, simulated."""\n\n\ndef grip(width):\n    return width * 10\n')
    (stubs / "extras.py").write_text("class VendorThing:\n    def __init__(self, n):\n        self.n = n\n\n\n"
                                     "def Home(axis):\n    return None\n")
    status, err = _translate(_project(tmp_path), tmp_path / "out", "--stubs", str(stubs))
    assert status == 0, err
    folder = tmp_path / "out" / "vendor_cell"
    assert (folder / "_user_vendorlib.py").read_text() == (stubs / "vendorlib.py").read_text()
    pkg = _import(folder)
    provided = {s["name"]: s["provided"] for s in pkg.PROJECT["stubs"]}
    assert provided["VendorLib.Grip"] and provided["Home"] and provided["VendorThing"]
    assert not provided["VendorLib.Release"]
    output, status, _ = _run(pkg, 1)
    assert (output, status) == ("start\ngrip 31\nspeed 42\ndone\n", 0)
    output, status, _ = _run(pkg, 4)  # Home and New VendorThing work; Speed was never stored
    assert status == 1 and output == "start\n"


def test_bad_stubs_folder_is_an_error(tmp_path: Path) -> None:
    status, err = _translate(_project(tmp_path), tmp_path / "out", "--stubs", str(tmp_path / "nowhere"))
    assert status == 1 and "error GPL3503: --stubs" in err


BUILTIN = """Module Main
    Public Sub Main()
        Dim loc As Location
        Dim n As Integer
        Try
            n = Controller.SomethingUnknown(1, 2)
        Catch ex As Exception
            Console.WriteLine("caught " & CStr(ex.ErrorCode))
        End Try
        Try
            loc = New Location
            Console.WriteLine(CStr(loc.NoSuchMember))
        Catch ex As Exception
            Console.WriteLine("caught " & CStr(ex.ErrorCode))
        End Try
        If n > 0 Then
            Controller.SomethingUnknown(3, 4)
            Robot.NoSuchMember = 5
        End If
        Console.WriteLine("done")
    End Sub
End Module
"""


def test_unknown_builtin_member_is_a_warning_and_a_stub(tmp_path: Path) -> None:
    proj = tmp_path / "B"
    proj.mkdir()
    (proj / "Main.gpl").write_text(BUILTIN)
    sink = DiagnosticSink()
    out = transpile(proj / "Main.gpl", sink)
    assert out is not None, [d.header() for d in sink]
    warnings = [d.header() for d in sink.warnings if d.code == "GPL3502"]
    assert len(warnings) == 3, warnings  # Controller.SomethingUnknown reported once for two uses
    assert "Controller has no member 'SomethingUnknown'" in warnings[0]
    assert "Location has no member 'NoSuchMember'" in warnings[1]
    assert "Robot has no member 'NoSuchMember'" in warnings[2]
    text = out.files[f"{out.package}/main_mod.py"]
    assert "_stubs.Controller_SomethingUnknown(1, 2)" in text
    assert "_stubs.Location_NoSuchMember(loc)" in text  # an instance member receives its object
    assert "_stubs.set_Robot_NoSuchMember(5)" in text  # an assigned Shared member: its set_ stub


def test_unknown_builtin_member_runs_and_raises_when_used(tmp_path: Path) -> None:
    proj = tmp_path / "B"
    proj.mkdir()
    (proj / "Main.gpl").write_text(BUILTIN)
    status, err = _translate(proj / "Main.gpl", tmp_path / "out")
    assert status == 0, err
    pkg = _import(next((tmp_path / "out").glob("*/__init__.py")).parent)
    sim = Simulation(capture=True, project="B")
    assert pkg.main(sim) == 0, sim.console.log_text
    assert sim.console.output == "caught -204\ncaught -204\ndone\n"


def test_run_prints_a_note_listing_stubs(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    stubs = tmp_path / "s"
    stubs.mkdir()
    (stubs / "vendorlib.py").write_text("def Grip(w):\n    return w\n")
    status = cli_main(["run", str(_project(tmp_path)), "--cache-dir", str(tmp_path / "cache"),
                       "--stubs", str(stubs)])
    captured = capsys.readouterr()
    assert status == 0, captured.err
    assert captured.out == "start\nspeed 42\ndone\n"
    note = [line for line in captured.err.splitlines() if line.startswith("note: ")]
    assert note == ["note: 5 stubs for protected or unsimulated code (4 raise error -204 if used): Home, "
                    "VendorLib.Grip (--stubs), VendorLib.Release, VendorLib.Speed, VendorThing"]
    strict = cli_main(["run", str(_project(tmp_path / "again")), "--cache-dir", str(tmp_path / "cache"),
                       "--strict"])
    assert strict == 1


def test_stub_modules_are_clean_python(tmp_path: Path) -> None:
    import pycodestyle
    from pyflakes.api import check as pyflakes_check
    from pyflakes.reporter import Reporter
    import io

    stubs = tmp_path / "s"
    stubs.mkdir()
    (stubs / "vendorlib.py").write_text("def Grip(w):\n    return w\n")
    for options in ((), ("--stubs", str(stubs))):
        out = tmp_path / f"out{len(options)}"
        status, err = _translate(_project(tmp_path / f"p{len(options)}"), out, *options)
        assert status == 0, err
        folder = out / "vendor_cell"
        generated = [f for f in sorted(folder.glob("*.py")) if not f.name.startswith("_user_")]
        assert {"_stubs.py", "vendor_lib.py"} <= {f.name for f in generated}
        style = pycodestyle.StyleGuide(max_line_length=99, quiet=True)
        assert style.check_files([str(f) for f in generated]).total_errors == 0
        for f in generated:
            warnings = io.StringIO()
            assert pyflakes_check(f.read_text(), str(f), Reporter(warnings, warnings)) == 0, warnings.getvalue()


def _check(*args: str) -> tuple[int, str]:
    import contextlib
    import io

    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        status = cli_main(["check", *args])
    return status, err.getvalue()


def test_check_takes_the_same_stub_options_as_translate_and_run(tmp_path: Path) -> None:
    proj = _project(tmp_path)
    good = tmp_path / "good"
    good.mkdir()
    (good / "vendorlib.py").write_text("def Grip(w):\n    return w\n")
    status, err = _check(str(proj), "--stubs", str(good))
    assert status == 0, err
    assert err.splitlines()[-1] == "checked 1 file: 0 errors, 6 warnings"
    status, err = _check(str(proj), "--stubs", str(tmp_path / "nowhere"))
    assert status == 1 and "error GPL3503: --stubs" in err and "no such folder" in err
    status, err = _check(str(proj), "--stubs", str(good / "vendorlib.py"))  # a file, not a folder
    assert status == 1 and "vendorlib.py: not a folder" in err, err
    broken = tmp_path / "broken"
    broken.mkdir()
    (broken / "vendorlib.py").write_text("def Grip(w)\n    return w\n")  # a missing colon
    status, err = _check(str(proj), "--stubs", str(broken))
    assert status == 1 and "error GPL3503" in err and "vendorlib.py" in err
    status, err = _check(str(proj), "--stubs", str(good), "--strict")
    assert status == 1 and "error GPL3501: 'VendorLib.Grip'" in err


def test_strict_stub_errors_say_what_happens(tmp_path: Path) -> None:
    """With --strict, GPL3501 said "a stub is generated that raises error -204 ... (--strict)",
    but --strict generates nothing: it refuses the project."""
    proj = _project(tmp_path)
    good = tmp_path / "good"
    good.mkdir()
    (good / "vendorlib.py").write_text("def Grip(w):\n    return w\n")
    status, err = _check(str(proj), "--stubs", str(good), "--strict")
    assert status == 1
    lines = {line.split("error GPL3501: ")[1] for line in err.splitlines() if "error GPL3501" in line}
    prefix = "is not declared in the readable sources; assuming the protected code defines it: "
    assert (f"'VendorLib.Grip' {prefix}the --stubs file vendorlib.py implements it, but --strict makes "
            "every stub an error") in lines, err
    assert (f"'VendorLib.Release' {prefix}--strict makes every stub an error, so nothing is generated "
            "for it") in lines, err
    assert "-204" not in err


def test_notebook_cell_loads_a_protected_project_with_user_stubs(tmp_path: Path) -> None:
    from gplrt.lang.errors import GplException
    from gpl2py.notebook import Cell, TranslationWarning

    stubs = tmp_path / "s"
    stubs.mkdir()
    (stubs / "vendorlib.py").write_text("def Grip(width):\n    return width * 10\n")
    proj = _project(tmp_path / "p")
    with pytest.warns(TranslationWarning) as shown:  # the notebook shows each stub's GPL3501
        cell = Cell.load(proj, echo=False, cache_dir=tmp_path / "cache", stubs=stubs)
    assert any("GPL3501: 'VendorLib.Release'" in str(w.message) for w in shown)
    provided = {s["name"]: s["provided"] for s in cell.package.PROJECT["stubs"]}
    assert provided["VendorLib.Grip"] and not provided["VendorLib.Release"]
    cell.init()
    cell.module("Main").Mode = 1
    cell.call("Main.Start")
    assert cell.console == "start\ngrip 31\nspeed 42\ndone\n"
    cell.module("Main").Mode = 3
    with pytest.raises(GplException) as info:
        cell.call("Main.Start")
    assert info.value.ErrorCode == -204 and "VendorLib.Release" in str(info.value)
    with pytest.warns(TranslationWarning) as shown:
        plain = Cell.load(proj, echo=False, cache_dir=tmp_path / "cache")  # no --stubs: its own entry
    assert any("GPL3501: 'VendorLib.Grip'" in str(w.message) for w in shown)
    assert not any(s["provided"] for s in plain.package.PROJECT["stubs"])


def test_stub_warning_names_what_implements_it(tmp_path: Path) -> None:
    """GPL3501 said "a stub is generated that raises -204" even for a name the user's --stubs file
    implements; check, translate and run now say which file does, and keep the -204 wording for
    the names nothing implements."""
    proj = _project(tmp_path)
    good = tmp_path / "good"
    good.mkdir()
    (good / "vendorlib.py").write_text("def Grip(w):\n    return w\n")
    for status, err in (_check(str(proj), "--stubs", str(good)),
                        _translate(proj, tmp_path / "out", "--stubs", str(good))):
        assert status == 0, err
        lines = {line.split("warning GPL3501: ")[1] for line in err.splitlines() if "warning GPL3501" in line}
        prefix = "is not declared in the readable sources; assuming the protected code defines it: "
        assert f"'VendorLib.Grip' {prefix}the --stubs file vendorlib.py implements it" in lines, err
        assert (f"'VendorLib.Release' {prefix}a stub is generated that raises error -204 if the program "
                "uses it") in lines, err

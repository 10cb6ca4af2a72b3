"""What a notebook shows (issue 15, item 1): GPL errors by their GPL line, translation warnings as
Python warnings, one figure per plot, short reprs and HTML tables, variables and I/O as tables,
progress for long calls; and the loader's place (issue 13, item 2: ``gpl2py.notebook``)."""

from __future__ import annotations

import re
import time
import warnings
from pathlib import Path

import pytest

from gpl2py.notebook import Cell, TranslationWarning
from gplrt.builtins import Location, Profile, RefFrame
from gplrt.display import Table
from gplrt.lang.errors import GplException
from gplrt.notebook import GplError, drive
from gpltest import write_project

LINES = [
    "Module Plant",
    "    Public count As Integer",
    "    Public label As String",
    "    Public home As Location",
    "    Public divisor As Integer",
    "",
    "    Public Function Divide(ByVal a As Integer, ByVal b As Integer) As Integer",
    "        count += 1",
    "        Return Inner(a, b)",
    "    End Function",
    "",
    "    Private Function Inner(ByVal a As Integer, ByVal b As Integer) As Integer",
    "        Dim r As Integer",
    "        r = a \\ b  ' the division",
    "        Return r",
    "    End Function",
    "",
    "    Public Sub Crash()",
    "        Dim n As Integer",
    "        n = Divide(1, divisor)",
    "    End Sub",
    "",
    "    Public Sub Main()",
    "        Dim t As New Thread(\"Plant.Crash\", 0, \"crasher\")",
    "        home = New Location",
    "        home.XYZ(300.123456789, 1.0E-13, 200, 0, 90, 180)",
    "        label = \"ready\"",
    "        Signal.DIO(3) = True",
    "        t.Start()",
    "        Console.WriteLine(\"main ends\")",
    "    End Sub",
    "End Module",
]
DIVISION = LINES.index("        r = a \\ b  ' the division") + 1
CALL = LINES.index("        Return Inner(a, b)") + 1
CRASH = LINES.index("        n = Divide(1, divisor)") + 1


@pytest.fixture
def cell(tmp_path: Path) -> Cell:
    proj = write_project(tmp_path, {"Plant.gpl": "\n".join(LINES) + "\n"}, start="Plant.Main", name="Plant")
    return Cell.load(proj, echo=False)


def test_an_unhandled_error_of_call_names_the_gpl_file_line_and_text(cell: Cell) -> None:
    with pytest.raises(GplError) as info:
        cell.call("Plant.Divide", 1, 0)
    err = info.value
    assert isinstance(err, GplException) and err.ErrorCode == -709  # except GplException still works
    text = str(err)
    first, source, *rest = text.splitlines()
    assert first.startswith(f"Plant.gpl:{DIVISION}: error -709: *Division by 0*")
    assert source.strip() == "r = a \\ b  ' the division"
    assert rest[0] == "GPL traceback (most recent call last):"
    assert f"Plant.gpl:{CALL}, in Divide" in text and "Return Inner(a, b)" in text
    assert "gplrt" not in text and "scheduler" not in text
    assert err.__suppress_context__  # the runtime's 40-line traceback is not chained in
    assert err.error.__traceback__ is not None  # but kept, for whoever wants every frame


def test_run_main_raises_the_first_thread_that_ended_unhandled(cell: Cell) -> None:
    with pytest.raises(GplError) as info:
        cell.run_main()
    err = info.value
    assert err.ErrorCode == -709 and err.thread == "crasher"
    assert str(err).startswith(f"Plant.gpl:{DIVISION}: error -709 in thread crasher: *Division by 0*")
    assert f"Plant.gpl:{CRASH}, in Crash" in str(err) and "n = Divide(1, divisor)" in str(err)
    assert cell.console == "main ends\n"
    with pytest.raises(GplError) as again:  # a second run fails again, with its own thread
        cell.run_main()
    assert again.value.error is not err.error and again.value.thread == "crasher"
    cell.module("Plant").divisor = 1  # now the thread ends cleanly: an earlier error is not this run's
    assert cell.run_main() == 0


def test_translation_warnings_are_python_warnings(tmp_path: Path) -> None:
    folder = tmp_path / "NoStart"
    folder.mkdir()
    (folder / "Main.gpl").write_text("Module Main\n    Public Sub Main()\n    End Sub\nEnd Module\n")
    with pytest.warns(TranslationWarning, match=r"Main\.gpl:2:5: warning GPL2032") as caught:
        loaded = Cell.load(folder, echo=False)
    assert caught[0].filename == __file__  # shown at the notebook's own line, not inside gpl2py
    assert loaded.diagnostics and "GPL2032" in loaded.diagnostics[0]
    with warnings.catch_warnings():
        warnings.simplefilter("error", TranslationWarning)
        with pytest.raises(TranslationWarning):
            Cell.load(folder, echo=False)


def test_a_plot_is_not_left_to_pyplot_to_draw_a_second_time(cell: Cell) -> None:
    import matplotlib.pyplot as plt

    cell.call("Plant.Divide", 4, 2)
    before = plt.get_fignums()
    fig = cell.plot_joints()
    fig2 = cell.plot_path()
    assert plt.get_fignums() == before  # Jupyter draws pyplot's open figures at a cell's end
    assert fig.axes and fig2.axes  # and the returned figures are whole


def _readable(text: str) -> None:
    assert " at 0x" not in text, text
    assert not re.search(r"\d\.\d{7,}", text), text  # no 17-digit floats
    assert "[[" not in text, text  # no matrix


def test_reprs_are_short_and_html_is_a_table(cell: Cell) -> None:
    cell.run_for(0.0)
    with pytest.raises(GplError):
        cell.run_main()
    home = cell.get("Plant.home")
    assert repr(home) == "Location(XYZ(300.123, 0, 200, 0, 90, 180))"
    assert "<td>300.123</td>" in home._repr_html_()
    frame = RefFrame()
    frame.Type = 1
    frame.set_PalletMaxIndex(1, 3)
    assert repr(frame).startswith("RefFrame(Type=1 (pallet), Loc=XYZ(0, 0, 0, 0, 0, 0), PalletIndex/Max=1/3")
    profile = Profile()
    profile.Speed = 33.333333333
    assert "Speed=33.3333," in repr(profile) and "<th>Speed</th>" in profile._repr_html_()
    pose = cell.where()
    trace = cell.trace()
    for shown in (home, frame, profile, pose, trace, Location.from_angles([1.0 / 3, 2, 3])):
        _readable(repr(shown))
        html = shown._repr_html_()
        assert html.startswith("<table>")
        _readable(re.sub(r'src="data:image/png;base64,[^"]*"', "", html))
    assert re.fullmatch(r"RobotPose\(t=[\d.]+ s, joints=\([-\d., ]+\), XYZ\([-\d., ]+\)\)", repr(pose)), repr(pose)
    assert re.fullmatch(r"Trace\(5 axes \(Z, Shoulder, Elbow, Wrist, Gripper\), \d+ samples, [\d.]+-[\d.]+ s\)",
                        repr(trace)), repr(trace)
    assert '<img src="data:image/png;base64,' in trace._repr_html_()  # a trace also shows its plot


def test_variables_and_io_state_are_tables(cell: Cell) -> None:
    cell.call("Plant.Divide", 4, 2)
    cell.set_input(10005, True)
    variables = cell.variables()
    assert isinstance(variables, Table) and variables.columns == ("module", "name", "type", "value")
    assert variables.rows == [("Plant", "count", "Integer", "1"), ("Plant", "label", "String", "''"),
                              ("Plant", "home", "Nothing", "None"), ("Plant", "divisor", "Integer", "0")]
    assert "<td>Plant</td><td>count</td><td>Integer</td><td>1</td>" in variables._repr_html_()
    assert repr(variables).splitlines()[:4][-1].split() == ["Plant", "count", "Integer", "1"]  # title, head, rule
    io = cell.io_state()
    assert io.rows == [(10005, "digital input", "on", 1, "0", "outside")]
    with pytest.raises(GplError):
        cell.run_main()
    assert (3, "digital output", "on", 1, "0", "program") in cell.io_state().rows
    assert cell.variables().column("value")[1] == "'ready'"


def test_tables_convert_to_pandas_when_it_is_installed(cell: Cell) -> None:
    table = cell.variables()
    try:
        import pandas  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="pip install pandas"):
            table.to_pandas()
        return
    frame = table.to_pandas()
    assert list(frame.columns) == list(table.columns) and len(frame) == len(table)


def test_a_long_call_shows_its_progress(cell: Cell, capsys: pytest.CaptureFixture[str]) -> None:
    assert drive(cell.sim, time.sleep, 0.3, progress_after=0.0) is None
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("running, 0 GPL threads: 0 s of controller time in ")
    assert err[-1].startswith("done: 0 s of controller time in ")
    assert drive(cell.sim, lambda: 7) == 7  # short: nothing shown
    assert capsys.readouterr().err == ""
    with pytest.raises(ZeroDivisionError):
        drive(cell.sim, lambda: 1 / 0)


def test_the_loader_is_gpl2py_and_the_old_import_says_where_it_went() -> None:
    with pytest.raises(ImportError, match=r"from gpl2py\.notebook import Cell"):
        from gplrt.notebook import Cell as Old  # noqa: F401


def test_a_python_error_in_a_stub_is_reported_at_the_gpl_line_that_called_it(tmp_path: Path) -> None:
    proj = tmp_path / "Vendor"
    proj.mkdir()
    (proj / "VendorLib.gpp").write_bytes(b"'#Protected|\x01\x02 vendor binary")
    (proj / "Main.gpl").write_text("Module Main\n    Public Function Width() As Double\n"
                                   "        Return VendorLib.Grip(3)\n    End Function\nEnd Module\n")
    stubs = tmp_path / "stubs"
    stubs.mkdir()
    (stubs / "vendorlib.py").write_text("def Grip(width):\n    return {}[width]\n")
    with pytest.warns(TranslationWarning):  # GPL1406 (the .gpp is skipped) and GPL3501
        cell = Cell.load(proj, echo=False, stubs=stubs, cache_dir=tmp_path / "cache")
    with pytest.raises(GplError) as info:
        cell.call("Main.Width")
    assert info.value.ErrorCode == -201  # the runtime made the KeyError a GPL error
    assert str(info.value).startswith("Main.gpl:3: error -201: *")
    assert "KeyError: 3" in str(info.value) and "Return VendorLib.Grip(3)" in str(info.value)


class _Shell:
    """What IPython's handler is given: records what it was asked to show."""

    def __init__(self) -> None:
        self.shown: list[tuple[str, str, list[str]]] = []
        self.fallback = 0

    def _showtraceback(self, etype: type, evalue: str, stb: list[str]) -> None:
        self.shown.append((etype.__name__, evalue, stb))

    def showtraceback(self, *args: object, **kwargs: object) -> None:
        self.fallback += 1


def test_ipython_shows_a_gpl_exception_from_generated_code_by_its_gpl_frames(cell: Cell) -> None:
    from gplrt.notebook import _show_gpl_error

    cell.init()
    shell = _Shell()
    try:
        cell.module("Plant").Divide(1, 0)  # the generated function itself, not through call()
    except GplException as exc:
        _show_gpl_error(shell, type(exc), exc, exc.__traceback__)
    name, evalue, stb = shell.shown[0]
    assert name == "GplException" and evalue.startswith(f"Plant.gpl:{DIVISION}: error -709")
    assert stb[0].startswith(f"GplException: Plant.gpl:{DIVISION}: error -709") and "r = a \\ b" in stb[1]
    assert not any("gplrt" in line or "site-packages" in line for line in stb)
    try:
        cell.get("Nowhere.x")  # a notebook typo passes through no GPL code: IPython's own traceback
    except GplException as exc:
        _show_gpl_error(shell, type(exc), exc, exc.__traceback__)
    assert shell.fallback == 1 and len(shell.shown) == 1

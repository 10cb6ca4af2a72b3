"""``As Object`` is rejected with a message that says GPL has no Object type [000 L852-855]."""

from __future__ import annotations

from pathlib import Path

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.transpile import transpile
from gpltest import analyze_text, module_src

NO_OBJECT = ("GPL has no Object type: declare the class of the objects it holds "
             "(late binding is not supported)")


def test_dim_as_object_says_gpl_has_no_object_type(tmp_path: Path) -> None:
    _, sink = analyze_text(tmp_path, module_src("""    Public Sub Main()
        Dim o As Object
    End Sub"""))
    assert [d.header().split("Main.gpl:", 1)[1] for d in sink.sorted()] == [f"3:18: error GPL2035: {NO_OBJECT}"]


def test_object_parameters_results_and_fields_are_rejected_each(tmp_path: Path) -> None:
    _, sink = analyze_text(tmp_path, module_src("""    Private held As object
    Public Function Pick(ByVal a As OBJECT) As Object
        Return a
    End Function
    Public Sub Main()
    End Sub"""))
    codes = [(d.code, d.span.line if d.span else 0) for d in sink.sorted()]
    assert ("GPL2035", 2) in codes and ("GPL2035", 3) in codes
    assert sum(c == "GPL2035" for c, _ in codes) == 3, codes
    assert not any(c == "GPL2003" for c, _ in codes)  # not "unknown type"


def test_a_project_class_named_object_is_still_a_type(tmp_path: Path) -> None:
    _, sink = analyze_text(tmp_path, module_src("""    Public Class Object
        Public n As Integer
    End Class
    Public Sub Main()
        Dim o As New Object
        o.n = 3
    End Sub"""))
    assert [d.header() for d in sink.sorted()] == []


def test_object_is_not_taken_for_a_protected_class(tmp_path: Path) -> None:
    """In a project with protected files an unknown type becomes a stub class; Object does not."""
    proj = tmp_path / "P"
    proj.mkdir()
    (proj / "Main.gpl").write_text(module_src("""    Public Sub Main()
        Dim o As Object
        Dim v As VendorThing
    End Sub"""))
    (proj / "Lib.gpp").write_bytes(b"'#Protected|\x00\x01binary")
    (proj / "Project.gpr").write_text('ProjectBegin\nProjectName="P"\nProjectStart="Main"\n'
                                      'ProjectSource="Main.gpl"\nProjectSource="Lib.gpp"\nProjectEnd\n')
    sink = DiagnosticSink()
    assert transpile(str(proj), sink) is None
    codes = [d.code for d in sink.sorted()]
    assert codes.count("GPL2035") == 1 and "GPL3501" in codes, codes  # VendorThing is the stub
    assert not any("'Object'" in d.message for d in sink), [d.header() for d in sink]

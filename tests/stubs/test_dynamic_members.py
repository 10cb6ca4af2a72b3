"""Members of values of unknown type reach GPL members only (issue 12, item 3; docs/security.md).

In a project with protected code, a stub's result or a value stored in a protected module's
variable has no type the transpiler knows, so ``obj.Name`` cannot be checked at translation time.
It must still never become a raw Python attribute: ``X.__reduce_ex__(2).__getitem__(0)
.__globals__`` would reach ``os.system``.  The runtime admits the Public members of GPL classes, the
GPL members of runtime objects and the public names of the user's own stubs, and nothing else.
"""

from __future__ import annotations

import contextlib
import io
import itertools
from pathlib import Path
from types import ModuleType

import pytest

from gpl2py.cli import main as cli_main
from gpl2py.run import import_package
from gplrt.lang.errors import GplException
from gplrt.lang.members import get_member, set_member
from gplrt.sim import Simulation

_serial = itertools.count()

ATTACK = """Module Main
    Public Sub Start()
        Try
            VendorLib.Anything = 5
            VendorLib.Anything.__reduce_ex__(2).__getitem__(0).__globals__.get("__builtins__").get("__import__")("os").system("touch PWNED")
            Console.WriteLine("escaped")
        Catch ex As Exception
            Console.WriteLine("caught " & CStr(ex.ErrorCode))
        End Try
        Try
            Console.WriteLine(VendorLib.Anything.__class__.__name__)
        Catch ex As Exception
            Console.WriteLine("caught " & CStr(ex.ErrorCode))
        End Try
    End Sub
End Module
"""

LEGIT = """Module Main
    Public Sub Start()
        Dim s As New Spot
        Dim w As New Location
        s.Label = "home"
        VendorLib.Saved = s
        Console.WriteLine(VendorLib.Saved.label & " " & CStr(VendorLib.Saved.Twice(4)))
        VendorLib.Saved.Label = "away"
        Console.WriteLine(s.Label)
        w.X = 1
        w.Z = 3
        VendorLib.Where = w
        Console.WriteLine(CStr(VendorLib.Where.x + VendorLib.Where.Z))
        Try
            Console.WriteLine(VendorLib.Saved.hidden)
        Catch ex As Exception
            Console.WriteLine("private " & CStr(ex.ErrorCode))
        End Try
        Try
            VendorLib.Where.Dist = 1
        Catch ex As Exception
            Console.WriteLine("where " & CStr(ex.ErrorCode))
        End Try
        VendorLib.Saved = Nothing
        Try
            Console.WriteLine(VendorLib.Saved.Label)
        Catch ex As Exception
            Console.WriteLine("nothing " & CStr(ex.ErrorCode))
        End Try
    End Sub
End Module

Class Spot
    Public Label As String
    Private hidden As Integer
    Public Function Twice(ByVal n As Integer) As Integer
        Return 2 * n
    End Function
End Class
"""


def _build(root: Path, main: str, stubs: Path | None = None) -> ModuleType:
    proj = root / "Cell"
    proj.mkdir()
    (proj / "Main.gpl").write_text(main)
    (proj / "VendorLib.gpp").write_bytes(b"'#Protected|\x00\x93\xfa\x01binary vendor code\xff")
    (proj / "Project.gpr").write_text('ProjectBegin\nProjectName="Cell"\nProjectStart="Main.Start"\n'
                                      'ProjectSource="Main.gpl"\nProjectSource="VendorLib.gpp"\nProjectEnd\n')
    err = io.StringIO()
    options = ["--stubs", str(stubs)] if stubs is not None else []
    with contextlib.redirect_stderr(err):
        status = cli_main([str(proj), "-o", str(root / "out"), *options])
    assert status == 0, err.getvalue()
    return import_package(root / "out" / "cell", f"_dynmem_{next(_serial)}")


def _run(pkg: ModuleType) -> str:
    sim = Simulation(capture=True, project="Cell")
    assert pkg.main(sim) == 0, sim.console.output
    return sim.console.output


def test_python_internals_are_out_of_reach(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    pkg = _build(tmp_path, ATTACK)
    assert _run(pkg) == "caught -729\ncaught -729\n"
    assert not (tmp_path / "PWNED").exists()
    assert "__reduce_ex__" not in "".join(
        line for line in (tmp_path / "out" / "cell" / "main_mod.py").read_text().splitlines()
        if not line.lstrip().startswith("#") and "get_member" not in line)


def test_gpl_members_of_unknown_values_work(tmp_path: Path) -> None:
    pkg = _build(tmp_path, LEGIT)
    assert _run(pkg) == "home 8\naway\n4\nprivate -729\nwhere -729\nnothing -757\n"


def test_user_stub_objects_show_their_public_names(tmp_path: Path) -> None:
    stubs = tmp_path / "stubs"
    stubs.mkdir()
    (stubs / "vendorlib.py").write_text(
        "class _Gripper:\n"
        "    def __init__(self):\n"
        "        self.width = 12.5\n"
        "        self._secret = 'no'\n\n\n"
        "def MakeGripper():\n"
        "    return _Gripper()\n")
    main = """Module Main
    Public Sub Start()
        Console.WriteLine(CStr(VendorLib.MakeGripper().Width))
        Try
            Console.WriteLine(VendorLib.MakeGripper()._secret)
        Catch ex As Exception
            Console.WriteLine("caught " & CStr(ex.ErrorCode))
        End Try
    End Sub
End Module
"""
    pkg = _build(tmp_path, main, stubs)
    assert _run(pkg) == "12.5\ncaught -729\n"


@pytest.mark.parametrize("value", [5, "text", 2.5, True, print, Path, io, (lambda: 0)])
@pytest.mark.parametrize("name", ["__class__", "__globals__", "real", "upper", "_secret", "gi_frame", "Name"])
def test_python_objects_have_no_gpl_members(value: object, name: str) -> None:
    with pytest.raises(GplException) as info:
        get_member(value, name)
    assert info.value.ErrorCode == -729
    with pytest.raises(GplException) as info:
        set_member(value, name, 1)
    assert info.value.ErrorCode == -729

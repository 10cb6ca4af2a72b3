"""Public names used unqualified (§6.4) are looked up in an index built once per project.

Every name that is not local, not a member of the enclosing class or module and not a module asks
``ProjectSyms.public_members`` -- each ``Console``, ``CInt`` or ``Math`` too.  Scanning every
module per question made the analysis of a project of thousands of files grow with the square of
its size (issue 13, item 3).  The index must give exactly the answers of that scan, in its order
(the ambiguity message lists modules in project order), and follow the member tables when the
collector changes them."""

from __future__ import annotations

from pathlib import Path

import pytest

from gpl2py import messages as M
from gpl2py.gpl.semantics.info import CallInfo
from gpl2py.gpl.semantics.symbols import ClassSym, ProjectSyms, PublicName
from gpltest import analyze_text


def _scan(project: ProjectSyms, name: str) -> list[PublicName]:
    """The rule as a scan of every module and top-level class (the oracle)."""
    key = name.lower()
    out = []
    for mod in project.module_list:
        m = mod.members.get(key)
        if m is not None and getattr(m, "public", False):
            out.append(PublicName(mod.name, mod, m))
    top = project.top
    if top is not None:
        cls = top.members.get(key)
        if isinstance(cls, ClassSym):
            out.append(PublicName(cls.name, top, cls))
        for c in top.members.values():
            if not isinstance(c, ClassSym) or not c.public:
                continue
            m = c.members.get(key)
            if m is not None and not isinstance(m, ClassSym) and getattr(m, "public", False) \
                    and (getattr(m, "shared", False) or getattr(m, "const", False)):
                out.append(PublicName(c.name, top, m))
    return out


PROJECT = """Module Alpha
    Public Speed As Double
    Private hidden As Integer
    Public Const LIMIT As Integer = 10
    Public Sub Go(ByVal n As Integer)
    End Sub
    Public Sub Go(ByVal s As String)
    End Sub
    Private Sub Secret()
    End Sub
    Public Class Gripper
        Public Width As Double
    End Class
End Module

Module Beta
    Public Speed As Double
    Public Function Twice(ByVal v As Integer) As Integer
        Return v * 2
    End Function
    Sub Use()
        Console.WriteLine(CStr(Twice(LIMIT)))
        Go(1)
    End Sub
End Module

Class Station
    Public Shared count As Integer
    Public Const STA_MAX As Integer = 4
    Public name As String
    Private Shared secret As Integer
    Public Shared Sub LoadFile()
    End Sub
End Class
"""


def test_the_index_answers_as_a_scan_of_every_module(tmp_path: Path) -> None:
    model, _ = analyze_text(tmp_path, PROJECT)
    project = model.project
    names = {key for mod in [*project.module_list, project.top] if mod is not None for key in mod.members}
    names |= {key for c in project.classes for key in c.members}
    names |= {"console", "cint", "nothing_at_all"}
    assert {"speed", "limit", "go", "twice", "station", "count", "sta_max", "name", "secret", "loadfile",
            "hidden", "gripper"} <= names
    for name in sorted(names):
        assert list(project.public_members(name)) == _scan(project, name), name
        assert list(project.public_members(name.upper())) == _scan(project, name), name
    assert [p.where for p in project.public_members("Speed")] == ["Alpha", "Beta"]


def test_an_ambiguous_name_still_lists_every_module(tmp_path: Path) -> None:
    gamma = "Module Gamma\n    Sub Use()\n        Speed = 2\n    End Sub\nEnd Module\n"
    _, sink = analyze_text(tmp_path, PROJECT + gamma)
    ambiguous = [d for d in sink if d.code == M.AMBIGUOUS_NAME.code]
    assert len(ambiguous) == 1 and "Alpha, Beta" in ambiguous[0].message


def test_the_index_is_built_once_per_project(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    modules = 60
    text = "\n".join(
        f"Module M{i}\n    Public Function F{i}(ByVal v As Integer) As Integer\n"
        f"        Console.WriteLine(CStr(v) & CStr(Math.Sqrt(v)))\n"
        f"        Return F{(i + 1) % modules}(v - 1)\n    End Function\nEnd Module\n" for i in range(modules))
    builds = []
    real = ProjectSyms._index_public

    def counted(self: ProjectSyms) -> object:
        builds.append(len(self.module_list))
        return real(self)

    monkeypatch.setattr(ProjectSyms, "_index_public", counted)
    model, sink = analyze_text(tmp_path, text)
    assert not sink.has_errors(), [d.header() for d in sink]
    assert builds == [modules]  # once, after every module was collected
    calls = [e for e, info in model.info.items() if isinstance(info, CallInfo)]
    assert len(calls) >= modules  # each F{i+1} was found through the index


def test_the_index_follows_an_overload_set_that_collapses(tmp_path: Path) -> None:
    """Two overloads with the same parameter types are one error and one procedure again, after
    the types (and the index, through a type named in another module) were resolved."""
    text = """Module Lib
    Public Class Part
        Public Id As Integer
    End Class
    Public Sub Store(ByVal n As Integer)
    End Sub
    Public Sub Store(ByVal m As Integer)
    End Sub
End Module

Module User
    Dim p As Part
    Sub Use()
        Store(1)
    End Sub
End Module
"""
    model, sink = analyze_text(tmp_path, text)
    assert [d.code for d in sink if d.severity.name == "ERROR"] == [M.DUPLICATE_DECLARATION.code]
    (store,) = model.project.public_members("store")
    assert store.member is model.project.modules["lib"].members["store"]
    assert type(store.member).__name__ == "ProcSym"

"""Strings meeting Nothing (issue 11, "Real GPL code", item 4; docs/design/real-code.md).

Real code tests ``s Is Nothing`` / ``Not s Is Nothing`` on Strings and writes
``Dim s As String = Nothing``.  gpl2py reads Nothing beside a String as the empty String, so every
place they meet type-checks as a String operation; the rest of the ``Is`` and Nothing rules stay.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from gpltest import analyze_text

DECLS = """
    Class Item
        Public name As String
        Public names(3) As String
    End Class
    Function Label(ByVal s As String) As String
        Return s
    End Function
    Sub Fill(ByRef s As String)
        s = "x"
    End Sub
    Function NoText() As String
        Return Nothing
    End Function
    Sub Opt(Optional ByVal s As String = Nothing)
    End Sub
"""


def _module(body: str) -> str:
    return f"Module Main\n{DECLS}\n    Public Sub Main()\n{body}\n    End Sub\nEnd Module\n"


def test_every_place_a_string_meets_nothing_is_accepted(tmp_path: Path) -> None:
    _, sink = analyze_text(tmp_path, _module("""
        Dim s As String = Nothing
        Dim arr(2) As String
        Dim it As New Item
        Dim b As Boolean
        s = Nothing
        arr(1) = Nothing
        it.name = Nothing
        it.names(0) = Nothing
        b = s Is Nothing
        b = Not s Is Nothing
        b = Nothing Is s
        b = arr(1) Is Nothing
        b = Not it.names(0) Is Nothing
        b = it.name Is Nothing OrElse (Not Label(s) Is Nothing)
        b = s = Nothing
        b = Nothing <> s
        b = (s < Nothing)
        s = s & Nothing
        s = Label(Nothing)
        Opt(Nothing)
        If s Is Nothing Then s = NoText()"""))
    assert [d.header() for d in sink] == []


def test_a_nothing_passed_to_a_byref_string_is_a_temporary_like_any_value(tmp_path: Path) -> None:
    _, sink = analyze_text(tmp_path, _module("        Fill(Nothing)"))
    assert [d.code for d in sink] == ["GPL2020"]  # the usual warning: nothing receives the store


@pytest.mark.parametrize("line, code", [
    ("Dim i As Integer = Nothing", "GPL2005"),  # Nothing is a String only beside a String
    ("b = (n Is Nothing)", "GPL2014"),  # Is on a number
    ("b = (s Is s)", "GPL2014"),  # Is between two Strings: not a test for Nothing
    ("b = (n = Nothing)", "GPL2014"),  # = between a number and Nothing
    ("n = s + Nothing", "GPL2014"),  # + is numeric when one side is not a String (§4.4)
])
def test_nothing_beside_anything_else_keeps_its_errors(tmp_path: Path, line: str, code: str) -> None:
    _, sink = analyze_text(tmp_path, _module(
        f"        Dim s As String\n        Dim n As Integer\n        Dim b As Boolean\n        {line}"))
    assert [d.code for d in sink.errors] == [code]


def test_is_nothing_on_a_value_of_unknown_type_is_accepted(tmp_path: Path) -> None:
    """A stub's result may be an object or a String: ``x Is Nothing`` is left to the runtime."""
    _, sink = analyze_text(tmp_path, _module("""
        Dim loc As New Location
        Dim b As Boolean
        b = loc.NoSuchMember Is Nothing
        b = Not Controller.NoSuchThing(1) Is Nothing
        b = Nothing Is loc.NoSuchMember
        b = loc.NoSuchMember Is loc"""))
    assert [d.code for d in sink.errors] == []
    assert {d.code for d in sink} == {"GPL3502"}  # the stubs' own warnings

"""Catalogue annotations: ``Any`` means "any value, the runtime converts" (not the error type, which
would hide mistakes in the argument); ``list[T]`` and ``GplArray[T]`` are GPL arrays."""

from __future__ import annotations

import types as pytypes
from pathlib import Path
from typing import Any

from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.catalogue import load_catalogue
from gpl2py.gpl.semantics.catalogue_gen import build_catalogue
from gplrt.lang.arrays import GplArray
from gplrt.lang.gpltypes import Integer, String
from gpltest import analyze_text


class Gadget:
    def Mix(self, value: Any, names: list[String]) -> GplArray[Integer]:  # type: ignore[type-arg]
        raise NotImplementedError

    def Anything(self) -> Any:
        raise NotImplementedError


def test_any_and_list_annotations_become_any_and_array_types() -> None:
    module = pytypes.ModuleType("fake")
    module.Gadget = Gadget  # type: ignore[attr-defined]
    module.CLASSES = {"Gadget": "Gadget"}  # type: ignore[attr-defined]
    mix = build_catalogue(module).lookup_class("gadget").member("mix")  # type: ignore[union-attr]
    assert mix is not None
    assert mix.params[0].type is t.ANY
    assert mix.params[1].type == t.ArrayType(t.STRING)
    assert mix.result == t.ArrayType(t.INTEGER)
    anything = build_catalogue(module).lookup_class("gadget").member("anything")  # type: ignore[union-attr]
    assert anything is not None and anything.result is t.ANY


def test_runtime_any_parameters_are_any_not_error() -> None:
    cat = load_catalogue()
    assert cat.lookup_function("CInt").params[0].type is t.ANY  # type: ignore[union-attr]
    assert cat.lookup_function("Chr").params[0].type is t.ANY  # type: ignore[union-attr]
    assert cat.lookup_function("Format").params[0].type is t.ANY  # type: ignore[union-attr]
    write = cat.lookup_class("Console").member("Write")  # type: ignore[union-attr]
    assert write is not None and write.params[0].type is t.ANY


def test_mistakes_in_any_arguments_are_still_reported(tmp_path: Path) -> None:
    _, sink = analyze_text(tmp_path, """Module Main
    Sub Report()
    End Sub
    Public Sub Main()
        Dim n As Integer
        n = CInt(Report())
        n = CInt(nowhere)
        Console.WriteLine(Report())
        n = CInt()
        Console.WriteLine(Format(1.5, "0.0") & Chr(65) & CStr(CInt("12")))
    End Sub
End Module
""")
    got = [(d.span.line, d.code) for d in sink.sorted() if d.span is not None]
    assert got == [(6, "GPL2009"), (7, "GPL2001"), (8, "GPL2009"), (9, "GPL2004")], [d.header() for d in sink]


def test_any_result_converts_at_run_time(tmp_path: Path) -> None:
    from gpltest import run_gpl

    result = run_gpl(tmp_path, """Module Main
    Public Sub Main()
        Dim n As Integer
        Dim s As String
        n = FromBitString(ToBitString(258, Integer, False), Integer, False) + 1
        s = n
        Console.WriteLine(s & " " & CStr(n * 2))
    End Sub
End Module
""")
    assert result.output == "259 518\n", result.log

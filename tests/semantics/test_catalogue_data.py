"""The transpiler reads the built-in catalogue from a data module; the runtime stays its source.

``gpl2py/gpl/semantics/builtins_data.py`` is generated from ``gplrt.builtins`` by
``python -m gpl2py.gpl.semantics.catalogue_gen``.  These tests fail when the runtime changed and the
data module was not regenerated, and when the data module loses anything the runtime declares."""

from __future__ import annotations

import difflib
import importlib
import types as pytypes
import typing
from pathlib import Path
from typing import Any

import pytest

from gpl2py.gpl.semantics import catalogue_gen
from gpl2py.gpl.semantics.catalogue import REGENERATE, Catalogue, catalogue_from_data, load_catalogue
from gplrt.lang.gpltypes import Integer, String


def _runtime() -> Catalogue:
    return catalogue_gen.build_catalogue(importlib.import_module("gplrt.builtins"))


def test_the_data_module_is_what_the_runtime_declares_now() -> None:
    path = catalogue_gen.data_path()
    committed = path.read_text(encoding="utf-8")
    fresh = catalogue_gen.generate()
    if committed != fresh:
        diff = list(difflib.unified_diff(committed.splitlines(), fresh.splitlines(), "committed", "runtime",
                                         lineterm="", n=0))
        pytest.fail(f"{path.name} is out of date with the runtime's built-ins: run `{REGENERATE}` and "
                    "commit the result.\n" + "\n".join(diff[:40]))


def test_the_transpiler_sees_exactly_the_runtimes_catalogue() -> None:
    # repr, not ==: ClassType compares by key only, and the spelling and built-in flag matter too
    assert repr(load_catalogue()) == repr(_runtime())


def test_every_convention_survives_the_data_module() -> None:
    """The runtime uses every convention of CATALOGUE.md, and each one comes back from the rows."""
    cat = _runtime()
    back = catalogue_from_data(catalogue_gen.catalogue_data(cat))
    assert repr(back) == repr(cat)
    members = [m for c in [*cat.classes.values(), *cat.type_members.values()] for m in c.members.values()]
    params = [p for m in members for f in (*m.call_forms, *m.set_forms) for p in f]
    assert any(len(m.set_forms) > 2 for m in members)  # typing.overload (of a set_M companion)
    assert any(len(f) > 1 for m in members for f in m.set_forms)  # set_M(args, value)
    assert any(m.kind == "property" and m.settable for m in members)
    assert any(m.action for m in members)  # do_M
    assert any(not m.simulated for m in members)  # @not_simulated
    assert any(m.shared for m in members) and any(not m.shared for m in members)
    assert any(p.byref for p in params)  # Ref[T]
    assert any(p.optional and p.default not in (None, 0) for p in params)
    assert any(c.constructor for c in cat.classes.values())
    assert any(c.is_global for c in cat.classes.values())
    assert cat.constants and cat.functions and cat.type_members
    assert {f.module for f in cat.functions.values()} - {"gplrt.builtins"}


class Camera:
    """Call forms declared with typing.overload: the runtime has none today, the rows hold them."""

    @typing.overload
    def Result(self) -> Integer: ...

    @typing.overload
    def Result(self, tool: String, index: Integer = Integer(1)) -> Integer: ...

    def Result(self, *args: Any) -> Integer:
        raise NotImplementedError


def test_call_overloads_survive_the_data_module() -> None:
    module = pytypes.ModuleType("camera")
    module.Camera = Camera  # type: ignore[attr-defined]
    module.CLASSES = {"Camera": "Camera"}  # type: ignore[attr-defined]
    cat = catalogue_gen.build_catalogue(module)
    result = cat.lookup_class("camera").member("result")  # type: ignore[union-attr]
    assert result is not None and len(result.overloads) == 2
    back = catalogue_from_data(catalogue_gen.catalogue_data(cat))
    assert repr(back) == repr(cat)


def test_functions_record_the_module_that_defines_them() -> None:
    for f in load_catalogue().functions.values():
        assert getattr(importlib.import_module(f.module), f.python_name) is \
            getattr(importlib.import_module("gplrt.builtins"), f.python_name), f.name


def test_a_default_the_data_module_cannot_hold_is_refused() -> None:
    class Odd:
        def Try(self, where: object = Path("/")) -> None:
            raise NotImplementedError

    module = pytypes.ModuleType("odd")
    module.Odd = Odd  # type: ignore[attr-defined]
    module.CLASSES = {"Odd": "Odd"}  # type: ignore[attr-defined]
    with pytest.raises(catalogue_gen.CatalogueError, match=r"default of Odd.Try\(where\)"):
        catalogue_gen.catalogue_data(catalogue_gen.build_catalogue(module))


def test_the_command_checks_and_rewrites_the_data_module(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                         capsys: pytest.CaptureFixture[str]) -> None:
    stale = tmp_path / "builtins_data.py"
    stale.write_text("CATALOGUE = {}\n", encoding="utf-8")
    monkeypatch.setattr(catalogue_gen, "data_path", lambda: stale)
    assert catalogue_gen.main(["--check"]) == 1
    assert REGENERATE in capsys.readouterr().err
    assert catalogue_gen.main([]) == 0
    assert stale.read_text(encoding="utf-8") == catalogue_gen.generate()
    assert catalogue_gen.main(["--check"]) == 0

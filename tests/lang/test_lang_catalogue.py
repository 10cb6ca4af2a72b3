"""The lang modules follow CATALOGUE.md: GPL members are PascalCase, annotations resolve to GPL types."""

from __future__ import annotations

import inspect
import typing

import pytest

from gplrt.lang import catalogue
from gplrt.lang.arrays import GplArray
from gplrt.lang.gpltypes import Double, String
from gplrt.lang.strings import StringMembers


def _callables():
    for name, fn in catalogue.FUNCTIONS.items():
        yield name, fn
    for cls_name, obj in {**catalogue.GLOBAL_CLASSES, **catalogue.TYPE_MEMBERS}.items():
        cls = obj if isinstance(obj, type) else type(obj)
        for name, raw in vars(cls).items():
            if not name[:1].isupper():
                continue
            func = raw.fget if isinstance(raw, property) else getattr(raw, "__func__", raw)
            yield f"{cls_name}.{name}", func


@pytest.mark.parametrize(("name", "func"), list(_callables()))
def test_annotations_resolve(name, func) -> None:
    hints = typing.get_type_hints(func)
    assert "return" in hints, name  # a Sub says ``-> None``: the catalogue reads it as Void
    assert inspect.signature(func).parameters.keys() <= hints.keys() | {"self", "cls"}, name


def test_function_names_are_gpl_spelling() -> None:
    assert set(catalogue.FUNCTIONS) >= {"CInt", "CStr", "Mid", "InStr", "Format", "Chr", "Asc", "Hex", "Fix", "Int"}
    assert not set(catalogue.FUNCTIONS) & set(catalogue.VB_EXTRAS)


def test_split_annotation_names_the_element_type() -> None:
    ret = typing.get_type_hints(StringMembers.Split)["return"]
    assert typing.get_origin(ret) is GplArray and typing.get_args(ret) == (String,)


def test_math_constants_are_double_properties() -> None:
    math_cls = type(catalogue.GLOBAL_CLASSES["Math"])
    assert isinstance(vars(math_cls)["PI"], property)
    assert typing.get_type_hints(vars(math_cls)["PI"].fget)["return"] is Double

"""Arrays handed back to GPL code through ByRef parameters (Modbus reads, GetFiles, ...).

Generated code represents GPL arrays as ``gplrt.lang.arrays.GplArray`` (docs/design/lowering.md),
written in parallel with this package.  This module is the single place that builds one, so the
I/O classes do not depend on its constructor: it uses ``GplArray.from_list`` when that exists and
falls back to a plain ``list`` (indexable from 0 like a GPL array) otherwise.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any


def make_array(values: Iterable[Any], element_type: object = None) -> Any:
    """A one-dimensional GPL array of ``element_type`` holding ``values`` (index 0 = first)."""
    items = list(values)
    try:
        from gplrt.lang.arrays import GplArray  # type: ignore[import-not-found]
    except ImportError:
        return items
    factory = getattr(GplArray, "from_list", None)
    return factory(items, element_type) if factory is not None else items


def to_list(values: Any) -> list[Any]:
    """The elements of a GPL array (or any iterable) as a Python list."""
    if values is None:
        return []
    return list(values)

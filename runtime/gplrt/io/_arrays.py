"""Arrays handed back to GPL code through ByRef parameters (Modbus reads, GetFiles, ...).

Generated code represents GPL arrays as ``gplrt.lang.arrays.GplArray`` (docs/design/lowering.md);
this module is the single place the I/O classes build one.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from gplrt.lang.arrays import GplArray


def make_array(values: Iterable[Any], element_type: object = None) -> Any:
    """A one-dimensional GPL array of ``element_type`` holding ``values`` (index 0 = first): a
    ``GplArray``, typed Any because the members that return one declare GPL array types."""
    return GplArray.from_list(values, element_type)


def to_list(values: Any) -> list[Any]:
    """The elements of a GPL array (or any iterable) as a Python list."""
    if values is None:
        return []
    return list(values)

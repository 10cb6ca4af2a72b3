"""GPL arrays (spec gpl-language.md §7, §14.6).

* Lower bound always 0; the declared number is the **upper bound**: ``Dim a(3)`` has 4 elements
  [000 L332-336].  Rank 1 to 4 [000 L328].  An upper bound of -1 gives an empty dimension (as in
  VB); below -1 is -707 Value out-of-range.
* New elements hold the element type's default: 0 (integer types), 0.0 (Single/Double), False,
  "" (String [000 L429]) and ``None`` (Nothing) for objects [000 L376-377].
* Element access is bounds-checked.  An index outside 0..upper bound -- **negative ones included,
  never Python's wrap-around** -- is **-767 Invalid array index**; the wrong number of subscripts is
  **-766 Array index mismatch** (the controller's texts for exactly these faults).  Non-integral
  subscripts use the Integer conversion (round half away from zero, §7 recommendation).
* Generated code writes ``a[i]`` and ``a[i, j]``.  Rank 1 and 2 have specialised classes whose
  ``__getitem__`` is one type test, one comparison and one list access; ranks 3-4 share a generic
  class.  Data is one flat list in row-major order (strides), so ``For Each`` / Python iteration
  yields elements in that order.
* Arrays are references: assignment shares the object (``CountB = CountA`` [000 L390-398]).
  ``ReDim`` (``redim``) allocates a fresh array of defaults and keeps the rank (AMB-17).
  ``ReDim Preserve`` (``redim_preserve``), which the manuals never mention but real code uses,
  also allocates a fresh array and copies into it every element that still fits
  (docs/design/real-code.md).
* Element stores do **not** convert the value: the lowering converts to the element type before
  storing (it knows the static types), which keeps ``a[i] = v`` as cheap as a list store.
* GPL members: ``GetUpperBound(dim)`` (dimension numbered from 0, AMB-18), ``Length`` (all
  elements), ``Rank``.  The manuals list no ``Clone`` for arrays, so there is none.
"""

from __future__ import annotations

import types
from collections.abc import Iterable, Iterator
from typing import Any, Final

from gplrt.lang.conversions import to_int32
from gplrt.lang.errors import (
    ARITHMETIC_OVERFLOW,
    ARRAY_INDEX_MISMATCH,
    INVALID_ARRAY_INDEX,
    VALUE_OUT_OF_RANGE,
    GplException,
)
from gplrt.lang.gpltypes import Boolean, Byte, Double, Integer, Short, Single, String


__all__ = ["GplArray", "redim", "redim_preserve", "default_value", "ARRAY_INDEX_MISMATCH", "INVALID_ARRAY_INDEX"]

_DEFAULTS: Final[dict[object, object]] = {
    Integer: 0,
    Short: 0,
    Byte: 0,
    Single: 0.0,
    Double: 0.0,
    Boolean: False,
    String: "",
    int: 0,
    float: 0.0,
    bool: False,
    str: "",
    "integer": 0,
    "short": 0,
    "byte": 0,
    "single": 0.0,
    "double": 0.0,
    "boolean": False,
    "string": "",
}


def default_value(element_type: object) -> object:
    """The value of a new variable or element of ``element_type`` (``None`` for objects)."""
    if isinstance(element_type, str):
        return _DEFAULTS.get(element_type.lower())
    return _DEFAULTS.get(element_type)


def _bad_index(detail: str) -> GplException:
    return GplException(INVALID_ARRAY_INDEX, detail=detail)


class GplArray:
    """A GPL array: ``GplArray(Integer, 3)`` is ``Dim a(3) As Integer``; ``GplArray(Double, 2, 3)``
    is ``Dim m(2, 3) As Double``.

    ``element_type`` is a gpltypes type (``Integer``, ``String``, ...), its name, or a class for
    object arrays (elements start as ``None``).  Constructing ``GplArray`` returns an instance of
    the subclass specialised for the rank.
    """

    __slots__ = ("_data", "_ub", "_etype", "_n1", "_strides")

    # ``GplArray[String]`` in annotations: the catalogue reads the element type from it.
    __class_getitem__ = classmethod(types.GenericAlias)

    _data: list[Any]
    _ub: tuple[int, ...]
    _etype: object
    _n1: int
    _strides: tuple[int, ...]

    def __new__(cls, element_type: object = None, *upper_bounds: Any) -> GplArray:
        rank = len(upper_bounds)
        if not 1 <= rank <= 4:
            raise GplException(ARRAY_INDEX_MISMATCH, detail=f"arrays have 1 to 4 dimensions, not {rank}")
        ub = tuple(to_int32(b) for b in upper_bounds)
        for b in ub:
            if b < -1:
                raise GplException(VALUE_OUT_OF_RANGE, detail=f"array upper bound {b}")
        if cls is GplArray:
            cls = _Array1 if rank == 1 else _Array2 if rank == 2 else _ArrayN
        self = object.__new__(cls)
        count = 1
        strides = []
        for b in reversed(ub):
            strides.append(count)
            count *= b + 1
        self._strides = tuple(reversed(strides))
        self._ub = ub
        self._etype = element_type
        self._n1 = ub[-1] + 1
        self._data = [default_value(element_type)] * count
        return self

    @classmethod
    def from_list(cls, values: Iterable[Any], element_type: object = None) -> GplArray:
        """A 1-D array holding ``values`` (used by built-ins that return arrays, e.g. Split)."""
        items = list(values)
        arr = GplArray(element_type, len(items) - 1)
        arr._data[:] = items
        return arr

    # -- GPL members -------------------------------------------------------------------------------

    def GetUpperBound(self, dimension: Integer) -> Integer:
        """Upper bound of ``dimension`` (0 = first, AMB-18); a bad dimension is -707."""
        d = to_int32(dimension)
        if not 0 <= d < len(self._ub):
            raise GplException(VALUE_OUT_OF_RANGE, detail=f"dimension {d} of a rank-{len(self._ub)} array")
        return self._ub[d]  # type: ignore[return-value]

    @property
    def Length(self) -> Integer:
        """Number of elements in all dimensions (``Dim a(3)`` -> 4, ``Dim m(2, 3)`` -> 12)."""
        return len(self._data)  # type: ignore[return-value]

    @property
    def Rank(self) -> Integer:
        """Number of dimensions."""
        return len(self._ub)  # type: ignore[return-value]

    # -- Python side --------------------------------------------------------------------------------

    @property
    def element_type(self) -> object:
        """The declared element type (used by ``redim``)."""
        return self._etype

    @property
    def upper_bounds(self) -> tuple[int, ...]:
        return self._ub

    def to_list(self) -> list[Any]:
        """A copy of the elements in row-major order."""
        return list(self._data)

    def __iter__(self) -> Iterator[Any]:
        """``For Each`` order: row-major over the flat data."""
        return iter(self._data)

    def __repr__(self) -> str:
        bounds = ", ".join(str(b) for b in self._ub)
        return f"GplArray({bounds}: {self._data!r})"

    def _flat(self, key: Any) -> int:
        """Slow path: validate any subscript form and return the flat position (or raise)."""
        idx = key if type(key) is tuple else (key,)
        if len(idx) != len(self._ub):
            raise GplException(
                ARRAY_INDEX_MISMATCH, detail=f"{len(idx)} subscripts for a rank-{len(self._ub)} array"
            )
        flat = 0
        for k, ub, stride in zip(idx, self._ub, self._strides):
            if type(k) is not int:
                try:
                    k = to_int32(k)
                except GplException as exc:
                    if exc.ErrorCode != ARITHMETIC_OVERFLOW:
                        raise
                    raise _bad_index(f"index {k} outside 0..{ub}") from None
            if not 0 <= k <= ub:
                raise _bad_index(f"index {k} outside 0..{ub}")
            flat += k * stride
        return flat

    def __getitem__(self, key: Any) -> Any:
        return self._data[self._flat(key)]

    def __setitem__(self, key: Any, value: Any) -> None:
        self._data[self._flat(key)] = value


class _Array1(GplArray):
    """Rank 1: ``a[i]``."""

    __slots__ = ()

    def __getitem__(self, i: Any) -> Any:
        if type(i) is int and 0 <= i < self._n1:
            return self._data[i]
        return self._data[self._flat(i)]

    def __setitem__(self, i: Any, value: Any) -> None:
        if type(i) is int and 0 <= i < self._n1:
            self._data[i] = value
        else:
            self._data[self._flat(i)] = value


class _Array2(GplArray):
    """Rank 2: ``a[i, j]``."""

    __slots__ = ()

    def __getitem__(self, key: Any) -> Any:
        if type(key) is tuple and len(key) == 2:
            i, j = key
            if type(i) is int and type(j) is int and 0 <= j < self._n1 and 0 <= i <= self._ub[0]:
                return self._data[i * self._n1 + j]
        return self._data[self._flat(key)]

    def __setitem__(self, key: Any, value: Any) -> None:
        if type(key) is tuple and len(key) == 2:
            i, j = key
            if type(i) is int and type(j) is int and 0 <= j < self._n1 and 0 <= i <= self._ub[0]:
                self._data[i * self._n1 + j] = value
                return
        self._data[self._flat(key)] = value


class _ArrayN(GplArray):
    """Ranks 3 and 4 (rare): the generic checked path."""

    __slots__ = ()


def redim(array: GplArray | None, element_type: object, *upper_bounds: Any) -> GplArray:
    """GPL ``ReDim``: a fresh array of defaults with new bounds (AMB-17, no Preserve).

    ``array`` is the variable's current value (``None`` if never allocated); ReDim cannot change
    the rank [000 L381-383], so a different number of bounds is -766.  ``element_type`` may be
    ``None`` to reuse the existing array's.
    """
    if array is not None:
        if len(upper_bounds) != len(array._ub):
            raise GplException(
                ARRAY_INDEX_MISMATCH,
                detail=f"ReDim cannot change rank {len(array._ub)} to {len(upper_bounds)}",
            )
        if element_type is None:
            element_type = array._etype
    return GplArray(element_type, *upper_bounds)


def redim_preserve(array: GplArray | None, element_type: object, *upper_bounds: Any) -> GplArray:
    """GPL ``ReDim Preserve``: a new array with new bounds that keeps every element that still fits.

    Real code (the vendor's TCS) grows arrays this way; the manuals do not document it, so it
    follows VB where VB defines it and stays total where VB would fail (docs/design/real-code.md):

    * an element whose subscripts are all within the new bounds keeps its value; new elements hold
      the element type's default;
    * an array that is Nothing is simply allocated (``redim``);
    * any dimension may change, not only the last one as in VB (where changing another dimension
      is an error): the elements at the same subscripts are kept, which equals VB's result
      wherever VB gives one;
    * the rank cannot change: a different number of bounds is -766, as for ``ReDim``.

    The new array is a new object, as VB's is: another variable that shared the old array keeps it.
    """
    new = redim(array, element_type, *upper_bounds)
    if array is None:
        return new
    old_ub = array._ub
    if len(old_ub) == 1:
        n = min(old_ub[0], new._ub[0]) + 1
        new._data[:n] = array._data[:n]
        return new
    keep = tuple(min(a, b) + 1 for a, b in zip(old_ub, new._ub))
    if min(keep) <= 0:
        return new
    _copy_block(array._data, array._strides, new._data, new._strides, keep, 0, 0, 0)
    return new


def _copy_block(src: list[Any], src_strides: tuple[int, ...], dst: list[Any], dst_strides: tuple[int, ...],
                keep: tuple[int, ...], dim: int, src_at: int, dst_at: int) -> None:
    """Copy the ``keep``-sized corner of a row-major array into another of other bounds, one
    contiguous run of the last dimension at a time."""
    if dim == len(keep) - 1:
        dst[dst_at:dst_at + keep[dim]] = src[src_at:src_at + keep[dim]]
        return
    for i in range(keep[dim]):
        _copy_block(src, src_strides, dst, dst_strides, keep, dim + 1,
                    src_at + i * src_strides[dim], dst_at + i * dst_strides[dim])

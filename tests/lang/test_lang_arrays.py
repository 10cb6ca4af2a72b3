"""GplArray: bounds, defaults, negative index errors, multi-dim, ReDim, members, references."""

from __future__ import annotations

import pytest

from gplrt.lang.arrays import GplArray, redim, redim_preserve
from gplrt.lang.gpltypes import Boolean, Byte, Double, Integer, Short, Single, String
from gpltest import code_of


class Widget:
    pass


def get(a, k):
    return a[k]


def put(a, k, v=1):
    a[k] = v


def test_upper_bound_declaration_gives_n_plus_one_elements() -> None:
    a = GplArray(Integer, 3)
    assert a.Length == 4 and a.Rank == 1 and a.GetUpperBound(0) == 3
    assert list(a) == [0, 0, 0, 0]
    count = GplArray(Integer, 9)  # Dim Count(9) As Integer allocates 10 elements
    assert count.Length == 10


@pytest.mark.parametrize(
    ("etype", "default"),
    [(Integer, 0), (Short, 0), (Byte, 0), (Single, 0.0), (Double, 0.0), (Boolean, False), (String, ""),
     (Widget, None), ("Integer", 0), ("string", "")],
)
def test_element_defaults(etype, default) -> None:
    a = GplArray(etype, 2)
    assert all(type(v) is type(default) and v == default for v in a)


def test_get_and_set_within_bounds() -> None:
    a = GplArray(Integer, 3)
    for i in range(4):
        a[i] = i * 10
    assert [a[i] for i in range(4)] == [0, 10, 20, 30]


@pytest.mark.parametrize("index", [-1, -4, 4, 100, 2**40])
def test_out_of_range_and_negative_index_is_767(index) -> None:
    a = GplArray(Integer, 3)
    assert code_of(get, a, index) == -767
    assert code_of(put, a, index) == -767
    assert list(a) == [0, 0, 0, 0]  # no wrap-around write happened


def test_boolean_index_is_minus_one_and_rejected() -> None:
    a = GplArray(Integer, 3)
    assert code_of(get, a, True) == -767


def test_non_integral_subscripts_round() -> None:
    a = GplArray(Integer, 3)
    a[2.5] = 7  # rounds half away from zero to 3
    assert a[3] == 7
    assert a[1.4] == 0
    assert code_of(get, a, 3.5) == -767


def test_two_dimensions_row_major() -> None:
    m = GplArray(Double, 2, 3)  # 3 x 4
    assert m.Length == 12 and m.Rank == 2
    assert m.GetUpperBound(0) == 2 and m.GetUpperBound(1) == 3
    for i in range(3):
        for j in range(4):
            m[i, j] = i * 10 + j
    assert m[2, 3] == 23 and m[1, 0] == 10
    assert list(m)[:5] == [0, 1, 2, 3, 10]
    assert code_of(get, m, (3, 0)) == -767
    assert code_of(get, m, (0, 4)) == -767
    assert code_of(get, m, (-1, 0)) == -767
    assert code_of(get, m, (0, -1)) == -767
    assert code_of(put, m, (0, 4)) == -767


def test_wrong_number_of_subscripts_is_766() -> None:
    m = GplArray(Integer, 2, 3)
    assert code_of(get, m, 1) == -766
    assert code_of(get, m, (1, 1, 1)) == -766
    a = GplArray(Integer, 3)
    assert code_of(get, a, (1, 1)) == -766


@pytest.mark.parametrize("bounds", [(1, 2, 3), (1, 1, 2, 2)])
def test_three_and_four_dimensions(bounds) -> None:
    a = GplArray(Integer, *bounds)
    n = 1
    for b in bounds:
        n *= b + 1
    assert a.Length == n and a.Rank == len(bounds)
    last = tuple(bounds)
    a[last] = 5
    assert a[last] == 5
    assert list(a)[-1] == 5
    first = (0,) * len(bounds)
    assert a[first] == 0
    bad = (bounds[0] + 1,) + last[1:]
    assert code_of(get, a, bad) == -767
    assert [a.GetUpperBound(d) for d in range(len(bounds))] == list(bounds)


def test_rank_limits() -> None:
    assert code_of(GplArray, Integer, 1, 1, 1, 1, 1) == -766
    assert code_of(GplArray, Integer) == -766


def test_negative_upper_bound() -> None:
    assert GplArray(Integer, -1).Length == 0  # VB's empty array
    assert code_of(GplArray, Integer, -2) == -707


def test_get_upper_bound_bad_dimension_is_707() -> None:
    a = GplArray(Integer, 3)
    assert code_of(a.GetUpperBound, 1) == -707
    assert code_of(a.GetUpperBound, -1) == -707


def test_redim_gives_fresh_defaults_and_keeps_rank() -> None:
    count = None  # Dim Count() As Integer
    count = redim(count, Integer, 9)  # ReDim Count(9)
    assert count.Length == 10
    count[3] = 42
    count = redim(count, None, 4)
    assert count.Length == 5 and list(count) == [0] * 5  # without Preserve: defaults (AMB-17)
    two = GplArray(Integer, 2, 3)
    two = redim(two, None, 1, 100)  # ReDim TwoDCount(1,100)
    assert two.GetUpperBound(1) == 100 and two.Length == 202
    assert code_of(redim, two, None, 5) == -766  # cannot change rank
    s = redim(GplArray(String, 1), None, 2)
    assert list(s) == ["", "", ""]


def test_redim_preserve_keeps_the_elements_that_still_fit() -> None:
    """ReDim Preserve (real code, docs/design/real-code.md): a new array of the new size holding
    the old elements that fit, defaults after them; growing and shrinking alike."""
    a = GplArray(String, 2)
    a[0], a[1], a[2] = "a", "b", "c"
    grown = redim_preserve(a, "String", 4)
    assert list(grown) == ["a", "b", "c", "", ""] and grown is not a
    assert list(a) == ["a", "b", "c"]  # another variable holding the old array keeps it
    shrunk = redim_preserve(grown, "String", 0)
    assert list(shrunk) == ["a"]
    assert list(redim_preserve(shrunk, "String", -1)) == []  # an empty array (upper bound -1)
    objs = GplArray(None, 1)
    w = Widget()
    objs[1] = w
    assert list(redim_preserve(objs, None, 2)) == [None, w, None]  # element type kept from the array


def test_redim_preserve_of_nothing_allocates() -> None:
    assert list(redim_preserve(None, Integer, 2)) == [0, 0, 0]
    assert list(redim_preserve(None, "Double", 1)) == [0.0, 0.0]


def test_redim_preserve_keeps_elements_at_their_subscripts_in_every_dimension() -> None:
    m = GplArray(Integer, 1, 2)  # 2 x 3
    for i in range(2):
        for j in range(3):
            m[i, j] = 10 * i + j
    last = redim_preserve(m, None, 1, 4)  # the last dimension only: VB's case
    assert [[last[i, j] for j in range(5)] for i in range(2)] == [[0, 1, 2, 0, 0], [10, 11, 12, 0, 0]]
    first = redim_preserve(m, None, 2, 1)  # the first grows, the last shrinks: what fits is kept
    assert [[first[i, j] for j in range(2)] for i in range(3)] == [[0, 1], [10, 11], [0, 0]]
    cube = GplArray(Integer, 1, 1, 1)
    cube[1, 1, 1] = 7
    cube[0, 1, 0] = 3
    big = redim_preserve(cube, None, 2, 2, 2)
    assert big[1, 1, 1] == 7 and big[0, 1, 0] == 3 and sum(big) == 10
    assert sum(redim_preserve(cube, None, 1, -1, 1)) == 0  # an empty dimension keeps nothing
    assert code_of(redim_preserve, m, None, 5) == -766  # the rank cannot change
    assert code_of(redim_preserve, m, None, 1, 2, 3) == -766


def test_whole_array_assignment_shares_the_reference() -> None:
    count_a = GplArray(Integer, 2)
    count_b = count_a  # CountB = CountA
    count_b[1] = 9
    assert count_a[1] == 9


def test_from_list_and_iteration() -> None:
    a = GplArray.from_list(["x", "y"], String)
    assert a.Length == 2 and a[1] == "y" and [v for v in a] == ["x", "y"]
    assert GplArray.from_list([]).Length == 0


def test_string_array_length_vs_element_length() -> None:
    sarray = GplArray(String, 3)
    sarray[0] = "abc"
    assert sarray.Length == 4
    assert len(sarray[0]) == 3

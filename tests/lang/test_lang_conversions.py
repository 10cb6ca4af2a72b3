"""Conversions: rounding, overflow codes, Boolean -1, String <-> number, CStr rendering."""

from __future__ import annotations

import math
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gplrt.lang.conversions import (
    CBool,
    CByte,
    CDbl,
    CInt,
    CShort,
    CSng,
    CStr,
    bool_num,
    chk_int16,
    chk_int32,
    chk_uint8,
    convert,
    parse_number,
    to_int32,
    to_string,
    to_string_single,
)
from gplrt.lang.gpltypes import Boolean, Byte, Double, Integer, Short, Single, String
from gpltest import code_of


@pytest.mark.parametrize(
    ("value", "expected"),
    [(0.5, 1), (-0.5, -1), (1.5, 2), (-1.5, -2), (2.5, 3), (-2.5, -3), (2.4999999, 2), (-2.4999999, -2),
     (7.875, 8), (0.49999999999999994, 0), (-0.49999999999999994, 0), (2147483647.4, 2147483647),
     (-2147483648.4, -2147483648), (3.0, 3), (-0.0, 0)],
)
def test_integer_conversion_rounds_half_away_from_zero(value: float, expected: int) -> None:
    assert CInt(value) == expected
    assert type(CInt(value)) is int


def test_assignment_example_from_manual() -> None:
    # a = 2.25, b = 3.5, c As Integer: c = a * b stores 8 [000 L1239-1243]
    assert convert(2.25 * 3.5, Integer) == 8


@pytest.mark.parametrize(
    ("fn", "value"),
    [(CInt, 2147483647.5), (CInt, -2147483648.5), (CInt, 2**31), (CInt, -(2**31) - 1), (CInt, math.inf),
     (CInt, math.nan), (CShort, 32767.5), (CShort, -32769), (CShort, 40000.0), (CByte, 255.5), (CByte, -1),
     (CByte, -0.5), (CByte, 256), (chk_int32, 2**31), (chk_int16, 32768), (chk_uint8, 256), (chk_uint8, -1)],
)
def test_integer_overflow_is_710(fn, value) -> None:
    assert code_of(fn, value) == -710


def test_integer_ranges_accept_their_limits() -> None:
    assert CShort(-32768) == -32768 and CShort(32767.4) == 32767
    assert CByte(254.5) == 255 and CByte(-0.4) == 0
    assert CInt("&HFFFFFFFF") == -1


def test_boolean_is_minus_one() -> None:
    assert CInt(True) == -1 and CInt(False) == 0
    assert CDbl(True) == -1.0
    assert bool_num(True) == -1 and bool_num(False) == 0
    assert CShort(True) == -1
    assert code_of(CByte, True) == -710  # -1 does not fit a Byte


@pytest.mark.parametrize(
    ("value", "expected"),
    [(0, False), (0.0, False), (1, True), (-1, True), (0.001, True), ("0", False), ("2.5", True),
     ("True", True), ("false", False), (" TRUE ", True), (True, True)],
)
def test_cbool(value, expected) -> None:
    assert CBool(value) is expected


@pytest.mark.parametrize(
    ("text", "expected"),
    [("1.01", 1.01), ("  -2.5 ", -2.5), ("+3", 3.0), (".9", 0.9), ("5.", 5.0), ("1E+32", 1e32), ("2e-3", 0.002),
     ("&H20", 32), ("&hff", 255), ("&O17", 15), ("-&H10", -16), ("&H80000000", -2147483648)],
)
def test_string_to_number(text: str, expected: float) -> None:
    assert parse_number(text) == expected
    assert CDbl(text) == pytest.approx(float(expected), abs=0, rel=1e-15)


@pytest.mark.parametrize("text", ["", "abc", "inf", "nan", "--1", "&HG", " ", "x1", ". 5", "e5"])
def test_text_that_does_not_start_with_a_number_is_717(text: str) -> None:
    assert code_of(CDbl, text) == -717
    assert code_of(CInt, text) == -717


@pytest.mark.parametrize(
    ("text", "expected"),
    [("20)", 20), ("180)", 180.0), ("-82.630104,", -82.630104), ("12abc", 12), ("1.2.3", 1.2),
     ("1_000", 1), ("0x10", 0), ("1e", 1), ("2.5E+3 mm", 2500.0), ("&H1FZ", 31), (" 7 8", 7)],
)
def test_characters_after_the_number_are_ignored(text: str, expected: float) -> None:
    """The controller reads the number a text starts with: TCS converts the bound of
    ``Public tcs_sta_flags_1(20) As Integer`` as ``CInt("20)")`` and the last argument of
    ``.XYZ(...,180)`` as ``CDbl("180)")`` when it loads a .gpo file (Class_gpofile.gpl:188-190),
    and loads the files the real TCS writes (docs/design/real-code.md)."""
    assert parse_number(text) == expected
    assert CDbl(text) == pytest.approx(float(expected), abs=0, rel=1e-15)
    assert CInt(text) == round(expected)


def test_string_to_integer_rounds() -> None:
    assert CInt("2.5") == 3 and CInt("-2.5") == -3 and CByte(" 17 ") == 17


@pytest.mark.parametrize(
    ("value", "text"),
    [(10.2, "10.2"), (0.1, "0.1"), (1e32, "1E+32"), (1 / 3, "0.333333333333333"), (-0.0, "0"), (0.0, "0"),
     (3.0, "3"), (-7.0, "-7"), (2.34 + 1.01, "3.35"), (0.1 + 0.2, "0.3"), (1e15, "1E+15"),
     (123456789012345.0, "123456789012345"), (1e-5, "1E-05"), (0.0001, "0.0001"), (1.5e-7, "1.5E-07"),
     (-1.25e-300, "-1.25E-300"), (1.7976931348623157e308, "1.79769313486232E+308"), (2 / 3, "0.666666666666667"),
     (123456.789, "123456.789"), (42, "42"), (-2147483648, "-2147483648"), (True, "-1"), (False, "0"),
     ("abc", "abc"), (math.inf, "Infinity"), (-math.inf, "-Infinity")],
)
def test_cstr(value, text: str) -> None:
    assert CStr(value) == text


def test_cstr_of_single_uses_seven_digits() -> None:
    assert to_string_single(CSng(0.1)) == "0.1"
    assert to_string_single(CSng(1 / 3)) == "0.3333333"
    assert CStr(CSng(0.1)) == "0.100000001490116"  # the same float seen as a Double


def test_csng_rounds_to_single_and_overflows() -> None:
    assert CSng(0.1) == 0.10000000149011612
    assert CSng(16777217) == 16777216.0
    assert code_of(CSng, 1e39) == -710


def test_convert_dispatches_on_gpl_types() -> None:
    assert convert(2.5, Integer) == 3
    assert convert(2.5, Short) == 3
    assert convert(2.5, Byte) == 3
    assert convert(3, Double) == 3.0 and type(convert(3, Double)) is float
    assert convert(0.1, Single) == CSng(0.1)
    assert convert(2, Boolean) is True
    assert convert(2.5, String) == "2.5"
    assert convert("7", "Integer") == 7
    sentinel = object()
    assert convert(sentinel, object) is sentinel  # objects: no conversion
    assert code_of(convert, 1, "Decimal") == -738


def test_nothing_to_string_is_782() -> None:
    assert code_of(to_string, None) == -782


@settings(max_examples=300, deadline=None)
@given(st.floats(min_value=-2.1e9, max_value=2.1e9, allow_nan=False))
def test_to_int32_matches_reference_rounding(x: float) -> None:
    # reference via exact fractions: round half away from zero
    f = Fraction(x)
    ref = math.floor(f + Fraction(1, 2)) if f >= 0 else -math.floor(-f + Fraction(1, 2))
    assert to_int32(x) == ref


@settings(max_examples=300, deadline=None)
@given(st.floats(allow_nan=False, allow_infinity=False))
def test_cstr_round_trips_to_15_digits(x: float) -> None:
    text = CStr(x)
    back = float(text)
    assert back == float("%.15g" % x)


def test_nothing_or_object_as_number() -> None:
    from gplrt.lang.conversions import to_number

    assert code_of(to_number, None) == -782
    assert code_of(to_number, object()) == -202


@pytest.mark.parametrize("value", [10**400, -(10**400), str(10**400), "1E400", "-1E400"])
def test_an_integer_beyond_the_double_range_is_710(value: object) -> None:
    """Only Python callers can pass such an int; it must be -710 like any value too big for its
    type, in CDbl and in every runtime function that takes a Double (they share to_double)."""
    from gplrt.lang.mathlib import Math
    from gplrt.lang.operators import power

    assert CDbl(10**300) == 1e300
    assert code_of(CDbl, value) == -710
    assert code_of(Math.Sqrt, value) == -710
    assert code_of(power, value, 1) == -710

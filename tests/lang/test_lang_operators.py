"""Operators: String/number mixing, division rules, shifts, logical vs bitwise, comparisons."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gplrt.lang.conversions import CStr, to_int32
from gplrt.lang.operators import (
    add,
    and_,
    concat,
    div,
    eq,
    ge,
    gt,
    idiv,
    le,
    lt,
    mod,
    mul,
    ne,
    neg,
    not_,
    or_,
    power,
    shl,
    shr,
    sub,
    xor,
)
from gpltest import code_of


def test_plus_with_one_string_adds_numerically() -> None:
    assert add(2.34, "1.01") == pytest.approx(3.35, abs=1e-12)
    assert CStr(add(2.34, "1.01")) == "3.35"  # the manual's "a will be equal to 3.35"
    assert add("1.01", 2.34) == pytest.approx(3.35, abs=1e-12)
    assert add("2", 3) == 5.0


def test_plus_with_two_strings_concatenates() -> None:
    assert add("ab", "cd") == "abcd"
    assert add("1", "2") == "12"


def test_plus_with_non_numeric_string_is_717() -> None:
    assert code_of(add, "a", 1) == -717
    assert code_of(add, 1, "x1") == -717


def test_boolean_arithmetic_uses_minus_one() -> None:
    assert add(True, 1) == 0
    assert add(True, True) == -2
    assert sub(0, True) == 1
    assert mul(True, 5) == -5
    assert neg(True) == 1
    assert add(False, 2.5) == 2.5


def test_real_division() -> None:
    assert div(5, 2) == 2.5
    assert div(-7, 2) == -3.5
    assert code_of(div, 1, 0) == -709
    assert code_of(div, 1.0, 0.0) == -709
    assert code_of(div, 0, 0) == -709
    assert code_of(div, 1e308, 1e-10) == -710


@pytest.mark.parametrize(
    ("a", "b", "q"),
    [(2.3, 2, 1), (7.9, 2, 3), (7, 2, 3), (-7, 2, -3), (7, -2, -3), (-7, -2, 3), (-2.3, 2, -1), (1, 3, 0),
     (6, 3, 2), (True, 1, -1)],
)
def test_integer_division_truncates_the_real_quotient(a, b, q) -> None:
    assert idiv(a, b) == q


def test_integer_division_by_zero_is_709() -> None:
    assert code_of(idiv, 5, 0) == -709
    assert code_of(idiv, 5, 0.0) == -709


@pytest.mark.parametrize(
    ("a", "b", "r"),
    [(13.3, 2, 1.3), (7, 3, 1), (-7, 3, -1), (7, -3, 1), (-7, -3, -1), (-13.3, 2, -1.3), (5.5, 2.5, 0.5), (6, 3, 0)],
)
def test_mod_is_real_remainder_with_sign_of_dividend(a, b, r) -> None:
    assert mod(a, b) == pytest.approx(r, abs=1e-12)


def test_mod_by_zero_is_709() -> None:
    assert code_of(mod, 1, 0) == -709
    assert code_of(mod, 1.5, 0.0) == -709


def test_power() -> None:
    assert power(2, 10) == 1024.0
    assert power(-2, 3) == -8.0
    assert power(-8, 2) == 64.0
    assert power(9, 0.5) == 3.0
    assert power(2, -1) == 0.5
    assert code_of(power, -8, 1 / 3) == -707  # negative base, fractional power: error, never NaN
    assert code_of(power, 0, -1) == -709
    assert code_of(power, 10, 400) == -710
    assert power(0, 0) == 1.0


def test_shifts_are_arithmetic_on_32_bits() -> None:
    assert shl(1, 4) == 16
    assert shl(1, 31) == -2147483648
    assert shl(3, 31) == -2147483648  # high bits drop off
    assert shl(1, 32) == 1  # count modulo 32
    assert shr(16, 2) == 4
    assert shr(-16, 2) == -4  # sign bit shifted in
    assert shr(-1, 31) == -1
    assert shr(2147483647, 30) == 1
    assert shl(2.6, 1) == 6  # operands rounded as Integer conversions
    assert code_of(shl, 2**31, 1) == -710


def test_and_or_xor_logical_for_two_booleans() -> None:
    assert and_(True, False) is False and and_(True, True) is True
    assert or_(False, False) is False and or_(True, False) is True
    assert xor(True, True) is False and xor(True, False) is True and xor(False, False) is False


def test_and_or_xor_bitwise_otherwise() -> None:
    assert and_(6, 3) == 2
    assert or_(5, 2) == 7
    assert xor(6, 3) == 5
    assert and_(True, 2) == 2  # True is -1: all bits set
    assert or_(True, 2) == -1
    assert and_(13, 1) == 1  # ii And 1 [000 L3565]
    assert and_(-1, 0xFF) == 255
    assert xor(-1, 0) == -1
    assert and_(2.6, 3) == 3  # 2.6 rounds to 3


def test_not_is_logical_even_on_integers() -> None:
    assert not_(5) is False
    assert not_(0) is True
    assert not_(True) is False
    assert not_(False) is True
    assert to_int32(not_(0)) == -1
    assert not_(0.0) is True
    assert not_("0") is True and not_("True") is False


def test_concat_uses_cstr_rules() -> None:
    assert concat("a", 5) == "a5"
    assert concat("x=", 0.1) == "x=0.1"
    assert concat(1 / 3, "") == "0.333333333333333"
    assert concat("flag ", True) == "flag -1"
    assert concat(False, "") == "0"  # Boolean is an integer type: its text is its value
    assert concat("Joe's balance: ", 10.2) == "Joe's balance: 10.2"
    assert concat(1, 2) == "12"


def test_string_comparison_is_case_sensitive_binary() -> None:
    assert eq("A", "A") is True
    assert eq("A", "a") is False
    assert ne("A", "a") is True
    assert lt("B", "a") is True  # 'B' (66) < 'a' (97)
    assert lt("abc", "abd") is True
    assert gt("b", "abc") is True
    assert le("a", "a") is True and ge("a", "b") is False
    assert lt("", "a") is True


def test_mixed_string_number_comparison_is_numeric() -> None:
    assert eq("1.0", 1) is True
    assert lt("10", 9) is False  # numeric, not text order
    assert eq(" 2", 2.0) is True
    assert code_of(eq, "abc", 1) == -717


def test_numeric_and_boolean_comparison() -> None:
    assert eq(1, 1.0) is True
    assert eq(True, -1) is True
    assert lt(True, False) is True  # -1 < 0
    assert gt(2, 1.5) is True and ge(2, 2) is True and le(1, 0.5) is False
    assert ne(0.1 + 0.2, 0.3) is True  # Double comparison, no fuzz


def test_overflow_of_runtime_arithmetic_is_710() -> None:
    assert code_of(mul, 1e308, "10") == -710
    assert code_of(add, 1e308, "1e308") == -710
    assert math.isfinite(add(1e308, "1"))


@settings(max_examples=400, deadline=None)
@given(st.integers(-(2**31), 2**31 - 1), st.integers(-(2**31), 2**31 - 1).filter(lambda b: b != 0))
def test_integer_fast_paths_match_double_semantics(a: int, b: int) -> None:
    assert idiv(a, b) == math.trunc(float(a) / float(b))
    assert mod(a, b) == math.fmod(float(a), float(b))

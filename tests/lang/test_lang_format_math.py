"""Format (every example of gpl-dictionary §12, plus the VB.NET rules around them) and Math."""

from __future__ import annotations

import math

import pytest

from gplrt.lang.errors import GplException
from gplrt.lang.format import Format
from gplrt.lang.mathlib import Fix, Int, Math, Rnd, rnd_seed
from gpltest import code_of


@pytest.mark.parametrize(
    ("value", "spec", "text"),
    [  # the dictionary's examples (§12), in order
        (5, "000", "005"),
        (5, "###", "5"),
        (3.14159, "0.00", "3.14"),
        (1234567, "#,##0", "1,234,567"),
        (0.25, "0%", "25%"),
        (1234.5, "0.00E+0", "1.23E+3"),
        (-3.7, "0.0;(0.0)", "(3.7)"),
        (255, "X", "FF"),
    ],
)
def test_dictionary_examples(value, spec: str, text: str) -> None:
    assert Format(value, spec) == text


@pytest.mark.parametrize(
    ("value", "spec", "text"),
    [
        (3.7, "0.0;(0.0)", "3.7"),
        (0, "0.0;(0.0)", "0.0"),
        (-0.04, "0.0;(0.0)", "0.0"),  # rounds to zero: the first section, no sign
        (0, "0.0;-0.0;zero", "zero"),
        (-2, "0.0;;zero", "-2.0"),  # empty negative section: first section with a sign
        (-5, "000", "-005"),
        (0, "#", ""),
        (0, "0", "0"),
        (0.5, "#.##", ".5"),
        (1.5, ".00", "1.50"),
        (12345, "0", "12345"),  # extra digits go into the leftmost placeholder
        (2.675, "0.00", "2.68"),  # 15-digit pre-rounding, half away from zero
        (-2.5, "0", "-3"),
        (2.5, "0", "3"),
        (1.0, "0.##", "1"),
        (1.2, "0.0#", "1.2"),
        (1.234, "0.0#", "1.23"),
        (-0.001, "0.00", "0.00"),
        (1234567, "0,,", "1"),
        (1234567890, "#,##0,,", "1,235"),
        (5551234567, "(###) ###-####", "(555) 123-4567"),
        (0.000123, "0.0e-00", "1.2e-04"),
        (123456, "0.0E+00", "1.2E+05"),
        (0.5, "0.0‰", "500.0‰"),
        (7, "\\#0", "#7"),
        (7, '"No. "0', "No. 7"),
        (7, "'x'0", "x7"),
        (0, "0.00E+0", "0.00E+0"),
        (999.99, "0.0", "1000.0"),
        (99.96, "0.0E+0", "1.0E+2"),
    ],
)
def test_custom_patterns(value, spec: str, text: str) -> None:
    assert Format(value, spec) == text


@pytest.mark.parametrize(
    ("value", "spec", "text"),
    [
        (1234.5678, "F", "1234.57"),
        (1234.5678, "F0", "1235"),
        (1234567.891, "N", "1,234,567.89"),
        (-1234.5, "N1", "-1,234.5"),
        (0.1234, "P", "12.34%"),
        (12345.6789, "E", "1.234568E+004"),
        (12345.6789, "e2", "1.23e+004"),
        (-0.00012, "E1", "-1.2E-004"),
        (42, "D5", "00042"),
        (-42, "D", "-42"),
        (-1, "X", "FFFFFFFF"),
        (255, "x4", "00ff"),
        (1 / 3, "G", "0.333333333333333"),
        (1 / 3, "G5", "0.33333"),
        (1e20, "G5", "1E+20"),
        (0.1, "R", "0.1"),
        (12.5, "C", "$12.50"),
        (-12.5, "C", "($12.50)"),
        (1234.5, "General Number", "1234.5"),
        (1234.5, "Fixed", "1234.50"),
        (1234.5, "Standard", "1,234.50"),
        (0.5, "Percent", "50.00%"),
        (12345, "Scientific", "1.23E+04"),
        (1, "Yes/No", "Yes"),
        (0, "True/False", "False"),
        (-1, "On/Off", "On"),
    ],
)
def test_standard_and_named_formats(value, spec: str, text: str) -> None:
    assert Format(value, spec) == text


def test_format_inputs_and_errors() -> None:
    assert Format("12.5", "0.00") == "12.50"  # numeric String accepted
    assert Format(True, "0") == "-1"
    assert Format(10.2, "") == "10.2"  # empty spec: CStr text
    assert code_of(Format, 1.5, "D") == -202
    assert code_of(Format, 1, "Q") == -202
    assert code_of(Format, "abc", "0") == -717


# -- Math ------------------------------------------------------------------------------------------


def test_math_trig_is_in_radians() -> None:
    assert Math.Sin(Math.PI / 2) == 1.0
    assert Math.Cos(0) == 1.0
    assert abs(Math.Cos(Math.PI / 3) - 0.5) < 1e-15
    assert Math.Tan(Math.PI / 4) == pytest.approx(1.0, abs=1e-15)
    assert 180.0 * Math.Atan2(1, 1) / Math.PI == pytest.approx(45.0, abs=1e-12)
    assert Math.Atan2(1, 0) == math.pi / 2  # (sine_factor, cosine_factor)
    assert Math.Asin(1) == math.pi / 2 and Math.Acos(1) == 0.0 and Math.Atan(1) == math.pi / 4


def test_math_members() -> None:
    assert Math.Abs(-2) == 2.0 and Math.Abs(True) == 1.0
    assert Math.Sqrt(3) == math.sqrt(3)
    assert Math.Pow(2, 0.5) == math.sqrt(2)
    assert Math.Floor(-2.5) == -3.0 and Math.Ceiling(-2.5) == -2.0 and Math.Ceiling(2.1) == 3.0
    assert Math.Max(2, 3.5) == 3.5 and Math.Min(2, 3.5) == 2.0 and Math.Max("4", 3) == 4.0
    assert Math.Sign(-4) == -1.0 and Math.Sign(0) == 0.0 and Math.Sign(0.1) == 1.0
    assert Math.Exp(1) == math.e and Math.Log(math.e) == 1.0 and Math.Log10(1000) == 3.0
    assert Math.Sinh(0) == 0.0 and Math.Cosh(0) == 1.0 and Math.Tanh(0) == 0.0
    assert Math.E == math.e and Math.PI == math.pi


def test_math_domain_and_overflow_errors() -> None:
    assert code_of(Math.Sqrt, -1) == -707
    assert code_of(Math.Log, 0) == -707
    assert code_of(Math.Log10, -5) == -707
    assert code_of(Math.Acos, 2) == -707
    assert code_of(Math.Asin, -1.5) == -707
    assert code_of(Math.Pow, -8, 0.5) == -707
    assert code_of(Math.Exp, 1000) == -710
    assert code_of(Math.Cosh, 1000) == -710


def test_math_catalogue_shape() -> None:
    members = {n for n in dir(type(Math)) if n[:1].isupper()}
    assert members == {"Abs", "Acos", "Asin", "Atan", "Atan2", "Ceiling", "Cos", "Cosh", "E", "Exp", "Floor", "Log",
                       "Log10", "Max", "Min", "PI", "Pow", "Sign", "Sin", "Sinh", "Sqrt", "Tan", "Tanh"}


def test_fix_and_int() -> None:
    assert Fix(2.7) == 2.0 and Fix(-2.7) == -2.0
    assert Int(2.7) == 2.0 and Int(-2.7) == -3.0 and Int(-3) == -3.0


@pytest.mark.parametrize("rounding", [Fix, Int, Math.Floor, Math.Ceiling])
@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf])
def test_rounding_a_value_that_is_not_finite_is_708(rounding, value: float) -> None:
    with pytest.raises(GplException) as caught:
        rounding(value)
    assert caught.value.ErrorCode == -708


@pytest.mark.parametrize("trig", [Math.Sin, Math.Cos, Math.Tan])
def test_trig_of_an_infinity_is_708(trig) -> None:
    """An infinite angle has no sine (math would raise a bare ValueError); finite ones still work."""
    assert trig(0.5) == pytest.approx(getattr(math, trig.__name__.lower())(0.5), abs=1e-15)
    assert code_of(trig, math.inf) == -708
    assert code_of(trig, -math.inf) == -708


def test_rnd_seed_rules() -> None:
    rnd_seed(1)
    values = [Rnd() for _ in range(100)]
    assert all(0.0 <= v < 1.0 for v in values) and len(set(values)) > 90
    assert Rnd(0) == values[-1]  # 0 repeats the previous value
    a = Rnd(-5)
    b = Rnd(1)
    assert Rnd(-5) == a  # same negative seed, same value
    assert Rnd(1) == b


@pytest.mark.parametrize(
    ("value", "spec", "head", "length"),
    [
        (1e308, "0", "1", 309),  # 15 significant digits, then zeros: not a decimal-context error
        (1e308, "F2", "1", 312),
        (-1.7976931348623157e308, "#,##0.00", "-179,769,313,486,231,600,000", 415),
    ],
)
def test_huge_doubles_are_written_out_in_full(value: float, spec: str, head: str, length: int) -> None:
    text = Format(value, spec)
    assert text.startswith(head) and len(text) == length
    assert set(text[len(head) :]) <= set("0,.")

"""String members (0-based) and legacy functions (1-based), with their error cases."""

from __future__ import annotations

import pytest

from gplrt.lang.gpltypes import Byte, Double, Integer, Short, Single
from gplrt.lang.strings import (
    Asc,
    Chr,
    FromBitString,
    Hex,
    InStr,
    LCase,
    Left,
    Len,
    LTrim,
    Mid,
    Right,
    RTrim,
    Space,
    Str,
    StrComp,
    StringMembers as S,
    ToBitString,
    Trim,
    UCase,
    Val,
)
from gpltest import code_of


# -- members ------------------------------------------------------------------------------------


def test_length() -> None:
    assert S.Length("") == 0 and S.Length("abc") == 3 and S.Length("a\x00b") == 3


def test_index_of_is_zero_based() -> None:
    assert S.IndexOf("hello world", "o") == 4
    assert S.IndexOf("hello world", "o", 5) == 7
    assert S.IndexOf("hello", "z") == -1
    assert S.IndexOf("hello", "H") == -1  # exact match, case-sensitive
    assert S.IndexOf("hello", "") == 0
    assert S.IndexOf("hello", "o", 5) == -1
    assert code_of(S.IndexOf, "hello", "o", 6) == -707
    assert code_of(S.IndexOf, "hello", "o", -1) == -707


def test_substring() -> None:
    inp = "CMD argument"
    assert S.Substring(inp, 0, 1) == "C"  # inp.Substring(0,1) is the first character
    assert S.Substring(inp, 4) == "argument"  # inp.Substring(4)
    assert S.Substring("abc", 3) == ""
    assert S.Substring("abc", 1, 2) == "bc"
    assert S.Substring("abc", 1.6, 1) == "c"  # position converted like an Integer
    assert code_of(S.Substring, "abc", 4) == -707
    assert code_of(S.Substring, "abc", -1) == -707
    assert code_of(S.Substring, "abc", 1, 3) == -707
    assert code_of(S.Substring, "abc", 0, -1) == -707


def test_case_conversion_is_ascii_only() -> None:
    assert S.ToUpper("abc Xyz 1") == "ABC XYZ 1"
    assert S.ToLower("ABC xYz") == "abc xyz"
    assert S.ToUpper("\xe9\xff\xdf") == "\xe9\xff\xdf"  # 8-bit codes stay 8-bit
    assert UCase("mixed\xe0") == "MIXED\xe0" and LCase("MIXED\xc0") == "mixed\xc0"


def test_trim_family() -> None:
    assert S.Trim("  a b \t\r\n") == "a b"
    assert S.TrimStart("  a  ") == "a  "
    assert S.TrimEnd("  a  ") == "  a"
    assert S.Trim("xxaxx", "x") == "a"
    assert S.Trim("-+a+-", "+-") == "a"
    assert S.TrimEnd("a\r\n", "\r\n") == "a"
    assert S.Trim("\xa0a\xa0") == "\xa0a\xa0"  # not C white space


def test_split() -> None:
    parts = S.Split("a,b,,c", ",")
    assert parts.Rank == 1 and parts.Length == 4 and list(parts) == ["a", "b", "", "c"]
    assert parts.GetUpperBound(0) == 3
    assert list(S.Split("a b", " ")) == ["a", "b"]
    assert list(S.Split("a;b,c", ",;")) == ["a", "b", "c"]
    assert list(S.Split("abc", ",")) == ["abc"]
    assert list(S.Split("", ",")) == [""]
    assert list(S.Split("a b\tc")) == ["a", "b", "c"]


def test_compare_is_shared() -> None:
    assert S.Compare("a", "b") == -1 and S.Compare("b", "a") == 1 and S.Compare("a", "a") == 0
    assert S.Compare("A", "a") == -1
    assert S.Compare("A", "a", True) == 0
    assert S.Compare("abc", "ABD", True) == -1
    assert "Compare" in S.shared_members


def test_catalogue_shape() -> None:
    members = {name for name in vars(S) if name[:1].isupper()}
    assert members == {"Compare", "Length", "IndexOf", "Split", "Substring", "ToLower", "ToUpper", "Trim", "TrimEnd",
                       "TrimStart"}
    assert all(isinstance(vars(S)[m], staticmethod) for m in members)


# -- legacy functions ---------------------------------------------------------------------------


def test_asc_and_chr() -> None:
    assert Asc("A") == 65 and Asc("abc") == 97 and Asc("\xff") == 255
    assert code_of(Asc, "") == -783
    assert Chr(65) == "A" and Chr(13) == "\r"
    assert Chr(0x1234) == "\x34"  # low byte (AMB-23)
    assert Chr(64.6) == "A"  # rounded
    block = 0x0102
    assert Chr(block / 256) + Chr(block) == "\x01\x02"
    assert Chr(-1) == "\xff"


def test_instr_is_one_based() -> None:
    assert InStr(1, "hello", "l") == 3
    assert InStr(4, "hello", "l") == 4
    assert InStr(5, "hello", "l") == 0
    assert InStr(1, "hello", "z") == 0
    assert InStr(1, "hello", "L") == 0
    assert InStr(9, "hello", "l") == 0
    assert InStr("hello", "lo") == 4  # VB two-argument form
    assert code_of(InStr, 0, "hello", "h") == -707


def test_len() -> None:
    assert Len("") == 0 and Len("four") == 4 and Len(12.5) == 4


def test_mid() -> None:
    assert Mid("hello", 2, 3) == "ell"
    assert Mid("hello", 1, 1) == "h"
    assert Mid("hello", 4, 100) == "lo"  # clipped
    assert Mid("hello", 9, 2) == ""
    assert Mid("hello", 3) == "llo"
    assert Mid("hello", 2, 0) == ""
    assert code_of(Mid, "hello", 0, 1) == -707
    assert code_of(Mid, "hello", 1, -1) == -707


def test_hex() -> None:
    assert Hex(255) == "FF" and Hex(0) == "0" and Hex(-1) == "FFFFFFFF" and Hex(4096) == "1000"
    assert Hex(10.5) == "B"
    assert Hex(-2147483648) == "80000000"
    assert code_of(Hex, 2**32) == -710


@pytest.mark.parametrize(
    ("value", "type_", "big", "packed"),
    [(1, Integer, False, "\x01\x00\x00\x00"), (1, Integer, True, "\x00\x00\x00\x01"), (-2, Short, False, "\xfe\xff"),
     (255, Byte, 0, "\xff"), (1.0, Single, True, "\x3f\x80\x00\x00"), (1.0, Double, False, "\x00" * 6 + "\xf0\x3f"),
     (258, "Short", -1, "\x01\x02")],
)
def test_bit_strings(value, type_, big, packed) -> None:
    assert ToBitString(value, type_, big) == packed
    assert FromBitString(packed, type_, big) == value


def test_bit_string_errors() -> None:
    assert code_of(ToBitString, 256, Byte, 0) == -710
    assert code_of(ToBitString, 40000, Short, 0) == -710
    assert code_of(ToBitString, 1, "Long", 0) == -202
    assert code_of(FromBitString, "\x01", Integer, 0) == -783
    assert FromBitString("\x01\x02\x03\x04\x05", Integer, 1) == 0x01020304


def test_vb_extras() -> None:
    assert Left("hello", 2) == "he" and Left("hi", 5) == "hi"
    assert Right("hello", 2) == "lo" and Right("hi", 5) == "hi" and Right("hi", 0) == ""
    assert LTrim("  a ") == "a " and RTrim(" a  ") == " a" and Trim("  a  ") == "a"
    assert Space(3) == "   "
    assert code_of(Space, -1) == -707
    assert code_of(Left, "a", -1) == -707
    assert StrComp("a", "A") == 1 and StrComp("a", "A", 1) == 0
    assert Val("  12.5abc") == 12.5 and Val("abc") == 0.0 and Val("1 2 3") == 123.0 and Val("&H1F") == 31.0
    assert Str(5) == " 5" and Str(-5) == "-5"

"""The built-ins against the manual's own examples (spec Appendix A, E41-E65): each runs as a
Listen-node packet (translated at run time, as a client would send it) and the values it leaves
are the ones the manual prints."""

from __future__ import annotations

import pytest
from tmpacket import packet_values as values
from tmpacket import run_packet as run

from gpl2py.tmscript.pipeline import translate_packet
from gplrt.tm import context
from gplrt.tm.values import TMError


def test_e41_byte_to_int16() -> None:
    got = values("byte[] bb1 = {0x90, 0x01, 0x05}\nbyte[] bb2 = {0x01}\n"
                 "int a = Byte_ToInt16(bb1, 0, 0)\nint b = Byte_ToInt16(bb1, 1, 0)\nint c = Byte_ToInt16(bb1, 1, 1)\n"
                 "int d = Byte_ToInt16(bb2, 0, 0)\nint e = Byte_ToInt16(bb2, 1, 1)", "a", "b", "c", "d", "e")
    assert got == ["400", "-28671", "36865", "1", "256"]


def test_e42_byte_concat() -> None:
    got = values("byte[] bb1 = {0x31, 0x32, 0x00, 0x4F, 1}\nbyte[] bb2 = {0x01, 0x02, 0x03}\nbyte bb3 = 0x5A\n"
                 'byte[] a = Byte_Concat(bb1, bb2, "", bb3)\nbyte[] b = Byte_Concat(bb2, 0x10, bb1)\n'
                 'byte[] c = Byte_Concat(bb1, "AB", bb2, 1000)', "a", "b", "c")
    assert got == ["{49,50,0,79,1,1,2,3,90}", "{1,2,3,16,49,50,0,79,1}", "{49,50,0,79,1,1,2,3}"]


@pytest.mark.parametrize("text, base, value", [
    ("1234", 10, 1234), ("1234", 16, 4660), ("1234", 2, 0), ("1100", 2, 12), ("0x1234", 10, 4660),
    ("0x1234", 16, 4660), ("0x1234", 2, 0), ("0b1100", 10, 12), ("0b1100", 16, 725248), ("0b1100", 2, 12),
    ("+1234", 10, 1234), ("-1234", 10, -1234), ("-0x1234", 16, 0), ("-0b1100", 2, 0),
])
def test_e43_string_to_integer(text: str, base: int, value: int) -> None:
    assert values(f'int val = String_ToInteger("{text}", {base})', "val") == [str(value)]


def test_e44_e45_substring_and_split() -> None:
    got = values('string a = String_Substring("0x12345", 2, 4)\nstring b = String_Substring("0x12345", -1, 4)\n'
                 'string c = String_Substring("0x12345", 7, 4)\nstring d = String_Substring("0x12345", 2, -1)\n'
                 'string e = String_Substring("0x12345", 2, 100)\n'
                 'string[] f = String_Split("0x112345", "1", 0)\nstring[] g = String_Split("0x112345", "1", 1)\n'
                 'string[] h = String_Split("", "1", 0)\nstring[] i = String_Split("", "1", 1)\n'
                 'string s1 = "123, ""456,67"" ,89"\nstring[] j = String_Split(s1, ",", 2)',
                 "a", "b", "c", "d", "e", "f", "g", "h", "i", "j")
    assert got == ["1234", "", "", "12345", "12345", "{0x,,2345}", "{0x,2345}", "{}", "{}", '{123,"456,67",89}']


def test_e46_e47_arrays() -> None:
    got = values("byte[] n1 = {100, 200, 30}\nbyte[] n2 = {40, 50, 60}\nbyte[] n3 = Array_Append(n1, n2)\n"
                 "n1 = Array_Append(n1, 100)\nint[] m = {100, 200, 30, 40, 50, 60}\nint[] r5 = Array_Remove(m, 0)\n"
                 "int[] r6 = Array_Remove(m, 1, 2)\nint[] r7 = Array_Remove(m, 1, 100)", "n3", "n1", "r5", "r6", "r7")
    assert got == ["{100,200,30,40,50,60}", "{100,200,30,100}", "{200,30,40,50,60}", "{100,40,50,60}", "{100}"]


def test_e48_get_bytes_int_forms() -> None:
    got = values("byte[] a = GetBytes(12345, 0, 0)\nbyte[] b = GetBytes(12345, 0, 1)\nbyte[] c = GetBytes(0x123456, 0, 1)\n"
                 "byte[] d = GetBytes(0x123456, 0, 2)\nbyte[] e = GetBytes(0x1234561, 1, 0)\nbyte[] f = GetBytes(0x1234561, 1, 2)",
                 "a", "b", "c", "d", "e", "f")
    assert got == ["{57,48,0,0}", "{57,48}", "{86,52,18,0}", "{86,52}", "{1,35,69,97}", "{69,97}"]


def test_e49_get_token() -> None:
    cases = [('"", "", 0', "$abcd$1234$ABCD$"), ('"$", "$"', "$abcd$"), ('"$", "$", 0', ""), ('"$", "$", 2', "$ABCD$"),
             ('"$", "$", 3', ""), ('"$", "$", -1, 1', "ABCD"), ('"$", "$", 1, 1', "abcd"), ('"$", "", 2', "$1234"),
             ('"$", "", 4', "$"), ('"", "$", 1', "$"), ('"", "$", 2', "abcd$"), ('"", "$", 4', "ABCD$")]
    script = 'string n = "$abcd$1234$ABCD$"\n' + "\n".join(f"string t{i} = GetToken(n, {a})" for i, (a, _) in enumerate(cases))
    assert values(script, *(f"t{i}" for i in range(len(cases)))) == [want for _, want in cases]


def test_e53_e54_e55_ctrl_and_checksums() -> None:
    got = values("string a = Ctrl(0x0D000A09)\nstring b = Ctrl(0x0D300A09)\nstring c = Ctrl(0x00)\n"
                 "byte[] bb1 = {0x10, 0x20, 0x50, 0xF0, 0xFF, 0xFF, 0xFF}\nbyte x = XOR8(bb1)\nbyte y = XOR8(bb1,0,Length(bb1))\n"
                 "byte[] c0 = CRC16(0, bb1,0,Length(bb1))\nbyte[] c1 = CRC16(0, bb1,1,-1)\nbyte[] c2 = CRC16(0, bb1,-1,-1)\n"
                 "byte[] c3 = CRC16(3, bb1,0,Length(bb1))\nbyte[] c4 = CRC16(4, bb1,0,Length(bb1))\n"
                 "bb1 = Byte_Concat(bb1, XOR8(bb1))", "a", "b", "c", "x", "y", "c0", "c1", "c2", "c3", "c4", "bb1")
    assert got == ["\r\n\t", "\r0\n\t", "", "111", "111", "{45,212}", "{236,197}", "{0,0}", "{66,18}", "{171,174}",
                   "{16,32,80,240,255,255,255,111}"]


def test_e55_crc16_every_algorithm() -> None:
    """Algorithms 1, 2, 5, 6 against their catalogue check values (CRC-16/MODBUS, the Sick
    checksum, XMODEM, KERMIT of "123456789"), 7 (Schunk gripper: init 0xFFFF, polynomial 0x1021
    forward, L7230) giving what 4 gives for the manual's bytes (L7245: {0xAB, 0xAE}); 8 is an error."""
    got = values('byte[] d = String_ToByte("123456789")\nbyte[] m = CRC16(1, d)\nbyte[] x = CRC16(5, d)\n'
                 "byte[] k = CRC16(6, d)\nbyte[] bb1 = {0x10, 0x20, 0x50, 0xF0, 0xFF, 0xFF, 0xFF}\n"
                 "byte[] s7 = CRC16(7, bb1)\nbyte[] s7b = CRC16(7, bb1, 1, 3)\nbyte[] s4b = CRC16(4, bb1, 1, 3)",
                 "m", "x", "k", "s7", "s7b", "s4b")
    assert got[:3] == ["{75,55}", "{49,195}", "{33,137}"]  # 0x4B37, 0x31C3, 0x2189
    assert got[3] == "{171,174}" and got[4] == got[5]
    with pytest.raises(TMError):
        run("byte[] bb1 = {1}\nbyte[] c = CRC16(8, bb1)")


def test_e56_listen_packet() -> None:
    got = values('string a = ListenPacket("", "2,Techman Robot")\nstring b = ListenPacket("TMSTA", "00")\n'
                 'string c = ListenPacket("TMSTA", "Hello World")', "a", "b", "c")
    assert got == ["$TMSCT,15,2,Techman Robot,*57\r\n", "$TMSTA,2,00,*41\r\n", "$TMSTA,11,Hello World,*53\r\n"]


def test_e62_sin_in_degrees_binary32() -> None:
    got = values("float a = sin(15)\ndouble b = sin((double)15)\nfloat c = acos(cos(15))", "a", "b", "c")
    assert got[0] == "0.25881904"  # L8889
    assert got[2] == "15.000003"  # L9081
    assert got[1].startswith("0.258819045102")


def test_numbers_e01_e02_e03_e09() -> None:
    got = values("byte b = 0 - 100\nbyte c = 255\nc = c + 1\nint i = 2147483647\ni = i + 1\n"
                 "int d = 10 / 3\nfloat f = 10 / 3.0\nint j = \"0x89AB\"\nint k = (int)1.99\nbyte m = (byte)1000",
                 "b", "c", "i", "d", "f", "j", "k", "m")
    assert got == ["156", "0", "-2147483648", "3", "3.3333333", "35243", "1", "232"]


def test_pose_math_round_trip_e63() -> None:
    context.use_robot("TM5-900")
    got = values("float[] p1 = {100, 200, 300, 10, 20, 30}\nfloat[] p2 = {150, 180, 320, -5, 45, 60}\n"
                 "float[] d = trans(p1, p2, true)\nfloat[] back = applytrans(p1, d, true)\n"
                 "float[] w = trans(p1, p2)\nfloat[] back2 = applytrans(p1, w)", "back", "back2")
    for text in got:
        nums = [float(x) for x in text.strip("{}").split(",")]
        assert all(abs(a - b) < 1e-3 for a, b in zip(nums, [150, 180, 320, -5, 45, 60]))


def test_points2coord_and_intercoord_l9733_l9843() -> None:
    """The manual's three examples, to the 7 significant digits it prints (1e-5 near 0)."""
    context.use_robot("TM5-900")
    got = values("float[] a = points2coord({389.9641,-4.797323,416.2175,177.3384,0.9190881,91.07789},"
                 "{365.0222,137.3036,423.2249,177.4598,0.9549707,112.4033},"
                 "{546.7307,94.02614,385.1812,176.3468,0.5975906,95.82078})\n"
                 "float[] b = points2coord(260,0,360,260,100,360,100,0,360)\n"
                 "float[] c = intercoord({-69.73,380.02,141.79,-176.11,1.13,-121.27},{58.81,613.03,140.7,171.62,-0.89,0.8})",
                 "a", "b", "c")
    want = [[389.9641, -4.797323, 416.2175, -168.6551, -2.780696, 99.9553], [260, 0, 360, 0, 0, 90],
            [-5.460001, 496.52502, 141.245, 176.06546, 0.23468152, 61.116673]]
    for text, manual in zip(got, want):
        assert [float(x) for x in text.strip("{}").split(",")] == pytest.approx(manual, rel=5e-7, abs=1e-5)
    with pytest.raises(TMError, match="do not define a frame"):
        run("float[] d = points2coord(0,0,0,1,0,0,2,0,0)")


def test_e04_e05_single_quoted_variables_in_strings() -> None:
    p = translate_packet('string s = "TM5"\nstring a = "Hi, \'s\' Robot"\nstring b = "Hi, \'x\' Robot"\n'
                         'string[] ss = {"Techman", "Robot"}\nstring c = "Hi, \'s\' \'ss[0]\' Robot"\n'
                         'string d = "Hi, s Robot"\nstring e = "Hi, \'" + "s" + "\' Robot"')
    assert [(w.code, w.span.line) for w in p.warnings] == [("GPL5315", 2), ("GPL5315", 5)]
    got = values('string s = "TM5"\nstring a = "Hi, \'s\' Robot"\nstring b = "Hi, \'x\' Robot"\n'
                 'string[] ss = {"Techman", "Robot"}\nstring c = "Hi, \'s\' \'ss[0]\' Robot"\n'
                 'string d = "Hi, s Robot"\nstring e = "Hi, \'" + "s" + "\' Robot"', "a", "b", "c", "d", "e")
    assert got == ["Hi, TM5 Robot", "Hi, 'x' Robot", "Hi, TM5 'ss[0]' Robot", "Hi, s Robot", "Hi, 's' Robot"]


def test_getstring_bases_formats_separators_l5111_l5560() -> None:
    """The manual's GetString examples that agree with its own parameter tables (its int[] and
    double[] hex lines and some binary ones have digits missing or doubled: L5205-L5240)."""
    got = values("byte n = 123\nstring a = GetString(n, 16)\nstring b = GetString(n, 2)\nstring c = GetString(n, 16, 3)\n"
                 "string d = GetString(n, 2, 2)\nbyte[] bn = {12, 34, 56}\nstring e = GetString(bn, 16)\n"
                 "string f = GetString(bn, 2)\nstring g = GetString(bn, 16, 3)\nstring h = GetString(bn, 2, 2)\n"
                 "int i = 1234\nstring j = GetString(i, 16)\nstring k = GetString(i, 16, 3)\nstring l = GetString(i, 2, 2)\n"
                 "int[] m = {123, 345, -123, -456}\nstring o = GetString(m, 16, 3)\nfloat p = 12.34\n"
                 "string q = GetString(p, 16)\nstring r = GetString(p, 2)\nstring s = GetString(p, 2, 2)\n"
                 "float[] t = {123.4, 345.6, -123.4, -456.7}\nstring u = GetString(t, 16)\ndouble w = 12.34\n"
                 "string x = GetString(w, 16)\nbool y = true\nstring z = GetString(y, 16, 3)",
                 *"abcdefghjkloqrsuxz")
    assert got == ["0x7B", "0b01111011", "7B", "0b1111011", "{0x0C,0x22,0x38}", "{0b00001100,0b00100010,0b00111000}",
                   "{C,22,38}", "{0b1100,0b100010,0b111000}", "0x000004D2", "4D2", "0b10011010010",
                   "{7B,159,FFFFFF85,FFFFFE38}", "0x414570A4", "0b01000001010001010111000010100100",
                   "0b1000001010001010111000010100100", "{0x42F6CCCD,0x43ACCCCD,0xC2F6CCCD,0xC3E4599A}",
                   "0x4028AE147AE147AE", "true"]
    v = run('string[] n = {"123.45", "345.67", "-12""3.48", "-45A6.79"}\nstring a = GetString(n, 1)\n'
            'string b = GetString(n, 2)\nstring c = GetString(n, 10, 3)\nstring d = GetString(n, "-", 2)\n'
            "byte[] bn = {12, 34, 56}\nstring e = GetString(bn, \"-\")\nstring f = GetString(bn, \"-\", 16, 3)\n"
            'string g = GetString(bn, "[0]=", "-")\nstring h = GetString(bn, "[0]=", "-", 2, 2)\n'
            'string i = GetString(bn, newline, 16)\nbyte one = 123\nstring j = GetString(one, "[0]=", "-", 16)')
    assert v.a == '{"123.45","345.67","-12""3.48","-45A6.79"}'
    assert v.b == '{123.45,345.67,-12"3.48,-45A6.79}'
    assert v.c == '{123.45,345.67,"-12""3.48",-45A6.79}'
    assert v.d == '123.45-345.67--12"3.48--45A6.79'
    assert (v.e, v.f) == ("12-34-56", "C-22-38")
    assert (v.g, v.h) == ("[0]=12-[1]=34-[2]=56", "[0]=0b1100-[1]=0b100010-[2]=0b111000")
    assert v.i in ("0x0C\r\n0x22\r\n0x38", "0x0C\n0x22\n0x38") and v.j == "0x7B"


def test_get_all_tokens_l6270() -> None:
    """The manual's GetAllTokens examples on "$abcd$1234$ABCD$" and "#abcd$1234#ABCD$5678#"
    (L6300-L6400; its comment lines under the first group are misplaced copies)."""
    first = [('"", ""', "{$abcd$1234$ABCD$}"), ('"$", "$"', "{$abcd$,$ABCD$}"), ('"$", "$", 1', "{abcd,ABCD}"),
             ('"$", ""', "{$abcd,$1234,$ABCD,$}"), ('"", "$", 1', "{,abcd,1234,ABCD}")]
    second = [('"", "", 0', "{#abcd$1234#ABCD$5678#}"), ('"$", "", 0', "{$1234#ABCD,$5678#}"),
              ('"$", "", 1', "{1234#ABCD,5678#}"), ('"$", "", 2', "{}"), ('"$", "", 3', "{}"),
              ('"$", "$", 0', "{$1234#ABCD$}"), ('"$", "$", 1', "{1234#ABCD}"), ('"$", "$", 2', "{}"),
              ('"#", "", 0', "{#abcd$1234,#ABCD$5678,#}"), ('"#", "", 1', "{abcd$1234,ABCD$5678,}"),
              ('"#", "", 2', "{#abcd$1234,#ABCD$5678,#}"), ('"#", "$", 1', "{abcd,ABCD}"),
              ('"#", "$", 2', "{#abcd$,#ABCD$}"), ('"", "$", 0', "{#abcd$,1234#ABCD$}"),
              ('"", "$", 3', "{#abcd,1234#ABCD}"), ('"", "#", 0', "{#,abcd$1234#,ABCD$5678#}"),
              ('"", "#", 1', "{,abcd$1234,ABCD$5678}")]
    for text, cases in (("$abcd$1234$ABCD$", first), ("#abcd$1234#ABCD$5678#", second)):
        script = f'string n = "{text}"\n' + "\n".join(
            f"string[] t{i} = GetAllTokens(n, {args})" for i, (args, _) in enumerate(cases))
        assert values(script, *(f"t{i}" for i in range(len(cases)))) == [want for _, want in cases]


def test_value_reverse_l4589() -> None:
    """The manual's ValueReverse examples (its string[] line drops a character: "GFEDCBA" for
    "ABCDEFGH", L4855)."""
    got = values("int i = 10000\nint a = ValueReverse(i, 0)\nint b = ValueReverse(i, 1)\nint j = 100000\n"
                 "int c = ValueReverse(j, 0)\nint d = ValueReverse(j, 1)\nint e = ValueReverse(j, 2)\n"
                 'string s = ValueReverse("ABCDEF")\nint[] k = {10000, 20000, 60000, 80000}\n'
                 "int[] f = ValueReverse(k, 0)\nint[] g = ValueReverse(k, 1)\nint[] h = ValueReverse(k, 2)\n"
                 "float[] x = {10000, 20000}\nfloat[] y = ValueReverse(x)\ndouble[] z = {10000, 20000}\n"
                 'double[] w = ValueReverse(z)\nstring[] t = {"ABCDEFGH", "12345678"}\nstring[] u = ValueReverse(t)',
                 *"abcdesfghyu")
    assert got[:9] == ["270991360", "4135", "-1601830656", "-1601830656", "-24442", "FEDCBA",
                       "{270991360,541982720,1625948160,-2143813376}", "{4135,8270,1625948160,-2143813376}",
                       "{4135,8270,24810,-32712}"]
    assert got[9] == "{5.887614E-39,5.933532E-39}" and got[10] == "{HGFEDCBA,87654321}"
    v = run("double[] z = {10000, 20000}\ndouble[] w = ValueReverse(z)")
    assert [float(x) for x in v.w] == pytest.approx([4.428251e-317, 4.430275e-317], rel=1e-6)

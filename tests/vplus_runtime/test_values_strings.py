"""V+ variables, operators, string functions and binary packing, called as generated code calls them."""

from __future__ import annotations

import struct

import pytest

from gplrt import vplus as vp
from gplrt.sim import Simulation


def test_undefined_read_is_vplus_error_and_defined_says_so(sim: Simulation) -> None:
    x = vp.Cell("x")
    assert vp.defined(x) == 0.0
    with pytest.raises(vp.VError) as info:
        _ = x.v
    assert info.value.ErrorCode == -401 and info.value.Message() == "*Undefined value*"
    x.v = 3
    assert x.v == 3.0 and vp.defined(x) == -1.0


def test_type_fixed_by_first_assignment(sim: Simulation) -> None:
    s = vp.Cell("$s")
    s.v = "abc"
    with pytest.raises(vp.VError) as info:
        s.v = 1.0
    assert info.value.Message() == "*Data type mismatch*"


def test_globals_per_session_and_15_significant_characters() -> None:
    a, b = Simulation(capture=True), Simulation(capture=True)
    with a:
        vp.G["mcp.noblink.char"].v = 3
        assert vp.G["MCP.NOBLINK.CHA"].v == 3.0  # one variable under the 15-character rule
    with b:
        assert not vp.G["mcp.noblink.cha"].defined  # another session shares nothing
    a.close()
    b.close()


def test_by_reference_and_by_value_arguments(sim: Simulation) -> None:
    """tests/vplustests.v2: CALL inc(a+0, b) changes b but not a."""
    @vp.program("inc")
    def inc(a: vp.Ref, b: vp.Ref) -> None:
        a.v = a.v + 1
        b.v = b.v + 1

    a, b = vp.Cell("a"), vp.G["b"]
    a.v, b.v = 1, 1
    inc(vp.byval(vp.add(a.v, 0)), b)
    assert (a.v, b.v) == (1.0, 2.0)
    vp.calls("INC", a, b)  # CALLS by name, case-insensitive
    assert (a.v, b.v) == (2.0, 3.0)
    with pytest.raises(vp.VError) as info:
        vp.calls("nosuch")
    assert info.value.Message() == "*Undefined program or variable name*"


def test_arrays_grow_last_and_element_references(sim: Simulation) -> None:
    a = vp.VArray("a", 5)
    for i in range(4):
        a[i] = i
    assert vp.last(a) == 3.0  # vplustests.v2 "array test [=> 0 1 2 3]"
    with pytest.raises(vp.VError):
        _ = a[4]
    a[40] = 7
    assert vp.last(a) == 40.0
    m = vp.G.array("m")
    m[2, 3] = 1
    assert vp.last(m, 2) == 3.0
    r = a.ref(1)
    r.v = 11
    assert a[1] == 11.0
    with pytest.raises(vp.VError) as info:
        a[-1] = 0
    assert info.value.Message() == "*Illegal array index*"


def test_string_array_element_never_assigned_is_undefined_value(sim: Simulation) -> None:
    """ros.v2 ros.srv.cmd appends $msg.jts[idx] that nothing assigned: an AUTO array's elements
    are allocated, not assigned, so the first one read is *Undefined value* (L4129-4143), as for
    a real array (docs/design/vplus.md, "string array elements")."""
    jts = vp.VArray("$msg.jts", 10)
    msg = vp.Cell("$msg")
    msg.v = "head"
    with pytest.raises(vp.VError) as info:
        msg.v = vp.add(msg.v, jts[1])
    assert (info.value.ErrorCode, info.value.Message()) == (-401, "*Undefined value*")
    assert msg.v == "head"
    jts[2] = "x"  # an assigned element of the same array reads as assigned
    assert vp.add(msg.v, jts[2]) == "headx"


def test_operators_are_vplus_logic() -> None:
    assert vp.band(3, 6) == 2.0 and vp.bor(3, 6) == 7.0 and vp.bxor(3, 6) == 5.0
    assert vp.and_(3, 6) == -1.0 and vp.or_(3, 0) == -1.0 and vp.xor_(3, 6) == 0.0
    assert vp.com(0) == -1.0 and vp.not_(5) == 0.0
    assert vp.mod(9, 6) == 3.0 and vp.sqr(2) - 1 == 3.0 and vp.sqrt(9) == 3.0
    assert vp.bmask(1, 5) == 31.0 and vp.sign(0) == 0.0
    assert vp.to_int(2.5) == 3 and vp.to_int(-2.5) == -3
    with pytest.raises(vp.VError) as info:
        vp.div(1, 0)
    assert info.value.Message() == "*Divide by zero*"


def test_string_compare_ignores_case_while_upper_is_on(sim: Simulation) -> None:
    assert vp.eq("yes", "YES") == -1.0
    vp.disable("UPPER")
    assert vp.eq("yes", "YES") == 0.0


def test_string_functions(sim: Simulation) -> None:
    assert vp.s_mid("abcdef", 2, 3) == "bcd"
    assert vp.len_("abc") == 3.0 and vp.asc("A") == 65.0 and vp.s_chr(65) == "A"
    assert vp.val("  12.5abc") == 12.5 and vp.val("x") == 0.0
    assert vp.pos("hello", "ll") == 3.0
    assert vp.s_error(-504) == "*Unexpected end of file*"
    text = vp.Cell("$t")
    text.v = "12,34"
    assert vp.s_decode(text, ",", 0) == "12" and text.v == ",34"
    assert vp.s_decode(text, ",", 1) == "," and text.v == "34"
    with pytest.raises(vp.VError) as info:
        vp.add("x" * 100, "y" * 29)
    assert info.value.Message() == "*String too long*"


def test_encode_formats() -> None:
    message = "The length of this line is: "
    # the Guide's example (L5363-5371)
    assert vp.s_encode(message, vp.fmt("/I0"), vp.len_(message) + 14) + " characters." == \
        "The length of this line is: 42 characters."
    assert vp.s_encode(27) == "27" and vp.s_encode(0.5) == "0.5" and vp.s_encode(2 ** 0.5) == "1.414214"
    assert vp.s_encode(vp.fmt("/F8.2"), 3.14159) == "    3.14"
    assert vp.s_encode(11000) == "11000"


def test_binary_packing_most_significant_byte_first() -> None:
    assert vp.s_lngb(56) == "\x00\x00\x00\x38"
    assert vp.lngb("\xff\xff\xff\xfe") == -2.0
    assert vp.s_intb(-2) == "\xff\xfe" and vp.intb("\x01\x02") == 258.0
    packed = vp.s_fltb(1.5)
    assert packed.encode("latin-1") == struct.pack(">f", 1.5)
    assert vp.fltb(packed) == 1.5
    assert vp.dblb(vp.s_dblb(0.1)) == 0.1
    # ros.v2's reversal of a packed field gives the little-endian bytes ROS reads
    assert vp.s_lngb(10)[::-1].encode("latin-1") == struct.pack("<i", 10)


def test_type_output(sim: Simulation) -> None:
    vp.type_("The value of x is ", 27, ".")
    vp.type_("All done. ", vp.fmt("/I0"), 100, " pieces processed.")
    vp.type_("no end", vp.fmt("/S"))
    vp.type_(vp.fmt("/C1"), "x")
    assert sim.console.output == "The value of x is 27.\nAll done. 100 pieces processed.\nno end\nx\n"


def test_tier3_keyword_is_not_implemented_naming_it() -> None:
    with pytest.raises(vp.VError) as info:
        vp.unsupported("VPICTURE", 1)
    assert info.value.Message() == "*Not implemented*" and "VPICTURE" in str(info.value)


def test_wrong_operand_types_are_vplus_errors() -> None:
    for call in (lambda: vp.sub("a", 1), lambda: vp.add("a", 1), lambda: vp.mul(vp.trans(1), 2),
                 lambda: vp.to_int("3")):
        with pytest.raises(vp.VError):
            call()


# The twelve error codes the User's Guide prints with their text (seed 002; the seeds hold no
# error-message appendix): $ERROR gives each as printed there (runtime/gplrt/vplus/errors.py).
GUIDE_ERRORS = {
    -504: "*Unexpected end of file*",    # L5359-5361, L8078
    -522: "*Data error on device*",      # L8064
    -524: "*Communications overrun*",    # L8069
    -526: "*No data received*",          # L8074, L7530-7535
    -620: "*Speed pot or STEP not pressed*",  # L9793-9795
    -624: "*Force protect limit exceeded*",   # L5830 (printed lower-case, its closing * lost)
    -666: "*Device Hardware not Present*",    # L12019 (and *Must use Monitor #1*, L12015)
    -1003: "*Time-out nulling errors*",  # L5832
    -1006: "*Soft envelope error*",      # L5833
    -1011: "*No zero index*",            # L12618
    -1012: "*Lost encoder sync*",        # L12616
    -1013: "*Encoder quadrature error*",  # L12617
}


def test_the_error_codes_the_guide_prints_have_its_texts() -> None:
    assert {code: vp.s_error(code) for code in GUIDE_ERRORS} == GUIDE_ERRORS

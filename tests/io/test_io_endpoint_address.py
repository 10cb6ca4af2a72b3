"""IPEndPoint.IPAddress accepts exactly a dotted-quad IPv4 address (or "" = any), else -1704.

The C library's ``inet_aton`` that the setter used to call also takes the historic short forms
("1.2.3" = 1.2.0.3, "10.1", "2130706433"), hex and octal parts ("0x7f.1", "010.0.0.1" = 8.0.0.1)
and anything after a space ("1.2.3.4 junk"); a controller would reject them, and a GPL program
that wrote one meant something else.
"""

from __future__ import annotations

import pytest

from gplrt.io import IPEndPoint
from gplrt.lang.errors import ARITHMETIC_OVERFLOW, INVALID_ADDRESS, INVALID_NUMBER_FORMAT, VALUE_OUT_OF_RANGE
from gplrt.lang.gpltypes import Integer, String
from gpltest import code_of, free_port

MALFORMED = [
    "1.2.3",  # three parts
    "1.2.3.4.5",  # five parts
    "10.1",
    "2130706433",  # one 32-bit number
    "256.1.1.1",  # a part above 255
    "1.2.3.999",
    "1..2.3",  # an empty part
    "1.2.3.",
    ".1.2.3",
    "0x7f.0.0.1",  # hex
    "1.2.3.-4",
    "+1.2.3.4",
    "1.2.3.4 junk",  # trailing garbage after a space
    "1.2 .3.4",
    "1.2.3.4/24",
    "1.2.3.0004",  # more than three digits
    "١.٢.٣.٤",  # non-ASCII digits
    "abc",
    "localhost",  # host names: see sockets.IPEndPoint's docstring
    "::1",  # IPv6: the controller's sockets are IPv4
]


@pytest.mark.parametrize("text", MALFORMED)
def test_malformed_address_is_1704_in_the_constructor(text: str) -> None:
    assert code_of(IPEndPoint, String(text), Integer(80)) == INVALID_ADDRESS


@pytest.mark.parametrize("text", MALFORMED)
def test_malformed_address_is_1704_in_the_setter_and_keeps_the_old_one(text: str) -> None:
    ep = IPEndPoint(String("10.0.0.7"), Integer(80))
    assert code_of(setattr, ep, "IPAddress", String(text)) == INVALID_ADDRESS
    assert ep.IPAddress == "10.0.0.7"


@pytest.mark.parametrize(
    ("text", "stored"),
    [
        ("192.168.0.2", "192.168.0.2"),
        ("0.0.0.0", "0.0.0.0"),
        ("255.255.255.255", "255.255.255.255"),
        ("  10.0.0.1 ", "10.0.0.1"),  # surrounding blanks ignored, as before
        ("", ""),  # any address
        ("   ", ""),
        # Leading zeros are decimal (not inet_aton's octal) and stored without them, so the
        # address connected to is the one written: 010 is ten, not eight.
        ("192.168.000.010", "192.168.0.10"),
    ],
)
def test_well_formed_address_is_accepted(text: str, stored: str) -> None:
    ep = IPEndPoint(String(text), Integer(80))
    assert ep.IPAddress == stored
    if stored:
        assert ep._remote() == (stored, 80)



# -- the Integer arguments of IPEndPoint and Socket convert by GPL's rules, not Python's int() ------


@pytest.mark.parametrize(("value", "port"), [(80.5, 81), (80.4, 80), ("8080", 8080), (-0.4, 0)])
def test_port_converts_like_any_integer_argument(value: object, port: int) -> None:
    assert IPEndPoint(String("1.2.3.4"), value).Port == port  # CInt rounds; int() truncated 80.5


@pytest.mark.parametrize(
    ("value", "code"),
    [("abc", INVALID_NUMBER_FORMAT), (float("nan"), ARITHMETIC_OVERFLOW), (1e300, ARITHMETIC_OVERFLOW),
     (65536, VALUE_OUT_OF_RANGE), (-1, VALUE_OUT_OF_RANGE)],
)
def test_bad_port_is_a_gpl_error(value: object, code: int) -> None:
    """Before: ValueError from int() for "abc" and NaN."""
    assert code_of(IPEndPoint, String("1.2.3.4"), value) == code


@pytest.mark.parametrize("member", ["ReceiveTimeout", "SendTimeout"])
def test_socket_timeouts_convert_by_gpl_rules(member: str) -> None:
    from gplrt.io.sockets import UdpClient

    udp = UdpClient(IPEndPoint(String("127.0.0.1"), Integer(0)))
    try:
        sock = udp.Client()
        setattr(sock, member, 99.5)
        assert getattr(sock, member) == 100
        assert code_of(setattr, sock, member, "soon") == INVALID_NUMBER_FORMAT
        assert code_of(setattr, sock, member, float("nan")) == ARITHMETIC_OVERFLOW
    finally:
        udp.Close()


def test_receive_and_send_lengths_convert_by_gpl_rules() -> None:
    from gplrt.io.sockets import UdpClient
    from gplrt.lang.byref import Box

    me = IPEndPoint(String("127.0.0.1"), Integer(free_port()))
    udp = UdpClient(me)
    try:
        sock = udp.Client()
        assert sock.SendTo(String("abcdef"), 2.5, me) == 3  # CInt(2.5) = 3 (half away from zero)
        got = Box("")
        assert sock.ReceiveFrom(got, 10, Box(None)) == 3 and got.value == "abc"
        assert code_of(sock.Receive, Box(""), float("nan")) == ARITHMETIC_OVERFLOW
        assert code_of(sock.ReceiveFrom, Box(""), "many", Box(None)) == INVALID_NUMBER_FORMAT
        assert code_of(sock.SendTo, String("x"), "all", me) == INVALID_NUMBER_FORMAT
    finally:
        udp.Close()

"""IPEndPoint.IPAddress accepts exactly a dotted-quad IPv4 address (or "" = any), else -1704.

The C library's ``inet_aton`` that the setter used to call also takes the historic short forms
("1.2.3" = 1.2.0.3, "10.1", "2130706433"), hex and octal parts ("0x7f.1", "010.0.0.1" = 8.0.0.1)
and anything after a space ("1.2.3.4 junk"); a controller would reject them, and a GPL program
that wrote one meant something else.
"""

from __future__ import annotations

import pytest

from gplrt.io import IPEndPoint
from gplrt.lang.errors import INVALID_ADDRESS
from gplrt.lang.gpltypes import Integer, String
from gpltest import code_of

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


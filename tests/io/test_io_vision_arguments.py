"""Vision members take their arguments by GPL's rules, as every other built-in class does: numbers
round like CInt, numeric text converts, bad text is -717, and the IP address is a dotted quad
(-1704 otherwise, as for IPEndPoint)."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from gplrt.io.vision import ScriptedVisionServer, Vision, VisionToolResult, set_vision_server
from gplrt.lang.errors import GplException


@pytest.fixture
def server() -> Iterator[ScriptedVisionServer]:
    srv = ScriptedVisionServer()
    srv.add_process("Main", {"part": [VisionToolResult(info=[10.0, 20.0, 30.0]),
                                      VisionToolResult(info=[40.0])]})
    set_vision_server(srv)
    yield srv
    set_vision_server(None)


def test_instance_and_indexes_round_like_cint_and_take_numeric_text(server: ScriptedVisionServer) -> None:
    vis = Vision()
    vis.Instance = 2.6
    assert vis.Instance == 3
    vis.Instance = "4"
    assert vis.Instance == 4
    vis.Process("Main", 7.5)
    assert vis.Result("part", 1.6).Info(0) == 40.0  # index 2
    assert vis.Result("part", "1").Info("2") == 30.0
    assert vis.Result("part", 1).Info(1.4) == 20.0


@pytest.mark.parametrize("member", ["Instance", "Result", "Info"])
def test_bad_text_is_717_not_a_python_error(server: ScriptedVisionServer, member: str) -> None:
    vis = Vision()
    vis.Process("Main")
    calls = {"Instance": lambda: setattr(vis, "Instance", "two"),
             "Result": lambda: vis.Result("part", "first"),
             "Info": lambda: vis.Result("part", 1).Info("x")}
    with pytest.raises(GplException) as exc:
        calls[member]()
    assert exc.value.ErrorCode == -717


@pytest.mark.parametrize("text", ["1.2.3", "1.2.3.256", "10.0.0.1 junk", "vision-host"])
def test_a_malformed_ip_address_is_1704(text: str) -> None:
    vis = Vision()
    with pytest.raises(GplException) as exc:
        vis.IPAddress = text
    assert exc.value.ErrorCode == -1704
    assert vis.IPAddress == ""


def test_a_dotted_quad_is_kept_in_its_canonical_form() -> None:
    vis = Vision()
    vis.IPAddress = " 192.168.000.010 "
    assert vis.IPAddress == "192.168.0.10"

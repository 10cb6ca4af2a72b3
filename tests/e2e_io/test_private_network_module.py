"""The harness's module form of ``private_network`` (``gpltest.private_network_module``).

A module-scoped fixture listens on a fixed port, as TCS does on 10100; every test of the module
shares it.  Outside the network namespace the module runs again inside one, and each test here
takes the outcome its twin had there: a pass passes, a failure fails (shown by the strict
expected failure below, which would XPASS, and so fail, if the inner failure were lost).
"""

from __future__ import annotations

import socket
from collections.abc import Iterator
from typing import Any

import pytest

from gpltest import PrivateRun, private_network_module

FIXED_PORT = 10100  # TCS's robot port: bound by every run of this module, never shared


class Server:
    """What the module's tests share: one listening socket on the fixed port."""

    def __init__(self) -> None:
        self.sock = socket.create_server(("127.0.0.1", FIXED_PORT))
        self.served: list[str] = []


@pytest.fixture(scope="module")
def server(request: Any) -> Iterator[Server | PrivateRun]:
    elsewhere = private_network_module(request)
    if elsewhere is not None:
        yield elsewhere
        return
    here = Server()
    try:
        yield here
    finally:
        here.sock.close()


def shared(server: Server | PrivateRun, request: Any) -> Server | None:
    """The live server, or None once this test has taken its outcome from the namespace."""
    if isinstance(server, PrivateRun):
        server.reproduce(request)
        return None
    return server


def test_first_test_binds_the_fixed_port(server: Server | PrivateRun, request: Any) -> None:
    here = shared(server, request)
    if here is None:
        return
    assert here.sock.getsockname()[1] == FIXED_PORT
    here.served.append("first")


def test_second_test_shares_the_first_ones_server(server: Server | PrivateRun, request: Any) -> None:
    here = shared(server, request)
    if here is None:
        return
    assert here.served == ["first"]  # the same object: one server for the module, in order
    with socket.create_connection(("127.0.0.1", FIXED_PORT), timeout=5):
        pass


@pytest.mark.xfail(strict=True, reason="fails inside the namespace on purpose: the failure must reach this run")
def test_a_failure_inside_fails_here(server: Server | PrivateRun, request: Any) -> None:
    here = shared(server, request)
    if here is None:
        return
    raise AssertionError("failing where the server runs")

"""Fixtures of the TM tests: a simulated TM5-900 with its Listen node and Ethernet Slave on free
loopback ports (the fast clock: motions take no wall time)."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from gplrt.tm import context
from gplrt.tm.listen import ListenNode
from gplrt.tm.slave import EthernetSlave

from gpl2py.tmscript.pipeline import translate_packet


@pytest.fixture
def tm_robot() -> Iterator[tuple[object, ListenNode, EthernetSlave]]:
    robot = context.use_robot("TM5-900")
    node = ListenNode(robot, translate_packet, "127.0.0.1", 0).serve()
    slave = EthernetSlave(robot, "127.0.0.1", 0).serve()
    try:
        yield robot, node, slave
    finally:
        node.close()
        slave.close()
        context.set_node(None)

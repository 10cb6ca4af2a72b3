"""A simulated TM robot whose flow sits in a Listen node, its packets translated by this front end.

The runtime's node (``gplrt.tm.listen``) never imports the transpiler; it is handed
:func:`gpl2py.tmscript.pipeline.translate_packet` here, so a packet's script goes through the
same front end as a script project's (no second interpreter).  :func:`serve` is what a notebook
or a test calls; :func:`main` is ``gpl2py run --robot TM5-900 --listen-node``.
"""

from __future__ import annotations

import math

from gplrt.tm.listen import PORT, EthernetSlave, ListenNode
from gplrt.tm.listen import main as _main
from gplrt.tm.listen import serve as _serve

from gpl2py.tmscript.pipeline import translate_packet

#: The Ethernet Slave's port on a TM robot (manual §3.19).
SVR_PORT = 5891


def serve(robot: str = "TM5-900", host: str = "127.0.0.1", port: int = PORT, svr_port: int = SVR_PORT,
          speed: float = math.inf, clock: str | None = None) -> tuple[ListenNode, EthernetSlave]:
    """``(node, slave)`` of a simulated ``robot``, serving in the background until
    ``node.close()`` and ``slave.close()``; port 0 takes a free port (``node.port``, ``slave.port``);
    ``clock`` ``fast`` (default), ``virtual`` or ``real`` (at ``speed``), docs/design/clock.md."""
    return _serve(translate_packet, robot, host, port, svr_port, speed, clock)


def main(robot: str = "TM5-900", host: str = "127.0.0.1", port: int = PORT, svr_port: int = SVR_PORT,
         speed: float = math.inf, clock: str | None = None) -> int:
    """Serve until interrupted (``gpl2py run --listen-node``); the exit status."""
    return _main(translate_packet, robot, host, port, svr_port, speed, clock)


__all__ = ["SVR_PORT", "main", "serve"]

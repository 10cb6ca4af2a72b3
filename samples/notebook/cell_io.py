"""The pick-and-place cell's conveyor and gripper, as seen from the controller's I/O.

The cell (samples/pick_and_place) talks to two devices through digital signals (Feeder.gpl and
Gripper.gpl document the wiring):

* output 2 asks the conveyor for a part; input 10001 says a part is at the pick position;
* output 1 closes the gripper; input 10002 says the jaws are closed.

``wire(io)`` makes the simulated controller answer like the real devices: a part arrives 0.2 s
after it is requested and is gone 0.3 s after the jaws close; the jaws report closed 0.15 s after
the close command and open 0.1 s after it drops.  ``setup(sim)`` is the hook
``gpl2py run --setup samples/notebook/cell_io.py`` calls before ProjectStart.
"""

from __future__ import annotations

from typing import Any

DOUT_CLOSE, DOUT_REQUEST = 1, 2
DIN_PRESENT, DIN_CLOSED = 10001, 10002


def wire(io: Any) -> None:
    """Add the conveyor's and the gripper's responses to ``io`` (a gplrt IoMap)."""
    io.when_output(DOUT_REQUEST, True).set_input(DIN_PRESENT, True, after=0.2)
    io.when_output(DOUT_CLOSE, True).set_input(DIN_PRESENT, False, after=0.3)
    io.when_output(DOUT_CLOSE, True).set_input(DIN_CLOSED, True, after=0.15)
    io.when_output(DOUT_CLOSE, False).set_input(DIN_CLOSED, False, after=0.1)


def setup(sim: Any) -> None:
    """``gpl2py run --setup`` hook: wire the devices of this cell."""
    wire(sim.io)

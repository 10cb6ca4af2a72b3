"""The pick-and-place cell (samples/pick_and_place) for ``gpl2py sweep``: its conveyor and gripper
wired as in samples/notebook/cell_io.py, with two of them varied by the parameter file:

* ``interval``: seconds from the cell's request (output 2) to the part at the pick position
  (input 10001) -- how fast the conveyor brings parts;
* ``speed``: the Speed (percent) of the cell's fast Profiles, ``GPO.prof_fast`` and
  ``GPO.prof_blend``, which carry the part between the conveyor and the pallet.

``gpl2py sweep`` calls ``setup(sim, params, cell)`` before each run's ProjectStart, after the
modules' Init (so the Profiles exist and a change here is the one the run uses).  This file is
shipped to the workers as text: it imports nothing but the standard library.
"""

from __future__ import annotations

from typing import Any

DOUT_CLOSE, DOUT_REQUEST = 1, 2
DIN_PRESENT, DIN_CLOSED = 10001, 10002


def setup(sim: Any, params: dict[str, Any], cell: Any) -> None:
    """Wire the conveyor (after ``interval`` s) and the gripper; set the fast Profiles' Speed."""
    io = sim.io
    io.when_output(DOUT_REQUEST, True).set_input(DIN_PRESENT, True, after=params.get("interval", 0.2))
    io.when_output(DOUT_CLOSE, True).set_input(DIN_PRESENT, False, after=0.3)
    io.when_output(DOUT_CLOSE, True).set_input(DIN_CLOSED, True, after=0.15)
    io.when_output(DOUT_CLOSE, False).set_input(DIN_CLOSED, False, after=0.1)
    if "speed" in params:
        gpo = cell.module("GPO")
        gpo.prof_fast.Speed = params["speed"]
        gpo.prof_blend.Speed = params["speed"]

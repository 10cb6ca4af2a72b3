#!/usr/bin/env bash
# The palletising sample on the simulated controller, end to end; sets up .venv first if needed.
# Transpiles samples/pick_and_place (cached: a second run starts at once), runs ProjectStart with
# the conveyor and gripper of samples/notebook/cell_io.py answering its I/O, prints the program's
# console output, and saves a plot of the robot's motion (GPL2PY_DEMO_OUT, default build/demo).
source "$(dirname "$0")/_venv.sh"
OUT="${GPL2PY_DEMO_OUT:-build/demo}"
gpl2py run samples/pick_and_place --setup samples/notebook/cell_io.py --plot "$OUT/pick_and_place.png"

# %% [markdown]
# # The palletising cell, step by step
#
# A cell-marked script (`# %%`): VS Code, PyCharm and JupyterLab (jupytext) run it cell by cell
# like a notebook; `python samples/notebook/pick_and_place.py` runs it top to bottom.  It uses
# `gpl2py.notebook.Cell` to translate `samples/pick_and_place` (through the same cache as
# `gpl2py run`), call single GPL procedures, drive inputs, read outputs and the robot's pose, run
# the whole cell, and show the motion, the variables and the I/O.  In Jupyter, a cell that ends
# with a pose, a frame, a table or a plot shows it (a table, a figure).
#
# The plot goes to `$GPL2PY_NOTEBOOK_OUT` (default `build/notebook/`).

# %%
import os
import sys
from pathlib import Path

from gpl2py.notebook import Cell
from gplrt.lang.errors import GplException


def _here() -> Path:
    """This folder, whether run as a script or cell by cell (where ``__file__`` is not set)."""
    if "__file__" in globals():
        return Path(__file__).resolve().parent
    for base in (Path.cwd(), *Path.cwd().parents):
        for folder in (base, base / "samples" / "notebook"):
            if (folder / "cell_io.py").is_file():
                return folder
    raise FileNotFoundError("run this notebook from the gpl2py repository")


HERE = _here()
OUT = Path(os.environ.get("GPL2PY_NOTEBOOK_OUT", "build/notebook"))
sys.path.insert(0, str(HERE))
from cell_io import DIN_CLOSED, DOUT_CLOSE, wire  # noqa: E402 - the cell's wiring, next to this file

# %% [markdown]
# ## Load the project on a simulated PF400SX, virtual clock
# Virtual time: every wait and motion is computed, not waited for, and each run is identical.

# %%
cell = Cell.load(HERE.parent / "pick_and_place", robot="PF400SX", clock="virtual")
cell.init()  # module variables, then each module's Init (GPO.Init teaches the positions)
print(cell)
print("parts placed so far:", cell.get("Cell.placed"))
print("robot 1 joints at start:", [round(j, 3) for j in cell.where().joints])
cell.where()  # in Jupyter: the joints and the tool pose as a table

# %% [markdown]
# The taught pallet frame, as the GPL module `GPO` holds it:

# %%
cell.module("GPO").pallet

# %% [markdown]
# ## The gripper by hand
# Nothing answers the gripper yet, so `Gripper.Grip(True)` raises the cell's own error code
# after its 2 s timeout: a `GplError` whose text starts with the GPL file, line and source line.
# Then we play the jaw sensor ourselves.

# %%
try:
    cell.call("Gripper.Grip", True)
except GplException as exc:
    print(f"Grip(True) without a sensor: error {exc.ErrorCode} after {cell.time:.2f} s")
    print(exc)
print("close output (DIO 1):", cell.output(DOUT_CLOSE))

cell.set_input(DIN_CLOSED, True)  # the sensor reports the jaws closed
cell.call("Gripper.Grip", True)  # now returns at once
print("Grip(True) with the sensor on: returned at", f"{cell.time:.2f} s")

# %% [markdown]
# ## Wire the conveyor and the gripper, ask for one part

# %%
cell.set_input(DIN_CLOSED, False)
cell.call("Gripper.Grip", False)
wire(cell.io)
waited = cell.call("Feeder.WaitForPart")
print(f"Feeder.WaitForPart: the part arrived after {waited} ms")

# %% [markdown]
# ## Run the whole cell (ProjectStart = Cell.Main)

# %%
status = cell.run_main()
print("status:", status, "- parts placed:", cell.get("Cell.placed"))
pose = cell.where()
x, y, z, yaw, pitch, roll = pose.cartesian
print(f"robot 1 ends at X {x:.3f} Y {y:.3f} Z {z:.3f} mm, yaw {yaw:.3f} pitch {pitch:.3f} roll {roll:.3f} deg"
      f" at {pose.time:.3f} s")
print("gripper commands:", sum(1 for _, signal, _ in cell.outputs_written() if signal == DOUT_CLOSE))

# %% [markdown]
# ## What the program left: its variables and the I/O

# %%
cell.variables()

# %%
cell.io_state()

# %% [markdown]
# ## Plot the motion
# Each plot call shows its figure once; `cell.trace()` shows a summary and the joints.

# %%
cell.plot_joints()

# %%
cell.plot_path()

# %%
cell.trace()

# %%
png = cell.save_plot(OUT / "pick_and_place.png")
print("plot saved to", png)

"""samples/notebook/pick_and_place.py, the cell-marked notebook, runs top to bottom.

The expected final pose comes from the cell's documented geometry (Globals.gpo: pallet frame at
(450, -120, 100) turned 30 deg about Z, rows 45 mm apart along the frame's X, layers 25 mm apart;
part 8 goes to row 2, column 1, layer 2; every depart rises to world Z 250; the hand points along
the frame's rows: yaw 30, pitch 90, roll 180), not from a previous run.
"""

from __future__ import annotations

import math
import os
import re
import subprocess
import sys
from pathlib import Path

from gpltest import REPO

SCRIPT = REPO / "samples/notebook/pick_and_place.py"


def test_cells_are_marked() -> None:
    text = SCRIPT.read_text()
    assert text.count("\n# %%\n") >= 5 and "# %% [markdown]" in text


def test_notebook_script_transpiles_runs_drives_io_and_saves_a_plot(tmp_path: Path) -> None:
    env = {**os.environ, "GPL2PY_NOTEBOOK_OUT": str(tmp_path / "nb")}
    r = subprocess.run([sys.executable, str(SCRIPT)], capture_output=True, text=True, cwd=tmp_path,
                       env=env, timeout=300)
    assert r.returncode == 0, r.stderr
    out = r.stdout
    assert "parts placed so far: 0" in out
    assert "Grip(True) without a sensor: error -3100 after 2.00 s" in out  # Gripper.TIMEOUT_MS
    assert "close output (DIO 1): True" in out
    assert "Feeder.WaitForPart: the part arrived after 200 ms" in out  # conveyor answers in 0.2 s
    assert "cell done: 8 parts placed, 9 requested" in out  # one part was asked for by hand
    assert "status: 0 - parts placed: 8" in out
    m = re.search(r"robot 1 ends at X (\S+) Y (\S+) Z (\S+) mm, yaw (\S+) pitch (\S+) roll (\S+) deg", out)
    assert m, out
    yaw = math.radians(30.0)
    expected = (450 + 45 * math.cos(yaw), -120 + 45 * math.sin(yaw), 250.0, 30.0, 90.0, 180.0)
    assert all(math.isclose(float(v), e, abs_tol=1e-3) for v, e in zip(m.groups(), expected)), m.groups()
    # changes of the close output: closed and opened once by hand (the second Grip(True) writes
    # the value it already has, which is no change), then closed and opened for each of 8 parts
    assert "gripper commands: 18" in out
    png = tmp_path / "nb" / "pick_and_place.png"
    assert f"plot saved to {png}" in out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000

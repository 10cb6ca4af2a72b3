"""samples/notebook/pick_and_place.py executed as a real notebook in a real IPython kernel (issue 15).

The cell-marked script (``# %%``) is turned into a notebook cell by cell, as jupytext does, and
nbclient runs it in an ipykernel, as Jupyter does.  What a person sees is asserted on the outputs
the kernel sent: each plot call shows exactly one image; a pose, a frame, the variables, the I/O
and a trace show as HTML tables (the trace with its plot); no output shows a raw object address;
and a cell that fails (appended here: the sample itself runs to the end) shows the GPL file, line
and source text of the error, not the runtime's frames.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import nbclient  # the test extra installs both (pyproject.toml): never skipped for want of them
import nbformat
import pytest

from gpltest import REPO

SAMPLE = REPO / "samples/notebook/pick_and_place.py"
GRIPPER = REPO / "samples/pick_and_place/Gripper.gpl"
#: Appended to the sample: a call that takes long enough in wall time to show its progress (the
#: threshold is lowered: a real run would take seconds), then a fresh Cell whose gripper nothing
#: answers, called without a Try.
SLOW = "import time\nfrom gplrt.notebook import drive\ndrive(cell.sim, time.sleep, 0.3, progress_after=0.0)"
FAILING = 'broken = Cell.load(HERE.parent / "pick_and_place", echo=False)\nbroken.call("Gripper.Grip", True)'


def cells_of(script: str) -> list[Any]:
    """The notebook cells of a ``# %%`` script: code cells, and ``# %% [markdown]`` comment cells."""
    cells = []
    for chunk in re.split(r"^# %%", script, flags=re.M)[1:]:
        header, _, body = chunk.partition("\n")
        if header.strip() == "[markdown]":
            text = "\n".join(line.removeprefix("#").removeprefix(" ") for line in body.strip().splitlines())
            cells.append(nbformat.v4.new_markdown_cell(text))
        else:
            cells.append(nbformat.v4.new_code_cell(body.strip()))
    return cells


@pytest.fixture(scope="module")
def executed(tmp_path_factory: pytest.TempPathFactory) -> Any:
    out = tmp_path_factory.mktemp("nb")
    book = nbformat.v4.new_notebook()
    book.cells = cells_of(SAMPLE.read_text(encoding="utf-8"))
    book.cells.append(nbformat.v4.new_code_cell(SLOW))
    book.cells.append(nbformat.v4.new_code_cell(FAILING, metadata={"tags": ["raises-exception"]}))
    client = nbclient.NotebookClient(book, timeout=120, kernel_name="python3",
                                     resources={"metadata": {"path": str(SAMPLE.parent)}})
    with pytest.MonkeyPatch.context() as env:
        env.setenv("GPL2PY_NOTEBOOK_OUT", str(out))  # the kernel inherits it
        client.execute()
    return book


def _cell(book: Any, source: str) -> Any:
    found = [c for c in book.cells if c.cell_type == "code" and c.source.strip().endswith(source)]
    assert len(found) == 1, f"no single cell ending with {source!r}"
    return found[0]


def _images(cell: Any) -> int:
    return sum(1 for o in cell.outputs if "image/png" in o.get("data", {}))


def _html(cell: Any) -> str:
    html = [o["data"]["text/html"] for o in cell.outputs if "text/html" in o.get("data", {})]
    assert len(html) == 1, cell.outputs
    return html[0]


def test_each_plot_call_shows_exactly_one_image(executed: Any) -> None:
    for call in ("cell.plot_joints()", "cell.plot_path()"):
        assert _images(_cell(executed, call)) == 1, call
    assert all(_images(c) == 0 for c in executed.cells if c.cell_type == "code"
               and "plot_" not in c.source)  # no figure leaks into another cell


def test_poses_frames_tables_and_traces_show_as_html(executed: Any) -> None:
    pose = _html(_cell(executed, "cell.where()  # in Jupyter: the joints and the tool pose as a table"))
    assert "<table>" in pose and "<th>Yaw</th>" in pose and "<th>J1</th>" in pose
    pallet = _html(_cell(executed, 'cell.module("GPO").pallet'))
    assert "RefFrame" in pallet and "1 (pallet)" in pallet and "450, -120, 100, 30, 0, 0" in pallet
    variables = _html(_cell(executed, "cell.variables()"))
    assert re.search(r"<td>Cell</td><td>placed</td><td>Integer</td><td>8</td>", variables), variables
    io = _html(_cell(executed, "cell.io_state()"))
    assert re.search(r"<td>1</td><td>digital output</td><td>off</td><td>\d+</td>", io), io
    trace = _html(_cell(executed, "cell.trace()"))
    assert "<table>" in trace and '<img src="data:image/png;base64,' in trace


def test_no_output_shows_an_object_address_or_a_long_float(executed: Any) -> None:
    for c in executed.cells:
        for o in c.get("outputs", []):
            text = o.get("text", "") + o.get("data", {}).get("text/plain", "") + o.get("data", {}).get("text/html", "")
            assert " at 0x" not in text, text
            assert not re.search(r"\d\.\d{9,}", text), text


def test_a_failing_cell_shows_the_gpl_line(executed: Any) -> None:
    failing = executed.cells[-1]
    errors = [o for o in failing.outputs if o.output_type == "error"]
    assert len(errors) == 1, failing.outputs
    error = errors[0]
    lines = GRIPPER.read_text(encoding="utf-8").splitlines()
    throw = next(i for i, line in enumerate(lines, 1) if line.strip().startswith("Throw"))
    assert error.ename == "GplError"
    assert error.evalue.startswith(f"Gripper.gpl:{throw}: error -3100")
    shown = "\n".join(re.sub(r"\x1b\[[0-9;]*m", "", line) for line in error.traceback)
    assert shown.splitlines()[0].startswith(f"GplError: Gripper.gpl:{throw}: error -3100")
    assert lines[throw - 1].strip() in shown  # the GPL source line itself
    assert "scheduler" not in shown and "gplrt" not in shown and len(error.traceback) < 10


def test_progress_is_one_line_updated_in_place(executed: Any) -> None:
    slow = executed.cells[-2]
    shown = [o for o in slow.outputs if "text/html" in o.get("data", {})]
    assert len(shown) == 1, slow.outputs  # one display, updated by its id (no widgets)
    assert shown[0]["data"]["text/html"].startswith("<code>done: ")
    assert not any(o.get("name") == "stderr" for o in slow.outputs)


def test_the_sample_ran_to_its_end_in_the_kernel(executed: Any) -> None:
    saved = _cell(executed, 'print("plot saved to", png)')
    text = "".join(o.get("text", "") for o in saved.outputs)
    assert "plot saved to" in text and Path(text.split("plot saved to", 1)[1].strip()).is_file()

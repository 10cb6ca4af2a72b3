"""Matplotlib views of a robot's trace for notebooks: joints against time, tool path from above.

Both functions draw into a given ``Axes`` (or a new figure) and return the figure, so a notebook
shows it and a test can ``fig.savefig(path)``.  matplotlib is imported only when a plot is made.
"""

from __future__ import annotations

from typing import Any

from gplrt.motion.trace import Trace


def _axes(ax: Any) -> tuple[Any, Any]:
    if ax is not None:
        return ax.figure, ax
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4.5))
    return fig, ax


def plot_joints(tr: Trace, ax: Any = None) -> Any:
    """Every joint (mm or deg) against controller time (s)."""
    fig, ax = _axes(ax)
    for i, name in enumerate(tr.names):
        ax.plot(tr.times, tr.joints[:, i], label=name)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("joint (mm or deg)")
    ax.legend(loc="best", fontsize="small")
    ax.grid(True, alpha=0.3)
    _note_dropped(tr, ax)
    return fig


def _note_dropped(tr: Trace, ax: Any) -> None:
    """Say on the plot when the trace does not start at the robot's first motion (``Trace.note``)."""
    if tr.dropped:
        ax.text(0.01, 0.99, f"earlier motions dropped: {tr.dropped} before t = {tr.times[0]:.3f} s "
                f"(history keeps {tr.window})", transform=ax.transAxes, va="top", ha="left",
                fontsize="small", color="firebrick")


def plot_path_xy(tr: Trace, ax: Any = None) -> Any:
    """The tool-tip path seen from above (X against Y, mm, equal scales); start and end marked."""
    fig, ax = _axes(ax)
    ax.plot(tr.xyz[:, 0], tr.xyz[:, 1], "-", lw=1.2)
    ax.plot(tr.xyz[:1, 0], tr.xyz[:1, 1], "o", label="start")
    ax.plot(tr.xyz[-1:, 0], tr.xyz[-1:, 1], "s", label="end")
    ax.set_xlabel("X (mm)")
    ax.set_ylabel("Y (mm)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(loc="best", fontsize="small")
    ax.grid(True, alpha=0.3)
    _note_dropped(tr, ax)
    return fig

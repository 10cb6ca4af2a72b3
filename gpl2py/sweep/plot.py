"""A sweep's metric against one parameter (a line) or two (a heat map), as a matplotlib Figure.

Why a ``matplotlib.figure.Figure`` and never pyplot: a notebook shows a returned Figure once,
under the cell; a pyplot figure would be shown twice (once by pyplot's own display, once as the
cell's value) and would pile up in pyplot's figure list over a long session.  Several rows per
point (the other parameters varied too, or random draws) are averaged, and a line shows their
lowest and highest values as a band.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

__all__ = ["plot", "save_plot"]


def plot(table: Any, metric: str, x: str, y: str | None = None) -> Any:
    """``metric`` against ``x`` (and ``y``): columns of ``table``, a sweep's DataFrame."""
    from matplotlib.figure import Figure

    for column in (metric, x, y):
        if column is not None and column not in table.columns:
            raise KeyError(f"no column {column!r}; the table has: {', '.join(map(str, table.columns))}")
    data = table[table[metric].notna()]
    figure = Figure(figsize=(6.4, 4.2), layout="constrained")
    ax = figure.subplots()
    if y is None:
        grouped = data.groupby(x)[metric].agg(["mean", "min", "max"]).sort_index()
        ax.plot(grouped.index, grouped["mean"], marker="o")
        if (grouped["min"] != grouped["max"]).any():
            ax.fill_between(grouped.index, grouped["min"], grouped["max"], alpha=0.2, label="lowest to highest")
            ax.legend()
        ax.set_xlabel(x)
        ax.set_ylabel(metric)
    else:
        grid = table.pivot_table(index=y, columns=x, values=metric, aggfunc="mean", dropna=False).sort_index()
        image = ax.imshow(grid.to_numpy(dtype=float), origin="lower", aspect="auto", cmap="viridis")
        ax.set_xticks(range(len(grid.columns)), [_label(v) for v in grid.columns])
        ax.set_yticks(range(len(grid.index)), [_label(v) for v in grid.index])
        ax.set_xlabel(x)
        ax.set_ylabel(y)
        figure.colorbar(image, ax=ax, label=metric)
        middle = (image.norm.vmin + image.norm.vmax) / 2
        for (i, j), value in _cells(grid):
            ax.text(j, i, _label(value), ha="center", va="center", fontsize=8,
                    color="black" if value > middle else "white")
    missing = len(table) - len(data)
    ax.set_title(f"{metric} ({len(data)} runs" + (f"; {missing} without a value)" if missing else ")"))
    return figure


def save_plot(table: Any, path: str | Path, metric: str, x: str, y: str | None = None) -> Path:
    """:func:`plot`, saved to ``path`` (PNG, SVG, PDF by its extension)."""
    plot(table, metric, x, y).savefig(path)
    return Path(path)


def _cells(grid: Any) -> list[tuple[tuple[int, int], float]]:
    values = grid.to_numpy(dtype=float)
    return [((i, j), values[i, j]) for i in range(values.shape[0]) for j in range(values.shape[1])
            if values[i, j] == values[i, j]]


def _label(value: Any) -> str:
    return f"{value:.4g}" if isinstance(value, float) else str(value)

"""How runtime values show themselves to a person: short text, small HTML tables, inline plots.

Notebooks (Jupyter, VS Code) call ``_repr_html_`` on the value a cell ends with, and ``repr`` is
what a plain Python prompt prints.  Both are for reading, not for round-tripping: numbers are
rounded to what a person compares (mm and degrees to 3 decimals), a 4x4 matrix is never printed,
and no ``<... at 0x7f...>`` appears.  Nothing here is on a hot path: the classes that use it
(``Location``, ``RefFrame``, ``Profile``, ``Trace``, ``RobotPose``) call it only from their reprs.

:class:`Table` is the one small table the runtime hands to notebooks (``Cell.variables()``,
``Cell.io_state()``): a text repr, an HTML repr, and ``to_pandas()`` when pandas is installed
(pandas is never required).

This module imports nothing from gplrt (it is a leaf every runtime class may use); matplotlib is
imported only when a plot is embedded.
"""

from __future__ import annotations

import base64
import html
import io
import math
import numbers
from collections.abc import Iterable, Iterator, Sequence
from typing import Any

__all__ = ["Table", "fixed", "number", "short", "html_table", "figure_html"]

#: The widest cell of a text table; longer values are cut with an ellipsis.
MAX_CELL = 60


def fixed(value: float, places: int = 3) -> str:
    """``value`` with at most ``places`` decimals and no trailing zeros: 350.0 -> "350",
    123.4567 -> "123.457", -0.0000001 -> "0"; huge or non-finite values in ``g`` form (1e+32)."""
    v = float(value)
    if not math.isfinite(v) or abs(v) >= 1e12:
        return f"{v:g}"
    text = f"{v:.{places}f}".rstrip("0").rstrip(".") if places > 0 else f"{v:.0f}"
    return "0" if text in ("-0", "") else text


def number(value: float) -> str:
    """A Double for reading: six significant digits (0.000125 stays visible; 17-digit noise goes)."""
    v = float(value)
    text = f"{v:.6g}"
    return "0" if text == "-0" else text


def short(value: Any) -> str:
    """One value as a table cell or inside a repr: numbers rounded, text quoted, others by their
    own (short) repr, cut to :data:`MAX_CELL` characters."""
    if isinstance(value, bool) or value is None:
        text = str(value)
    elif isinstance(value, numbers.Integral):
        text = str(int(value))
    elif isinstance(value, numbers.Real):
        text = number(float(value))
    elif isinstance(value, str):
        text = repr(value)
    elif isinstance(value, (list, tuple)):
        inner = ", ".join(short(v) for v in value[:8])
        more = ", ..." if len(value) > 8 else ""
        text = f"[{inner}{more}]" if isinstance(value, list) else f"({inner}{more})"
    else:
        text = repr(value)
    return text if len(text) <= MAX_CELL else text[: MAX_CELL - 1] + "…"


def _cell(value: Any) -> str:
    """A table cell's text: a str as it is (the table's maker chose it), anything else :func:`short`."""
    return value if isinstance(value, str) else short(value)


def html_table(columns: Sequence[str], rows: Iterable[Sequence[Any]], caption: str = "") -> str:
    """A small HTML table; each cell is :func:`short` of its value unless it is already a str."""
    head = "".join(f"<th>{html.escape(str(c))}</th>" for c in columns)
    body = "".join(
        "<tr>" + "".join(f"<td>{html.escape(_cell(c))}</td>" for c in row) + "</tr>"
        for row in rows
    )
    cap = f"<caption>{html.escape(caption)}</caption>" if caption else ""
    return f"<table>{cap}<thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def figure_html(figure: Any, dpi: int = 80) -> str:
    """A matplotlib figure as an inline PNG ``<img>`` (for an HTML repr that shows a plot)."""
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=dpi, bbox_inches="tight")
    data = base64.b64encode(buffer.getvalue()).decode("ascii")
    return f'<img src="data:image/png;base64,{data}"/>'


class Table:
    """Rows of values under named columns, shown as a table in a notebook and as text elsewhere.

    ``table.columns`` and ``table.rows`` (tuples) are plain data; ``len(table)``, iteration and
    ``table[i]`` go over rows; ``table.column("Value")`` is one column.  ``to_pandas()`` gives a
    ``pandas.DataFrame`` when pandas is installed (it is optional).
    """

    def __init__(self, columns: Sequence[str], rows: Iterable[Sequence[Any]], title: str = "") -> None:
        self.columns = tuple(columns)
        self.rows = [tuple(r) for r in rows]
        self.title = title
        for row in self.rows:
            if len(row) != len(self.columns):
                raise ValueError(f"row {row!r} has {len(row)} values for {len(self.columns)} columns")

    def __len__(self) -> int:
        return len(self.rows)

    def __iter__(self) -> Iterator[tuple[Any, ...]]:
        return iter(self.rows)

    def __getitem__(self, index: int) -> tuple[Any, ...]:
        return self.rows[index]

    def column(self, name: str) -> list[Any]:
        """Every value of column ``name``."""
        try:
            i = self.columns.index(name)
        except ValueError:
            raise KeyError(f"no column {name!r}; the columns are {', '.join(self.columns)}") from None
        return [row[i] for row in self.rows]

    def to_pandas(self) -> Any:
        """The table as a ``pandas.DataFrame`` (pandas is an optional dependency)."""
        try:
            import pandas
        except ImportError:
            raise ImportError("Table.to_pandas needs pandas, which is not installed: pip install pandas") from None
        return pandas.DataFrame(self.rows, columns=list(self.columns))

    def _repr_html_(self) -> str:
        return html_table(self.columns, self.rows, self.title)

    def __repr__(self) -> str:
        cells = [list(self.columns)] + [[_cell(v) for v in row] for row in self.rows]
        widths = [max(len(row[i]) for row in cells) for i in range(len(self.columns))]
        lines = ["  ".join(c.ljust(w) for c, w in zip(row, widths)).rstrip() for row in cells]
        lines.insert(1, "  ".join("-" * w for w in widths))
        if self.title:
            lines.insert(0, self.title)
        if not self.rows:
            lines.append("(none)")
        return "\n".join(lines)

    __str__ = __repr__

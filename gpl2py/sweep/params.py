"""The parameter sets of a sweep: a grid, a list, or random draws with a seed; read from TOML or CSV.

A parameter set is a plain ``dict`` of names to scalars (int, float, bool, str), in the order the
parameter file names them; each becomes one run and one row, its parameters one column each.

Why sets are identified by their values (:func:`run_id`), not by their position: ``--resume``
must recognise the runs already in the output after the file was edited or reordered, and two
equal sets give the same row anyway (every run is deterministic on the virtual clock), so a
set listed twice runs once.

The file formats (docs/sweep.md has examples):

* TOML, exactly one of ``[grid]`` (each value a list, or a scalar held fixed: every combination,
  the first name varying slowest), ``[[run]]`` (one table per set) or ``[random]`` (``count``,
  ``seed``, and per name ``{uniform = [lo, hi]}``, ``{integers = [lo, hi]}`` (both ends
  included), ``{choice = [...]}`` or a fixed scalar).  The same file may hold ``[metrics]``
  (``gpl2py.sweep.metrics.from_table``) and ``[plot]`` (``metric``, ``x``, ``y``).
* CSV: a header of names, one set per row; a value is read as an int, a float, true/false, or
  else kept as text.
"""

from __future__ import annotations

import csv
import hashlib
import itertools
import json
import random
import tomllib
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

Scalar = int | float | bool | str
ParamSet = dict[str, Scalar]

__all__ = ["ParamSet", "ParamsError", "ParamsFile", "grid", "draws", "read_params", "run_id", "unique"]


class ParamsError(ValueError):
    """The parameter file (or the sets given in Python) cannot be used; the text says where."""


def run_id(params: Mapping[str, Scalar]) -> str:
    """A stable name for a parameter set, from its names and values (module docstring)."""
    text = json.dumps(dict(sorted(params.items())), sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def grid(**axes: Scalar | Sequence[Scalar]) -> list[ParamSet]:
    """Every combination of ``axes`` (a list of values each, or a scalar held fixed); the first
    name varies slowest: ``grid(interval=[0.2, 0.5], speed=[20, 80])`` is four sets."""
    names = list(axes)
    values = [list(v) if isinstance(v, (list, tuple)) else [v] for v in axes.values()]
    for name, vals in zip(names, values):
        if not vals:
            raise ParamsError(f"grid: {name} has no values")
    return [dict(zip(names, combo)) for combo in itertools.product(*values)]


def draws(count: int, seed: int, /, **spec: Any) -> list[ParamSet]:
    """``count`` sets drawn at random, the same ones for the same ``seed`` on any machine.

    Each name gets ``{"uniform": [lo, hi]}``, ``{"integers": [lo, hi]}`` (both ends included),
    ``{"choice": [...]}`` or a scalar held fixed; draws go name by name, set by set, from one
    ``random.Random(seed)``, so adding a set at the end keeps the others.  (``count`` and ``seed``
    are positional: a parameter may be called ``seed`` too, for a setup's own random numbers.)"""
    if isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise ParamsError(f"random: count must be a whole number >= 1, not {count!r}")
    if isinstance(seed, bool) or not isinstance(seed, int):
        raise ParamsError(f"random: seed must be a whole number, not {seed!r}")
    rng = random.Random(seed)
    draw = {name: _drawer(name, how) for name, how in spec.items()}
    return [{name: d(rng) for name, d in draw.items()} for _ in range(count)]


def _drawer(name: str, how: Any) -> Any:
    if not isinstance(how, Mapping):
        _scalar(name, how)
        return lambda rng: how
    if len(how) != 1:
        raise ParamsError(f"random: {name} needs one of uniform, integers, choice, not {sorted(how)}")
    kind, arg = next(iter(how.items()))
    if kind == "choice":
        if not isinstance(arg, list) or not arg:
            raise ParamsError(f"random: {name}.choice must be a non-empty list")
        return lambda rng: rng.choice(arg)
    if kind in ("uniform", "integers"):
        if not (isinstance(arg, list) and len(arg) == 2 and all(_is_number(a) for a in arg) and arg[0] <= arg[1]):
            raise ParamsError(f"random: {name}.{kind} must be [low, high] with low <= high")
        lo, hi = arg
        if kind == "uniform":
            return lambda rng: rng.uniform(lo, hi)
        if not all(isinstance(a, int) for a in arg):
            raise ParamsError(f"random: {name}.integers takes whole numbers")
        return lambda rng: rng.randint(lo, hi)
    raise ParamsError(f"random: {name}: unknown draw {kind!r} (uniform, integers or choice)")


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _scalar(name: str, value: Any) -> Scalar:
    if not isinstance(value, (int, float, bool, str)):
        raise ParamsError(f"{name}: a parameter is a number, true/false or text, not {value!r}")
    return value


def unique(sets: Iterable[Mapping[str, Scalar]]) -> list[ParamSet]:
    """The sets, each once (by :func:`run_id`), in their first order; checks names and values."""
    seen: set[str] = set()
    out: list[ParamSet] = []
    for i, params in enumerate(sets):
        if not isinstance(params, Mapping) or not params:
            raise ParamsError(f"parameter set {i + 1} is not a non-empty table of names to values")
        clean = {str(k): _scalar(str(k), v) for k, v in params.items()}
        key = run_id(clean)
        if key not in seen:
            seen.add(key)
            out.append(clean)
    return out


@dataclass
class ParamsFile:
    """What a parameter file says: the sets, and (TOML) the metrics and the plot it asks for."""

    sets: list[ParamSet]
    metrics: dict[str, Any] = field(default_factory=dict)
    plot: dict[str, Any] = field(default_factory=dict)


def read_params(path: str | Path) -> ParamsFile:
    """Read a ``.toml`` or ``.csv`` parameter file (module docstring); ParamsError says what is wrong."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise ParamsError(f"{path}: {exc.strerror or exc}") from None
    suffix = path.suffix.lower()
    if suffix == ".csv":
        return ParamsFile(_csv_sets(path, text))
    if suffix != ".toml":
        raise ParamsError(f"{path}: a parameter file is .toml or .csv")
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ParamsError(f"{path}: {exc}") from None
    kinds = [k for k in ("grid", "run", "random") if k in doc]
    if len(kinds) != 1:
        raise ParamsError(f"{path}: give exactly one of [grid], [[run]] or [random] (found: "
                          f"{', '.join(kinds) or 'none'})")
    unknown = set(doc) - {"grid", "run", "random", "metrics", "plot"}
    if unknown:
        raise ParamsError(f"{path}: unknown table {', '.join(sorted(unknown))}")
    try:
        if kinds[0] == "grid":
            sets = grid(**doc["grid"])
        elif kinds[0] == "run":
            if not isinstance(doc["run"], list):
                raise ParamsError("write each set as a [[run]] table")
            sets = doc["run"]
        else:
            spec = dict(doc["random"])
            unknown = set(spec) - {"count", "seed", "params"}
            if unknown or not isinstance(spec.get("params"), dict):
                raise ParamsError("[random] holds count, seed and a [random.params] table of draws"
                                  + (f", not {', '.join(sorted(unknown))}" if unknown else ""))
            sets = draws(spec.get("count", 0), spec.get("seed"), **spec["params"])
        found = unique(sets)
    except ParamsError as exc:
        raise ParamsError(f"{path}: {exc}") from None
    return ParamsFile(found, dict(doc.get("metrics", {})), dict(doc.get("plot", {})))


def _csv_sets(path: Path, text: str) -> list[ParamSet]:
    rows = list(csv.reader(text.splitlines()))
    rows = [r for r in rows if any(cell.strip() for cell in r)]
    if len(rows) < 2:
        raise ParamsError(f"{path}: a header of parameter names and at least one row of values")
    names = [n.strip() for n in rows[0]]
    if any(not n for n in names) or len(set(names)) != len(names):
        raise ParamsError(f"{path}: the header needs distinct, non-empty names")
    sets = []
    for line, row in enumerate(rows[1:], start=2):
        if len(row) != len(names):
            raise ParamsError(f"{path}:{line}: {len(row)} values for {len(names)} names")
        sets.append({n: _csv_value(v.strip()) for n, v in zip(names, row)})
    return unique(sets)


def _csv_value(text: str) -> Scalar:
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    lowered = text.lower()
    if lowered in ("true", "false"):
        return lowered == "true"
    return text

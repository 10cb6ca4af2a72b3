"""Location speed against a bare numpy 4x4 product, measured side by side in one run.

Times each operation (``--runs`` samples of ``--number`` calls, collector off as ``timeit`` runs them) and
prints it as a ratio to the bare ``a @ b`` of two (4, 4) float arrays.  Target (issue "Geometry"):
Mul <= 3x the bare product.

The machine is shared, so its speed drifts during a run: each operation's samples are taken in
turns with samples of the bare product (``_sidebyside``), and printed are the medians of each and
the median of the per-turn ratios, not a figure against one taken at the start.  The reference
workload R (``_reference``) runs in every turn too, and each time per call is printed once more
in µR (millionths of R of its turn): the figures to compare between machines.

    python benchmarks/geometry_speed.py [--number 50000] [--runs 7]
"""

from __future__ import annotations

import argparse
import sys
import timeit
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _reference import HOW_TO_COMPARE, Reference  # noqa: E402
from _sidebyside import Pair, side_by_side  # noqa: E402

from gplrt.geometry import Location, RefFrame, xyzypr_to_matrix  # noqa: E402

NUMBER = 50_000
REPEATS = 7


BARE = "ma @ mb"


def paired(stmt: str, env: dict[str, object], ref: Reference, number: int, runs: int) -> Pair:
    """Seconds per call of ``stmt`` (side a) and of the bare product (side b), in turns with R."""
    op, bare = timeit.Timer(stmt, globals=env), timeit.Timer(BARE, globals=env)
    pair = side_by_side(lambda: op.timeit(number), lambda: bare.timeit(number), runs,
                        gc_enabled=False, reference=ref)
    for side in (pair.a, pair.b):
        side.values[:] = [v / number for v in side.values]
    return pair


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--number", type=int, default=NUMBER, help=f"calls per sample (default {NUMBER:,})")
    ap.add_argument("--runs", type=int, default=REPEATS, help=f"samples per side (default {REPEATS})")
    args = ap.parse_args()
    a = Location.XYZValue(10, 25, -40, 30, 45, 60)
    b = Location.XYZValue(1, 2, 3, -20, 100, 5)
    frame = RefFrame()
    frame.Loc.XYZ(100, 0, 0, 0, 0, 90)
    c = b.Clone()
    c.RefFrame = frame
    ma = xyzypr_to_matrix(10, 25, -40, 30, 45, 60)
    mb = xyzypr_to_matrix(1, 2, 3, -20, 100, 5)
    env: dict[str, object] = {"a": a, "b": b, "c": c, "ma": ma, "mb": mb, "np": np}

    cases = [
        ("Mul", "a.Mul(b)"),
        ("Mul (right operand on a frame)", "a.Mul(c)"),
        ("Inverse", "a.Inverse()"),
        ("numpy inv (reference)", "np.linalg.inv(ma)"),
        ("X read", "a.X"),
        ("X write", "a.X = 12.5"),
        ("XYZ(6 values) write", "a.XYZ(1, 2, 3, 30, 45, 60)"),
        ("X..Roll read (6 values, as written)", "(a.X, a.Y, a.Z, a.Yaw, a.Pitch, a.Roll)"),
        ("Mul, then X..Roll read (decompose)", "m = a.Mul(b); (m.X, m.Y, m.Z, m.Yaw, m.Pitch, m.Roll)"),
        ("Yaw read after Mul", "a.Mul(b).Yaw"),
        ("Pos through a frame", "c.Pos"),
    ]
    print(f"bare = numpy (4,4) a @ b, timed in turns with each operation (medians of {args.runs} x {args.number} calls)")
    print(f"{'operation':36s} {'us/op':>8s} {'bare us':>8s} {'µR/op':>8s} {'bare µR':>8s}  ratio (spread)")
    ratios: dict[str, float] = {}
    ref = Reference()
    for name, stmt in cases:
        pair = paired(stmt, env, ref, args.number, args.runs)
        ratios[name] = pair.ratio
        print(f"{name:36s} {pair.a.median * 1e6:8.3f} {pair.b.median * 1e6:8.3f} "
              f"{pair.a_in_r.median * 1e6:8.2f} {pair.b_in_r.median * 1e6:8.2f}  {pair.ratio_text()}")
    mul_ratio = ratios["Mul"]
    print(f"Mul target <= 3.00x: {'met' if mul_ratio <= 3.0 else 'NOT met'} ({mul_ratio:.2f}x)")
    print(ref.line())
    print(HOW_TO_COMPARE)


if __name__ == "__main__":
    main()

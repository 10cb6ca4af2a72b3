"""Location speed against a bare numpy 4x4 product, measured side by side in one run.

Times (best of REPEATS, each NUMBER calls) per operation, and prints each as a ratio to the
bare ``a @ b`` of two (4, 4) float arrays.  Target (issue "Geometry"): Mul <= 3x the bare product.

The machine is shared, so its speed drifts during a run: each operation's repeats are interleaved
with repeats of the bare product, and its ratio is taken against the bare product's best time
measured alongside it (the ``bare`` column), not against one figure taken at the start.

    python benchmarks/geometry_speed.py
"""

from __future__ import annotations

import timeit

import numpy as np

from gplrt.geometry import Location, RefFrame, xyzypr_to_matrix

NUMBER = 50_000
REPEATS = 7


BARE = "ma @ mb"


def paired_us(stmt: str, env: dict[str, object]) -> tuple[float, float]:
    """Best time per call in microseconds of ``stmt`` and of the bare product, interleaved."""
    op, bare = timeit.Timer(stmt, globals=env), timeit.Timer(BARE, globals=env)
    t_op, t_bare = [], []
    for _ in range(REPEATS):
        t_bare.append(bare.timeit(NUMBER))
        t_op.append(op.timeit(NUMBER))
    return min(t_op) / NUMBER * 1e6, min(t_bare) / NUMBER * 1e6


def main() -> None:
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
    print(f"bare = numpy (4,4) a @ b, timed alongside each operation (best of {REPEATS} x {NUMBER})")
    print(f"{'operation':36s} {'us/op':>8s} {'bare us':>8s} {'ratio':>7s}")
    ratios: dict[str, float] = {}
    for name, stmt in cases:
        t, base = paired_us(stmt, env)
        ratios[name] = t / base
        print(f"{name:36s} {t:8.3f} {base:8.3f} {t / base:7.2f}x")
    mul_ratio = ratios["Mul"]
    print(f"Mul target <= 3.00x: {'met' if mul_ratio <= 3.0 else 'NOT met'} ({mul_ratio:.2f}x)")


if __name__ == "__main__":
    main()

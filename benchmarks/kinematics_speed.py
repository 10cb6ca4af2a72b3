"""Kinematics speed: forward and inverse calls per second for each default robot model.

Run: ``.venv/bin/python benchmarks/kinematics_speed.py [N]``.  Prints µs per call measured side by
side in one run, so the numbers compare robots (closed-form PF400 / gantry vs the 6-axis analytic
seed + Pinocchio DLS refinement) on the same machine and load.
"""

from __future__ import annotations

import sys
import time

import numpy as np

from gplrt.controller.pdb import default_database
from gplrt.motion.kinematics import build_model


def main(n: int = 5000) -> None:
    rng = np.random.default_rng(0)
    print(f"{'model':<12} {'forward µs':>11} {'inverse µs':>11}")
    for name in ("PF400SX", "PF400SXL", "PF3400SX", "GANTRY4", "ARM6"):
        model = build_model(default_database(name))
        qs = rng.uniform(model.lower_limits, model.upper_limits, size=(n, model.axis_count))
        t0 = time.perf_counter()
        poses = [model.forward(q) for q in qs]
        t1 = time.perf_counter()
        for q, T in zip(qs, poses, strict=True):
            model.inverse(T, model.config_of(q), q)
        t2 = time.perf_counter()
        print(f"{name:<12} {1e6 * (t1 - t0) / n:11.1f} {1e6 * (t2 - t1) / n:11.1f}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5000)

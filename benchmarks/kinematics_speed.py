"""Kinematics speed: each robot model's ``forward`` and ``inverse`` against the bare call they wrap.

Run: ``.venv/bin/python benchmarks/kinematics_speed.py [N] [RUNS]``.  For each default robot model
it times ``model.forward(joints)`` and ``model.inverse(T, config, current)`` over the same ``N``
random poses as a *yardstick* that does the same computation with nothing around it, measured side
by side in one run (``_sidebyside``: the two in turns after a warm-up, ``RUNS`` >= 5 samples each,
medians with their spread, the ratio as the median of the per-turn ratios; defaults N = 500,
RUNS = 21).  Times are the process's CPU time (``time.process_time``): on a shared machine a
sample that loses the processor to another program would otherwise count that program's time.  Target (issue 14
item 5): every wrapper <= 3x its yardstick.

The yardsticks:

* **forward**: the bare Pinocchio call, ``forwardKinematics`` + ``updateFramePlacement`` of the
  flange frame and its 4x4 (``.homogeneous``), on a configuration vector already in Pinocchio's
  joint order and SI units.  What the wrapper adds: GPL units in and out (mm, degrees), the
  argument checks (-202 for a wrong length or a NaN), the Tool and Base, and the lock that keeps
  two GPL threads out of one ``pin.Data``;
* **inverse**, PF400 family and gantry: the bare closed form in Python floats, written below from
  the module docstrings' formulas: the 4x4 in, the Tool offset off, law of cosines (or the gantry's
  axes), joints in mm/degrees out, with none of the checks (reach, orientation, soft limits, the
  branch boundary), no turn chosen for the rotary axes and no error codes;
* **inverse**, URDF robots (Viper s650, Cobra s600, TM5-900): the solver of the robot's family
  on a flange target already in SI, every branch (``UrdfModel._solver``: the Viper's and the
  Cobra's closed forms, the TM's closed form and its Pinocchio polish), none of the branch choice
  by the Config bits, the turns, the unit conversions or the checks; the wrapper's answer must be
  one of its candidates (modulo a turn);
* **inverse**, ARM6: its closed-form seed (``analytic``) and the Pinocchio damped-least-squares
  refinement (``solve_dls``) on a ``pin.SE3`` flange target already in SI: the work of the IK
  without the unit conversions, the Tool and Base, the branch choice or the checks.

Each yardstick's answers are checked against the wrapper's (to 1e-9 mm/degrees, modulo a turn
for the rotary axes whose turn the bare form does not choose), so both sides compute the same.

The reference workload R (``_reference``) runs in every turn too, timed on the same CPU clock, and
each time per call is printed once more in µR (millionths of R of its turn): the figures to
compare between machines.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pinocchio as pin

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _reference import HOW_TO_COMPARE, Reference  # noqa: E402
from _sidebyside import Pair, side_by_side  # noqa: E402

from gplrt.controller.pdb import default_database  # noqa: E402
from gplrt.motion.kinematics import (  # noqa: E402
    GPL_RIGHTY,
    Articulated6Model,
    GantryModel,
    Pf400Model,
    RobotModel,
    UrdfModel,
    build_model,
    solve_dls,
)

MODELS = ("PF400SX", "PF400SXL", "PF3400SX", "GANTRY4", "ARM6", "VIPER-S650", "COBRA-S600", "TM5-900")
TARGET = 3.0
#: CPU time of this process: the machine is shared, and a sample of a few milliseconds that loses
#: the processor to another program would otherwise count the other program's time.
CLOCK = time.process_time
Joints = list[float]


def _forward_yardstick(model: RobotModel, qs: list[Joints]) -> Callable[[], object]:
    """The bare Pinocchio forward kinematics of every sample (configurations prepared)."""
    assert model.pin_model is not None and model.pin_data is not None
    M, D, F = model.pin_model, model.pin_data, model.flange_frame
    prepared = [model.q_pin(np.array(model._to_si_list(q))) for q in qs]
    fk, place = pin.forwardKinematics, pin.updateFramePlacement

    def bare() -> list[np.ndarray]:
        return [(fk(M, D, q), place(M, D, F).homogeneous)[1] for q in prepared]

    return bare


def _pf400_bare(model: Pf400Model) -> Callable[[np.ndarray, bool, Joints], Joints]:
    """The PF400's closed form with nothing around it (module docstring)."""
    l1, l2 = model.l1, model.l2
    assert model._tool_inv_shift is not None and model._base_is_identity  # (the default tools are offsets)
    tx, ty, tz = model._tool_inv_shift
    i_z, i_sh, i_el, i_wr, i_rail = model._z, model._shoulder, model._elbow, model._wrist, model._rail
    dx, dy, dz = model.rail_direction_list
    atan2, acos, sin, cos, degrees = math.atan2, math.acos, math.sin, math.cos, math.degrees
    two_pi = 2.0 * math.pi

    def ik(T: np.ndarray, righty: bool, current: Joints) -> Joints:
        (r11, r12, r13, x), (r21, r22, r23, y), (r31, r32, r33, z), _ = T.tolist()
        x, y, z = (r11 * tx + r12 * ty + r13 * tz + x) / 1000.0, (r21 * tx + r22 * ty + r23 * tz + y) / 1000.0, \
            (r31 * tx + r32 * ty + r33 * tz + z) / 1000.0
        if i_rail >= 0:
            c = current[i_rail] / 1000.0
            x, y, z = x - c * dx, y - c * dy, z - c * dz
        elbow = acos((x * x + y * y - l1 * l1 - l2 * l2) / (2.0 * l1 * l2))
        j3 = elbow if righty else two_pi - elbow
        j2 = atan2(y, x) - atan2(l2 * sin(j3), l1 + l2 * cos(j3))
        q = list(current)
        q[i_z], q[i_sh], q[i_el] = z * 1000.0, degrees(j2), degrees(j3)
        if i_wr >= 0:
            q[i_wr] = degrees(atan2(r23, r13) - j2 - j3)
        return q

    return ik


def _gantry_bare(model: GantryModel) -> Callable[[np.ndarray, int, Joints], Joints]:
    """The XYZ-Theta gantry's closed form with nothing around it (its tool and base: none)."""
    assert model._tool_is_identity and model._base_is_identity
    index = [model._i.get(role, -1) for role in ("x", "y", "z", "theta")]
    ix, iy, iz, it = index
    atan2, degrees = math.atan2, math.degrees

    def ik(T: np.ndarray, bits: int, current: Joints) -> Joints:
        (r11, _, _, x), (r21, _, _, y), (_, _, _, z), _ = T.tolist()
        q = list(current)
        q[ix], q[iy], q[iz], q[it] = x, y, -z, -degrees(atan2(r21, r11))
        return q

    return ik


def _inverse_yardstick(model: RobotModel, Ts: list[np.ndarray], configs: list[int],
                       qs: list[Joints]) -> Callable[[], list[Joints]]:
    """The bare inverse of every sample (see the module docstring)."""
    if isinstance(model, Pf400Model):
        ik = _pf400_bare(model)
        rightys = [bool(c & GPL_RIGHTY) for c in configs]
        jobs = list(zip(Ts, rightys, qs, strict=True))
        return lambda: [ik(T, r, q) for T, r, q in jobs]
    if isinstance(model, GantryModel):
        gik = _gantry_bare(model)
        gjobs = list(zip(Ts, configs, qs, strict=True))
        return lambda: [gik(T, c, q) for T, c, q in gjobs]
    if isinstance(model, UrdfModel):
        return _urdf_bare(model, Ts, qs)
    assert isinstance(model, Articulated6Model) and model.pin_model is not None and model.pin_data is not None
    M, D, F = model.pin_model, model.pin_data, model.flange_frame
    mm = 1000.0
    targets = []
    for T in Ts:
        flange = model._base_inv @ T @ model._tool_inv
        targets.append(pin.SE3(flange[:3, :3].copy(), flange[:3, 3] / mm))
    currents = [np.array(model._to_si_list(q)) for q in qs]
    ajobs = list(zip(targets, configs, currents, strict=True))
    degrees = np.degrees

    def bare() -> list[Joints]:
        out = []
        for target, bits, current in ajobs:
            seed = model.analytic(target, bits, current)
            q, _, _ = solve_dls(M, D, F, target, model.q_pin(seed))
            out.append(degrees(q).tolist())
        return out

    return bare


def _urdf_bare(model: UrdfModel, Ts: list[np.ndarray], qs: list[Joints]) -> Callable[[], list[list[Joints]]]:
    """Every branch's solution of every sample, in degrees/mm (the module docstring)."""
    solver, linear = model._solver, [j.linear for j in model.joints]
    jobs = []
    for T, q in zip(Ts, qs, strict=True):
        flange = model._base_inv @ T @ model._tool_inv
        jobs.append((flange[:3, :3].copy(), flange[:3, 3] / 1000.0, model._to_si_list(q)))

    def every(_q: list[float]) -> bool:
        return True

    def bare() -> list[list[Joints]]:
        return [[[v * 1000.0 if lin else math.degrees(v) for v, lin in zip(c, linear)] for c in solver(R, p, q, every)[0]]
                for R, p, q in jobs]

    return bare


def _among(answers: list[Joints], candidates: list[list[Joints]], what: str, rotary: np.ndarray) -> None:
    """Each wrapper answer is one of its sample's candidates (rotary axes modulo a turn)."""
    for k, (a, cands) in enumerate(zip(answers, candidates, strict=True)):
        d = np.array(cands, dtype=float) - np.array(a, dtype=float)
        d[:, rotary] = (d[:, rotary] + 180.0) % 360.0 - 180.0
        if not float(np.abs(d).max(axis=1).min()) <= 1e-9:
            raise SystemExit(f"{what}: sample {k}: the wrapper's answer is none of the yardstick's")


def _same(a: list[Joints] | list[np.ndarray], b: list[Joints] | list[np.ndarray], what: str,
          rotary: np.ndarray | None = None) -> None:
    """The wrapper and its yardstick agree (``rotary`` axes modulo a turn): the two compute the same."""
    d = np.array(a, dtype=float) - np.array(b, dtype=float)
    if rotary is not None:
        d[:, rotary] = (d[:, rotary] + 180.0) % 360.0 - 180.0
    worst = float(np.abs(d).max())
    if not worst <= 1e-9:
        raise SystemExit(f"{what}: the yardstick disagrees with the wrapper by {worst:.3g}")


def _line(name: str, what: str, pair: Pair, n: int) -> str:
    per = 1e-6 * n
    flag = "" if pair.ratio <= TARGET else "  <-- over target"
    return (f"{name:<10} {what:<8} {pair.a.text(per, 'µs')}  {pair.b.text(per, 'µs')}  "
            f"{pair.ratio_text()}{flag}\n"
            f"{'':<10} {'in R':<8} {pair.a_in_r.text(per, 'µR')}  {pair.b_in_r.text(per, 'µR')}")


def main(n: int = 500, runs: int = 21) -> None:
    rng = np.random.default_rng(0)
    ref = Reference()
    print(f"{n} calls per sample, {runs} samples per side, in turns after a warm-up; target <= {TARGET:g}x")
    print(f"{'model':<10} {'call':<8} {'wrapper per call':>36}  {'yardstick per call':>36}  ratio")
    for name in MODELS:
        model = build_model(default_database(name))
        lower = np.maximum(model.lower_limits, -1e3)
        upper = np.minimum(model.upper_limits, 1e3)
        qs = [q.tolist() for q in rng.uniform(lower, upper, size=(n, model.axis_count))]
        rotary = np.array([not j.linear for j in model.joints])
        Ts = [model.forward(q) for q in qs]
        configs = [model.config_of(q) for q in qs]
        fwd = model.forward
        bare_fwd = _forward_yardstick(model, qs)
        flanges = bare_fwd()
        _same([fwd(q) for q in qs], [model.base @ units_mm(F) @ model.tool for F in flanges], f"{name} forward")
        pair = side_by_side(lambda: [fwd(q) for q in qs], bare_fwd, runs, warmup=2, clock=CLOCK, reference=ref)
        print(_line(name, "forward", pair, n))

        inv = model.inverse
        jobs = list(zip(Ts, configs, qs, strict=True))
        bare_inv = _inverse_yardstick(model, Ts, configs, qs)
        if isinstance(model, UrdfModel):
            _among([inv(T, c, q) for T, c, q in jobs], bare_inv(), f"{name} inverse", rotary)  # type: ignore[arg-type]
        else:
            _same([inv(T, c, q) for T, c, q in jobs], bare_inv(), f"{name} inverse", rotary)
        pair = side_by_side(lambda: [inv(T, c, q) for T, c, q in jobs], bare_inv, runs, warmup=2, clock=CLOCK, reference=ref)
        print(_line(name, "inverse", pair, n))
    print(ref.line())
    print(HOW_TO_COMPARE)


def units_mm(F: np.ndarray) -> np.ndarray:
    """A bare flange pose (m) with its translation in mm, for the agreement check only."""
    T = F.copy()
    T[:3, 3] *= 1000.0
    return T


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))

"""Six-axis articulated arm with a spherical wrist (our ``ARM6``; module 116 = 22) and the
Pinocchio damped-least-squares IK used to refine its solutions.

Geometry from 16050 (layout ours, documented in data/robots/README.md): [1] d1 shoulder height,
[2] a1 shoulder forward offset, [3] a2 upper arm, [4] a3 elbow offset, [5] d4 forearm,
[6] d6 wrist centre → flange.  Joints (Pinocchio, built programmatically):

    J1 RZ at the base origin
    J2 RY at (a1, 0, d1) in the J1 frame        (positive tilts the upper arm forward)
    J3 RY at (0, 0, a2)                          (0 = forearm in line with the upper arm)
    J4 RZ at (a3, 0, d4)   (wrist centre W; J4, J5, J6 axes meet here)
    J5 RY, J6 RZ at W; flange = J6 frame · Trans(0, 0, d6)  (flange z = approach)

At all-zero joints the arm points straight up.  Config bits (GPL_… constants; our definitions,
documented because no Brooks page defines them for a concrete six-axis geometry):

* **Righty / Lefty** (shoulder): Righty when the wrist centre is in front of the J1 axis (its x
  in the J1 frame ≥ 0, the usual working posture), Lefty when the arm reaches over backwards
  (J1 turned by 180° from the wrist centre's azimuth).
* **Above / Below** (elbow): with φ = J3 + atan2(a3, d4) the forearm's bend relative to the upper
  arm, Above ⇔ (sin φ ≥ 0) for Righty and (sin φ < 0) for Lefty, i.e. the elbow lies above the
  shoulder–wrist line whenever the wrist is in front of the shoulder.
* **Flip / NoFlip** (wrist): NoFlip ⇔ J5 ≥ 0 (wrapped), Flip ⇔ J5 < 0.
* **Single**: J6 in (−180°, 180°]; otherwise J4 and J6 (multi-turn, ±270° / ±360°) are unwound
  toward their current values.
* A pair the bits leave open keeps the current branch — except exactly on its boundary (J5 = 0 in
  the all-zero home posture), where both are tried and the in-limits solution nearest the current
  joints wins (``_solve``).

Inverse: the closed form decouples the wrist (W = p − d6·z), picks J1 by Righty/Lefty, J2/J3 by
Above/Below (two-link law of cosines in the arm plane) and J4–J6 by Flip/NoFlip (ZYZ of
R₀₃ᵀ·R), then ``solve_dls`` refines the result on ``pin.computeFrameJacobian`` so the pose error
is at machine precision; it normally converges in 0–2 iterations because the seed is exact up
to rounding.  Unreachable wrist centres raise -1040 / -1039.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from gplrt.controller.pdb import ParameterDatabase
from gplrt.lang.errors import (
    INVALID_CARTESIAN,
    POSITION_TOO_CLOSE,
    POSITION_TOO_FAR,
    GplException,
)
from gplrt.motion.kinematics import units
from gplrt.motion.kinematics.base import (
    RobotModel,
    axis_roles,
    read_joints,
    read_transform,
)
from gplrt.motion.kinematics.config import (
    GPL_ABOVE,
    GPL_BELOW,
    GPL_FLIP,
    GPL_LEFTY,
    GPL_NOFLIP,
    GPL_RIGHTY,
    GPL_SINGLE,
    preference,
    wrap_pi,
)

MODULE_ARTICULATED6 = 22
_NAMES = ("Base", "Shoulder", "Elbow", "Wrist1", "Wrist2", "Wrist3")
_ROLES = ("j1", "j2", "j3", "j4", "j5", "j6")
_JOINT_NAMES = {**dict(zip(_ROLES, _NAMES, strict=True)), "gripper": "Gripper"}
_SINGULAR = 1e-12
#: Within this of a branch boundary (J5 = 0 or 180°, |sin φ|, the wrist centre's distance from the
#: J1 axis in m) the arm is in both branches of the pair (``_solve``).
BRANCH_EDGE = 1e-9


def solve_dls(model: pin.Model, data: pin.Data, frame_id: int, target: pin.SE3, q0: np.ndarray,
              tol: float = 1e-13, max_iter: int = 100, damping: float = 1e-10) -> tuple[np.ndarray, float, int]:
    """Damped least squares (Levenberg–Marquardt style) on the frame Jacobian, after Pinocchio's
    own inverse-kinematics example: returns (q, final error norm of log6, iterations).

    ``tol`` is on the 6-vector ``log6(oMf⁻¹ · target)`` (m and rad)."""
    q = q0.copy()
    err_norm = math.inf
    for it in range(max_iter + 1):
        pin.forwardKinematics(model, data, q)
        oMf = pin.updateFramePlacement(model, data, frame_id)
        fMd = oMf.actInv(target)
        err = pin.log6(fMd).vector
        err_norm = float(np.linalg.norm(err))
        if err_norm < tol or it == max_iter:
            return q, err_norm, it
        J = pin.computeFrameJacobian(model, data, q, frame_id, pin.ReferenceFrame.LOCAL)
        J = -pin.Jlog6(fMd.inverse()) @ J
        v = -J.T @ np.linalg.solve(J @ J.T + damping * np.eye(6), err)
        q = pin.integrate(model, q, v)
    return q, err_norm, max_iter


class Articulated6Model(RobotModel):
    """Six-axis spherical-wrist arm; see the module docstring."""

    single_axis = 5

    def __init__(self, pdb: ParameterDatabase, robot: int = 1) -> None:
        roles = axis_roles(int(pdb.get_num(2003, robot)), _ROLES, ((0x40, "gripper"),))
        name, joints = read_joints(pdb, robot, roles, _JOINT_NAMES, ("gripper",))
        super().__init__(name, robot, MODULE_ARTICULATED6, joints,
                         read_transform(pdb, 16051, robot), read_transform(pdb, 16052, robot))
        self.roles = roles
        d = [units.length_to_si(pdb.get_num(16050, robot, 1, k)) for k in range(1, 7)]
        self.d1, self.a1, self.a2, self.a3, self.d4, self.d6 = d
        self.l3 = math.hypot(self.a3, self.d4)
        self.gamma = math.atan2(self.a3, self.d4)
        self.last_iterations = 0
        self._build_pin_model()

    def _build_pin_model(self) -> None:
        model = pin.Model()
        model.name = self.name

        def at(x: float, y: float, z: float) -> pin.SE3:
            return pin.SE3(np.eye(3), np.array([x, y, z]))

        j1 = model.addJoint(0, pin.JointModelRZ(), pin.SE3.Identity(), _NAMES[0])
        j2 = model.addJoint(j1, pin.JointModelRY(), at(self.a1, 0.0, self.d1), _NAMES[1])
        j3 = model.addJoint(j2, pin.JointModelRY(), at(0.0, 0.0, self.a2), _NAMES[2])
        j4 = model.addJoint(j3, pin.JointModelRZ(), at(self.a3, 0.0, self.d4), _NAMES[3])
        j5 = model.addJoint(j4, pin.JointModelRY(), pin.SE3.Identity(), _NAMES[4])
        j6 = model.addJoint(j5, pin.JointModelRZ(), pin.SE3.Identity(), _NAMES[5])
        ids = [j1, j2, j3, j4, j5, j6]
        flange = model.addFrame(pin.Frame("flange", j6, at(0.0, 0.0, self.d6), pin.FrameType.OP_FRAME))
        if "gripper" in self.roles:
            ids.append(model.addJoint(j6, pin.JointModelPY(), at(0.0, 0.0, self.d6), "Gripper"))
        self._finish_pin_model(model, ids, flange)

    # -- configuration --------------------------------------------------------------------------

    def _branches(self, q: Sequence[float]) -> tuple[bool, bool, bool]:
        """(righty, above, noflip) of SI joints."""
        phi = q[2] + self.gamma
        x_wrist = self.a1 + self.a2 * math.sin(q[1]) + self.l3 * math.sin(q[1] + phi)
        righty = x_wrist >= 0.0
        above = (math.sin(phi) >= 0.0) == righty
        return righty, above, wrap_pi(q[4]) >= 0.0

    def _config(self, q: Sequence[float]) -> int:
        righty, above, noflip = self._branches(q)
        return ((GPL_RIGHTY if righty else GPL_LEFTY) | (GPL_ABOVE if above else GPL_BELOW)
                | (GPL_NOFLIP if noflip else GPL_FLIP))

    # -- inverse --------------------------------------------------------------------------------

    def analytic(self, target: pin.SE3, bits: int, current: np.ndarray) -> np.ndarray:
        """Closed-form solution (SI) for the branch the bits select (current branch by default)."""
        cur_righty, cur_above, cur_noflip = self._branches(current)
        righty = preference(bits, GPL_RIGHTY, GPL_LEFTY)
        above = preference(bits, GPL_ABOVE, GPL_BELOW)
        noflip = preference(bits, GPL_NOFLIP, GPL_FLIP)
        righty = cur_righty if righty is None else righty
        above = cur_above if above is None else above
        noflip = cur_noflip if noflip is None else noflip

        R, p = target.rotation, target.translation
        w = p - self.d6 * R[:, 2]
        rho = math.hypot(w[0], w[1])
        azimuth = math.atan2(w[1], w[0]) if rho > _SINGULAR else float(current[0]) if righty else float(current[0]) + math.pi
        q1 = azimuth if righty else wrap_pi(azimuth + math.pi)
        x_l = (rho if righty else -rho) - self.a1
        z_l = w[2] - self.d1
        a2, l3 = self.a2, self.l3
        c = (x_l * x_l + z_l * z_l - a2 * a2 - l3 * l3) / (2.0 * a2 * l3)
        if c > 1.0 + 1e-12:
            raise GplException(POSITION_TOO_FAR, robot_num=self.robot, detail="wrist centre beyond reach")
        if c < -1.0 - 1e-12:
            raise GplException(POSITION_TOO_CLOSE, robot_num=self.robot, detail="wrist centre too close to the shoulder")
        phi = math.acos(max(-1.0, min(1.0, c))) * (1.0 if above == righty else -1.0)
        q3 = phi - self.gamma
        vx, vz = l3 * math.sin(phi), a2 + l3 * math.cos(phi)
        q2 = math.atan2(x_l, z_l) - math.atan2(vx, vz)

        c1, s1 = math.cos(q1), math.sin(q1)
        c23, s23 = math.cos(q2 + q3), math.sin(q2 + q3)
        r03 = np.array([[c1 * c23, -s1, c1 * s23], [s1 * c23, c1, s1 * s23], [-s23, 0.0, c23]])
        r = r03.T @ R
        s5 = math.hypot(r[0, 2], r[1, 2])
        if s5 < _SINGULAR:  # J4 and J6 about the same axis: keep J4, give the rest to J6
            q5 = 0.0
            q4 = float(current[3])
            q6 = math.atan2(r[1, 0], r[0, 0]) - q4
        elif noflip:
            q5 = math.atan2(s5, r[2, 2])
            q4 = math.atan2(r[1, 2], r[0, 2])
            q6 = math.atan2(r[2, 1], -r[2, 0])
        else:
            q5 = -math.atan2(s5, r[2, 2])
            q4 = math.atan2(-r[1, 2], -r[0, 2])
            q6 = math.atan2(-r[2, 1], r[2, 0])
        q = current.copy()
        q[:6] = [q1, q2, q3, q4, q5, q6]
        return q

    def _solve(self, target: pin.SE3, bits: int, current: np.ndarray) -> np.ndarray:
        """The branch the bits ask for, the current one for the pairs they leave open — and where
        the arm sits exactly on the boundary of such a pair (J5 = 0: the all-zero home posture;
        the wrist centre on the J1 axis; the elbow stretched or folded) it is in both branches at
        once, so "keep the current branch" decides nothing.  Decision [P] (gpl-classes §22.1
        item 11: no preference → the solution nearest the current joints): every open boundary
        pair is tried both ways, and the solution within the soft limits nearest the current
        joints (sum of squared radians over J1–J6) wins; on a tie, the branch ``config_of``
        reports now."""
        open_pairs = self._boundary_pairs(bits, current)
        if not open_pairs:
            return self._solve_branch(target, bits, current)
        found: list[np.ndarray] = []
        error: GplException | None = None
        now = self._config(current)
        choices = [(yes, no) if now & yes else (no, yes) for yes, no in open_pairs]  # current first
        for combo in itertools.product(*choices):
            try:
                found.append(self._solve_branch(target, bits | sum(combo), current))
            except GplException as exc:
                error = error or exc
        if not found:
            assert error is not None
            raise error
        pool = [q for q in found if self._limits_hold(q[None, :])] or found
        return min(pool, key=lambda q: float(np.sum((q[:6] - current[:6]) ** 2)))  # first of equals

    def _boundary_pairs(self, bits: int, current: np.ndarray) -> list[tuple[int, int]]:
        """The (yes, no) bit pairs the bits leave open and the current joints sit on the edge of."""
        phi = current[2] + self.gamma
        x_wrist = self.a1 + self.a2 * math.sin(current[1]) + self.l3 * math.sin(current[1] + phi)
        q5 = abs(wrap_pi(float(current[4])))
        edges = ((GPL_RIGHTY, GPL_LEFTY, abs(x_wrist) <= BRANCH_EDGE),
                 (GPL_ABOVE, GPL_BELOW, abs(math.sin(phi)) <= BRANCH_EDGE),
                 (GPL_NOFLIP, GPL_FLIP, q5 <= BRANCH_EDGE or math.pi - q5 <= BRANCH_EDGE))
        return [(yes, no) for yes, no, on_edge in edges if on_edge and preference(bits, yes, no) is None]

    def _solve_branch(self, target: pin.SE3, bits: int, current: np.ndarray) -> np.ndarray:
        seed = self.analytic(target, bits, current)
        assert self.pin_model is not None and self.pin_data is not None
        with self.lock:
            q_pin, err, self.last_iterations = solve_dls(self.pin_model, self.pin_data, self.flange_frame, target,
                                                         self.q_pin(seed))
        if err > 1e-9:
            raise GplException(INVALID_CARTESIAN, robot_num=self.robot, detail=f"numeric IK did not converge ({err:.2e})")
        # Python floats for the turn choice: numpy scalars cost several times more per operation
        q = self.q_gpl(q_pin).tolist()
        now = current.tolist()
        single = bool(bits & GPL_SINGLE)
        unwind = self._unwind
        for i in range(6):
            q[i] = unwind(i, q[i], now, single)
        return np.array(q)

"""PreciseFlex 400 family (kinematic module 116 = 12): PF400 S/SX/SXL, PF3400SX.

Geometry (robot-models.md §4, all read from the parameter database of the robot):

* axes from the axis mask 2003: J1 Z (column), J2 shoulder, J3 elbow, then in order the optional
  wrist (&H8), servo gripper (&H20), linear rail (&H40), second gripper (&H80);
* links l1 = 16050[2], l2 = 16050[3]; rail direction a = 16050[5] (deg) moves the robot base
  along d(a) = (−sin a, cos a, 0);
* soft limits 16077/16078; Tool/Base at restart 16051/16052.

The Pinocchio model is a chain rail → Z → shoulder → elbow → wrist with the world origin on the
shoulder axis at J1 = 0 and rail = 0 (§4.2); the flange frame sits on the wrist axis with
orientation Rz(ψ)·Ry(90°)·Rz(180°), ψ = J2 + J3 + J4, i.e. flange x up and z along the gripper.
The gripper is a prismatic joint on the hand that moves no frame we report (§4.3: "J5 does not
enter the pose").

Inverse (closed form, §4.4): orientation must have flange x = world up (else -1033; tolerance
1e-6°, the spec's [P]); reach outside [|l1 − l2|, l1 + l2] → -1039 / -1040; elbow branch by
Config: **Righty** (&H01) → J3 in (0°, 180°], **Lefty** (&H02) → [180°, 360°), neither or both →
the current branch (from exactly J3 = 0° or 180°, in both branches at once: the in-limits solution
nearest the current joints, ``_nearest_branch``); J2 wrapped to (−180°, 180°]; J4 = ψ − J2 − J3 unwound toward the current J4
within ±960° (``GPL_Single``: J4 in (−180°, 180°]); rail and gripper keep their current values;
then every axis is checked against the soft limits (-1012).  Above/Below/Flip/NoFlip have no
meaning on this arm and are ignored (§5.2 [P]).  ``config_of`` reports Righty when
J3 mod 360 < 180, else Lefty (§4.3 [INF]); it never reports ``GPL_Single`` (unknown whether the
controller does, §8 q.4).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from gplrt.controller.pdb import ParameterDatabase
from gplrt.geometry.transforms import Pose
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
from gplrt.motion.kinematics.config import GPL_LEFTY, GPL_RIGHTY, GPL_SINGLE, TWO_PI, preference, wrap_pi

MODULE_PF400 = 12
_OPTIONAL_AXES = ((0x08, "wrist"), (0x20, "gripper"), (0x40, "rail"), (0x80, "gripper2"))
_NAMES = {"z": "Z", "shoulder": "Shoulder", "elbow": "Elbow", "wrist": "Wrist", "gripper": "Gripper",
          "rail": "Rail", "gripper2": "Gripper2"}
_LINEAR_ROLES = {"z", "gripper", "rail", "gripper2"}
#: Flange orientation at ψ = 0: Ry(90°)·Rz(180°) (x up, z along the hand).
FLANGE_ROTATION = np.array([[0.0, 0.0, 1.0], [0.0, -1.0, 0.0], [1.0, 0.0, 0.0]])
#: Allowed tilt of the flange x axis from vertical: 1e-6 degree.
ORIENTATION_TOLERANCE = math.sin(math.radians(1e-6))
#: An elbow within this (rad) of 0° or 180° is on the branch boundary (``_nearest_branch``).
BRANCH_EDGE = 1e-9
#: Slack on the reach checks (m) so that poses computed at full stretch are not refused.
_REACH_SLACK = 1e-12
#: Config bits ``_plain_inverse`` leaves to the general steps (all but the elbow's branch).
_NOT_BRANCH = ~(GPL_RIGHTY | GPL_LEFTY)
# ``_plain_inverse`` runs per straight-line destination and per path cycle: module-level names
# for the math it uses save an attribute lookup each (a fifth of its time).
_atan2, _sqrt, _hypot, _sin, _cos, _remainder = math.atan2, math.sqrt, math.hypot, math.sin, math.cos, math.remainder
_radians, _degrees, _PI, _MM = math.radians, math.degrees, math.pi, units.MM_PER_M


class Pf400Model(RobotModel):
    """A PF400-family arm; see the module docstring for the geometry and the Config rules."""

    def __init__(self, pdb: ParameterDatabase, robot: int = 1) -> None:
        mask = int(pdb.get_num(2003, robot))
        roles = axis_roles(mask, ("z", "shoulder", "elbow"), _OPTIONAL_AXES)
        name, joints = read_joints(pdb, robot, roles, _NAMES, _LINEAR_ROLES)
        super().__init__(name, robot, MODULE_PF400, joints,
                         read_transform(pdb, 16051, robot), read_transform(pdb, 16052, robot))
        self.roles = roles
        self.l1 = units.length_to_si(pdb.get_num(16050, robot, 1, 2))
        self.l2 = units.length_to_si(pdb.get_num(16050, robot, 1, 3))
        self.rail_angle = math.radians(pdb.get_num(16050, robot, 1, 5, default=0.0))
        self.rail_direction = np.array([-math.sin(self.rail_angle), math.cos(self.rail_angle), 0.0])
        self.rail_direction_list = self.rail_direction.tolist()
        self._i = {role: roles.index(role) for role in roles}
        # the axis indices the closed form writes (-1: no such axis), read on every solve
        self._z, self._shoulder, self._elbow = self._i["z"], self._i["shoulder"], self._i["elbow"]
        self._wrist, self._rail = self._i.get("wrist", -1), self._i.get("rail", -1)
        self._n_axes = len(roles)
        self.single_axis = self._i.get("wrist")
        self._build_pin_model()

    def _build_pin_model(self) -> None:
        model = pin.Model()
        model.name = self.name
        ids: dict[str, int] = {}
        parent = 0
        if "rail" in self._i:
            parent = ids["rail"] = model.addJoint(0, pin.JointModelPrismaticUnaligned(self.rail_direction),
                                                  pin.SE3.Identity(), "Rail")
        ids["z"] = model.addJoint(parent, pin.JointModelPZ(), pin.SE3.Identity(), "Z")
        ids["shoulder"] = model.addJoint(ids["z"], pin.JointModelRZ(), pin.SE3.Identity(), "Shoulder")
        ids["elbow"] = model.addJoint(ids["shoulder"], pin.JointModelRZ(),
                                      pin.SE3(np.eye(3), np.array([self.l1, 0.0, 0.0])), "Elbow")
        to_wrist = pin.SE3(np.eye(3), np.array([self.l2, 0.0, 0.0]))
        if "wrist" in self._i:
            hand = ids["wrist"] = model.addJoint(ids["elbow"], pin.JointModelRZ(), to_wrist, "Wrist")
            hand_placement = pin.SE3.Identity()
        else:
            hand, hand_placement = ids["elbow"], to_wrist
        flange = model.addFrame(pin.Frame("flange", hand, hand_placement * pin.SE3(FLANGE_ROTATION, np.zeros(3)),
                                          pin.FrameType.OP_FRAME))
        model.addFrame(pin.Frame("hand", hand, hand_placement, pin.FrameType.OP_FRAME))
        for role in ("gripper", "gripper2"):
            if role in self._i:
                ids[role] = model.addJoint(hand, pin.JointModelPY(), hand_placement, _NAMES[role])
        self._finish_pin_model(model, [ids[r] for r in self.roles], flange)

    # -- inverse --------------------------------------------------------------------------------

    def _plain_inverse(self, pose: Pose, bits: int, current: list[float], check: bool) -> list[float] | None:
        """The closed form (the steps of ``RobotModel.inverse_pose`` and ``_solve_pose``) for the
        case nearly every call is: Base the identity, Tool none or a pure offset, the elbow off
        its branch boundary, every angle's nearest turn within its limits, the result within the
        soft limits.  None for anything else, which the general steps then solve (and refuse
        with their codes).

        Why a second path: a straight ``Move.Loc`` solves its destination when it is queued and
        every cycle of its path solves one pose — ``benchmarks/motion_speed.py`` times the
        former against a bare Ruckig call, and the general steps' calls cost more than the
        solution itself.  The arithmetic is the general steps', operation for operation
        (tests/motion/test_kinematics_pf400.py checks the two agree), except that the axes the
        arm does not solve (gripper, rail) keep their values exactly instead of going through
        metres and back."""
        if bits & _NOT_BRANCH or not self._base_is_identity or len(current) != self._n_axes:
            return None
        r11, r12, r13, r21, r22, r23, r31, r32, r33, x, y, z = pose
        if not self._tool_is_identity:
            shift = self._tool_inv_shift
            if shift is None:
                return None
            tx, ty, tz = shift
            x = r11 * tx + r12 * ty + r13 * tz + x
            y = r21 * tx + r22 * ty + r23 * tz + y
            z = r31 * tx + r32 * ty + r33 * tz + z
        if not (_hypot(r11, r21) <= ORIENTATION_TOLERANCE and r31 >= 0.0):
            return None  # (a NaN anywhere fails a test on this path too)
        psi = _atan2(r23, r13)
        mm = _MM
        x, y, z = x / mm, y / mm, z / mm
        rail = self._rail
        if rail >= 0:
            c, d = current[rail] / mm, self.rail_direction_list
            x, y, z = x - c * d[0], y - c * d[1], z - c * d[2]
        l1, l2 = self.l1, self.l2
        rho = _sqrt(x * x + y * y)
        big, small = l1 + l2, abs(l1 - l2)
        if not small - _REACH_SLACK <= rho <= big + _REACH_SLACK:
            return None
        elbow = 2.0 * _atan2(_sqrt(max(0.0, (big - rho) * (big + rho))), _sqrt(max(0.0, (rho - small) * (rho + small))))
        sh, el, wr = self._shoulder, self._elbow, self._wrist
        el_now = _radians(current[el])
        if bits == GPL_RIGHTY or bits == GPL_LEFTY:
            righty = bits == GPL_RIGHTY
        else:
            e = el_now % TWO_PI
            if min(e, abs(e - _PI), TWO_PI - e) <= BRANCH_EDGE:
                return None
            righty = e < _PI
        j3 = elbow if righty else TWO_PI - elbow
        j2 = _remainder(_atan2(y, x) - _atan2(l2 * _sin(j3), l1 + l2 * _cos(j3)), TWO_PI)
        if j2 == -_PI:
            j2 = _PI  # wrap_pi
        lo, hi = self._slack_lower_si, self._slack_upper_si
        # each angle the turn nearest its current value (``_unwind``'s first case)
        sh_now = _radians(current[sh])
        j2 += round((sh_now - j2) / TWO_PI) * TWO_PI
        j3 += round((el_now - j3) / TWO_PI) * TWO_PI
        if not (abs(j2 - sh_now) < _PI and lo[sh] <= j2 <= hi[sh] and abs(j3 - el_now) < _PI and lo[el] <= j3 <= hi[el]):
            return None
        q = current.copy()
        q[self._z], q[sh], q[el] = z * mm, _degrees(j2), _degrees(j3)
        if wr >= 0:
            wr_now = _radians(current[wr])
            j4 = psi - j2 - j3
            j4 += round((wr_now - j4) / TWO_PI) * TWO_PI
            if not (abs(j4 - wr_now) < _PI and lo[wr] <= j4 <= hi[wr]):
                return None
            q[wr] = _degrees(j4)
        elif abs(wrap_pi(psi - j2 - j3)) > ORIENTATION_TOLERANCE:
            return None
        if check:
            for v, (a, b) in zip(q, self._joint_bounds):
                if not a <= v <= b:
                    return None
        return q

    def _solve_pose(self, rotation: Sequence[float], position: Sequence[float], bits: int,
                    current: list[float]) -> list[float]:
        # Python floats throughout, not numpy: a straight Move.Loc solves its destination when
        # queued, and the path's cycles solve one pose each.
        r00, _, r02, r10, _, r12, r20, _, _ = rotation
        if math.hypot(r00, r10) > ORIENTATION_TOLERANCE or r20 < 0.0:
            raise GplException(INVALID_CARTESIAN, robot_num=self.robot,
                               detail="a PF400 flange must be horizontal (pitch 90, roll 180)")
        psi = math.atan2(r12, r02)
        x, y, z = position
        rail = self._rail
        if rail >= 0:
            d = self.rail_direction_list
            x, y, z = x - current[rail] * d[0], y - current[rail] * d[1], z - current[rail] * d[2]
        l1, l2 = self.l1, self.l2
        rho = math.sqrt(x * x + y * y)
        if rho > l1 + l2 + _REACH_SLACK:
            raise GplException(POSITION_TOO_FAR, robot_num=self.robot, detail=f"radius {rho * 1000:.3f} mm")
        if rho < abs(l1 - l2) - _REACH_SLACK:
            raise GplException(POSITION_TOO_CLOSE, robot_num=self.robot, detail=f"radius {rho * 1000:.3f} mm")
        # Half-angle form of the law of cosines: tan(J3/2) = √((L−ρ)(L+ρ) / ((ρ−D)(ρ+D))), L = l1 + l2,
        # D = |l1 − l2|.  It keeps full precision near the stretched and folded poses, where
        # acos / √(1 − c²) lose half the digits.
        big, small = l1 + l2, abs(l1 - l2)
        elbow = 2.0 * math.atan2(math.sqrt(max(0.0, (big - rho) * (big + rho))),
                                 math.sqrt(max(0.0, (rho - small) * (rho + small))))
        p = (x, y, z)
        righty = preference(bits, GPL_RIGHTY, GPL_LEFTY) if bits else None
        if righty is None:
            e = current[self._elbow] % TWO_PI
            if min(e, abs(e - math.pi), TWO_PI - e) <= BRANCH_EDGE:
                return self._nearest_branch(p, psi, elbow, bits, current, first=e < math.pi)
            righty = e < math.pi
        return self._branch(p, psi, elbow, righty, bits, current)

    def _solve(self, target: pin.SE3, bits: int, current: np.ndarray) -> np.ndarray:
        return np.array(self._solve_pose(target.rotation.ravel().tolist(), target.translation.tolist(), bits,
                                         current.tolist()))

    def _branch(self, p: tuple[float, float, float], psi: float, elbow: float, righty: bool, bits: int,
                current: list[float]) -> list[float]:
        """The solution on one elbow branch (flange position ``p`` in m, rail removed)."""
        l1, l2 = self.l1, self.l2
        q = list(current)
        j3 = elbow if righty else TWO_PI - elbow
        j2 = wrap_pi(math.atan2(p[1], p[0]) - math.atan2(l2 * math.sin(j3), l1 + l2 * math.cos(j3)))
        shoulder, elbow_i, wrist = self._shoulder, self._elbow, self._wrist
        q[self._z] = p[2]
        q[shoulder] = self._unwind(shoulder, j2, current)
        q[elbow_i] = self._unwind(elbow_i, j3, current)
        if wrist >= 0:
            q[wrist] = self._unwind(wrist, psi - q[shoulder] - q[elbow_i], current, single=bool(bits & GPL_SINGLE))
        elif abs(wrap_pi(psi - q[shoulder] - q[elbow_i])) > ORIENTATION_TOLERANCE:
            raise GplException(INVALID_CARTESIAN, robot_num=self.robot, detail="yaw not reachable without a wrist axis")
        return q

    def _nearest_branch(self, p: tuple[float, float, float], psi: float, elbow: float, bits: int,
                        current: list[float], first: bool) -> list[float]:
        """Config 0 with the elbow exactly on a branch boundary (J3 = 0° or 180°: stretched or
        folded, the PF400's usual parking posture): the arm is in both branches at once, so "keep
        the current branch" decides nothing.  Decision [P] (gpl-classes §22.1 item 11: no
        preference → the solution nearest the current joints): the solution within the soft
        limits nearest the current shoulder/elbow/wrist (sum of squared radians); on a tie the
        branch ``config_of`` reports now (``first``: Righty at 0°, Lefty at 180°)."""
        found: list[list[float]] = []
        error: GplException | None = None
        for righty in (first, not first):
            try:
                found.append(self._branch(p, psi, elbow, righty, bits, current))
            except GplException as exc:
                error = error or exc
        if not found:
            assert error is not None
            raise error
        pool = [q for q in found if self._limits_hold(np.array([q]))] or found
        arm = [self._i[r] for r in ("shoulder", "elbow", "wrist") if r in self._i]
        return min(pool, key=lambda q: sum((q[k] - current[k]) ** 2 for k in arm))  # first of equals

    def inverse_path(self, Ts: np.ndarray, seeds: np.ndarray) -> np.ndarray | None:
        """``_solve`` of every pose in numpy (see ``RobotModel.inverse_path``).

        Consecutive samples of a path are far less than half a turn apart, so "the turn nearest
        the previous solution" is the continuous one: each angle is unwrapped along the path from
        the start joints and then written as ``raw + k·2π``, the very expression ``unwind`` uses.
        The elbow keeps the start's branch (it cannot change without folding through J3 = 180°,
        below the reach the checks allow).  Anything else returns None."""
        if Ts.ndim != 3 or not np.isfinite(Ts).all():
            return None
        i = self._i
        target = self._targets(Ts)
        r = target[:, :3, :3]
        if (np.hypot(r[:, 0, 0], r[:, 1, 0]) > ORIENTATION_TOLERANCE).any() or (r[:, 2, 0] < 0.0).any():
            return None
        psi = np.arctan2(r[:, 1, 2], r[:, 0, 2])
        q = units_to_si(seeds, self._linear)
        p = target[:, :3, 3] / units.MM_PER_M
        if "rail" in i:
            p = p - q[:, i["rail"], None] * self.rail_direction
        l1, l2 = self.l1, self.l2
        rho = np.hypot(p[:, 0], p[:, 1])
        big, small = l1 + l2, abs(l1 - l2)
        if rho.max() > big + _REACH_SLACK or rho.min() < small - _REACH_SLACK:
            return None
        start = q[0]
        elbow_now = float(start[i["elbow"]]) % TWO_PI
        if abs(elbow_now - math.pi) < 1e-9 or elbow_now < 1e-9 or TWO_PI - elbow_now < 1e-9:
            return None  # on a branch boundary: pose by pose decides
        elbow = 2.0 * np.arctan2(np.sqrt(np.maximum(0.0, (big - rho) * (big + rho))),
                                 np.sqrt(np.maximum(0.0, (rho - small) * (rho + small))))
        j3 = elbow if elbow_now < math.pi else TWO_PI - elbow
        j2 = np.arctan2(p[:, 1], p[:, 0]) - np.arctan2(l2 * np.sin(j3), l1 + l2 * np.cos(j3))
        j2 = np.remainder(j2 + math.pi, TWO_PI) - math.pi  # wrap_pi up to the ±π tie, which unwinding absorbs
        q[:, i["z"]] = p[:, 2]
        arm = _unwrap_from(np.stack((j2, j3), axis=1), start[[i["shoulder"], i["elbow"]]])
        if arm is None:
            return None
        sh, el = arm[:, 0], arm[:, 1]
        q[:, i["shoulder"]], q[:, i["elbow"]] = sh, el
        if "wrist" in i:
            wr = _unwrap_from((psi - sh - el)[:, None], start[[i["wrist"]]])
            if wr is None:
                return None
            q[:, i["wrist"]] = wr[:, 0]
        elif (np.abs(np.remainder(psi - sh - el + math.pi, TWO_PI) - math.pi) > ORIENTATION_TOLERANCE).any():
            return None
        if not self._limits_hold(q):
            return None
        return si_to_units(q, self._linear)

    def _config(self, q: Sequence[float]) -> int:
        return GPL_RIGHTY if q[self._elbow] % TWO_PI < math.pi else GPL_LEFTY


def _unwrap_from(raw: np.ndarray, start: np.ndarray) -> np.ndarray | None:
    """Column by column (N×m), ``raw + k·2π`` with each k giving the turn nearest the previous
    value (``start`` before the first row): None when two neighbours are half a turn apart or
    more, where "nearest" is not clear."""
    steps = np.empty_like(raw)
    steps[0] = raw[0] - start
    steps[1:] = raw[1:] - raw[:-1]
    wrapped = np.remainder(steps + math.pi, TWO_PI) - math.pi
    if np.abs(wrapped).max() >= math.pi - 1e-6:
        return None
    cont = start + np.cumsum(wrapped, axis=0)
    return raw + np.round((cont - raw) / TWO_PI) * TWO_PI


def units_to_si(q: np.ndarray, linear: list[bool]) -> np.ndarray:
    """N×n joints in GPL units (mm, deg) → SI (m, rad), column by column as ``units.joints_to_si_list``."""
    lin = np.array(linear)
    return np.where(lin, q / units.MM_PER_M, np.radians(q))


def si_to_units(q: np.ndarray, linear: list[bool]) -> np.ndarray:
    """N×n SI joints → GPL units (the inverse of ``units_to_si``)."""
    lin = np.array(linear)
    return np.where(lin, q * units.MM_PER_M, np.degrees(q))

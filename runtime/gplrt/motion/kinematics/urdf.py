"""Robot models built from a URDF with Pinocchio: the Adept Viper s650 and Cobra s600, the
Techman TM5-700, TM5-900, TM12 and TM14 (kinematic modules 9001-9006, ours; the catalogue and
the parameter database derived from each URDF are in ``gplrt.controller.urdf_catalogue``).

**The model.** ``pin.buildModelFromUrdf`` reads every joint of the file.  A ``<mimic>`` joint
(the Cobra's ``flyover_cable_joint``, which follows ``inner_joint``) is not an axis: it is locked
out of the model the kinematics run on (``pin.buildReducedModel``), so the robot has one
actuated joint where the URDF has two, and ``urdf_joint_values`` gives the value the follower
takes (``multiplier · leader + offset``) for whoever shows the whole URDF (a viewer, a ROS
joint_states).  Pinocchio's own mimic support cannot load this file: urdfdom orders a link's
children by name, so ``flyover_cable_joint`` comes before the ``inner_joint`` it follows and
Pinocchio refuses it ("The parent joint of the mimic joint is not in the kinematic tree"); and
the follower moves only a cable, nothing between the base and the flange.

Axes are the joints from the root to the flange frame, in that order (J1 … Jn); units as every
GPL robot: degrees, mm for the Cobra's quill.  Position limits come from the parameter database,
which holds the URDF's; the flange is the catalogue's frame (``tool0`` for the Adept arms,
``flange`` for the TMs); Tool and Base work as on every robot (``RobotModel``).

**Configuration bits** (the V+ words, gplrt's GPL_… bits; the manual's definitions, V+ Language
User's Guide L6732-6996, made geometric so that one rule serves every arm):

* **Righty / Lefty.**  SCARA: the first two links resemble a right arm seen from above, i.e. the
  outer link turns counter-clockwise from the inner one (sin of the elbow angle ≥ 0; the Cobra's
  J2 ≥ 0).  Six axes: the wrist point (origin of J5) in front of the J1 axis (x ≥ 0 in the J1
  frame), as ``articulated.py`` decides it for ARM6.
* **Above / Below** (six axes): the elbow (origin of J3) above the line from the shoulder (origin
  of J2) to the wrist point, seen in the arm's plane with the reach pointing forward.
* **Flip / NoFlip** (six axes): "the pitch angle of the wrist" J5 negative / positive or zero.
* A pair the bits leave open keeps the branch the robot is in; where the robot sits exactly on a
  branch's boundary (J5 = 0, the arm stretched, the wrist point on the J1 axis) both branches are
  tried and the in-limits solution nearest the current joints wins (as ``articulated.py``).

**Inverse kinematics.**  Closed forms where the geometry allows, checked against Pinocchio's
forward kinematics to 1e-9 (tests/motion/test_kinematics_urdf.py):

* ``SphericalWrist`` (Viper): J1 vertical, J2 ∥ J3 horizontal, J4-J5-J6 meeting at the wrist
  centre; the wrist centre gives J1 (Righty/Lefty) and J2, J3 (a two-link law of cosines,
  Above/Below), the orientation left for the wrist gives J4, J5, J6 (ZYZ, Flip/NoFlip).
* ``Scara`` (Cobra): two parallel vertical revolutes, the vertical quill, the roll about it; the
  flange must keep its vertical axis (else -1033).  Its usual case also has a one-method path
  (``Scara.plain``, through ``_plain_inverse``), bit for bit the general steps' answer, as the
  PF400's: a straight line solves a pose per cycle.
* ``OffsetWrist`` (TM: J2 ∥ J3 ∥ J4 and an offset wrist, like a UR): a closed form on the
  product of exponentials read from the model (J1 from the wrist point's offset across the arm's
  plane, J5 and J6 from the approach, J2/J3 by the law of cosines, J4 the rest), each candidate
  polished by ``articulated.solve_dls`` on the Pinocchio model, because the TM files write π/2
  as 1.570796 and the structure holds only to 3e-7.

Errors are the controller's (as the PF400 and ARM6 models): -1040 / -1039 for a position beyond
or inside the reach, -1033 for an orientation the arm cannot take (SCARA) or a pose with no
solution in the configuration asked for, -1012 (with the axis) for a solution outside the soft limits.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
import pinocchio as pin

from gplrt.controller.pdb import ParameterDatabase
from gplrt.controller.urdf_catalogue import BY_MODULE, OFFSET_WRIST, SCARA, SPHERICAL_WRIST, UrdfChain, UrdfRobot, read_chain
from gplrt.geometry.transforms import Pose
from gplrt.lang.errors import (
    INVALID_AXIS_COUNT,
    INVALID_CARTESIAN,
    POSITION_TOO_CLOSE,
    POSITION_TOO_FAR,
    GplException,
)
from gplrt.motion.kinematics import units
from gplrt.motion.kinematics.articulated import solve_dls
from gplrt.motion.kinematics.base import JointInfo, JointKind, RobotModel, read_limits, read_transform, robot_name
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

#: Within this of a branch boundary (a measure of ``_measures``: m, m² or rad) the arm is in both
#: branches of the pair.  A micrometre, not 1e-9: the TM files' π/2 (1.570796) leaves their
#: straight-up zero pose 3e-7 m off the J1 axis, and that pose is on every boundary.
BRANCH_EDGE = 1e-6
#: Allowed tilt of a SCARA flange's vertical axis: 1e-6 degree (as the PF400's, pf400.py).
ORIENTATION_TOLERANCE = math.sin(math.radians(1e-6))
#: Slack on reach checks (m) so that poses computed at full stretch are not refused.
_REACH_SLACK = 1e-12
#: The polish's acceptance (``OffsetWrist``): the pose error (log6 norm, m and rad) of a solution.
POLISH_TOLERANCE = 1e-10
#: Config pairs (yes, no) in the order of ``_measures``.
_PAIRS = ((GPL_RIGHTY, GPL_LEFTY), (GPL_ABOVE, GPL_BELOW), (GPL_NOFLIP, GPL_FLIP))

_TWO_PI = 2.0 * math.pi
#: Config bits the SCARA's ``plain`` leaves to the general steps (all but the elbow's).
_NOT_ELBOW = ~(GPL_RIGHTY | GPL_LEFTY)

Candidate = list[float]  # GPL-ordered SI joints
#: A solver's answer: its candidates (every branch it reaches), and why it missed the others.
Solutions = tuple[list[Candidate], GplException | None]


class UrdfModel(RobotModel):
    """A robot from the URDF its kinematic module names (module docstring)."""

    def __init__(self, pdb: ParameterDatabase, robot: int = 1) -> None:
        module = int(pdb.get_num(116, 1, 1, robot, default=0.0))
        spec = BY_MODULE[module]
        chain = read_chain(spec.path, spec.flange)
        name = robot_name(pdb, robot)
        n = int(pdb.get_num(2000, robot))
        if n != len(chain.axes):
            raise GplException(INVALID_AXIS_COUNT, detail=f"{name}: 2000 = {n} axes but {spec.file} has {len(chain.axes)}")
        lower, upper = read_limits(pdb, robot, n)
        joints = [JointInfo(j.name, JointKind.LINEAR if j.linear else JointKind.ROTARY, f"j{i + 1}", lo, hi)
                  for i, (j, lo, hi) in enumerate(zip(chain.axes, lower, upper, strict=True))]
        super().__init__(name, robot, module, joints, read_transform(pdb, 16051, robot), read_transform(pdb, 16052, robot))
        self.spec: UrdfRobot = spec
        self.chain: UrdfChain = chain
        #: Every joint of the URDF, the mimic ones included (``urdf_joint_values``' reader).
        self.full_model = pin.buildModelFromUrdf(str(spec.path))
        locked = [self.full_model.getJointId(j.name) for j in chain.mimics]
        model = pin.buildReducedModel(self.full_model, locked, pin.neutral(self.full_model)) if locked else pin.Model(self.full_model)
        model.name = name
        if not model.existFrame(spec.flange):
            raise ValueError(f"{spec.file}: no frame {spec.flange!r}")
        self._axis_ids = [model.getJointId(j.name) for j in chain.axes]
        self._finish_pin_model(model, self._axis_ids, model.getFrameId(spec.flange))
        self.single_axis = n - 1
        self._solver: _Solver = {
            SPHERICAL_WRIST: SphericalWrist, SCARA: Scara, OFFSET_WRIST: OffsetWrist}[spec.solver](self)

    # -- the whole URDF -------------------------------------------------------------------------

    def urdf_joint_values(self, joints: Sequence[float]) -> dict[str, float]:
        """Every movable URDF joint's value (degrees or mm) for a joint vector: the axes as given,
        each mimic joint ``multiplier · leader + offset`` (in SI, as the URDF defines it)."""
        values = {j.name: float(v) for j, v in zip(self.chain.axes, joints, strict=True)}
        by_name = {j.name: j for j in self.chain.axes}
        for m in self.chain.mimics:
            assert m.mimic is not None
            leader, multiplier, offset = m.mimic
            lead = by_name[leader]
            si = units.joint_to_si(values[leader], lead.linear)
            values[m.name] = m.to_units(multiplier * si + offset)
        return values

    def full_configuration(self, joints: Sequence[float]) -> np.ndarray:
        """``full_model``'s configuration vector (SI) for a joint vector: the URDF's every joint."""
        q = pin.neutral(self.full_model)
        by_name = {j.name: j for j in (*self.chain.axes, *self.chain.mimics)}
        for name, value in self.urdf_joint_values(joints).items():
            jid = self.full_model.getJointId(name)
            q[self.full_model.joints[jid].idx_q] = units.joint_to_si(value, by_name[name].linear)
        return q

    # -- configuration --------------------------------------------------------------------------

    def _measures(self, q: Sequence[float]) -> tuple[float, ...]:
        """Signed measures of the branches of SI joints ``q``, one per pair of ``_PAIRS`` the arm
        has: positive (or zero) for the first bit of the pair (Righty, Above, NoFlip)."""
        return self._solver.measures(q)

    def _config(self, q: Sequence[float]) -> int:
        bits = 0
        for (yes, no), m in zip(_PAIRS, self._measures(q)):
            bits |= yes if m >= 0.0 else no
        return bits

    # -- inverse --------------------------------------------------------------------------------

    def _solve_pose(self, rotation: Sequence[float], position: Sequence[float], bits: int,
                    current: list[float]) -> Sequence[float]:
        R = np.array(rotation, dtype=float).reshape(3, 3)
        p = np.array(position, dtype=float)
        now = self._measures(current)
        wanted: list[bool | None] = []
        for (yes, no), m in zip(_PAIRS, now):
            pref = preference(bits, yes, no)
            wanted.append(pref if pref is not None else None if abs(m) <= BRANCH_EDGE else m >= 0.0)
        single = bool(bits & GPL_SINGLE)

        seen: dict[tuple[float, ...], bool] = {}

        def fits(q: Candidate) -> bool:
            key = tuple(q)
            ok = seen.get(key)
            if ok is None:
                ok = seen[key] = all(w is None or abs(m) <= BRANCH_EDGE or (m >= 0.0) == w
                                     for w, m in zip(wanted, self._measures(q)))
            return ok

        candidates, error = self._solver(R, p, current, fits)
        found = [self._turns(q, current, single) for q in candidates if fits(q)]
        if len(found) > 1:  # (the solver may have returned the same solution twice)
            found = [q for k, q in enumerate(found) if q not in found[:k]]
        if not found:
            if error is not None:  # the branch asked for is out of reach, the others not
                raise error
            raise GplException(INVALID_CARTESIAN, robot_num=self.robot,
                               detail=f"{self.name}: no solution in the configuration asked for")
        lower, upper = self._slack_lower_si, self._slack_upper_si
        pool = [q for q in found if all(a <= v <= b for v, a, b in zip(q, lower, upper))] or found
        return min(pool, key=lambda q: sum((a - b) ** 2 for a, b in zip(q, current)))  # first of equals

    def _plain_inverse(self, pose: Pose, bits: int, current: list[float], check: bool) -> list[float] | None:
        """The solver's one-method path for the usual case (``Scara.plain``), or None: Base the
        identity, Tool none or a pure offset, applied with the general steps' arithmetic."""
        plain = self._solver.plain
        if plain is None or not self._base_is_identity or len(current) != len(self.joints):
            return None
        r11, r12, r13, r21, r22, r23, r31, r32, r33, x, y, z = pose
        if not self._tool_is_identity:
            shift = self._tool_inv_shift
            if shift is None:
                return None
            tx, ty, tz = shift
            x, y, z = (r11 * tx + r12 * ty + r13 * tz + x, r21 * tx + r22 * ty + r23 * tz + y,
                       r31 * tx + r32 * ty + r33 * tz + z)
        mm = units.MM_PER_M
        return plain((r11, r12, r13, r21, r22, r23, r31, r32, r33), (x / mm, y / mm, z / mm), bits, current, check)

    def _turns(self, q: Candidate, current: list[float], single: bool) -> Candidate:
        """Each rotary axis on the turn nearest its current value (``RobotModel._unwind``)."""
        return [self._unwind(i, v, current, single) if not j.linear else v
                for i, (v, j) in enumerate(zip(q, self.joints, strict=True))]

    # -- Pinocchio helpers for the solvers -----------------------------------------------------

    def joint_origins(self, q: Sequence[float]) -> list[pin.SE3]:
        """The joint frames J1 … Jn in the world (m) for SI joints ``q``, no Base or Tool."""
        assert self.pin_model is not None and self.pin_data is not None
        with self.lock:
            pin.forwardKinematics(self.pin_model, self.pin_data, self.q_pin(q))
            return [self.pin_data.oMi[i].copy() for i in self._axis_ids]


class _Solver:
    """What a solver family knows of the model it was built for."""

    #: The one-method inverse of the usual case (``Scara.plain``), where the family has one.
    plain: Callable[[Sequence[float], Sequence[float], int, list[float], bool], list[float] | None] | None = None

    def __init__(self, model: UrdfModel) -> None:
        self.model = model
        self.robot = model.robot

    def measures(self, q: Sequence[float]) -> tuple[float, ...]:
        raise NotImplementedError

    def __call__(self, R: np.ndarray, p: np.ndarray, current: list[float],
                 fits: Callable[[Candidate], bool]) -> Solutions:
        raise NotImplementedError

    def too_far(self, detail: str) -> GplException:
        return GplException(POSITION_TOO_FAR, robot_num=self.robot, detail=detail)

    def too_close(self, detail: str) -> GplException:
        return GplException(POSITION_TOO_CLOSE, robot_num=self.robot, detail=detail)


def _arm_measures(origins: list[pin.SE3], q: Sequence[float]) -> tuple[float, float, float]:
    """(Righty, Above, NoFlip) measures of a six-axis arm from its joint frames (module
    docstring): the wrist point's x in the J1 frame; the signed area of shoulder → wrist and
    shoulder → elbow in the arm's plane, mirrored for a wrist behind the J1 axis; sin-free J5."""
    j1 = origins[0]
    s, e, w = (j1.actInv(o.translation) for o in (origins[1], origins[2], origins[4]))
    reach = 1.0 if w[0] >= 0.0 else -1.0
    dx, dz, fx, fz = w[0] - s[0], w[2] - s[2], e[0] - s[0], e[2] - s[2]
    return float(w[0]), reach * (dx * fz - dz * fx), wrap_pi(float(q[4]))


class SphericalWrist(_Solver):
    """Closed form for a 6R arm with J1 about z, J2 and J3 about y, J4 about z, J5 about y, J6
    about z, every joint frame aligned with the base at zero, no sideways (y) offsets, and J4, J5,
    J6 meeting in one point (the Viper s650).  Geometry read from the Pinocchio model."""

    def __init__(self, model: UrdfModel) -> None:
        super().__init__(model)
        m = model.pin_model
        assert m is not None
        ids = [m.getJointId(j.name) for j in model.chain.axes]
        axes = [j.shortname() for j in (m.joints[i] for i in ids)]
        place = [m.jointPlacements[i] for i in ids]
        flange = m.frames[model.flange_frame]
        if (axes != ["JointModelRZ", "JointModelRY", "JointModelRY", "JointModelRZ", "JointModelRY", "JointModelRZ"]
                or any(not np.allclose(pl.rotation, np.eye(3), atol=1e-12) for pl in place)
                or any(abs(pl.translation[1]) > 1e-12 for pl in place[1:])
                or any(abs(pl.translation[k]) > 1e-12 for pl in place[4:6] for k in (0, 1))
                or flange.parentJoint != ids[5]):
            raise ValueError(f"{model.spec.file}: not a spherical-wrist arm of the expected layout")
        self.base = place[0].translation.copy()  # J1 origin (m)
        self.a1, self.d1 = float(place[1].translation[0]), float(place[1].translation[2])
        self.u = (float(place[2].translation[0]), float(place[2].translation[2]))  # J2 → J3 at zero
        v4, v5 = place[3].translation, place[4].translation
        self.v = (float(v4[0] + v5[0]), float(v4[2] + v5[2]))  # J3 → wrist centre at zero
        self.d6 = float(place[5].translation[2])  # wrist centre → J6 origin, along J6's z
        self.flange_inv = flange.placement.inverse()  # J6 frame = flange target · this
        ux, uz = self.u
        vx, vz = self.v
        self.lu, self.lv = math.hypot(ux, uz), math.hypot(vx, vz)
        self.phi = math.atan2(ux * vz - uz * vx, ux * vx + uz * vz)

    def measures(self, q: Sequence[float]) -> tuple[float, ...]:
        """``_arm_measures`` in the arm's plane by hand (each IK weighs eight candidates): the
        elbow is the shoulder + Ry(J2)·u, the wrist centre the elbow + Ry(J2 + J3)·v."""
        (ux, uz), (vx, vz) = self.u, self.v
        c2, s2 = math.cos(q[1]), math.sin(q[1])
        c23, s23 = math.cos(q[1] + q[2]), math.sin(q[1] + q[2])
        fx, fz = ux * c2 + uz * s2, -ux * s2 + uz * c2  # shoulder → elbow
        dx, dz = fx + vx * c23 + vz * s23, fz - vx * s23 + vz * c23  # shoulder → wrist centre
        wx = self.a1 + dx
        return wx, (1.0 if wx >= 0.0 else -1.0) * (dx * fz - dz * fx), wrap_pi(q[4])

    def __call__(self, R: np.ndarray, p: np.ndarray, current: list[float],
                 fits: Callable[[Candidate], bool]) -> Solutions:
        j6 = pin.SE3(R, p) * self.flange_inv
        R6, p6 = j6.rotation, j6.translation
        w = p6 - self.d6 * R6[:, 2] - self.base
        rho = math.hypot(w[0], w[1])
        azimuth = math.atan2(w[1], w[0]) if rho > BRANCH_EDGE else current[0]
        out: list[Candidate] = []
        error: GplException | None = None
        for shoulder in (0.0, math.pi):  # Righty, then Lefty (the wrist centre behind J1)
            q1 = wrap_pi(azimuth + shoulder)
            x = (rho if shoulder == 0.0 else -rho) - self.a1
            z = w[2] - self.d1
            k = (x * x + z * z - self.lu ** 2 - self.lv ** 2) / (2.0 * self.lu * self.lv)
            if k > 1.0 + 1e-12:
                error = error or self.too_far(f"wrist centre {math.hypot(x, z) * 1000:.3f} mm from the shoulder")
                continue
            if k < -1.0 - 1e-12:
                error = error or self.too_close(f"wrist centre {math.hypot(x, z) * 1000:.3f} mm from the shoulder")
                continue
            bend = math.acos(max(-1.0, min(1.0, k)))
            for q3 in (self.phi + bend, self.phi - bend):
                c3, s3 = math.cos(q3), math.sin(q3)
                vx, vz = self.v
                mx = self.u[0] + c3 * vx + s3 * vz
                mz = self.u[1] - s3 * vx + c3 * vz
                q2 = math.atan2(x, z) - math.atan2(mx, mz)
                c1, s1 = math.cos(q1), math.sin(q1)
                c23, s23 = math.cos(q2 + q3), math.sin(q2 + q3)
                r03 = np.array([[c1 * c23, -s1, c1 * s23], [s1 * c23, c1, s1 * s23], [-s23, 0.0, c23]])
                r = r03.T @ R6
                s5 = math.hypot(r[0, 2], r[1, 2])
                if s5 < 1e-12:  # J4 and J6 about one axis: keep J4, give the rest to J6
                    q4 = current[3]
                    wrists = [(q4, 0.0, math.atan2(r[1, 0], r[0, 0]) - q4)]
                else:
                    wrists = [(math.atan2(r[1, 2], r[0, 2]), math.atan2(s5, r[2, 2]), math.atan2(r[2, 1], -r[2, 0])),
                              (math.atan2(-r[1, 2], -r[0, 2]), -math.atan2(s5, r[2, 2]), math.atan2(-r[2, 1], r[2, 0]))]
                out.extend([q1, wrap_pi(q2), wrap_pi(q3), q4, q5, q6] for q4, q5, q6 in wrists)
        if not out:
            assert error is not None
            raise error
        return out, error


class Scara(_Solver):
    """Closed form for a SCARA: J1 and J2 about vertical axes, J3 a vertical prismatic quill, J4
    a roll about the quill, the flange on the quill's axis (the Cobra s600).  Geometry read from
    the Pinocchio model at zero; axis directions (the Cobra's J4 turns about −z) kept as signs."""

    def __init__(self, model: UrdfModel) -> None:
        super().__init__(model)
        m, data = model.pin_model, model.pin_data
        assert m is not None and data is not None
        zero = [0.0] * 4
        o = model.joint_origins(zero)
        pin.updateFramePlacements(m, data)
        f0 = data.oMf[model.flange_frame].copy()
        ids = [m.getJointId(j.name) for j in model.chain.axes]
        signs = []
        for k, (jid, frame) in enumerate(zip(ids, o)):
            axis = frame.rotation @ _joint_axis(m.joints[jid])
            if abs(abs(axis[2]) - 1.0) > 1e-12:
                raise ValueError(f"{model.spec.file}: axis {k + 1} is not vertical")
            signs.append(1.0 if axis[2] > 0 else -1.0)
        self.s1, self.s2, self.s3, self.s4 = signs
        self.c = (float(o[0].translation[0]), float(o[0].translation[1]))  # J1 axis (m)
        e = o[1].translation[:2] - o[0].translation[:2]  # J1 → J2 at zero
        h = f0.translation[:2] - o[1].translation[:2]  # J2 → flange at zero
        if np.linalg.norm(f0.translation[:2] - o[3].translation[:2]) > 1e-12:
            raise ValueError(f"{model.spec.file}: the flange is not on the roll axis")
        self.l1, self.l2 = float(np.linalg.norm(e)), float(np.linalg.norm(h))
        self.t1 = math.atan2(e[1], e[0])  # direction of the inner link at zero
        self.t2 = math.atan2(h[1], h[0]) - self.t1  # outer link's angle to the inner one at zero
        self.z0 = float(f0.translation[2])
        self.axis0 = tuple(f0.rotation[:, 2].tolist())  # the flange's vertical axis (the Cobra's: down)
        self.r0_x = tuple(f0.rotation[:, 0].tolist())  # the flange's x axis at zero (R0ᵀ's first row)

    def measures(self, q: Sequence[float]) -> tuple[float, ...]:
        return (math.sin(self.t2 + self.s2 * q[1]),)

    def __call__(self, R: np.ndarray, p: np.ndarray, current: list[float],
                 fits: Callable[[Candidate], bool]) -> Solutions:
        yaw, x, y, bend, d3 = self._target(R.ravel().tolist(), p.tolist())
        return [self._branch(yaw, x, y, bend, d3, righty) for righty in (True, False)], None

    def _target(self, rotation: Sequence[float], position: Sequence[float]) -> tuple[float, float, float, float, float]:
        """(yaw, x and y from the J1 axis, the elbow's bend, J3) of a flange target (row-major
        rotation, position in m); -1033 for a tilted flange, -1040 / -1039 beyond the reach."""
        r00, r01, r02, r10, r11, r12, _, _, r22 = rotation
        a0, a1, a2 = self.axis0
        if r02 * a0 + r12 * a1 + r22 * a2 < 1.0 - ORIENTATION_TOLERANCE ** 2 / 2:
            raise GplException(INVALID_CARTESIAN, robot_num=self.robot,
                               detail=f"{self.model.name}: the flange axis must stay vertical")
        # yaw of the target about the vertical, relative to the flange at zero: R · R0ᵀ's first column
        b00, b01, b02 = self.r0_x
        yaw = math.atan2(r10 * b00 + r11 * b01 + r12 * b02, r00 * b00 + r01 * b01 + r02 * b02)
        x, y = position[0] - self.c[0], position[1] - self.c[1]
        rho = math.hypot(x, y)
        big, small = self.l1 + self.l2, abs(self.l1 - self.l2)
        if rho > big + _REACH_SLACK:
            raise self.too_far(f"radius {rho * 1000:.3f} mm")
        if rho < small - _REACH_SLACK:
            raise self.too_close(f"radius {rho * 1000:.3f} mm")
        # half-angle law of cosines (pf400.py): full precision near stretched and folded
        bend = 2.0 * math.atan2(math.sqrt(max(0.0, (big - rho) * (big + rho))),
                                math.sqrt(max(0.0, (rho - small) * (rho + small))))
        return yaw, x, y, bend, (position[2] - self.z0) / self.s3

    def _branch(self, yaw: float, x: float, y: float, bend: float, d3: float, righty: bool) -> Candidate:
        """The solution (SI) with the outer link turning counter-clockwise (Righty) or not."""
        beta = bend if righty else -bend
        inner = math.atan2(y, x) - math.atan2(self.l2 * math.sin(beta), self.l1 + self.l2 * math.cos(beta))
        q1 = wrap_pi((inner - self.t1) / self.s1)
        q2 = wrap_pi((beta - self.t2) / self.s2)
        return [q1, q2, d3, wrap_pi((yaw - self.s1 * q1 - self.s2 * q2) / self.s4)]

    def plain(self, rotation: Sequence[float], position: Sequence[float], bits: int, current: list[float],
              check: bool) -> list[float] | None:
        """``UrdfModel.inverse`` for the case nearly every call is, in GPL units (``current`` too),
        or None for the general steps: no bits but the elbow's, the elbow off its boundary (now
        and at the target), the target reachable, every rotary axis's nearest turn inside its
        limits, the result inside the soft limits.  The arithmetic is the general steps', so
        the answer is theirs to the bit (tests/motion/test_kinematics_urdf.py).

        Why: a straight line solves a pose per trajectory cycle, and the general steps weigh two
        candidates around a closed form of a few dozen operations (benchmarks/kinematics_speed.py)."""
        if bits & _NOT_ELBOW:
            return None
        if bits == GPL_RIGHTY or bits == GPL_LEFTY:
            righty = bits == GPL_RIGHTY
        else:
            now = math.sin(self.t2 + self.s2 * math.radians(current[1]))
            if abs(now) <= BRANCH_EDGE:
                return None
            righty = now >= 0.0
        try:
            yaw, x, y, bend, d3 = self._target(rotation, position)
        except GplException:
            return None  # (the general steps raise it)
        if abs(math.sin(bend)) <= BRANCH_EDGE:
            return None
        q = self._branch(yaw, x, y, bend, d3, righty)
        model = self.model
        lo, hi = model._slack_lower_si, model._slack_upper_si
        for i in (0, 1, 3):  # each angle the turn nearest its current value (``_unwind``'s first case)
            now_i = math.radians(current[i])
            near = q[i] + round((now_i - q[i]) / _TWO_PI) * _TWO_PI
            if not (abs(near - now_i) < math.pi and lo[i] <= near <= hi[i]):
                return None
            q[i] = near
        joints = [math.degrees(q[0]), math.degrees(q[1]), q[2] * units.MM_PER_M, math.degrees(q[3])]
        if check:
            for v, (a, b) in zip(joints, model._joint_bounds):
                if not a <= v <= b:
                    return None
        return joints


class OffsetWrist(_Solver):
    """Six axes with J2, J3, J4 parallel and an offset wrist (the TMs, like a UR): J4's axis
    meets J5's, J5's meets J6's, J5 is square to J4 and J6 to J5.  A closed form on the product
    of exponentials of the model at zero (axes and points read from Pinocchio), then
    ``articulated.solve_dls`` polishes each candidate on the Pinocchio model itself: the TM files
    write π/2 as 1.570796, so the structure holds to 3e-7 and the closed form is a seed that the
    polish takes to machine precision in a few iterations.

    Steps (W: where J5 and J6 meet, fixed in the flange; P: where J4 and J5 meet):
    J1 from W's offset across the arm's plane (two answers: Righty/Lefty); J5 from the angle
    between J6's axis and the J2 axis (two answers: Flip/NoFlip); J6 from the J2 axis seen in the
    flange; J2+J3+J4 from the rotation left; J2 and J3 from P by the law of cosines (two answers:
    Above/Below); J4 the rest."""

    def __init__(self, model: UrdfModel) -> None:
        super().__init__(model)
        m, data = model.pin_model, model.pin_data
        assert m is not None and data is not None
        o = model.joint_origins([0.0] * 6)
        pin.updateFramePlacements(m, data)
        self.M = data.oMf[model.flange_frame].copy()
        ids = [m.getJointId(j.name) for j in model.chain.axes]
        self.w = [frame.rotation @ _joint_axis(m.joints[jid]) for jid, frame in zip(ids, o)]  # axes at zero
        self.c = [frame.translation.copy() for frame in o]  # a point on each axis
        n = self.w[1]
        self.n = n
        self.s = [float(np.dot(self.w[k], n)) for k in (1, 2, 3)]  # J2-J4: ±n
        if (any(abs(abs(v) - 1.0) > 1e-6 for v in self.s) or abs(np.dot(self.w[4], n)) > 1e-6
                or abs(np.dot(self.w[5], self.w[4])) > 1e-6):
            raise ValueError(f"{model.spec.file}: not an offset-wrist arm (J2 ∥ J3 ∥ J4, J5 ⊥ J4, J6 ⊥ J5)")
        self.P0 = _meet(self.c[3], self.w[3], self.c[4], self.w[4])
        self.W0 = _meet(self.c[4], self.w[4], self.c[5], self.w[5])
        self.w_flange = self.M.actInv(self.W0)  # W in flange coordinates (constant)
        self.k = float(np.dot(self.W0 - self.c[0], n))  # W's offset across the arm's plane
        self.beta = math.atan2(n[1], n[0])
        self.e1 = _perpendicular(n)  # the arm's plane (square to n)
        self.e2 = _cross(n, self.e1)
        self.A = float(np.dot(self.w[5], n))
        self.B = float(np.dot(_cross(self.w[4], self.w[5]), n))
        # ``measures``' constants: the J1 frame at zero, the shoulder in it, the links at zero
        j1 = o[0]
        self._to_j1 = j1.rotation.T.tolist()
        self._links = (tuple(j1.actInv(self.c[1]).tolist()), *(tuple((self.c[k + 1] - self.c[k]).tolist()) for k in (1, 2, 3)))
        self._axes234 = tuple(tuple(self.w[k].tolist()) for k in (1, 2, 3))
        self.reach = float(np.linalg.norm(self.c[2] - self.c[1]) + np.linalg.norm(self.P0 - self.c[2])
                           + np.linalg.norm(self.W0 - self.P0) + np.linalg.norm(self.M.translation - self.W0))

    def measures(self, q: Sequence[float]) -> tuple[float, ...]:
        """``_arm_measures`` on the product of exponentials (every IK weighs eight candidates):
        the elbow (J3's origin) and the wrist point (J5's) turned about the J2, J3, J4 axes as
        the model has them at zero, in the J1 frame, where J1 itself changes nothing."""
        s, arm3, arm4, arm5 = self._links
        (w2, w3, w4) = self._axes234
        v = _turn(w4, q[3], arm5)
        v = _turn(w3, q[2], (arm4[0] + v[0], arm4[1] + v[1], arm4[2] + v[2]))
        f = _turn(w2, q[1], arm3)  # shoulder → elbow
        d = _turn(w2, q[1], (arm3[0] + v[0], arm3[1] + v[1], arm3[2] + v[2]))  # shoulder → wrist point
        to_j1 = self._to_j1
        e = [sum(to_j1[r][k] * f[k] for k in range(3)) for r in range(3)]
        w = [sum(to_j1[r][k] * d[k] for k in range(3)) for r in range(3)]
        wx = s[0] + w[0]
        return wx, (1.0 if wx >= 0.0 else -1.0) * (w[0] * e[2] - w[2] * e[0]), wrap_pi(q[4])

    def __call__(self, R: np.ndarray, p: np.ndarray, current: list[float],
                 fits: Callable[[Candidate], bool]) -> Solutions:
        model = self.model
        target = pin.SE3(R, p)
        W = target.act(self.w_flange)
        if float(np.linalg.norm(W - self.c[1])) > self.reach + _REACH_SLACK:
            raise self.too_far(f"wrist {np.linalg.norm(W - self.c[1]) * 1000:.3f} mm from the shoulder")
        d = W - self.c[0]
        r = math.hypot(d[0], d[1])
        if r < abs(self.k) - _REACH_SLACK:  # (exactly |k|: the arm straight up, one J1 for both)
            raise self.too_close(f"wrist {r * 1000:.3f} mm from the J1 axis")
        psi = math.atan2(d[1], d[0])
        across = math.acos(max(-1.0, min(1.0, self.k / r)))
        out: list[Candidate] = []
        error: GplException | None = None
        for q1 in (psi - self.beta - across, psi - self.beta + across):
            # J5: J6's axis against the J2 axis (turned by J1)
            R1 = pin.AngleAxis(q1, self.w[0]).matrix()
            n1 = R1 @ self.n
            a = R @ self.M.rotation.T @ self.w[5]  # J6's axis at the target
            h = math.hypot(self.A, self.B)
            cos5 = max(-1.0, min(1.0, float(np.dot(a, n1)) / h))
            for q5 in (math.atan2(self.B, self.A) + math.acos(cos5), math.atan2(self.B, self.A) - math.acos(cos5)):
                R5 = pin.AngleAxis(q5, self.w[4]).matrix()
                # J6: the J2 axis seen from the flange, against the same seen at J6 = 0
                v = self.M.rotation @ R.T @ n1  # = R(w6, -q6) · R5ᵀ n
                u = R5.T @ self.n
                # (J5 near 0 or 180°: J6 ∥ J4, only their sum counts; the polish settles it)
                q6 = -_rotation_angle(self.w[5], u, v) if abs(math.sin(q5)) > BRANCH_EDGE else current[5]
                R6 = pin.AngleAxis(q6, self.w[5]).matrix()
                R234 = R1.T @ R @ self.M.rotation.T @ R6.T @ R5.T  # a rotation about n
                theta = _rotation_angle(self.n, self.e1, R234 @ self.e1)
                # P (J4 ∩ J5) from W, then J2 and J3 from P in the arm's plane
                P = W - R1 @ R234 @ (self.W0 - self.P0)
                P1 = R1.T @ (P - self.c[0]) + self.c[0]  # back in J1's zero frame
                try:
                    arms = self._planar(P1)
                except GplException as exc:
                    error = error or exc
                    continue
                for q2, q3 in arms:
                    q4 = (theta - self.s[0] * q2 - self.s[1] * q3) / self.s[2]
                    out.append([wrap_pi(v) for v in (q1, q2, q3, q4, q5, q6)])
        if not out:
            assert error is not None
            raise error
        polished: list[Candidate] = []
        # (the seeds' branches are the solutions' but on a boundary: polish those that fit first)
        for group in ([q for q in out if fits(q)], [q for q in out if not fits(q)]):
            for seed in group:
                with model.lock:
                    q, err, _ = solve_dls(model.pin_model, model.pin_data, model.flange_frame, target, model.q_pin(seed))
                if err <= POLISH_TOLERANCE:
                    polished.append(model.q_gpl(q).tolist())
            if any(fits(q) for q in polished):
                break
        if not polished:
            raise GplException(INVALID_CARTESIAN, robot_num=self.robot, detail=f"{model.name}: no joint solution")
        return polished, error

    def _planar(self, P: np.ndarray) -> list[tuple[float, float]]:
        """(J2, J3) pairs that rotate P0 to P about the J3 then the J2 axis (both ∥ n)."""
        e1, e2 = self.e1, self.e2

        def flat(v: np.ndarray) -> complex:
            return complex(float(np.dot(v, e1)), float(np.dot(v, e2)))

        a, b, d, t = (flat(v) for v in (self.c[1], self.c[2], self.P0, P))
        L1, L2, L = abs(b - a), abs(d - b), abs(t - a)
        c = (L * L - L1 * L1 - L2 * L2) / (2.0 * L1 * L2)
        if c > 1.0 + 1e-9:
            raise self.too_far(f"{L * 1000:.3f} mm from the shoulder")
        if c < -1.0 - 1e-9:
            raise self.too_close(f"{L * 1000:.3f} mm from the shoulder")
        delta0 = math.atan2(((d - b) / (b - a)).imag, ((d - b) / (b - a)).real)
        out = []
        for turn in (math.acos(max(-1.0, min(1.0, c))), -math.acos(max(-1.0, min(1.0, c)))):
            gamma = turn - delta0  # J3's rotation of (d - b)
            m = (b - a) + (d - b) * complex(math.cos(gamma), math.sin(gamma))
            rot2 = math.atan2((t - a).imag, (t - a).real) - math.atan2(m.imag, m.real)
            out.append((rot2 / self.s[0], gamma / self.s[1]))
        return out


def _turn(axis: tuple[float, float, float], angle: float, v: Sequence[float]) -> tuple[float, float, float]:
    """``v`` turned by ``angle`` about the unit ``axis`` (Rodrigues), in Python floats."""
    c, s = math.cos(angle), math.sin(angle)
    kx, ky, kz = axis
    vx, vy, vz = v
    dot = (kx * vx + ky * vy + kz * vz) * (1.0 - c)
    return (vx * c + (ky * vz - kz * vy) * s + kx * dot, vy * c + (kz * vx - kx * vz) * s + ky * dot,
            vz * c + (kx * vy - ky * vx) * s + kz * dot)


def _meet(c1: np.ndarray, w1: np.ndarray, c2: np.ndarray, w2: np.ndarray) -> np.ndarray:
    """The point where two axes (point, unit direction) meet: the midpoint of their closest
    points; ``ValueError`` if they miss each other by more than 1 µm."""
    r = c2 - c1
    b = float(np.dot(w1, w2))
    den = 1.0 - b * b
    t1 = (float(np.dot(r, w1)) - b * float(np.dot(r, w2))) / den
    t2 = (b * float(np.dot(r, w1)) - float(np.dot(r, w2))) / den
    p1, p2 = c1 + t1 * w1, c2 + t2 * w2
    if np.linalg.norm(p1 - p2) > 1e-6:
        raise ValueError("wrist axes do not meet")
    return (p1 + p2) / 2.0


def _perpendicular(n: np.ndarray) -> np.ndarray:
    """A unit vector square to ``n``."""
    v = _cross(n, np.array((1.0, 0.0, 0.0) if abs(n[0]) < 0.9 else (0.0, 1.0, 0.0)))
    return v / np.linalg.norm(v)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``np.cross`` of two 3-vectors, written out (a tenth of its cost)."""
    return np.array((a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]))


def _rotation_angle(axis: np.ndarray, u: np.ndarray, v: np.ndarray) -> float:
    """The angle that turns ``u`` into ``v`` about ``axis`` (their parts square to it)."""
    u1 = u - np.dot(u, axis) * axis
    v1 = v - np.dot(v, axis) * axis
    return math.atan2(float(np.dot(axis, _cross(u1, v1))), float(np.dot(u1, v1)))


def _joint_axis(joint: pin.JointModel) -> np.ndarray:
    """The unit axis of a one-degree-of-freedom joint in its own frame."""
    name = joint.shortname()
    for suffix, axis in (("X", (1.0, 0.0, 0.0)), ("Y", (0.0, 1.0, 0.0)), ("Z", (0.0, 0.0, 1.0))):
        if name in (f"JointModelR{suffix}", f"JointModelP{suffix}"):
            return np.array(axis)
    return np.asarray(joint.extract().axis, dtype=float)


def modules() -> dict[int, Callable[[ParameterDatabase, int], RobotModel]]:
    """DataID 116 value → factory, for ``models.MODULES``."""
    return {module: UrdfModel for module in BY_MODULE}

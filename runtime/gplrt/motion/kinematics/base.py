"""``RobotModel``: the interface every kinematic module implements, plus shared PDb readers.

Interface (GPL units at this boundary: mm for linear axes and Cartesian XYZ, degrees for rotary
axes; poses are 4×4 homogeneous transforms with translation in mm):

* ``axis_count``, ``joint_names``, ``joints`` (``JointInfo``: name, kind, role, soft limits),
  ``lower_limits`` / ``upper_limits``, ``module`` (DataID 116 value), ``robot`` (robot number);
* ``tool`` / ``base``: 4×4 (mm), initialised from DataIDs 16051 / 16052 ("Tool/Base set at
  restart"); the motion layer may assign new matrices (``Robot.Tool = ...``); the stored arrays
  are read-only (their inverses are cached for ``inverse``), so assign, never edit in place;
* ``forward(joints) -> 4×4``: ``Base · Flange(q) · Tool`` (``Robot.Where``, gpl-classes §22.1.10);
* ``flange(joints) -> 4×4``: the flange pose without Base and Tool;
* ``inverse_pose(pose, config_bits=0, current_joints=None)``: the same for a pose tuple
  (``gplrt.geometry.transforms.Pose``: row-major rotation then translation in mm), the form a
  Location keeps; ``inverse`` converts its matrix to one and calls it, so the two agree to the bit;
* ``inverse(T, config_bits=0, current_joints=None) -> list[float]``: solves
  ``Flange(q) = Base⁻¹ · T · Tool⁻¹`` for the branch the bits ask for, unwinding multi-turn axes
  toward ``current_joints`` (axes that do not affect the pose — gripper, rail — keep their
  current values); raises GplException -1033 (orientation impossible for the robot), -1039 /
  -1040 (position too close / too far), -1012 (joint out of range, with ``Axis``), -1036
  (no kinematics for this robot type);
* ``config_of(joints) -> int``: the configuration bits of a joint vector (what ``Where`` reports);
* ``check_limits(joints)``: -1012 for the first axis outside its soft limits.

Internally everything is SI (m, rad) and conversions happen only in ``units.py``.  The forward
kinematics always goes through the Pinocchio model (``pin_model``), which is built from the
parameter database like a controller builds its kinematic module; closed-form solvers are used
for the inverse where the geometry allows.  ``forward`` and ``flange`` run on a copy of it in
millimetres with a frame at the tool tip (``units.model_in_mm``, ``_finish_pin_model``): they are
called for every ``Where`` and trace sample, and cost at most 3x the bare Pinocchio call
(``benchmarks/kinematics_speed.py``).
"""

from __future__ import annotations

import math
import threading
from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass
from enum import Enum
from typing import NoReturn

import numpy as np
import pinocchio as pin

from gplrt.controller.pdb import ParameterDatabase
from gplrt.geometry.transforms import Pose, matrix_to_pose, pose_mul, xyzypr_to_matrix
from gplrt.lang.errors import (
    INVALID_ARGUMENT,
    INVALID_AXIS_COUNT,
    JOINT_OUT_OF_RANGE,
    KINEMATICS_NOT_INSTALLED,
    GplException,
)
from gplrt.motion.kinematics import units
from gplrt.motion.kinematics.config import LIMIT_SLACK, TWO_PI, unwind
from gplrt.motion.kinematics.units import Matrix

#: FLT_MAX as written in .pac files: "no limit".
_FLT_MAX = 3.4e38
_FLOAT64 = np.dtype(np.float64)


class JointKind(Enum):
    LINEAR = "linear"  # mm
    ROTARY = "rotary"  # degrees


@dataclass(frozen=True)
class JointInfo:
    """One axis as GPL sees it: soft limits in mm or degrees (±inf when the PDb says FLT_MAX)."""

    name: str
    kind: JointKind
    role: str
    lower: float
    upper: float

    @property
    def linear(self) -> bool:
        return self.kind is JointKind.LINEAR


class RobotModel:
    """Base class; subclasses set up ``pin_model`` and implement ``_solve`` and ``_config``.

    A bare ``RobotModel`` (unknown kinematic module) still knows its axes and limits, so joint
    moves work, but every Cartesian operation raises -1036 (robot-models.md §3 step 1)."""

    #: index (GPL axis order) of the axis that ``GPL_Single`` restricts to ±180°, if any.
    single_axis: int | None = None

    def __init__(self, name: str, robot: int, module: int, joints: list[JointInfo],
                 tool: Matrix | None = None, base: Matrix | None = None) -> None:
        self.name = name
        self.robot = robot
        self.module = module
        self.joints = joints
        self.tool = np.eye(4) if tool is None else tool
        self.base = np.eye(4) if base is None else base
        self._linear = [j.linear for j in joints]
        self._lower_si = np.array([units.joint_to_si(j.lower, j.linear) for j in joints])
        self._upper_si = np.array([units.joint_to_si(j.upper, j.linear) for j in joints])
        #: The same limits with ``LIMIT_SLACK``, as Python floats (``_unwind``'s common case).
        self._slack_lower_si = [v - LIMIT_SLACK for v in self._lower_si.tolist()]
        self._slack_upper_si = [v + LIMIT_SLACK for v in self._upper_si.tolist()]
        self.pin_model: pin.Model | None = None
        self.pin_data: pin.Data | None = None
        self.flange_frame: int = -1
        self._tool_frame: int = -1  # the tool tip's frame (``_finish_pin_model``)
        #: Axes ``_pose`` accepts: none until the model has kinematics (``_refuse_joints`` says why).
        self._fk_axes = -1
        # pin q index of each GPL axis (GPL axis order differs from tree order, e.g. the rail).
        self._q_index: list[int] = []
        #: The soft limits in GPL units with the slack ``check_limits`` allows, per axis.
        self._joint_bounds = [
            (j.lower - LIMIT_SLACK * (units.MM_PER_M if j.linear else 180.0 / math.pi),
             j.upper + LIMIT_SLACK * (units.MM_PER_M if j.linear else 180.0 / math.pi)) for j in joints]
        # One pin.Data per model: GPL threads sharing a robot must not interleave computations in it.
        self.lock = threading.RLock()

    # -- Tool and Base ---------------------------------------------------------------------------
    #
    # ``inverse`` needs Base⁻¹ and Tool⁻¹ on every call (a straight line solves it dozens of times
    # per move): they are computed once when Tool/Base are assigned.  The stored matrices are made
    # read-only so that an in-place edit cannot leave a stale inverse behind (it raises instead).

    @property
    def tool(self) -> Matrix:
        return self._tool

    @tool.setter
    def tool(self, value: Matrix) -> None:
        tool, tool_inv, is_identity = _frozen_with_inverse(value)
        if getattr(self, "pin_model", None) is not None:
            with self._fk_lock:  # (a forward on another thread reads the tool frame)
                self._tool = tool
                self._fk_model.frames[self._tool_frame].placement = self._tool_placement_mm()
        self._tool, self._tool_inv, self._tool_is_identity = tool, tool_inv, is_identity
        self._tool_inv_pose = matrix_to_pose(self._tool_inv)
        #: Tool⁻¹'s translation when it has no rotation (``inverse_pose``'s shortcut), else None
        self._tool_inv_shift = (tuple(self._tool_inv_pose[9:])
                                if self._tool_inv_pose[:9] == (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0) else None)

    @property
    def base(self) -> Matrix:
        return self._base

    @base.setter
    def base(self, value: Matrix) -> None:
        self._base, self._base_inv, self._base_is_identity = _frozen_with_inverse(value)
        self._base_inv_pose = matrix_to_pose(self._base_inv)

    # -- description ----------------------------------------------------------------------------

    @property
    def axis_count(self) -> int:
        return len(self.joints)

    @property
    def joint_names(self) -> list[str]:
        return [j.name for j in self.joints]

    @property
    def lower_limits(self) -> list[float]:
        return [j.lower for j in self.joints]

    @property
    def upper_limits(self) -> list[float]:
        return [j.upper for j in self.joints]

    @property
    def has_kinematics(self) -> bool:
        return self.pin_model is not None

    def ready_joints(self) -> list[float]:
        """The posture assumed when no current joints are given: 0 clipped into each axis's limits."""
        return [min(max(0.0, j.lower), j.upper) for j in self.joints]

    # -- Pinocchio plumbing ---------------------------------------------------------------------

    def _finish_pin_model(self, model: pin.Model, gpl_joint_ids: Sequence[int], flange_frame: int) -> None:
        """Record the built model; ``gpl_joint_ids[i]`` is the pin joint id of GPL axis i.

        Also builds what ``forward`` and ``flange`` use: a copy of the model in millimetres
        (``units.model_in_mm``) with a frame at the tool tip (the flange frame times Tool, moved
        when Tool is assigned), so that ``Flange · Tool`` in mm comes straight out of Pinocchio,
        and the order and factors that turn a GPL joint vector into its configuration."""
        self.pin_model = model
        self.pin_data = model.createData()
        self.flange_frame = flange_frame
        self._q_index = [model.joints[jid].idx_q for jid in gpl_joint_ids]
        if model.nq != len(self._q_index) or sorted(self._q_index) != list(range(model.nq)):
            raise ValueError(f"{self.name}: every GPL axis must be one configuration value of the model")
        # The soft limits from the PDb (16077/16078), not any URDF's, bound the model (spec §3 step 4).
        model.lowerPositionLimit = self.q_pin(self._lower_si)
        model.upperPositionLimit = self.q_pin(self._upper_si)

        mm = self._fk_model = units.model_in_mm(model)
        flange = mm.frames[flange_frame]
        self._flange_placement_mm = flange.placement.copy()
        self._tool_frame = mm.addFrame(pin.Frame("tool", flange.parentJoint, self._tool_placement_mm(),
                                                 pin.FrameType.OP_FRAME))
        self._fk_data = mm.createData()
        self._fk_lock = threading.Lock()  # (its own pin.Data: forward never waits for an IK)
        # Pinocchio's configuration holds the GPL axes in tree order: position p is GPL axis order[p].
        order = sorted(range(len(self._q_index)), key=self._q_index.__getitem__)
        self._fk_configuration = units.configuration_of(self._linear, order)
        self._fk_axes = len(order)

    def _tool_placement_mm(self) -> pin.SE3:
        """The tool frame on the flange's joint: the flange's placement times Tool (mm)."""
        return self._flange_placement_mm * units.matrix_to_se3_mm(self._tool)

    def q_pin(self, q_gpl_si: Sequence[float]) -> np.ndarray:
        """GPL-ordered SI joint vector → Pinocchio configuration vector."""
        assert self.pin_model is not None
        q = np.zeros(self.pin_model.nq)
        q[self._q_index] = q_gpl_si
        return q

    def q_gpl(self, q_pin: np.ndarray) -> np.ndarray:
        """Pinocchio configuration vector → GPL-ordered SI joint vector."""
        return np.asarray(q_pin)[self._q_index]

    def flange_se3(self, q_gpl_si: Sequence[float]) -> pin.SE3:
        """Flange placement (SI) for a GPL-ordered SI joint vector, through Pinocchio."""
        if self.pin_model is None:
            raise GplException(KINEMATICS_NOT_INSTALLED, detail=f"{self.name}: robot type {self.module}")
        assert self.pin_data is not None
        with self.lock:
            pin.forwardKinematics(self.pin_model, self.pin_data, self.q_pin(q_gpl_si))
            return pin.updateFramePlacement(self.pin_model, self.pin_data, self.flange_frame).copy()

    # -- public GPL-unit API --------------------------------------------------------------------

    def _pose(self, joints: Sequence[float], frame: int) -> Matrix:
        """4×4 (mm) of ``frame`` of the millimetre model at ``joints`` (mm/deg), checked: -1036
        without kinematics, -202 for a wrong length or a value that is not finite.

        One list step, one ``np.array`` (``units.configuration_of``) and the two Pinocchio calls:
        ``forward`` runs for every ``Where`` and trace sample, and ``benchmarks/kinematics_speed.py``
        holds it to 3x the bare Pinocchio call (each further Python call costs a tenth of that)."""
        values = joints if type(joints) is list else joints.tolist() if type(joints) is np.ndarray else list(joints)
        if len(values) != self._fk_axes or not math.isfinite(sum(values)):  # (a finite sum: every value finite)
            self._refuse_joints(values)
        q = self._fk_configuration(values)
        model, data, lock = self._fk_model, self._fk_data, self._fk_lock
        lock.acquire()  # one pin.Data: GPL threads must not interleave in it
        try:
            pin.forwardKinematics(model, data, q)
            return pin.updateFramePlacement(model, data, frame).homogeneous  # type: ignore[no-any-return]
        finally:
            lock.release()

    def _refuse_joints(self, values: list[float]) -> NoReturn:
        """Why ``values`` cannot go through the kinematics (``_pose``): -1036, or -202."""
        if self.pin_model is None:
            raise GplException(KINEMATICS_NOT_INSTALLED, detail=f"{self.name}: robot type {self.module}")
        if len(values) != len(self._linear):
            raise GplException(INVALID_ARGUMENT, detail=f"{self.name} has {self.axis_count} axes, {len(values)} values given")
        raise GplException(INVALID_ARGUMENT, detail=f"joint values must be finite: {values}")

    def _to_si_list(self, joints: Sequence[float]) -> list[float]:
        """GPL joints (mm/deg) → SI (m/rad) as Python floats (the scalar solvers' form), checked:
        -202 for a wrong length or a value that is not finite."""
        values = joints if type(joints) is list else joints.tolist() if type(joints) is np.ndarray else list(joints)
        if len(values) != len(self._linear):
            raise GplException(INVALID_ARGUMENT, detail=f"{self.name} has {self.axis_count} axes, {len(values)} values given")
        if not math.isfinite(sum(values)):
            raise GplException(INVALID_ARGUMENT, detail=f"joint values must be finite: {values}")
        return units.joints_to_si_list(values, self._linear)

    def flange(self, joints: Sequence[float]) -> Matrix:
        """Flange pose (mm) of a joint vector (mm/deg), without Base and Tool."""
        return self._pose(joints, self.flange_frame)

    def forward(self, joints: Sequence[float]) -> Matrix:
        """``Base · Flange(joints) · Tool`` (mm): what ``Robot.Where`` reports.  The Tool is the
        tool frame's own placement in the millimetre model (``_finish_pin_model``)."""
        if self._base_is_identity:
            return self._pose(joints, self._tool_frame)
        return self._base @ self._pose(joints, self._tool_frame)

    def inverse(self, T: Matrix, config_bits: int = 0, current_joints: Sequence[float] | None = None,
                check: bool = True) -> list[float]:
        """Joints (mm/deg) that put ``Base · Flange · Tool`` at ``T`` (4×4, mm); see module docstring.

        ``check=False`` skips the final soft-limit check (-1012): for reading a planned path
        between the samples its limits were checked at."""
        if type(T) is np.ndarray and T.shape == (4, 4) and T.dtype is _FLOAT64 and type(current_joints) is list:
            # the usual call, straight to the model's closed form (``matrix_to_pose``'s first case)
            (r11, r12, r13, x), (r21, r22, r23, y), (r31, r32, r33, z), _ = T.tolist()
            pose = (r11, r12, r13, r21, r22, r23, r31, r32, r33, x, y, z)
            if math.isfinite(sum(pose)):  # (else the general steps' -202)
                q = self._plain_inverse(pose, config_bits, current_joints, check)
                if q is not None:
                    return q
        pose = matrix_to_pose(T)  # -202 for what is not a numeric matrix
        if (T.shape if type(T) is np.ndarray else np.shape(T)) != (4, 4):
            raise GplException(INVALID_ARGUMENT, detail="target must be a finite 4x4 homogeneous transform")
        # (``inverse_pose`` refuses a pose that is not finite, -202)
        return self.inverse_pose(pose, config_bits, current_joints, check)

    def inverse_pose(self, pose: Pose, config_bits: int = 0, current_joints: Sequence[float] | None = None,
                     check: bool = True) -> list[float]:
        """``inverse`` of a pose tuple (translation in mm), in Python floats throughout.

        Why a second entry point: a Location is a pose tuple, and a straight ``Move.Loc`` solves
        its destination when it is queued — on the hot path ``benchmarks/motion_speed.py`` times.
        Converting to a matrix and back costs more than a closed-form solution itself.

        The model's ``_plain_inverse`` answers first; what it leaves (None) takes the general
        steps, which check everything and raise the controller's codes."""
        if current_joints is None:
            current: list[float] = self.ready_joints()
        else:
            current = (current_joints if type(current_joints) is list else current_joints.tolist()
                       if type(current_joints) is np.ndarray else list(current_joints))
        q = self._plain_inverse(pose, config_bits, current, check) if math.isfinite(sum(pose)) else None
        return q if q is not None else self._general_inverse(pose, config_bits, current, check)

    def _plain_inverse(self, pose: Pose, bits: int, current: list[float], check: bool) -> list[float] | None:
        """The model's closed form for the case nearly every call is, in one method, or None for
        the general steps (``_general_inverse``).  Its answer must be theirs, to the bit.  ``pose``
        is finite (the callers check: the general steps refuse the rest with -202).

        Why: ``inverse`` runs for every Cartesian ``Move`` and every cycle of a straight line, and
        the general steps' calls cost more than a closed-form solution (``benchmarks/
        kinematics_speed.py`` holds the wrappers to 3x the bare closed form).  Models without a
        closed form (the articulated arm's numeric refinement) keep this default."""
        return None

    def _general_inverse(self, pose: Pose, config_bits: int, current: list[float], check: bool) -> list[float]:
        """``inverse_pose`` step by step: the checks (-1036, -202), Base and Tool, the model's
        ``_solve_pose`` in SI, the soft limits (-1012)."""
        if self.pin_model is None:
            raise GplException(KINEMATICS_NOT_INSTALLED, detail=f"{self.name}: robot type {self.module}")
        if not math.isfinite(sum(pose)):
            raise GplException(INVALID_ARGUMENT, detail="target must be a finite homogeneous transform")
        if not self._base_is_identity:
            pose = pose_mul(self._base_inv_pose, pose)
        if not self._tool_is_identity:
            shift = self._tool_inv_shift
            if shift is None:
                pose = pose_mul(pose, self._tool_inv_pose)
            else:  # ``pose_mul`` by a pure translation (the usual gripper offset), term for term
                r11, r12, r13, r21, r22, r23, r31, r32, r33, x, y, z = pose
                tx, ty, tz = shift
                pose = (r11, r12, r13, r21, r22, r23, r31, r32, r33, r11 * tx + r12 * ty + r13 * tz + x,
                        r21 * tx + r22 * ty + r23 * tz + y, r31 * tx + r32 * ty + r33 * tz + z)
        mm = units.MM_PER_M
        q = self._solve_pose(pose[:9], (pose[9] / mm, pose[10] / mm, pose[11] / mm), int(config_bits),
                             self._to_si_list(current))
        joints = units.q_to_joints(q, self._linear)
        if check:
            self.check_limits(joints)
        return joints

    def inverse_path(self, Ts: np.ndarray, seeds: np.ndarray) -> np.ndarray | None:
        """Joints (N×n, mm/deg) for poses sampled along a continuous path (N×4×4, mm), all in one
        pass: pose k is solved with Config 0 as ``inverse(Ts[k], 0, current)`` would, where
        ``current`` is solution k − 1 (``seeds[0]`` for the first) with the axes the IK does not
        solve (rail, grippers) taken from ``seeds[k]``.

        None means "solve pose by pose": the default for models without a batch solver, and what
        a batch solver returns when any sample leaves the plain case (a soft limit, an unreachable
        pose, an ambiguous turn or branch), so that ``inverse`` raises the proper code."""
        return None

    def _limits_hold(self, q_si: np.ndarray) -> bool:
        """Every row of ``q_si`` (N×n, SI) inside the soft limits (with ``LIMIT_SLACK``)."""
        return bool((q_si >= self._lower_si - LIMIT_SLACK).all() and (q_si <= self._upper_si + LIMIT_SLACK).all())

    def _targets(self, Ts: np.ndarray) -> np.ndarray:
        """``Base⁻¹ · T · Tool⁻¹`` of every pose (N×4×4, mm): the flange targets."""
        out = Ts if self._base_is_identity else self._base_inv @ Ts
        return out if self._tool_is_identity else out @ self._tool_inv

    def config_of(self, joints: Sequence[float]) -> int:
        """Configuration bits of a joint vector (mm/deg)."""
        if self.pin_model is None:
            return 0
        return self._config(self._to_si_list(joints))  # (Python floats: ``_config`` does scalar math)

    def check_limits(self, joints: Sequence[float]) -> None:
        """-1012 *Joint out-of-range* (with ``Axis``) for the first axis outside its soft limits."""
        bounds = self._joint_bounds
        if len(joints) == len(bounds):
            for v, (lo, hi) in zip(joints, bounds):
                if not lo <= v <= hi:
                    break
            else:
                return
        for i, (value, info) in enumerate(zip(joints, self.joints, strict=True)):
            slack = LIMIT_SLACK * (units.MM_PER_M if info.linear else 180.0 / math.pi)
            if not info.lower - slack <= value <= info.upper + slack:
                raise GplException(JOINT_OUT_OF_RANGE, robot_num=self.robot, axis=i + 1,
                                   detail=f"{info.name} = {value:.6g} outside [{info.lower:g}, {info.upper:g}]")

    # -- for subclasses -------------------------------------------------------------------------

    def _solve_pose(self, rotation: Sequence[float], position: Sequence[float], bits: int,
                    current: list[float]) -> Sequence[float]:
        """Flange target (row-major rotation, position in m) → GPL-ordered SI joints.

        Closed-form solvers override this on Python floats; the default hands a ``pin.SE3`` to
        ``_solve`` (the numeric solver of the articulated arm needs one anyway)."""
        target = pin.SE3(np.array(rotation, dtype=float).reshape(3, 3), np.array(position, dtype=float))
        return self._solve(target, bits, np.array(current))

    def _solve(self, target: pin.SE3, bits: int, current: np.ndarray) -> np.ndarray:
        """Flange target (SI) → GPL-ordered SI joints."""
        raise GplException(KINEMATICS_NOT_INSTALLED, detail=f"{self.name}: robot type {self.module}")

    def _config(self, q: Sequence[float]) -> int:
        return 0

    def _unwind(self, i: int, angle: float, current: np.ndarray, single: bool = False) -> float:
        """Choose the turn of rotary axis ``i``: (−π, π] under ``GPL_Single`` for the single axis,
        otherwise nearest the current value within limits."""
        if single and i == self.single_axis:
            return unwind(angle, 0.0, -math.pi + 1e-15, math.pi)
        now = float(current[i])
        # ``unwind``'s first case inline (the turn strictly nearest ``now``, inside the limits):
        # almost every call ends here, and this runs several times per IK.
        near = angle + round((now - angle) / TWO_PI) * TWO_PI
        if abs(near - now) < math.pi and self._slack_lower_si[i] <= near <= self._slack_upper_si[i]:
            return near
        return unwind(angle, now, float(self._lower_si[i]), float(self._upper_si[i]))


def _frozen_with_inverse(value: Matrix) -> tuple[Matrix, Matrix, bool]:
    """A read-only copy of a 4×4 transform, its inverse, and whether it is the identity."""
    m = np.array(value, dtype=float)
    if m.shape != (4, 4):
        raise GplException(INVALID_ARGUMENT, detail="Tool/Base must be a 4x4 homogeneous transform")
    inv = np.linalg.inv(m)
    m.flags.writeable = False
    inv.flags.writeable = False
    return m, inv, bool(np.array_equal(m, np.eye(4)))


# -- reading the parameter database -------------------------------------------------------------


def robot_name(pdb: ParameterDatabase, robot: int) -> str:
    """The robot's model name (DataID 2002), ``Robot <n>`` when the database has none."""
    return pdb.get_str(2002, robot) if pdb.has(2002, robot) else f"Robot {robot}"


def read_joints(pdb: ParameterDatabase, robot: int, roles: Sequence[str], names: Mapping[str, str],
                linear: Collection[str]) -> tuple[str, list[JointInfo]]:
    """The robot's name and one ``JointInfo`` per role (its name from ``names``, linear when the role
    is in ``linear``, soft limits from the database), after the axis-count check: the part of
    building a model that every kinematic module shares."""
    name = robot_name(pdb, robot)
    check_axis_count(pdb, robot, roles, name)
    lower, upper = read_limits(pdb, robot, len(roles))
    joints = [JointInfo(names[r], JointKind.LINEAR if r in linear else JointKind.ROTARY, r, lo, hi)
              for r, lo, hi in zip(roles, lower, upper, strict=True)]
    return name, joints


def read_limits(pdb: ParameterDatabase, robot: int, n: int) -> tuple[list[float], list[float]]:
    """Soft limits 16078 (min) / 16077 (max), FLT_MAX → ±inf; missing entries are unlimited."""

    def one(data_id: int, i: int, default: float) -> float:
        v = pdb.get_num(data_id, robot, 1, i + 1, default=default)
        return math.copysign(math.inf, v) if abs(v) >= _FLT_MAX else v

    return [one(16078, i, -math.inf) for i in range(n)], [one(16077, i, math.inf) for i in range(n)]


def read_transform(pdb: ParameterDatabase, data_id: int, robot: int) -> Matrix:
    """Tool (16051) or Base (16052) at restart: (x, y, z, yaw, pitch, roll) → 4×4 (mm); identity if absent."""
    if not pdb.has(data_id, robot):
        return np.eye(4)
    vals = (pdb.get_nums(data_id, robot) + [0.0] * 6)[:6]
    return xyzypr_to_matrix(*vals)


def axis_roles(mask: int, required: Sequence[str], optional: Sequence[tuple[int, str]]) -> list[str]:
    """Axis roles in GPL order from the axis mask (DataID 2003): the required axes first, then
    the optional ones whose bit is set, numbered consecutively (robot-models.md §4.1)."""
    return [*required, *(role for bit, role in optional if mask & bit)]


def check_axis_count(pdb: ParameterDatabase, robot: int, roles: Sequence[str], name: str) -> None:
    """DataID 2000 (Number of axes) must agree with the axes the mask implies (-1516 otherwise)."""
    n = int(pdb.get_num(2000, robot))
    if n != len(roles):
        raise GplException(INVALID_AXIS_COUNT, detail=f"{name}: 2000 = {n} axes but the axis mask gives {roles}")

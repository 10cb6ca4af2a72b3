"""``build_model(pdb, robot)``: pick and build the kinematic module a robot's PDb asks for.

Like a controller at power-up (robot-models.md §3): DataID 116 (Robot types, one entry per robot)
selects the kinematic module, which then reads its axes, dimensions, limits, Tool and Base from
the robot's own DataIDs.  Modules implemented:

| 116 | module | class |
|---|---|---|
| 2 | XYZTheta (gantry, PrecisePlace style) | ``GantryModel`` |
| 12 | PreciseFlex 400 family (PF400, PF3400) | ``Pf400Model`` |
| 22 | six-axis articulated arm (our ARM6 geometry) | ``Articulated6Model`` |
| 9001-9006 | a robot from its URDF (Viper s650, Cobra s600, TM5-700/900, TM12, TM14; ours) | ``UrdfModel`` |

Any other value gives a bare ``RobotModel`` that knows its axes and soft limits (joint moves
work) but raises -1036 *Kinematics not installed* on every Cartesian operation (§3 step 1).
A robot number that is not configured raises -1001 *Undefined robot*.
"""

from __future__ import annotations

from collections.abc import Callable

from gplrt.controller.pdb import ParameterDatabase, default_database
from gplrt.lang.errors import UNDEFINED_ROBOT, GplException
from gplrt.motion.kinematics.articulated import MODULE_ARTICULATED6, Articulated6Model
from gplrt.motion.kinematics.base import JointInfo, JointKind, RobotModel, read_limits, read_transform, robot_name
from gplrt.motion.kinematics.gantry import MODULE_XYZTHETA, GantryModel
from gplrt.motion.kinematics.pf400 import MODULE_PF400, Pf400Model
from gplrt.motion.kinematics.urdf import modules as urdf_modules


MODULES: dict[int, Callable[[ParameterDatabase, int], RobotModel]] = {
    MODULE_XYZTHETA: GantryModel,
    MODULE_PF400: Pf400Model,
    MODULE_ARTICULATED6: Articulated6Model,
    **urdf_modules(),
}


def robot_model(name: str, robot: int = 1) -> RobotModel:
    """The kinematic model of catalogue robot ``name`` (``--robot``'s names: ``VIPER-S650``,
    ``TM5-900``, ``PF400SX`` ...), built from its shipped parameter database: the one call a
    language layer needs for forward and inverse kinematics outside a running controller."""
    return build_model(default_database(name), robot)


def robot_type(pdb: ParameterDatabase, robot: int = 1) -> int:
    """The kinematic module number of ``robot`` (DataID 116 element ``robot``; 0 if absent)."""
    return int(pdb.get_num(116, 1, 1, robot, default=0.0))


def build_model(pdb: ParameterDatabase, robot: int = 1) -> RobotModel:
    """The ``RobotModel`` for robot number ``robot`` of a parameter database."""
    if not pdb.has(2000, robot):
        raise GplException(UNDEFINED_ROBOT, detail=f"robot {robot} is not in the parameter database")
    module = robot_type(pdb, robot)
    factory = MODULES.get(module)
    if factory is not None:
        return factory(pdb, robot)
    n = int(pdb.get_num(2000, robot))
    lower, upper = read_limits(pdb, robot, n)
    joints = [JointInfo(f"J{i + 1}", JointKind.LINEAR, f"j{i + 1}", lo, hi)
              for i, (lo, hi) in enumerate(zip(lower, upper, strict=True))]
    return RobotModel(robot_name(pdb, robot), robot, module, joints, read_transform(pdb, 16051, robot), read_transform(pdb, 16052, robot))

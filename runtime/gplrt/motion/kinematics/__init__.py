"""Robot kinematics built from the parameter database, on Pinocchio.

Public API (GPL units: mm / degrees; poses are 4×4 matrices in mm):

* ``build_model(pdb, robot=1) -> RobotModel`` — the kinematic module DataID 116 selects;
* ``robot_model(name) -> RobotModel`` — the same for a catalogue name (``VIPER-S650``, ``TM12``...);
* ``RobotModel``: ``axis_count``, ``joint_names``, ``joints``, ``lower_limits``, ``upper_limits``,
  ``tool``, ``base``, ``forward(joints)``, ``flange(joints)``,
  ``inverse(T, config_bits=0, current_joints=None)``, ``config_of(joints)``, ``check_limits(joints)``;
* configuration bits ``GPL_RIGHTY`` … ``GPL_SINGLE``.

See base.py for the interface contract and pf400.py / gantry.py / articulated.py / urdf.py for
each module's geometry and Config rules (docs/design/robots.md for the URDF robots).
"""

from gplrt.motion.kinematics.articulated import Articulated6Model, solve_dls
from gplrt.motion.kinematics.base import JointInfo, JointKind, RobotModel
from gplrt.motion.kinematics.config import (
    GPL_ABOVE,
    GPL_BELOW,
    GPL_FLIP,
    GPL_LEFTY,
    GPL_NOFLIP,
    GPL_RIGHTY,
    GPL_SINGLE,
)
from gplrt.motion.kinematics.gantry import GantryModel
from gplrt.motion.kinematics.models import MODULES, build_model, robot_model, robot_type
from gplrt.motion.kinematics.pf400 import Pf400Model
from gplrt.motion.kinematics.urdf import UrdfModel

__all__ = [
    "GPL_ABOVE", "GPL_BELOW", "GPL_FLIP", "GPL_LEFTY", "GPL_NOFLIP", "GPL_RIGHTY", "GPL_SINGLE",
    "MODULES", "Articulated6Model", "GantryModel", "JointInfo", "JointKind", "Pf400Model", "RobotModel",
    "UrdfModel", "build_model", "robot_model", "robot_type", "solve_dls",
]

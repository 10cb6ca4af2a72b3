"""Geometry: homogeneous transforms with GPL's ZYZ Euler angles, Location and RefFrame.

Public API:
  transforms: ``xyzypr_to_matrix``, ``matrix_to_xyzypr`` (numpy (4, 4), mm and degrees)
  ``Location``, ``RefFrame`` (GPL classes), ``Conveyor`` + ``register_conveyor`` (belt model the
  simulation drives), ``KinematicsProvider`` + ``set_kinematics_provider`` (robot hook for
  Location.KineSol / Location.Here).
"""

from gplrt.geometry.kinematics_provider import KinematicsProvider, set_kinematics_provider
from gplrt.geometry.location import Location
from gplrt.geometry.refframe import Conveyor, RefFrame, get_conveyor, register_conveyor
from gplrt.geometry.transforms import matrix_to_xyzypr, xyzypr_to_matrix

__all__ = [
    "Conveyor",
    "KinematicsProvider",
    "Location",
    "RefFrame",
    "get_conveyor",
    "matrix_to_xyzypr",
    "register_conveyor",
    "set_kinematics_provider",
    "xyzypr_to_matrix",
]

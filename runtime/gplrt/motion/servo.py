"""What the servos of a simulated robot feel: the servo gripper's fingers against a plate or their
stop, the torques the controller reports (DataIDs 12304/12331), and the gripper's end-of-travel
input.

There is no servo loop in the simulation: the motion queue says where every axis is *commanded*
to be (``RobotState.queue``), and this module says where an axis actually is and what torque the
servo puts out, read off that command whenever a program asks.  Only the servo gripper of a
PF400 (the joint whose role is ``gripper``, joint 5 on a PF400SX) meets anything:

* **The fingers' closed stop** is ``CLOSED_STOP_MARGIN`` (4 mm) above the joint's minimum soft
  limit (DataID 16078; 69 mm on a PF400SX, so 73 mm): the soft limit lies beyond the mechanical
  stop, which is what PARobot.gpl:2640-2642 says when it adds 4 mm to the minimum soft stop "to
  keep setpoint within the actual lower hardstop".
* **A plate**: ``ServoGripper.plate_width`` (mm; None = nothing between the fingers, the
  default) is the width of the plate the fingers find whenever they close on it: a closing
  command narrower than the plate leaves the fingers on the plate.  A ``--setup`` file or a
  notebook sets it (``gripper_of(sim).plate_width = 80``), and may change it at any time (an I/O
  rule's ``call``), e.g. to None once a plate has been put down for good.
* **Where the fingers are** (``Robot.WhereAngles``) is the command held back by the plate or the
  stop; ``Robot.DestAngles`` is the command itself, as on the controller (PARobot's ReleasePlate
  compares the two).
* **Torque** (torque counts, tcnt: ±32768 is the amplifier's peak current): the PID output is
  ``Kp·e + I`` (``e`` the position error in encoder counts: mm × the joint-to-motor scale 2300;
  ``Kp`` DataID 10331; the integrator ``I`` wound up to its limit 10334 once the fingers are held
  back — the steady state the controller reaches within a few servo periods), clipped to the PID
  torque limits 10351 (positive) / 10352 (negative), 0 meaning "no limit" (the amplifier's
  ±32767).  The feedforward (12331) is the spring compensation 10342 × (10344 + 10345 × the
  command in encoder counts); the output (12304) is feedforward + PID.  With power off every
  torque is 0; other axes report their feedforward 0 and PID 0 (the simulated arm follows its
  command exactly).  So a gripper that closes on a plate with a force limit reads exactly that
  limit, which is what GraspPlate tests, and one that closes on nothing reads 0.
* **End-of-travel input** (``EOT_INPUT``, digital input 210002 on a PF400: the gripper's servo
  node's input 2) is on while the fingers are within 2 mm of their closed stop; reading it is a
  read of ``Signal.DIO`` like any input (``gplrt.controller.signals`` asks this module).

Axes in torque mode (``gplrt.motion.special``) report their commanded torque as PID output.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from gplrt.controller.pdb import ParameterDatabase
from gplrt.controller.signals import add_input_provider
from gplrt.controller.state import POWER_ON_STATES
from gplrt.motion.kinematics import RobotModel

if TYPE_CHECKING:
    from gplrt.motion.robot import RobotState
    from gplrt.session import Session

#: mm between the gripper's minimum soft limit and its mechanical closed stop (module docstring).
CLOSED_STOP_MARGIN = 4.0
#: mm from the closed stop within which the end-of-travel sensor is on.
EOT_RANGE = 2.0
#: The end-of-travel input of robot 1's gripper (node 2, input 2) on a PF400.
EOT_INPUT = 210002
#: Torque counts of the amplifier's peak current.
PEAK_TCNT = 32767.0

_KP, _MAX_INTEGRATOR = 10331, 10334
_POSFF_GAIN, _POSADJ_COEF0, _POSADJ_COEF1 = 10342, 10344, 10345
_MAX_POS_PID, _MAX_NEG_PID = 10351, 10352
_JOINT_TO_MOTOR = 2300


@dataclass
class ServoGripper:
    """The servo gripper of one robot (module docstring)."""

    axis: int  # 0-based index of the gripper joint
    closed_stop: float  # mm
    plate_width: float | None = None

    def actual(self, commanded: float) -> float:
        """Where the fingers are when commanded to ``commanded`` (mm)."""
        floor = self.closed_stop if self.plate_width is None else max(self.closed_stop, float(self.plate_width))
        return commanded if commanded >= floor else floor

    def fully_closed(self, position: float) -> bool:
        return position <= self.closed_stop + EOT_RANGE


def gripper_of(sim: Session, robot: int = 1) -> ServoGripper | None:
    """Robot ``robot``'s servo gripper (None when it has none): where a setup sets ``plate_width``."""
    return sim.robot(int(robot)).gripper


def make_gripper(model: RobotModel) -> ServoGripper | None:
    """The servo gripper of a robot model: its joint whose role is ``gripper``, if any."""
    for i, joint in enumerate(model.joints):
        if joint.role == "gripper":
            return ServoGripper(i, float(joint.lower) + CLOSED_STOP_MARGIN)
    return None


def joint_to_motor_scale(pdb: ParameterDatabase, robot: int, axis_count: int) -> list[float]:
    """Motor counts per mm or degree of each joint (DataID 2300, robot-models.md §2.6): element 1
    is J1, elements 2-10 a 3×3 matrix for J2-J4 whose diagonal (2, 6, 10) applies here, 11 J5,
    12 J6; a robot with fewer values (the XYZTheta layout) has one per axis."""
    values = pdb.get_nums(_JOINT_TO_MOTOR, robot) if pdb.has(_JOINT_TO_MOTOR, robot) else []
    if len(values) >= 11:
        picks = [0, 1, 5, 9, 10, 11]
        scale = [values[i] if i < len(values) else 0.0 for i in picks]
    else:
        scale = list(values)
    scale += [0.0] * (axis_count - len(scale))
    return scale[:axis_count]


def _num(pdb: ParameterDatabase, data_id: int, robot: int, axis: int) -> float:
    return float(pdb.get_num(data_id, robot, 1, axis + 1, default=0.0))


def axis_torques(s: Session, robot: RobotState, t: float) -> tuple[list[float], list[float]]:
    """(PID output, feedforward) in torque counts for every axis of ``robot`` of session ``s`` at
    time ``t``."""
    n = robot.axis_count
    pid, ff = [0.0] * n, [0.0] * n
    if s.controller.power_state not in POWER_ON_STATES:
        return pid, ff
    for axis, torque in robot.commanded_torques().items():
        pid[axis] = torque
    gripper = robot.gripper
    if gripper is None or gripper.axis in robot.commanded_torques():
        return pid, ff
    pdb = s.database()
    i = gripper.axis
    commanded = float(robot.queue.joints_at(t)[i])
    scale = robot.motor_scale[i]
    error = (commanded - gripper.actual(commanded)) * scale  # encoder counts; <= 0 (held back)
    out = _num(pdb, _KP, robot.number, i) * error
    if error:
        out += float(np.sign(error)) * _num(pdb, _MAX_INTEGRATOR, robot.number, i)
    high = _num(pdb, _MAX_POS_PID, robot.number, i) or PEAK_TCNT
    low = _num(pdb, _MAX_NEG_PID, robot.number, i) or -PEAK_TCNT
    pid[i] = min(max(out, low), high)
    gain = _num(pdb, _POSFF_GAIN, robot.number, i)
    ff[i] = gain * (_num(pdb, _POSADJ_COEF0, robot.number, i) + _num(pdb, _POSADJ_COEF1, robot.number, i)
                    * commanded * scale)
    return pid, ff


def eot_input(sim: Session, signal: int) -> bool | None:
    """The end-of-travel input ``signal`` of a robot's gripper (on while the fingers are fully
    closed), or None when ``signal`` is not such an input."""
    if signal != EOT_INPUT:
        return None
    robot = sim.robot(1)
    gripper = robot.gripper
    if gripper is None:
        return None
    return gripper.fully_closed(float(robot.joints_at(sim.now())[gripper.axis]))


add_input_provider(eot_input)

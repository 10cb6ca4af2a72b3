"""Robots described by a URDF: the catalogue by name, the URDF's joints, and their PDb layer.

The Adept and Techman arms (``VIPER-S650``, ``COBRA-S600``, ``TM5-700`` … ``TM14``) come with no
``.pac`` backup: their geometry and limits are a URDF (``data/robots/urdf/``, provenance and
licences in ``data/robots/README.md``).  The simulated controller still reads every robot from a
parameter database (axis count, soft limits, speeds, the kinematic module in DataID 116), so for
these robots the database is *derived from the URDF* when it is loaded (``pdb_layers``): the URDF
stays the one truth for positions and speeds, and the rest of the runtime (motion limits, the
registry, ``Controller.PDb``) sees a robot like any other.  ``gplrt.motion.kinematics.urdf`` builds
the Pinocchio model and the inverse kinematics from the same file.

This module reads the URDF with ``xml.etree`` only (no Pinocchio): ``gpl2py run --help`` lists the
model names, and must not pay for importing the kinematics.  The files are ours (shipped in the
package, chosen by catalogue name), never user input.

Decisions (docs/design/robots.md):

* **Joint order** is the chain from the root to the flange link; a joint with ``<mimic>`` is not
  an axis (the Cobra's ``flyover_cable_joint`` follows ``inner_joint``).
* **Units**: revolute joints in degrees, prismatic in mm, as every GPL robot.
* **Acceleration**: the URDFs give none, and neither manual gives per-joint values.  Each joint's
  100 % acceleration (DataID 2702) is its URDF velocity limit reached in ``ACCEL_TIME`` = 0.2 s —
  the "time to top speed" of the TMscript manual's motion examples (tmscript-language.md L2469:
  ``PTP("JPP", targetP1, 10, 200, …)``, 200 ms) — and the jerk ramp (2712/2713) is ``RAMP_TIME``.
* **Cartesian speed** (2701/2703): ``CARTESIAN_SPEED`` mm/s and deg/s at 100 %, reached in the same
  0.2 s (ours: no manual value for these arms in the seeds).
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from functools import cache
from pathlib import Path

#: The shipped URDFs (``gplrt.controller.pdb.DATA_DIR / "urdf"``; pdb imports this module, not
#: the other way round).
URDF_DIR = Path(__file__).resolve().parent.parent / "data" / "robots" / "urdf"
#: Seconds from standstill to a joint's top speed at 100 % Accel (module docstring).
ACCEL_TIME = 0.2
#: Accel/decel ramp time (s): jerk = acceleration / RAMP_TIME.
RAMP_TIME = 0.05
#: FLT_MAX, what a .pac file writes for "no limit" (a continuous joint).
_FLT_MAX = 3.402823e38
#: 100 % Cartesian speed: (linear mm/s, rotation deg/s).
CARTESIAN_SPEED = (1000.0, 360.0)

#: Solver families (``gplrt.motion.kinematics.urdf``): closed forms where the geometry allows.
SPHERICAL_WRIST = "spherical-wrist"  # 6R, J1 vertical, J2 ∥ J3, J4-J5-J6 meeting in one point
SCARA = "scara"  # two parallel vertical revolutes, a vertical quill, a roll about it
OFFSET_WRIST = "offset-wrist"  # 6R, J2 ∥ J3 ∥ J4, J5 and J6 offset (a UR-like wrist)


@dataclass(frozen=True)
class UrdfRobot:
    """One catalogue entry: what the URDF does not say about the robot."""

    name: str  # the --robot name
    title: str  # DataID 2002 (Robot name)
    file: str  # under data/robots/urdf/
    module: int  # DataID 116: the kinematic module (ours, 9001-9099: not a Brooks number)
    flange: str  # the URDF frame (link) that is the tool flange: Tool = identity puts the TCP here
    solver: str  # SPHERICAL_WRIST, SCARA or OFFSET_WRIST

    @property
    def path(self) -> Path:
        return URDF_DIR / self.file


#: The catalogue.  The flange is the URDF's own flange frame: ``tool0`` for the Adept arms (the
#: Viper's ``tool0`` has two ``<origin>`` elements; URDF parsers, Pinocchio's included, read the
#: first, the identity, so it is ``link_6`` with z out of the flange), ``flange`` for the TMs.
URDF_ROBOTS: dict[str, UrdfRobot] = {r.name: r for r in (
    UrdfRobot("VIPER-S650", "Adept Viper s650", "adept_viper_s650.urdf", 9001, "tool0", SPHERICAL_WRIST),
    UrdfRobot("COBRA-S600", "Adept Cobra s600", "adept_cobra_s600.urdf", 9002, "tool0", SCARA),
    UrdfRobot("TM5-700", "Techman TM5-700", "tm5-700-nominal.urdf", 9003, "flange", OFFSET_WRIST),
    UrdfRobot("TM5-900", "Techman TM5-900", "tm5-900-nominal.urdf", 9004, "flange", OFFSET_WRIST),
    UrdfRobot("TM12", "Techman TM12", "tm12-nominal.urdf", 9005, "flange", OFFSET_WRIST),
    UrdfRobot("TM14", "Techman TM14", "tm14-nominal.urdf", 9006, "flange", OFFSET_WRIST),
)}
#: DataID 116 value → catalogue entry (the kinematic module factory looks robots up by it).
BY_MODULE: dict[int, UrdfRobot] = {r.module: r for r in URDF_ROBOTS.values()}


@dataclass(frozen=True)
class UrdfJoint:
    """One movable URDF joint, in SI as the file has it (rad or m, rad/s or m/s)."""

    name: str
    kind: str  # "revolute", "continuous" or "prismatic"
    parent: str
    child: str
    lower: float
    upper: float
    velocity: float
    mimic: tuple[str, float, float] | None  # (joint it follows, multiplier, offset)

    @property
    def linear(self) -> bool:
        return self.kind == "prismatic"

    def to_units(self, value: float) -> float:
        """SI → GPL units: mm for a prismatic joint, degrees for a revolute one."""
        return value * 1000.0 if self.linear else math.degrees(value)


@dataclass(frozen=True)
class UrdfChain:
    """The axes of a URDF robot in GPL order, and its mimic joints."""

    axes: tuple[UrdfJoint, ...]
    mimics: tuple[UrdfJoint, ...]


@cache
def read_chain(path: Path, flange: str) -> UrdfChain:
    """The movable joints from the root link to ``flange`` (GPL axis order), and the ``<mimic>``
    joints anywhere in the file.  A ``ValueError`` for a file that is not such a chain."""
    root = ET.parse(path).getroot()
    joints: dict[str, UrdfJoint] = {}
    by_child: dict[str, ET.Element] = {}
    for el in root.findall("joint"):
        by_child[_attr(el, "child", "link")] = el
        kind = el.get("type", "")
        if kind in ("revolute", "continuous", "prismatic"):
            joints[el.get("name", "")] = _joint(el, kind)
    chain: list[UrdfJoint] = []
    link = flange
    while link in by_child:
        el = by_child[link]
        found = joints.get(el.get("name", ""))
        if found is not None:
            if found.mimic is not None:
                raise ValueError(f"{path.name}: mimic joint {found.name} on the flange's chain")
            chain.append(found)
        link = _attr(el, "parent", "link")
    if not chain:
        raise ValueError(f"{path.name}: no movable joint between the root and {flange!r}")
    return UrdfChain(tuple(reversed(chain)), tuple(j for j in joints.values() if j.mimic is not None))


def _attr(el: ET.Element, child: str, name: str) -> str:
    sub = el.find(child)
    if sub is None or sub.get(name) is None:
        raise ValueError(f"URDF joint {el.get('name')!r} has no <{child} {name}=...>")
    return str(sub.get(name))


def _joint(el: ET.Element, kind: str) -> UrdfJoint:
    lim = el.find("limit")
    lower = float(lim.get("lower", "-inf")) if lim is not None and kind != "continuous" else -math.inf
    upper = float(lim.get("upper", "inf")) if lim is not None and kind != "continuous" else math.inf
    velocity = float(lim.get("velocity", "0")) if lim is not None else 0.0
    if not velocity > 0.0:
        raise ValueError(f"URDF joint {el.get('name')!r} has no velocity limit")
    m = el.find("mimic")
    mimic = None if m is None else (str(m.get("joint")), float(m.get("multiplier", "1")),
                                     float(m.get("offset", "0")))
    return UrdfJoint(str(el.get("name")), kind, _attr(el, "parent", "link"), _attr(el, "child", "link"),
                     lower, upper, velocity, mimic)


def _number(value: float) -> str:
    """A number as .pac text (``pdb.format_number``'s rule): integers bare, others round-trip."""
    return str(int(value)) if value == int(value) and abs(value) < 1e15 else repr(value).upper()


def pdb_layers(name: str) -> list[tuple[str, str]]:
    """The parameter database of catalogue robot ``name`` as ``(file name, .pac text)`` layers:
    ``controller.pac`` (116 = the module) and ``robot01.pac``/``calib01.pac`` (axes, limits and
    speeds from the URDF, accelerations by the module docstring's rule)."""
    robot = URDF_ROBOTS[name]
    axes = read_chain(robot.path, robot.flange).axes
    n = len(axes)

    def record(data_id: int, label: str, values: list[float] | str) -> str:
        text = f'"{values}"' if isinstance(values, str) else ", ".join(
            _number(v) if math.isfinite(v) else _number(math.copysign(_FLT_MAX, v)) for v in values)
        return f'DI: {data_id}, 0, 0, 0, "{label}" = {text}'

    def layer(*records: str) -> str:
        head = (f"' {robot.title}: derived from {robot.file} by gplrt (ours, not from a real controller)")
        return "\n".join([head, "", "Begin: 1.0", "", *records, "", "End:", ""])

    speeds = [j.to_units(j.velocity) for j in axes]
    lin, rot = CARTESIAN_SPEED
    controller = layer(
        record(109, "Controller name", f"{robot.title} (gplrt, from URDF)"),
        record(116, "Robot types", [float(robot.module)] + [0.0] * 11),
        record(600, "Trajectory Generator update period in sec", [0.004]),
        record(601, "System wide test speed in %", [50.0]),
        record(602, "Rate of change of test speed in %/sec", [100.0]))
    robot01 = layer(
        record(2000, "Number of axes", [float(n)]),
        record(2002, "Robot name", robot.title),
        record(2003, "Axis mask", [float(2 ** n - 1)]),
        record(2004, "Number of extra, non-servoed, axes", [0.0]),
        record(2104, "Enable robot operation", [1.0]),
        record(2700, "100% joint speeds in (mm or deg)/sec", speeds),
        record(2701, "100% Cartesian speeds in (mm or deg)/sec", [lin, rot]),
        record(2702, "100% joint accels in (mm or deg)/sec^2", [v / ACCEL_TIME for v in speeds]),
        record(2703, "100% Cartesian accels in (mm or deg)/sec^2", [lin / ACCEL_TIME, rot / ACCEL_TIME]),
        record(2704, "Max %speed allowed", [100.0]),
        record(2705, "Max %accel allowed", [100.0]),
        record(2706, "Max %decel allowed", [100.0]),
        record(2708, "Default %speed", [50.0]),
        record(2709, "Default Cartesian rotation %speed", [0.0]),
        record(2710, "Default %accel", [100.0]),
        record(2711, "Default %decel", [100.0]),
        record(2712, "Default max accel ramp time in sec", [RAMP_TIME]),
        record(2713, "Default max decel ramp time in sec", [RAMP_TIME]))
    calib01 = layer(
        record(16000, "Robot serial number", f"GPLRT-{robot.name}"),
        record(16051, "Tool set at restart", [0.0] * 6),
        record(16052, "Base set at restart", [0.0] * 6),
        record(16077, "Joint max soft stop limit", [j.to_units(j.upper) for j in axes]),
        record(16078, "Joint min soft stop limit", [j.to_units(j.lower) for j in axes]))
    return [("controller.pac", controller), ("robot01.pac", robot01), ("calib01.pac", calib01)]

"""Small builders shared by the geometry tests (pytest puts this folder on ``sys.path``).

One copy of each, so that every test file means the same thing by "a Location at these
coordinates" and a change to the members they call is made once.
"""

from __future__ import annotations

from gplrt.geometry import Location, RefFrame


def xyz(loc: Location) -> tuple[float, ...]:
    """The six Cartesian values of ``loc`` as GPL reads them: X, Y, Z, Yaw, Pitch, Roll."""
    return (loc.X, loc.Y, loc.Z, loc.Yaw, loc.Pitch, loc.Roll)


def cartesian(*v: float) -> Location:
    """A new Location set with ``XYZ(*v)``."""
    loc = Location()
    loc.XYZ(*v)
    return loc


def angles(*v: float) -> Location:
    """A new Angles Location set with ``Angles(*v)``."""
    loc = Location()
    loc.Angles(*v)
    return loc


def in_a_frame_loop() -> Location:
    """A Location whose RefFrame chain loops (f1 -> f2 -> f1): its total position is undefined."""
    f1, f2 = RefFrame(), RefFrame()
    f1.Loc.RefFrame = f2
    f2.Loc.RefFrame = f1
    loc = Location()
    loc.RefFrame = f1
    return loc


def conveyor_frame(robot: int) -> RefFrame:
    """A new conveyor RefFrame (Type 2) following the belt registered as conveyor robot ``robot``."""
    rf = RefFrame()
    rf.Type = 2
    rf.ConveyorRobot = robot
    return rf

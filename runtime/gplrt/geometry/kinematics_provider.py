"""The hook through which Locations reach a robot: forward/inverse kinematics and the current pose.

``Location.KineSol`` and ``Location.Here`` need a robot model, which belongs to the simulated
controller, not to geometry.  Geometry therefore defines only this small Protocol and a slot;
the controller registers its object once it has loaded a robot:

    from gplrt.geometry import set_kinematics_provider
    set_kinematics_provider(my_robot_kinematics)

Until then those members raise GPL error -1036 *Kinematics not installed* — a clear refusal,
never an invented answer.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol, runtime_checkable

from gplrt.lang.errors import KINEMATICS_NOT_INSTALLED, GplException

if TYPE_CHECKING:
    from gplrt.geometry.location import Location


@runtime_checkable
class KinematicsProvider(Protocol):
    """What a robot model offers to Location.

    * ``forward(angles)``: an Angles Location -> the Cartesian Location of the tool (Base and Tool
      included, Config filled with the configuration the joints are in).
    * ``inverse(loc, config, current)``: a Cartesian pose (a Location whose *total* position is the
      target) -> an Angles Location; ``config`` holds the GPL_Righty... bits (0 = keep the current
      configuration), ``current`` is the Angles Location to stay near (None = the robot's present
      joints).  Unreachable targets raise GplException with the controller's code (-1039, -1040, ...).
    * ``where()`` / ``where_angles()``: the robot's present Cartesian pose / joint values.
    """

    def forward(self, angles: Location) -> Location: ...

    def inverse(self, loc: Location, config: int, current: Location | None) -> Location: ...

    def where(self) -> Location: ...

    def where_angles(self) -> Location: ...


_provider: KinematicsProvider | None = None


def set_kinematics_provider(provider: KinematicsProvider | None) -> None:
    """Install (or with ``None`` remove) the robot model used by KineSol and Here."""
    global _provider
    _provider = provider


def get_kinematics_provider() -> KinematicsProvider:
    """The installed provider, or GPL error -1036 *Kinematics not installed*."""
    if _provider is None:
        raise GplException(KINEMATICS_NOT_INSTALLED, detail="no robot kinematics registered with the geometry runtime")
    return _provider

"""The catalogue of GPL built-ins: the one list of what GPL programs can name without declaring.

Generated code imports from here (``from gplrt.builtins import Location, Move``) and the
transpiler's semantic pass introspects the same tables (``gpl2py.gpl.semantics.catalogue``), so the
runtime and the transpiler cannot drift apart.  See ``gplrt/CATALOGUE.md`` for the conventions the
entries follow.

Each table maps the GPL spelling to the Python name exported by this module:

* ``CLASSES``   classes programs instantiate or declare variables of (``Dim l As Location``);
* ``GLOBAL_CLASSES`` classes with only Shared members, exported as one instance (``Move.Loc(...)``);
* ``FUNCTIONS`` functions called without a class prefix (``CInt``, ``Chr``, ``Format``);
* ``CONSTANTS`` predefined constants (``GPL_Righty``, ``GPL_CR``);
* ``TYPE_MEMBERS`` member catalogues of value types (``"String"`` -> the class whose staticmethods
  implement ``s.Length``, ``s.Substring(...)``; the string is the first argument).

The language tables come from ``gplrt.lang.catalogue`` (one place per package); classes of the other
packages are listed here by hand because each package exports exactly one Python class per GPL
class.  Importing ``gplrt.motion.robot_class`` also installs the robot kinematics behind
``Location.Here`` and ``KineSol``.  ``gplrt.sim`` is imported too: hand-written Python that uses
these names without making a ``Simulation`` gets the default session (``gplrt.session``).
"""

from __future__ import annotations

from gplrt.controller.services import Controller
from gplrt.controller.signals import Latch, Signal
from gplrt.geometry import Location, RefFrame
from gplrt.io import (
    File,
    IPEndPoint,
    Modbus,
    Socket,
    StreamReader,
    StreamWriter,
    TcpClient,
    TcpListener,
    UdpClient,
    Vision,
    VisResult,
    XmlDoc,
    XmlNode,
)
from gplrt.lang import catalogue as _lang
from gplrt.lang.arrays import GplArray
from gplrt.lang.conversions import CBool, CByte, CDbl, CInt, CShort, CSng, CStr
from gplrt.lang.console import Console
from gplrt.lang.constants import GPL_CR, GPL_LF, GPL_Above, GPL_Below, GPL_Flip, GPL_Lefty, GPL_NoFlip, GPL_Righty, GPL_Single
from gplrt.lang.errors import GplException
from gplrt.lang.format import Format
from gplrt.lang.mathlib import Fix, Int, Math, Rnd
from gplrt.lang.strings import (
    Asc,
    Chr,
    FromBitString,
    Hex,
    InStr,
    LCase,
    Len,
    Mid,
    StringMembers,
    ToBitString,
    UCase,
)
from gplrt.motion.move import Move
from gplrt.motion.profile import Profile
from gplrt.motion.robot_class import Robot
from gplrt.threads import Thread
from gplrt import sim as _sim  # noqa: F401 - registers the default session

CLASSES: dict[str, str] = {
    "Exception": "GplException",
    "Location": "Location",
    "RefFrame": "RefFrame",
    "Profile": "Profile",
    "Thread": "Thread",
    "Latch": "Latch",
    "StreamReader": "StreamReader",
    "StreamWriter": "StreamWriter",
    "XmlDoc": "XmlDoc",
    "XmlNode": "XmlNode",
    "IPEndPoint": "IPEndPoint",
    "Socket": "Socket",
    "TcpClient": "TcpClient",
    "TcpListener": "TcpListener",
    "UdpClient": "UdpClient",
    "Modbus": "Modbus",
    "Vision": "Vision",
    "VisResult": "VisResult",
    # File has only Shared members but is a class in the manuals (File.Exists(...)).
    "File": "File",
}

GLOBAL_CLASSES: dict[str, str] = {name: name for name in _lang.GLOBAL_CLASSES}
GLOBAL_CLASSES.update({"Controller": "Controller", "Signal": "Signal", "Move": "Move", "Robot": "Robot"})

FUNCTIONS: dict[str, str] = {name: name for name in _lang.FUNCTIONS}

CONSTANTS: dict[str, str] = {name: name for name in _lang.CONSTANTS}

TYPE_MEMBERS: dict[str, str] = {"String": "StringMembers", "Array": "GplArray"}

__all__ = sorted(
    {"GplException", "GplArray", "StringMembers"}
    | set(CLASSES.values())
    | set(GLOBAL_CLASSES.values())
    | set(FUNCTIONS.values())
    | set(CONSTANTS.values())
)

# Every table entry must name an object of this module (checked at import: a typo here would
# otherwise surface as a confusing transpiler error).
for _table in (CLASSES, GLOBAL_CLASSES, FUNCTIONS, CONSTANTS, TYPE_MEMBERS):
    for _py in _table.values():
        if _py not in globals():
            raise ImportError(f"gplrt.builtins lists {_py!r} but does not import it")
del _table, _py

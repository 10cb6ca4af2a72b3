"""Stand-ins for ``PARobot_auto_center.gpp``, the protected auto-centring module of Precise's
PARobot plug-in for the TCP Command Server (TCS 3.0C1 with PARobot).

The module's source is encrypted, so gpl2py cannot translate it.  Two of its names are used on
paths every TCS user takes, and would otherwise end TCS before it serves anyone:

* ``PARobot_auto_center.Version`` is read by ``PARobot_auto_center_intf.Init`` when the project
  starts (it names the plug-in in the ``version`` reply and the system messages);
* ``AC_InitAutoCenter(robot)`` is called by ``PARobot_auto_center_intf.Hook_InitCommand`` each
  time a client connection creates a command object for a robot: it sets up the module's
  per-robot variables, of which the simulation has none.

The force-controlled search itself (``AC_HeightDetect``, behind the ``HeightDetect`` command) and
``AC_ErrorMessage`` are not stood in for: they stay stubs that raise -204 *Not implemented* when
used, which TCS's command handler reports to the client as the command's error.

gpl2py ships this file and uses it when the project has these stubs and ``--stubs DIR`` does not
implement them itself (docs/design/real-code.md, "Protected plug-in code").
"""

from __future__ import annotations

#: What the plug-in reports as its version: the name of the protected module and why it is not
#: the vendor's own text (which is in the encrypted source).
Version = "PARobot_auto_center (protected module; gpl2py stand-in, auto-centring not simulated)"


def AC_InitAutoCenter(RobNum: int) -> None:
    """Per-robot set-up of the protected module: the simulation keeps no state for it."""
    return None

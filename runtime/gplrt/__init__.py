"""gplrt: the runtime that transpiled GPL programs import.

It owns GPL's language semantics (``gplrt.lang``), the geometry of Location/RefFrame
(``gplrt.geometry``), the simulated controller's motion, I/O and clock (``gplrt.motion``,
``gplrt.controller``, ``gplrt.io``), and threads.  It must run generated code and hand-written
Python alike.  See ``gplrt/CATALOGUE.md`` for how built-in GPL classes are declared.
"""

# Loads the conversions first: they install the Integer conversion GplException's members use.
from gplrt.lang import conversions as _conversions  # noqa: F401
from gplrt.lang.errors import GplException

__all__ = ["GplException"]

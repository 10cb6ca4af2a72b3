"""gplrt: the runtime that transpiled GPL programs import.

It owns GPL's language semantics (``gplrt.lang``), the geometry of Location/RefFrame
(``gplrt.geometry``), the simulated controller's motion, I/O and clock (``gplrt.motion``,
``gplrt.controller``, ``gplrt.io``), and threads.  It must run generated code and hand-written
Python alike.  See ``gplrt/CATALOGUE.md`` for how built-in GPL classes are declared.
"""

from gplrt.lang.errors import GplException

__all__ = ["GplException"]

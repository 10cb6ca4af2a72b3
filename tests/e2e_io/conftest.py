"""End-to-end tests of threads, sockets and files through transpiled GPL (issue "Threads, I/O").

The GPL programs live in ``projects/``; ``gplrun`` (shared with tests/samples) transpiles them with
the ``gpl2py`` command and imports the generated package.
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "samples"))

PROJECTS = Path(__file__).resolve().parent / "projects"

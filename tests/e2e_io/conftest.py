"""End-to-end tests of threads, sockets and files through transpiled GPL (issue "Threads, I/O").

The GPL programs live in ``projects/``; ``gpltest`` (tests/gpltest.py) transpiles them with
the ``gpl2py`` command and imports the generated package.
"""

from __future__ import annotations

from pathlib import Path

PROJECTS = Path(__file__).resolve().parent / "projects"

"""``python -m gpl2py``: the same command as the installed ``gpl2py`` script."""

import sys

from gpl2py.cli import main

sys.exit(main())

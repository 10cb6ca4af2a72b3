"""``python -m gpl2py``: the same command as the installed ``gpl2py`` script."""

import sys

from gpl2py.entry import main

sys.exit(main())

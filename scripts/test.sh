#!/usr/bin/env bash
# Runs the whole test suite; sets up .venv first if needed.  Extra arguments go to pytest.
# pytest exits 5 when it collects no test: that is a failure here, never a silent pass.
source "$(dirname "$0")/_venv.sh"
# The tests run on every core (pytest-xdist; GPL2PY_TEST_WORKERS=0 runs them in this process).
python -m pytest -q -n "${GPL2PY_TEST_WORKERS:-auto}" "$@"

#!/usr/bin/env bash
# The README's test command as a new user meets it: a fresh clone of this repository's HEAD in a
# temporary folder with nothing beside it (no ../shared), outside CI (CI=true would turn the
# missing corpus into failures) and with no GPL_CORPUS / GPL_SPEC.  The tests that need the real
# code must skip, each naming the variable that points at it; every other test must run and pass.
# pytest itself fails on an error during collection (exit 2) and on collecting no test (exit 5).
# The whole suite is collected first (what a collection-time skip once broke: 0 tests ran); then
# a subset runs: every test file that reads the real code, with the samples, the semantic tests and
# the command line beside them (CI's main run is the one long one: twice the whole suite would not
# fit its 30 minutes).  Arguments replace the subset (`tests` for the whole suite).
set -euo pipefail
SUBSET=(tests/realworld tests/semantics tests/samples tests/e2e_io tests/frontend/test_corpus_syntax.py
        tests/frontend/test_check_matches_translate.py tests/frontend/test_cli.py
        tests/tooling/test_transpiler_imports.py)
[ "$#" -gt 0 ] && SUBSET=("$@")
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
git clone --quiet --no-hardlinks "$ROOT" "$WORK/gpl2py"
cd "$WORK/gpl2py"
LOG="$WORK/pytest.log"
status=0
env -u CI -u GPL_CORPUS -u GPL_SPEC -u GPL2PY_VENV bash scripts/test.sh --collect-only -p no:cacheprovider \
    > "$WORK/collect.log" 2>&1 || status=$?
if [ "$status" -ne 0 ]; then
    tail -n 30 "$WORK/collect.log" >&2
    echo "fresh clone: collecting the whole suite failed (exit $status)" >&2
    exit "$status"
fi
echo "fresh clone: $(tail -n 1 "$WORK/collect.log")"
env -u CI -u GPL_CORPUS -u GPL_SPEC -u GPL2PY_VENV bash scripts/test.sh -rs -p no:cacheprovider "${SUBSET[@]}" \
    2>&1 | tee "$LOG" || status=$?
if [ "$status" -ne 0 ]; then
    echo "fresh clone: the README's test command failed (exit $status)" >&2
    exit "$status"
fi
# The clone must really have run without the corpus: some test skipped for want of it.
if ! grep -q "set GPL_CORPUS" "$LOG"; then
    echo "fresh clone: no test skipped for want of GPL_CORPUS; was the corpus found beside the clone?" >&2
    exit 1
fi
echo "fresh clone: $(tail -n 1 "$LOG")"

#!/usr/bin/env bash
# Installs gpl2py with the lowest versions of its dependencies that pyproject.toml allows (its
# floors), in a virtual environment of its own, and runs a smoke test: the floors must really
# install together and work.  .ci/run calls it after the test suite.  The environment is
# .venv-floors (or $GPL2PY_FLOORS_VENV), made afresh each time.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="${GPL2PY_FLOORS_VENV:-$ROOT/.venv-floors}"
PY="${PYTHON:-python3}"
started=$SECONDS
"$PY" -m venv --clear "$VENV"
"$VENV/bin/python" "$ROOT/scripts/floors.py" constraints plot lsp sweep > "$VENV/floors.txt"
# Not editable: the wheel a user would get, with its package data.
"$VENV/bin/python" -m pip install --quiet --constraint "$VENV/floors.txt" "$ROOT[plot,lsp,sweep]"
"$VENV/bin/python" "$ROOT/scripts/floors.py" verify plot lsp sweep

WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"  # away from the checkout: the installed package, not the source tree, is imported
export GPL2PY_CACHE_DIR="$WORK/cache" MPLBACKEND=Agg
G="$VENV/bin/gpl2py"
"$G" --version
"$G" check "$ROOT/samples/tcp_command_server"
"$G" run "$ROOT/samples/pick_and_place" --setup "$ROOT/samples/notebook/cell_io.py" \
    --plot "$WORK/cell.png" --quiet > "$WORK/console.txt"
grep -q "cell done: 8 parts placed" "$WORK/console.txt"
head -c 4 "$WORK/cell.png" | grep -q PNG
"$G" "$ROOT/samples/pick_and_place" -o "$WORK/out" --quiet
(cd "$WORK/out" && "$VENV/bin/python" -m pick_and_place > "$WORK/plain.txt" || test $? -eq 1)
grep -q "palletising cell" "$WORK/plain.txt"
# the language server at its floors: initialize, a file's diagnostics, shutdown, exit
lsp_message() { printf 'Content-Length: %d\r\n\r\n%s' "${#1}" "$1"; }
mkdir "$WORK/lsp" && printf 'Module Main\n    Sub Main()\n    End Sub\nEnd Module\n' > "$WORK/lsp/Main.gpl"
MAIN_URI="file://$WORK/lsp/Main.gpl"
{ lsp_message '{"jsonrpc":"2.0","id":1,"method":"initialize","params":{"capabilities":{},"initializationOptions":{"debounceMs":0}}}'
  lsp_message '{"jsonrpc":"2.0","method":"initialized","params":{}}'
  lsp_message '{"jsonrpc":"2.0","method":"textDocument/didOpen","params":{"textDocument":{"uri":"'"$MAIN_URI"'","languageId":"gpl","version":1,"text":"Module Main\n    Sub Main()\n        x = 1\n    End Sub\nEnd Module\n"}}}'
  sleep 5
  lsp_message '{"jsonrpc":"2.0","id":2,"method":"shutdown"}'
  lsp_message '{"jsonrpc":"2.0","method":"exit"}'; } | "$G" lsp > "$WORK/lsp.txt"
grep -q "GPL2001" "$WORK/lsp.txt"
printf 'interval,speed\n0.2,80\n6.0,80\n' > "$WORK/params.csv"
"$G" sweep "$ROOT/samples/pick_and_place" --params "$WORK/params.csv" --setup "$ROOT/samples/sweep/setup.py" \
    --workers 2 -o "$WORK/sweep.parquet" --quiet
"$VENV/bin/python" -c "import pandas as pd, sys; df = pd.read_parquet(sys.argv[1]); \
assert list(df['status']) == ['ok', 'ok'] and df['end_time'][0] > df['end_time'][1], df" "$WORK/sweep.parquet"
echo "floors: smoke test passed in $((SECONDS - started)) s"

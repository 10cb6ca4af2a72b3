"""The command of a generated data module: a front end's table the transpiler reads instead of
importing the runtime it was read from (GPL's built-in catalogue, TMscript's members), written or
checked by ``python -m <its generator>``."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path


def main(prog: str, description: str, generate: Callable[[], str], path: Path, argv: list[str] | None) -> int:
    """Write ``generate()`` to ``path`` when it differs; with ``--check``, write nothing and return 1
    when it differs."""
    ap = argparse.ArgumentParser(prog=prog, description=description)
    ap.add_argument("--check", action="store_true",
                    help="write nothing; exit status 1 if the data module is out of date")
    args = ap.parse_args(argv)
    text = generate()
    current = path.read_text(encoding="utf-8") if path.exists() else None
    if args.check:
        if current != text:
            print(f"{path} is out of date: run {prog}", file=sys.stderr)
            return 1
        return 0
    if current != text:
        path.write_text(text, encoding="utf-8")
        print(f"wrote {path}")
    else:
        print(f"{path} is up to date")
    return 0

"""The lowest versions pyproject.toml allows, as pip constraints; and a check that they installed.

    python scripts/floors.py constraints [EXTRA ...]   print name==floor for every dependency
    python scripts/floors.py verify [EXTRA ...]        exit 1 unless each is installed at its floor

Every runtime dependency (and every one of the named extras) must state a floor with ``>=``: a
dependency without one could not be tested at its lowest version, so it is an error here.  Only
the direct dependencies are pinned (uv's ``--resolution lowest-direct``); pip chooses the rest.
Used by scripts/floors.sh, which .ci/run calls.
"""

from __future__ import annotations

import re
import sys
import tomllib
from importlib import metadata
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
_FLOOR = re.compile(r"^\s*([A-Za-z0-9][A-Za-z0-9._-]*)\s*(?:\[[^\]]*\])?\s*>=\s*([^,;\s]+)\s*(?:[,;].*)?$")


def floors(extras: list[str]) -> dict[str, str]:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    requirements = list(project["dependencies"])
    for extra in extras:
        requirements += project["optional-dependencies"][extra]
    out: dict[str, str] = {}
    for req in requirements:
        found = _FLOOR.match(req)
        if found is None:
            raise SystemExit(f"floors.py: {req!r} in pyproject.toml states no floor ('name>=version')")
        out[found.group(1).lower()] = found.group(2)
    return out


def _release(version: str) -> tuple[object, ...]:
    """``2.2`` and ``2.2.0`` alike (PEP 440 pads releases with zeros)."""
    parts: list[object] = [int(p) if p.isdigit() else p for p in version.split(".")]
    while len(parts) > 1 and parts[-1] == 0:
        parts.pop()
    return tuple(parts)


def main(argv: list[str]) -> int:
    if not argv or argv[0] not in ("constraints", "verify"):
        print(__doc__, file=sys.stderr)
        return 2
    wanted = floors(argv[1:])
    if argv[0] == "constraints":
        for name, version in sorted(wanted.items()):
            print(f"{name}=={version}")
        return 0
    wrong = [f"{name} {metadata.version(name)} (floor {version})" for name, version in sorted(wanted.items())
             if _release(metadata.version(name)) != _release(version)]
    if wrong:
        print("floors.py: not at their floors: " + ", ".join(wrong), file=sys.stderr)
        return 1
    print("floors: " + ", ".join(f"{n} {v}" for n, v in sorted(wanted.items())))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

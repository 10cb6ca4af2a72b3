"""The source map written next to a generated package (``_sourcemap.json``).

Per generated module: the GPL source file and runs ``[first_python_line, gpl_line]`` (a new run
starts wherever the GPL line changes; 0 means "no GPL line").  ``gplrt.lang.sourcemap`` reads it
back to name the GPL file and line of each frame of a traceback.
"""

from __future__ import annotations

import json
import os


def runs(gmap: list[int]) -> list[list[int]]:
    out: list[list[int]] = []
    last = None
    for i, g in enumerate(gmap):
        if g != last:
            out.append([i + 1, g])
            last = g
    return out


def sourcemap_json(entries: dict[str, tuple[str, list[int]]]) -> str:
    """``entries`` maps a module file name to (GPL source path, per-line GPL lines)."""
    data = {
        "version": 1,
        "modules": {
            name: {"source": os.path.basename(src), "runs": runs(gmap)}
            for name, (src, gmap) in sorted(entries.items())
        },
    }
    return json.dumps(data, sort_keys=True, separators=(",", ":")) + "\n"

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


def runs_json(gmap: list[int]) -> str:
    """``json.dumps(runs(gmap), separators=(",", ":"))`` without the list of runs: the pipeline
    keeps this text per module instead of the per-line list (docs/security.md, "Input size")."""
    out: list[str] = []
    last = None
    for i, g in enumerate(gmap):
        if g != last:
            out.append(f"[{i + 1},{g}]")
            last = g
    return "[" + ",".join(out) + "]"


def sourcemap_json(entries: dict[str, tuple[str, str]]) -> str:
    """``entries`` maps a module file name to (GPL source path, :func:`runs_json` of its lines).
    The text is what ``json.dumps(..., sort_keys=True, separators=(",", ":"))`` gives."""
    parts = []
    for name, (src, run_text) in sorted(entries.items()):
        parts.append(f'{json.dumps(name)}:{{"runs":{run_text},"source":{json.dumps(os.path.basename(src))}}}')
    return '{"modules":{' + ",".join(parts) + '},"version":1}\n'

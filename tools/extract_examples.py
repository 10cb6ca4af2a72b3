"""Extract the manual examples from the GPL specs into ``tests/frontend/examples/`` (run once, commit).

Usage::

    python tools/extract_examples.py [--spec-dir /work/shared/spec] [--out tests/frontend/examples]

Sources: Appendix A and B of ``gpl-language.md`` (headings ``### E01 — …`` / ``### X01 — …``) and
Appendix A of ``gpl-classes.md`` (``### EX-01 — …``).  Only ``vb``/``vbnet`` code blocks are taken
(XML and plain-text blocks are not GPL).

* An example split by ``# ---- next fragment ----`` lines becomes one file per fragment
  (``lang_E42_1.gpl``, ``lang_E42_2.gpl`` …): fragments are separate listings in the manual and may
  re-declare the same names or mix module-level and statement-level code.
* When the spec gives a "Repaired for parser tests" version (PDF line-wrap artifacts), the repaired
  block is the main file and the verbatim block is kept as ``…_verbatim.gpl`` (it must show the
  artifact as an error, or parse if the artifact happens to be valid syntax).
* Files are written verbatim (no header lines), so line numbers in the test's expectation table
  are the manual's lines.  ``manifest.json`` records where every file came from.

The test (``tests/frontend/test_appendix_examples.py``) reads only the committed files, so it does
not depend on ``/work/shared`` at run time.
"""

from __future__ import annotations

import argparse
import json
import re
from dataclasses import asdict, dataclass
from pathlib import Path

_HEADING = re.compile(r"^### (?P<id>E\d+|X\d+|EX-\d+) — (?P<title>.*)$")
_FENCE = re.compile(r"^```(?P<lang>\w*)\s*$")
_FRAGMENT = "# ---- next fragment ----"
_REPAIRED = "Repaired for parser tests"


@dataclass
class Entry:
    file: str
    source: str
    example: str
    title: str
    fragment: int
    variant: str  # "main" | "verbatim"


def _examples(path: Path) -> list[tuple[str, str, list[tuple[str, list[str], bool]]]]:
    """``(id, title, [(lang, lines, repaired?)])`` for every example heading in ``path``."""
    out: list[tuple[str, str, list[tuple[str, list[str], bool]]]] = []
    current: tuple[str, str, list[tuple[str, list[str], bool]]] | None = None
    in_block = False
    lang = ""
    block: list[str] = []
    repaired_next = False
    for line in path.read_text(encoding="utf-8").splitlines():
        if in_block:
            if line.startswith("```"):
                in_block = False
                if current is not None:
                    current[2].append((lang, block, repaired_next))
                repaired_next = False
            else:
                block.append(line.rstrip())
            continue
        m = _HEADING.match(line)
        if m:
            current = (m.group("id"), m.group("title").strip(), [])
            out.append(current)
            repaired_next = False
            continue
        if line.startswith("## ") and current is not None:
            current = None  # left the appendix section
            continue
        if _REPAIRED in line:
            repaired_next = True
        f = _FENCE.match(line)
        if f:
            in_block = True
            lang = f.group("lang")
            block = []
    return out


def _fragments(lines: list[str]) -> list[list[str]]:
    frags: list[list[str]] = [[]]
    for line in lines:
        if line.strip() == _FRAGMENT:
            frags.append([])
        else:
            frags[-1].append(line)
    return [f for f in frags if any(x.strip() for x in f)]


def extract(spec_dir: Path, out_dir: Path) -> list[Entry]:
    out_dir.mkdir(parents=True, exist_ok=True)
    for old in out_dir.glob("*.gpl"):
        old.unlink()
    entries: list[Entry] = []
    for doc, prefix in (("gpl-language.md", "lang"), ("gpl-classes.md", "classes")):
        for ex_id, title, blocks in _examples(spec_dir / doc):
            code = [(lines, rep) for lang, lines, rep in blocks if lang in ("vb", "vbnet")]
            if not code:
                continue
            has_repaired = any(rep for _, rep in code)
            for lines, rep in code:
                variant = "verbatim" if has_repaired and not rep else "main"
                frags = _fragments(lines)
                for n, frag in enumerate(frags, start=1):
                    name = f"{prefix}_{ex_id}"
                    if len(frags) > 1:
                        name += f"_{n}"
                    if variant == "verbatim":
                        name += "_verbatim"
                    (out_dir / f"{name}.gpl").write_text("\n".join(frag) + "\n", encoding="utf-8")
                    entries.append(Entry(f"{name}.gpl", doc, ex_id, title, n, variant))
    (out_dir / "manifest.json").write_text(json.dumps([asdict(e) for e in entries], indent=1) + "\n")
    return entries


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spec-dir", type=Path, default=Path("/work/shared/spec"))
    ap.add_argument("--out", type=Path, default=Path(__file__).resolve().parents[1] / "tests/frontend/examples")
    args = ap.parse_args()
    entries = extract(args.spec_dir, args.out)
    print(f"wrote {len(entries)} example files to {args.out}")


if __name__ == "__main__":
    main()

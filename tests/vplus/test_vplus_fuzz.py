"""Fuzz the V+ front end's whole pipeline (bad input gets a clear answer, as GPL's fuzz holds it).

Seeds: the V+ programs of the corpus (``../shared/corpus/vplus``: the ROS-Industrial server, the
robot-sandbox teaching programs and self-tests, read in place; skipped naming ``GPL_CORPUS`` when
absent outside CI) and the V+ sources written in the V+ tests (string constants with a
``.PROGRAM``, read from the test modules with ``ast``).  Each input is a mutant: lines deleted,
duplicated, swapped or borrowed from another seed; words replaced by V+ keywords, operators or
hostile names; bytes inserted, deleted or flipped; names renamed consistently to Python keywords,
builtins, the runtime's names (``vp``, ``s_chr``), the lowering's (``$x`` is ``s_x``, ``a.b`` is
``a_b``) and dunders; and the shapes V+ has of its own: every block kind (IF, DO, WHILE, FOR,
CASE) nested past what CPython compiles, long operator chains and deep parentheses, labels and
GOTOs everywhere, EXIT n / NEXT n of any depth, REACTE on and off, data sections (.LOCATIONS,
.REALS, .STRINGS) mutated, huge literals -- in one-file, several-file and folder projects with
hostile file names, and sometimes a hostile ``--start``.  Each goes through ``transpile``
in-process with ``GPL2PY_TRACEBACK=1`` (a bug is an exception here).  The properties are the GPL
fuzz's (tests/frontend/test_fuzz.py; the shared machinery is tests/fuzzkit.py): no exception and
no GPL9000; a translation without errors compiles (warnings are errors) and imports without doing
anything forbidden; ``--keep-going`` output compiles; ``check`` reports exactly what
``translate`` reports; every diagnostic is ``file:line:col: severity GPLnnnn: message``;
nothing is written outside the batch's temporary folder.

``GPL2PY_VPLUS_FUZZ_INPUTS`` inputs per run (default 1,200, in ``FUZZ_PARTS`` parts, each with
its own random stream), ``GPL2PY_FUZZ_SEED`` (fixed by default; ``random`` for a new one).
"""

from __future__ import annotations

import ast
import os
import re
from pathlib import Path

import pytest

import gplrt.vplus  # noqa: F401  (its first import loads native code: before the audit of generated packages)
from fuzzkit import (BUILTIN_NAMES, FuzzInput, HOSTILE_FILES, PYTHON_HOSTILE, TextMutations, check_diagnostics,
                     check_matches_translate, check_translated, compile_all, part_inputs, part_rng, run_part,
                     write_input)
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.transpile import transpile
from gpl2py.vplus.syntax.keywords import GENERIC, STRUCTURE, TIER3, ZERO_ARG
from gpltest import corpus_dir

FUZZ_INPUTS = int(os.environ.get("GPL2PY_VPLUS_FUZZ_INPUTS", "1200"))
FUZZ_PARTS = 4
START = frozenset({"GPL4311"})  # --start names no program: about the option, no file to point at

#: Words a renamed V+ name must not be (it would only be a syntax error).
VPLUS_WORDS = {w.upper() for w in GENERIC | STRUCTURE | TIER3 | ZERO_ARG} | {
    "CALL", "CALLS", "RETURN", "RETURNE", "EXECUTE", "REACT", "REACTI", "REACTE", "SET", "AUTO", "LOCAL",
    "GLOBAL", "DOUBLE", "REAL", "AND", "OR", "XOR", "NOT", "BAND", "BOR", "BXOR", "MOD", "TO", "STEP", "OF",
    "THEN", "DO", "TRUE", "FALSE", "ON", "OFF"}
#: Names gpl2py's V+ lowering and the V+ runtime layer use (gpl2py/vplus/lower/names.py).
VPLUS_GENERATED = ["vp", "s_chr", "s_msg", "p_safe", "b_b1", "abs_", "in_", "list_", "wait_event", "task",
                   "program", "run", "main", "vars", "frame", "state", "loop", "jump", "label", "goto",
                   "_vp", "_l", "_lbl", "_pc", "_g", "_block", "_step", "_react", "_args"]
HOSTILE_NAMES = [n for n in sorted({*PYTHON_HOSTILE, *BUILTIN_NAMES, *VPLUS_GENERATED})
                 if re.fullmatch(r"[A-Za-z][A-Za-z0-9_.]*", n) and n.upper() not in VPLUS_WORDS]
#: Words put in place of a word of the source.
REPLACEMENTS = ["IF", "THEN", "ELSE", "END", "DO", "UNTIL", "WHILE", "FOR", "TO", "STEP", "CASE", "OF", "VALUE",
                "ANY", "EXIT", "NEXT", "GOTO", "CALL", "RETURN", "REACTE", "REACT", "AUTO", "LOCAL", "GLOBAL",
                "TYPE", "MOVE", "HERE", "SET", "(", ")", "[", "]", ",", ":", "=", "+", "-", "*", "/", "^",
                "$", "#", "%", ".", '"', ";", "^H", "^B", "1E", "1E+400", ".END", ".PROGRAM", "\n", "\t",
                "é", "\x00", "10", "99999", "-", "$x", "#p", "%b", "a.b", "a_b"]
PIECE = re.compile(r"[A-Za-z_][A-Za-z0-9_.]*|[ \t]+|\r?\n|.", re.DOTALL)
NAME = re.compile(r"(?<![A-Za-z0-9_.$#%])([$#%]?)([A-Za-z][A-Za-z0-9_.]*)")
DECLARED = re.compile(r"(?im)^[ \t]*(?:\.PROGRAM[ \t]+([A-Za-z][A-Za-z0-9_.]*)|(?:\d+[ \t]+)?[$#]?([A-Za-z][A-Za-z0-9_.]*)"
                      r"(?:\[[^\]\n]*\])?[ \t]*=)")


def _declared(text: str) -> list[str]:
    """The program names and assigned variable names of ``text`` (the renames' targets)."""
    return sorted({a or b for a, b in DECLARED.findall(text)} - {""} - {w.lower() for w in VPLUS_WORDS}
                  - {w for w in VPLUS_WORDS})


def written_sources() -> list[str]:
    """The V+ sources written in the V+ tests: their string constants that hold a program."""
    out = []
    for path in sorted(Path(__file__).parent.glob("test_*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and ".PROGRAM" in node.value.upper() \
                    and "gpl2py:" not in node.value:  # (an ignore directive: check applies it, transpile does not)
                out.append(node.value)
    return out


def vplus_seeds() -> list[str]:
    root = corpus_dir() / "vplus"
    corpus = [p.read_bytes().decode("latin-1") for p in sorted(root.rglob("*")) if p.suffix.lower() in (".v2", ".pg")]
    assert len(corpus) >= 15, len(corpus)
    return corpus + written_sources()


class Mutator(TextMutations):
    """Mutations of real V+ by lines, words and bytes, hostile renames, and V+'s own shapes."""

    def __init__(self, rng: object, seeds: list[str]) -> None:
        self.rng = rng  # type: ignore[assignment]
        self.seeds = seeds
        self.donors = seeds
        self.programs = [m.group(0) for s in seeds
                         for m in re.finditer(r"(?ims)^\.PROGRAM\b.*?^\.END[^\n]*(?:\n|$)", s)]

    def source(self) -> str:
        rng = self.rng
        if rng.random() < 0.6:
            return rng.choice(self.seeds)
        return "".join(rng.sample(self.programs, k=min(len(self.programs), rng.randint(1, 3))))

    def mutate(self, text: str, what: list[str]) -> str:
        rng = self.rng
        declared = _declared(text)
        for _ in range(rng.choice([0, 1, 1, 2, 2, 3, 5])):
            op = rng.choices(
                ["rename", "rename_pair", "line_del", "line_dup", "line_swap", "line_donor", "token",
                 "token_hostile", "byte_ins", "byte_del", "byte_flip", "deep", "long_expr", "labels", "exit_next",
                 "reacte", "data", "huge_literal"],
                weights=[8, 4, 3, 2, 2, 2, 4, 2, 1, 1, 1, 2, 1, 2, 2, 1, 2, 0.5])[0]
            what.append(op)
            text = getattr(self, "op_" + op)(text, declared)
        return text

    # -- names
    def hostile_name(self) -> str:
        name = self.rng.choice(HOSTILE_NAMES)
        r = self.rng.random()
        if r < 0.2:
            name = self.rng.choice(["$", "#", "%"]) + name
        elif r < 0.3:
            name = name.upper()
        elif r < 0.4:
            name = name.replace("_", ".") if "_" in name else name + ".x"
        return name

    def _rename(self, text: str, old: str, new: str) -> str:
        pattern = re.compile(rf"(?<![A-Za-z0-9_.$#%])([$#%]?){re.escape(old)}(?![A-Za-z0-9_.])", re.IGNORECASE)
        if new[:1] in "$#%":
            return pattern.sub(lambda m: new if m.group(1) else new[1:], text)
        return pattern.sub(lambda m: m.group(1) + new, text)

    def op_rename(self, text: str, declared: list[str]) -> str:
        if not declared:
            return text
        return self._rename(text, self.rng.choice(declared), self.hostile_name().lstrip("$#%"))

    def op_rename_pair(self, text: str, declared: list[str]) -> str:
        """Two names renamed to two that the lowering could make one Python name: ``a.b`` and
        ``a_b``, ``x`` and ``x_`` (a builtin gets a ``_``), ``s_x`` and ``$x``."""
        if len(declared) < 2:
            return self.op_rename(text, declared)
        first, second = self.rng.sample(declared, 2)
        base = self.rng.choice([n for n in HOSTILE_NAMES if "." not in n]).rstrip("_") or "list"
        a, b = self.rng.choice([(f"{base}.x", f"{base}_x"), (base, base + "_"), (f"s_{base}", base),
                                (f"p_{base}", base), (f"{base}.2", f"{base}_2")])
        return self._rename(self._rename(text, first, a), second, b)

    # -- words
    def op_token(self, text: str, declared: list[str]) -> str:
        return self.mutate_piece(text, PIECE, REPLACEMENTS)

    def op_token_hostile(self, text: str, declared: list[str]) -> str:
        words = [m for m in NAME.finditer(text)]
        if not words:
            return text
        m = self.rng.choice(words)
        return text[:m.start(2)] + self.hostile_name().lstrip("$#%") + text[m.end(2):]

    # -- V+'s own shapes
    def _in_program(self, text: str, body: str) -> str:
        """``body`` (lines) after a ``.PROGRAM`` line, or a new program when there is none."""
        heads = [m.end() for m in re.finditer(r"(?im)^\.PROGRAM[^\n]*\n", text)]
        if not heads:
            return text + f".PROGRAM fuzz()\n{body}.END\n"
        at = self.rng.choice(heads)
        return text[:at] + body + text[at:]

    def op_deep(self, text: str, declared: list[str]) -> str:
        """One block kind (or a mix) nested around 20 (CPython's limit), 50, 100 or 1,000 deep."""
        rng = self.rng
        n = rng.choice([5, 19, 20, 21, 22, 50, 100, 1000])
        kinds = ["IF", "DO", "WHILE", "FOR", "CASE"]
        kind = rng.choice(kinds + ["mix"])
        heads, tails = [], []
        for i in range(n):
            k = rng.choice(kinds) if kind == "mix" else kind
            if k == "IF":
                heads.append(f"IF i{i % 3} > 0 THEN\n"), tails.append("ELSE\nTYPE 1\nEND\n" if i % 2 else "END\n")
            elif k == "DO":
                heads.append("DO\n"), tails.append("UNTIL TRUE\n")
            elif k == "WHILE":
                heads.append("WHILE FALSE DO\n"), tails.append("END\n")
            elif k == "FOR":
                heads.append(f"FOR i{i} = 1 TO 2\n"), tails.append("END\n")
            else:
                heads.append(f"CASE i{i % 3} OF\nVALUE 1, 2:\n"), tails.append("ANY\nTYPE 0\nEND\n")
        inner = rng.choice(["TYPE \"x\"\n", "EXIT\n", "NEXT\n", f"EXIT {rng.randint(1, n + 2)}\n", "GOTO 10\n",
                            "10 TYPE 1\n", ""])
        body = "".join(heads) + inner + "".join(reversed(tails))
        if rng.random() < 0.2:  # an unbalanced nest
            body = body[:rng.randrange(len(body) + 1)]
        return self._in_program(text, body)

    def op_long_expr(self, text: str, declared: list[str]) -> str:
        rng = self.rng
        n = rng.choice([100, 300, 1000, 3000])
        shape = rng.random()
        if shape < 0.4:
            expr = rng.choice([" + ", " * ", " AND ", " BOR ", " - ", " / "]).join([rng.choice(["1", "x", "1.5"])] * n)
        elif shape < 0.6:
            expr = "(" * n + "1" + ")" * n
        elif shape < 0.8:
            expr = "-" * n + "1" if rng.random() < 0.5 else "NOT " * n + "1"
        else:
            expr = "ABS(" * n + "1" + ")" * n
        target = rng.choice(["x", "$s", "a[1]", "x"])
        line = f"{target} = {expr}\n" if not target.startswith("$") else f"$s = {'+'.join(['$x'] * n)}\n"
        return self._in_program(text, line)

    def op_labels(self, text: str, declared: list[str]) -> str:
        """Numeric labels on random lines, and GOTOs to them (into blocks, out of them, backwards)
        or to labels that do not exist."""
        rng = self.rng
        lines = text.splitlines(keepends=True)
        if not lines:
            return text
        labels = []
        for _ in range(rng.randint(1, 8)):
            i = rng.randrange(len(lines))
            label = rng.choice([str(rng.randint(1, 99999)), "0", "65535", "65536", "-1", "10"])
            lines[i] = f"{label} {lines[i].lstrip()}"
            labels.append(label)
        for _ in range(rng.randint(1, 8)):
            i = rng.randrange(len(lines) + 1)
            target = rng.choice(labels) if rng.random() < 0.8 else str(rng.randint(1, 100))
            lines.insert(i, rng.choice([f"GOTO {target}\n", f"IF x THEN GOTO {target}\n",
                                        f"IF x THEN\nGOTO {target}\nEND\n", f"{target} GOTO {target}\n"]))
        return "".join(lines)

    def op_exit_next(self, text: str, declared: list[str]) -> str:
        rng = self.rng
        lines = text.splitlines(keepends=True)
        for _ in range(rng.randint(1, 4)):
            n = rng.choice(["", "", "0", "1", "2", "3", "25", "-1", "x", "1.5", "99999999999"])
            lines.insert(rng.randrange(len(lines) + 1), f"{rng.choice(['EXIT', 'NEXT'])} {n}\n")
        return "".join(lines)

    def op_reacte(self, text: str, declared: list[str]) -> str:
        rng = self.rng
        target = rng.choice(declared) if declared and rng.random() < 0.7 else rng.choice(["nope", "fuzz", "0"])
        line = rng.choice([f"REACTE {target}\n", "REACTE\n", "REACTE 0\n", f"REACT 1001, {target}\n",
                           f"REACTI -1, {target}, 5\n", "IGNORE 1001\n", f"REACTE {target}\nREACTE\n",
                           "REACTE ,\n", "RETURNE\n"])
        lines = text.splitlines(keepends=True)
        for _ in range(rng.randint(1, 3)):
            lines.insert(rng.randrange(len(lines) + 1), line)
        return "".join(lines)

    def op_data(self, text: str, declared: list[str]) -> str:
        """A data section, well formed or not: names with sigils, too few or many values, huge or
        odd numbers, unterminated strings, a missing .END."""
        rng = self.rng
        kind = rng.choice(["LOCATIONS", "REALS", "STRINGS", "PRECISION", "INTEGER", "NOPE"])
        rows = []
        for _ in range(rng.randint(0, 6)):
            name = rng.choice([rng.choice(declared) if declared else "x", self.hostile_name(), "#safe", "$name",
                               "pick", "a.b", "a[1]", "1x", ""])
            nums = " ".join(rng.choice(["100", "-90", "1E+400", "0", "12.5", "x", "1e", "-", "^H10", "99" * 200])
                            for _ in range(rng.choice([0, 1, 3, 6, 7, 12, 1000])))
            rows.append(rng.choice([f"{name} {nums}\n", f'{name} "cell {rng.randint(0, 9)}"\n', f'{name} "open\n',
                                    f"{name}\n", "\n", ";comment\n"]))
        section = f".{kind}\n" + "".join(rows) + (".END\n" if rng.random() < 0.85 else "")
        if rng.random() < 0.3:
            section = self.op_token(section, declared)
        return text + section if rng.random() < 0.8 else section + text

    def op_huge_literal(self, text: str, declared: list[str]) -> str:
        rng = self.rng
        literal = rng.choice(["9" * 309, "1" + "0" * 4301, "1E+400", "1E-400", "^H" + "F" * 40, "^B" + "1" * 80,
                              "1.5E+308", "4294967296", "-2147483649"])
        numbers = list(re.finditer(r"(?<![\w.])\d+(?![\w.])", text))
        if numbers and rng.random() < 0.7:
            m = rng.choice(numbers)
            return text[:m.start()] + literal + text[m.end():]
        return self._in_program(text, f"x = {literal}\n")

    # -- projects
    def project(self, number: int) -> FuzzInput:
        rng = self.rng
        what: list[str] = []
        kind = rng.choices(["one", "several", "folder"], weights=[70, 20, 10])[0]
        what.append(kind)
        files: dict[str, bytes] = {}
        for _ in range(1 if kind == "one" else rng.randint(2, 3)):
            text = self.mutate(self.source(), what)
            stem = rng.choice(HOSTILE_FILES) if rng.random() < 0.3 else f"src{len(files)}"
            name = f"{stem}.{rng.choice(['v2', 'v2', 'pg', 'V2'])}"
            if name in files:
                name = f"src{len(files)}.v2"
            files[name] = text.encode("utf-8" if rng.random() < 0.9 else "latin-1", errors="replace")
        start = None
        if rng.random() < 0.1:
            start = rng.choice([*HOSTILE_NAMES, "", "a.ros", "nope", "x" * 300, "$x", "1"])
            what.append(f"start {start[:20]!r}")
        folder = rng.choice(HOSTILE_FILES).replace("\n", "_") if rng.random() < 0.3 else f"p{number}"
        return FuzzInput(folder, files, keep_going=rng.random() < 0.5, check_cli=rng.random() < 0.1, what=what,
                         start=start)


def run_input(item: FuzzInput, root: Path) -> bool:
    """Translate the project in-process (the folder, or its one file) and check the properties."""
    folder = write_input(item, root)
    target = folder if len(item.files) > 1 or "folder" in item.what else folder / next(iter(item.files))
    sink = DiagnosticSink()
    out = transpile(target, sink, keep_going=False, start=item.start)
    check_diagnostics(sink, folder, START if item.start is not None else frozenset())
    if out is not None:
        check_translated(out, sink, root)
    elif item.keep_going:
        kept = DiagnosticSink()
        out = transpile(target, kept, keep_going=True, start=item.start)
        check_diagnostics(kept, folder, START if item.start is not None else frozenset())
        if out is not None:
            compile_all(out.files, strict=False)
    if item.check_cli and item.start is None:
        check_matches_translate(target, sink)
    return (root / "out").is_dir()


@pytest.mark.parametrize("part", range(FUZZ_PARTS))
def test_vplus_pipeline_fuzz(part: int, tmp_path_factory: pytest.TempPathFactory,
                             monkeypatch: pytest.MonkeyPatch) -> None:
    seeds = vplus_seeds()
    seed, rng = part_rng(part)
    mutator = Mutator(rng, seeds)
    monkeypatch.setenv("GPL2PY_TRACEBACK", "1")  # a bug is an exception here, not a GPL9000
    monkeypatch.delenv("GPL2PY_MAX_SOURCE_MB", raising=False)
    translated = run_part("V+ pipeline fuzz", part, seed, part_inputs(FUZZ_INPUTS, FUZZ_PARTS, part),
                          mutator.project, run_input, tmp_path_factory)
    assert translated > 0  # some inputs reached the end of the pipeline

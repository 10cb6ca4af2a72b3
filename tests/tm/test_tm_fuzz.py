"""Fuzz the TMscript front end: script projects through the pipeline, Listen-node packets through
``translate_packet`` (bad input gets a clear answer, as GPL's fuzz holds it).

Seeds: the manual's examples (``tests/tm/examples/*.tms``) and the TMscript written in the TM
tests (their string constants: whole scripts with a ``main`` block, and statement lists, which
are packets; a ``$TMSCT`` frame's script part too), read from the test modules with ``ast``.
Each input is a mutant: lines deleted, duplicated, swapped or borrowed; tokens replaced by
TMscript keywords, operators or hostile names; bytes inserted, deleted or flipped; declared names
renamed consistently to Python keywords, builtins, the runtime's names (``tm``, ``v``, ``script``)
and dunders; blocks of every kind (if/else, while, do-while, for, switch, bare braces) nested
around CPython's limit and past the parser's, long operator chains, deep parentheses, huge and
odd literals, strings with escapes and unterminated ones.

**Scripts** (one file or a folder of them, hostile file names) go through ``transpile`` with
``GPL2PY_TRACEBACK=1``: no exception, no GPL9000; a translation without errors compiles (warnings
are errors) and imports without doing anything forbidden; ``--keep-going`` output compiles;
``check`` reports exactly what ``translate`` reports; every diagnostic has the
``file:line:col: severity GPLnnnn: message`` form; nothing is written outside the batch's folder.

**Packets** go through ``translate_packet`` as the Listen node calls it (lines joined by CRLF,
sometimes with the variables an earlier packet declared): it must never raise (nor give GPL9000),
every error has a position in the packet, and a packet without errors is Python that compiles.

``GPL2PY_TM_FUZZ_INPUTS`` inputs per run (default 1,500: scripts and packets, in ``FUZZ_PARTS``
parts with a random stream each), ``GPL2PY_FUZZ_SEED`` (fixed by default; ``random`` for a new one).
"""

from __future__ import annotations

import ast
import io
import os
import re
import tokenize
from pathlib import Path

import pytest

import gplrt.tm  # noqa: F401  # (its first import loads native code: before the audit of generated packages)
from fuzzkit import (BUILTIN_NAMES, FuzzInput, HOSTILE_FILES, PYTHON_HOSTILE, TextMutations, check_diagnostics,
                     check_matches_translate, check_translated, compile_all, compile_py, part_inputs, part_rng,
                     run_part, write_input)
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.tmscript.pipeline import translate_packet
from gpl2py.tmscript.semantics.library import BUILTINS
from gpl2py.tmscript.syntax.lexer import KEYWORDS
from gpl2py.transpile import transpile

FUZZ_INPUTS = int(os.environ.get("GPL2PY_TM_FUZZ_INPUTS", "1500"))
FUZZ_PARTS = 4
HERE = Path(__file__).parent

#: Names the generated Python uses for TMscript (gpl2py/tmscript/lower) and the runtime's.
TM_GENERATED = ["tm", "v", "script", "run", "main", "closestop", "errorstop", "define", "g", "_g", "_v", "_f",
                "_i", "_r", "_loop", "_brk", "_sw", "_case", "_ret", "self", "IO", "Robot", "Point", "Base", "TCP",
                "var_i", "g_count"]
HOSTILE_NAMES = [n for n in sorted({*PYTHON_HOSTILE, *BUILTIN_NAMES, *TM_GENERATED, *list(BUILTINS)[:40]})
                 if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", n) and n not in KEYWORDS]
REPLACEMENTS = ["if", "else", "while", "do", "for", "switch", "case", "default", "break", "continue", "return",
                "void", "int", "float", "double", "byte", "bool", "string", "define", "main", "true", "false",
                "{", "}", "(", ")", "[", "]", ";", ",", ":", "?", "=", "==", "+", "-", "*", "/", "%", "++", "--",
                "<<", ">>=", "&&", "||", "!", "~", '"', "'", "\\", "//", "/*", "*/", "0x", "0b", "1e", "1e400",
                ".5", "\n", "\r\n", "\t", "é", "\x00", "Display", "ThreadRun", "IO", "Robot", "[0]", "\"\\\"\""]
#: What the comments the fuzz adds say after their marker: what could end a line in Python or an
#: editor, code, quotes, backslashes, long words and long sentences, a lone CR (a line end for
#: TMscript: the rest is code).
COMMENT_TEXTS = ["", " note", "\x0bimport os", "\u2028y = 1", "\x0c\x1c\x1d\x1e\x85z", '";__import__("os").system("x")',
                 '"""', "\\", " \\", "\t\ttabs", "\x00\x01\x7f", "é" * 50, " word" * 40, "x" * 300, "*", "/", "#",
                 " # noqa", "\rDisplay(1)", " {", " }", " else", "\u00a0nbsp", "\uffff"]
#: The marker each added comment starts with (``fzc12_``): the check finds them in the Python.
MARKER = re.compile(r"fzc\d+_")
TOKEN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*|\d+(?:\.\d*)?|\"(?:[^\"\\\n]|\\.)*\"|[ \t]+|\r?\n|.", re.DOTALL)
DECLARED = re.compile(r"(?m)\b(?:byte|int|float|double|bool|string|void)(?:\[\])?[ \t]+([A-Za-z_][A-Za-z0-9_]*)")


def _constants() -> list[str]:
    """The string constants of the TM test modules, and the scripts of their ``$TMSCT`` frames."""
    out = []
    for path in sorted(HERE.glob("test_*.py")):
        if path.name.startswith("test_tm_fuzz"):
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Constant) and isinstance(node.value, (str, bytes)):
                text = node.value.decode("latin-1") if isinstance(node.value, bytes) else node.value
                m = re.fullmatch(r"(?s)\$TMSCT,\d+,[^,]*,(.*),\*[0-9A-Fa-f]{2}\r\n", text)
                if "gpl2py:" not in text:  # (an ignore directive: check applies it, transpile does not)
                    out.append(m.group(1) if m else text)
    return out


def seeds() -> tuple[list[str], list[str]]:
    """(scripts, packets): whole scripts have a main or define block; packets are statement lists
    (a constant with an assignment, a call or a declaration)."""
    scripts = [p.read_text(encoding="utf-8") for p in sorted((HERE / "examples").glob("*.tms"))]
    packets = []
    for text in _constants():
        if re.search(r"(?m)^\s*(main|define)\s*$", text) and "{" in text:
            scripts.append(text)
        elif len(text) >= 6 and re.search(r"[=(]", text) and not text.startswith(("$", "TM", "GPL")) \
                and "\x00" not in text:
            packets.append(text.replace("\r\n", "\n"))
    assert len(scripts) >= 14 and len(packets) >= 10, (len(scripts), len(packets))
    # every script's main body is a packet too
    for s in scripts:
        m = re.search(r"(?ms)^main\s*\{\n(.*?)^\}", s)
        if m:
            packets.append(m.group(1))
    return scripts, packets


#: The blocks ``op_deep`` nests: a head (``{i}`` the depth, ``{o}`` the opening brace, on the head's
#: line or its own) and the tail that closes it.
_NESTED = {
    "if": ("if (i == {i}){o}", "}\n"),
    "ifelse": ("if (i == {i}){o}", "}\nelse\n{\nDisplay(1)\n}\n"),
    "while": ("while (i < {i}){o}", "}\n"),
    "do": ("do{o}", "} while (false)\n"),
    "for": ("for (int f{i} = 0; f{i} < 1; f{i}++){o}", "}\n"),
    "switch": ("switch (i){o}case {i}:\n", "break\n}\n"),
    "brace": ("{{\n", "}\n"),
}


class Mutator(TextMutations):
    """Mutations of TMscript by lines, tokens and bytes, hostile renames, and deep or long shapes."""

    def __init__(self, rng: object, scripts: list[str], packets: list[str]) -> None:
        self.rng = rng  # type: ignore[assignment]
        self.scripts = scripts
        self.packets = packets
        self.donors = scripts + packets

    def mutate(self, text: str, what: list[str], packet: bool) -> str:
        rng = self.rng
        self.packet = packet  # (where a block goes: a packet is a statement list)
        declared = sorted(set(DECLARED.findall(text)) - KEYWORDS)
        for _ in range(rng.choice([0, 1, 1, 2, 2, 3, 5])):
            op = rng.choices(
                ["rename", "rename_pair", "line_del", "line_dup", "line_swap", "line_donor", "token",
                 "token_hostile", "byte_ins", "byte_del", "byte_flip", "deep", "long_expr", "literal", "string"],
                weights=[8, 3, 3, 2, 2, 2, 5, 2, 1, 1, 1, 2, 1, 1, 1])[0]
            what.append(op)
            text = getattr(self, "op_" + op)(text, declared)
        if rng.random() < 0.3:  # (last: no later mutation moves a comment into code)
            what.append("comment")
            text = self.add_comments(text)
        return text

    def add_comments(self, text: str) -> str:
        """One to three comments, each starting with a marker of its own: a ``//`` line, a ``//`` at
        the end of a line, a ``/* */`` on a line or over three lines."""
        rng = self.rng
        lines = text.split("\n")
        for _ in range(rng.choice([1, 1, 2, 3])):
            marker = f"fzc{rng.randrange(10**6)}_"
            body = marker + rng.choice(COMMENT_TEXTS)
            at = rng.randrange(len(lines) + 1)
            form = rng.choice(["line", "end", "block", "lines"])
            if form == "end" and at < len(lines):
                cr = "\r" if lines[at].endswith("\r") else ""
                lines[at] = lines[at][:len(lines[at]) - len(cr)] + " // " + body + cr
            elif form == "block":
                lines.insert(at, f"/* {body} */")
            elif form == "lines":
                lines.insert(at, f"  /* {body}\n   {marker}more\n */")
            else:
                lines.insert(at, f"// {body}")
        return "\n".join(lines)

    def hostile_name(self) -> str:
        name = self.rng.choice(HOSTILE_NAMES)
        return name + "_" if self.rng.random() < 0.15 else name

    def _rename(self, text: str, old: str, new: str) -> str:
        return re.sub(rf"(?<![A-Za-z0-9_]){re.escape(old)}(?![A-Za-z0-9_])", new, text)

    def op_rename(self, text: str, declared: list[str]) -> str:
        return self._rename(text, self.rng.choice(declared), self.hostile_name()) if declared else text

    def op_rename_pair(self, text: str, declared: list[str]) -> str:
        if len(declared) < 2:
            return self.op_rename(text, declared)
        first, second = self.rng.sample(declared, 2)
        base = self.rng.choice(HOSTILE_NAMES).rstrip("_") or "list"
        return self._rename(self._rename(text, first, base), second, base + "_")

    def op_token(self, text: str, declared: list[str]) -> str:
        return self.mutate_piece(text, TOKEN, REPLACEMENTS)

    def op_token_hostile(self, text: str, declared: list[str]) -> str:
        words = list(re.finditer(r"(?<![A-Za-z0-9_\"])[A-Za-z_][A-Za-z0-9_]*", text))
        if not words:
            return text
        m = self.rng.choice(words)
        return text[:m.start()] + self.hostile_name() + text[m.end():]

    def _in_body(self, text: str, body: str) -> str:
        """``body`` after the first brace of a block (a packet: on a random line)."""
        rng = self.rng
        if self.packet:
            lines = text.split("\n")
            lines.insert(rng.randrange(len(lines) + 1), body.rstrip("\n"))
            return "\n".join(lines)
        braces = [m.end() for m in re.finditer(r"(?m)^\s*\{[^\n]*\n", text)]
        if not braces:
            return text + "main\n{\n" + body + "}\n"
        at = rng.choice(braces)
        return text[:at] + body + text[at:]

    def op_deep(self, text: str, declared: list[str]) -> str:
        rng = self.rng
        n = rng.choice([5, 19, 20, 21, 22, 49, 50, 51, 100, 600])
        kinds = ["if", "ifelse", "while", "do", "for", "switch", "brace"]
        kind = rng.choice(kinds + ["mix"])
        brace_line = rng.random() < 0.5  # "{" on its own line, or at the end of the head
        heads, tails = [], []
        for i in range(n):
            head, tail = _NESTED[rng.choice(kinds) if kind == "mix" else kind]
            heads.append(head.format(i=i, o="\n{\n" if brace_line else " {\n"))
            tails.append(tail)
        inner = rng.choice(["Display(\"x\")\n", "break\n", "continue\n", "return\n", "i++\n", ""])
        body = "int i = 0\n" + "".join(heads) + inner + "".join(reversed(tails))
        if rng.random() < 0.2:
            body = body[:rng.randrange(len(body) + 1)]
        return self._in_body(text, body)

    def op_long_expr(self, text: str, declared: list[str]) -> str:
        rng = self.rng
        n = rng.choice([100, 300, 1000, 3000])
        shape = rng.random()
        if shape < 0.4:
            expr = rng.choice([" + ", " * ", " && ", " | ", " - ", " / ", " << ", " ? 1 : "]).join(["1"] * n)
        elif shape < 0.6:
            expr = "(" * n + "1" + ")" * n
        elif shape < 0.8:
            expr = rng.choice(["-", "!", "~", "(int)", "++"]) * n + "1"
        else:
            expr = "Length(" * n + '"a"' + ")" * n
        return self._in_body(text, f"{rng.choice(['int', 'string', 'bool', 'float', 'var'])} fz = {expr}\n")

    def op_literal(self, text: str, declared: list[str]) -> str:
        rng = self.rng
        lit = rng.choice(["9" * 310, "1" + "0" * 4301, "1e400", "1e-400", "0x" + "F" * 40, "0b" + "1" * 80,
                          "2147483648", "-2147483649", "1.5e308", "0x", "0b2", "1e", "1.2.3", "99999999999999999999"])
        numbers = list(re.finditer(r"(?<![\w.])\d+(?![\w.])", text))
        if numbers and rng.random() < 0.7:
            m = rng.choice(numbers)
            return text[:m.start()] + lit + text[m.end():]
        return self._in_body(text, f"{rng.choice(['int', 'float', 'double', 'byte'])} fz = {lit}\n")

    def op_string(self, text: str, declared: list[str]) -> str:
        rng = self.rng
        s = rng.choice(['"a\\"b"', '"\\', '"open', "'x'", '"\\u0000"', '"\\x"', '"' + "é" * 50 + '"',
                        '"{0}"', '"\\n\\r\\t"', '"""', '"' + "x" * 5000 + '"', '"\\\\"', "\"'\"'\""])
        return self._in_body(text, f"string fz = {s}\nDisplay({s})\n")

    # -- inputs
    def script_input(self, number: int) -> FuzzInput:
        rng = self.rng
        what: list[str] = []
        kind = rng.choices(["one", "folder"], weights=[85, 15])[0]
        what.append(kind)
        files: dict[str, bytes] = {}
        for _ in range(1 if kind == "one" else rng.randint(1, 3)):
            text = self.mutate(rng.choice(self.scripts), what, packet=False)
            stem = rng.choice(HOSTILE_FILES) if rng.random() < 0.3 else f"s{len(files)}"
            name = f"{stem}.{rng.choice(['tms', 'tms', 'tmscript', 'TMS'])}"
            if name in files:
                name = f"s{len(files)}.tms"
            files[name] = text.encode("utf-8" if rng.random() < 0.9 else "latin-1", errors="replace")
        folder = rng.choice(HOSTILE_FILES).replace("\n", "_") if rng.random() < 0.3 else f"p{number}"
        return FuzzInput(folder, files, keep_going=rng.random() < 0.5, check_cli=rng.random() < 0.1, what=what)

    def packet_input(self, number: int) -> FuzzInput:
        what = ["packet"]
        texts = [self.mutate(self.rng.choice(self.packets), what, packet=True)
                 for _ in range(self.rng.choice([1, 1, 2, 3]))]  # later packets see the earlier's variables
        return FuzzInput(f"k{number}", {f"packet{i}.txt": t.encode("utf-8", "surrogatepass")
                                        for i, t in enumerate(texts)}, what=what)

    def make(self, number: int) -> FuzzInput:
        return self.packet_input(number) if self.rng.random() < 0.4 else self.script_input(number)


def run_packets(item: FuzzInput) -> bool:
    """The packets of ``item`` in turn through ``translate_packet``, as the Listen node does."""
    known: dict[str, object] = {}
    ok = False
    for name, data in item.files.items():
        script = data.decode("utf-8", "surrogatepass").replace("\n", "\r\n")
        packet = translate_packet(script, known, name=name)  # type: ignore[arg-type]
        lines = script.count("\n") + script.count("\r") + 2
        for d in [*packet.errors, *packet.warnings]:
            assert d.code != "GPL9000", d.header()
            assert d.span is not None and 1 <= d.span.line <= lines and d.span.col >= 1, d.header()
            assert d.header().isprintable(), d.header()
        if not packet.errors:
            assert packet.python, "a packet without errors and without Python"
            compile_py(packet.python, name)
            if "comment" in item.what:
                check_comments({name: script}, {f"{name}.py": packet.python})
            known.update(packet.declared)
            ok = True
    return ok


def check_comments(sources: dict[str, str], generated: dict[str, str]) -> None:
    """Each comment the fuzz added (its marker) is in the Python of a translation without errors,
    and only ever inside a Python comment (never code nor a string: its text cannot escape)."""
    markers = {m for text in sources.values() for m in MARKER.findall(text)}
    carried: set[str] = set()
    for name, py in generated.items():
        if not name.endswith(".py"):
            continue
        in_comments = [m for t in tokenize.generate_tokens(io.StringIO(py).readline) if t.type == tokenize.COMMENT
                       for m in MARKER.findall(t.string)]
        assert len(in_comments) == len(MARKER.findall(py)), (name, "a comment's text outside a comment")
        carried.update(in_comments)
    assert markers <= carried, ("comments lost", sorted(markers - carried))


def run_input(item: FuzzInput, root: Path) -> bool:
    if item.what[0] == "packet":
        write_input(item, root)  # (kept for the failure message)
        return run_packets(item)
    folder = write_input(item, root)
    target = folder if "folder" in item.what else folder / next(iter(item.files))
    sink = DiagnosticSink()
    out = transpile(target, sink, keep_going=False, language="tmscript")
    check_diagnostics(sink, folder)
    if out is not None:
        check_translated(out, sink, root)
        if "comment" in item.what:
            check_comments({n: d.decode("utf-8", "replace") for n, d in item.files.items()}, out.files)
    elif item.keep_going:
        kept = DiagnosticSink()
        out = transpile(target, kept, keep_going=True, language="tmscript")
        check_diagnostics(kept, folder)
        if out is not None:
            compile_all(out.files, strict=False)
    if item.check_cli:
        check_matches_translate(target, sink)
    return (root / "out").is_dir()


@pytest.mark.parametrize("part", range(FUZZ_PARTS))
def test_tmscript_fuzz(part: int, tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch) -> None:
    scripts, packets = seeds()
    seed, rng = part_rng(part)
    mutator = Mutator(rng, scripts, packets)
    monkeypatch.setenv("GPL2PY_TRACEBACK", "1")  # a bug is an exception here, not a GPL9000
    translated = run_part("TMscript fuzz", part, seed, part_inputs(FUZZ_INPUTS, FUZZ_PARTS, part),
                          mutator.make, run_input, tmp_path_factory)
    assert translated > 0

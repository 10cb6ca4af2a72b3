"""Fuzz the front end and the whole pipeline (issue 12: untrusted GPL must never run host Python).

Two kinds of fuzzing live here.

**Lexer and parser** (``test_*_never_crash``): realistic GPL (the manual examples in ``examples/``
plus a dense module written for this test) mutated at two levels -- word/operator pieces (delete,
duplicate, swap, replace with a GPL keyword or operator) and characters (delete, duplicate, swap,
insert random bytes/Unicode, insert the characters the lexer treats specially) -- and purely random
text over a GPL-flavoured alphabet.  Each Hypothesis example checks several mutants; each test
asserts the number of inputs it actually fed.  Besides "no exception", every run checks that all
diagnostics have a valid position and render, and that the token stream ends with EOF.

**The pipeline, seeded from real code** (``test_pipeline_fuzz_seeded_from_the_corpus``): the
vendor's TCS (``../shared/corpus``, read in place) mutated by lines, tokens and bytes, with hostile
names -- identifiers renamed consistently to Python keywords, builtins, runtime helpers, names
gpl2py generates and dunders; hostile source file names, folder names, ProjectName and ProjectStart
values -- in one-file, several-file, folder and whole-TCS projects -- and with the shapes that
once gave internal errors (issue 20): decimal literals past the Double range and past Python's
4,300-digit limit, deep nesting in module-level initialisers, operator chains of up to 5,000 terms
and Dim lists of up to 5,000 names (sizes where an input takes seconds: the speed of a
million-term chain is benchmarks/memory.py's subject).  Each input goes through ``transpile`` in-process
(``GPL2PY_TRACEBACK=1``, so a bug is an exception here rather than a GPL9000); one with errors
also with ``--keep-going``, or with every error ignored, and some through ``gpl2py check --json``.
The properties:

* no exception (no traceback, no internal error GPL9000), whatever the errors and whether they
  are kept or ignored (the codes translated ignored are printed);
* a translation without errors (what ``translate`` exits 0 with) writes modules that compile
  and a source map that is JSON; ``--keep-going`` output and output with the errors ignored
  compile too;
* ``check`` reports exactly what ``translate`` reports;
* nothing is written outside the batch's temporary folder (an audit hook sees every write);
* every diagnostic is ``file:line:col: severity GPLnnnn: message`` (only the three about the
  path itself, GPL1400-GPL1402, have no file to point at).

At least 5,000 inputs per run (``GPL2PY_FUZZ_INPUTS`` for more); the seed is fixed so CI is
repeatable (``GPL2PY_FUZZ_SEED`` to explore others; a failure names its seed, part and input number
and keeps the failing project).  The inputs come in ``FUZZ_PARTS`` tests of their own, each drawing
from its own random stream (the seed and the part's number), so that a parallel run (``pytest -n``)
spreads them over the cores.  Each part runs in batches sharing one temporary folder each, and
prints the slowest input's time (CPU and wall; never asserted: the machine may be shared).  The
machinery the V+ and TMscript fuzzes share with this one (the audit hook, the checks, the batch loop,
line and byte mutations) is in ``tests/fuzzkit.py``.
"""

from __future__ import annotations

import keyword
import os
import random
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from fuzzkit import (FuzzInput, HOSTILE_FILES, TextMutations, check_diagnostics, check_matches_translate,
                     check_translated, compile_all, part_inputs, part_rng, run_part, write_input)
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.lower.names import RUNTIME_NAMES
from gpl2py.selection import Selection
from gpl2py.source import SourceFile
from gpl2py.gpl.syntax.lexer import tokenize
from gpl2py.gpl.syntax.parser import parse
from gpl2py.gpl.syntax.tokens import KEYWORDS, TokenKind
from gpl2py.transpile import transpile
from gpltest import corpus_dir

EXAMPLES = Path(__file__).parent / "examples"

DENSE = """' dense module exercising most of the grammar
#Region "fuzz"
Module Fuzz
    Public Shared counter As Integer = &H10 ' trailing
    Private Const LIMIT As Double = 1E+32
    Dim grid(3, 4) As Integer, names() As String
    Delegate Function Op(ByVal a As Integer) As Integer
    Public Class Box
        Private size_in As Integer
        Public Property Size As Integer
            Get
                Return size_in
            End Get
            Set (value As Integer)
                size_in = value
            End Set
        End Property
        Public Sub New (ByVal v As Integer)
            Me.size_in = v
        End Sub
    End Class
    Public Function Calc(ByRef x As Double, Optional ByVal k As Integer = 2) As Double
        Dim i As Integer
        Dim exc As New Exception
        For i = 0 To 10 Step 2
            If i Mod 3 = 0 Then Exit For Else x += i ^ -2
            Select Case i
                Case 1, 2 To 4, Is > 8
                    x = x * -k \\ 3 & "s" << 1
                Case Else
                    GoTo done
            End Select
        Next i
        Try
retry:
            Move.Loc(loc1, prof)
            Move.WaitForEOM
        Catch exc
            If exc.ErrorCode = -153 Then GoTo retry
            Throw exc
        Finally
            Exit Try
        End Try
        Do While Not x Is Nothing AndAlso x <> 0 OrElse x > 1 Xor True
            x -= 1 : x = 0
        Loop
        Console.WriteLine("a ""q"" " & _
            CStr(x) _ ' note
            & "b")
done:
        Return x
    End Function
End Module
#End Region
"""

CORPUS = [DENSE] + [p.read_text(encoding="utf-8") for p in sorted(EXAMPLES.glob("*.gpl"))]
PIECE = re.compile(r"\w+|[ \t]+|\r?\n|.", re.DOTALL)
REPLACEMENTS = [
    "If", "Then", "Else", "ElseIf", "End", "End If", "Sub", "Function", "Next", "Loop", "Do", "For",
    "While", "Select", "Case", "Try", "Catch", "Finally", "Module", "Class", "Property", "Get", "Set",
    "Dim", "As", "New", "(", ")", ",", ".", ":", "=", "&H", "&O", '"', "'", "#", " _", "_", "\n",
    "\r", "<<=", "Not", "Is", "IsNot", "ReDim", "Preserve", "GoTo", "Exit", "Return", "AddressOf",
    "Me", "Nothing", "1E", ".5", "&HEAD", "With", "GoSub", "On Error", "é", "\x00", "\t",
]
ALPHABET = st.sampled_from(
    list("abcxyzABC019_ .,()=<>+-*/\\^&:'\"#\n\r\t") + ["If ", "Then ", "End ", "Sub ", "Dim ", " As ", "\u00e9", "\u2013"]
)

FUZZ_SETTINGS = settings(
    max_examples=700,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)


#: Inputs checked so far in this process: each test asserts how many it fed, so the "at least
#: 5,000 inputs per run" promise is measured, not inferred from the settings.
CHECKED = [0]
MIN_INPUTS_PER_TEST = 1700  # three tests: over 5,000 in all (nominally 2,100 + 2,100 + 3,500)


def check(text: str) -> None:
    """The property: tokenize and parse return normally with well-formed diagnostics."""
    CHECKED[0] += 1
    source = SourceFile("fuzz.gpl", text)
    sink = DiagnosticSink()
    toks = tokenize(source, sink)
    assert toks and toks[-1].kind is TokenKind.EOF
    sink = DiagnosticSink()
    unit = parse(source, sink)
    assert unit.path == "fuzz.gpl"
    n_lines = text.count("\n") + text.count("\r") + 2
    for d in sink:
        assert d.span is not None
        assert 1 <= d.span.line <= n_lines and d.span.col >= 1
        d.render(source)


def mutate_pieces(text: str, ops: list[tuple[int, int, int, int]]) -> str:
    pieces = PIECE.findall(text)
    for op, i, j, r in ops:
        if not pieces:
            break
        i %= len(pieces)
        j %= len(pieces)
        if op == 0:
            del pieces[i]
        elif op == 1:
            pieces.insert(i, pieces[i])
        elif op == 2:
            pieces[i], pieces[j] = pieces[j], pieces[i]
        else:
            pieces[i] = REPLACEMENTS[r % len(REPLACEMENTS)]
    return "".join(pieces)


def mutate_chars(text: str, ops: list[tuple[int, int, int, str]]) -> str:
    chars = list(text)
    for op, i, j, s in ops:
        if not chars:
            chars = list(s)
            continue
        i %= len(chars)
        j %= len(chars)
        if op == 0:
            del chars[i : i + 1 + j % 4]
        elif op == 1:
            chars.insert(i, chars[i])
        elif op == 2:
            chars[i], chars[j] = chars[j], chars[i]
        else:
            chars[i:i] = list(s)
    return "".join(chars)


piece_ops = st.lists(
    st.tuples(st.integers(0, 3), st.integers(0, 10**6), st.integers(0, 10**6), st.integers(0, 1000)),
    min_size=1,
    max_size=6,
)
char_ops = st.lists(
    st.tuples(
        st.integers(0, 3),
        st.integers(0, 10**6),
        st.integers(0, 10**6),
        st.one_of(
            st.binary(min_size=1, max_size=4).map(lambda b: b.decode("latin-1")),
            st.sampled_from(["_", '"', "'", "#", "&H", "\n", " _\n", ":", "\r\n", "\u00e9", "\ufeff"]),
            st.text(max_size=3),
        ),
    ),
    min_size=1,
    max_size=6,
)


@FUZZ_SETTINGS
@given(base=st.sampled_from(CORPUS), mutations=st.lists(piece_ops, min_size=3, max_size=3))
def piece_mutations(base: str, mutations: list[list[tuple[int, int, int, int]]]) -> None:
    for ops in mutations:  # three mutants per example
        check(mutate_pieces(base, ops))


@FUZZ_SETTINGS
@given(base=st.sampled_from(CORPUS), mutations=st.lists(char_ops, min_size=3, max_size=3))
def character_mutations(base: str, mutations: list[list[tuple[int, int, int, str]]]) -> None:
    for ops in mutations:
        check(mutate_chars(base, ops))


@FUZZ_SETTINGS
@given(texts=st.lists(st.lists(ALPHABET, max_size=80).map("".join), min_size=2, max_size=2), raw=st.text(max_size=60))
def random_text(texts: list[str], raw: str) -> None:
    for t in texts:
        check(t)
        check("Module M\nSub S()\n" + t + "\nEnd Sub\nEnd Module\n")
    check(raw)


def fed(search: Callable[[], None]) -> int:
    """Run one Hypothesis search and return how many inputs it checked."""
    before = CHECKED[0]
    search()
    return CHECKED[0] - before


def test_piece_mutations_never_crash() -> None:
    assert fed(piece_mutations) >= MIN_INPUTS_PER_TEST


def test_character_mutations_never_crash() -> None:
    assert fed(character_mutations) >= MIN_INPUTS_PER_TEST


def test_random_text_never_crashes() -> None:
    assert fed(random_text) >= MIN_INPUTS_PER_TEST


# ==================================================================================================
# The whole pipeline, seeded from the corpus


FUZZ_INPUTS = int(os.environ.get("GPL2PY_FUZZ_INPUTS", "5000"))
FUZZ_PARTS = 10  # tests the inputs are shared among (each with its own random stream)

#: Names the generated Python must never confuse with a GPL name: Python keywords that are not GPL
#: keywords, builtins, names of the runtime and of what gpl2py generates, dunders, and the same
#: with underscores added (list / list_ / list__ are three GPL names).
HOSTILE_NAMES = sorted({
    *(k for k in keyword.kwlist + keyword.softkwlist if k.isidentifier() and k.lower() not in KEYWORDS and k != "_"),
    "print", "list", "str", "int", "len", "range", "open", "eval", "exec", "compile", "globals", "locals",
    "object", "super", "property", "staticmethod", "classmethod", "isinstance", "float", "bool", "min", "max",
    "chr", "BaseException", "type", "id", "input", "vars", "getattr", "setattr", "sys", "os", "math", "self",
    "cls", "init", "main", "PROJECT", "_this", "_result", "_reset", "_init", "_e", "_g1", "_sel1", "_jump1",
    "_enter1", "_k1", "_s_Main_x", "_stubs", "_session", "_VARIABLES", "set_x", "_u_x",
    "__init__", "__class__", "__dict__", "__slots__", "__name__", "__file__", "__builtins__", "__import__",
    "__getattr__", "__all__", "__path__", "__main__", "__globals__", "__reduce_ex__",
    *sorted(RUNTIME_NAMES),
    "ChkInt32", "ToInt32", "Current", "Checkpoint", "RegisterPackage", "UseProcedures", "GplEntry",
    "GplArray", "Simulation", "Location", "CStr", "Sys", "Os", "Init", "Main", "Con", "Nul", "Numpy", "Gplrt",
})
HOSTILE_NAMES = [n for n in HOSTILE_NAMES if re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*|_+[A-Za-z0-9][A-Za-z0-9_]*", n)
                 and n.lower() not in KEYWORDS]  # a GPL keyword would only make a syntax error
#: ProjectName / ProjectStart values.
HOSTILE_VALUES = [
    'x""";import os;os.system("id");"""', "'''", "\\N", "\\", "numpy", "gplrt", "sys", "__init__", "..",
    "a/b", "../../x", "", "\u202e", "x" * 300, "Main.Main", "Main", "Nope", "print", "__import__('os')",
    "a\x0bb", "a\x85b", "a\u2028b", "# comment", "{0}", "%s",
]
IDENT = re.compile(r"(?<![A-Za-z0-9_])[A-Za-z_][A-Za-z0-9_]*")
DECLARED = re.compile(r"(?im)^[ \t]*(?:(?:public|private|shared|static|const|dim|byval|byref|optional)[ \t]+)*"
                      r"(?:dim|const|sub|function|module|class|property|static)[ \t]+([A-Za-z_][A-Za-z0-9_]*)")
# names declared on one line: parameters, and the names of a Dim list
ONE_LINE_NAMES = re.compile(r"(?i)(?:\b(?:byval|byref|dim)[ \t]+|,[ \t]*)([A-Za-z_][A-Za-z0-9_]*)(?=[ \t]*(?:\(\))?[ \t]*(?:,|as\b))")
SUB = re.compile(r"(?im)^[ \t]*public[ \t]+sub[ \t]+([A-Za-z_][A-Za-z0-9_]*)[ \t]*(?:\([ \t]*\))?[ \t]*(?:'.*)?$")
PROCEDURE = re.compile(r"(?ims)^[ \t]*(?:public[ \t]+|private[ \t]+)?(?:shared[ \t]+)?(sub|function)[ \t].*?"
                       r"^[ \t]*end[ \t]+\1\b[^\n]*\n")
@dataclass
class Seed:
    """One corpus source file: its text, and the names it declares."""

    name: str
    text: str
    declared: list[str]


def corpus_seeds() -> tuple[list[Seed], list[Path]]:
    """Every distinct corpus source, and the corpus projects (folders with Project.gpr)."""
    root = corpus_dir()
    seeds: dict[str, Seed] = {}
    for path in sorted(root.rglob("*")):
        if path.suffix.lower() in (".gpl", ".gpo") and path.is_file():
            data = path.read_bytes()
            if data.startswith(b"'#Protected|"):
                continue
            text = data.decode("utf-8", errors="replace") if _utf8(data) else data.decode("latin-1")
            seeds.setdefault(text, Seed(path.name, text, sorted(set(DECLARED.findall(text)))))
    projects = sorted(p.parent for p in root.rglob("Project.gpr"))
    assert len(seeds) >= 14 and len(projects) >= 2, (len(seeds), projects)
    return list(seeds.values()), projects


def clean_seeds(seeds: list[Seed], root: Path) -> list[Seed]:
    """The seeds that translate on their own without an error (more as gpl2py accepts more of
    the corpus)."""
    out = []
    for i, seed in enumerate(seeds):
        path = root / f"seed{i}.gpl"
        path.write_text(seed.text, encoding="utf-8", errors="replace")
        if transpile(path, DiagnosticSink()) is not None:
            out.append(seed)
    return out


def _utf8(data: bytes) -> bool:
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        return False
    return True


class Mutator(TextMutations):
    """Mutations of real GPL by lines, tokens and bytes, and hostile renames."""

    def __init__(self, rng: random.Random, seeds: list[Seed], clean: list[Seed]) -> None:
        self.rng = rng
        self.seeds = seeds
        self.donors = [s.text for s in seeds]
        self.clean = clean or seeds
        self.small = [s for s in seeds if s.text.count("\n") <= 700]
        self.procedures = [m.group(0) for s in seeds for m in PROCEDURE.finditer(s.text)]

    def source(self) -> tuple[str, list[str]]:
        """A starting text: a corpus file that translates on its own (so that mutants reach the
        lowering), another small one, or procedures of any file in a module."""
        rng = self.rng
        r = rng.random()
        if r < 0.7:
            seed = rng.choice(self.clean if r < 0.45 else self.small)
            return seed.text, seed.declared
        procs = rng.sample(self.procedures, k=min(len(self.procedures), rng.randint(1, 3)))
        text = f"Module {rng.choice(['Fuzz', 'Cmd', 'Main', *HOSTILE_NAMES])}\n" + "".join(procs) + "End Module\n"
        return text, sorted(set(DECLARED.findall(text)))

    def mutate(self, text: str, declared: list[str], what: list[str]) -> str:
        rng = self.rng
        for _ in range(rng.choice([0, 1, 1, 2, 2, 3, 5])):
            op = rng.choices(
                ["rename", "rename_pair", "line_del", "line_dup", "line_swap", "line_donor", "token",
                 "token_hostile", "byte_ins", "byte_del", "byte_flip", "literal", "deep", "huge_literal",
                 "deep_init", "huge_expr", "long_dim"],
                weights=[12, 6, 3, 2, 2, 2, 3, 3, 1, 1, 1, 1, 1, 0.5, 0.5, 0.5, 0.5])[0]
            what.append(op)
            text = getattr(self, "op_" + op)(text, declared)
        return text

    # -- names
    def op_rename(self, text: str, declared: list[str]) -> str:
        """Rename a declared name everywhere (any case) to a hostile one: the code stays valid."""
        if not declared:
            return text
        old = self.rng.choice(declared)
        new = self.hostile_name()
        pattern = re.compile(rf"(?<![A-Za-z0-9_]){re.escape(old)}(?![A-Za-z0-9_])", re.IGNORECASE)
        return pattern.sub(new, text)

    def op_rename_pair(self, text: str, declared: list[str]) -> str:
        """Rename two names to one hostile name with and without a trailing underscore (list /
        list_): two GPL names that a careless mapping makes one Python name.  Half the time two
        names declared on one line (parameters of one procedure, ``Dim a, b``)."""
        together = [names for line in text.splitlines()
                    if len(names := sorted(set(ONE_LINE_NAMES.findall(line)))) >= 2]
        if together and self.rng.random() < 0.5:
            declared = self.rng.choice(together)
        if len(declared) < 2:
            return self.op_rename(text, declared)
        first, second = self.rng.sample(declared, 2)
        base = self.rng.choice(HOSTILE_NAMES).rstrip("_") or "list"
        for old, new in ((first, base), (second, base + "_")):
            pattern = re.compile(rf"(?<![A-Za-z0-9_]){re.escape(old)}(?![A-Za-z0-9_])", re.IGNORECASE)
            text = pattern.sub(new, text)
        return text

    def hostile_name(self) -> str:
        rng = self.rng
        name = rng.choice(HOSTILE_NAMES)
        r = rng.random()
        if r < 0.15:
            name += "_" * rng.randint(1, 2)
        elif r < 0.25:
            name = name.upper() if rng.random() < 0.5 else name.capitalize()
        return name

    # -- tokens
    def op_token(self, text: str, declared: list[str]) -> str:
        pieces = PIECE.findall(text)
        if pieces:
            i = self.rng.randrange(len(pieces))
            pieces[i] = self.rng.choice(REPLACEMENTS)
        return "".join(pieces)

    def op_token_hostile(self, text: str, declared: list[str]) -> str:
        matches = list(IDENT.finditer(text))
        if not matches:
            return text
        m = self.rng.choice(matches)
        return text[:m.start()] + self.hostile_name() + text[m.end():]

    def op_literal(self, text: str, declared: list[str]) -> str:
        """A string literal or comment carrying Python: it must stay text."""
        lines = text.splitlines(keepends=True)
        payload = self.rng.choice(['"x"";__import__(""os"").system(""id"")#"', "' \\\"\"\"; import os\n",
                                   '" \\N{x} \\x00 """ \'\'\' "', "'\\u2028 hidden\\x0b line"])
        lines.insert(self.rng.randrange(len(lines) + 1), payload + "\n")
        return "".join(lines)

    def op_deep(self, text: str, declared: list[str]) -> str:
        """Deep nesting around one line (blocks or expressions)."""
        lines = text.splitlines(keepends=True)
        if not lines:
            return text
        i = self.rng.randrange(len(lines))
        n = self.rng.choice([10, 19, 20, 21, 60, 99, 100, 160])
        kind = self.rng.choice(["If x Then\n|End If\n", "While x\n|End While\n", "Try\n|Catch e\nEnd Try\n",
                                "Select x\nCase 1\n|End Select\n", "Do\n|Loop\n", "For i = 1 To n\n|Next\n"])
        head, tail = kind.split("|")
        lines[i:i + 1] = [head * n, lines[i], tail * n]
        return "".join(lines)

    # -- the shapes of issue 20: each was a GPL9000 (or a run of over a minute) in mutants of real code
    def op_huge_literal(self, text: str, declared: list[str]) -> str:
        """A decimal literal of 310 digits or more (past the Double range), 4,301 or more (past
        Python's int() limit), or a real with as many: in place of a number, or a new line."""
        rng = self.rng
        digits = rng.choice([309, 310, 4301, 20_000])
        literal = rng.choice(["9", "1"]) + "0" * (digits - 1) + rng.choice(["", "", ".5", "E+2"])
        numbers = list(re.finditer(r"(?<![\w.&])\d+(?![\w.])", text))
        if numbers and rng.random() < 0.7:
            m = rng.choice(numbers)
            return text[:m.start()] + literal + text[m.end():]
        return self._in_procedure(text, f"fuzz_big = {literal}\n")

    def op_deep_init(self, text: str, declared: list[str]) -> str:
        """Deep nesting in a module-level initialiser (a Const, a variable, a Shared field, an
        Optional parameter's default): parentheses past the parser's limit, chained calls or
        members past the checker's recursion, unary operators."""
        rng = self.rng
        n = rng.choice([149, 150, 151, 478, 500])
        deep = rng.choice([("(" * n) + "1" + (")" * n), "a" + "(1)" * n, "a" + ".b" * n, "a" + ".b(1)" * n,
                           "-" * n + "1", "CInt(" * min(n, 200) + "1" + ")" * min(n, 200)])
        line = rng.choice([f"Public Const FUZZ_DEEP As Integer = {deep}\n", f"Private fuzz_deep As Double = {deep}\n",
                           f"Public Class FuzzDeep\nPublic Shared Y As Integer = {deep}\nEnd Class\n",
                           f"Sub FuzzDeep(Optional ByVal q As Integer = {deep})\nEnd Sub\n"])
        return self._in_module(text, line)

    def op_huge_expr(self, text: str, declared: list[str]) -> str:
        """A long operator chain in a procedure (real code builds strings over hundreds of continued
        lines).  At most 5,000 terms, a few seconds for an input (translated, kept or ignored,
        compiled and imported): a million took a minute before the memory work (branch memory),
        whose subject the speed is."""
        rng = self.rng
        n = rng.choice([300, 1000, 3000, 5000])
        op = rng.choice([" + ", " & ", " * ", " And ", " - "])
        term = rng.choice(["1", '"a"', "fuzz_x", "1.5"])
        continued = " _\n" if rng.random() < 0.3 else ""
        chain = (op.rstrip() + continued + " ").join([term] * n) if continued else op.join([term] * n)
        return self._in_procedure(text, f"fuzz_sum = {chain}\n")

    def op_long_dim(self, text: str, declared: list[str]) -> str:
        """A long Dim list, in a procedure or a module (quadratic once; at most 5,000 names here,
        for the same reason as op_huge_expr)."""
        rng = self.rng
        n = rng.choice([100, 500, 2000, 5000])
        names = ", ".join(f"fuzz_d{i}" + ("(3)" if i % 7 == 3 else "") for i in range(n))
        line = f"Dim {names} As {rng.choice(['Integer', 'String', 'Location', 'Nonsense'])}\n"
        return self._in_procedure(text, line) if rng.random() < 0.5 else self._in_module(text, line)

    def _in_module(self, text: str, line: str) -> str:
        """``line`` after a ``Module`` line (the start of the text when there is none)."""
        heads = [m.end() for m in re.finditer(r"(?im)^[ \t]*Module[ \t]+\w+[^\n]*\n", text)]
        at = self.rng.choice(heads) if heads else 0
        return text[:at] + line + text[at:]

    def _in_procedure(self, text: str, line: str) -> str:
        """``line`` after a ``Sub``/``Function`` line (after a Module line when there is none)."""
        heads = [m.end() for m in re.finditer(r"(?im)^[ \t]*(?:(?:public|private|shared)[ \t]+)*(?:sub|function)[ \t][^\n]*\n", text)]
        if not heads:
            return self._in_module(text, line)
        at = self.rng.choice(heads)
        return text[:at] + line + text[at:]

    # -- projects
    def project(self, number: int, whole: list[Path]) -> FuzzInput:
        rng = self.rng
        what: list[str] = []
        kind = rng.choices(["one", "several", "folder", "tcs"], weights=[70, 20, 8, 2])[0]
        what.append(kind)
        files: dict[str, bytes] = {}
        names: list[str] = []
        if kind == "tcs":
            root = rng.choice(whole)
            sources = [p for p in sorted(root.iterdir()) if p.suffix.lower() in (".gpl", ".gpo")]
            victim = rng.choice(sources)
            for p in sources:
                text = p.read_bytes().decode("latin-1")
                if p == victim:
                    text = self.mutate(text, sorted(set(DECLARED.findall(text))), what)
                files[p.name] = text.encode("latin-1", errors="replace")
                names.append(p.name)
        else:
            for _ in range(1 if kind != "several" else rng.randint(2, 3)):
                text, declared = self.source()
                text = self.mutate(text, declared, what)
                stem = rng.choice(HOSTILE_FILES) if rng.random() < 0.3 else f"Src{len(names)}"
                name = f"{stem}.{rng.choice(['gpl', 'gpl', 'gpl', 'gpo', 'GPL'])}"
                if name in files:
                    name = f"Src{len(names)}.gpl"
                files[name] = text.encode("utf-8" if rng.random() < 0.9 else "latin-1", errors="replace")
                names.append(name)
        if kind != "folder":
            subs = [m.group(1) for data in files.values() for m in SUB.finditer(data.decode("latin-1"))]
            files["Project.gpr"] = self.gpr(names, subs, what)
        folder = rng.choice(HOSTILE_FILES) if rng.random() < 0.3 else f"P{number}"
        return FuzzInput(folder.replace("\n", "_") if kind == "folder" else folder, files,
                           keep_going=rng.random() < 0.5, check_cli=rng.random() < 0.1, what=what)

    def gpr(self, names: list[str], subs: list[str], what: list[str]) -> bytes:
        rng = self.rng
        name = rng.choice(HOSTILE_VALUES) if rng.random() < 0.3 else "FuzzCell"
        r = rng.random()
        start = rng.choice(HOSTILE_VALUES) if r < 0.15 else rng.choice(subs) if subs and r < 0.8 else None
        lines = ["ProjectBegin", f'ProjectName="{name}"', *([f'ProjectStart="{start}"'] if start is not None else [])]
        lines += [f'ProjectSource="{n}"' if '"' not in n else f"ProjectSource={n}" for n in names]
        lines.append("ProjectEnd")
        text = "\r\n".join(lines) + "\r\n"
        if rng.random() < 0.1:
            what.append("gpr")
            text = self.mutate(text, [], what)
        return text.encode("utf-8", errors="replace")


def run_input(item: FuzzInput, root: Path) -> bool:
    """Write the project below ``root``, translate it in-process and check the properties."""
    folder = write_input(item, root)
    sink = DiagnosticSink()
    out = transpile(folder, sink, keep_going=False)
    check_diagnostics(sink, folder)
    if out is not None:
        check_translated(out, sink, root)
    elif item.keep_going:
        kept = DiagnosticSink()
        out = transpile(folder, kept, keep_going=True)
        check_diagnostics(kept, folder)
        if out is not None:
            compile_all(out.files, strict=False)
    else:
        # every error ignored (--ignore GPL1,GPL2,GPL3): the translation goes on, and the lines
        # that carry one raise it when reached (issue 20); whatever the errors, no GPL9000
        ignored = DiagnosticSink(Selection(None, ("GPL1", "GPL2", "GPL3")))
        out = transpile(folder, ignored)
        check_diagnostics(ignored, folder)
        assert not ignored.has_errors(), [d.header() for d in ignored]
        IGNORED_CODES.update(d.code for d in ignored.ignored_errors)
        if out is not None:
            compile_all(out.files, strict=False)
    if item.check_cli:
        check_matches_translate(folder, sink)
    return (root / "out").is_dir()


#: The error codes the pipeline fuzz translated with the error ignored (printed: the codes walked).
IGNORED_CODES: set[str] = set()


@pytest.mark.parametrize("part", range(FUZZ_PARTS))
def test_pipeline_fuzz_seeded_from_the_corpus(part: int, tmp_path_factory: pytest.TempPathFactory,
                                              monkeypatch: pytest.MonkeyPatch) -> None:
    seeds, whole = corpus_seeds()
    seed, rng = part_rng(part)
    inputs = part_inputs(FUZZ_INPUTS, FUZZ_PARTS, part)
    mutator = Mutator(rng, seeds, clean_seeds(seeds, tmp_path_factory.mktemp("seeds")))
    monkeypatch.setenv("GPL2PY_TRACEBACK", "1")  # a bug is an exception here, not a GPL9000
    monkeypatch.delenv("GPL2PY_MAX_SOURCE_MB", raising=False)
    translated = run_part("pipeline fuzz", part, seed, inputs, lambda n: mutator.project(n, whole), run_input,
                          tmp_path_factory)
    print(f"{len(IGNORED_CODES)} error codes translated ignored ({', '.join(sorted(IGNORED_CODES))})")
    assert translated > 0  # some inputs reached the end of the pipeline

"""What the pipeline fuzzes of every front end share (tests/frontend/test_fuzz.py for GPL,
tests/vplus/test_vplus_fuzz.py for V+, tests/tm/test_tm_fuzz.py for TMscript): the audit hook that records
every write (nothing may be written outside a batch's temporary folder) and what importing a
generated package must never do; the checks of the diagnostics' form and of the generated
Python; line and byte mutations of a seed text; hostile names of the Python side; the ``check``
== ``translate`` comparison; and the loop that runs one part's inputs in batches, keeps a failing
input and reports the slowest.  One copy, so that the three fuzzes hold gpl2py to one standard.
"""

from __future__ import annotations

import builtins
import contextlib
import gc
import importlib
import io
import itertools
import json
import keyword
import os
import random
import re
import shutil
import sys
import tempfile
import threading
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from gpl2py.cli import main as cli_main
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.output import Output, write_package
from gpl2py.run import import_package

FUZZ_SEED = os.environ.get("GPL2PY_FUZZ_SEED", "12")
BATCH = 250  # inputs sharing one temporary folder (and one check that nothing was written outside it)

#: Python-side names a generated module must never confuse with a source name: Python keywords,
#: builtins, modules, dunders, and the names translated code commonly defines.  Each fuzz adds
#: its front end's runtime and generated names and drops its language's keywords.
PYTHON_HOSTILE = sorted({
    *(k for k in keyword.kwlist + keyword.softkwlist if k.isidentifier() and k != "_"),
    "print", "list", "str", "int", "len", "range", "open", "eval", "exec", "compile", "globals", "locals",
    "object", "super", "property", "staticmethod", "classmethod", "isinstance", "float", "bool", "min", "max",
    "chr", "BaseException", "type", "id", "input", "vars", "getattr", "setattr", "sys", "os", "math", "self",
    "cls", "init", "main", "run", "script", "PROJECT", "_this", "_result", "_e", "_stubs", "_session",
    "__init__", "__class__", "__dict__", "__slots__", "__name__", "__file__", "__builtins__", "__import__",
    "__getattr__", "__all__", "__path__", "__main__", "__globals__", "__reduce_ex__", "numpy", "gplrt",
})
BUILTIN_NAMES = sorted(n for n in dir(builtins) if n[:1].isalpha())

#: File and folder names a project may carry (Linux allows all of these).
HOSTILE_FILES = [
    "Main", "sys", "os", "numpy", "gplrt", "__init__", "__main__", "_stubs", "_sourcemap", "con", "nul",
    "a b", "x'y", 'x"y', "x\\y", "-rf", "..x", ".hidden", "é", "中文", "x" * 200, "a\nb", "a\tb", "$HOME",
    "`id`", "$(id)", "x;y", "x%s", "{x}", "x\"\"\"y", "'''", "Print", "List_", "ChkInt32", "Current",
]

WRITE_EVENTS = {"os.mkdir", "os.rename", "os.replace", "os.remove", "os.rmdir", "os.symlink", "os.link",
                "os.truncate", "os.chmod", "os.utime", "shutil.copyfile", "shutil.copymode", "shutil.move",
                "shutil.rmtree"}
WRITE_FLAGS = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_APPEND | os.O_TRUNC
PATH_CODES = {"GPL1400", "GPL1401", "GPL1402", "GPL4112", "GPL5700"}  # about the path given: nothing else to point at
HEADER = re.compile(r"^(?P<file>.+):(?P<line>\d+):(?P<col>\d+): (error|warning|note) GPL\d{4}: \S")

_watch_thread = [0]  # the thread whose writes are watched (the fuzz's)
_watch: list[list[str]] = []  # while a batch runs: the paths written to (the audit hook's record)
#: What importing a generated package must never do (audit events): run programs, open
#: connections, load native code.
FORBIDDEN = ("os.system", "os.exec", "os.posix_spawn", "os.spawn", "os.fork", "os.kill", "subprocess.",
             "socket.", "ctypes.", "webbrowser.", "os.startfile")
_forbidden: list[list[str]] = []  # while a generated package is imported: forbidden events seen


# the argument positions of the folder descriptors a path of these events is relative to
_DIR_FD = {"os.mkdir": {0: 2}, "os.remove": {0: 1}, "os.rmdir": {0: 1}, "os.rename": {0: 2, 1: 3},
           "os.replace": {0: 2, 1: 3}, "os.symlink": {1: 2}, "os.link": {0: 2, 1: 3}, "os.chmod": {0: 2},
           "os.utime": {0: 3}}


def _audit(event: str, args: tuple[object, ...]) -> None:
    if _forbidden and event.startswith(FORBIDDEN):
        _forbidden[-1].append(f"{event}{args!r:.200}")
    if not _watch or threading.get_ident() != _watch_thread[0]:
        return  # (another thread's write: a server an earlier test left running in this process)
    if event == "open":
        path, mode, flags = args
        if isinstance(path, int) or path is None:
            return
        writes = any(c in mode for c in "wax+") if isinstance(mode, str) else bool(int(flags or 0) & WRITE_FLAGS)
        if writes:
            _watch[-1].append(os.path.abspath(os.fsdecode(path)))  # type: ignore[arg-type]
    elif event in WRITE_EVENTS:
        fds = _DIR_FD.get(event, {})
        for i, a in enumerate(args[:2]):
            if isinstance(a, (str, bytes, os.PathLike)):
                path = os.fsdecode(a)
                fd = args[fds[i]] if i in fds and fds[i] < len(args) else None
                if isinstance(fd, int) and not os.path.isabs(path):  # relative to an open folder
                    path = os.path.join(os.readlink(f"/proc/self/fd/{fd}"), path)
                _watch[-1].append(os.path.abspath(path))


sys.addaudithook(_audit)


def check_diagnostics(sink: DiagnosticSink, project: Path, unplaced: frozenset[str] = frozenset()) -> None:
    """Every diagnostic is ``file:line:col: severity GPLnnnn: message`` about a file of the project
    (but those about the path, and ``unplaced``: about a command-line option the input gave)."""
    for d in sink:
        assert d.code != "GPL9000", d.header()
        if d.code in PATH_CODES or d.code in unplaced:
            continue
        assert d.span is not None, f"no position: {d.header()}"
        header = d.header()
        assert header.isprintable(), header  # one line, whatever the names in it (one_line)
        m = HEADER.match(header)
        assert m is not None and d.span.line >= 1 and d.span.col >= 1, header
        assert Path(d.span.file).resolve().is_relative_to(project.resolve()), header
        d.render()


def compile_py(text: str, name: str, strict: bool = True) -> None:
    """compile(); ``strict``: its warnings ("is" with a literal, invalid escapes) are errors (the
    output of a translation without errors; --keep-going output of an erroneous program may
    compare with a literal where the program did)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error" if strict else "ignore")
        compile(text, name, "exec", dont_inherit=True)


def compile_all(files: dict[str, str], strict: bool = True) -> None:
    for name, text in files.items():
        if name.endswith(".py"):
            compile_py(text, name, strict)
        elif name.endswith(".json"):
            json.loads(text)


_imports = itertools.count()


def import_generated(folder: Path) -> None:
    """Import the package (module code runs: definitions, registrations) and forget it; it must
    neither fail (two names in one __slots__, a helper hidden by a module, a program's run-time
    error: nothing of the program runs at import) nor do anything of FORBIDDEN."""
    name = f"_fuzz_pkg_{next(_imports)}"
    seen: list[str] = []
    _forbidden.append(seen)
    try:
        package = import_package(folder, name)
        for sub in sorted(folder.glob("*.py")):
            if sub.stem not in ("__init__", "__main__"):
                importlib.import_module(f"{name}.{sub.stem}")
        del package
    finally:
        _forbidden.pop()
        for mod in [m for m in sys.modules if m == name or m.startswith(name + ".")]:
            del sys.modules[mod]
    assert seen == [], seen




@dataclass
class FuzzInput:
    """One input: the files of a project folder (relative path -> bytes), and how to run it."""

    folder: str
    files: dict[str, bytes]
    keep_going: bool = False
    check_cli: bool = False
    what: list[str] = field(default_factory=list)  # the mutations, for the failure message
    start: str | None = None  # --start (a front end that has one)


def write_input(item: FuzzInput, root: Path) -> Path:
    """The project's folder below ``root``, with its files."""
    folder = root / item.folder
    folder.mkdir()
    for rel, data in item.files.items():
        (folder / rel).write_bytes(data)
    return folder


def check_matches_translate(target: Path, sink: DiagnosticSink) -> None:
    """``gpl2py check --json`` reports exactly what ``translate`` reported in ``sink``."""
    stdout, stderr = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
        status = cli_main(["check", "--json", "--no-config", str(target)])
    assert status in (0, 1), stderr.getvalue()
    checked = json.loads(stdout.getvalue())["diagnostics"]
    for d in checked:
        assert d["code"] != "GPL9000", d
        assert d["code"] in PATH_CODES or (d["file"] and d["line"] >= 1 and d["column"] >= 1), d
    assert sorted(json.dumps(d, sort_keys=True) for d in checked) == \
        sorted(json.dumps(d.to_json(), sort_keys=True) for d in sink)


def part_rng(part: int) -> tuple[int, random.Random]:
    """The seed of this run and part ``part``'s own random stream (``GPL2PY_FUZZ_SEED``; ``random``
    for a new one each run)."""
    seed = random.randrange(2**32) if FUZZ_SEED == "random" else int(FUZZ_SEED)
    return seed, random.Random(f"{seed}/{part}")  # a str seed is hashed with SHA-512: the same stream everywhere


def part_inputs(total: int, parts: int, part: int) -> int:
    """How many of ``total`` inputs part ``part`` of ``parts`` runs."""
    return total // parts + (part < total % parts)


def run_part(label: str, part: int, seed: int, inputs: int, make: Callable[[int], FuzzInput],
             run: Callable[[FuzzInput, Path], bool], tmp_path_factory: pytest.TempPathFactory) -> int:
    """Run ``inputs`` inputs (``make(number)``), each by ``run(item, root)`` in a folder of its own
    (True when it was translated without errors), in batches sharing one temporary folder; a
    failure names the seed, the part and the input and keeps the input's folder; nothing may be
    written outside the batch's folder.  Prints the slowest input's time (never asserted: the
    machine may be shared) and returns how many inputs were translated without errors."""
    fed = translated = 0
    slowest: tuple[tuple[float, float], int, list[str]] = ((0.0, 0.0), -1, [])
    while fed < inputs:
        batch = tmp_path_factory.mktemp("fuzz")
        written: list[str] = []
        # (an earlier test's garbage is collected now, not while the batch is watched: a simulated
        # robot's temporary flash folder is deleted by its finalizer, on whichever thread the
        # collection happens to run)
        gc.collect()
        _watch_thread[0] = threading.get_ident()
        _watch.append(written)
        try:
            for _ in range(min(BATCH, inputs - fed)):
                item = make(fed)
                root = batch / f"i{fed}"
                root.mkdir()
                started, cpu = time.perf_counter(), time.process_time()
                try:
                    translated += bool(run(item, root))
                except BaseException as exc:
                    kept = Path(tempfile.mkdtemp(prefix=f"gpl2py-fuzz-{seed}-{part}-{fed}-"))
                    shutil.copytree(root, kept, dirs_exist_ok=True, symlinks=True)
                    raise AssertionError(f"{label} input {fed} of part {part} (GPL2PY_FUZZ_SEED={seed}, mutations "
                                         f"{item.what}) failed; the input is kept in {kept / item.folder!r}: "
                                         f"{type(exc).__name__}: {exc}") from exc
                seconds = (time.process_time() - cpu, time.perf_counter() - started)
                if seconds > slowest[0]:
                    slowest = (seconds, fed, item.what)
                fed += 1
                shutil.rmtree(root, ignore_errors=True)
        finally:
            _watch.pop()
        outside = sorted({p for p in written if not Path(p).resolve().is_relative_to(batch.resolve())})
        assert outside == [], f"written outside the temporary folder (seed {seed}, part {part}): {outside[:10]}"
    print(f"{label}, part {part}: {fed} inputs (seed {seed}), {translated} translated without errors; "
          f"slowest input {slowest[1]}: {slowest[0][0]:.2f} s of CPU, {slowest[0][1]:.2f} s wall "
          f"({', '.join(slowest[2])})")
    assert fed == inputs
    return translated


class TextMutations:
    """Mutations of a text by lines and bytes, for a mutator with ``rng`` (a ``random.Random``)
    and ``donors`` (texts whose lines may be inserted)."""

    rng: random.Random
    donors: list[str]

    # -- lines
    def op_line_del(self, text: str, declared: list[str]) -> str:
        lines = text.splitlines(keepends=True)
        if lines:
            del lines[self.rng.randrange(len(lines))]
        return "".join(lines)

    def op_line_dup(self, text: str, declared: list[str]) -> str:
        lines = text.splitlines(keepends=True)
        if lines:
            i = self.rng.randrange(len(lines))
            lines.insert(i, lines[i])
        return "".join(lines)

    def op_line_swap(self, text: str, declared: list[str]) -> str:
        lines = text.splitlines(keepends=True)
        if len(lines) > 1:
            i, j = self.rng.randrange(len(lines)), self.rng.randrange(len(lines))
            lines[i], lines[j] = lines[j], lines[i]
        return "".join(lines)

    def op_line_donor(self, text: str, declared: list[str]) -> str:
        donor = self.rng.choice(self.donors).splitlines(keepends=True)
        lines = text.splitlines(keepends=True)
        if donor:
            lines.insert(self.rng.randrange(len(lines) + 1), self.rng.choice(donor))
        return "".join(lines)

    # -- bytes
    def op_byte_ins(self, text: str, declared: list[str]) -> str:
        data = bytearray(text.encode("latin-1", errors="replace"))
        i = self.rng.randrange(len(data) + 1)
        data[i:i] = bytes(self.rng.randrange(256) for _ in range(self.rng.randint(1, 4)))
        return data.decode("latin-1")

    def op_byte_del(self, text: str, declared: list[str]) -> str:
        if not text:
            return text
        i = self.rng.randrange(len(text))
        return text[:i] + text[i + self.rng.randint(1, 8):]

    def op_byte_flip(self, text: str, declared: list[str]) -> str:
        if not text:
            return text
        i = self.rng.randrange(len(text))
        return text[:i] + chr(ord(text[i]) ^ (1 << self.rng.randrange(7))) + text[i + 1:]

    def mutate_piece(self, text: str, piece: re.Pattern[str], replacements: list[str]) -> str:
        """One piece of ``text`` (as ``piece`` cuts it: words, operators, blanks) deleted,
        duplicated, swapped with another, or replaced by one of ``replacements``."""
        pieces = piece.findall(text)
        if not pieces:
            return text
        rng = self.rng
        i = rng.randrange(len(pieces))
        r = rng.random()
        if r < 0.3:
            del pieces[i]
        elif r < 0.5:
            pieces.insert(i, pieces[i])
        elif r < 0.65:
            j = rng.randrange(len(pieces))
            pieces[i], pieces[j] = pieces[j], pieces[i]
        else:
            pieces[i] = rng.choice(replacements)
        return "".join(pieces)


def check_translated(out: Output, sink: DiagnosticSink, root: Path) -> None:
    """A translation without errors: its files compile (warnings are errors), it writes below
    ``root / "out"``, and the package imports without raising or doing anything forbidden
    (:func:`import_generated`)."""
    assert not sink.has_errors(), [d.header() for d in sink]
    compile_all(out.files)
    written = root / "out"
    assert write_package(out, written, sink), [d.header() for d in sink]
    for py in written.rglob("*.py"):
        compile_py(py.read_text(encoding="utf-8"), str(py))
    import_generated(written / out.package)

"""Shared helpers for tests that transpile GPL and run the result on the simulated controller.

Two ways in, for two kinds of test:

* ``run_gpl(tmp_path, source)`` writes GPL text into a fresh project, transpiles it through the
  library API and runs ``main(sim)`` on a virtual-clock simulation with captured console: what the
  construct-level end-to-end tests need.
* ``transpile(project, out_root)`` runs the ``gpl2py PROJECT -o OUT`` command, as a user porting a
  cell does, and imports the package it writes under a unique name: what the sample and I/O tests
  need (it also checks the command's contract: exit status 0, no error diagnostics).
"""

from __future__ import annotations

import importlib
import importlib.util
import itertools
import math
import os
import re
import shutil
import socket
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Callable
from xml.etree import ElementTree

import numpy as np

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.run import import_package
from gpl2py.selection import Selection
from gpl2py.transpile import transpile as transpile_project
from gpl2py.transpile import write_package
from gplrt.sim import Simulation

if TYPE_CHECKING:
    import pytest
    from gpl2py.gpl.semantics.check import Model

REPO = Path(__file__).resolve().parents[1]
SAMPLES = REPO / "samples"
_counter = itertools.count()


def _main_checkout(repo: Path) -> Path:
    """The repository's main working tree: ``repo`` itself, or for a linked worktree (whose
    ``.git`` is a file ``gitdir: <common>/worktrees/<name>``) the folder holding the common ``.git``."""
    git = repo / ".git"
    if not git.is_file():
        return repo
    gitdir = Path(git.read_text(encoding="utf-8").split(":", 1)[1].strip())
    common = gitdir / "commondir"
    root = (gitdir / common.read_text(encoding="utf-8").strip()).resolve() if common.is_file() else gitdir.parents[1]
    return root.parent


def _shared_candidates(name: str, env: str) -> list[Path]:
    given = os.environ.get(env)
    return [Path(given)] if given else [REPO.parent / "shared" / name,
                                        _main_checkout(REPO).parent / "shared" / name]


def find_shared(name: str, env: str) -> Path | None:
    """The folder :func:`shared_dir` finds, or None: for the one thing collection may do with the
    shared material, choosing parameters (whose test then calls :func:`shared_dir` when None)."""
    return next((path for path in _shared_candidates(name, env) if path.is_dir()), None)


def shared_dir(name: str, env: str) -> Path:
    """A folder of the project's shared material (``corpus``, ``spec``): ``$<env>`` if set, else
    ``../shared/<name>`` next to the repository root (of the main checkout, for a worktree).

    CI always has it, so there a missing folder fails the test; elsewhere the test is skipped
    with the reason, which names ``<env>``.  (Tests read the material in place and never copy it
    into the project.)

    Only a running test may ask, never the collection of tests (a parametrisation, a module's
    top level): a user's fresh clone has no ``../shared``, and a skip raised while collecting
    ends the whole session with "1 error during collection" and runs no test at all.  The
    collection is refused here even where the material exists, so the mistake shows at once.
    """
    import pytest

    if os.environ.get("GPL2PY_TESTS_COLLECTING"):
        raise RuntimeError(f"shared {name} looked for while pytest collects tests: look for it inside "
                           f"the test (a fresh clone without ../shared must still collect every test)")
    path = find_shared(name, env)
    if path is not None:
        return path
    candidates = ", ".join(map(str, dict.fromkeys(_shared_candidates(name, env))))
    reason = f"shared {name} not found (looked in {candidates}; set {env})"
    if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
        pytest.fail(reason)
    pytest.skip(reason)


def corpus_dir() -> Path:
    """The real GPL written by others (``../shared/corpus``, or ``$GPL_CORPUS``)."""
    return shared_dir("corpus", "GPL_CORPUS")


def spec_dir() -> Path:
    """The specs distilled from the manuals (``../shared/spec``, or ``$GPL_SPEC``)."""
    return shared_dir("spec", "GPL_SPEC")


class TranspileFailed(AssertionError):
    """gpl2py rejected the project: carries its diagnostics, which say which construct is missing."""

@dataclass
class RunResult:
    output: str
    log: str
    status: int
    files: dict[str, str]
    package: ModuleType
    sim: Simulation


def write_project(root: Path, sources: dict[str, str], start: str = "Main", name: str | None = None) -> str:
    # unique per process even when this helper is imported twice (as gpltest and tests.gpltest,
    # each with its own counter): a repeated name would import the other test's cached package
    name = name or f"E2e{next(_counter)}x{id(_counter) % 100000}"
    proj = root / name
    proj.mkdir(parents=True)
    lines = ["ProjectBegin", f'ProjectName="{name}"', f'ProjectStart="{start}"']
    for fname, text in sources.items():
        (proj / fname).write_text(text)
        lines.append(f'ProjectSource="{fname}"')
    lines.append("ProjectEnd")
    (proj / "Project.gpr").write_text("\n".join(lines) + "\n")
    return str(proj)


def transpile_to(root: Path, sources: dict[str, str] | str, start: str = "Main", ignore: tuple[str, ...] = (),
                 keep_going: bool = False) -> tuple[str, dict[str, str], DiagnosticSink]:
    """``ignore``: codes or prefixes ignored as ``--ignore`` ignores them; ``keep_going``: as
    ``--keep-going``."""
    if isinstance(sources, str):
        sources = {"Main.gpl": sources}
    proj = write_project(root, sources, start)
    sink = DiagnosticSink(Selection(None, ignore) if ignore else None)
    out = transpile_project(proj, sink, keep_going=keep_going)
    if out is None:
        raise TranspileFailed("\n".join(f"{d.header()}" for d in sink.sorted()))
    out_dir = root / "out"
    write_package(out, out_dir, sink)
    return out.package, out.files, sink


def translation_of(root: Path, text: str) -> tuple[dict[str, str], list[str]]:
    """The files and diagnostics of the one-file project ``text`` (``--keep-going``), the project's
    own name and folder (a fresh one each call) taken out: what two ways of holding one program
    must give alike (tests/frontend/test_chain.py, test_compact_dim.py)."""
    package, files, sink = transpile_to(root, text, keep_going=True)
    name = re.compile(re.escape(package), re.IGNORECASE)
    return ({name.sub("P", path): name.sub("P", body) for path, body in files.items()},
            [d.header().replace(str(root), "").split("Main.gpl", 1)[-1] for d in sink.sorted()])


def run_gpl(root: Path, sources: dict[str, str] | str, start: str = "Main",
            setup: Callable[[Simulation], object] | None = None, slice_checkpoints: int = 1000,
            ignore: tuple[str, ...] = (), keep_going: bool = False) -> RunResult:
    """Transpile and run ``sources``; ``setup(sim)`` prepares the controller first (a slow
    power-up, an input), as ``gpl2py run --setup`` does.  A short ``slice_checkpoints`` makes
    tests of thread scheduling fast (the controller's is 1000).  ``ignore``, ``keep_going``: the
    translation's options of the same names (:func:`transpile_to`)."""
    package, files, _ = transpile_to(root, sources, start, ignore, keep_going)
    out_dir = str(root / "out")
    sys.path.insert(0, out_dir)
    try:
        pkg = importlib.import_module(package)
        sim = Simulation(capture=True, project=package, slice_checkpoints=slice_checkpoints)
        if setup is not None:
            setup(sim)
        status = pkg.main(sim)
    finally:
        sys.path.remove(out_dir)
    return RunResult(sim.console.output, sim.console.log_text, status, files, pkg, sim)


def module_src(body: str, name: str = "Main") -> str:
    """Wrap procedure text in ``Module <name>``."""
    return f"Module {name}\n{body}\nEnd Module\n"


def gpl2py(*args: str, cwd: Path | None = None, timeout: float = 180, env: dict[str, str] | None = None
           ) -> subprocess.CompletedProcess[str]:
    """``python -m gpl2py ARGS`` in a subprocess, as a user types it (stdout and stderr are pipes,
    not a TTY); ``env`` adds to this process's environment."""
    return subprocess.run([sys.executable, "-m", "gpl2py", *args], capture_output=True, text=True,
                          cwd=cwd or REPO, timeout=timeout, env={**os.environ, **(env or {})})


class CommandResult:
    """What ``gpl2py`` run in this process printed, shaped like subprocess.CompletedProcess."""

    def __init__(self, returncode: int, stdout: str, stderr: str) -> None:
        self.returncode, self.stdout, self.stderr = returncode, stdout, stderr


def in_process(capsys: pytest.CaptureFixture[str], *args: str) -> CommandResult:
    """The ``gpl2py`` command in this process (fast; for cases that need no separate interpreter)."""
    from gpl2py.cli import main as cli_main

    capsys.readouterr()
    status = cli_main(list(args))
    out, err = capsys.readouterr()
    return CommandResult(status, out, err)


@dataclass
class Transpiled:
    """A transpiled project: its generated package (imported) and where it was written."""

    package: ModuleType
    folder: Path
    diagnostics: str

    def assert_clean(self) -> None:
        """Fail unless the translation printed no diagnostic at all: its stderr must be exactly the
        summary line, reporting 0 errors and 0 warnings (an exit status of 0 still allows warnings)."""
        lines = self.diagnostics.strip().splitlines()
        assert len(lines) == 1 and re.fullmatch(r"transpiled .*: 0 errors, 0 warnings", lines[0]), \
            self.diagnostics


def transpile(project: Path, out_root: Path) -> Transpiled:
    """Run ``gpl2py project -o out_root``; import and return the generated package."""
    out_root.mkdir(parents=True, exist_ok=True)
    proc = gpl2py(str(project), "-o", str(out_root), timeout=120)
    if proc.returncode != 0:
        raise TranspileFailed(f"gpl2py exit status {proc.returncode}:\n{proc.stderr}{proc.stdout}")
    packages = [p.parent for p in out_root.glob("*/__init__.py")]
    if len(packages) != 1:
        raise TranspileFailed(f"expected one package in {out_root}, found {packages}")
    folder = packages[0]
    package = import_package(folder, f"_gpl_{folder.name}_{next(_counter)}")
    return Transpiled(package, folder, proc.stderr)


def copy_project(project: Path, dest: Path, replace: dict[str, str] | None = None) -> Path:
    """Copy a project folder, replacing text in its sources (e.g. the server's port number).

    Each replacement must match exactly once, so a test never silently runs the unmodified text.
    """
    shutil.copytree(project, dest)
    for old, new in (replace or {}).items():
        hits = [f for f in dest.iterdir() if f.is_file() and old in f.read_text(encoding="latin-1")]
        if len(hits) != 1 or hits[0].read_text(encoding="latin-1").count(old) != 1:
            raise AssertionError(f"{old!r} must occur exactly once in {project}, found in {hits}")
        text = hits[0].read_text(encoding="latin-1")
        hits[0].write_text(text.replace(old, new), encoding="latin-1")
    return dest


PRIVATE_NETWORK = "GPL2PY_TEST_PRIVATE_NETWORK"  # set inside the network namespace of private_network


def _namespace_prefix() -> list[str] | None:
    """The command prefix that runs a program in a fresh network namespace with its loopback up
    (``unshare --net``), or None where none can be made (not root, no ``unshare``/``ip``)."""
    unshare, ip = shutil.which("unshare"), shutil.which("ip")
    if unshare is None or ip is None or subprocess.run(
            [unshare, "--net", "true"], capture_output=True).returncode != 0:
        return None
    return [unshare, "--net", "sh", "-c", f'"{ip}" link set lo up && exec "$0" "$@"']


def private_network(request: object, timeout: float = 900.0) -> bool:
    """Give a test that must listen on fixed ports (TCS: 10100, 10000) a loopback of its own.

    Returns True when the calling test should run its body here: inside the private network
    namespace, or on a machine where none can be made (not root, no ``unshare``/``ip``), where
    the fixed ports must be free.  Otherwise it runs this very test again in a fresh network
    namespace (``unshare --net``, loopback up) with ``--runxfail``, fails with that run's output
    if it failed, and returns False: the caller returns.  So parallel runs of the suite (several
    engineers on one machine, CI) never fight over the ports, and an expected failure is
    reported as the inner run's, not hidden by the re-run.
    """
    import pytest

    if os.environ.get(PRIVATE_NETWORK) == "1":
        return True
    prefix = _namespace_prefix()
    if prefix is None:
        return True
    nodeid = request.node.nodeid  # type: ignore[attr-defined]
    env = dict(os.environ, **{PRIVATE_NETWORK: "1"})
    run = subprocess.run([*prefix, sys.executable, "-m", "pytest", "-q",
                          "-p", "no:cacheprovider", "--runxfail", "-rN", nodeid],
                         cwd=REPO, env=env, capture_output=True, text=True, timeout=timeout)
    if run.returncode != 0:
        pytest.fail(f"{nodeid} failed in its own network namespace:\n{run.stdout[-20000:]}{run.stderr[-5000:]}",
                    pytrace=False)
    return False


@dataclass
class PrivateRun:
    """The tests of one module, run again together in a network namespace of their own
    (:func:`private_network_module`): each one's outcome there, by node id."""

    outcomes: dict[str, tuple[str, str]]  # node id -> ("passed"|"failed"|"skipped", text)
    output: str  # the inner pytest's own output, for a test that has no outcome

    def reproduce(self, request: object) -> None:
        """Give the calling test the outcome its twin had inside: fail or skip with the inner
        run's text, or return (it passed)."""
        import pytest

        nodeid = request.node.nodeid  # type: ignore[attr-defined]
        outcome = self.outcomes.get(nodeid)
        if outcome is None:
            pytest.fail(f"{nodeid} has no outcome from its network namespace:\n{self.output[-20000:]}",
                        pytrace=False)
        kind, text = outcome
        if kind == "failed":
            pytest.fail(f"{nodeid} failed in its own network namespace:\n{text}", pytrace=False)
        if kind == "skipped":
            pytest.skip(text)


def private_network_module(request: object, timeout: float = 900.0) -> PrivateRun | None:
    """:func:`private_network` for a module whose tests share one server (a module-scoped
    fixture that listens on fixed ports): call it from that fixture.

    Returns None when the module's tests should run here (inside the namespace, or where none
    can be made).  Otherwise, the first call runs every test of the module that this session
    selected, together and in order, in a fresh network namespace with ``--runxfail`` (one
    server for all of them, as here), and returns their outcomes; each test then calls
    :meth:`PrivateRun.reproduce`, so it passes, fails or is skipped as it did inside, and an
    expected failure stays expected.  Later calls (a parametrized fixture) reuse that run.
    """
    import pytest

    if os.environ.get(PRIVATE_NETWORK) == "1":
        return None
    prefix = _namespace_prefix()
    if prefix is None:
        return None
    module = request.node  # type: ignore[attr-defined]
    runs: dict[str, PrivateRun] = module.config.__dict__.setdefault("_gpl2py_private_runs", {})
    if module.nodeid in runs:
        return runs[module.nodeid]
    nodeids = [item.nodeid for item in module.session.items if item.nodeid.split("::")[0] == module.nodeid]
    env = dict(os.environ, **{PRIVATE_NETWORK: "1"})
    with tempfile.TemporaryDirectory() as tmp:
        junit = Path(tmp) / "junit.xml"
        run = subprocess.run([*prefix, sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                              "--runxfail", "-rN", f"--junitxml={junit}", "-o", "junit_family=xunit1",
                              *nodeids],
                             cwd=REPO, env=env, capture_output=True, text=True, timeout=timeout)
        output = run.stdout[-20000:] + run.stderr[-5000:]
        if not junit.is_file():
            pytest.fail(f"{module.nodeid}: no results from its network namespace:\n{output}", pytrace=False)
        cases = ElementTree.parse(junit).getroot().iter("testcase")
        by_name = {(case.get("classname", ""), case.get("name", "")): case for case in cases}
    outcomes: dict[str, tuple[str, str]] = {}
    for nodeid in nodeids:
        path, *classes, name = nodeid.split("::")
        classname = ".".join([*Path(path).with_suffix("").parts, *classes])
        case = by_name.get((classname, name))
        if case is None:
            continue
        failed = case.find("failure") if case.find("failure") is not None else case.find("error")
        skipped = case.find("skipped")
        if failed is not None:
            outcomes[nodeid] = ("failed", f"{failed.get('message', '')}\n{failed.text or ''}")
        elif skipped is not None:
            outcomes[nodeid] = ("skipped", skipped.get("message", ""))
        else:
            outcomes[nodeid] = ("passed", "")
    runs[module.nodeid] = PrivateRun(outcomes, output)
    return runs[module.nodeid]


def free_port() -> int:
    """A TCP port on loopback that nothing listens on right now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def hand_rotation(yaw: float) -> np.ndarray:
    """Rotation of GPL orientation (yaw, 90, 180) = Rz(yaw)·Ry(90)·Rz(180): a PF400 hand horizontal
    along ``yaw`` (the pose every sample teaches), worked out by hand rather than by the runtime."""
    c, s = math.cos(math.radians(yaw)), math.sin(math.radians(yaw))
    rz = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    return rz @ np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]]) @ np.diag([-1.0, -1.0, 1.0])


def wait_for_console(sim: Simulation, runner: threading.Thread, text: str, timeout: float = 10.0) -> None:
    """Wait until the program running on ``runner`` has written ``text`` on the console; fail the
    test with everything it wrote when it does not within ``timeout`` real seconds (or ends)."""
    deadline = time.monotonic() + timeout
    while text not in sim.console.output and runner.is_alive() and time.monotonic() < deadline:
        runner.join(0.02)
    assert text in sim.console.output, sim.console.output + sim.console.log_text


def start_server(target: Callable[[], object], sim: Simulation, ready: str = "listening",
                 timeout: float = 10.0) -> threading.Thread:
    """Run a sample server (``target`` calls its ``main(sim)``) on a daemon thread and return the
    thread once the server says ``ready`` on the console."""
    runner = threading.Thread(target=target, daemon=True)
    runner.start()
    wait_for_console(sim, runner, ready, timeout)
    return runner


def shutdown_server(port: int, runner: threading.Thread, timeout: float = 15.0) -> None:
    """Fixture teardown: a server a test left running is sent ``shutdown`` on a new connection and
    given ``timeout`` seconds to end (a server that already stopped is left alone)."""
    if not runner.is_alive():
        return
    try:
        client = LineClient(port)
        client.ask("shutdown")
        client.close()
    except OSError:
        pass
    runner.join(timeout)


class LineClient:
    """A line-based TCP test client for the sample servers: sends request lines, reads CR-LF reply lines.

    Every socket operation has ``timeout`` seconds and the read loop is bounded, so a broken server
    fails the test instead of hanging it.  ``newline`` ends each request: the servers accept both
    CR-LF and bare LF, and the tests keep using the one their protocol describes.
    """

    def __init__(self, port: int, timeout: float = 15.0, newline: str = "\r\n") -> None:
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=timeout)
        self.newline = newline
        self.pending = b""

    def send(self, text: str) -> None:
        """Send ``text`` as it is (no line ending added)."""
        self.sock.sendall(text.encode("latin-1"))

    def line(self) -> str:
        """The next CR-LF terminated reply line, without its ending."""
        for _ in range(10_000):
            if b"\r\n" in self.pending:
                head, self.pending = self.pending.split(b"\r\n", 1)
                return head.decode("latin-1")
            chunk = self.sock.recv(4096)
            if not chunk:
                raise ConnectionError(f"closed by the server; unread {self.pending!r}")
            self.pending += chunk
        raise AssertionError(f"no complete line; unread {self.pending[-200:]!r}")

    def ask(self, text: str) -> str:
        """Send one request line and return the one reply line."""
        self.send(text + self.newline)
        return self.line()

    def close(self) -> None:
        self.sock.close()

    def __enter__(self) -> LineClient:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def ask_all(port: int, requests: dict[int, list[str]], timeout: float = 15.0) -> dict[int, list[str]]:
    """One client per key, all sending at the same moment; each returns its replies in order."""
    replies: dict[int, list[str]] = {k: [] for k in requests}
    errors: list[BaseException] = []
    barrier = threading.Barrier(len(requests))

    def client(k: int) -> None:
        try:
            c = LineClient(port, timeout)
            try:
                barrier.wait(timeout)
                for line in requests[k]:
                    replies[k].append(c.ask(line))
            finally:
                c.close()
        except BaseException as exc:  # reported by the test thread below
            errors.append(exc)

    workers = [threading.Thread(target=client, args=(k,)) for k in requests]
    for w in workers:
        w.start()
    for w in workers:
        w.join(4 * timeout)
    assert not errors, errors
    return replies


def code_of(fn: Callable[..., object], *args: object, **kwargs: object) -> int:
    """The controller error code of the GplException that ``fn(*args, **kwargs)`` raises.

    Fails the test if the call returns normally or raises anything but a GplException.
    """
    import pytest

    from gplrt.lang.errors import GplException

    with pytest.raises(GplException) as info:
        fn(*args, **kwargs)
    return info.value.ErrorCode


def generated_main_module(tmp_path: Path, body: str, decls: str = "", name: str = "Main") -> str:
    """The Python module gpl2py writes for ``Module <name>`` holding ``decls`` and a ``Sub Main``
    whose statements are ``body``: what the tests of generated-code shape read.  Fails the test
    with the diagnostics if the program is rejected."""
    src = f"Module {name}\n{decls}\n    Public Sub Main()\n{body}\n    End Sub\nEnd Module\n"
    f = tmp_path / f"{name}.gpl"
    f.write_text(src)
    sink = DiagnosticSink()
    out = transpile_project(str(f), sink)
    assert out is not None, [d.header() for d in sink.sorted()]
    return next(v for k, v in out.files.items() if k.endswith(".py") and "__" not in k)


def main_body(text: str) -> str:
    """The body of ``def Main()`` in a generated module (up to the next top-level definition)."""
    return text.split("def Main() -> None:\n", 1)[1].split("\n\n\n", 1)[0]


def analyze_text(tmp_path: Path, text: str, start: str | None = None) -> tuple[Model, DiagnosticSink]:
    """Parse ``text`` as the one file of a project and run the semantic pass on it: the model and
    every diagnostic, for tests of name resolution and typing.  Syntax errors fail the test."""
    from gpl2py.project import load_project
    from gpl2py.gpl.semantics.catalogue import load_catalogue
    from gpl2py.gpl.semantics.check import analyze
    from gpl2py.gpl.syntax.parser import parse

    f = tmp_path / "Main.gpl"
    f.write_text(text)
    sink = DiagnosticSink()
    project = load_project(f, sink)
    assert project is not None
    units = [parse(s, sink) for s in project.sources]
    assert not sink.has_errors(), [d.header() for d in sink]
    return analyze(units, sink, load_catalogue(), "P", start), sink


def analyze_project(path: Path) -> tuple[Model, DiagnosticSink]:
    """Load, parse and analyze a project folder as ``gpl2py check`` does (protected files make
    unknown names stubs), without lowering it: the model and every diagnostic."""
    from gpl2py.project import load_project
    from gpl2py.gpl.semantics.catalogue import load_catalogue
    from gpl2py.gpl.semantics.check import analyze
    from gpl2py.gpl.syntax.parser import parse

    sink = DiagnosticSink()
    project = load_project(path, sink)
    assert project is not None, [d.header() for d in sink]
    units = [parse(s, sink) for s in project.sources]
    model = analyze(units, sink, load_catalogue(), project.name, project.start,
                    protected=bool(project.protected))
    return model, sink


def compiled_modules(files: dict[str, str]) -> dict[str, str]:
    """Compile every generated ``.py`` file of a transpilation (a SyntaxError fails the test) and
    return the GPL modules' files (not ``__init__``/``__main__``), name -> text, so a test of
    ``--keep-going`` output asserts on what it compiled (an empty result would prove nothing)."""
    modules: dict[str, str] = {}
    for name, code in files.items():
        if name.endswith(".py"):
            compile(code, name, "exec")
            if "__" not in name:
                modules[name] = code
    return modules


#: ``python -c FOREGROUND ARGS...`` is ``python -m gpl2py ARGS...`` as a terminal's foreground
#: runs it, for tests that send it Ctrl-C.  A terminal delivers Ctrl-C to a foreground program whose SIGINT is at its default.  A test run
# started as a background job of a shell script (several suites at once: `pytest ... &`) inherits
# SIGINT *ignored*, as POSIX has it for background jobs, and so would gpl2py, which then rightly
# keeps ignoring it: reset it, as the terminal's foreground would have it, then run gpl2py exactly
# as `python -m gpl2py` does.
FOREGROUND = ("import runpy, signal; signal.signal(signal.SIGINT, signal.default_int_handler); "
              "runpy.run_module('gpl2py', run_name='__main__', alter_sys=True)")

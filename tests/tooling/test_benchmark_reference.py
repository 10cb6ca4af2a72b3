"""Issue 20, item 8: every benchmark that prints an absolute figure (a time, a rate, a factor
against the clock) also prints, from the same run, the reference workload R's time and the figure
normalised by R, so that figures from two machines can be compared.

Each benchmark runs here at its smallest size, in a fresh process, and its output must carry R's
line, the sentence saying how to compare machines, and its figures in R.  Nothing is timed: the
figures' values are the benchmarks' business, the tests check that they are printed.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from gpltest import corpus_dir

ROOT = Path(__file__).resolve().parents[2]
BENCHMARKS = ROOT / "benchmarks"
sys.path.insert(0, str(BENCHMARKS))

import _reference  # noqa: E402
from _reference import HOW_TO_COMPARE, Reference, reference_workload  # noqa: E402
from _sidebyside import Pair, Samples, side_by_side  # noqa: E402

#: Each benchmark's smallest run, and what its normalised figures look like in its output.
SMALLEST: dict[str, tuple[list[str], str]] = {
    "check_startup.py": (["--runs", "1"], r"gpl2py check, 5-line GPL file: .* ms .*\d R \(spread"),
    "client_session.py": (["--server", "sample", "--moves", "2", "--runs", "1"],
                          r"CPU  time [\d.]+ R .*s of simulated motion per R"),
    "file_speed.py": (["--n", "3", "--runs", "1"], r"all five .* in R: [\d.]+ R, [\d.]+ R"),
    "geometry_speed.py": (["--number", "10", "--runs", "1"], r"µR/op(.|\n)*\nMul +[\d.]+ +[\d.]+ +[\d.]+ +[\d.]+ "),
    "kinematics_speed.py": (["5", "1"], r"PF400SX +forward .*\n +in R .*µR"),
    "load_check.py": (["--parts", "1", "--runs", "1", "--spinners", "0,1", "--rounds", "1"],
                      r"1 extra CPU-bound processes(.|\n)*normalised +[\d.]+ controller s per R"),
    "motion_speed.py": (["--runs", "1", "--block", "1", "--cell-runs", "1", "--parts", "1"],
                        r"normalised: wall .* controller s per R \(wall\).* controller s per R \(CPU\)"),
    "parse_speed.py": (["--lines", "800", "--runs", "1"], r"in R: +gpl2py .* R .*GPL lines per R"),
    "tm_listen.py": (["--moves", "2", "--runs", "1"], r"100 statements: .* µR \(spread"),
    "lsp_latency.py": (["--edits", "2", "--requests", "1", "--checks", "1"],
                       r"hover +[\d.]+ ms \(spread .*\) +[\d.]+ R \(spread"),
    "vplus_speed.py": (["--lines", "300", "--runs", "1"], r"translate +V\+ *: .* us/line, [\d.]+ µR/line"),
    "runtime_speed.py": (["--n", "50", "--runs", "5", "--on", "direct"], r"class method call .*\n +in R +[\d.]+ R"),
    "sweep_speed.py": (["--sets", "4", "--runs", "1"], r"2 workers \(sweep\) +[\d.]+ s .*in R: +[\d.]+ R \(spread"),
    "transpile_speed.py": (["--lines", "300", "--runs", "1"],
                           r"transpile: .* ms .* R \(spread(.|\n)*translate .* mR/line"),
}

#: The benchmarks that measure the real code (the TCS project).
NEEDS_CORPUS = {"lsp_latency.py"}

R_LINE = re.compile(r"^R, the reference workload \(benchmarks/_reference\.py v\d+, \w+ [\d.]+\): "
                    r"[\d.]+ ms wall \(spread [\d.]+-[\d.]+\), [\d.]+ ms CPU \(spread [\d.]+-[\d.]+\), "
                    r"\d+ runs in turns with the samples$", re.M)


def test_every_benchmark_with_an_absolute_figure_is_checked_here() -> None:
    # memory.py prints memory per byte of source, a ratio of sizes: no time, no rate.
    scripts = {p.name for p in BENCHMARKS.glob("*.py") if not p.name.startswith("_")}
    assert scripts - {"memory.py"} == set(SMALLEST)


@pytest.mark.slow
@pytest.mark.parametrize("script", sorted(SMALLEST))
def test_benchmark_prints_the_reference_and_its_figures_in_r(script: str, tmp_path: Path) -> None:
    args, normalised = SMALLEST[script]
    env = dict(os.environ)
    if script in NEEDS_CORPUS:
        env["GPL_CORPUS"] = str(corpus_dir())  # (skips, naming GPL_CORPUS, where there is none)
    done = subprocess.run([sys.executable, str(BENCHMARKS / script), *args], cwd=tmp_path,
                          capture_output=True, text=True, timeout=900, env=env)
    assert done.returncode == 0, done.stderr[-3000:]
    out = done.stdout
    assert R_LINE.search(out), out[-3000:]
    assert HOW_TO_COMPARE in out
    assert re.search(normalised, out), out[-3000:]


def test_the_reference_workload_is_the_one_figures_were_normalised_by() -> None:
    # A changed workload makes every figure in R incomparable with earlier ones: change VERSION too.
    assert (_reference.VERSION, _reference.ITERATIONS, reference_workload()) == (1, 60_000, 4_755_748_119)


def test_a_changed_workload_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(_reference, "ITERATIONS", 1_000)
    with pytest.raises(RuntimeError, match="changed"):
        Reference().run()


def test_side_by_side_runs_r_once_in_every_turn_after_its_warm_up() -> None:
    calls: list[str] = []
    ref = Reference()
    pair = side_by_side(lambda: calls.append("a"), lambda: calls.append("b"), 3, warmup=2, reference=ref)
    assert calls == ["a", "b"] * 5
    assert len(ref.wall) == len(ref.cpu) == 3
    assert pair.ref is not None and pair.ref.values == ref.wall


def test_figures_in_r_are_taken_turn_by_turn() -> None:
    pair = Pair(Samples([2.0, 9.0, 4.0]), Samples([1.0, 3.0, 1.0]), Samples([1.0, 3.0, 2.0]))
    assert pair.a_in_r.values == [2.0, 3.0, 2.0]
    assert pair.b_in_r.values == [1.0, 1.0, 0.5]
    assert _reference.times_r([10.0, 20.0], [0.5, 0.25]) == [5.0, 5.0]


def test_r_runs_for_a_share_of_a_long_turn_and_records_the_mean_run(monkeypatch: pytest.MonkeyPatch) -> None:
    ticks = iter(range(100))  # a clock that moves one second each time it is read
    monkeypatch.setattr(_reference.time, "perf_counter", lambda: float(next(ticks)))
    runs: list[int] = []
    monkeypatch.setattr(_reference, "reference_workload", lambda: runs.append(1) or _reference.CHECKSUM)
    ref = Reference()
    ref.run(match=3.0 / _reference.SHARE)  # R must run for 3 s: read at 0, then 1, 2, 3 after each run
    assert len(runs) == 3
    assert ref.wall == [4.0 / 3]  # the last read (4) ends the block: the mean of three runs

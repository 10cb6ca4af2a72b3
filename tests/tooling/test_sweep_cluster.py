"""gpl2py sweep on a real Dask cluster (``distributed.LocalCluster``, worker processes on this
machine): runs that fail or stall are rows, a worker killed mid-run has its run retried on
another, an interrupted sweep resumes from its parts (``gpl2py sweep --resume``), no row is lost
or duplicated; the workers never import the translator; and a parameter set gives the same row on
one worker, on two and in a plain loop in this process."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path

# Imported, not importorskip'd: the test extra (what CI installs) has distributed, and a missing
# one must fail the run rather than skip the cluster tests unseen.
import distributed
import pandas as pd
import pytest

from gpltest import SAMPLES, gpl2py
from sweepkit import THROW_LINE, tiny_project

from gpl2py.sweep import Count, EndTime, EventTime, Sweep, run_id
from gpl2py.sweep.results import parts_folder

#: The translator: its entry, the front ends (GPL's under gpl2py.gpl, V+, TMscript) and the writer
#: of the generated Python; the old places of GPL's front end too, in case a module is left there.
TRANSLATOR = ("gpl2py.transpile", "gpl2py.gpl", "gpl2py.vplus", "gpl2py.tmscript", "gpl2py.pywriter",
              "gpl2py.lower", "gpl2py.semantics", "gpl2py.syntax")


@pytest.fixture
def client() -> Iterator[distributed.Client]:
    """Two worker processes, one thread each (a test kills one: processes=True); a cluster per test,
    so that a worker a test killed and that did not come back (on a loaded machine) leaves no test
    after it waiting for workers that are not there."""
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0",
                                  silence_logs=50) as cluster, distributed.Client(cluster) as c:
        yield c


def _sweep(project: str, setup: Path, sets: list[dict[str, object]], **options: object) -> Sweep:
    metrics = [EndTime(), Count("made", "^part "), Count("grips", signal=1), EventTime("done_at", "^done")]
    return Sweep(project, setup, sets, metrics=metrics, **options)  # type: ignore[arg-type]


def _translator_on_workers(client: distributed.Client) -> dict[str, list[str]]:
    def loaded() -> list[str]:
        return sorted(m for m in sys.modules if m.startswith(TRANSLATOR))

    return client.run(loaded)


def test_faults_are_rows_a_killed_worker_loses_nothing_and_no_worker_translates(
        client: distributed.Client, tmp_path: Path) -> None:
    project, setup = tiny_project(tmp_path)
    marker = tmp_path / "killed-once"
    sets: list[dict[str, object]] = [{"mode": "ok", "parts": n} for n in range(1, 5)]
    sets += [{"mode": "fail", "parts": 1}, {"mode": "stall", "parts": 1}, {"mode": "loop", "parts": 1},
             {"mode": "kill", "parts": 3, "marker": str(marker)}]
    before = set(client.scheduler_info()["workers"])
    out = tmp_path / "results.parquet"
    df = _sweep(project, setup, sets, timeout=5.0).run(client=client, output=out)

    assert marker.exists()  # the worker that took the "kill" set died in it ...
    assert set(client.scheduler_info()["workers"]) != before  # ... and its nanny started another
    assert len(df) == len(sets) and df["run_id"].is_unique
    assert list(df["run_id"]) == [run_id(p) for p in sets]  # the sets' order, not the order runs ended
    by_mode = df.groupby("mode")["status"].agg(list).to_dict()
    assert by_mode == {"ok": ["ok"] * 4, "fail": ["error"], "stall": ["stalled"], "loop": ["timeout"],
                       "kill": ["ok"]}  # retried on another worker, where it ran to the end
    fail = df[df["mode"] == "fail"].iloc[0]
    assert (fail["error_code"], fail["error_file"], fail["error_line"]) == (-3100, "Main.gpl", THROW_LINE)
    assert df[df["mode"] == "stall"].iloc[0]["stalled_threads"] == "Main"
    assert list(df[df["mode"] != "kill"]["made"]) == [1, 2, 3, 4, 0, 0, 0]
    assert df[df["mode"] == "kill"].iloc[0]["made"] == 3
    pd.testing.assert_frame_equal(pd.read_parquet(out), df)
    assert _translator_on_workers(client) == {w: [] for w in client.scheduler_info()["workers"]}


def test_a_run_that_kills_every_worker_it_is_tried_on_is_a_lost_row(client: distributed.Client,
                                                                   tmp_path: Path) -> None:
    project, setup = tiny_project(tmp_path)

    def allow(failures: int) -> None:
        client.run_on_scheduler(lambda dask_scheduler: setattr(dask_scheduler, "allowed_failures", failures))

    allow(1)  # (default 3) one retry, so that the test kills two workers, not four
    try:
        df = _sweep(project, setup, [{"mode": "killall", "parts": 1}]).run(client=client)
    finally:
        allow(3)
    [row] = df.to_dict("records")
    assert row["status"] == "lost" and row["error_message"].startswith("KilledWorker")
    assert row["parts"] == 1 and pd.isna(row["made"]) and row["run_id"] == run_id({"mode": "killall", "parts": 1})


def test_an_interrupted_sweep_with_faults_and_a_killed_worker_resumes_with_the_command(
        client: distributed.Client, tmp_path: Path) -> None:
    project, setup = tiny_project(tmp_path)
    marker = tmp_path / "killed-once"
    params = tmp_path / "params.toml"
    runs = "".join(f'[[run]]\nmode = "ok"\nparts = {n}\n' for n in (1, 2, 3, 4, 5, 6))
    runs += ('[[run]]\nmode = "fail"\nparts = 7\n[[run]]\nmode = "stall"\nparts = 8\n'
             f'[[run]]\nmode = "kill"\nparts = 9\nmarker = "{marker.as_posix()}"\n')
    params.write_text(runs + '[metrics]\nparts_done = { count = "^part " }\n')
    before = set(client.scheduler_info()["workers"])
    sweep = Sweep.from_file(project, params, setup)
    out = tmp_path / "results.parquet"

    def interrupt_after_three(done: int, total: int) -> None:
        if done == 3:
            raise KeyboardInterrupt  # Ctrl-C while the other runs are still on the cluster

    with pytest.raises(KeyboardInterrupt):
        sweep.run(client=client, output=out, progress=interrupt_after_three)
    kept = sweep.already_done(out)
    assert kept >= 3 and not out.exists()  # the rows that had arrived are in the parts
    # The runs that had not come back were cancelled: the cluster works on nothing of the sweep.
    assert client.run_on_scheduler(lambda dask_scheduler: [k for k in dask_scheduler.tasks
                                                           if str(k).startswith("gpl2py-run-")]) == []

    address = client.scheduler.address
    done = gpl2py("sweep", project, "--params", str(params), "--setup", str(setup), "-o", str(out),
                  "--scheduler", address, "--resume", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert f"sweeping {9 - kept} of 9 parameter sets ({kept} already in {out})" in done.stderr
    assert "swept 9 parameter sets in" in done.stderr and ": 7 ok, 1 error, 1 stalled; results in" in done.stderr
    assert marker.exists() and set(client.scheduler_info()["workers"]) != before  # a worker died mid-run
    df = pd.read_parquet(out)
    assert list(df["parts"]) == list(range(1, 10)) and df["run_id"].is_unique  # none lost, none twice
    assert list(df["status"]) == ["ok"] * 6 + ["error", "stalled", "ok"]  # the killed run, run again
    assert list(df["parts_done"]) == [1, 2, 3, 4, 5, 6, 0, 0, 9]
    assert not parts_folder(out).exists()


def test_the_same_sets_give_the_same_rows_on_one_worker_on_two_and_in_a_plain_loop(
        client: distributed.Client, tmp_path: Path) -> None:
    cell = Sweep.from_file(SAMPLES / "pick_and_place", SAMPLES / "sweep" / "params.toml",
                           SAMPLES / "sweep" / "setup.py", timeout=60.0)
    cell.sets = [{"interval": i, "speed": s} for i, s in ((0.2, 20), (1.0, 100), (6.0, 60), (0.5, 80))]
    loop = cell.run_in_process()
    assert list(loop["status"]) == ["timeout", "timeout", "ok", "timeout"]  # the cell takes > 60 s
    one = cell.run(workers=1)  # a local cluster of its own, started and closed by the sweep
    two = cell.run(client=client)
    pd.testing.assert_frame_equal(one, loop)
    pd.testing.assert_frame_equal(two, loop)

    project, setup = tiny_project(tmp_path)
    tiny = _sweep(project, setup, [{"mode": m, "parts": 2} for m in ("ok", "fail", "stall", "loop", "setup")],
                  timeout=5.0)
    pd.testing.assert_frame_equal(tiny.run(client=client), tiny.run_in_process())


def _busy() -> int:
    """Half a second of Python on a worker: long enough for Dask's profiler to sample it often."""
    import time

    started, spins = time.perf_counter(), 0
    while time.perf_counter() - started < 0.5:
        spins += 1
    return spins


def test_the_local_cluster_has_dasks_profiler_off_and_its_monitors_slower() -> None:
    import dask

    from gpl2py.sweep.cluster import local_cluster

    with local_cluster(1) as cluster, distributed.Client(cluster) as c:
        assert c.submit(_busy, pure=False).result() > 0
        assert c.profile()["count"] == 0  # no stack sample taken from the run (Dask's default: every 10 ms)
        settings = c.run(lambda: (dask.config.get("distributed.worker.profile.enabled"),
                                  dask.config.get("distributed.worker.memory.monitor-interval")))
        assert list(settings.values()) == [(False, "1s")]


def _tries(log: Path) -> dict[int, list[str]]:
    """The Dask task that ran each set (by its ``n``), once per try, from the setup's log."""
    tries: dict[int, list[str]] = {}
    for line in log.read_text().splitlines():
        n, key = line.split(" ", 1)
        tries.setdefault(int(n), []).append(key)
    return tries


def test_a_task_runs_a_batch_of_sets_a_fault_stays_its_runs_row_and_a_killed_batch_reruns_only_the_unreported(
        client: distributed.Client, tmp_path: Path) -> None:
    project, setup = tiny_project(tmp_path)
    log, marker = tmp_path / "tries.log", tmp_path / "killed-once"
    modes = ["ok", "fail", "kill", "ok", "stall", "loop", "setup"] + ["ok"] * 18  # 25 sets: batches of 4, 3, ...
    sets: list[dict[str, object]] = [{"mode": m, "n": n, "parts": 1, "log": str(log), "marker": str(marker)}
                                     for n, m in enumerate(modes)]
    seen: list[int] = []
    df = _sweep(project, setup, sets, timeout=5.0).run(client=client, per_task=4,
                                                       progress=lambda done, total: seen.append(done))

    assert seen == list(range(1, 26))  # one row at a time, as each run ended
    assert len(df) == 25 and list(df["run_id"]) == [run_id(p) for p in sets]  # none lost, none twice
    assert list(df["status"][:7]) == ["ok", "error", "ok", "ok", "stalled", "timeout", "setup error"]
    assert set(df["status"][7:]) == {"ok"}
    tries = _tries(log)
    first = tries[0][0]
    assert [tries[n][-1] for n in range(4)] == [first] * 4  # the first four sets: one task, a batch
    # Its worker died in set 2 (the kill): Dask ran the task again, which ran set 2 and set 3
    # only; sets 0 and 1 had reported their rows before and ran once.
    assert tries[0] == tries[1] == [first] and tries[2] == [first, first] and tries[3] == [first]
    assert len(set(tries[4])) == 1 and len(tries[4]) == 2  # the stall: run_one makes it again without the time-out
    assert all(len(tries[n]) == 1 for n in range(5, 25))
    assert len({key for keys in tries.values() for key in keys}) < 25  # fewer tasks than runs


def test_a_batch_that_kills_every_worker_loses_only_the_run_that_kills(client: distributed.Client,
                                                                       tmp_path: Path) -> None:
    project, setup = tiny_project(tmp_path)
    log = tmp_path / "tries.log"
    modes = ["ok", "killall", "ok", "ok"] + ["ok"] * 21
    sets: list[dict[str, object]] = [{"mode": m, "n": n, "parts": 1, "log": str(log)} for n, m in enumerate(modes)]

    def allow(failures: int, saturation: float) -> None:
        def set_up(dask_scheduler: distributed.Scheduler) -> None:
            dask_scheduler.allowed_failures = failures
            dask_scheduler.WORKER_SATURATION = saturation

        client.run_on_scheduler(set_up)

    # No retry: the batch is tried once, then its unreported sets one task each.  One task at a
    # time on each worker: Dask counts a worker's death against every task it holds, also one
    # waiting behind the run that killed it, and one death would make that one lost too.
    allow(0, 1.0)
    try:
        df = _sweep(project, setup, sets).run(client=client, per_task=4)
    finally:
        allow(3, 1.1)
    assert list(df["run_id"]) == [run_id(p) for p in sets]
    assert list(df["status"]) == ["ok", "lost"] + ["ok"] * 23
    assert df.iloc[1]["error_message"].startswith("KilledWorker")
    tries = _tries(log)
    assert len(set(tries[1])) == 2 == len(tries[1])  # once in the batch, once on its own
    assert tries[0] == [tries[1][0]]  # the batch's first set ran once, its row reported before the kill


def test_batches_keep_the_sets_order_and_shrink_to_single_runs_at_the_end() -> None:
    from gpl2py.sweep.cluster import batches

    sets: list[dict[str, object]] = [{"n": n} for n in range(200)]
    cut = batches(sets, slots=2, most=8)  # type: ignore[arg-type]
    assert [p for batch in cut for p in batch] == sets
    sizes = [len(b) for b in cut]
    assert sizes[0] == 8 and max(sizes) == 8 and sizes == sorted(sizes, reverse=True)
    assert sizes[-8:] == [1] * 8  # the workers finish together: the last tasks are single runs
    assert len(cut) < 50  # a quarter of the tasks of one run each
    assert [len(b) for b in batches(sets[:6], slots=2)] == [1] * 6  # a small sweep: one run a task

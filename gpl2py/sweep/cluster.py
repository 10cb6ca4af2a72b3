"""Where the runs of a sweep run: Dask (a local cluster, or an existing scheduler), or a plain loop.

Why Dask (dask.distributed) rather than Ray or a process pool: a sweep's runs are independent
tasks of a fraction of a second to minutes, which is what Dask's scheduler is built for; the same
code runs on a laptop (``LocalCluster``: processes on this machine, started and closed here) and
on any existing Dask cluster (``--scheduler tcp://host:8786``: Kubernetes, HPC job queues and
cloud deployments all start one); a worker that dies has its tasks rescheduled on the others
(``distributed.scheduler.allowed-failures``) without code of ours; and it is a pure-Python
install with nothing else to run.  Ray brings its own object store and raylet processes and its
own cluster manager, more than independent tasks need; ``concurrent.futures`` and
``multiprocessing`` stop at one machine and lose the task of a killed process
(``BrokenProcessPool``) instead of retrying it.

The package reaches the workers through a worker plugin (:class:`ShipSweep`): the scheduler
keeps it and hands it to every worker, also one that joins or is restarted after the sweep
began, which unpacks the package's bytes into its own local folder.  The plugin carries the
sweep's setup, metrics and time-out too, once per worker; tasks carry only parameter sets.

Why a task runs a few parameter sets, not one (:func:`batches`): every task costs the scheduler,
the client and the worker some milliseconds of Dask's bookkeeping (the graph, the task's
transitions, fetching its result from the worker), and on a machine with as many workers as
cores that CPU time comes out of the runs'.  The batches shrink towards the end of the sweep
(guided self-scheduling: a batch is a quarter of the remaining sets' share of one worker
thread, at most :data:`MOST` sets), so that the last tasks are single runs and the workers
finish together.  Batching changes neither what a run does nor how faults are kept apart:

* each run's row is reported as soon as the run ends, as a Dask event (``log_event``) the client
  subscribed to, so the rows still stream and are written as they arrive, one per run;
* a run that raises, stalls or times out is a row (:func:`gpl2py.sweep.worker.run_one` never
  raises) and the batch goes on with the next set;
* when the worker dies mid-batch, Dask runs the task again elsewhere, and the retried task first
  reads the events its earlier attempts logged (the batch's own topic, its task key) and runs
  only the sets without one;
* a batch whose worker died more often than the cluster allows is split: its sets without a row
  become single-run tasks, so that only the run that kills its workers ends up ``lost``.

A run whose worker died more often than the cluster allows (a run that crashes its process
every time) becomes a row with status ``lost``; the others go on.
"""

from __future__ import annotations

import itertools
import logging
import math
import pickle
import queue
import uuid
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

import dask
from distributed import Client, Future, KilledWorker, LocalCluster, WorkerPlugin, get_client, get_worker

from gpl2py.sweep.engine import lost_row, row_of
from gpl2py.sweep.metrics import Metric
from gpl2py.sweep.params import ParamSet, run_id
from gpl2py.sweep.worker import Setup, SetupSource, Shipment, install, installed, run_one

__all__ = ["MOST", "PRELOAD", "QUIET", "Client", "Job", "ShipSweep", "batches", "local_cluster", "on_dask"]

#: The most parameter sets one task runs (module docstring).  At a run of 0.1 to 0.2 s (the
#: pick-and-place sample) Dask's few milliseconds per task then cost well under 1 % of the runs.
MOST = 8
#: Tasks per worker thread, at least, over what is left of the sweep: the batches' guided share.
SHARE = 4


@dataclass(frozen=True)
class Job:
    """What every run of one sweep shares, shipped to each worker once with the plugin."""

    token: str  # this sweep's own name: its plugin, its tasks' keys and its events' topic
    digest: str  # the shipment's
    setup: Setup | SetupSource | None
    metrics: list[Metric]
    timeout: float | None

    @property
    def topic(self) -> str:
        """The Dask event topic the workers log every row to, the client subscribes to."""
        return f"gpl2py-sweep-{self.token}"


#: The sweeps whose plugin this worker process has, by token.
_jobs: dict[str, Job] = {}


class ShipSweep(WorkerPlugin):
    """A Dask worker plugin carrying the shipment and the sweep's :class:`Job`: ``setup(worker)``
    unpacks and imports the package in the worker's local folder, on every worker, present or
    future."""

    def __init__(self, shipment: Shipment, job: Job) -> None:
        self.shipment = shipment
        self.job = job
        self.name = job.topic

    def setup(self, worker: Any) -> None:
        install(self.shipment, worker.local_directory)
        _jobs[self.job.token] = self.job

    def teardown(self, worker: Any) -> None:
        _jobs.pop(self.job.token, None)


def batches(sets: list[ParamSet], slots: int, most: int = MOST) -> list[list[ParamSet]]:
    """``sets`` in order, cut into tasks for ``slots`` worker threads (module docstring): each
    batch a ``1 / (SHARE * slots)`` part of the sets still left, between 1 and ``most``."""
    out: list[list[ParamSet]] = []
    done = 0
    while done < len(sets):
        size = max(1, min(most, math.ceil((len(sets) - done) / (SHARE * max(1, slots)))))
        out.append(sets[done:done + size])
        done += size
    return out


def _batch(token: str, key: str, sets: list[ParamSet]) -> list[tuple[str, dict[str, Any]]]:
    """What a Dask task runs: its sets in turn, each row logged as an event as its run ends; the
    rows an earlier attempt of this task logged (its worker died) are taken, not run again.
    Returns every set's ``(run_id, result)``."""
    job = _jobs[token]
    project = installed(job.digest)
    earlier = dict(pickle.loads(message) for _, message in get_client().get_events(key))
    worker = get_worker()
    rows: list[tuple[str, dict[str, Any]]] = []
    for params in sets:
        rid = run_id(params)
        if rid not in earlier:
            result = run_one(project, job.setup, params, job.metrics, job.timeout)
            worker.log_event([job.topic, key], pickle.dumps((rid, result)))
            earlier[rid] = result
        rows.append((rid, earlier[rid]))
    return rows


def local_cluster(workers: int) -> LocalCluster:
    """A Dask cluster of ``workers`` processes on this machine, one thread each (a run holds the
    GIL: two runs in one process would take turns, not run side by side).  Each worker imports
    the runtime as it starts (``preload``, seconds of pinocchio and the robot models), so the
    cluster is ready to run once it is up, and that cost is not paid again inside the sweep.
    Dask's own diagnostics are turned down first (:data:`QUIET`); the nannies pass the settings
    on to the worker processes they start."""
    with dask.config.set(QUIET):
        return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0",
                            silence_logs=logging.ERROR, preload=list(PRELOAD))


#: What a worker imports as it starts (``dask worker --preload gplrt.sim`` does it on a cluster).
PRELOAD = ("gplrt.sim", "gpl2py.sweep.worker")

#: Dask's diagnostics, off or polled less often on the local cluster: they take CPU time from
#: the runs, and on a machine with as many workers as cores that time comes out of the sweep's.
#: The sampling profiler stops the running task every 10 ms to walk its stack (for the
#: dashboard's profile page: about a tenth of a run's CPU time); the nanny's memory monitor reads
#: each worker's memory every 100 ms, the event loops check their own latency every 20 ms and the
#: system monitor samples the processes every 500 ms (together about 6 % of a core in this
#: process, the scheduler's).  docs/sweep.md has the figures and the same settings for
#: ``dask worker``.
QUIET = {
    "distributed.worker.profile.enabled": False,
    "distributed.worker.memory.monitor-interval": "1s",
    "distributed.admin.system-monitor.interval": "2s",
    "distributed.admin.tick.interval": "500ms",
}


def on_dask(client: Any, shipment: Shipment, setup: Setup | SetupSource | None, sets: list[ParamSet],
            metrics: list[Metric], timeout: float | None,
            progress: Callable[[int, int], None] | None = None, most: int = MOST) -> Iterator[dict[str, Any]]:
    """Submit every set to ``client``'s cluster, ``most`` at most per task (:func:`batches`), and
    yield the rows as the runs end."""
    job = Job(uuid.uuid4().hex[:16], shipment.digest, setup, metrics, timeout)
    plugin = ShipSweep(shipment, job)
    client.register_plugin(plugin, name=plugin.name)
    # Both the rows the workers log and the tasks that end come here, in the order they arrive.
    arrived: queue.SimpleQueue[Any] = queue.SimpleQueue()
    client.subscribe_topic(job.topic, arrived.put)
    waiting = {run_id(p): p for p in sets}  # the sets without a row yet
    futures: dict[Future, list[ParamSet]] = {}
    serial = itertools.count()
    keys: list[str] = []

    def submit(groups: list[list[ParamSet]]) -> None:
        named = [f"gpl2py-run-{job.token}-{next(serial)}" for _ in groups]
        keys.extend(named)
        # One graph for them all (client.map): a submit per task costs the client milliseconds each.
        for future, group in zip(client.map(_batch, [job.token] * len(groups), named, groups, key=named,
                                            pure=False), groups):
            futures[future] = group
            future.add_done_callback(arrived.put)

    try:
        submit(batches(sets, sum(client.nthreads().values()), most))
        done = 0
        while waiting:
            item = _next(arrived)
            if isinstance(item, Future):
                rows = _ended(item, futures.pop(item, None), waiting, submit)
                item.release()
            else:  # an event: (time, message)
                rows = [pickle.loads(item[1])]
            for rid, result in rows:
                params = waiting.pop(rid, None)
                if params is None:
                    continue  # its row came already (by event, or in the result of its task)
                yield row_of(params, result) if isinstance(result, dict) else lost_row(params, result, metrics)
                done += 1
                if progress is not None:
                    progress(done, len(sets))
    finally:
        _close(client, job, plugin, list(futures), keys)


def _ended(future: Future, group: list[ParamSet] | None, waiting: dict[str, ParamSet],
           submit: Callable[[list[list[ParamSet]]], None]) -> list[tuple[str, dict[str, Any] | str]]:
    """The results of a task that ended, by run id: what it returned; or, for a batch whose
    worker died more often than the cluster allows, nothing yet (its sets without a row go
    again, one per task); or, for the sets without a row, why they are lost (a text)."""
    if group is None or future.cancelled():
        return []
    try:
        return list(future.result())
    except Exception as exc:  # KilledWorker (the batch killed every worker it ran on), ...
        left = [p for p in group if run_id(p) in waiting]
        if isinstance(exc, KilledWorker) and len(left) > 1:
            submit([[params] for params in left])
            return []
        return [(run_id(p), f"{type(exc).__name__}: {exc}") for p in left]


def _next(arrived: queue.SimpleQueue[Any]) -> Any:
    """The next row or ended task; waiting in short steps, so that Ctrl-C is seen at once."""
    while True:
        try:
            return arrived.get(timeout=0.2)
        except queue.Empty:
            continue


def _close(client: Any, job: Job, plugin: ShipSweep, left: list[Future], keys: list[str]) -> None:
    """Undo what the sweep left on the cluster: the tasks not yet seen to end (when it stopped
    early, Ctrl-C: they are not wanted any more, and must not start on a worker that joins once
    the package's plugin is gone), the subscription, the events and the plugin."""
    try:
        if left:
            client.cancel(left)
        client.unsubscribe_topic(job.topic)
        client.run_on_scheduler(_forget_topics, [job.topic, *keys])
        client.unregister_worker_plugin(plugin.name)
    except Exception:  # noqa: BLE001 - the cluster may be gone already; nothing to undo then
        pass


def _forget_topics(names: list[str], dask_scheduler: Any = None) -> None:
    """Drop the sweep's event topics from the scheduler's log (every row is kept there until
    then; on a long-lived cluster they would pile up sweep after sweep).  Dask has no public
    call for it: the broker's table of topics, when this Dask version has one."""
    topics = getattr(getattr(dask_scheduler, "_broker", None), "_topics", None)
    if isinstance(topics, dict):
        for name in names:
            topics.pop(name, None)

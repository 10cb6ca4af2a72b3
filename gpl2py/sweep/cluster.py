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

The package reaches the workers through a worker plugin (:class:`ShipPackage`): the scheduler
keeps it and hands it to every worker, also one that joins or is restarted after the sweep
began, which unpacks the package's bytes into its own local folder.  Tasks carry only the
parameter set.  A run whose worker died more often than the cluster allows (a run that crashes
its process every time) becomes a row with status ``lost``; the others go on.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterator
from typing import Any

import dask
from distributed import Client, LocalCluster, WorkerPlugin, as_completed

from gpl2py.sweep.engine import lost_row, row_of
from gpl2py.sweep.metrics import Metric
from gpl2py.sweep.params import ParamSet, run_id
from gpl2py.sweep.worker import Setup, SetupSource, Shipment, install, installed, run_one

__all__ = ["PRELOAD", "QUIET", "Client", "ShipPackage", "local_cluster", "on_dask"]


class ShipPackage(WorkerPlugin):
    """A Dask worker plugin carrying the shipment: ``setup(worker)`` unpacks and imports the
    package in the worker's local folder, on every worker, present or future."""

    def __init__(self, shipment: Shipment) -> None:
        self.shipment = shipment
        self.name = f"gpl2py-sweep-{shipment.digest}"

    def setup(self, worker: Any) -> None:
        install(self.shipment, worker.local_directory)


def _task(digest: str, setup: Setup | SetupSource | None, params: ParamSet, metrics: list[Metric],
          timeout: float | None) -> dict[str, Any]:
    """What a Dask task runs: one run, with the package the plugin installed in this process."""
    return run_one(installed(digest), setup, params, metrics, timeout)


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
            progress: Callable[[int, int], None] | None = None) -> Iterator[dict[str, Any]]:
    """Submit every set to ``client``'s cluster and yield the rows as the runs end."""
    plugin = ShipPackage(shipment)
    client.register_plugin(plugin, name=plugin.name)
    futures: dict[Any, ParamSet] = {}
    try:
        for params in sets:
            future = client.submit(_task, shipment.digest, setup, params, metrics, timeout,
                                   key=f"gpl2py-run-{shipment.digest}-{run_id(params)}", pure=False)
            futures[future] = params
        done = 0
        for future in as_completed(futures):
            params = futures.pop(future)
            try:
                yield row_of(params, future.result())
            except Exception as exc:  # KilledWorker (the run killed every worker it ran on), ...
                yield lost_row(params, f"{type(exc).__name__}: {exc}", metrics)
            future.release()
            done += 1
            if progress is not None:
                progress(done, len(sets))
    finally:
        try:
            if futures:  # stopped early (Ctrl-C): the runs not yet back are not wanted any more, and
                # must not start on a worker that joins once the package's plugin is gone
                client.cancel(list(futures))
            client.unregister_worker_plugin(plugin.name)
        except Exception:  # noqa: BLE001 - the cluster may be gone already; nothing to undo then
            pass

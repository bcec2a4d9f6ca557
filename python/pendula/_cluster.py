"""Running a sweep's chunks on a Dask distributed cluster (private; see :func:`pendula.sweep`).

The thread rule
---------------
On every machine of the cluster, the OpenMP threads of one task times the
tasks that machine runs at once never exceed its cores:

    threads per task = max(1, cores // slots)

where ``cores`` is the number of cores the worker process may run on
(``os.sched_getaffinity``) and ``slots`` the sum of ``nthreads`` of all the
worker processes on that machine (a worker runs ``nthreads`` tasks at once).
Two single-threaded workers on a 2-core machine give 1 OpenMP thread per task;
one worker on it gives 2.  A ``threads`` given to ``sweep`` lowers this, never
raises it.  (Dask's nanny sets OMP_NUM_THREADS=1 in every worker; that is a
default of Dask's, not a choice of the user's, so the rule ignores it.)  When
there are more slots than cores the rule gives 1 thread and the
oversubscription is the cluster's own.

The chunks go to the workers as tasks, at most a few per slot in flight, and
their results come back to the driving process, which writes them to the
store: the workers need no access to the store's folder, and the driving
process holds a bounded number of chunks whatever the grid's size.  A worker
that dies takes its running tasks with it; the scheduler gives them to
another worker, so the sweep still completes, with the same numbers (every
chunk depends on the plan alone).
"""

from __future__ import annotations

import contextlib
import os
from urllib.parse import urlparse

from ._optional import require


def usable_cores() -> int:
    """Cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


def omp_threads(cores: int, slots: int, requested: int = 0) -> int:
    """OpenMP threads per task: ``max(1, cores // slots)``, lowered to ``requested`` when that is > 0.

    Examples
    --------
    >>> omp_threads(2, 2), omp_threads(2, 1), omp_threads(8, 3), omp_threads(8, 2, requested=1)
    (1, 2, 2, 1)
    """
    n = max(1, int(cores) // max(1, int(slots)))
    return min(n, int(requested)) if requested and requested > 0 else n


def _host(address: str) -> str:
    return urlparse(address).hostname or address


def slots_by_host(client) -> dict:
    """{host: tasks its workers run at once (the sum of their nthreads)} from the scheduler."""
    slots: dict = {}
    for addr, w in client.scheduler_info(n_workers=-1)["workers"].items():
        h = _host(addr)
        slots[h] = slots.get(h, 0) + int(w.get("nthreads", 1))
    return slots


def task_threads(requested: int, slots: dict) -> int:
    """On a worker: the OpenMP threads one task may use there (the rule above)."""
    get_worker = require("distributed", "sweep", "a Dask cluster").get_worker

    w = get_worker()
    here = slots.get(_host(w.address))
    if here is None:   # a worker that joined after the sweep started: assume its host is as full as the fullest
        here = max(list(slots.values()) + [w.state.nthreads])
    return omp_threads(usable_cores(), here, requested)


def _run_task(fn, plan, i, requested, slots):
    return fn(plan, i, task_threads(requested, slots))


def run_chunks(client, fn, plan, todo, threads, done, per_slot: int = 2) -> None:
    """Compute ``fn(plan, i, omp_threads)`` for every i in ``todo`` on the client's workers,
    calling ``done(*result)`` in the driving process as each finishes."""
    as_completed = require("distributed", "sweep", "a Dask cluster").as_completed

    slots = slots_by_host(client)
    width = max(2, per_slot * max(1, sum(slots.values())))
    pending = iter(todo)
    running = as_completed()
    for i in pending:
        running.add(client.submit(_run_task, fn, plan, i, threads, slots, pure=False))
        if running.count() >= width:
            break
    for fut in running:
        result = fut.result()
        fut.release()
        done(*result)
        nxt = next(pending, None)
        if nxt is not None:
            running.add(client.submit(_run_task, fn, plan, nxt, threads, slots, pure=False))


@contextlib.contextmanager
def local_client(n_workers: int):
    """A Client of a LocalCluster of ``n_workers`` single-threaded worker processes on 127.0.0.1,
    closed (cluster included) on leaving."""
    distributed = require("distributed", "sweep", "a Dask cluster")
    Client, LocalCluster = distributed.Client, distributed.LocalCluster

    with LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=None) as cluster, Client(cluster) as client:
        yield client

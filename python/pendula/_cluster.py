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

Ctrl-C (or any error) in the driving process stops the cluster's work too:
the futures not yet finished are cancelled, and a Dask ``Event`` named for
the sweep is set, which every running task polls twice a second; it then sets
its kernel's cancel flag, so the workers are free again within about a second.
"""

from __future__ import annotations

import contextlib
import os
import uuid
from urllib.parse import urlparse

from . import _checks, _interrupt
from ._optional import require


def check_client(client) -> None:
    """``client`` must be a running dask.distributed.Client: TypeError for another kind
    (an address such as 'tcp://host:8786' is not a Client), ValueError for a closed one."""
    distributed = require("distributed", "sweep", "a Dask cluster (client=)")
    _checks.instance(client, "client", distributed.Client,
                     "a dask.distributed.Client (make one with Client('tcp://host:8786'))")
    status = getattr(client, "status", "running")
    if status != "running":
        raise ValueError(f"client: the Dask client is {status}, not running (give a running Client)")


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


def _run_task(fn, plan, i, requested, slots, stop_name):
    """One chunk on a worker; its kernel stops when the sweep's stop Event is set (Ctrl-C in the driver)."""
    event = require("distributed", "sweep", "a Dask cluster").Event(stop_name)
    with _interrupt.watching(event.is_set):
        return fn(plan, i, task_threads(requested, slots))


def run_chunks(client, fn, plan, todo, threads, done, per_slot: int = 2) -> None:
    """Compute ``fn(plan, i, omp_threads)`` for every i in ``todo`` on the client's workers,
    calling ``done(*result)`` in the driving process as each finishes."""
    distributed = require("distributed", "sweep", "a Dask cluster")

    slots = slots_by_host(client)
    width = max(2, per_slot * max(1, sum(slots.values())))
    stop_name = f"pendula-sweep-stop-{uuid.uuid4().hex}"
    stop = distributed.Event(stop_name, client=client)
    pending = iter(todo)
    running = distributed.as_completed()
    submitted = []

    def submit(i):
        fut = client.submit(_run_task, fn, plan, i, threads, slots, stop_name, pure=False)
        submitted.append(fut)
        running.add(fut)

    try:
        for i in pending:
            submit(i)
            if running.count() >= width:
                break
        for fut in running:
            result = fut.result()
            fut.release()
            done(*result)
            nxt = next(pending, None)
            if nxt is not None:
                submit(nxt)
    except BaseException:
        # Ctrl-C, a failed chunk: the running tasks stop their kernels, the others never start
        with contextlib.suppress(Exception):
            stop.set()
        with contextlib.suppress(Exception):
            client.cancel([f for f in submitted if not f.done()], force=True)
        raise


@contextlib.contextmanager
def local_client(n_workers: int):
    """A Client of a LocalCluster of ``n_workers`` single-threaded worker processes on 127.0.0.1,
    closed (cluster included) on leaving."""
    distributed = require("distributed", "sweep", "a Dask cluster")
    Client, LocalCluster = distributed.Client, distributed.LocalCluster
    from distributed.deploy.spec import SpecCluster

    before = set(SpecCluster._instances)
    try:
        cluster = LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                               dashboard_address=None)
    except BaseException:
        # interrupted while starting (Ctrl-C in its first second): the half-made cluster cannot be
        # closed (Dask's own exit hook would fail on it with a traceback); its worker processes are
        # children of this one and end with it
        for c in set(SpecCluster._instances) - before:
            SpecCluster._instances.discard(c)
        raise
    with cluster, Client(cluster) as client:
        yield client

"""Sweeps on a real multi-process Dask cluster: a worker killed mid-run, the
result still complete and identical to the local run; the thread rule (OpenMP
threads per task times the tasks a machine runs at once <= its cores); the CLI
closes the cluster it opens."""

import doctest
import logging
import os
import signal
import threading
import time

import numpy as np
import pytest

import pendula
from pendula import Scene

xr = pytest.importorskip("xarray")
pytest.importorskip("zarr")
distributed = pytest.importorskip("dask.distributed")
from pendula import _cluster  # noqa: E402

SCENE = Scene(damping=0.1)
# running orbits (torque > eps) integrated over the whole window: every point costs the same
KW = dict(over={"torque": np.linspace(1.05, 2.0, 24), "v0": [0.0, 0.5]}, measure="mean_velocity",
          transient=0.0, t_max=250.0, chunk_points=2)


def process_cluster(n):
    return distributed.LocalCluster(n_workers=n, threads_per_worker=1, processes=True, host="127.0.0.1",
                                     dashboard_address=None, silence_logs=logging.CRITICAL)


def commits(out):
    d = out / "sweep.zarr" / "commits"
    return len(list(d.glob("c*/zarr.json"))) if d.exists() else 0


def test_process_cluster_worker_killed_mid_run_result_complete_and_identical(tmp_path):
    """Two worker processes on 127.0.0.1 (the thread rule checked on them), a sweep through them to a
    store, one worker SIGKILLed after two chunks were committed: the sweep completes, equal to the local run."""
    local = pendula.sweep(SCENE, **KW)
    nchunks = 24
    with process_cluster(2) as cluster, distributed.Client(cluster, timeout=60) as client:
        client.wait_for_workers(2, timeout=60)
        check_thread_rule(client)
        for attempt in range(2):
            out = tmp_path / f"o{attempt}"
            pids = client.run(os.getpid)          # {worker address: pid}
            victim = pids[sorted(pids)[0]]
            result = {}

            def run():
                try:
                    result["ds"] = pendula.sweep(SCENE, out=out, client=client, **KW).load()
                except BaseException as exc:   # reported below
                    result["exc"] = exc
            t = threading.Thread(target=run, daemon=True)
            t.start()
            t0 = time.time()
            while commits(out) < 2 and t.is_alive() and time.time() - t0 < 60:
                time.sleep(0.005)
            done_at_kill = commits(out)
            mid_run = t.is_alive() and done_at_kill < nchunks
            os.kill(victim, signal.SIGKILL)
            t.join(120)
            assert not t.is_alive(), "the sweep did not finish within 120 s of the kill"
            assert "exc" not in result, result.get("exc")
            assert result["ds"].identical(local)
            assert commits(out) == nchunks
            if mid_run:
                break
            client.wait_for_workers(2, timeout=60)   # the nanny restarts the killed worker
        assert mid_run, "the sweep ended before the worker could be killed (twice)"
    # the worker really died
    with pytest.raises(ProcessLookupError):
        os.kill(victim, 0)


def check_thread_rule(client):
    """Each of the two single-threaded workers on 127.0.0.1 gives a task max(1, cores // 2) threads."""
    slots = _cluster.slots_by_host(client)
    assert slots == {"127.0.0.1": 2}
    cores = client.run(_cluster.usable_cores)
    for addr, c in cores.items():
        n = client.submit(_cluster.task_threads, 0, slots, workers=[addr], pure=False).result(timeout=60)
        assert n == max(1, c // 2)
        assert n * slots["127.0.0.1"] <= c or n == 1
        # a threads argument lowers the rule's number, never raises it
        m = client.submit(_cluster.task_threads, 10 ** 6, slots, workers=[addr], pure=False).result(timeout=60)
        assert m == n


def test_thread_rule_never_oversubscribes():
    for cores in range(1, 65):
        for slots in range(1, 65):
            n = _cluster.omp_threads(cores, slots)
            assert n >= 1
            if slots <= cores:
                assert n * slots <= cores and (n + 1) * slots > cores   # as many as fit, no more
            else:
                assert n == 1
            assert _cluster.omp_threads(cores, slots, requested=1) == 1
            assert _cluster.omp_threads(cores, slots, requested=10 ** 6) == n


def test_cluster_docstring_examples_run():
    failures, tried = doctest.testmod(_cluster)
    assert tried >= 1 and failures == 0


def _children():
    kids = set()
    for task in os.listdir(f"/proc/{os.getpid()}/task"):
        try:
            with open(f"/proc/{os.getpid()}/task/{task}/children") as fh:
                kids |= {int(p) for p in fh.read().split()}
        except OSError:
            pass
    alive = set()
    for k in kids:
        try:
            with open(f"/proc/{k}/stat") as fh:
                if fh.read().split(") ")[1][0] != "Z":
                    alive.add(k)
        except OSError:
            pass
    return alive


@pytest.mark.skipif(not os.path.exists("/proc/self/task"), reason="needs /proc")
def test_cli_workers_closes_the_cluster_it_opens(tmp_path, capsys):
    from pendula.cli import main
    scene = tmp_path / "s.nml"
    scene.write_text("&scene\n damping = 0.1\n grid = 'v0', 'damping'\n grid1_range = 0, 4, 12\n"
                     " grid2 = 0.05, 0.2\n measure = 'final_well'\n rtol = 1e-8\n atol = 1e-10\n/\n")
    before = _children()
    assert main(["sweep", str(scene), "-o", str(tmp_path / "o"), "-q", "--workers", "1", "--chunk-points", "4"]) == 0
    t0 = time.time()
    while _children() - before and time.time() - t0 < 30:
        time.sleep(0.1)
    assert not _children() - before, "worker processes left running"
    ds = xr.open_zarr(tmp_path / "o" / "sweep.zarr").load()
    local = pendula.sweep(Scene.from_file(scene), chunk_points=4)
    assert ds.drop_attrs().identical(local.drop_attrs())

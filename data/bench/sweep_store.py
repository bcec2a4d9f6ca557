"""Benchmark (not a test): a large final-well map swept to a Zarr store on a
local Dask process cluster of 1 and of 2 workers, with the driving process's
memory measured.

    .venv/bin/python data/bench/sweep_store.py                  # 3163 x 3163 = 10^7 points
    .venv/bin/python data/bench/sweep_store.py --side 1000      # a smaller map

The map is final_well over (v0 in [0, 4], damping in [0.02, 0.3]) at rtol
1e-8, atol 1e-10 (the grid and tolerances of ``pendula bench sweep``).  For
each worker count: a LocalCluster of single-threaded worker processes on
127.0.0.1 (each task's OpenMP threads from the thread rule in
pendula._cluster: max(1, cores // slots)), the sweep written to a fresh store,
wall time from the call to the returned (lazy) dataset, points per second, and
the driving process's peak resident memory during the sweep (VmHWM after
resetting it through /proc/self/clear_refs; the baseline before the sweep is
recorded too).  The result is appended to data/bench/sweep_store.json
({"records": [...]}) with the machine, date, load average and versions.  The machine is shared: other
users' load is in these figures (the load average is recorded).
"""

import argparse
import json
import logging
import os
import pathlib
import shutil
import sys
import tempfile
import threading
import time

import numpy as np


def rss_kib(field: str) -> int:
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    return -1


def reset_peak() -> bool:
    try:
        with open("/proc/self/clear_refs", "w") as fh:
            fh.write("5")       # resets VmHWM to the current RSS (Linux >= 4.0)
        return True
    except OSError:
        return False


def du(path: pathlib.Path) -> int:
    return sum(f.stat().st_size for f in path.rglob("*") if f.is_file())


def run(side: int, workers: int, chunk_points: int, root: pathlib.Path) -> dict:
    import distributed
    import xarray  # noqa: F401 - imported before the baseline, as the sweep imports them
    import zarr  # noqa: F401

    import pendula
    from pendula import _cluster

    over = {"v0": np.linspace(0.0, 4.0, side), "damping": np.linspace(0.02, 0.3, side)}
    out = root / f"w{workers}"
    shutil.rmtree(out, ignore_errors=True)
    with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None, silence_logs=logging.ERROR) as cluster, \
            distributed.Client(cluster) as client:
        client.wait_for_workers(workers, timeout=120)
        slots = _cluster.slots_by_host(client)
        cores = client.run(_cluster.usable_cores)
        omp = {a: _cluster.omp_threads(c, slots[_cluster._host(a)]) for a, c in cores.items()}
        # warm the workers (imports), so that start-up is not in the figure
        client.run(lambda: __import__("pendula.sweeps"))
        base = rss_kib("VmRSS")
        exact_peak = reset_peak()
        samples = []
        stop = threading.Event()

        def sample():
            while not stop.wait(0.2):
                samples.append(rss_kib("VmRSS"))
        th = threading.Thread(target=sample, daemon=True)
        th.start()
        load0 = os.getloadavg()
        t0 = time.perf_counter()
        ds = pendula.sweep(pendula.Scene(damping=0.1), over=over, measure="final_well", rtol=1e-8, atol=1e-10,
                           out=out, chunk_points=chunk_points, client=client)
        secs = time.perf_counter() - t0
        stop.set()
        th.join()
        peak = rss_kib("VmHWM") if exact_peak else max(samples + [base])
        load1 = os.getloadavg()
    st = ds.status
    n = int(st.size)
    rec = {"workers": workers, "threads_per_worker": 1, "omp_threads_per_task": sorted(set(omp.values())),
           "seconds": secs, "points_per_second": n / secs,
           "driver_rss_before_MiB": base / 1024, "driver_peak_rss_MiB": peak / 1024,
           "driver_peak_rss_how": "VmHWM reset before the sweep" if exact_peak else "VmRSS sampled every 0.2 s",
           "fraction_decided": ds.attrs.get("fraction_decided"),
           "store_MiB": du(out / "sweep.zarr") / 2 ** 20,
           "raw_MiB": sum(ds[v].size * ds[v].dtype.itemsize for v in ds.data_vars) / 2 ** 20,
           "load_average_before": load0, "load_average_after": load1}
    shutil.rmtree(out, ignore_errors=True)
    return rec


def save(path, record) -> None:
    """Keep the earlier records of the file ({"records": [...]}) and put this one (replaced as it grows) last."""
    p = pathlib.Path(path)
    try:
        records = json.loads(p.read_text())["records"]
    except (OSError, ValueError, KeyError):
        records = []
    records = [r for r in records if r.get("machine", {}).get("date_utc") != record["machine"]["date_utc"]]
    p.write_text(json.dumps({"records": records + [record]}, indent=1) + "\n")


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--side", type=int, default=3163, help="points per axis (default 3163: 10^7 points)")
    p.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    p.add_argument("--chunk-points", type=int, default=100_000)
    p.add_argument("--dir", default=None, help="folder for the stores (default: a temporary folder)")
    p.add_argument("--json", default=str(pathlib.Path(__file__).with_name("sweep_store.json")))
    args = p.parse_args(argv)

    import importlib.metadata as md

    from pendula.studies.bench import machine_record

    record = {"what": "final-well map swept to a Zarr store on a local Dask process cluster",
              "grid": f"{args.side} x {args.side} over v0 in [0, 4], damping in [0.02, 0.3]",
              "points": args.side ** 2, "chunk_points": args.chunk_points, "rtol": 1e-8, "atol": 1e-10,
              "machine": machine_record(), "runs": []}
    for pkg in ("zarr", "numcodecs", "xarray", "dask", "distributed"):
        try:
            record["machine"]["versions"][pkg] = md.version(pkg)
        except md.PackageNotFoundError:
            record["machine"]["versions"][pkg] = None
    root = pathlib.Path(args.dir) if args.dir else pathlib.Path(tempfile.mkdtemp(prefix="pendula-bench-"))
    try:
        for w in args.workers:
            r = run(args.side, w, args.chunk_points, root)
            record["runs"].append(r)
            print(f"{args.side ** 2} points, {w} worker(s) x 1 thread, OpenMP {r['omp_threads_per_task']} per task: "
                  f"{r['seconds']:.1f} s, {r['points_per_second']:.0f} points/s; driving process peak RSS "
                  f"{r['driver_peak_rss_MiB']:.0f} MiB (before the sweep {r['driver_rss_before_MiB']:.0f} MiB); "
                  f"store {r['store_MiB']:.0f} MiB for {r['raw_MiB']:.0f} MiB raw; load {r['load_average_before']}",
                  flush=True)
            save(args.json, record)   # after every run
    finally:
        if not args.dir:
            shutil.rmtree(root, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())

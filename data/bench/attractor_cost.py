"""The cost of an attractor map against the final-well map of the same size.

Both maps are n x n grids over (theta0, v0) of the damped pendulum (beta = 0.5):
the final-well map of the undriven pendulum (measure ``final_well``, each point
stops when its well is decided) and the attractor map of the driven one
(A = 1.35, Omega = 2/3: ``pendula.attractor_map``, a transient and
stroboscopic samples for every point, then the recurrence labelling).  Each is
timed once in this process (wall and CPU), the labelling separately, and the
result written as JSON beside this file.

    python data/bench/attractor_cost.py [--n 1000] [--threads 0]
"""

import argparse
import json
import os
import pathlib
import platform
import time

import numpy as np

import pendula
from pendula import attractor_map
from pendula.dynamics.attractors import label_attractors


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200, help="points per axis (the issue's size: 1000)")
    ap.add_argument("--threads", type=int, default=0, help="OpenMP threads (0: all cores)")
    ap.add_argument("--out", default=str(pathlib.Path(__file__).with_name("attractor_cost.json")))
    a = ap.parse_args()
    n = a.n
    grid = {"theta0": np.linspace(-np.pi, np.pi, n), "v0": np.linspace(-3.0, 3.0, n)}
    rows = {}

    t0, c0 = time.perf_counter(), time.process_time()
    fw = pendula.sweep(pendula.Scene(damping=0.5), over=grid, measure="final_well", t_max=500.0,
                       threads=a.threads)
    rows["final_well"] = {"wall_s": time.perf_counter() - t0, "cpu_s": time.process_time() - c0,
                          "fraction_decided": float((fw.status == 0).mean())}

    sc = pendula.Scene(damping=0.5, drive_amplitude=1.35, drive_frequency=2 / 3, rtol=1e-9, atol=1e-11)
    t0, c0 = time.perf_counter(), time.process_time()
    am = attractor_map(sc, grid, transient=300.0, samples=16, threads=a.threads)
    rows["attractor"] = {"wall_s": time.perf_counter() - t0, "cpu_s": time.process_time() - c0,
                         "attractors": [(x.kind, x.period, x.fraction) for x in am.attractors]}
    # the labelling alone, on the same samples
    pc = pendula.sweep(sc, over={"theta0": grid["theta0"][:50], "v0": grid["v0"]}, measure="poincare",
                       transient=300.0, samples=16, threads=a.threads)
    th = np.tile(pc.theta.values, (n // 50 + 1, 1, 1))[:n]
    t0 = time.perf_counter()
    label_attractors(th, np.tile(pc.v.values, (n // 50 + 1, 1, 1))[:n])
    rows["attractor"]["labelling_wall_s"] = time.perf_counter() - t0
    ratio = rows["attractor"]["wall_s"] / rows["final_well"]["wall_s"]
    rec = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "machine": platform.processor() or
           platform.machine(), "cores": os.cpu_count(), "load_average": os.getloadavg(), "n": n,
           "threads": a.threads, "pendula": pendula.__version__, "rows": rows, "ratio_wall": ratio}
    pathlib.Path(a.out).write_text(json.dumps(rec, indent=1) + "\n")
    print(f"{n} x {n}: final-well map {rows['final_well']['wall_s']:.2f} s, attractor map "
          f"{rows['attractor']['wall_s']:.2f} s (labelling {rows['attractor']['labelling_wall_s']:.2f} s): "
          f"{ratio:.1f}x")


if __name__ == "__main__":
    main()

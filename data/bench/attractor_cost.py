"""The cost of the default attractor map against the default final-well map of the same grid.

Both maps are n x n grids over theta0 in [-pi, pi], v0 in [-3, 3] of the damped pendulum (beta = 0.5):
the final-well map of the undriven pendulum (``pendula.sweep(..., 'final_well')`` with its defaults: each
point stops when its well is decided) and the attractor map of the driven one (Omega = 2/3, at the
amplitudes A = 1.07 (two period-2 attractors), 1.2 (one chaotic) and 1.35 (two period-1 rotations):
``pendula.attractor_map`` with its defaults: the recurrence method with early stopping, built coarse to fine
with labels inherited from the level above).  The runs are
interleaved (final-well, then each attractor map, ``--repeat`` times) on the same threads and the best
wall time of each is kept (the machine is shared; its load average is recorded before and after).  For the
smaller grids the former method (``method='samples'``: 600 time units and 48 samples for every point) is
timed once too.  The record goes to data/bench/attractor_cost.json (one record per grid size, replaced
when measured again), with the machine and the date.

    python data/bench/attractor_cost.py [--n 150] [--repeat 3] [--threads 2] [--amplitudes 1.07,1.2,1.35]
"""

import json
import math
import os
import pathlib

import numpy as np

import pendula
from pendula.studies.bench import machine_record
from _bench_timing import cost_arguments, timed

OUT = pathlib.Path(__file__).with_name("attractor_cost.json")


def main():
    ap = cost_arguments(__doc__, 150, "points per axis")
    ap.add_argument("--amplitudes", default="1.07,1.2,1.35")
    ap.add_argument("--samples-method", choices=("auto", "yes", "no"), default="auto",
                    help="time the former method once (auto: for n <= 150)")
    a = ap.parse_args()
    n = a.n
    amps = [float(x) for x in a.amplitudes.split(",")]
    grid = {"theta0": np.linspace(-math.pi, math.pi, n), "v0": np.linspace(-3.0, 3.0, n)}
    load0 = os.getloadavg()
    best = {"final_well": math.inf, **{f"attractor_{A}": math.inf for A in amps}}
    cpu = dict.fromkeys(best, math.inf)
    info = {}
    for _ in range(a.repeat):
        w, c, _ = timed(lambda: pendula.sweep(pendula.Scene(damping=0.5), grid, "final_well", threads=a.threads))
        best["final_well"], cpu["final_well"] = min(best["final_well"], w), min(cpu["final_well"], c)
        for A in amps:
            sc = pendula.Scene(damping=0.5, drive_amplitude=A, drive_frequency=2 / 3)
            w, c, am = timed(lambda: pendula.attractor_map(sc, grid, threads=a.threads))
            k = f"attractor_{A}"
            best[k], cpu[k] = min(best[k], w), min(cpu[k], c)
            info[k] = {"attractors": [[x.kind, x.period, round(x.fraction, 6)] for x in am.attractors],
                       "undecided": am.undecided, "rechecked": am.rechecked, "recheck_changed": am.recheck_changed,
                       "mean_drive_periods_per_point": am.dataset.attrs["mean_periods"],
                       "levels": am.dataset.attrs["levels"], "inherited": am.dataset.attrs["inherited"],
                       "boundary_inherited_not_rechecked": am.dataset.attrs["boundary_inherited"],
                       "tight_from_start": am.dataset.attrs["tight_from_start"],
                       "new_in_labelling": am.dataset.attrs["new_in_labelling"]}
    rows = {k: {"best_wall_s": best[k], "best_process_cpu_s": cpu[k], **info.get(k, {})} for k in best}
    for A in amps:
        rows[f"attractor_{A}"]["ratio_to_final_well"] = best[f"attractor_{A}"] / best["final_well"]
    if a.samples_method == "yes" or (a.samples_method == "auto" and n <= 150):
        for A in amps:
            sc = pendula.Scene(damping=0.5, drive_amplitude=A, drive_frequency=2 / 3)
            w, c, am = timed(lambda: pendula.attractor_map(sc, grid, method="samples", threads=a.threads))
            rows[f"samples_method_{A}"] = {
                "wall_s_once": w, "process_cpu_s": c, "ratio_to_final_well": w / best["final_well"],
                "attractors": [[x.kind, x.period, round(x.fraction, 6)] for x in am.attractors]}
    rec = {"what": "default attractor map (recurrence, early stopping) against the default final-well map of "
                   "the same grid, interleaved, best of --repeat wall times",
           "grid": f"{n} x {n} over theta0 in [-pi, pi], v0 in [-3, 3]", "n": n, "threads": a.threads,
           "repeat": a.repeat, "machine": machine_record(), "load_average_before": load0,
           "load_average_after": os.getloadavg(), "rows": rows}
    records = []
    if OUT.exists():
        try:
            records = [r for r in json.loads(OUT.read_text()).get("records", []) if r.get("n") != n]
        except (ValueError, AttributeError):
            records = []
    OUT.write_text(json.dumps({"records": sorted(records + [rec], key=lambda r: r["n"])}, indent=1) + "\n")
    print(f"{n} x {n}, {a.threads} threads, best of {a.repeat}: final-well map {best['final_well']:.2f} s")
    for A in amps:
        r = rows[f"attractor_{A}"]
        print(f"  A = {A}: attractor map {r['best_wall_s']:.2f} s = {r['ratio_to_final_well']:.1f}x "
              f"({r['mean_drive_periods_per_point']:.1f} drive periods a point, {r['inherited']} inherited, "
              f"{r['rechecked']} rechecked, {r['recheck_changed']} changed)")
        if f"samples_method_{A}" in rows:
            s = rows[f"samples_method_{A}"]
            print(f"           former method {s['wall_s_once']:.2f} s = {s['ratio_to_final_well']:.1f}x")


if __name__ == "__main__":
    main()

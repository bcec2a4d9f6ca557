"""What a whole diagram costs: bifurcation_tree from A = 1.0 (damping 0.5, drive_frequency 2/3) to
depth 5, past the fourth period doubling (every branch to period 16: the symmetric orbit, its two
asymmetric children and, in each child's subtree, the orbits of period 2, 4, 8 and 16; 11 branches),
against two peers:

* the scipy computation of the attracting route's five branch points (data/gen_continuation_reference.py:
  DOP853 at 1e-13 on the variational equations, Newton, brentq): one route, not the tree;
* a brute-force orbit diagram, ``sweep(measure='poincare')`` over A on a grid, whose edges are only as good
  as the grid: the grid of 2000 points over [1.0, 1.0828] (step 4e-5) that it takes to see the
  period-16 window at all, and the edge accuracy that grid gives (half a step), against the tree's 1e-12.

pendula best of two, the peers once; wall and CPU seconds.  The target: the tree under 30 s.

    .venv/bin/python data/bench/branch_tree_cost.py     # writes data/bench/branch_tree_cost.json
"""

import json
import os
import platform
import time
from pathlib import Path

import numpy as np

import pendula
from _bench_timing import reference_script, timed

HERE = Path(__file__).resolve().parent
STOP = 1.0828


def run_tree():
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2 / 3)
    tree = pendula.bifurcation_tree(sc, (0.1, 1.9), "drive_amplitude", STOP, depth=5)
    return tree


def run_sweep():
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2 / 3)
    A = np.linspace(1.0, STOP, 2000)
    return pendula.sweep(sc, {"drive_amplitude": A}, "poincare", transient=600.0, samples=32)


def main():
    ref = reference_script("gen_continuation_reference.py", "gen_ref")
    tree_runs = [timed(run_tree) for _ in range(2)]
    bt = min(tree_runs, key=lambda r: r[0])
    tree = bt[2]
    sw = timed(run_sweep)
    peer = timed(ref.cascade)
    want = {(p["kind"], p["k"]): p["value"] for p in peer[2]}
    diffs = [abs(b.value - want[(b.kind, int(b.period))]) for n in tree.walk() for b in n.branch.bifurcations
             if (b.kind, int(b.period)) in want]
    periods = sorted({int(p) for b in tree.branches() for p in np.unique(b.period)})
    rec = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
           "machine": platform.processor() or platform.machine(), "cores": os.cpu_count(),
           "load_average": os.getloadavg(), "pendula": pendula.__version__,
           "task": f"bifurcation_tree(depth=5) from A=1.0 to {STOP} (damping 0.5, drive_frequency 2/3)",
           "rows": {"pendula_tree": {"wall_s": bt[0], "cpu_s": bt[1], "all_wall_s": [r[0] for r in tree_runs],
                                     "branches": len(tree), "periods": periods,
                                     "points": int(sum(len(b) for b in tree.branches())),
                                     "branch_point_accuracy": "located to about 1e-12"},
                    "pendula_sweep_2000": {"wall_s": sw[0], "cpu_s": sw[1],
                                           "edge_accuracy": float((STOP - 1.0) / 1999 / 2)},
                    "scipy_route": {"wall_s": peer[0], "cpu_s": peer[1],
                                    "what": "gen_continuation_reference.cascade(): the attracting route's five "
                                            "points by brentq on the multipliers (one route, no tree)"}},
           "max_difference_to_scipy": max(diffs), "target_s": 30.0,
           "ratio_sweep_to_tree_wall": sw[0] / bt[0], "ratio_scipy_route_to_tree_wall": peer[0] / bt[0]}
    print(f"tree {bt[0]:.2f} s wall ({bt[1]:.2f} s CPU, {len(tree)} branches, periods {periods}); "
          f"sweep of 2000 {sw[0]:.2f} s (edges to {rec['rows']['pendula_sweep_2000']['edge_accuracy']:.1e}); "
          f"scipy route {peer[0]:.2f} s; branch points agree with scipy to {max(diffs):.1e}")
    (HERE / "branch_tree_cost.json").write_text(json.dumps(rec, indent=1) + "\n")


if __name__ == "__main__":
    main()

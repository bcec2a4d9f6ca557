"""The cost per sample of the spherical pendulum's exact path against numpy's sin.

One orbit (a generic one, 40 degrees to 80 degrees or so, L_z of order one),
``--n`` sample times spread over 1000 polar periods: ``SphericalOrbit.path(t)``
(theta, phi and both rates) against ``np.sin`` of the same number of values,
and the planar exact path (``pendula.exact_motion``) as a second yardstick.
The three are interleaved ``--repeat`` times and the best wall time of each is
kept (the machine is shared).  The ratio path / sin is printed and the record
goes to data/bench/spherical_cost.json with the machine and the date.

    python data/bench/spherical_cost.py [--n 1000000] [--repeat 7]
"""

import argparse
import json
import pathlib
import time

import numpy as np

import pendula
from pendula.studies.bench import machine_record

OUT = pathlib.Path(__file__).with_name("spherical_cost.json")


def best(fn, times):
    t0 = time.perf_counter()
    fn()
    times.append(time.perf_counter() - t0)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1_000_000, help="samples")
    ap.add_argument("--repeat", type=int, default=7, help="interleaved repetitions (best of)")
    a = ap.parse_args()
    o = pendula.spherical_orbit(0.8, 0.5, 1.1)
    t = np.linspace(0.0, 1000 * o.period, a.n)
    x = t.copy()
    o.path(t[:1000])
    runs = {"spherical_path": [], "numpy_sin": [], "planar_exact_path": []}
    for _ in range(a.repeat):
        best(lambda: o.path(t), runs["spherical_path"])
        best(lambda: np.sin(x), runs["numpy_sin"])
        best(lambda: pendula.exact_motion(0.8, 0.5, 1.0, t), runs["planar_exact_path"])
    ns = {k: min(v) / a.n * 1e9 for k, v in runs.items()}
    ratio = ns["spherical_path"] / ns["numpy_sin"]
    for k, v in ns.items():
        print(f"{k:>18}: {v:8.2f} ns per sample")
    print(f"spherical path / numpy sin: {ratio:.1f}  (goal: 4)")
    print(f"spherical path / planar exact path: {ns['spherical_path'] / ns['planar_exact_path']:.1f}")
    rec = {"what": "exact spherical path (theta, phi, rates) per sample against numpy's sin of as many values, "
                   "interleaved, best of --repeat wall times",
           "orbit": "theta0 = 0.8, theta_dot0 = 0.5, phi_dot0 = 1.1, eps = 1; t over 1000 polar periods",
           "n": a.n, "repeat": a.repeat, "ns_per_sample": ns, "ratio_to_numpy_sin": ratio,
           "ratio_to_planar_exact_path": ns["spherical_path"] / ns["planar_exact_path"],
           "machine": machine_record()}
    OUT.write_text(json.dumps(rec, indent=1) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()

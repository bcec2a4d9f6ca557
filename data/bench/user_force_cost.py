"""What a force of one's own costs against the built-in effect it restates.

The driven damped pendulum theta'' = -sin(theta) - 0.1 theta' + 1.2 cos(0.7 t) (theta0 = 1, v0 = 0.5,
DOP853 at rtol 1e-10, t up to 20000, chaotic) run four ways in one process:
  builtin   damping = 0.1 (the kernel's own force law);
  c         the same force -p[0] v as a C function compiled here with the system cc and passed
            as a ctypes function (force=, force_params=[0.1]);
  python    the same force as a Python callable (the documented slow path; a shorter span,
            scaled by the right-hand-side evaluations);
  scipy     the peer: scipy's solve_ivp DOP853 on the same right-hand side in Python (a shorter
            span, scaled likewise).
The runs are interleaved, best of N; the time per right-hand-side evaluation and the ratios to
the built-in are printed and written as JSON beside this file.  The brief's goal: c <= 2 x builtin.

    python data/bench/user_force_cost.py [--repeat 15]
"""

import argparse
import ctypes
import json
import os
import pathlib
import platform
import shutil
import subprocess
import tempfile
import time

import numpy as np
from scipy.integrate import solve_ivp

import pendula

SRC = "double lin(double t, double th, double v, const double *p) { return -p[0] * v; }\n"


def _compile(d):
    cc = shutil.which("cc")
    src, lib = pathlib.Path(d) / "f.c", pathlib.Path(d) / "libf.so"
    src.write_text(SRC)
    subprocess.run([cc, "-O2", "-shared", "-fPIC", str(src), "-o", str(lib)], check=True)
    f = ctypes.CDLL(str(lib)).lin
    f.restype = ctypes.c_double
    f.argtypes = [ctypes.c_double] * 3 + [ctypes.POINTER(ctypes.c_double)]
    return f, cc


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=15)
    ap.add_argument("--out", default=str(pathlib.Path(__file__).with_name("user_force_cost.json")))
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as d:
        f, cc = _compile(d)
        base = pendula.Scene(theta0=1.0, v0=0.5, drive_amplitude=1.2, drive_frequency=0.7, rtol=1e-10, atol=1e-12)
        t_long, t_short = np.linspace(0, 20000, 2001), np.linspace(0, 100, 51)
        cc_version = subprocess.run([cc, "--version"], capture_output=True, text=True).stdout.splitlines()[0]

        def builtin():
            return pendula.simulate(base.replace(damping=0.1), t_long).stats["rhs_evaluations"]

        def c():
            return pendula.simulate(base, t_long, force=f, force_params=[0.1]).stats["rhs_evaluations"]

        def python():
            return pendula.simulate(base, t_short, force=lambda t, th, v, p: -p[0] * v,
                                    force_params=[0.1]).stats["rhs_evaluations"]

        def scipy():
            s = solve_ivp(lambda t, y: [y[1], -np.sin(y[0]) - 0.1 * y[1] + 1.2 * np.cos(0.7 * t)], (0, 100), [1.0, 0.5], method="DOP853",
                          rtol=1e-10, atol=1e-12, t_eval=t_short)
            return s.nfev

        runs = {"builtin": builtin, "c": c, "python": python, "scipy": scipy}
        best = {k: (np.inf, 0) for k in runs}
        for _ in range(a.repeat):            # interleaved: the load changes all alike
            for k, fn in runs.items():
                t0 = time.perf_counter()
                n = fn()
                dt = time.perf_counter() - t0
                if dt < best[k][0]:
                    best[k] = (dt, n)
        # agreement of the compiled force with the built-in damping over t <= 100 (the orbit is chaotic:
        # the two sum the same terms in another order, and later the rounding grows; the test asserts 1e-8)
        diff = float(np.max(np.abs(pendula.simulate(base.replace(damping=0.1), t_short).theta -
                                   pendula.simulate(base, t_short, force=f, force_params=[0.1]).theta)))
    per = {k: best[k][0] / best[k][1] for k in runs}
    rows = {k: {"seconds": best[k][0], "rhs_evaluations": int(best[k][1]), "seconds_per_rhs": per[k],
                "ratio_to_builtin_per_rhs": per[k] / per["builtin"]} for k in runs}
    for k, r in rows.items():
        print(f"{k:8s} {r['seconds']:.4f} s  {r['rhs_evaluations']:8d} rhs  {r['seconds_per_rhs'] * 1e9:8.1f} ns/rhs"
              f"  x{r['ratio_to_builtin_per_rhs']:.2f}")
    print(f"c / builtin (whole run): {best['c'][0] / best['builtin'][0]:.2f}; max |theta_c - theta_builtin| (t <= 100) = {diff:.2e}")
    rec = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
           "machine": platform.processor() or platform.machine(), "cores": os.cpu_count(),
           "load_average": os.getloadavg(), "pendula": pendula.__version__, "compiler": cc_version,
           "repeat": a.repeat, "rows": rows, "ratio_c_to_builtin_wall": best["c"][0] / best["builtin"][0],
           "max_theta_difference": diff}
    pathlib.Path(a.out).write_text(json.dumps(rec, indent=1) + "\n")


if __name__ == "__main__":
    main()

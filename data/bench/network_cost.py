"""What a chain of pendula costs: pendula.Network.simulate (DOP853) against SciPy's solve_ivp (DOP853,
the right-hand side vectorised in numpy) on the Frenkel-Kontorova chain

    φ_i'' = −sin φ_i + K (φ_{i+1} − 2 φ_i + φ_{i−1}),  free ends, K = 1,

N = 2, 16, 256, 4096, from a smooth wave φ_i(0) = 0.5 sin(2πi/N + 0.3), over t = 0 .. 10.
Equal error: both run at rtol 1e-6, 1e-8, 1e-10 (atol rtol/100); each run's error is measured against
SciPy's own DOP853 at rtol 1e-13 (the reference, not pendula's output); SciPy's time at pendula's error
is interpolated in log-log between SciPy's two bracketing runs.  pendula and SciPy are interleaved, best
of three each (best of one for SciPy at N = 4096, whose runs take seconds).  numbalsoda and diffrax are
timed only when already installed.

    .venv/bin/python data/bench/network_cost.py     # writes data/bench/network_cost.json
"""

import json
import os
import platform
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

import pendula

HERE = Path(__file__).resolve().parent
SIZES = (2, 16, 256, 4096)
RTOLS = (1e-6, 1e-8, 1e-10)
T_END = 10.0
K = 1.0


def rhs_factory(n):
    def f(t, y):
        q, v = y[:n], y[n:]
        lap = np.zeros(n)
        lap[:-1] += q[1:] - q[:-1]
        lap[1:] += q[:-1] - q[1:]
        return np.concatenate([v, -np.sin(q) + K * lap])
    return f


def timed(fn, repeat):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def peers_installed():
    found = []
    for name in ("numbalsoda", "diffrax"):
        try:
            __import__(name)
            found.append(name)
        except ImportError:
            pass
    return found


def main():
    rows = []
    for n in SIZES:
        phi0 = 0.5 * np.sin(2 * np.pi * np.arange(n) / n + 0.3)
        y0 = np.concatenate([phi0, np.zeros(n)])
        f = rhs_factory(n)
        ref = solve_ivp(f, (0, T_END), y0, method="DOP853", rtol=1e-13, atol=1e-15).y[:, -1]
        net = pendula.Network(n, topology="chain", strength=K)
        reps_s = 1 if n >= 4096 else 3
        pend, sci = [], []
        for rtol in RTOLS:
            tp, run = timed(lambda: net.simulate([0.0, T_END], phi0, 0.0, rtol=rtol, atol=rtol / 100), 5)
            yp = np.concatenate([run.phi.values[-1], run.v.values[-1]])
            ts, sol = timed(lambda: solve_ivp(f, (0, T_END), y0, method="DOP853", rtol=rtol, atol=rtol / 100),
                            reps_s)
            pend.append((rtol, float(np.max(np.abs(yp - ref))), tp, int(run.attrs["steps"])))
            sci.append((rtol, float(np.max(np.abs(sol.y[:, -1] - ref))), ts, int(sol.t.size - 1)))
        # SciPy's time at pendula's error: log-log interpolation between SciPy's runs
        le = np.log([s[1] for s in sci])
        lt = np.log([s[2] for s in sci])
        order = np.argsort(le)
        for (rtol, err, tp, steps), s in zip(pend, sci):
            ts_eq = float(np.exp(np.interp(np.log(err), le[order], lt[order])))
            inside = le.min() <= np.log(err) <= le.max()
            rows.append({"n": n, "rtol": rtol, "pendula_error": err, "pendula_s": tp, "pendula_steps": steps,
                         "scipy_error": s[1], "scipy_s": s[2], "scipy_steps": s[3],
                         "scipy_s_at_pendula_error": ts_eq, "interpolated": bool(inside),
                         "ratio_scipy_over_pendula": ts_eq / tp})
            print(f"N={n:5d} rtol={rtol:.0e}  pendula {tp * 1e3:9.3f} ms err {err:.1e}   "
                  f"scipy {s[2] * 1e3:9.3f} ms err {s[1]:.1e}   scipy/pendula at equal error "
                  f"{ts_eq / tp:8.1f}{'' if inside else ' (extrapolated)'}", flush=True)
    rec = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
           "machine": platform.processor() or platform.machine(), "cores": os.cpu_count(),
           "load_average": os.getloadavg(), "pendula": pendula.__version__,
           "task": f"FK chain, free ends, K={K}, t = 0..{T_END}, DOP853 both; error vs SciPy DOP853 rtol 1e-13",
           "peers_not_installed": [p for p in ("numbalsoda", "diffrax") if p not in peers_installed()],
           "rows": rows}
    (HERE / "network_cost.json").write_text(json.dumps(rec, indent=1) + "\n")


if __name__ == "__main__":
    main()

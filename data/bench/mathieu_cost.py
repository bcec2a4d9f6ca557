"""What a Mathieu characteristic value costs: pendula.mathieu_a / mathieu_b against
SciPy's mathieu_a / mathieu_b and GSL's gsl_sf_mathieu_a_e / _b_e (ctypes on
libgsl, its error handler off, status codes checked), per value, on the same
points, interleaved (best of five rounds each), and the accuracy of each
against data/mathieu_reference.csv (integer orders; SciPy and GSL take no
other).  A transmon spectrum (10 levels at 1,000 offset charges, E_J/E_C = 50)
against scqubits' charge-basis Transmon (ncut = 30, its levels then agree
with pendula's to 3e-13) when scqubits is installed.  GSL is called once per
value through ctypes, which adds a few tenths of a microsecond to each.

    .venv/bin/python data/bench/mathieu_cost.py     # writes data/bench/mathieu_cost.json

Single-threaded (OMP_NUM_THREADS=1 is set before pendula loads): a per-value
comparison.
"""

import csv
import ctypes
import ctypes.util
import json
import os
import platform
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402
import scipy  # noqa: E402
import scipy.special as sp  # noqa: E402

import pendula  # noqa: E402

HERE = Path(__file__).resolve().parent
EPS = np.finfo(float).eps


class _Result(ctypes.Structure):
    _fields_ = [("val", ctypes.c_double), ("err", ctypes.c_double)]


def _gsl():
    lib = ctypes.CDLL(ctypes.util.find_library("gsl"))
    lib.gsl_set_error_handler_off()
    for name in ("gsl_sf_mathieu_a_e", "gsl_sf_mathieu_b_e"):
        f = getattr(lib, name)
        f.argtypes = [ctypes.c_int, ctypes.c_double, ctypes.POINTER(_Result)]
        f.restype = ctypes.c_int
    return lib


def gsl_values(lib, kind, n, q):
    f = lib.gsl_sf_mathieu_a_e if kind == "a" else lib.gsl_sf_mathieu_b_e
    out = np.empty(len(n))
    r = _Result()
    for i, (ni, qi) in enumerate(zip(n, q)):
        st = f(int(ni), float(qi), ctypes.byref(r))
        out[i] = r.val if st == 0 else np.nan
    return out


def timed(fn, rounds=5):
    best = np.inf
    out = None
    for _ in range(rounds):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def points(rng, size, qmax):
    n = rng.integers(0, 11, size)
    q = 10 ** rng.uniform(-2, np.log10(qmax), size)
    return n.astype(float), q


def accuracy():
    rows = [r for r in csv.DictReader(open(HERE.parent / "mathieu_reference.csv"))
            if float(r["nu"]) == int(float(r["nu"])) and float(r["nu"]) <= 200]
    lib = _gsl()
    worst = {"pendula": 0.0, "scipy": 0.0, "gsl": 0.0}
    wrong = {"pendula": 0, "scipy": 0, "gsl": 0}
    for r in rows:
        n, q, ref = int(float(r["nu"])), float(r["q"]), float(r["value"])
        f = pendula.mathieu_a if r["kind"] == "a" else pendula.mathieu_b
        s = sp.mathieu_a if r["kind"] == "a" else sp.mathieu_b
        got = {"pendula": float(f(n, q)), "scipy": float(s(n, q)),
               "gsl": float(gsl_values(lib, r["kind"], [n], [q])[0])}
        for k, v in got.items():
            e = abs(v - ref) / max(1.0, abs(ref)) / EPS if np.isfinite(v) else np.inf
            worst[k] = max(worst[k], e)
            wrong[k] += int(e > 1e6)
    worst = {k: (float(v) if np.isfinite(v) else "a value failed (NaN or an error status)") for k, v in worst.items()}
    return {"points": len(rows), "worst_error_eps": worst, "values_off_by_more_than_1e6_eps_or_failed": wrong}


def main():
    rng = np.random.default_rng(7)
    lib = _gsl()
    rec = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
           "machine": platform.processor() or platform.machine(), "cores": os.cpu_count(),
           "load_average": os.getloadavg(), "pendula": pendula.__version__, "scipy": scipy.__version__,
           "threads": os.environ["OMP_NUM_THREADS"], "cases": {}}
    for label, qmax in (("q in [0.01, 10]", 10.0), ("q in [0.01, 1000]", 1000.0)):
        n, q = points(rng, 2000, qmax)
        t_p = t_s = t_g = np.inf
        for _ in range(3):   # interleaved rounds
            t_p = min(t_p, timed(lambda: pendula.mathieu_a(n, q))[0])
            t_s = min(t_s, timed(lambda: sp.mathieu_a(n, q))[0])
            t_g = min(t_g, timed(lambda: gsl_values(lib, "a", n, q), rounds=2)[0])
        per = {k: v / len(n) * 1e6 for k, v in (("pendula", t_p), ("scipy", t_s), ("gsl", t_g))}
        rec["cases"][label] = {"values": len(n), "us_per_value": per,
                               "scipy_over_pendula": t_s / t_p, "gsl_over_pendula": t_g / t_p}
        print(f"{label}: pendula {per['pendula']:.2f} us, scipy {per['scipy']:.2f} us, "
              f"gsl {per['gsl']:.2f} us per value; scipy/pendula {t_s / t_p:.2f}, gsl/pendula {t_g / t_p:.2f}")
    rec["accuracy"] = accuracy()
    print("accuracy on the reference's integer orders:", rec["accuracy"])
    # the transmon: 10 levels at 1,000 offset charges
    ng = np.linspace(-1.0, 1.0, 1000)
    t = pendula.Transmon(50.0, 1.0)
    t_tr = min(timed(lambda: t.levels(10, ng), rounds=3)[0] for _ in range(2))
    row = {"pendula_s": t_tr}
    try:
        import scqubits
        tm = scqubits.Transmon(EJ=50.0, EC=1.0, ng=0.0, ncut=30, truncated_dim=10)
        t_sq, spec = timed(lambda: tm.get_spectrum_vs_paramvals("ng", ng, evals_count=10,
                                                                   subtract_ground=False), rounds=1)
        ev = np.asarray(spec.energy_table)
        ours = t.levels(10, ng)
        row.update({"scqubits_s": t_sq, "scqubits_over_pendula": t_sq / t_tr, "scqubits": scqubits.__version__,
                    "ncut": 30, "max_abs_difference": float(np.max(np.abs(ev - ours)))})
    except ImportError:
        row["scqubits"] = "not installed"
    rec["transmon_10_levels_1000_ng"] = row
    print("transmon:", row)
    (HERE / "mathieu_cost.json").write_text(json.dumps(rec, indent=1) + "\n")


if __name__ == "__main__":
    main()

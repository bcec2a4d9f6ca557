"""What a Mathieu characteristic value costs: pendula.mathieu_a / mathieu_b against
SciPy's mathieu_a / mathieu_b and GSL's gsl_sf_mathieu_a_e / _b_e, per value, on
the same points, interleaved (best of several rounds each), and the accuracy of
each against data/mathieu_reference.csv (integer orders; SciPy and GSL take no
other).  GSL is called in a C loop (the kernel's GSL glue, its error handler
off, status codes checked), so its time has no Python in it; SciPy and pendula
are each one call on the whole array.  The time is compared only where SciPy
is right (within 1e-10 of pendula, whose accuracy the reference checks): where
it is wrong its speed does not matter.

The transmon: 10 levels at 1,000 offset charges (E_J/E_C = 50) by pendula
(Transmon.levels, one kernel window per offset charge) against scqubits'
charge-basis Transmon at the smallest cutoff ncut whose levels agree with
pendula's to 1e-12 (relative where a level exceeds 1, absolute below; pendula's
are within 4 eps of the 40-digit reference of tests/test_mathieu.py), and against
numpy's batched eigvalsh at that cutoff (the whole stack of Hamiltonians in one
call, building them included).

    .venv/bin/python data/bench/mathieu_cost.py     # writes data/bench/mathieu_cost.json

Single-threaded (OMP_NUM_THREADS=1 and OPENBLAS_NUM_THREADS=1 are set before
anything loads): a per-value comparison.
"""

import csv
import json
import os
import platform
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
import scipy  # noqa: E402
import scipy.special as sp  # noqa: E402

import pendula  # noqa: E402
from pendula import _kernel  # noqa: E402

HERE = Path(__file__).resolve().parent
EPS = np.finfo(float).eps


def gsl_values(kind, n, q):
    """GSL's a_n(q) or b_n(q), one gsl_sf_mathieu_*_e call per value in C (NaN where it fails)."""
    return _kernel.gsl_mathieu_v(1 if kind == "a" else 2, np.asarray(n, dtype=np.int32),
                                 np.asarray(q, dtype=np.float64))[0]


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
    worst = {"pendula": 0.0, "scipy": 0.0, "gsl": 0.0}
    wrong = {"pendula": 0, "scipy": 0, "gsl": 0}
    for r in rows:
        n, q, ref = int(float(r["nu"])), float(r["q"]), float(r["value"])
        f = pendula.mathieu_a if r["kind"] == "a" else pendula.mathieu_b
        s = sp.mathieu_a if r["kind"] == "a" else sp.mathieu_b
        got = {"pendula": float(f(n, q)), "scipy": float(s(n, q)),
               "gsl": float(gsl_values(r["kind"], [n], [q])[0])}
        for k, v in got.items():
            e = abs(v - ref) / max(1.0, abs(ref)) / EPS if np.isfinite(v) else np.inf
            worst[k] = max(worst[k], e)
            wrong[k] += int(e > 1e6)
    worst = {k: (float(v) if np.isfinite(v) else "a value failed (NaN or an error status)") for k, v in worst.items()}
    return {"points": len(rows), "worst_error_eps": worst, "values_off_by_more_than_1e6_eps_or_failed": wrong}


def _charge_hamiltonians(ej, ec, ng, ncut):
    """The charge-basis Hamiltonians 4 E_C (n - n_g)^2 - E_J/2 (|n><n+1| + h.c.), stacked over n_g."""
    n = np.arange(-ncut, ncut + 1)
    h = np.zeros((len(ng), n.size, n.size))
    i = np.arange(n.size)
    h[:, i, i] = 4.0 * ec * (n[None, :] - np.asarray(ng)[:, None]) ** 2
    h[:, i[:-1], i[1:]] = -ej / 2.0
    h[:, i[1:], i[:-1]] = -ej / 2.0
    return h


def transmon(ej=50.0, ec=1.0, levels=10, points=1000):
    ng = np.linspace(-1.0, 1.0, points)
    t = pendula.Transmon(ej, ec)
    t_p = min(timed(lambda: t.levels(levels, ng), rounds=3)[0] for _ in range(2))
    ours = t.levels(levels, ng)
    # the cutoff of equal accuracy: the smallest ncut whose levels agree with
    # pendula's to 1e-12 (relative where a level exceeds 1, absolute below);
    # pendula's levels are within 4 eps of a 40-digit reference (tests/test_mathieu.py)
    def off(c):
        e = np.linalg.eigvalsh(_charge_hamiltonians(ej, ec, ng, c))[:, :levels]
        return float(np.max(np.abs(e - ours) / np.maximum(1.0, np.abs(ours))))
    ncut = next(c for c in range((levels + 1) // 2, 61) if off(c) <= 1e-12)
    row = {"E_J_over_E_C": ej, "levels": levels, "offset_charges": points, "pendula_s": t_p,
           "numpy_at_ncut_vs_pendula_max_rel": off(ncut), "numpy_at_ncut_plus_10_vs_pendula_max_rel": off(ncut + 10)}
    h = _charge_hamiltonians(ej, ec, ng, ncut)
    t_np = min(timed(lambda: np.linalg.eigvalsh(_charge_hamiltonians(ej, ec, ng, ncut)), rounds=3)[0]
               for _ in range(2))
    row.update({"ncut_for_1e-12": ncut, "numpy_batched_eigvalsh_s": t_np, "numpy_over_pendula": t_np / t_p})
    del h
    try:
        import scqubits
        scqubits.settings.PROGRESSBAR_DISABLED = True
        tm = scqubits.Transmon(EJ=ej, EC=ec, ng=0.0, ncut=ncut, truncated_dim=levels)
        t_sq, spec = timed(lambda: tm.get_spectrum_vs_paramvals("ng", ng, evals_count=levels,
                                                                   subtract_ground=False), rounds=2)
        ev = np.asarray(spec.energy_table)
        row.update({"scqubits": scqubits.__version__, "scqubits_s": t_sq, "scqubits_over_pendula": t_sq / t_p,
                    "scqubits_vs_pendula_max_rel":
                        float(np.max(np.abs(ev - ours) / np.maximum(1.0, np.abs(ours))))})
    except ImportError:
        row["scqubits"] = "not installed (pip install scqubits)"
    return row


def main_transmon():
    """Only the transmon's row (``mathieu_cost.py transmon``), printed."""
    print(transmon())


def main():
    rng = np.random.default_rng(7)
    _kernel.gsl_init()
    rec = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
           "machine": platform.processor() or platform.machine(), "cores": os.cpu_count(),
           "load_average": os.getloadavg(), "pendula": pendula.__version__, "scipy": scipy.__version__,
           "threads": os.environ["OMP_NUM_THREADS"], "cases": {}}
    for label, qmax in (("q in [0.01, 10]", 10.0), ("q in [0.01, 1000]", 1000.0)):
        n, q = points(rng, 4000, qmax)
        ours = pendula.mathieu_a(n, q)
        right = np.abs(sp.mathieu_a(n, q) - ours) <= 1e-10 * np.maximum(1.0, np.abs(ours))
        n, q = n[right], q[right]
        t_p = t_s = t_g = np.inf
        for _ in range(3):   # interleaved rounds
            t_p = min(t_p, timed(lambda: pendula.mathieu_a(n, q))[0])
            t_s = min(t_s, timed(lambda: sp.mathieu_a(n, q))[0])
            t_g = min(t_g, timed(lambda: gsl_values("a", n, q), rounds=2)[0])
        per = {k: v / len(n) * 1e6 for k, v in (("pendula", t_p), ("scipy", t_s), ("gsl", t_g))}
        rec["cases"][label] = {"values": len(n), "scipy_right_fraction": float(right.mean()),
                               "us_per_value": per,
                               "scipy_over_pendula": t_s / t_p, "gsl_over_pendula": t_g / t_p}
        print(f"{label} ({len(n)} values where SciPy is right, {right.mean():.1%}): pendula {per['pendula']:.3f} us, "
              f"scipy {per['scipy']:.3f} us, gsl {per['gsl']:.3f} us per value; "
              f"scipy/pendula {t_s / t_p:.2f}, gsl/pendula {t_g / t_p:.2f}")
    rec["accuracy"] = accuracy()
    print("accuracy on the reference's integer orders:", rec["accuracy"])
    row = transmon()
    rec["transmon_10_levels_1000_ng"] = row
    print("transmon:", row)
    (HERE / "mathieu_cost.json").write_text(json.dumps(rec, indent=1) + "\n")


if __name__ == "__main__":
    import sys
    main_transmon() if sys.argv[1:] == ["transmon"] else main()

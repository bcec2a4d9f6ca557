"""Benchmarks: pendula against its peers on the same work, in one run.

Benchmarks are not tests: nothing here asserts a time.  Each benchmark prints
nanoseconds per element (the best of several repeats) and the ratios, so a
reader sees what pendula costs next to scipy, GSL and numpy on the same
machine at the same moment.

Run ``python -m pendula.studies.bench elliptic`` (or ``pendula bench elliptic``).
"""

from __future__ import annotations

import argparse
import platform
import time

import numpy as np
from .._optional import require
from .._files import open_text  # the one writer: regular files only, whole or absent


def best_time(fn, repeat: int = 5) -> float:
    """The best wall time of ``repeat`` calls of ``fn`` (seconds)."""
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def _report(title: str, n: int, rows: list[tuple[str, float]], ref: str) -> list[dict]:
    base = dict(rows)[ref]
    print(f"\n{title}  (n = {n:,}, best of 3-7 repeats, {platform.processor() or platform.machine()})")
    print(f"  {'what':44s} {'ns/elem':>9s} {'ratio to ' + ref:>22s}")
    out = []
    for name, t in rows:
        ns = t / n * 1e9
        print(f"  {name:44s} {ns:9.1f} {t / base:22.2f}")
        out.append({"what": name, "ns_per_element": ns, "ratio": t / base})
    return out


def bench_elliptic(n: int = 1_000_000, seed: int = 1) -> list[dict]:
    """Time sn/cn/dn(/am) and K on the same 10^6-element arrays.

    Three workloads for the Jacobi functions: (a) one parameter for all u (the
    pendulum's case: many times at one energy), (b) a different m for every u,
    (c) large arguments (u up to 1000 periods).  Peers: scipy.special.ellipj
    (Cephes: descending Landen), GSL gsl_sf_elljac_e (Bulirsch) through
    pendula's C glue, numpy.sin as a yardstick.
    """
    sc = require("scipy.special", "bench", "pendula bench")

    from .. import _kernel
    from ..elliptic import ellipj, ellipk

    rng = np.random.default_rng(seed)
    u = rng.uniform(-10.0, 10.0, n)
    mvar = rng.uniform(0.0, 1.0, n)
    m1 = np.full(n, 0.7)
    ubig = rng.uniform(-4000.0, 4000.0, n)
    results = []

    rows = [
        ("pendula.ellipj(u, 0.7)  [scalar m]", best_time(lambda: ellipj(u, 0.7))),
        ("scipy.special.ellipj(u, 0.7)", best_time(lambda: sc.ellipj(u, 0.7))),
        ("GSL gsl_sf_elljac_e (m = 0.7)", best_time(lambda: _kernel.gsl_elljac_v(u, m1))),
        ("numpy.sin(u)", best_time(lambda: np.sin(u))),
    ]
    results += _report("Jacobi sn, cn, dn (+am), u in [-10, 10], m = 0.7", n, rows,
                       "pendula.ellipj(u, 0.7)  [scalar m]")
    rows = [
        ("pendula.ellipj(u, m)  [m per element]", best_time(lambda: ellipj(u, mvar))),
        ("scipy.special.ellipj(u, m)", best_time(lambda: sc.ellipj(u, mvar))),
        ("GSL gsl_sf_elljac_e", best_time(lambda: _kernel.gsl_elljac_v(u, mvar))),
    ]
    results += _report("Jacobi sn, cn, dn (+am), u in [-10, 10], m in [0, 1)", n, rows,
                       "pendula.ellipj(u, m)  [m per element]")
    rows = [
        ("pendula.ellipj(u, 0.7)  [u to 1000 periods]", best_time(lambda: ellipj(ubig, 0.7))),
        ("scipy.special.ellipj", best_time(lambda: sc.ellipj(ubig, 0.7))),
        ("GSL gsl_sf_elljac_e", best_time(lambda: _kernel.gsl_elljac_v(ubig, m1))),
    ]
    results += _report("Jacobi, large arguments |u| <= 4000, m = 0.7", n, rows,
                       "pendula.ellipj(u, 0.7)  [u to 1000 periods]")
    rows = [
        ("pendula.ellipk(m)", best_time(lambda: ellipk(mvar))),
        ("scipy.special.ellipk(m)", best_time(lambda: sc.ellipk(mvar))),
        ("scipy.special.ellipkm1(1 - m)", best_time(lambda: sc.ellipkm1(1.0 - mvar))),
        ("GSL gsl_sf_ellint_Kcomp_e", best_time(lambda: _kernel.gsl_kcomp_v(mvar))),
    ]
    results += _report("Complete integral K(m), m in [0, 1)", n, rows, "pendula.ellipk(m)")
    return results


def bench_exact(n: int = 1_000_000, seed: int = 2) -> list[dict]:
    """The exact pendulum path per sample against numpy.sin per sample (target: at most 3x in every regime)."""
    from ..systems.rigid import exact_motion

    t = np.sort(np.random.default_rng(seed).uniform(0.0, 1000.0, n))
    rows = [
        ("pendula.exact_motion (libration v0 = 1.9)", best_time(lambda: exact_motion(0.0, 1.9, 1.0, t))),
        ("pendula.exact_motion (rotation v0 = 2.5)", best_time(lambda: exact_motion(0.0, 2.5, 1.0, t))),
        ("pendula.exact_motion (v0 = 2 - 1e-12)", best_time(lambda: exact_motion(0.0, 2 - 1e-12, 1.0, t))),
        ("numpy.sin(t)", best_time(lambda: np.sin(t))),
    ]
    return _report("Exact path theta(t), v(t) per sample, t in [0, 1000]", n, rows, "numpy.sin(t)")


def bench_integrators(n: int = 0, seed: int = 0) -> list[dict]:
    """DOP853 against scipy's solve_ivp DOP853 and GSL rk8pd; the cost of effects."""
    si = require("scipy.integrate", "bench", "pendula bench")

    from ..scene import Scene
    from ..systems.rigid import exact_motion
    from ..integrate import integrate_scene

    results = []
    # 1. the same damped scene at the same tolerances, 201 outputs on [0, 100]
    t = np.linspace(0.0, 100.0, 201)
    sc = Scene(v0=2.3, damping=0.1, rtol=1e-10, atol=1e-12)

    def rhs(tt, y):
        return [y[1], -np.sin(y[0]) - 0.1 * y[1]]

    ref = si.solve_ivp(rhs, (0, 100), [0.0, 2.3], method="DOP853", rtol=1e-10, atol=1e-12, t_eval=t)
    mine = integrate_scene(sc, t, "dop853")
    rows = [("pendula dop853 (damped, rtol 1e-10)", best_time(lambda: integrate_scene(sc, t, "dop853"))),
            ("scipy solve_ivp DOP853, same tolerances", best_time(lambda: si.solve_ivp(
                rhs, (0, 100), [0.0, 2.3], method="DOP853", rtol=1e-10, atol=1e-12, t_eval=t), repeat=3))]
    print(f"\nDOP853 on a damped scene: pendula {mine.stats['steps']} steps, "
          f"{mine.stats['rhs_evaluations']} rhs evaluations; scipy {ref.nfev} rhs evaluations; "
          f"max |theta difference| {np.abs(mine.theta - ref.y[0]).max():.1e}")
    results += _report_runs("DOP853 against scipy.integrate.solve_ivp(method='DOP853')", rows,
                            "pendula dop853 (damped, rtol 1e-10)")
    # 2. DOP853 against GSL rk8pd at equal final error (conservative, exact reference)
    tt = np.array([0.0, 100.0])
    exact = exact_motion(0.0, 1.999, 1.0, tt)[0][-1]
    curves = {}
    for method in ("dop853", "gsl-rk8pd"):
        pts = []
        for tol in np.geomspace(1e-6, 1e-14, 9):
            s2 = Scene(v0=1.999, rtol=tol, atol=tol * 1e-2)
            tr = integrate_scene(s2, tt, method)
            e = abs(tr.theta[-1] - exact)
            sec = best_time(lambda: integrate_scene(s2, tt, method), repeat=7)
            pts.append((e, sec, tr.stats["rhs_evaluations"]))
        curves[method] = sorted(pts)
    print("\nDOP853 against GSL rk8pd at equal final error (v0 = 1.999, t = 100, exact reference):")
    print(f"  {'error':>8s} {'pendula dop853 (us)':>20s} {'GSL rk8pd (us)':>16s} {'ratio GSL/pendula':>18s}")
    for target in (1e-6, 1e-8, 1e-10):
        ts = {}
        for method, pts in curves.items():
            e = np.log([p[0] for p in pts])
            sec = np.log([p[1] for p in pts])
            ts[method] = float(np.exp(np.interp(np.log(target), e, sec)))
        print(f"  {target:8.0e} {ts['dop853'] * 1e6:20.1f} {ts['gsl-rk8pd'] * 1e6:16.1f} "
              f"{ts['gsl-rk8pd'] / ts['dop853']:18.2f}")
        results.append({"what": f"equal error {target:g}", "dop853_us": ts["dop853"] * 1e6,
                        "gsl_us": ts["gsl-rk8pd"] * 1e6})
    # 3. effects cost only when named
    base = Scene(v0=1.9, rtol=1e-10, atol=1e-12, t_end=1000.0)
    tt = np.array([0.0, 1000.0])
    variants = [("gravity only (the conservative scene, numerically)", base),
                ("gravity + damping", base.replace(damping=0.01)),
                ("gravity + damping + torque + drive", base.replace(damping=0.01, torque=0.1,
                                                                    drive_amplitude=0.1, drive_frequency=0.7))]
    print("\nThe right-hand side holds only the effects a scene names (DOP853, rtol 1e-10, t = 1000):")
    for name, scn in variants:
        tr = integrate_scene(scn, tt, "dop853")
        sec = best_time(lambda: integrate_scene(scn, tt, "dop853"), repeat=5)
        per = sec / tr.stats["rhs_evaluations"] * 1e9
        print(f"  {name:52s} {per:6.1f} ns per rhs evaluation ({tr.stats['rhs_evaluations']} evaluations)")
        results.append({"what": name, "ns_per_rhs": per})
    return results


def _report_runs(title, rows, ref, per_call=False):
    """Print the rows (name, seconds) with their ratios to the row named `ref`; returns the bench
    record's rows: whole runs in ms, or with `per_call` the cost of one call in us."""
    base = dict(rows)[ref]
    print(f"\n{title}")
    out = []
    for name, tsec in rows:
        if per_call:
            print(f"  {name:50s} {tsec * 1e6:9.1f} us per call {tsec / base:8.2f}x")
            out.append({"what": name, "us_per_call": tsec * 1e6, "ratio": tsec / base})
        else:
            print(f"  {name:44s} {tsec * 1e3:9.3f} ms {tsec / base:10.1f}x")
            out.append({"what": name, "ms": tsec * 1e3, "ratio": tsec / base})
    return out


def bench_spectrum(n: int = 1 << 20, seed: int = 3) -> list[dict]:
    """Power spectra of 2^20 samples: pendula (FFTW, one plan reused across a
    sweep) against numpy.fft.rfft on the same signals, in one run."""
    from ..spectrum import spectra, spectrum

    n = 1 << 20
    rng = np.random.default_rng(seed)
    t = np.arange(n) * 1e-3
    one = rng.standard_normal(n)
    sweep = rng.standard_normal((8, n))

    def numpy_power(x):
        a = 2 * np.abs(np.fft.rfft(x)) / x.size
        return a * a

    import time

    t0 = time.perf_counter()
    spectrum(t, one)
    first = time.perf_counter() - t0
    from ..spectrum import wisdom_path

    spectra(t, one, measure=True)               # measured plan, paid once here (as `pendula wisdom` does)
    rows = [
        ("pendula.spectrum, one signal of 2^20", best_time(lambda: spectrum(t, one), repeat=7)),
        ("pendula.spectra, one signal, measured plan", best_time(lambda: spectra(t, one, measure=True),
                                                                 repeat=7)),
        ("numpy.fft.rfft + |A|^2, one signal", best_time(lambda: numpy_power(one), repeat=7)),
    ]
    have = wisdom_path().is_file()
    out = _report("Spectrum of 2^20 samples (default plan: " + ("measured, from the wisdom file"
                  if have else "FFTW_ESTIMATE, no wisdom file: run `pendula wisdom`") + ")", n, rows,
                  "pendula.spectrum, one signal of 2^20")
    for r in out:
        r["wisdom_file"] = have
    print(f"  (first call, planning included: {first * 1e9 / n:.1f} ns/elem)")
    rows = [
        ("pendula.spectra, 8 signals, one plan", best_time(lambda: spectra(t, sweep), repeat=3)),
        ("numpy.fft.rfft + |A|^2, 8 signals", best_time(lambda: [numpy_power(x) for x in sweep], repeat=3)),
    ]
    out += _report("A sweep of 8 spectra of 2^20 samples (ns per sample and signal / 8)", 8 * n, rows,
                   "pendula.spectra, 8 signals, one plan")
    t0 = time.perf_counter()
    spectra(t, sweep, measure=True)
    first = time.perf_counter() - t0
    rows = [("pendula.spectra, FFTW_MEASURE plan (kept)", best_time(lambda: spectra(t, sweep, measure=True),
                                                                    repeat=3)),
            ("numpy.fft.rfft + |A|^2, 8 signals", best_time(lambda: [numpy_power(x) for x in sweep], repeat=3))]
    print(f"\n(FFTW_MEASURE planning took {first:.1f} s once; the plan is then kept for the process)")
    out += _report("The same sweep with a measured plan", 8 * n, rows, "pendula.spectra, FFTW_MEASURE plan (kept)")
    return out


# ---- flexible cord (Garfinkel) ----
def bench_cord(n: int = 10_000, seed: int = 4) -> list[dict]:
    """Time per simulated flip (departure, flight, re-entry, jerk) against the closed-form map.

    One run of 10^4 flips in state k = 1 (xi(0) = 0.2), the map f evaluated
    at the 10^4 energies of that run, and the whole Table 2 experiment.
    """
    import warnings

    from ..demos.cord import table2
    from ..systems.cord import flip_map
    from ..motion import simulate
    from ..scene import Scene

    nf = min(int(n), 10_000)
    sc = Scene(cord="flexible", v0=(3 * 0.2 + 2) ** 0.5, t_end=1e12, n_samples=2, max_flips=nf)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        tr = simulate(sc)
        t_sim = best_time(lambda: simulate(sc), repeat=3)
    xs = tr.flips["xi_before"]
    t_map = best_time(lambda: flip_map(xs))
    rows = _report("Flexible cord: one flip", nf, [("pendula.simulate, one run of flips (kernel cord_run)", t_sim),
                                                   ("pendula.flip_map, closed form (numpy)", t_map)],
                   "pendula.flip_map, closed form (numpy)")
    t0 = time.perf_counter()
    table2()
    t_tab = time.perf_counter() - t0
    print(f"  Table 2 experiment (13 runs, k(0) = 0..12, plus circulation): {t_tab * 1e3:.0f} ms")
    return rows + [{"what": "table2", "seconds": t_tab}]


def bench_sweep(n: int = 1_000_000, seed: int = 14) -> list[dict]:
    """Sweeps: a sqrt(n) x sqrt(n) final-well map over (v0, beta)
    (goal: 10^6 points in 60 s on 2 cores), OpenMP threads 1 against 2, the
    per-point cost against a scipy solve_ivp loop with a terminal event on a
    20 x 20 subgrid, and the fraction of points decided early."""
    import os

    solve_ivp = require("scipy.integrate", "bench", "pendula bench").solve_ivp

    from ..scene import Scene
    from ..sweeps import sweep

    side = max(20, int(round(n ** 0.5)))
    s = Scene(damping=0.1)
    rt, at = 1e-8, 1e-10   # the same tolerances for pendula and scipy

    def grid(k):
        return {"v0": np.linspace(0.0, 4.0, k), "damping": np.linspace(0.02, 0.3, k)}

    t0 = time.perf_counter()
    ds = sweep(s, over=grid(side), measure="final_well", rtol=rt, atol=at)
    t_map = time.perf_counter() - t0
    st = ds.status.values
    print(f"\nSweep: final-well map {side} x {side} over (v0, beta), DOP853 rtol {rt:g}: {t_map:.1f} s "
          f"({os.cpu_count()} cores, OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}; "
          "the machine is shared: other users' load is in these figures)")
    td = ds.t_decided.values[st == 0]
    print(f"  decided {100 * np.mean(st == 0):.2f} %, uncertain (answer changes with tolerance) "
          f"{int(np.sum(st == 4))}, not settled {int(np.sum(st == 1))}; median decision time {np.median(td):.1f} "
          f"(the limit is {s.sweep_t_max:g}): every decided point stopped early")
    sub = grid(200)
    t1 = best_time(lambda: sweep(s, over=sub, measure="final_well", rtol=rt, atol=at, threads=1), repeat=2)
    t2 = best_time(lambda: sweep(s, over=sub, measure="final_well", rtol=rt, atol=at, threads=2), repeat=2)
    print(f"  200 x 200: 1 thread {t1:.2f} s, 2 threads {t2:.2f} s: speed-up {t1 / t2:.2f}")
    small = grid(20)
    tp = best_time(lambda: sweep(s, over=small, measure="final_well", rtol=rt, atol=at, threads=1), repeat=3)

    def scipy_loop():
        res = []
        for v0 in small["v0"]:
            for b in small["damping"]:
                def f(t, y, b=b):
                    return [y[1], -np.sin(y[0]) - b * y[1]]

                def trapped(t, y):   # energy below the barrier 2 eps: trapped for good
                    return 0.5 * y[1] ** 2 + 1 - np.cos(y[0]) - 2.0
                trapped.terminal, trapped.direction = True, -1
                e0 = 0.5 * v0 ** 2
                if e0 < 2.0:
                    res.append(0)
                    continue
                r = solve_ivp(f, (0, s.sweep_t_max), [0.0, v0], method="DOP853", rtol=rt, atol=at, events=trapped)
                res.append(int(np.round(r.y[0, -1] / (2 * np.pi))))
        return res
    ts = best_time(scipy_loop, repeat=1)
    print(f"  20 x 20 subgrid, 1 thread: pendula {tp / 400 * 1e6:.1f} us/point, scipy solve_ivp + event loop "
          f"{ts / 400 * 1e6:.1f} us/point: ratio {ts / tp:.0f}x")
    return [{"what": "final-well map, seconds", "value": t_map},
            {"what": "points", "value": float(side * side)},
            {"what": "speed-up, 2 threads over 1", "value": t1 / t2},
            {"what": "scipy solve_ivp loop over pendula, per point", "value": ts / tp}]


BENCHMARKS = {"elliptic": bench_elliptic, "exact": bench_exact, "integrators": bench_integrators,
              "spectrum": bench_spectrum, "cord": bench_cord, "sweep": bench_sweep}


def _per_call(fn, calls: int = 20, repeat: int = 60) -> float:
    """The best over ``repeat`` rounds of the mean wall time of ``calls`` calls of ``fn`` (seconds).

    Short rounds, many of them: on a loaded machine a round that the scheduler
    did not interrupt is then among them."""
    fn()
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(calls):
            fn()
        best = min(best, (time.perf_counter() - t0) / calls)
    return best


def bench_simulate(n: int = 0, seed: int = 0) -> list[dict]:
    """What one :func:`pendula.simulate` call costs beside the work it asks for.

    The checked scene is kept as the kernel takes it (numbers and words, made
    once per frozen Scene), so a run parses nothing.  Two comparisons, each
    on the same times: (1) simulate on an 11-sample conservative scene
    against exact_motion (the exact path with no scene at all; target within
    2x); (2) a short damped DOP853 run through simulate against the
    integrator's binding called directly (the kernel's integration and the
    f2py call alone; target within 1.5x).  Mean per call of 20 calls, best
    of 60 rounds.
    """
    from .. import _kernel
    from ..motion import simulate
    from ..scene import Scene
    from ..systems.rigid import exact_motion

    t = np.linspace(0.0, 10.0, 11)
    conservative = Scene(v0=1.0, t_end=10.0, n_samples=11)
    rows = [("simulate, conservative scene, 11 samples", _per_call(lambda: simulate(conservative))),
            ("exact_motion on the same 11 times", _per_call(lambda: exact_motion(0.0, 1.0, 1.0, t)))]
    out = _report_runs("simulate against the exact path on the same times (target: within 2x)", rows,
                       "exact_motion on the same 11 times", per_call=True)
    damped = Scene(v0=1.0, damping=0.1, t_end=10.0, n_samples=11, rtol=1e-10, atol=1e-12)
    fields = damped._kernel_fields      # the scene as the kernel checked it
    cancel = np.zeros(1, dtype=np.int32)

    def kernel_alone():
        return _kernel.integrate_v(*fields, 9, t, 0, 0.0, 0, 0, 1, cancel)

    if not np.array_equal(kernel_alone()[0], simulate(damped).theta):
        raise RuntimeError("bench simulate: the two runs compared differ; they must be the same work")
    rows = [("simulate, damped scene, dop853, 11 samples", _per_call(lambda: simulate(damped))),
            ("the integrator's binding alone, same run", _per_call(kernel_alone))]
    out += _report_runs("a short DOP853 run: simulate against the kernel's integration alone "
                        "(target: within 1.5x)", rows, "the integrator's binding alone, same run", per_call=True)
    return out


BENCHMARKS["simulate"] = bench_simulate


def machine_record() -> dict:
    """Machine, versions and date of a benchmark run (for the JSON record)."""
    import datetime
    import importlib.metadata as md
    import os

    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    versions = {"python": platform.python_version()}
    for pkg in ("pendula", "numpy", "scipy", "mpmath"):
        try:
            versions[pkg] = md.version(pkg)
        except md.PackageNotFoundError:
            versions[pkg] = None
    try:
        load = os.getloadavg()
    except OSError:
        load = None
    return {"date_utc": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "cpu": cpu, "cores": os.cpu_count(), "platform": platform.platform(),
            "load_average": load, "versions": versions}


def readme_tables(record: dict) -> str:
    """Markdown tables of the benchmark report (docs/source/reports/benchmarks.md) from a recorded run (``pendula bench --readme FILE``)."""
    m = record["machine"]
    load = m.get("load_average")
    load = "/".join(f"{x:.1f}" for x in load) if load else "unknown"
    lines = [f"Recorded {m['date_utc']} on {m['cpu']} ({m['cores']} cores, load average {load}), "
             + ", ".join(f"{k} {v}" for k, v in m["versions"].items() if v) + ".", ""]
    for name, rows in record["results"].items():
        lines += [f"**{name}**", ""]
        keys = None
        for r in rows:                          # one table per run of rows with the same fields
            cols = [k for k in r if k != "what"]
            if cols != keys:
                if keys is not None:
                    lines.append("")
                keys = cols
                lines += ["| what | " + " | ".join(k.replace("_", " ") for k in cols) + " |",
                          "|---|" + "---:|" * len(cols)]
            cells = [f"{r[k]:.3g}" if isinstance(r[k], float) else str(r[k]) for k in cols]
            what = str(r["what"]).replace("|", "\\|")      # a '|' in a name would split the cell
            lines.append(f"| {what} | " + " | ".join(cells) + " |")
        lines.append("")
    return "\n".join(lines)


def main(argv=None) -> int:
    import json

    p = argparse.ArgumentParser(prog="pendula bench", description=__doc__.splitlines()[0])
    p.add_argument("which", nargs="*", help=f"benchmarks to run: {', '.join(sorted(BENCHMARKS))} (default: all)")
    p.add_argument("-n", type=int, default=1_000_000, help="elements per array (default 10^6)")
    p.add_argument("--json", default="bench.json",
                   help="where to record the run as JSON (default bench.json; '' for none)")
    p.add_argument("--readme", metavar="FILE", default=None,
                   help="print README's Markdown tables from a recorded JSON run, and run nothing")
    p.add_argument("--into", metavar="README", default=None,
                   help="with --readme: replace the text between the '<!-- bench:begin -->' and "
                        "'<!-- bench:end -->' lines of this file instead of printing")
    args = p.parse_args(argv)
    if args.readme is not None:
        try:
            with open(args.readme) as fh:
                tables = readme_tables(json.load(fh))
        except (OSError, ValueError, KeyError, TypeError) as exc:
            print(f"pendula bench --readme: cannot read {args.readme}: {exc}")
            return 2
        if args.into is None:
            print(tables)
            return 0
        begin, end = "<!-- bench:begin -->", "<!-- bench:end -->"
        try:
            with open(args.into) as fh:
                text = fh.read()
        except OSError as exc:
            print(f"pendula bench --into: {exc}")
            return 2
        if text.count(begin) != 1 or text.count(end) != 1 or text.index(begin) > text.index(end):
            print(f"pendula bench --into: {args.into} needs one '{begin}' line and one '{end}' line after it")
            return 2
        head, rest = text.split(begin)
        _, tail = rest.split(end)
        note = f"\n<!-- generated by: pendula bench --readme {args.readme} --into {args.into} -->\n"
        with open_text(args.into) as fh:
            fh.write(head + begin + note + tables.rstrip("\n") + "\n" + end + tail)
        print(f"README tables written into {args.into} from {args.readme}")
        return 0
    if args.n <= 0:
        p.error("-n must be positive")
    unknown = [w for w in args.which if w not in BENCHMARKS]
    if unknown:
        p.error(f"unknown benchmark(s) {', '.join(unknown)}; known: {', '.join(sorted(BENCHMARKS))}")
    record = {"machine": machine_record(), "n": args.n, "results": {}}
    for name in args.which or sorted(BENCHMARKS):
        record["results"][name] = BENCHMARKS[name](n=args.n)
    if args.json:
        with open_text(args.json) as fh:
            json.dump(record, fh, indent=1)
        print(f"\nrecorded in {args.json}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

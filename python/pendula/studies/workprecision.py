"""What accuracy costs in time: the work-precision study of the integrators.

Problems, references, peers, timing and the tables/figures made from the
recorded run (data/bench/work_precision.json); see docs/source/work_precision.rst.
The problem definitions come first and are plain data: the reference generator
(data/gen_work_precision_reference.py) reads them without importing the package.
"""

from __future__ import annotations

#: The problems of the study: theta'' = -eps sin(theta) - beta theta' + tau + amp cos(omega t + phase),
#: from (theta0, v0) at t = 0 to t_end; outputs at N_OUT + 1 equally spaced times including 0 and t_end.
PROBLEMS = {
    "libration": dict(theta0=0.0, v0=1.999, eps=1.0, t_end=100.0, conservative=True),
    "rotation": dict(theta0=0.0, v0=2.5, eps=1.0, t_end=100.0, conservative=True),
    "damped": dict(theta0=0.0, v0=2.3, eps=1.0, beta=0.1, t_end=100.0, conservative=False),
    "torqued": dict(theta0=0.0, v0=3.0, eps=1.0, beta=0.16, tau=0.5, t_end=100.0, conservative=False),
    "driven": dict(theta0=0.0, v0=0.0, eps=1.0, beta=0.5, amp=1.15, omega=2.0 / 3.0, t_end=50.0,
                   conservative=False),
}
N_OUT = 100

# ---- end of problem definitions

__all__ = ["PROBLEMS", "N_OUT", "TARGETS", "load_reference", "errors", "best_time", "run_study", "answer_table",
           "auto_picks", "auto_noise", "AUTO_CANDIDATES", "AUTO_DECADES",
           "answer_rst", "write_figures", "merge_records", "study_main", "regenerate_docs"]

import datetime
import json
import math
import pathlib
import platform
import time

import numpy as np

from .._files import open_text, save_figure  # the one writer: regular files only, whole or absent
from .._optional import require

#: target errors of the answer table
TARGETS = (1e-3, 1e-6, 1e-9, 1e-12)
#: how long one timed batch should last (s of CPU time) and the spread the best time must reach
BATCH_SECONDS = 0.01
SPREAD_GOAL = 0.03
MAX_BATCHES = 10

#: pendula's methods and their settings (rtol for adaptive ones, with atol = rtol; dt for fixed-step ones)
TOLS = [10.0 ** -k for k in range(3, 15)]
#: the suffix of a method run with its steps landing on the output times (simulate's land_on_outputs)
LANDED = "-landed"
PENDULA_ADAPTIVE = ("dopri5", "dop853", "dop853" + LANDED, "vern9", "vern9" + LANDED, "vern8", "vern8" + LANDED,
                    "gsl-rk8pd")
#: methods for theta'' = f(t, theta) only (no damping): the Runge-Kutta-Nystrom pair
PENDULA_NYSTROM = ("dprkn6",)
PENDULA_FIXED = {"rk4": [0.1, 0.05, 0.025, 0.0125, 0.00625, 0.003125],
                 "yoshida6": [0.2, 0.1, 0.05, 0.025, 0.0125],
                 "yoshida8": [0.4, 0.2, 0.1, 0.05, 0.025],
                 "gauss6": [0.4, 0.2, 0.1, 0.05, 0.025, 0.0125]}
SCIPY_METHODS = ("RK45", "DOP853", "Radau", "LSODA")
#: the tightest rtol each SciPy method is asked for (Radau and LSODA take seconds per run below it)
SCIPY_TIGHTEST = {"RK45": 1e-10, "DOP853": 1e-14, "Radau": 1e-9, "LSODA": 1e-12}
#: the short form (make demo): one problem, a few settings, short batches
QUICK = dict(problems=("damped",), tols=[1e-3, 1e-6, 1e-9], batch=0.005, max_batches=3)
#: a run slower than this (s) is timed in 3 batches of one run (SciPy's tightest settings take seconds)
SLOW_RUN = 0.25

GSL = "gsl-rk8pd"


# ---------------------------------------------------------------- references

def reference_path() -> pathlib.Path:
    """The stored reference (data/work_precision_reference.json, written by
    data/gen_work_precision_reference.py): the copy installed with the package (pendula/data), else
    the repository's (the working directory, the source tree)."""
    from importlib.resources import files

    installed = pathlib.Path(str(files("pendula") / "data" / "work_precision_reference.json"))
    for p in [installed] + [base / "data" / "work_precision_reference.json"
                            for base in (pathlib.Path.cwd(), pathlib.Path(__file__).resolve().parents[2])]:
        if p.is_file():
            return p
    raise FileNotFoundError("data/work_precision_reference.json not found: reinstall pendula "
                            "(data/gen_work_precision_reference.py in the repository writes it)")


def load_reference(path=None) -> dict:
    """The stored references of the study's problems.

    Parameters
    ----------
    path : str or path, optional
        The reference file (default: data/work_precision_reference.json).

    Returns
    -------
    dict
        Per problem: ``t``, ``theta``, ``v`` (float64 arrays, rounded from the stored
        35 digits), ``reference_check`` (the difference of two Taylor integrations),
        ``floor_error_final`` and ``floor_error_max`` (the double-precision floor).

    Raises
    ------
    FileNotFoundError
        When the file is not found.

    Examples
    --------
    >>> from pendula.studies.workprecision import load_reference
    >>> ref = load_reference()                                  # doctest: +SKIP
    >>> ref["damped"]["reference_check"] < 1e-20                # doctest: +SKIP
    True
    """
    data = json.loads(pathlib.Path(path or reference_path()).read_text())
    out = {}
    for name, r in data["problems"].items():
        out[name] = {"t": np.array([float(x) for x in r["t"]]),
                     "theta": np.array([float(x) for x in r["theta"]]),
                     "v": np.array([float(x) for x in r["v"]]),
                     "reference_check": r["reference_check"],
                     "floor_error_final": r["floor_error_final"], "floor_error_max": r["floor_error_max"]}
    return out


def _params(p) -> np.ndarray:
    return np.array([p["eps"], p.get("beta", 0.0), p.get("tau", 0.0), p.get("amp", 0.0),
                     p.get("omega", 0.0), p.get("phase", 0.0)], dtype=np.float64)


def errors(p, ref, theta, v) -> dict:
    """Errors of one run against the reference.

    Parameters
    ----------
    p : dict
        The problem (an entry of PROBLEMS).
    ref : dict
        Its reference (an entry of :func:`load_reference`).
    theta, v : array_like
        The run's state at the reference's output times.

    Returns
    -------
    dict
        ``error_final``: max(|d theta|, |d v|) at the final time; ``error_max``: the largest
        over the output times (inf where the run is not finite); ``error_energy``: the
        largest |E - E0| for a conservative problem, else None.

    Examples
    --------
    >>> import numpy as np
    >>> from pendula.studies.workprecision import PROBLEMS, errors
    >>> ref = {"theta": np.zeros(3), "v": np.zeros(3)}
    >>> errors(PROBLEMS["damped"], ref, [0.0, 1e-9, 0.0], [0.0, 0.0, 2e-12])["error_max"]
    1e-09
    """
    theta = np.asarray(theta, dtype=float)
    v = np.asarray(v, dtype=float)
    e = np.maximum(np.abs(theta - ref["theta"]), np.abs(v - ref["v"]))
    e[~np.isfinite(e)] = np.inf
    out = {"error_final": float(e[-1]), "error_max": float(e.max()), "error_energy": None}
    if p["conservative"]:
        energy = 0.5 * v ** 2 - p["eps"] * np.cos(theta)
        e0 = 0.5 * p["v0"] ** 2 - p["eps"] * math.cos(p["theta0"])
        out["error_energy"] = float(np.max(np.abs(energy - e0)))
    return out


# ---------------------------------------------------------------- timing

def best_time(run_batch, batch_seconds=BATCH_SECONDS, max_batches=MAX_BATCHES) -> dict:
    """Time a run until its best time is stable.

    n is chosen from one calibrating call so that a batch lasts about batch_seconds;
    batches are repeated until the best three agree within SPREAD_GOAL (the relative
    spread of the best time, (third best - best) / best), or max_batches (3 when one
    run takes over SLOW_RUN seconds).

    Parameters
    ----------
    run_batch : callable
        run_batch(n) runs the solver n times and returns the CPU seconds of one run,
        measured around the runs alone.
    batch_seconds : float
        The length of one batch.
    max_batches : int
        The most batches.

    Returns
    -------
    dict
        ``seconds`` (the best batch's time per run), ``repeats`` (runs timed in all,
        the calibrating call not counted), ``spread``.

    Examples
    --------
    >>> from pendula.studies.workprecision import best_time
    >>> best_time(lambda n: 1e-3)["seconds"]
    0.001
    """
    n = 1
    t1 = run_batch(1)
    if t1 < batch_seconds:
        n = max(1, min(100000, int(batch_seconds / max(t1, 1e-7))))
    if t1 > SLOW_RUN:
        max_batches = min(max_batches, 3)
    times = []
    spread = float("inf")
    while len(times) < max_batches:
        times.append(run_batch(n))
        if len(times) >= 3:
            s = sorted(times)
            spread = (s[2] - s[0]) / s[0] if s[0] > 0 else float("inf")
            if spread < SPREAD_GOAL:
                break
    return {"seconds": min(times), "repeats": n * len(times), "spread": spread}


def _first_round(run_batch, batch_seconds=BATCH_SECONDS, max_batches=MAX_BATCHES) -> dict:
    """The interleaved study's first timing of a run: n calibrated as in :func:`best_time`, one batch;
    the run_batch is kept (``_run_batch``) for the later rounds (:func:`_more_rounds`)."""
    t1 = run_batch(1)
    n = max(1, min(100000, int(batch_seconds / max(t1, 1e-7)))) if t1 < batch_seconds else 1
    sec = run_batch(n)
    return {"seconds": sec, "repeats": n, "spread": float("inf"), "_run_batch": (run_batch, n, [sec])}


def _more_rounds(timers, rounds, progress, label):
    """Rounds 2..rounds of the interleaved study: every run once per round, in turn; each row keeps
    its best round and the spread of its three best ((third - best) / best)."""
    for k in range(1, rounds):
        for row, (run_batch, n, times) in timers:
            times.append(run_batch(n))
        if progress:
            print(f"  {label}: round {k + 1} of {rounds}", flush=True)
    for row, (run_batch, n, times) in timers:
        s = sorted(times)
        row["seconds"] = s[0]
        row["repeats"] = n * len(times)
        row["spread"] = (s[2] - s[0]) / s[0] if len(s) >= 3 and s[0] > 0 else float("inf")


def _process_batch(fn):
    """run_batch for a Python-called solver: process CPU time around n calls."""
    def run_batch(n):
        t0 = time.process_time()
        for _ in range(n):
            fn()
        return (time.process_time() - t0) / n
    return run_batch


# ---------------------------------------------------------------- pendula (kernel clock)

_KCODES = {"exact": 0, "rk4": 1, "verlet": 2, "yoshida4": 3, "yoshida6": 4, "yoshida8": 5, "gauss4": 6,
           "gauss6": 7, "dopri5": 8, "dop853": 9, "gsl-rk8pd": 10, "dprkn6": 11, "vern9": 12,
           "vern8": 14}


def run_pendula(p, t, method, rtol=0.0, dt=0.0, batch=BATCH_SECONDS, max_batches=MAX_BATCHES, timer=None):
    """theta, v and the timing of one pendula run, timed by the kernel's own clock
    (integrate_timed_v: the integration repeated inside the kernel); the timing carries the run's
    work: steps (attempted), rejected, rhs_evaluations."""
    from .. import _kernel

    land = method.endswith(LANDED)
    code = _KCODES[method[:-len(LANDED)] if land else method]
    prm = _params(p)
    last = {}

    def run_batch(n):
        th, v, stats, sec, status = _kernel.integrate_timed_v(n, code, prm, p["theta0"], p["v0"], t, rtol, rtol, dt,
                                                              -1.0, int(land))
        if status != 0:
            raise RuntimeError(f"{method}: kernel status {status}")
        last["theta"], last["v"], last["stats"] = th, v, stats
        return sec

    tm = (timer or best_time)(run_batch, batch, max_batches)
    if code != 0:
        st = last["stats"]
        tm.update({"steps": int(st[0]), "rejected": int(st[2]), "rhs_evaluations": int(st[3])})
    return last["theta"], last["v"], tm


# ---------------------------------------------------------------- peers

def _rhs_numpy(p):
    eps, beta, tau, amp, om, ph = _params(p)

    def f(t, y):
        a = -eps * math.sin(y[0])
        if beta:
            a -= beta * y[1]
        if tau:
            a += tau
        if amp:
            a += amp * math.cos(om * t + ph)
        return np.array([y[1], a])
    return f


def run_scipy(p, t, method, rtol, batch=BATCH_SECONDS, max_batches=MAX_BATCHES, timer=None):
    """SciPy's solve_ivp at the output times t (its dense output), timed by process CPU time."""
    solve_ivp = require("scipy.integrate", "bench", "pendula accuracy integrators (the SciPy peers)").solve_ivp

    f = _rhs_numpy(p)
    y0 = np.array([p["theta0"], p["v0"]])
    last = {}

    def once():
        last["sol"] = solve_ivp(f, (0.0, t[-1]), y0, method=method, t_eval=t, rtol=rtol, atol=rtol)
    tm = (timer or best_time)(_process_batch(once), batch, max_batches)
    sol = last["sol"]
    if not sol.success or sol.y.shape[1] != t.size:
        return None, None, tm
    return sol.y[0], sol.y[1], tm


def run_cvode(p, t, method, rtol, batch=BATCH_SECONDS, max_batches=MAX_BATCHES, timer=None):
    """SUNDIALS CVODE (scikit-sundae) with 'Adams' or 'BDF', outputs at t, timed by process CPU time."""
    from sksundae.cvode import CVODE

    eps, beta, tau, amp, om, ph = _params(p)

    def rhs(tt, y, yp):
        a = -eps * math.sin(y[0])
        if beta:
            a -= beta * y[1]
        if tau:
            a += tau
        if amp:
            a += amp * math.cos(om * tt + ph)
        yp[0] = y[1]
        yp[1] = a

    y0 = np.array([p["theta0"], p["v0"]])
    solver = CVODE(rhs, method=method, rtol=rtol, atol=rtol, max_num_steps=10 ** 7)
    last = {}

    def once():
        last["sol"] = solver.solve(t, y0)
    tm = (timer or best_time)(_process_batch(once), batch, max_batches)
    sol = last["sol"]
    if not sol.success or sol.y.shape[0] != t.size:
        return None, None, tm
    return sol.y[:, 0], sol.y[:, 1], tm


_NUMBA_CACHE: dict = {}


def _numbalsoda_runner(p, method):
    """A numba-compiled loop calling numbalsoda's solver n times (rhs as a numba.cfunc)."""
    import numba as nb
    import numbalsoda

    key = (tuple(_params(p)), method)
    if key in _NUMBA_CACHE:
        return _NUMBA_CACHE[key]
    eps, beta, tau, amp, om, ph = (float(x) for x in _params(p))

    @nb.cfunc(numbalsoda.lsoda_sig)
    def rhs(tt, u, du, data):
        a = -eps * math.sin(u[0]) - beta * u[1] + tau + amp * math.cos(om * tt + ph)
        du[0] = u[1]
        du[1] = a

    addr = rhs.address
    solve = numbalsoda.lsoda if method == "lsoda" else numbalsoda.dop853

    @nb.njit
    def loop(n, y0, t, rtol):
        usol = np.empty((t.size, 2))
        ok = True
        for _ in range(n):
            usol, ok = solve(addr, y0, t, rtol=rtol, atol=rtol, mxstep=10 ** 7)
        return usol, ok
    _NUMBA_CACHE[key] = loop
    return loop


def run_numbalsoda(p, t, method, rtol, batch=BATCH_SECONDS, max_batches=MAX_BATCHES, timer=None):
    """numbalsoda's LSODA or DOP853 (compiled, rhs a numba.cfunc), called n times from a jitted loop
    (no Python inside the timed interval but the one call), timed by process CPU time."""
    loop = _numbalsoda_runner(p, method)
    y0 = np.array([p["theta0"], p["v0"]])
    loop(1, y0, t, rtol)  # compile outside the clock
    last = {}

    def run_batch(n):
        t0 = time.process_time()
        last["r"] = loop(n, y0, t, rtol)
        return (time.process_time() - t0) / n
    tm = (timer or best_time)(run_batch, batch, max_batches)
    usol, ok = last["r"]
    if not ok:
        return None, None, tm
    return usol[:, 0], usol[:, 1], tm


#: diffrax's solvers in the study, and the batch of the vmapped form (one problem repeated: the time per problem)
DIFFRAX_SOLVERS = ("Dopri8", "Tsit5")
DIFFRAX_BATCH = 256
_DIFFRAX_CACHE: dict = {}


def _diffrax_solver(solver, batched):
    """A jitted diffrax solve (x64) of theta'' = -eps sin(theta) - beta v + tau + amp cos(omega t + phase)
    with the parameters, times, initial state and tolerance as arguments (traced: one compilation per
    solver and form, whatever the problem and the tolerance).  Returns (function, compile seconds)."""
    key = (solver, batched)
    if key in _DIFFRAX_CACHE:
        return _DIFFRAX_CACHE[key]
    import jax

    jax.config.update("jax_enable_x64", True)
    import diffrax
    import jax.numpy as jnp

    def rhs(tt, y, prm):
        eps, beta, tau, amp, om, ph = prm[0], prm[1], prm[2], prm[3], prm[4], prm[5]
        return jnp.stack([y[1], -eps * jnp.sin(y[0]) - beta * y[1] + tau + amp * jnp.cos(om * tt + ph)])

    term = diffrax.ODETerm(rhs)
    method = getattr(diffrax, solver)()

    def one(y0, ts, prm, rtol):
        sol = diffrax.diffeqsolve(term, method, t0=ts[0], t1=ts[-1], dt0=None, y0=y0, args=prm,
                                  saveat=diffrax.SaveAt(ts=ts),
                                  stepsize_controller=diffrax.PIDController(rtol=rtol, atol=rtol),
                                  max_steps=10 ** 6, throw=False)
        return sol.ys, sol.result == diffrax.RESULTS.successful

    fn = jax.jit(jax.vmap(one, in_axes=(0, None, None, None)) if batched else one)
    _DIFFRAX_CACHE[key] = fn
    return fn


def run_diffrax(p, t, method, rtol, batch=BATCH_SECONDS, max_batches=MAX_BATCHES, timer=None):
    """diffrax (JAX, jitted, x64): 'Dopri8' or 'Tsit5' on one problem, or '...-vmap256' on a batch of
    DIFFRAX_BATCH copies (seconds: per problem).  Timed by process CPU time around the calls (all of
    XLA's threads); the first call of a form (compilation) is timed apart as ``compile_seconds``."""
    import jax.numpy as jnp

    batched = method.endswith(f"-vmap{DIFFRAX_BATCH}")
    solver = method.split("-")[0]
    fresh = (solver, batched) not in _DIFFRAX_CACHE
    fn = _diffrax_solver(solver, batched)
    y0 = jnp.array([p["theta0"], p["v0"]])
    if batched:
        y0 = jnp.tile(y0, (DIFFRAX_BATCH, 1))
    args = (y0, jnp.asarray(t), jnp.asarray(_params(p)), jnp.asarray(rtol))
    c0 = time.process_time()
    ys, ok = fn(*args)
    ys.block_until_ready()
    first = time.process_time() - c0
    per = DIFFRAX_BATCH if batched else 1
    last = {}

    def run_batch(n):
        t0 = time.process_time()
        for _ in range(n):
            r = fn(*args)
            r[0].block_until_ready()
        last["r"] = r
        return (time.process_time() - t0) / n / per
    tm = (timer or best_time)(run_batch, batch, max_batches)
    if fresh:
        tm["compile_seconds"] = max(0.0, first - tm["seconds"] * per)
    ys, ok = last["r"]
    ys, ok = np.asarray(ys), np.asarray(ok)
    if not np.all(ok):
        return None, None, tm
    if batched:
        ys = ys[0]
    return ys[:, 0], ys[:, 1], tm


# ---------------------------------------------------------------- the study

def peer_versions() -> dict:
    """Versions of pendula, numpy and every peer that is installed (None: not installed)."""
    import importlib.metadata as md

    out = {}
    for name in ("pendula", "numpy", "scipy", "scikit-sundae", "numbalsoda", "numba", "mpmath", "jax", "diffrax"):
        try:
            out[name] = md.version(name)
        except md.PackageNotFoundError:
            out[name] = None
    try:
        import subprocess
        out["gsl"] = subprocess.run(["gsl-config", "--version"], capture_output=True, text=True,
                                    timeout=10).stdout.strip() or None
    except (OSError, subprocess.SubprocessError):
        out["gsl"] = None
    try:
        import subprocess
        out["gfortran"] = subprocess.run(["gfortran", "--version"], capture_output=True, text=True,
                                         timeout=10).stdout.splitlines()[0]
    except (OSError, IndexError, subprocess.SubprocessError):
        out["gfortran"] = None
    return out


def machine() -> dict:
    cpu = platform.processor() or ""
    try:
        for line in pathlib.Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    import os
    return {"cpu": cpu, "cores": os.cpu_count(), "system": platform.platform(), "python": platform.python_version()}


def _plan(p, tols, quick):
    """The runs of the study on problem p: (package, method, knob, value)."""
    runs = []
    for m in PENDULA_ADAPTIVE + (PENDULA_NYSTROM if not p.get("beta") else ()):
        pkg = "gsl" if m == GSL else "pendula"
        runs += [(pkg, m, "rtol", r) for r in tols]
    if not quick:
        for m, dts in PENDULA_FIXED.items():
            runs += [("pendula", m, "dt", d) for d in dts]
    for m in SCIPY_METHODS if not quick else ("RK45", "DOP853"):
        runs += [("scipy", m, "rtol", r) for r in tols if r >= SCIPY_TIGHTEST[m]]
    if quick:
        return runs
    try:
        import sksundae  # noqa: F401
        runs += [("sundials", f"CVODE-{m}", "rtol", r) for m in ("Adams", "BDF") for r in tols if r >= 1e-13]
    except ImportError:
        pass
    try:
        import numbalsoda  # noqa: F401
        runs += [("numbalsoda", m, "rtol", r) for m in ("lsoda", "dop853") for r in tols]
    except ImportError:
        pass
    try:
        import diffrax  # noqa: F401
        runs += [("diffrax", m + form, "rtol", r) for m in DIFFRAX_SOLVERS for form in ("", f"-vmap{DIFFRAX_BATCH}")
                 for r in tols]
    except ImportError:
        pass
    return runs


def run_study(problems=None, tols=None, quick=False, progress=True, reference=None, methods=None,
              packages=None, interleave=0) -> dict:
    """Run the work-precision study.

    Every method and setting on every problem; errors against the stored reference;
    the CPU time of the solver alone (:func:`best_time`).  Peers that are not installed
    (scikit-sundae, numbalsoda: ``make bench-peers``) are left out.

    Parameters
    ----------
    problems : sequence of str, optional
        Names of PROBLEMS (default: all; quick: 'damped').
    tols : sequence of float, optional
        rtol (= atol) of the adaptive methods (default TOLS).
    quick : bool
        The short form of ``make demo``: pendula's adaptive methods, GSL and SciPy's
        RK45 and DOP853 at three tolerances, short batches.
    progress : bool
        Print one line per run.
    reference : str or path, optional
        The reference file (see :func:`load_reference`).
    methods : sequence of str, optional
        Only these methods.
    packages : sequence of str, optional
        Only these packages ('pendula', 'gsl', 'scipy', 'sundials', 'numbalsoda', 'diffrax').
    interleave : int
        0: each run timed to a stable best (:func:`best_time`) before the next.  N > 0: every run of
        a problem is calibrated and timed once, then all of them again in turn, N rounds in all, and
        the best round kept (pendula and its peers side by side under the same load).

    Returns
    -------
    dict
        The record: ``date``, ``machine``, ``versions``, the timing and error rules,
        ``floors`` per problem and ``rows`` (problem, package, method, setting,
        error_final, error_max, error_energy, seconds, repeats, spread).

    Examples
    --------
    >>> from pendula.studies.workprecision import run_study
    >>> rec = run_study(problems=("damped",), tols=[1e-6], quick=True, progress=False)  # doctest: +SKIP
    >>> sorted({r["package"] for r in rec["rows"]})                                      # doctest: +SKIP
    ['gsl', 'pendula', 'scipy']
    """
    import warnings

    ref_all = load_reference(reference)
    if quick:
        problems = problems or QUICK["problems"]
        tols = tols or QUICK["tols"]
        batch, max_batches = QUICK["batch"], QUICK["max_batches"]
    else:
        problems = problems or tuple(PROBLEMS)
        tols = tols or TOLS
        batch, max_batches = BATCH_SECONDS, MAX_BATCHES
    rows = []
    floors = {}
    for pname in problems:
        p = PROBLEMS[pname]
        ref = ref_all[pname]
        t = ref["t"]
        floors[pname] = {"floor_error_final": ref["floor_error_final"], "floor_error_max": ref["floor_error_max"],
                         "reference_check": ref["reference_check"]}
        runs = _plan(p, tols, quick)
        if methods:
            runs = [r for r in runs if r[1] in methods]
        if packages:
            runs = [r for r in runs if r[0] in packages]
        timers = []
        if p["conservative"] and (not methods or "exact" in methods) and (not packages or "pendula" in packages):
            runs = [("pendula", "exact", "-", 0.0)] + runs
        for k, (pkg, method, knob, value) in enumerate(runs):
            kw = dict(batch=batch, max_batches=max_batches)
            if interleave:
                kw["timer"] = _first_round
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                try:
                    if pkg in ("pendula", "gsl"):
                        th, v, tm = run_pendula(p, t, method, rtol=value if knob == "rtol" else 0.0,
                                                dt=value if knob == "dt" else 0.0, **kw)
                    elif pkg == "scipy":
                        th, v, tm = run_scipy(p, t, method, value, **kw)
                    elif pkg == "sundials":
                        th, v, tm = run_cvode(p, t, method.split("-")[1], value, **kw)
                    elif pkg == "diffrax":
                        th, v, tm = run_diffrax(p, t, method, value, **kw)
                    else:
                        th, v, tm = run_numbalsoda(p, t, method, value, **kw)
                except RuntimeError as exc:
                    if progress:
                        print(f"  {pname} {pkg} {method} {knob}={value:g}: failed ({exc})")
                    continue
            if th is None:
                continue
            err = errors(p, ref, th, v)
            row = {"problem": pname, "package": pkg, "method": method, "setting": f"{knob}={value:g}"
                   if knob != "-" else "-", knob if knob != "-" else "rtol": value if knob != "-" else None}
            row.update(err)
            timer_state = tm.pop("_run_batch", None)
            row.update(tm)
            rows.append(row)
            if timer_state is not None:
                timers.append((row, timer_state))
            if progress:
                print(f"  {pname:9s} {pkg:10s} {method:12s} {row['setting']:12s} err {err['error_max']:9.2e} "
                      f"{tm['seconds'] * 1e3:9.3f} ms  ({tm['repeats']} runs, spread {tm['spread']:.1%})",
                      flush=True)
        _more_rounds(timers, interleave, progress, pname)
    import os

    return {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
            "machine": machine(), "versions": peer_versions(), "load_average_1_5_15": list(os.getloadavg()),
            "interleave": interleave,
            "clock": "process CPU time: the kernel's cpu_time around the repeated integration for pendula and "
                     "GSL; time.process_time around the calls for the Python-called peers (numbalsoda: around "
                     "one call of a jitted loop over the runs)",
            "timing_rule": f"runs batched to ~{batch} s; batches repeated until the best three agree within "
                           f"{SPREAD_GOAL:.0%} or {max_batches} batches; seconds = best batch / runs per batch",
            "error_rule": "state error max(|theta - ref|, |v - ref|) at the final time (error_final) and the "
                          "largest over the output times (error_max); error_energy: largest |E - E0| "
                          "(conservative problems)",
            "n_out": N_OUT, "quick": quick, "floors": floors, "rows": rows}


# ---------------------------------------------------------------- the answer: tables and figures

def repo_root() -> pathlib.Path:
    """The source tree: the working directory when it holds data/bench, else the one this module sits in."""
    for base in (pathlib.Path.cwd(), pathlib.Path(__file__).resolve().parents[2]):
        if (base / "data" / "bench").is_dir():
            return base
    raise FileNotFoundError("run from the repository root (data/bench/ not found)")


def record_path() -> pathlib.Path:
    """data/bench/work_precision.json in the source tree (the recorded run)."""
    return repo_root() / "data" / "bench" / "work_precision.json"


def _fastest(rows, target, pred):
    ok = [r for r in rows if pred(r) and r["error_max"] <= target]
    return min(ok, key=lambda r: r["seconds"]) if ok else None


def answer_table(record: dict, targets=TARGETS) -> list[dict]:
    """The answer a user can act on, from a recorded run.

    Parameters
    ----------
    record : dict
        A record of :func:`run_study` (e.g. data/bench/work_precision.json).
    targets : sequence of float
        Target errors (the largest state error over the output times).

    Returns
    -------
    list of dict
        Per problem and target: ``pendula`` (the fastest pendula integrator's row that
        reaches it, or None), ``peer``, ``scipy``, ``compiled`` (the fastest peer other
        than SciPy), and the time ratios ``peer_ratio``, ``scipy_ratio``,
        ``compiled_ratio`` (theirs / pendula's).

    Examples
    --------
    >>> from pendula.studies.workprecision import answer_table
    >>> rows = [{"problem": "damped", "package": "pendula", "method": "dop853", "error_max": 1e-7, "seconds": 1e-4},
    ...         {"problem": "damped", "package": "scipy", "method": "RK45", "error_max": 1e-7, "seconds": 1e-2}]
    >>> answer_table({"rows": rows}, targets=[1e-6])[0]["scipy_ratio"]
    100.0
    """
    out = []
    rows = record["rows"]
    problems = list(dict.fromkeys(r["problem"] for r in rows))
    for pname in problems:
        pr = [r for r in rows if r["problem"] == pname]
        for target in targets:
            pend = _fastest(pr, target, lambda r: r["package"] == "pendula" and r["method"] != "exact")
            peer = _fastest(pr, target, lambda r: r["package"] != "pendula")
            sci = _fastest(pr, target, lambda r: r["package"] == "scipy")
            comp = _fastest(pr, target, lambda r: r["package"] not in ("pendula", "scipy"))
            out.append({"problem": pname, "target": target, "pendula": pend, "peer": peer, "scipy": sci,
                        "compiled": comp,
                        "peer_ratio": peer["seconds"] / pend["seconds"] if pend and peer else None,
                        "scipy_ratio": sci["seconds"] / pend["seconds"] if pend and sci else None,
                        "compiled_ratio": comp["seconds"] / pend["seconds"] if pend and comp else None})
    return out


def _cell(r):
    if r is None:
        return "not reached"
    name = r["method"] if r["package"] in ("pendula",) else f"{r['package']} {r['method']}"
    if r["package"] == "gsl":
        name = r["method"]
    return f"{name} {r['setting']}: {_ms(r['seconds'])}"


def _ms(s):
    return f"{s * 1e3:.3g} ms" if s >= 1e-3 else f"{s * 1e6:.3g} us"


def _ratio(x):
    return "-" if x is None else f"{x:.3g}"


def _with_ratio(r, ratio) -> str:
    """A table cell: the run and its time against pendula's fastest (no '-' alone: RST would make it a bullet)."""
    if r is None:
        return "not reached"
    return _cell(r) + (f" ({ratio:.3g}x)" if ratio is not None else "")


def _problem_text(pname: str) -> str:
    p = PROBLEMS[pname]
    desc = ", ".join(f"{k} = {p[k]:g}" for k in ("beta", "tau", "amp", "omega") if p.get(k))
    return f"v0 = {p['v0']:g}{', ' + desc if desc else ''}, 0 <= t <= {p['t_end']:g}"


def answer_rst(record: dict) -> str:
    """The answer of the report page (docs/source/work_precision.rst), generated from the recorded
    run: per problem its work-precision figure and a table of four columns (the target error,
    pendula's fastest, the fastest peer and SciPy's fastest with their times against pendula's)."""
    lines = []
    problems = list(dict.fromkeys(r["problem"] for r in record["rows"]))
    table = answer_table(record)
    for pname in problems:
        title = pname.capitalize()
        lines += [title, "~" * len(title), "", f"{_problem_text(pname)}.", "",
                  f".. image:: ../figures/work_precision_{pname}.png",
                  f"   :alt: work-precision diagram of the {pname} problem", "",
                  ".. list-table::", "   :header-rows: 1", "   :widths: 12 29 30 29", "",
                  "   * - target error", "     - pendula's fastest", "     - fastest peer (time / pendula's)",
                  "     - SciPy's fastest (time / pendula's)"]
        for a in (x for x in table if x["problem"] == pname):
            if a["pendula"] is None:
                why = _why_not(record, pname, a["target"])
                lines += [f"   * - {a['target']:.0e}", f"     - {why}", "     - not reached", "     - not reached"]
                continue
            lines += [f"   * - {a['target']:.0e}", f"     - {_cell(a['pendula'])}",
                      f"     - {_with_ratio(a['peer'], a['peer_ratio'])}",
                      f"     - {_with_ratio(a['scipy'], a['scipy_ratio'])}"]
        lines.append("")
    return "\n".join(lines).rstrip("\n") + "\n"


def _why_not(record: dict, problem: str, target: float) -> str:
    """Why no run reached a target, in a few words: below the double-precision floor, or
    tighter than the tightest tolerance the run tried."""
    floor = record["floors"][problem]["floor_error_max"]
    if target < floor:
        return f"not reached: below the floor {floor:.0e}"
    rtols = [r["rtol"] for r in record["rows"] if r["problem"] == problem and r.get("rtol")]
    return f"not reached: tightest rtol run {min(rtols):.0e}" if rtols else "not reached"


def _short(r) -> str:
    if r is None:
        return "not reached"
    name = r["method"] if r["package"] in ("pendula", "gsl") else f"{r['package']} {r['method']}"
    return f"{name} {r['setting']}: {_ms(r['seconds'])}"


def answer_text(record: dict) -> str:
    """The answer table as plain text for a terminal (what ``pendula accuracy integrators`` and
    ``pendula demo`` print): per problem and target, pendula's fastest, the fastest peer and
    SciPy's fastest with the time ratios, and why a target was not reached.

    Parameters
    ----------
    record : dict
        A record of :func:`run_study`.

    Returns
    -------
    str
        One header line and one line per problem and target.

    Examples
    --------
    >>> from pendula.studies.workprecision import answer_text
    >>> rows = [{"problem": "damped", "package": "pendula", "method": "dop853", "setting": "rtol=1e-08",
    ...          "rtol": 1e-8, "error_max": 1e-7, "seconds": 1e-4},
    ...         {"problem": "damped", "package": "scipy", "method": "RK45", "setting": "rtol=1e-08",
    ...          "rtol": 1e-8, "error_max": 1e-7, "seconds": 1e-2}]
    >>> print(answer_text({"rows": rows, "floors": {"damped": {"floor_error_max": 1e-14}}}))
    problem    target  pendula's fastest               fastest peer                    ratio  SciPy / pendula
    damped     1e-03   dop853 rtol=1e-08: 100 us       scipy RK45 rtol=1e-08: 10 ms      100  100
    damped     1e-06   dop853 rtol=1e-08: 100 us       scipy RK45 rtol=1e-08: 10 ms      100  100
    damped     1e-09   not reached: tightest rtol run 1e-08
    damped     1e-12   not reached: tightest rtol run 1e-08
    """
    lines = [f"{'problem':10s} {'target':7s} {'pendula' + chr(39) + 's fastest':31s} {'fastest peer':31s} "
             f"{'ratio':>5s}  SciPy / pendula"]
    for a in answer_table(record):
        head = f"{a['problem']:10s} {a['target']:<7.0e}"
        if a["pendula"] is None:
            lines.append(f"{head} {_why_not(record, a['problem'], a['target'])}")
            continue
        lines.append(f"{head} {_short(a['pendula']):31s} {_short(a['peer']):31s} {_ratio(a['peer_ratio']):>5s}  "
                     f"{_ratio(a['scipy_ratio'])}")
    return "\n".join(lines)


def _same_setting_ratios(record, package, method, ref_method="dop853"):
    """Time ratios package:method / pendula:ref_method at equal problem and rtol."""
    mine = {(r["problem"], r["setting"]): r["seconds"] for r in record["rows"]
            if r["package"] == "pendula" and r["method"] == ref_method}
    return [r["seconds"] / mine[(r["problem"], r["setting"])] for r in record["rows"]
            if r["package"] == package and r["method"] == method and (r["problem"], r["setting"]) in mine]


def summary_rst(record: dict) -> str:
    """The measured verdicts of the report page, as an RST bullet list generated from the record:
    the ratio ranges against SciPy and the compiled peers, and the cells where pendula is slower."""
    table = answer_table(record)
    sci = [a["scipy_ratio"] for a in table if a["scipy_ratio"] is not None]
    comp = [a for a in table if a["compiled_ratio"] is not None]
    slower = [a for a in comp if a["compiled_ratio"] < 1.0]
    lines = []
    if sci:
        lines.append(f"* SciPy's fastest / pendula's fastest: {min(sci):.0f} to {max(sci):.0f} over the {len(sci)} "
                     f"cells both reach; below 30 in {sum(x < 30 for x in sci)} of them.")
    if comp:
        lines.append(f"* fastest compiled peer / pendula's fastest: {min(a['compiled_ratio'] for a in comp):.2f} to "
                     f"{max(a['compiled_ratio'] for a in comp):.2f} over {len(comp)} cells; pendula is slower in "
                     + (f"{len(slower)}: " + ", ".join(f"{a['problem']} {a['target']:.0e} ({_cell(a['compiled'])}, "
                                                       f"{a['compiled_ratio']:.2f})" for a in slower)
                        if slower else "none") + ".")
    slow_sci = [a for a in table if a["scipy_ratio"] is not None and a["scipy_ratio"] < 30]
    if slow_sci:
        lines.append("* below 30 times SciPy: " + ", ".join(
            f"{a['problem']} {a['target']:.0e} (pendula {_cell(a['pendula'])}, SciPy {_cell(a['scipy'])}, "
            f"{a['scipy_ratio']:.0f})" for a in slow_sci) + ".")
    for pkg, method in (("numbalsoda", "dop853"), ("gsl", "gsl-rk8pd"), ("sundials", "CVODE-Adams"),
                        ("numbalsoda", "lsoda"), ("diffrax", "Dopri8"), ("diffrax", f"Dopri8-vmap{DIFFRAX_BATCH}"),
                        ("diffrax", "Tsit5"), ("diffrax", f"Tsit5-vmap{DIFFRAX_BATCH}")):
        r = _same_setting_ratios(record, pkg, method)
        if r:
            lines.append(f"* {pkg} {method} / pendula's dop853 at the same problem and rtol: median "
                         f"{float(np.median(r)):.2f} (from {min(r):.2f} to {max(r):.2f}, {len(r)} settings).")
    ex = [r for r in record["rows"] if r["method"] == "exact"]
    for r in ex:
        integ = [q["seconds"] for q in record["rows"] if q["problem"] == r["problem"] and q["method"] != "exact"]
        lines.append(f"* exact path, {r['problem']}: {_ms(r['seconds'])} for {record.get('n_out', N_OUT) + 1} "
                     f"outputs, error {r['error_max']:.1e}; the cheapest integrator run of any accuracy costs "
                     f"{min(integ) / r['seconds']:.0f} times more.")
    return "\n".join(lines) + "\n"


def versions_rst(record: dict) -> str:
    """Machine, date and versions of the recorded run, as an RST field list."""
    m = record["machine"]
    lines = [f":date: {record['date']}", f":machine: {m['cpu']}, {m['cores']} cores, {m['system']}, "
             f"Python {m['python']}"]
    for k, v in record["versions"].items():
        lines.append(f":{k}: {v if v else 'not installed'}")
    return "\n".join(lines) + "\n"


PACKAGE_STYLE = {"pendula": "-", "gsl": "--", "scipy": ":", "sundials": "-.", "numbalsoda": "-.", "diffrax": ":"}

#: the families of methods a figure shows one curve of (the best), in the legend's order
FAMILIES = (("pendula, adaptive", lambda r: r["package"] == "pendula" and r["method"] not in PENDULA_FIXED
             and r["method"] != "exact"),
            ("pendula, fixed step", lambda r: r["package"] == "pendula" and r["method"] in PENDULA_FIXED),
            ("GSL", lambda r: r["package"] == "gsl"),
            ("SciPy", lambda r: r["package"] == "scipy"),
            ("SUNDIALS", lambda r: r["package"] == "sundials"),
            ("numbalsoda", lambda r: r["package"] == "numbalsoda"))
#: the error levels at which methods are compared for "best of the family"
_LEVELS = tuple(10.0 ** (-k / 2) for k in range(4, 27))


#: the pairs method='auto' chooses from (outputs interpolated, steps not landed) and the rtol decades
AUTO_CANDIDATES = ("dopri5", "dop853", "vern9", "vern8")
AUTO_DECADES = tuple(range(3, 15))
#: a candidate qualifies with an error up to this many times rtol (or up to DOP853's own)
AUTO_SLACK = 10.0
#: the name of the rows that stand for method='auto' in the figures
AUTO = "auto"


def auto_picks(rows: list[dict]) -> dict:
    """What ``method='auto'`` integrates with, per problem and rtol decade, from a recorded study.

    For each of the study's problems (a class of scenes) and each rtol = atol = 10^-k, k = 3 ... 14,
    the fastest of pendula's pairs with an interpolant (AUTO_CANDIDATES) whose largest error over
    the outputs is no larger than DOP853's at that rtol or than 10 rtol, within the study's noise
    (:func:`auto_noise`): the qualifying pairs whose time is within that of the fastest are tied,
    and the tie goes to the smallest error (a time the study cannot tell apart is not a reason to
    give up accuracy).  The one rule: data/bench/gen_auto_methods.py writes it into the kernel's
    dispatcher, the figures draw it.

    Parameters
    ----------
    rows : list of dict
        The rows of a record of :func:`run_study`.

    Returns
    -------
    dict
        (problem, k) -> the row of the pick (None when the record has no candidate there).

    Examples
    --------
    >>> from pendula.studies.workprecision import auto_picks
    >>> rows = [dict(problem="damped", package="pendula", method=m, rtol=1e-6, error_max=e, seconds=s)
    ...         for m, e, s in (("dop853", 4e-6, 2.0), ("vern9", 3e-6, 1.5), ("vern8", 9e-5, 1.0))]
    >>> auto_picks(rows)["damped", 6]["method"]
    'vern9'
    """
    cand = [r for r in rows if r["package"] == "pendula" and r["method"] in AUTO_CANDIDATES
            and r.get("error_max") is not None and r.get("rtol")]
    noise = auto_noise(rows)
    out = {}
    for pname in dict.fromkeys(r["problem"] for r in rows):
        for k in AUTO_DECADES:
            rtol = 10.0 ** -k
            at = {r["method"]: r for r in cand if r["problem"] == pname and abs(r["rtol"] - rtol) <= 1e-6 * rtol}
            base = at.get("dop853")
            bound = max(AUTO_SLACK * rtol, base["error_max"] if base else 0.0)
            ok = [r for r in at.values() if r["error_max"] <= bound]
            if not ok:
                out[pname, k] = base
                continue
            fastest = min(r["seconds"] for r in ok)
            tied = [r for r in ok if r["seconds"] <= (1.0 + noise) * fastest]
            out[pname, k] = min(tied, key=lambda r: (r["error_max"], r["seconds"]))
    return out


def auto_noise(rows: list[dict]) -> float:
    """The study's own timing noise among the candidates of ``method='auto'``: the median over
    their rows of the spread of the best three rounds ((third - best) / best, the rows'
    ``spread``); 0 when the rows carry none.

    Parameters
    ----------
    rows : list of dict
        The rows of a record of :func:`run_study`.

    Returns
    -------
    float
        The relative difference in time below which two candidates count as equally fast.

    Examples
    --------
    >>> from pendula.studies.workprecision import auto_noise
    >>> rows = [dict(package="pendula", method="vern9", rtol=1e-6, error_max=1e-6, spread=s)
    ...         for s in (0.05, 0.1, 0.2)]
    >>> auto_noise(rows)
    0.1
    """
    sp = sorted(float(r["spread"]) for r in rows if r.get("package") == "pendula"
                and r.get("method") in AUTO_CANDIDATES and r.get("rtol") and r.get("error_max") is not None
                and r.get("spread") is not None and math.isfinite(float(r["spread"])))
    if not sp:
        return 0.0
    n = len(sp)
    return sp[n // 2] if n % 2 else 0.5 * (sp[n // 2 - 1] + sp[n // 2])


def best_of_families(rows: list[dict]) -> list[tuple[str, str, str]]:
    """The curves of a problem's figure: the best method of each family, and what ``method='auto'``
    integrates with (:func:`auto_picks`: rows named 'auto', when the rows have them).

    The best method of a family is the one fastest at the most error levels (10^-2 ... 10^-13 in
    half decades, each reached by at least one of the family); ties go to the smaller sum of log
    times.

    Parameters
    ----------
    rows : list of dict
        The rows of one problem of a record of :func:`run_study`.

    Returns
    -------
    list of (family, package, method)
        At most one per family, plus pendula's DOP853: at most 7 curves.

    Examples
    --------
    >>> from pendula.studies.workprecision import best_of_families
    >>> rows = [dict(package="scipy", method=m, error_max=e, seconds=s)
    ...         for m, e, s in (("RK45", 1e-6, 2.0), ("DOP853", 1e-6, 1.0), ("DOP853", 1e-9, 1.5))]
    >>> best_of_families(rows)
    [('SciPy', 'scipy', 'DOP853')]
    """
    out = []
    has_auto = any(r["method"] == AUTO for r in rows)
    rows = [r for r in rows if r["method"] != AUTO]
    for family, member in FAMILIES:
        fam = [r for r in rows if member(r)]
        methods = list(dict.fromkeys((r["package"], r["method"]) for r in fam))
        if not methods:
            continue
        wins = {m: 0 for m in methods}
        logt = {m: 0.0 for m in methods}
        for level in _LEVELS:
            best = {}
            for r in fam:
                if r["error_max"] <= level:
                    key = (r["package"], r["method"])
                    best[key] = min(best.get(key, math.inf), r["seconds"])
            if not best:
                continue
            wins[min(best, key=best.get)] += 1
            for m in methods:
                logt[m] += math.log(best.get(m, 1e3))      # a level a method misses counts as very slow
        pkg, method = max(methods, key=lambda m: (wins[m], -logt[m]))
        out.append((family, pkg, method))
        if family == "pendula, adaptive" and has_auto:
            out.append(("pendula, method='auto'", "pendula", AUTO))
    return out


def write_figures(record: dict, outdir) -> list[pathlib.Path]:
    """One work-precision diagram per problem: the best method of each family.

    Error against CPU time (log-log), at most 8 curves (:func:`best_of_families`),
    with the double-precision floor and (conservative problems) the exact path;
    every method's numbers are in the record and the page's tables.

    Parameters
    ----------
    record : dict
        A record of :func:`run_study`.
    outdir : str or path
        Folder for work_precision_PROBLEM.png (created).

    Returns
    -------
    list of pathlib.Path
        The files written.

    Examples
    --------
    >>> import json
    >>> from pendula.studies.workprecision import record_path, write_figures
    >>> write_figures(json.loads(record_path().read_text()), "out")   # doctest: +SKIP
    """
    matplotlib = require("matplotlib", "accuracy", "pendula accuracy integrators (figures)")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    outdir = pathlib.Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    files = []
    rows = record["rows"]
    # method='auto': the rows of its picks, one per rtol decade
    rows = rows + [dict(r, method=AUTO) for r in auto_picks(rows).values() if r is not None]
    for pname in dict.fromkeys(r["problem"] for r in rows):
        pr = [r for r in rows if r["problem"] == pname]
        fig, ax = plt.subplots(figsize=(7.5, 5.8))
        for family, pkg, method in best_of_families(pr):
            sel = sorted((r for r in pr if r["package"] == pkg and r["method"] == method),
                         key=lambda r: r["seconds"])
            err = np.maximum([r["error_max"] for r in sel], 1e-17)
            sec = [r["seconds"] for r in sel]
            ax.loglog(sec, err, PACKAGE_STYLE.get(pkg, "-"), marker="o" if pkg == "pendula" else ".",
                      ms=4, lw=1.4 if pkg == "pendula" else 1.1, label=f"{family}: {method}")
        ex = [r for r in pr if r["method"] == "exact"]
        if ex:
            ax.loglog([ex[0]["seconds"]], [max(ex[0]["error_max"], 1e-17)], "k*", ms=12, label="pendula: exact path")
        floor = record["floors"][pname]["floor_error_max"]
        ax.axhline(floor, color="k", lw=0.8, ls="--")
        ax.text(ax.get_xlim()[0], floor, " double-precision floor (1 ulp in v0)", va="bottom", fontsize=7)
        for target in TARGETS:
            ax.axhline(target, color="0.85", lw=0.5)
        ax.set_xlabel("CPU time of one run (s)")
        ax.set_ylabel("largest state error over the outputs")
        title = f"{pname}: {_problem_text(pname)}"
        if pname == "driven":
            title += "\nchaotic: compared over ~5 Lyapunov times only (lambda ~ 0.1)"
        ax.set_title(title, fontsize=9)
        ax.grid(True, which="both", alpha=0.25)
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=3, frameon=False)
        fig.tight_layout()
        path = outdir / f"work_precision_{pname}.png"
        try:
            save_figure(fig, path, dpi=100)
        finally:
            plt.close(fig)
        files.append(path)
    return files


def merge_records(records: list[dict]) -> dict:
    """One record from runs of the study on disjoint sets of problems (the recorded run was made
    as one process per problem): rows and floors joined, the first record's header kept, the
    dates joined."""
    out = dict(records[0])
    out["rows"] = [r for rec in records for r in rec["rows"]]
    out["floors"] = {k: v for rec in records for k, v in rec["floors"].items()}
    out["date"] = " / ".join(sorted({rec["date"] for rec in records}))
    return out


def study_main(outdir, quick=False, progress=True, record_to=None, problems=None) -> list[pathlib.Path]:
    """``pendula accuracy integrators`` (and its short form in ``make demo``).

    Runs the study, writes the record and the figures, prints the answer table.

    Parameters
    ----------
    outdir : str or path
        Folder for the record (work_precision.json) and the figures.
    quick : bool
        The short form (see :func:`run_study`).
    progress : bool
        Print one line per run.
    record_to : str or path, optional
        Where to write the record instead (e.g. data/bench/work_precision.json).
    problems : sequence of str, optional
        Only these problems.

    Returns
    -------
    list of pathlib.Path
        The files written.

    Examples
    --------
    >>> from pendula.studies.workprecision import study_main
    >>> study_main("out", quick=True)      # doctest: +SKIP
    """
    # the optional packages first: a missing one is one line before the study runs, never a traceback after
    require("scipy.integrate", "bench", "pendula accuracy integrators (the SciPy peers)")
    require("matplotlib", "accuracy", "pendula accuracy integrators (figures)")
    outdir = pathlib.Path(outdir)
    if outdir.exists() and not outdir.is_dir():
        raise NotADirectoryError(20, "is not a folder", str(outdir))
    outdir.mkdir(parents=True, exist_ok=True)
    record = run_study(problems=problems, quick=quick, progress=progress)
    path = pathlib.Path(record_to) if record_to else outdir / "work_precision.json"
    with open_text(path) as fh:
        fh.write(json.dumps(record, indent=1) + "\n")
    files = [path] + write_figures(record, outdir)
    print(answer_text(record))
    return files


#: the report page and the markers around its generated parts
PAGE = pathlib.Path("docs") / "source" / "work_precision.rst"
GENERATED = {"table": (".. generated answer table (pendula.studies.workprecision.answer_rst): do not edit by hand",
                       ".. end of the generated answer table"),
             "versions": (".. generated run description (pendula.studies.workprecision.versions_rst): do not edit",
                          ".. end of the generated run description"),
             "summary": (".. generated verdicts (pendula.studies.workprecision.summary_rst): do not edit",
                         ".. end of the generated verdicts")}


def generated_parts(record: dict) -> dict:
    """The page's generated parts from the recorded run: the answer table and the run description."""
    return {"table": answer_rst(record), "versions": versions_rst(record), "summary": summary_rst(record)}


def page_part(text: str, key: str) -> str:
    """The text between one pair of markers of the report page."""
    start, end = GENERATED[key]
    a = text.index(start) + len(start)
    b = text.index(end)
    return text[a:b].strip("\n") + "\n"


def update_page(record: dict, page=None) -> None:
    """Write the generated parts of the report page (docs/source/work_precision.rst) from the record."""
    page = pathlib.Path(page or repo_root() / PAGE)
    text = page.read_text()
    for key, body in generated_parts(record).items():
        start, end = GENERATED[key]
        a = text.index(start) + len(start)
        b = text.index(end)
        text = text[:a] + "\n\n" + body + "\n" + text[b:]
    page.write_text(text)


def regenerate_docs(record_file=None) -> list[pathlib.Path]:
    """The figures and the report page's tables from the recorded run.

    Parameters
    ----------
    record_file : str or path, optional
        The record (default data/bench/work_precision.json).

    Returns
    -------
    list of pathlib.Path
        docs/figures/work_precision_*.png and docs/source/work_precision.rst.

    Examples
    --------
    >>> from pendula.studies.workprecision import regenerate_docs
    >>> regenerate_docs()          # doctest: +SKIP
    """
    record = json.loads(pathlib.Path(record_file or record_path()).read_text())
    files = write_figures(record, repo_root() / "docs" / "figures")
    update_page(record)
    return files + [repo_root() / PAGE]

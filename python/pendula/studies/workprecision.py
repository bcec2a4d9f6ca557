"""What accuracy costs in time: the work-precision study of the integrators.

Problems, references, peers and timing; the tables, figures and page made
from the recorded run (data/bench/work_precision.json) are
:mod:`pendula.studies.workprecision_report`; see docs/source/work_precision.rst.
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

__all__ = ["PROBLEMS", "N_OUT", "TARGETS", "load_reference", "errors", "best_time", "run_study"]

import datetime
import json
import math
import pathlib
import platform
import time

import numpy as np

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

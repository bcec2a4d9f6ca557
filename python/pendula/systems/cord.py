"""The pendulum on a flexible cord (Garfinkel 1957, seed 000).

A bob on a massless inextensible cord of length l that can go slack.  Units:
lengths in l (the pivot at the origin, x to the right, y up, the bob at
(sin theta, -cos theta) on the circle), gravity eps = g/l.

Phases
------
circle
    While the tension m l (v^2 + eps cos theta) is positive.  Without effects
    the motion is the exact elliptic solution (:func:`pendula.exact_motion`)
    and the departure point and time are closed forms of the energy
    xi = (v^2 - 2 eps cos theta) / (3 eps): cos theta1 = -xi, and the time to
    reach it is an incomplete elliptic integral F (no root search).  This
    conservative case runs whole in the kernel (kernel/models/pendula_cord.f90,
    ``cord_run``; binding ``cord_run_v``), about 1 us per flip.  With
    damping, torque or drive the circle is integrated by the scene's adaptive
    method (dopri5/dop853) and the departure is located as an event of the
    tension (event kind 4 of the kernel integrators).  Fixed-step methods have
    no dense output: they are refused with a ValueError naming the method.
flight
    A parabola in closed form.  |p(tau)|^2 - 1 is a quartic in the flight time
    tau whose low coefficients vanish at a tangential departure (r' = 0 and
    zero tension make tau^3 a factor), so the re-entry time is the root of the
    remaining linear factor: tau = -4 (u . g) / |g|^2 (the seed's eq. 13.1),
    never the departure point itself.  After a springy re-entry (restitution
    e > 0) the flight starts with an inward radial velocity: then tau is the
    smallest positive root of a cubic, taken from its companion matrix and
    polished by bisection on a sign-change bracket.
    Damping, torque and drive are effects applied at the pivot (the damping
    beta v is pivot friction): a slack cord transmits none of them, so the
    flight is free fall under gravity alone.
jerk
    At re-entry the cord removes the radial velocity (times 1 + e): the angular
    momentum about the pivot is conserved, energy is lost.

Stopping: a run ends after ``max_flips`` flips or at a flight shorter than
``min_flight`` (in units of 1/sqrt(eps)); output times after the stop are NaN
(RuntimeWarning) and ``stats['stop_reason']`` says why.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .. import _kernel
from .._checks import as_float
from .rigid import energy

__all__ = ["flip_map", "cord_state", "flip_sequence", "simulate_cord", "xi_of"]

TWO_PI = 2.0 * math.pi


# ------------------------------------------------------------ closed forms

def flip_map(xi):
    """Garfinkel's flip map f (seed eqs. 14-15), vectorised.

    f(x) = x - (64/3) [x (1 - x^2)]^3 for 0 <= x <= 1, and f(x) = x outside
    (the kernel's elemental ``flip_map``, kernel/models/pendula_cord.f90).

    Examples
    --------
    >>> import pendula
    >>> float(pendula.flip_map(0.5))
    -0.625
    >>> float(pendula.flip_map(1.5))
    1.5
    """
    x = as_float(xi, "xi")
    out = _kernel.cord_flip_map_v(np.ascontiguousarray(x, dtype=np.float64).reshape(-1)).reshape(x.shape)
    return out if out.ndim else out[()]


def _finv_upper(y):
    """The inverse of f on its increasing branch above its minimum (x in [0.5458, 1]),
    by bisection on the bracket (f is monotone there): robust, about 1 ulp."""
    lo, hi = _XMIN, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        w = mid * (1.0 - mid) * (1.0 + mid)
        if mid - (64.0 / 3.0) * w * w * w < y:  # f(mid), the same expression as flip_map
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _argmin_f():
    # f'(x) = 1 - 64 w^2 (1 - 3 x^2) with w = x(1 - x^2); f' < 0 on (0.2, 0.55) region's right
    # end; bisection on f' in [1/3^0.5 - 0.1, 1/3^0.5) where the minimum lies
    def fp(x):
        w = x * (1 - x * x)
        return 1.0 - 64.0 * w * w * (1.0 - 3.0 * x * x)
    lo, hi = 0.5, 0.577  # fp(0.5) < 0 < fp(0.577)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        if fp(mid) < 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


_XMIN = _argmin_f()


def flip_sequence(n: int) -> np.ndarray:
    """The first n terms of Garfinkel's sequence x_k (seed eqs. 16-17).

    x_0 = -2/3, x_1, x_2, x_3 the zeros of f (0, 0.2360, 0.7511), then
    x_{k+4} = f^{-1}(x_{k+2}) on the branch of f above its minimum, found by
    bisection (f is monotone there), so every term is good to about 1 ulp.

    Examples
    --------
    >>> import pendula
    >>> [round(float(x), 3) for x in pendula.flip_sequence(5)]
    [-0.667, 0.0, 0.236, 0.751, 0.791]
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise ValueError(f"n must be a non-negative whole number, got {n!r}")
    # the zeros of f in (0, 1): w^3 = 3 x / 64 with w = x (1 - x^2), i.e. (1 - x^2)^3 x^2 = 3/64;
    # g(x) = x^2 (1 - x^2)^3 rises on (0, 1/2) and falls on (1/2, 1): one root on each side.
    def g(x):
        return x * x * (1 - x * x) ** 3 - 3.0 / 64.0

    def bis(lo, hi):
        glo = g(lo)
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if mid <= lo or mid >= hi:
                break
            if (g(mid) < 0) == (glo < 0):
                lo, glo = mid, g(mid)
            else:
                hi = mid
        return 0.5 * (lo + hi)

    xs = [-2.0 / 3.0, 0.0, bis(0.0, 0.5), bis(0.5, 1.0)]
    while len(xs) < n:
        xs.append(_finv_upper(xs[len(xs) - 2]))
    return np.array(xs[:n])


def cord_state(xi, nmax: int = 200):
    """Garfinkel's state index k of an energy xi (seed eq. 18), vectorised.

    k such that x_k <= xi < x_{k+1} for -2/3 <= xi < 1; ``math.inf`` for xi >= 1
    (circulation).  The sequence is computed to ``nmax`` terms (x_200 lies
    1e-3 below 1); xi beyond the last term gives k = nmax - 1 with a
    RuntimeWarning.  xi < -2/3 is not an energy: NaN with a RuntimeWarning.

    Examples
    --------
    >>> import pendula
    >>> float(pendula.cord_state(0.777))
    3.0
    """
    x = as_float(xi, "xi")
    seq = flip_sequence(nmax)
    k = np.searchsorted(seq, x, side="right").astype(float) - 1.0
    k = np.where(x >= 1.0, math.inf, k)
    bad = (x < seq[0] - 1e-15) | np.isnan(x)
    if np.any(bad):
        warnings.warn("cord_state: xi below -2/3 is not an energy: NaN", RuntimeWarning, stacklevel=2)
        k = np.where(bad, np.nan, k)
    top = (x >= seq[-1]) & (x < 1.0)
    if np.any(top):
        warnings.warn(f"cord_state: xi above x_{nmax - 1}: raise nmax", RuntimeWarning, stacklevel=2)
    k = np.where((x >= seq[0] - 1e-15) & (x < seq[0]), 0.0, k)
    return k if k.ndim else k[()]


def xi_of(theta, v, eps):
    """Garfinkel's normalised energy xi = (v^2 - 2 eps cos theta) / (3 eps)."""
    return (np.asarray(v) ** 2 - 2.0 * eps * np.cos(theta)) / (3.0 * eps)


# ------------------------------------------------------------ the engine

def _flight_time(p, u, g, tangential):
    """Smallest positive root of |p + u tau + g tau^2/2|^2 = 1 (|p| = 1).

    Coefficients of |p(tau)|^2 - 1: c1 tau + c2 tau^2 + c3 tau^3 + c4 tau^4 with
    c1 = 2 p.u, c2 = |u|^2 + p.g (the tension / m), c3 = u.g, c4 = |g|^2/4.
    Tangential departure with zero tension: c1 = c2 = 0 exactly (set, not
    computed from rounded numbers), tau = -c3/c4.  Otherwise tau divides out
    once and the cubic's smallest positive root is bracketed and bisected.
    """
    c3 = u[0] * g[0] + u[1] * g[1]
    c4 = 0.25 * (g[0] * g[0] + g[1] * g[1])
    if tangential:
        return -c3 / c4 if c3 < 0 else math.nan
    c1 = 2.0 * (p[0] * u[0] + p[1] * u[1])
    c2 = u[0] * u[0] + u[1] * u[1] + p[0] * g[0] + p[1] * g[1]
    if c1 == 0.0:  # tangential with tension c2 <= 0: the quadratic c2 + c3 tau + c4 tau^2
        if c2 > 0:
            return math.nan
        if c2 == 0.0:
            return -c3 / c4 if c3 < 0 else math.nan
        return (-c3 + math.sqrt(c3 * c3 - 4.0 * c4 * c2)) / (2.0 * c4)
    if c1 > 0:
        return math.nan  # moving outward: the cord is taut, no flight

    def P(t):
        return c1 + t * (c2 + t * (c3 + t * c4))

    roots = np.roots([c4, c3, c2, c1])
    real = sorted(r.real for r in roots if abs(r.imag) <= 1e-9 * (1 + abs(r)) and r.real > 0)
    # P(0) = c1 < 0 and P -> +inf: a positive root exists; bracket the smallest one
    hi = real[0] * (1 + 1e-6) + 1e-300 if real else 1.0
    while P(hi) < 0:
        hi *= 2.0
    lo = 0.0
    if real:
        lo = max(0.0, real[0] * (1 - 1e-6))
        if P(lo) >= 0:
            lo = 0.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        if P(mid) < 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _land(p, u, g, tau, theta_ref, restitution):
    x = p[0] + u[0] * tau + 0.5 * g[0] * tau * tau
    y = p[1] + u[1] * tau + 0.5 * g[1] * tau * tau
    wx = u[0] + g[0] * tau
    wy = u[1] + g[1] * tau
    th = math.atan2(x, -y)
    th += TWO_PI * round((theta_ref - th) / TWO_PI)
    r = math.hypot(x, y)  # 1 to rounding; the tangential direction uses the unit vector
    ct, st = -y / r, x / r
    vt = wx * ct + wy * st  # tangential velocity = l * theta'
    vr = wx * st - wy * ct  # radial (outward) velocity, annihilated (or reversed by e)
    return tau, th, vt, -restitution * vr


def _flight_positions(p, u, g, ts):
    x = p[0] + u[0] * ts + 0.5 * g[0] * ts * ts
    y = p[1] + u[1] * ts + 0.5 * g[1] * ts * ts
    wx = u[0] + g[0] * ts
    wy = u[1] + g[1] * ts
    r = np.hypot(x, y)
    th = np.arctan2(x, -y)
    thdot = np.where(r > 0, (x * wy - y * wx) / np.where(r > 0, r * r, 1.0), np.nan)
    return x, y, r, th, thdot


def _integrate_segment(scene, method, t0, theta0, v0, t_out):
    """Integrate the circle from (t0, theta0, v0) to the tension event or t_out[-1].

    Returns (theta, v at t_out before the event, event (t, theta, v) or None, stats)."""
    params = np.array([scene.eps, scene.damping, scene.torque, scene.drive_amplitude,
                       scene.drive_frequency, scene.drive_phase + scene.drive_frequency * t0], dtype=np.float64)
    from ..integrate import CODES, _STATUS
    ts = np.ascontiguousarray(np.asarray(t_out, dtype=np.float64) - t0)
    th, v, st, status, nev, tev, thev, vev = _kernel.integrate_v(
        CODES[method], params, 0, 0.0, theta0, v0, ts, scene.rtol, scene.atol, scene.dt, 4, 0.0, -1, 1, 1,
        np.zeros(1, dtype=np.int32))
    if status not in (0, 10):
        raise ValueError(f"{method}: {_STATUS.get(status, f'kernel status {status}')}")
    ev = (t0 + float(tev[0]), float(thev[0]), float(vev[0])) if status == 10 and nev > 0 else None
    return th, v, ev, st


_LOG = ("t_leave", "theta_leave", "t_return", "theta_return", "xi_before", "xi_after", "v_leave", "v_return")
_STOPS = {0: "t_end", 1: "max_flips", 2: "min_flight"}
_CORD_STATUS = {1: "eps must be positive and finite", 2: "theta0 and v0 must be finite",
                3: "t must be finite and >= 0", 4: "restitution must be in [0, 1)"}


def _exact_run(scene, t, ts, back):
    """The conservative case: the compiled path (kernel/models/pendula_cord.f90, cord_run)."""
    from ..trajectory import Trajectory

    cap = max(1, min(scene.max_flips, 65536))
    while True:
        th, v, x, y, r, fl, nf, stop, status = _kernel.cord_run_v(
            cap, scene.eps, scene.theta0, scene.v0, scene.restitution, scene.max_flips, scene.min_flight, ts)
        if status:
            raise ValueError(_CORD_STATUS.get(status, f"cord kernel status {status}"))
        if not (stop == 1 and nf == cap and cap < scene.max_flips):
            break
        cap = min(scene.max_flips, 8 * cap)  # the flip log was full: run again with room
    nan_after = int(np.count_nonzero(np.isnan(th)))
    if nan_after:
        warnings.warn(f"flexible cord: the run stopped ({_STOPS[int(stop)]}) at flip {nf}; "
                      f"{nan_after} later output time(s) are NaN", RuntimeWarning, stacklevel=4)
    theta, vv = back(th), back(v)
    flips = {k: fl[i, :nf].copy() for i, k in enumerate(_LOG)}
    stats = {"flips": int(nf), "stop_reason": _STOPS[int(stop)]}
    return Trajectory(t, theta, vv, energy(theta, vv, scene.eps), "exact", scene, stats,
                      x=back(x), y=back(y), r=back(r), flips=flips)


def simulate_cord(scene, t):
    """A Trajectory of a flexible-cord scene at the times t (>= 0, any order).

    The Trajectory gains x, y, r (the bob's position in units of l; r < 1 in
    flight) and ``flips``: a dict of arrays t_leave, theta_leave, t_return,
    theta_return, xi_before, xi_after, v_leave, v_return, one entry per flip in
    time order (xi_before at departure, xi_after after the jerk, v_return the
    angular velocity after the jerk).  ``stats`` holds
    'flips', 'stop_reason' ('t_end', 'max_flips' or 'min_flight') and the
    integrator's work.
    """
    from ..integrate import ADAPTIVE, FIXED_STEP
    from ..trajectory import Trajectory

    t = as_float(t, "t")
    flat = np.ascontiguousarray(t, dtype=np.float64).reshape(-1)
    if not np.all(np.isfinite(flat)):
        raise ValueError("t must be finite")
    if flat.size and flat.min() < 0:
        raise ValueError("t: a flexible cord runs forward only (the jerk is irreversible): give times >= 0")
    eps = scene.eps
    method = scene.method
    exact = not any(e for e in scene.effects if e != "cord")
    if exact:
        if method not in ("auto", "exact"):
            exact = False
    if not exact:
        if method == "auto":
            method = "dop853"
        if method in FIXED_STEP:
            raise ValueError(f"method {method!r}: a flexible cord with effects needs the tension event located "
                             f"on dense output; {method!r} is fixed-step and has none: use dopri5 or dop853")
        if method not in ADAPTIVE or method == "gsl-rk8pd":
            raise ValueError(f"method {method!r} cannot locate the tension event: use dopri5 or dop853")

    order = np.argsort(flat, kind="stable")
    ts = flat[order]
    n = ts.size
    inv = np.empty(n, dtype=np.intp)
    inv[order] = np.arange(n)

    def back(a):
        return a[inv].reshape(t.shape)

    if exact:
        return _exact_run(scene, t, np.ascontiguousarray(ts), back)
    TH = np.full(n, np.nan)
    V = np.full(n, np.nan)
    X = np.full(n, np.nan)
    Y = np.full(n, np.nan)
    R = np.full(n, np.nan)
    logs = {k: [] for k in ("t_leave", "theta_leave", "t_return", "theta_return", "xi_before", "xi_after",
                                 "v_leave", "v_return")}
    stats = {"steps": 0, "rhs_evaluations": 0}
    t_end = float(ts[-1]) if n else 0.0
    tc, thc, vc, vr = 0.0, float(scene.theta0), float(scene.v0), 0.0
    i = 0  # next output index
    nflips = 0
    stop = "t_end"
    e = scene.restitution
    g = (0.0, -eps)

    def fill_circle(j_end, th, v):
        nonlocal i
        TH[i:j_end], V[i:j_end] = th, v
        X[i:j_end], Y[i:j_end], R[i:j_end] = np.sin(th), -np.cos(th), 1.0
        i = j_end

    while True:
        # ---- the circle phase from (tc, thc, vc), unless the bob is in flight (vr < 0) or slack
        tension = vc * vc + eps * math.cos(thc)
        leave = None
        if vr < 0.0 or tension <= 0.0:
            leave = (tc, thc, vc, vr < 0.0 or tension < 0.0)
        else:
            j_lim = n
            t_req = ts[i:] if i < n else np.array([tc])
            t_req = t_req[t_req >= tc]
            if t_req.size == 0:
                t_req = np.array([tc])
            th, v, ev, st = _integrate_segment(scene, method, tc, thc, vc, t_req)
            stats["steps"] += int(st[0])
            stats["rhs_evaluations"] += int(st[3])
            if ev is not None:
                leave = (ev[0], ev[1], ev[2], False)
                j_lim = int(np.searchsorted(ts, ev[0], side="right"))
            m = j_lim - i
            if m > 0:
                fill_circle(j_lim, th[:m], v[:m])
        if leave is None or leave[0] > t_end and not (n == 0):
            stop = "t_end"
            break
        if nflips >= scene.max_flips:
            stop = "max_flips"
            break
        # ---- the flight
        t1, th1, v1, general = leave
        p = (math.sin(th1), -math.cos(th1))
        u = (v1 * math.cos(th1) + vr * p[0], v1 * math.sin(th1) + vr * p[1])  # tangential + radial
        xi_b = float((v1 * v1 + vr * vr - 2 * eps * math.cos(th1)) / (3 * eps))
        tau = _flight_time(p, u, g, tangential=not general)
        if not math.isfinite(tau):  # tension zero but rising: stays on the circle
            tc, thc, vc, vr = t1, th1, v1, 0.0
            continue
        if general and vr < 0.0 and tau < max(scene.min_flight, 1e-9) / math.sqrt(eps):
            vr = 0.0  # a springy cord's bounces shorter than the threshold: absorbed, the cord stays taut
            tc, thc, vc = t1, th1, v1
            continue
        if tau < scene.min_flight / math.sqrt(eps):
            stop = "min_flight"
            break
        _, th2, v2, vr2 = _land(p, u, g, tau, th1 + 0.0, e)
        j = int(np.searchsorted(ts, t1 + tau, side="right"))
        if j > i:
            x, y, r, th, thd = _flight_positions(p, u, g, ts[i:j] - t1)
            # the angle continuous with the departure angle
            th = th + TWO_PI * np.round((th1 - th) / TWO_PI)
            TH[i:j], V[i:j], X[i:j], Y[i:j], R[i:j] = th, thd, x, y, r
            i = j
        nflips += 1
        logs["t_leave"].append(t1)
        logs["theta_leave"].append(th1)
        logs["t_return"].append(t1 + tau)
        logs["theta_return"].append(th2)
        logs["xi_before"].append(xi_b)
        logs["v_leave"].append(v1)
        logs["v_return"].append(v2)
        logs["xi_after"].append(float((v2 * v2 + vr2 * vr2 - 2 * eps * math.cos(th2)) / (3 * eps)))
        tc, thc, vc, vr = t1 + tau, th2, v2, vr2
        if tc > t_end:
            break
    if i < n:
        warnings.warn(f"flexible cord: the run stopped ({stop}) at flip {nflips}; "
                      f"{n - i} later output time(s) are NaN", RuntimeWarning, stacklevel=3)
    stats["flips"] = nflips
    stats["stop_reason"] = stop
    theta, v = back(TH), back(V)
    flips = {k: np.array(vals, dtype=float) for k, vals in logs.items()}
    return Trajectory(t, theta, v, energy(theta, v, eps), method, scene, stats,
                      x=back(X), y=back(Y), r=back(R), flips=flips)

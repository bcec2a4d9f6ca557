"""Random mpmath reference grids for the models: non-uniform gravity, the angle density,
the cycloidal pendulum, the flexible cord's flips and the integrators' events.

Every point is a set of exact doubles drawn log-uniformly (seeded) in every regime
of its class, plus the special places (next to the separatrix, next to the top,
next to the turning points, the uniform limit of the inverse-square field, heavy
damping).  Every reference is evaluated by mpmath at the exact double inputs by
two routes, and the row is kept only when they agree to 1e-25 (relative, or
absolute with the class's scale):

- gravity_orbit: the period as the integral over phi after sin(theta/2) =
  sqrt(w_m) sin(phi) (route A, 40 digits) and as the integral over theta itself
  (route B, tanh-sinh at the inverse-square-root endpoint, 60 digits); for the
  uniform field route B is the closed form 4 K(m) / sqrt(eps).  theta_max from
  the inversion of V(theta_max) = E in closed form (route A) and by findroot on
  V = E (route B).
- angle_cdf, angle_density: the time from 0 to theta over the period, by the
  same two integrals (uniform field: route A the closed form F(phi|m) / (2 K)).
- cycloid_period: 4 pi sqrt(R / eps) at 40 and at 80 digits; cycloid_geometry:
  the curves at the exact double nodes, at 40 and 80 digits.
- cycloid_motion (heavy damping): the closed form of the over-damped oscillator
  at 40 digits (exponentials of both roots) and at 80.
- cord flips: Garfinkel's closed forms (his eqs. 9, 13, 14; with the slips listed on
  the documentation's known-slips page corrected) at 40 and 80 digits; the circle time to departure
  as the integral over theta (route A) and as F (route B).
- find_events / numerical_period: turning-point times (2j+1) K / sqrt(eps) - u0
  and angle-crossing times from F, at 40 and 80 digits.

Each row also carries ``cond``: the condition number of the quantity, the sum
over the inputs x_i of |d y / d ln x_i| / max(|y|, scale), by a finite
difference (relative step 1e-25) at 50 digits.  A double-precision result can
be expected within a few eps plus about cond eps.  The tests
(tests/test_model_grids.py) state their tolerances as A + B cond (in eps).

Run:  python data/gen_model_grids.py   (about ten minutes on one core; writes
data/model_grids.csv.gz beside this script).
"""

from __future__ import annotations

import csv
import gzip
import math
import os
import sys

import mpmath as mp
import numpy as np

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "model_grids.csv.gz")
AGREE = mp.mpf("1e-25")
FD = mp.mpf("1e-25")
COLUMNS = ["cls", "quantity", "x0", "x1", "x2", "x3", "x4", "x5", "ref", "cond", "scale"]


def loguni(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


# ------------------------------------------------------------ fields (exact in mpmath)

KIND = {"uniform": 0, "inverse-square": 1, "linear": 2}


def f_mp(kind, par, eps, w):
    """V as a function of w = sin^2(theta/2) (kernel/models/pendula_gravity.f90)."""
    if kind == 1:
        d = par
        rho = mp.sqrt((d - 1) ** 2 + 4 * d * w)
        return eps * 4 * d * (d - 1) * w / (rho * (rho + d - 1))
    if kind == 2:
        return 2 * eps * (w - par * w * w)
    return 2 * eps * w


def q_mp(kind, par, eps, w, wm):
    """(f(wm) - f(w)) / (wm - w), in closed form."""
    if kind == 1:
        d = par
        rho = mp.sqrt((d - 1) ** 2 + 4 * d * w)
        rhom = mp.sqrt((d - 1) ** 2 + 4 * d * wm)
        return eps * (d - 1) ** 2 * 4 * d / (rho * rhom * (rho + rhom))
    if kind == 2:
        return 2 * eps * (1 - par * (w + wm))
    return 2 * eps


def energy_mp(kind, par, eps, theta0, v0):
    return v0 * v0 / 2 + f_mp(kind, par, eps, mp.sin(theta0 / 2) ** 2)


def wmax_mp(kind, par, eps, e):
    """w_m with f(w_m) = E (libration), in closed form."""
    if kind == 1:
        d = par
        c = e / (eps * (d - 1))
        # rho = (d - 1) / (1 - c), w = (rho - d + 1)(rho + d - 1) / (4 d), without the cancellation
        return (e / eps) * (2 - c) * (d - 1) / (4 * d * (1 - c) ** 2)
    if kind == 2:
        if par == 0:
            return e / (2 * eps)
        return (1 - mp.sqrt(1 - 2 * par * e / eps)) / (2 * par)
    return e / (2 * eps)


def wmax_root(kind, par, eps, e, guess):
    return mp.findroot(lambda w: f_mp(kind, par, eps, w) - e, guess)


# ------------------------------------------------------------ gravity_orbit

def splits(a, b, width):
    """Subdivision points of [a, b] that resolve a peak of the given width at b: b - width 4^j."""
    pts = [a]
    mid = (a + b) / 2
    extra = []
    x = width
    while b - x > mid:
        extra.append(b - x)
        x *= 4
    return pts + [mid] + sorted(extra) + [b]


def inv_sqrt(x):
    """1/sqrt(x), 0 at a node that rounds onto the inverse-square-root endpoint (its weight is nil)."""
    return 1 / mp.sqrt(x) if x > 0 else mp.mpf(0)


def gap_fn(kind, par, eps, e, f1, wm, thm):
    """E - V(theta) without cancellation: Q(w, w_m) sin((thm - |th|)/2) sin((thm + |th|)/2) in
    libration, (E - f(1)) + Q(w, 1) cos^2(th/2) in rotation."""
    if e < f1:
        def gap(th):
            w = mp.sin(th / 2) ** 2
            return max(q_mp(kind, par, eps, w, wm) * mp.sin((thm - abs(th)) / 2) * mp.sin((thm + abs(th)) / 2),
                       mp.mpf(0))
    else:
        de = e - f1

        def gap(th):
            w = mp.sin(th / 2) ** 2
            return de + q_mp(kind, par, eps, w, 1) * mp.cos(th / 2) ** 2
    return gap


def consts(kind, par, eps, theta0, v0, root=False):
    """E, f(1), w_m and theta_max (libration), and the distance from the separatrix
    f(1) - E = Q(w0, 1) cos^2(theta0/2) - v0^2/2 (formed so: f(1) - f(w0) cancels)."""
    e = energy_mp(kind, par, eps, theta0, v0)
    f1 = f_mp(kind, par, eps, 1)
    dist = q_mp(kind, par, eps, mp.sin(theta0 / 2) ** 2, 1) * mp.cos(theta0 / 2) ** 2 - v0 * v0 / 2
    wm = thm = None
    if dist > 0:
        wm = wmax_mp(kind, par, eps, e)
        if root:
            wm = wmax_root(kind, par, eps, e, wm)
        mc = dist / q_mp(kind, par, eps, wm, 1)
        if mc < 0.5:
            wm = 1 - mc
        thm = 2 * mp.atan2(mp.sqrt(wm), mp.sqrt(mc))
        e = f1 - dist
    else:
        e = f1 - dist
    return e, f1, wm, thm


def orbit_a(kind, par, eps, theta0, v0, with_period=True):
    """Route A: regime, E, theta_max (closed-form inversion), period (libration: the integral over
    phi; rotation: over theta)."""
    e, f1, wm, thm = consts(kind, par, eps, theta0, v0)
    out = {"energy": e}
    if e < f1:
        out["regime"] = mp.mpf(0)
        out["theta_max"] = thm
        if with_period:
            mc = mp.cos(thm / 2) ** 2
            g = lambda ph: mp.sqrt(2 / q_mp(kind, par, eps, wm * mp.sin(ph) ** 2, wm)) / \
                mp.sqrt(mp.cos(ph) ** 2 + mc * mp.sin(ph) ** 2)
            out["period"] = 4 * mp.quad(g, splits(0, mp.pi / 2, mp.cos(thm / 2)))
    elif e > f1:
        out["regime"] = mp.mpf(2)
        out["theta_max"] = mp.inf
        if with_period:
            gap = gap_fn(kind, par, eps, e, f1, wm, thm)
            g = lambda th: inv_sqrt(2 * gap(th))
            out["period"] = 2 * mp.quad(g, splits(0, mp.pi, mp.sqrt((e - f1) / e)))
    else:
        out["regime"] = mp.mpf(1)
        out["theta_max"] = mp.pi
        out["period"] = mp.inf
    return out


def orbit_b(kind, par, eps, theta0, v0):
    """Route B: theta_max by findroot, the period over theta (libration) or theta/2 (rotation);
    uniform field: the closed forms 4 K / sqrt(eps) and 2 K / (k sqrt(eps))."""
    e, f1, wm, thm = consts(kind, par, eps, theta0, v0, root=True)
    out = {"energy": e}
    gap = gap_fn(kind, par, eps, e, f1, wm, thm)
    if e < f1:
        out["regime"] = mp.mpf(0)
        out["theta_max"] = thm
        if kind == 0:
            out["period"] = 4 * mp.ellipk(wm) / mp.sqrt(eps)
        else:
            g = lambda th: inv_sqrt(2 * gap(th))
            out["period"] = 4 * mp.quad(g, splits(0, thm, mp.pi - thm))
    elif e > f1:
        out["regime"] = mp.mpf(2)
        out["theta_max"] = mp.inf
        m = f1 / e
        if kind == 0:
            out["period"] = 2 * 2 * mp.ellipk(m) / mp.sqrt(2 * e)
        else:
            g = lambda ph: 2 * inv_sqrt(2 * gap(2 * ph))
            out["period"] = 2 * mp.quad(g, splits(0, mp.pi / 2, mp.sqrt((e - f1) / e) / 2))
    else:
        out["regime"] = mp.mpf(1)
        out["theta_max"] = mp.pi
        out["period"] = mp.inf
    return out


def gravity_points(rng, kind, n):
    """(region, eps, par, theta0, v0) log-uniform in every region."""
    pts = []
    for i in range(n):
        eps = loguni(rng, 1e-2, 1e2)
        if kind == 1:
            par = 1.0 + loguni(rng, 3e-2, 1e4) if i % 10 else loguni(rng, 1e16, 1e300)
        elif kind == 2:
            par = float(rng.choice([-1, 1])) * loguni(rng, 1e-3, 0.49)
            if i % 7 == 0:
                par = 0.5 - loguni(rng, 1e-3, 0.1)
        else:
            par = 0.0
        region = ["libration", "rotation", "near-separatrix", "near-top"][i % 4]
        th0 = float(rng.uniform(-math.pi, math.pi))
        # the separatrix energy f(1) and the state's distance from it
        f1 = float(f_mp(kind, mp.mpf(par), mp.mpf(eps), 1))
        w0 = math.sin(th0 / 2) ** 2
        v0 = 0.0
        if region == "libration":
            e = f1 * rng.uniform(0.05, 0.95)
            th0 = float(rng.uniform(-1, 1)) * 0.3
            v2 = 2 * (e - float(f_mp(kind, mp.mpf(par), mp.mpf(eps), math.sin(th0 / 2) ** 2)))
            v0 = math.copysign(math.sqrt(max(v2, 0.0)), rng.uniform(-1, 1))
        elif region == "rotation":
            e = f1 * loguni(rng, 1.05, 1e4)
            v2 = 2 * (e - float(f_mp(kind, mp.mpf(par), mp.mpf(eps), w0)))
            v0 = math.copysign(math.sqrt(max(v2, 0.0)), rng.uniform(-1, 1))
        elif region == "near-separatrix":
            th0 = float(rng.uniform(-1, 1)) * 0.5
            w0 = math.sin(th0 / 2) ** 2
            e = f1 * (1 + float(rng.choice([-1, 1])) * loguni(rng, 1e-15, 1e-2))
            v2 = 2 * (e - float(f_mp(kind, mp.mpf(par), mp.mpf(eps), w0)))
            v0 = math.copysign(math.sqrt(max(v2, 0.0)), rng.uniform(-1, 1))
        else:  # near the top: theta0 next to pi, small v0 (either regime)
            th0 = math.copysign(math.pi - loguni(rng, 1e-15, 1e-2), rng.uniform(-1, 1))
            v0 = math.copysign(loguni(rng, 1e-12, 1e-1), rng.uniform(-1, 1)) if i % 3 else 0.0
        pts.append((region, eps, par, th0, v0))
    return pts


def cond_of(fun, args, which, quantities, scale):
    """sum_i |dy/d ln x_i| / max(|y|, scale) by a forward difference at step FD."""
    base = fun(*args)
    cond = {q: mp.mpf(0) for q in quantities}
    for i in which:
        if args[i] == 0:
            continue
        a = list(args)
        a[i] = a[i] * (1 + FD)
        b = fun(*a)
        for q in quantities:
            if mp.isinf(base[q]) or base[q] != base[q]:
                continue
            cond[q] += abs((b[q] - base[q]) / FD) / max(abs(base[q]), scale.get(q, 0))
    return cond


def agree(a, b, scale=0):
    if mp.isinf(a) or mp.isinf(b):
        return a == b
    return abs(a - b) <= AGREE * max(abs(a), abs(b), scale)


def gen_gravity(rng, rows, n_per_kind):
    for name, kind in KIND.items():
        for region, eps, par, th0, v0 in gravity_points(rng, kind, n_per_kind):
            args = [mp.mpf(par), mp.mpf(eps), mp.mpf(th0), mp.mpf(v0)]
            with mp.workdps(50):
                a = orbit_a(kind, *args)
            with mp.workdps(70):
                b = orbit_b(kind, *args)
            if a["regime"] != b["regime"]:
                print("regime disagreement", name, eps, par, th0, v0, file=sys.stderr)
                continue
            with mp.workdps(60):
                qs = [q for q in ("energy", "theta_max", "period") if not mp.isinf(a[q])]
                cond = cond_of(lambda *x: orbit_a(kind, *x), args, [0, 1, 2, 3] if kind else [1, 2, 3], qs, {})
            cls = f"gravity_orbit/{name}/{region}"
            rows.append([cls, "regime", eps, par, th0, v0, "", "", int(a["regime"]), 0, 0])
            for q in ("energy", "theta_max", "period"):
                if not agree(a[q], b[q]):
                    print("disagreement", cls, q, eps, par, th0, v0, mp.nstr(a[q], 20), mp.nstr(b[q], 20),
                          file=sys.stderr)
                    continue
                rows.append([cls, q, eps, par, th0, v0, "", "", mp.nstr(a[q], 25), mp.nstr(cond.get(q, 0), 5), 0])


# ------------------------------------------------------------ the angle density

def time_a(kind, par, eps, theta0, v0, theta):
    """Route A: (regime, t(theta), period or turn, gap); t by the integral over phi (libration) or
    theta (rotation), the uniform field in closed form through F and K."""
    e, f1, wm, thm = consts(kind, par, eps, theta0, v0)
    gap = gap_fn(kind, par, eps, e, f1, wm, thm)
    if e < f1:
        a = min(abs(theta), thm)
        x = mp.sin(a / 2) / mp.sqrt(wm)
        phi = mp.asin(x) if x < 1 else mp.pi / 2
        if kind == 0:
            t = mp.ellipf(phi, wm) / mp.sqrt(eps)
            T = 4 * mp.ellipk(wm) / mp.sqrt(eps)
        else:
            mc = mp.cos(thm / 2) ** 2
            g = lambda ph: mp.sqrt(2 / q_mp(kind, par, eps, wm * mp.sin(ph) ** 2, wm)) / \
                mp.sqrt(mp.cos(ph) ** 2 + mc * mp.sin(ph) ** 2)
            t = mp.quad(g, splits(0, phi, mp.pi / 2 - phi + mp.cos(thm / 2)))
            T = 4 * mp.quad(g, splits(0, mp.pi / 2, mp.cos(thm / 2)))
        return 0, mp.sign(theta) * t, T, gap
    m = f1 / e
    if kind == 0:
        t = 2 * mp.ellipf(theta / 2, m) / mp.sqrt(2 * e)
        T = 4 * mp.ellipk(m) / mp.sqrt(2 * e)
    else:
        g = lambda th: inv_sqrt(2 * gap(th))
        d = mp.sqrt((e - f1) / e)
        t = mp.sign(theta) * mp.quad(g, splits(0, abs(theta), mp.pi - abs(theta) + d))
        T = 2 * mp.quad(g, splits(0, mp.pi, d))
    return 2, t, T, gap


def time_b(kind, par, eps, theta0, v0, theta):
    """Route B: t(theta) over theta itself (libration; tanh-sinh at the turning point) or over
    theta/2 (rotation), with theta_max by findroot."""
    e, f1, wm, thm = consts(kind, par, eps, theta0, v0, root=True)
    gap = gap_fn(kind, par, eps, e, f1, wm, thm)
    if e < f1:
        g = lambda th: inv_sqrt(2 * gap(th))
        a = min(abs(theta), thm)
        t = mp.quad(g, splits(0, a, thm - a + (mp.pi - thm)))
        T = 4 * mp.quad(g, splits(0, thm, mp.pi - thm))
        return 0, mp.sign(theta) * t, T, gap
    g = lambda ph: 2 * inv_sqrt(2 * gap(2 * ph))
    d = mp.sqrt((e - f1) / e) / 2
    t = mp.sign(theta) * mp.quad(g, splits(0, abs(theta) / 2, mp.pi / 2 - abs(theta) / 2 + d))
    T = 2 * mp.quad(g, splits(0, mp.pi / 2, d))
    return 2, t, T, gap


def density_cdf(timef, kind, par, eps, theta0, v0, theta):
    reg, t, T, gap = timef(kind, par, eps, theta0, v0, theta)
    vv = 2 * gap(theta)
    if reg == 0:
        if vv <= 0:
            return {"cdf": mp.mpf(1) if theta > 0 else mp.mpf(0), "density": mp.mpf(0)}
        return {"cdf": mp.mpf(1) / 2 + 2 * t / T, "density": 2 / (T * mp.sqrt(vv))}
    return {"cdf": mp.mpf(1) / 2 + t / T, "density": 1 / (T * mp.sqrt(vv))}


def gen_density(rng, rows, n_per_kind):
    for name, kind in KIND.items():
        pts = gravity_points(rng, kind, n_per_kind)
        for j, (region, eps, par, th0, v0) in enumerate(pts):
            args = [mp.mpf(par), mp.mpf(eps), mp.mpf(th0), mp.mpf(v0)]
            with mp.workdps(40):
                o = orbit_a(kind, *args, with_period=False)
            if o["regime"] == 1:
                continue
            if o["regime"] == 0:
                thm = float(o["theta_max"])
                if rng.random() < 0.5:
                    sub = "libration-turning"
                    theta = math.copysign(thm * (1 - loguni(rng, 1e-14, 1e-3)), rng.uniform(-1, 1))
                else:
                    sub = "libration"
                    theta = float(rng.uniform(-0.97, 0.97)) * thm
                if not abs(theta) < thm:
                    continue
            else:
                sub = "rotation"
                theta = float(rng.uniform(-math.pi, math.pi))
            if region in ("near-separatrix", "near-top"):
                sub += "-" + region
            targs = args + [mp.mpf(theta)]
            with mp.workdps(50):
                a = density_cdf(time_a, kind, *targs)
            with mp.workdps(70):
                b = density_cdf(time_b, kind, *targs)
            with mp.workdps(60):
                cond = cond_of(lambda *x: density_cdf(time_a, kind, *x), targs,
                               [0, 1, 2, 3, 4] if kind else [1, 2, 3, 4], ["cdf", "density"], {"cdf": 1})
            for q, sc in (("cdf", 1), ("density", 0)):
                cls = f"angle_{q}/{name}/{sub}"
                if not agree(a[q], b[q], sc):
                    print("disagreement", cls, eps, par, th0, v0, theta, mp.nstr(a[q], 20), mp.nstr(b[q], 20),
                          file=sys.stderr)
                    continue
                rows.append([cls, q, eps, par, th0, v0, theta, "", mp.nstr(a[q], 25), mp.nstr(cond[q], 5), sc])


# ------------------------------------------------------------ the cycloid

def gen_cycloid(rng, rows, n):
    for i in range(n):
        eps, R = loguni(rng, 1e-3, 1e3), loguni(rng, 1e-3, 1e3)
        refs = []
        for dps in (40, 80):
            with mp.workdps(dps):
                refs.append(4 * mp.pi * mp.sqrt(mp.mpf(R) / mp.mpf(eps)))
        assert agree(*refs)
        rows.append(["cycloid_period", "period", eps, R, "", "", "", "", mp.nstr(refs[0], 25), 1.0, 0])
    # the geometry at the exact double nodes (numpy's linspace; the test checks they are the same doubles)
    for i in range(n // 4):
        R = loguni(rng, 1e-3, 1e3)
        nn = int(rng.integers(2, 2000))
        phi = np.linspace(-math.pi, math.pi, nn)
        ph = np.linspace(0.0, math.pi, nn)
        a = np.linspace(-math.pi / 2, math.pi / 2, nn)
        for j in rng.choice(nn, size=min(nn, 6), replace=False):
            j = int(j)
            for dps, store in ((40, True), (80, False)):
                with mp.workdps(dps):
                    Rm, p, q, c = mp.mpf(R), mp.mpf(float(phi[j])), mp.mpf(float(ph[j])), mp.mpf(float(a[j]))
                    vals = {"path_x": Rm * (p + mp.sin(p)), "path_y": Rm * (1 - mp.cos(p)),
                            "cheek_x": Rm * (q - mp.sin(q)), "cheek_y": Rm * (3 + mp.cos(q)),
                            "circle_x": 4 * Rm * mp.sin(c), "circle_y": 4 * Rm - 4 * Rm * mp.cos(c)}
                    # condition: the node's rounding (relative eps of the angle) times the slope, in units of R
                    cnd = {"path_x": abs(p * (1 + mp.cos(p))), "path_y": abs(p * mp.sin(p)),
                           "cheek_x": abs(q * (1 - mp.cos(q))), "cheek_y": abs(q * mp.sin(q)),
                           "circle_x": abs(4 * c * mp.cos(c)), "circle_y": abs(4 * c * mp.sin(c))}
                if store:
                    first = vals
                else:
                    for k in vals:
                        assert agree(first[k], vals[k], R)
            for k in first:
                rows.append(["cycloid_geometry", k, R, nn, j, float(phi[j]), "", "", mp.nstr(first[k], 25),
                             mp.nstr(cnd[k] + 1, 5), R])


def overdamped_mp(eps, R, beta, theta0, v0, t):
    """theta(t) of the conservative-free over-damped cycloid (no torque, no drive), closed form."""
    w2 = eps / (4 * R)
    s0, sd0 = 4 * R * mp.sin(theta0), 4 * R * mp.cos(theta0) * v0
    h = beta / 2
    mu = mp.sqrt(h * h - w2)
    r1, r2 = -w2 / (h + mu), -h - mu       # -h + mu without its cancellation (h up to 1e250)
    A = (sd0 - r2 * s0) / (r1 - r2)
    B = s0 - A
    s = A * mp.exp(r1 * t) + B * mp.exp(r2 * t)
    return {"theta": mp.asin(s / (4 * R))}


def gen_cycloid_damped(rng, rows, n):
    for i in range(n):
        eps, R = loguni(rng, 1e-2, 1e2), loguni(rng, 1e-2, 1e1)
        w = math.sqrt(eps / (4 * R))
        beta = w * loguni(rng, 3.0, 1e12) if i % 5 else w * loguni(rng, 1e150, 1e250)
        th0 = float(rng.uniform(-1.5, 1.5))
        v0 = 0.0 if i % 2 else float(rng.uniform(-1, 1)) * 1e-3 * w
        # times where the slow mode has decayed between 1e-3 and 1 (the fast one long gone)
        slow = w * w / beta
        t = loguni(rng, 1e-2, 5.0) / slow
        args = [mp.mpf(x) for x in (eps, R, beta, th0, v0, t)]
        with mp.workdps(40):
            a = overdamped_mp(*args)
        with mp.workdps(80):
            b = overdamped_mp(*args)
        if not agree(a["theta"], b["theta"]):
            continue
        with mp.workdps(50):
            cond = cond_of(overdamped_mp, args, [0, 1, 2, 3, 4, 5], ["theta"], {})
        rows.append(["cycloid_motion/over-damped", "theta", eps, R, beta, th0, v0, t, mp.nstr(a["theta"], 25),
                     mp.nstr(cond["theta"], 5), 0])


# ------------------------------------------------------------ the flexible cord (Garfinkel)

def garfinkel(eps, theta0, v0, route):
    """The first flip of a cord started on the circle at (theta0 in (-pi/2, pi/2), v0 > 0):
    xi = (v^2 - 2 eps cos theta)/(3 eps); departure cos theta1 = -xi, theta1' = sqrt(eps xi) (eq. 9);
    flight omega tau = 4 sqrt(xi (1 - xi^2)), theta2 = 2 pi - 3 theta1, theta2' = theta1'
    (-3 + 12 xi^2 - 8 xi^4) (eq. 13); xi' = f(xi) (eq. 14).  The time on the circle from theta0 to
    theta1 by the integral over theta (route A) or through F (route B)."""
    xi = (v0 * v0 - 2 * eps * mp.cos(theta0)) / (3 * eps)
    th1 = mp.acos(-xi)
    out = {"xi_after": xi - mp.mpf(64) / 3 * (xi * (1 - xi * xi)) ** 3,
           "theta_leave": th1, "theta_return": 2 * mp.pi - 3 * th1,
           "v_leave": mp.sqrt(eps * xi), "v_return": mp.sqrt(eps * xi) * (-3 + 12 * xi ** 2 - 8 * xi ** 4),
           "flight": 4 * mp.sqrt(xi * (1 - xi * xi)) / mp.sqrt(eps)}
    e = v0 * v0 / 2 + 2 * eps * mp.sin(theta0 / 2) ** 2
    if route == "A":
        g = lambda th: 1 / mp.sqrt(2 * (e - 2 * eps * mp.sin(th / 2) ** 2))
        out["t_leave"] = mp.quad(g, [theta0, th1])
    else:
        k2 = e / (2 * eps)
        if k2 < 1:
            F = lambda th: mp.ellipf(mp.asin(mp.sin(th / 2) / mp.sqrt(k2)), k2)
            out["t_leave"] = (F(th1) - F(theta0)) / mp.sqrt(eps)
        else:
            F = lambda th: mp.ellipf(th / 2, 1 / k2)
            out["t_leave"] = (F(th1) - F(theta0)) / (mp.sqrt(k2) * mp.sqrt(eps))
    return out


def gen_cord(rng, rows, n):
    qs = ["xi_after", "theta_leave", "theta_return", "v_leave", "v_return", "flight", "t_leave"]
    for i in range(n):
        eps = loguni(rng, 1e-2, 1e2)
        xi = float(rng.uniform(0.02, 0.98)) if i % 4 else float(rng.choice([loguni(rng, 1e-6, 1e-2),
                                                                            1 - loguni(rng, 1e-6, 1e-2)]))
        th0 = float(rng.uniform(-1.2, 1.2))
        v2 = 3 * eps * xi + 2 * eps * math.cos(th0)
        v0 = math.sqrt(v2)
        args = [mp.mpf(x) for x in (eps, th0, v0)]
        with mp.workdps(40):
            a = garfinkel(*args, "A")
        with mp.workdps(80):
            b = garfinkel(*args, "B")
        with mp.workdps(50):
            cond = cond_of(lambda *x: garfinkel(*x, "B"), args, [0, 1, 2], qs, {})
        for q in qs:
            if not agree(a[q], b[q]):
                print("disagreement cord", q, eps, th0, v0, file=sys.stderr)
                continue
            rows.append(["cord_flip", q, eps, th0, v0, "", "", "", mp.nstr(a[q], 25), mp.nstr(cond[q], 5), 0])


# ------------------------------------------------------------ events of the integrators

def events_mp(eps, theta0, v0, kind, level, j):
    """The j-th (0-based) event time after t = 0 of the conservative rigid pendulum (libration):
    'turning' maxima (v falling through 0): u = (4 i + 1) K - u0 ... in the phase u = sqrt(eps) t + u0;
    'theta' crossings of theta = level (rising and falling)."""
    k2 = v0 * v0 / (4 * eps) + mp.sin(theta0 / 2) ** 2
    K = mp.ellipk(k2)
    # u0: sn(u0) = sin(theta0/2)/k, cn(u0) = v0 / (2 k sqrt(eps))
    k = mp.sqrt(k2)
    ph = mp.atan2(mp.sin(theta0 / 2) / k, v0 / (2 * k * mp.sqrt(eps)))
    u0 = mp.ellipf(ph, k2)   # phi in (-pi, pi]: F continues through 2K at phi = pi
    period_u = 4 * K
    if kind == "turning":
        # maxima at u = K + 4 K i
        first = K - u0
        while first <= 0:
            first += period_u
        while first - period_u > 0:
            first -= period_u
        return {"t": (first + j * period_u) / mp.sqrt(eps), "T": 4 * K / mp.sqrt(eps)}
    # theta = level: sn(u) = sin(level/2)/k at u = F(a) (rising) and 2K - F(a) (falling)
    a = mp.asin(mp.sin(level / 2) / k)
    us = []
    for base in (mp.ellipf(a, k2), 2 * K - mp.ellipf(a, k2)):
        u = base - u0
        while u <= 0:
            u += period_u
        while u - period_u > 0:
            u -= period_u
        us.append(u)
    us.sort()
    u = us[j % 2] + (j // 2) * period_u
    return {"t": u / mp.sqrt(eps), "T": 4 * K / mp.sqrt(eps)}


def gen_events(rng, rows, n):
    for i in range(n):
        eps = loguni(rng, 1e-1, 1e1)
        amp = float(rng.uniform(0.1, 3.0)) if i % 4 else math.pi - loguni(rng, 1e-6, 1e-2)
        th0 = float(rng.uniform(-1, 1)) * amp
        k2 = math.sin(amp / 2) ** 2
        v0 = math.copysign(2 * math.sqrt(eps * max(k2 - math.sin(th0 / 2) ** 2, 0.0)), rng.uniform(-1, 1))
        kind = "turning" if i % 2 else "theta"
        level = float(rng.uniform(-0.9, 0.9)) * amp if kind == "theta" else 0.0
        j = int(rng.integers(0, 12))
        args = [mp.mpf(x) for x in (eps, th0, v0)]
        refs = []
        for dps in (40, 80):
            with mp.workdps(dps):
                refs.append(events_mp(*args, kind, mp.mpf(level), j))
        assert agree(refs[0]["t"], refs[1]["t"])
        # the event time's sensitivity to the state (an integrator at rtol perturbs it by about rtol):
        # large next to the separatrix, where the period depends on the energy like log(1/mc)
        with mp.workdps(50):
            cond = cond_of(lambda *x: events_mp(*x, kind, mp.mpf(level), j), args, [0, 1, 2], ["t", "T"], {})
        rows.append([f"find_events/{kind}", "t", eps, th0, v0, level, j, float(refs[0]["T"]),
                     mp.nstr(refs[0]["t"], 25), mp.nstr(cond["t"], 5), 0])
        if i % 4 == 1:
            rows.append(["numerical_period", "period", eps, th0, v0, "", "", "", mp.nstr(refs[0]["T"], 25),
                         mp.nstr(cond["T"], 5), 0])


PREFIX = {"gravity": ("gravity_orbit",), "density": ("angle_",), "cycloid": ("cycloid_period", "cycloid_geometry"),
          "damped": ("cycloid_motion",), "cord": ("cord_flip",), "events": ("find_events", "numerical_period")}


def main():
    """python data/gen_model_grids.py [STEP ...]: all steps, or only the named ones (their rows replaced
    in the stored file).  Each step draws from its own seeded generator, so a step run alone
    reproduces its rows of a full run."""
    gens = {"gravity": lambda r, rows: gen_gravity(r, rows, 36), "density": lambda r, rows: gen_density(r, rows, 48),
            "cycloid": lambda r, rows: gen_cycloid(r, rows, 60), "damped": lambda r, rows: gen_cycloid_damped(r, rows, 60),
            "cord": lambda r, rows: gen_cord(r, rows, 80), "events": lambda r, rows: gen_events(r, rows, 48)}
    only = sys.argv[1:] or list(gens)
    rows = []
    if sys.argv[1:] and os.path.exists(OUT):
        drop = tuple(p for name in only for p in PREFIX[name])
        with gzip.open(OUT, "rt", newline="") as fh:
            rows = [r for r in list(csv.reader(fh))[1:] if not r[0].startswith(drop)]
    for index, name in enumerate(gens):
        if name not in only:
            continue
        rng = np.random.default_rng([20261201, index])
        n0 = len(rows)
        gens[name](rng, rows)
        print(f"{name}: {len(rows) - n0} rows", file=sys.stderr)
    with gzip.open(OUT, "wt", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(COLUMNS)
        for r in rows:
            w.writerow([repr(x) if isinstance(x, float) else x for x in r])
    print(f"wrote {len(rows)} rows to {OUT}", file=sys.stderr)


if __name__ == "__main__":
    main()

"""mpmath references for the kernel's hard cases, and a fresh random hunt around each.

Five classes of inputs where pendula once lost digits, each with its reproducer (the exact
double inputs that showed it) and a set of fresh random points of its own (seeded):

- ``tiny``: |v0|, theta0 and eps down to the smallest normal and subnormal numbers, where
  k^2 = sin^2(theta0/2) + v0^2 / (4 eps) and sin^2(theta0/2) underflow: every public function
  of an orbit (orbit, exact_motion, energy, gravity_orbit in the three fields, angle_density,
  angle_cdf).  Error relative to max(|ref|, 2^-1022): one unit is an ulp, subnormals included.
- ``einc_above_one``: E(phi|m) and F(phi|m) next to +-pi/2 (and odd multiples) for m just above
  1, m - 1 from 1e-16 down to 1e-300 (where m itself rounds to 1).
- ``inverse_square_near_one``: gravity_orbit in the inverse-square field with the distance
  d -> 1 (d - 1 from 0.3 down to 1e-4): theta_max, period, energy.
- ``separatrix_long_time``: exact_motion just above the separatrix (k^2 - 1 from 1e-15 to
  1e-3, any theta0) at times up to 1e3 turns; error in units of the velocity scale
  2 k sqrt(eps) (v), and of max(1, |theta|) (theta).
- ``ellip_huge_m_edge``: F(phi|m) and E(phi|m) for m from 1e270 to 1.7e308 with m sin^2 phi in
  (1/2, 1], next to the edge of the real domain (relative to |ref|).
- ``ellip_tiny_phi_huge_m``: F and E(phi|m) for |m| from 1e200 to 1.7e308 (both signs) and phi
  with |m| phi^2 from 1e-6 to 1 (m > 0) or to 1e6 (m < 0) (relative to |ref|).
- ``jacobi_m_far_below_zero``: sn, cn, dn(u|m) for m from -2 to -1e300 and u from 1e3 to 3e13
  quarter periods (sn and cn relative to max(1, |ref|), dn relative to |ref| >= 1).
- ``periodic_exact``: every periodic input reduced exactly: angle_density and angle_cdf of a
  rotation at |theta| up to 2^52, energy at |theta| up to 2^52, gravity_orbit at |theta0| up to
  2^52 (three fields), ellipf and ellipeinc at |phi| up to 2^52.

References by mpmath at the exact double inputs, at two precisions (P and P + 40 digits, P
above the digits the parameter needs); a row is kept only when the two agree to 1e-30
relative.  The angle density and the non-uniform fields use the integrals of
data/gen_model_grids.py (route A).

Run:  python data/gen_hard_cases.py [CLASS ...]   (a few minutes on one core; writes
data/hard_cases.csv.gz beside this script, read by the tests through tests/conftest.py's
hard_cases(); with class names, e.g. ``huge-m-edge tiny-phi jacobi-far``, only those are
drawn again and replace their rows, the others kept).
"""

from __future__ import annotations

import csv
import gzip
import json
import math
import os
import sys

import mpmath as mp
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gen_model_grids import orbit_a, density_cdf, time_a, energy_mp  # noqa: E402

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "hard_cases.csv.gz")
COLUMNS = ["set", "cls", "func", "args", "quantity", "ref", "floor", "cond"]
SEED = 20261203
TINY = 2.0 ** -1022
KINDS = {"uniform": 0, "inverse-square": 1, "linear": 2}


def loguni(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


def twice(f, dps):
    """f() at dps and dps + 40 digits: the first, or None when they disagree (beyond 1e-30)."""
    try:
        with mp.workdps(dps):
            a = f()
        with mp.workdps(dps + 40):
            b = f()
    except (ZeroDivisionError, ValueError) as e:
        print("no reference:", e, file=sys.stderr)
        return None
    for q in a:
        x, y = a[q], b[q]
        if mp.isinf(x) or mp.isinf(y):
            if x != y:
                return None
            continue
        if abs(x - y) > mp.mpf("1e-30") * max(abs(y), mp.mpf(10) ** -330):
            print("disagreement", q, mp.nstr(x, 25), mp.nstr(y, 25), file=sys.stderr)
            return None
    return a


# ------------------------------------------------------------ the exact pendulum in mpmath

def exact_mp(theta0, v0, eps, t=None):
    """k, theta_max, period, and theta(t), v(t) of theta'' + eps sin(theta) = 0."""
    th0, w0, e = mp.mpf(theta0), mp.mpf(v0), mp.mpf(eps)
    n = mp.nint(th0 / (2 * mp.pi))
    r = th0 - 2 * mp.pi * n
    se = mp.sqrt(e)
    s0, c0 = mp.sin(r / 2), mp.cos(r / 2)
    w = w0 / (2 * se)
    k2 = s0 ** 2 + w ** 2
    k = mp.sqrt(k2)
    out = {"k": k}
    if k2 < 1:
        m = k2
        out["theta_max"] = 2 * mp.asin(k)
        out["period"] = 4 * mp.ellipk(m) / se
        if t is not None:
            phi0 = mp.atan2(s0 / k, w / k)
            u = mp.ellipf(phi0, m) + se * mp.mpf(t)
            sn, cn = mp.ellipfun("sn", u, m), mp.ellipfun("cn", u, m)
            dn = mp.ellipfun("dn", u, m)
            out["theta"] = 2 * mp.pi * n + 2 * mp.atan2(k * sn, dn)
            out["v"] = 2 * k * se * cn
    else:
        m = 1 / k2
        out["period"] = 2 * mp.ellipk(m) / (k * se)
        if t is not None:
            d = mp.sign(w0)
            K = mp.ellipk(m)
            u = mp.ellipf(r / 2, m) + d * k * se * mp.mpf(t)
            j = mp.nint(u / (2 * K))
            ur = u - 2 * K * j
            am = j * mp.pi + mp.atan2(mp.ellipfun("sn", ur, m), mp.ellipfun("cn", ur, m))
            out["theta"] = 2 * mp.pi * n + 2 * am
            out["v"] = d * 2 * k * se * mp.ellipfun("dn", ur, m)
    return out


def vscale(theta0, v0, eps):
    k2 = math.sin(theta0 / 2) ** 2 + (v0 / (2 * math.sqrt(eps))) ** 2
    return max(1.0, 2 * math.sqrt(k2) * math.sqrt(eps))


# ------------------------------------------------------------ rows

class Rows:
    def __init__(self):
        self.rows = []

    def add(self, set_, cls, func, args, refs, floors, conds=None):
        for q, ref in refs.items():
            self.rows.append([set_, cls, func, json.dumps([repr(a) if isinstance(a, float) else a
                                                           for a in args]),
                              q, mp.nstr(ref, 30), repr(float(floors.get(q, 1.0))),
                              mp.nstr((conds or {}).get(q, 0), 5)])


def add_exact(rows, set_, cls, theta0, v0, eps, t, floor):
    ref = twice(lambda: exact_mp(theta0, v0, eps, t), dps_for(theta0, v0, eps))
    if ref is None:
        return
    fl = floor if floor is not None else {"theta": 1.0, "v": vscale(theta0, v0, eps)}
    rows.add(set_, cls, "exact_motion", [theta0, v0, eps, t], {q: ref[q] for q in ("theta", "v")},
             fl if isinstance(fl, dict) else {"theta": fl, "v": fl})


def add_orbit(rows, set_, cls, theta0, v0, eps, floor):
    ref = twice(lambda: exact_mp(theta0, v0, eps), dps_for(theta0, v0, eps))
    if ref is None:
        return
    qs = ("k", "theta_max", "period") if "theta_max" in ref else ("k", "period")
    rows.add(set_, cls, "orbit", [theta0, v0, eps], {q: ref[q] for q in qs}, {q: floor for q in qs})


def dps_for(theta0, v0, eps):
    """digits enough for the distance from the separatrix and for 2 pi n at theta0."""
    return 60 + int(max(0, math.log10(abs(theta0) + 1)))


def add_gravity(rows, set_, cls, kind, par, eps, theta0, v0, floor, dps=40):
    def f():
        args = (KINDS[kind], mp.mpf(par), mp.mpf(eps), mp.mpf(theta0), mp.mpf(v0))
        o = orbit_a(*args)
        # the energy as it stands (orbit_a's f(1) - distance cancels for a tiny one), and a tiny
        # amplitude without the cancellation of the linear field's inversion
        o["energy"] = energy_mp(*args)
        if o["regime"] == 0 and o["theta_max"] < 1e-100:
            o["theta_max"] = theta_max_tiny_mp(kind, par, eps, theta0, v0)
        return {q: o[q] for q in ("energy", "theta_max", "period")}
    ref = twice(f, dps)
    if ref is None:
        return
    ref = {q: x for q, x in ref.items() if not mp.isinf(x)}
    rows.add(set_, cls, "gravity_orbit", [kind, par, eps, theta0, v0], ref, {q: floor for q in ref})


def add_density(rows, set_, cls, kind, par, eps, theta0, v0, theta, floor_density, dps=40):
    def f():
        return density_cdf(time_a, KINDS[kind], mp.mpf(par), mp.mpf(eps), mp.mpf(theta0), mp.mpf(v0),
                           mp.mpf(theta))
    ref = twice(f, dps)
    if ref is None:
        return
    rows.add(set_, cls, "angle_density", [kind, par, eps, theta0, v0, theta], {"density": ref["density"]},
             {"density": floor_density})
    rows.add(set_, cls, "angle_cdf", [kind, par, eps, theta0, v0, theta], {"cdf": ref["cdf"]}, {"cdf": 1.0})


def theta_max_tiny_mp(kind, par, eps, theta0, v0):
    """theta_max of a libration from f(w_m) = E, w_m in a form without cancellation for any E
    (gen_model_grids' 1 - sqrt(1 - 2 kappa E / eps) of the linear field is 0 for a tiny E)."""
    args = (KINDS[kind], mp.mpf(par), mp.mpf(eps), mp.mpf(theta0), mp.mpf(v0))
    e = energy_mp(*args) / mp.mpf(eps)
    if kind == "linear":
        wm = e / (1 + mp.sqrt(1 - 2 * mp.mpf(par) * e))
    elif kind == "inverse-square":
        d = mp.mpf(par)
        c = e / (d - 1)
        wm = e * (2 - c) * (d - 1) / (4 * d * (1 - c) ** 2)
    else:
        wm = e / 2
    return 2 * mp.asin(mp.sqrt(wm))


def add_density_tiny(rows, set_, cls, kind, par, eps, theta0, v0, theta):
    """An amplitude below 1e-150: every field is harmonic there to O(theta_max^2) < 1e-290 relative,
    and the density is the arcsine law 1 / (pi sqrt(theta_max^2 - theta^2)), the CDF
    1/2 + asin(theta / theta_max) / pi, with theta_max from mpmath's inversion of V = E."""
    def f():
        thm, th = theta_max_tiny_mp(kind, par, eps, theta0, v0), mp.mpf(theta)
        return {"density": 1 / (mp.pi * mp.sqrt(thm ** 2 - th ** 2)), "cdf": mp.mpf(1) / 2 + mp.asin(th / thm) / mp.pi}
    ref = twice(f, 60)
    if ref is None:
        return
    rows.add(set_, cls, "angle_density", [kind, par, eps, theta0, v0, theta], {"density": ref["density"]},
             {"density": 1e-300})
    rows.add(set_, cls, "angle_cdf", [kind, par, eps, theta0, v0, theta], {"cdf": ref["cdf"]}, {"cdf": 1.0})


def add_density_rotation(rows, set_, cls, kind, par, eps, theta0, v0, theta):
    """A rotation at a large theta: the reference reduces theta exactly (mpmath at enough digits)
    and counts the turns of the CDF."""
    dps = 40 + int(math.log10(abs(theta) + 1))
    with mp.workdps(40):
        if orbit_a(KINDS[kind], mp.mpf(par), mp.mpf(eps), mp.mpf(theta0), mp.mpf(v0), with_period=False)[
                "regime"] != 2:
            return

    def f():
        th = mp.mpf(theta)
        n = mp.floor((th + mp.pi) / (2 * mp.pi))
        w = th - 2 * mp.pi * n
        r = density_cdf(time_a, KINDS[kind], mp.mpf(par), mp.mpf(eps), mp.mpf(theta0), mp.mpf(v0), w)
        return {"density": r["density"], "cdf": r["cdf"] + n}
    ref = twice(f, dps)
    if ref is None:
        return
    # the condition number in the reduced angle w (the rounding of the computation there, not of
    # theta, which is exact): |w p'(w) / p| for the density, |w p(w)| for the CDF (absolute)
    with mp.workdps(dps):
        th = mp.mpf(theta)
        w = th - 2 * mp.pi * mp.floor((th + mp.pi) / (2 * mp.pi))
        h = mp.mpf("1e-20") * w
        args = (KINDS[kind], mp.mpf(par), mp.mpf(eps), mp.mpf(theta0), mp.mpf(v0))
        p0 = density_cdf(time_a, *args, w)["density"]
        p1 = density_cdf(time_a, *args, w + h)["density"]
        cond = {"density": abs(w * (p1 - p0) / h / p0), "cdf": abs(w * p0)}
    rows.add(set_, cls, "angle_density", [kind, par, eps, theta0, v0, theta], {"density": ref["density"]},
             {"density": 1e-300}, cond)
    rows.add(set_, cls, "angle_cdf", [kind, par, eps, theta0, v0, theta], {"cdf": ref["cdf"]}, {"cdf": 1.0}, cond)


def incomplete_reference(phi, digits, m=None, mc=None):
    """E(phi|m) and F(phi|m) by mpmath (checked by `twice`), m the exact double `m` or formed as
    1 - `mc` at the working precision; None where they are not real or do not agree."""
    def f():
        par = mp.mpf(m) if mc is None else 1 - mp.mpf(mc)
        out = {"ellipeinc": mp.ellipe(mp.mpf(phi), par), "ellipf": mp.ellipf(mp.mpf(phi), par)}
        if any(mp.im(x) != 0 for x in out.values()):
            return None
        return {q: mp.re(x) for q, x in out.items()}
    with mp.workdps(digits):
        if f() is None:
            return None
    return twice(f, digits)


def add_einc(rows, set_, cls, phi, mc):
    digits = 40 + int(max(0, -math.log10(abs(mc)))) + int(math.log10(abs(phi) + 1))
    ref = incomplete_reference(phi, digits, mc=mc)
    if ref is None:
        return
    rows.add(set_, cls, "ellip", [phi, mc], ref, {"ellipeinc": 1.0, "ellipf": 1.0})


def add_ellip_m(rows, set_, cls, phi, m):
    """F(phi|m) and E(phi|m) at the exact doubles phi and m (given to pendula as m), relative."""
    digits = 40 + int(math.log10(abs(m) + 1)) // 4
    ref = incomplete_reference(phi, digits, m=m)
    if ref is None:
        return
    rows.add(set_, cls, "ellip_m", [phi, m], ref, {"ellipeinc": TINY, "ellipf": TINY})


def add_jacobi(rows, set_, cls, u, m):
    """sn, cn, dn(u|m) at the exact doubles u and m < 0 by mpmath's ellipfun, with digits for
    1 - m and for u's multiple of the period."""
    mo = 1.0 - m
    digits = 40 + int(math.log10(mo)) + int(max(0.0, math.log10(abs(u) * math.sqrt(mo) + 1.0)))

    def f():
        vals = [mp.ellipfun(n, mp.mpf(u), mp.mpf(m)) for n in ("sn", "cn", "dn")]
        return {n: mp.re(v) for n, v in zip(("sn", "cn", "dn"), vals)}
    ref = twice(f, digits)
    if ref is None:
        return
    rows.add(set_, cls, "ellipj", [u, m], ref, {"sn": 1.0, "cn": 1.0, "dn": 1.0})


# ------------------------------------------------------------ the classes

def gen_huge_m_edge(rng, rows, n):
    cls = "ellip_huge_m_edge"
    add_ellip_m(rows, "reproducer", cls, 3e-154, 1e307)
    for _ in range(n):
        m = loguni(rng, 1e270, 1.7e308)
        r = float(rng.uniform(0.5, 1.0))
        with mp.workdps(40):
            phi = float(mp.asin(mp.sqrt(r / mp.mpf(m))))
        add_ellip_m(rows, "hunt", cls, phi, m)


def gen_tiny_phi(rng, rows, n):
    cls = "ellip_tiny_phi_huge_m"
    add_ellip_m(rows, "reproducer", cls, 5e-126, 1e250)
    for _ in range(n):
        m = float(rng.choice([-1, 1])) * loguni(rng, 1e200, 1.7e308)
        r = loguni(rng, 1e-6, 1.0) if m > 0 else loguni(rng, 1e-6, 1e6)
        add_ellip_m(rows, "hunt", cls, math.sqrt(r / abs(m)), m)


def gen_jacobi_far(rng, rows, n):
    cls = "jacobi_m_far_below_zero"
    add_jacobi(rows, "reproducer", cls, 2.582159487283872e-114, -3.974831433674558e+258)
    for _ in range(n):
        m = -loguni(rng, 2.0, 1e300)
        with mp.workdps(40):
            q = float(mp.ellipk(mp.mpf(m)))
        u = float(rng.choice([-1, 1])) * q * loguni(rng, 1e3, 3e13)
        add_jacobi(rows, "hunt", cls, u, m)


def gen_tiny(rng, rows, n):
    cls = "tiny"
    add_orbit(rows, "reproducer", cls, 0.0, 9.604726896081261e-209, 31.092660763526805, TINY)
    add_exact(rows, "reproducer", cls, 0.0, -5.889670126685722e-188, 2.643058719640813, -0.02395422390411285, TINY)
    smallest = [5e-324, 2.0 ** -1074 * 3, TINY, TINY * 3.7]
    for i in range(n):
        # |v0|, theta0 and eps log-uniform down to the smallest subnormal (a quarter of the draws at
        # the smallest normal and subnormal themselves); |v0| / (2 sqrt(eps)) kept below 1e150
        def draw(lo, hi):
            return smallest[rng.integers(len(smallest))] if rng.random() < 0.25 else loguni(rng, lo, hi)
        eps = draw(5e-324, 1e10)
        th0 = float(rng.choice([-1, 1])) * draw(5e-324, 1e-150) if rng.random() < 0.8 else 0.0
        v0 = float(rng.choice([-1, 1])) * draw(5e-324, 1e-150) if rng.random() < 0.8 else 0.0
        if th0 == 0.0 and v0 == 0.0:
            v0 = draw(5e-324, 1e-150)
        if not abs(v0) / (2 * math.sqrt(eps)) < 1e150:
            continue
        t = float(rng.uniform(-1, 1)) * 10 ** rng.uniform(-3, 3) / math.sqrt(eps)
        which = i % 6
        if which == 0:
            add_orbit(rows, "hunt", cls, th0, v0, eps, TINY)
        elif which == 1:
            add_exact(rows, "hunt", cls, th0, v0, eps, t, TINY)
        elif which == 2:
            with mp.workdps(60):
                ref = mp.mpf(v0) ** 2 / 2 + 2 * mp.mpf(eps) * mp.sin(mp.mpf(th0) / 2) ** 2
            rows.add("hunt", cls, "energy", [th0, v0, eps], {"energy": ref}, {"energy": TINY})
        elif which in (3, 4):
            kind = ["uniform", "inverse-square", "linear"][(i // 6 + which) % 3]
            par = {"uniform": 0.0, "inverse-square": loguni(rng, 1.01, 100.0),
                   "linear": float(rng.uniform(-2, 0.45))}[kind]
            if eps > 1e300 or not abs(v0) < 1e150:
                continue
            add_gravity(rows, "hunt", cls, kind, par, eps, th0, v0, TINY)
        else:
            kind = ["uniform", "inverse-square", "linear"][(i // 6) % 3]
            par = {"uniform": 0.0, "inverse-square": loguni(rng, 1.01, 100.0),
                   "linear": float(rng.uniform(-2, 0.45))}[kind]
            with mp.workdps(60):
                thm_mp = theta_max_tiny_mp(kind, par, eps, th0, v0)
            if not 0 < thm_mp < 1e-100:
                continue
            thm = float(thm_mp)
            theta = float(rng.uniform(-0.97, 0.97)) * thm
            add_density_tiny(rows, "hunt", cls, kind, par, eps, th0, v0, theta)


def gen_einc(rng, rows, n):
    cls = "einc_above_one"
    add_einc(rows, "reproducer", cls, -1.5707963257148592, -1.550741002689761e-180)
    for _ in range(n):
        mc = -loguni(rng, 1e-300, 1e-16)
        d = loguni(rng, max(1e-12, 4 * math.sqrt(-mc)), 1e-2)
        j = int(rng.choice([0, 0, 0, 1, -1, 2, -3]))
        phi = float(rng.choice([-1, 1])) * (math.pi / 2 - d) + j * math.pi
        add_einc(rows, "hunt", cls, phi, mc)


def gen_inverse_square(rng, rows, n):
    cls = "inverse_square_near_one"
    add_gravity(rows, "reproducer", cls, "inverse-square", 1.004060579092217, 16.098412378537102,
                -0.3907747745618768, -0.0008660513423679383, 1.0)
    add_gravity(rows, "reproducer", cls, "inverse-square", 1.063666134970304, 9.671778405492999,
                1.0716940666240364, -0.05036377822313806, 1.0)
    for _ in range(n):
        # (below d - 1 = 1e-4 the period's quadrature needs more than 2^18 panels and is refused)
        d = 1 + loguni(rng, 1e-4, 0.3)
        eps = loguni(rng, 1e-2, 1e2)
        th0 = float(rng.uniform(-1.5, 1.5))
        v0 = float(rng.choice([-1, 1])) * loguni(rng, 1e-8, 1e-1) if rng.random() < 0.8 else 0.0
        add_gravity(rows, "hunt", cls, "inverse-square", d, eps, th0, v0, 1.0)


def gen_separatrix(rng, rows, n):
    cls = "separatrix_long_time"
    add_exact(rows, "reproducer", cls, 1.5621929090512134, 36.18425821586078, 649.0661529478261,
              2222.5873936302924, None)
    for _ in range(n):
        th0 = float(rng.uniform(-math.pi, math.pi))
        eps = loguni(rng, 1e-2, 1e3)
        dk = loguni(rng, 1e-15, 1e-3)
        v0 = float(rng.choice([-1, 1])) * 2 * math.sqrt(eps) * math.sqrt(1 + dk - math.sin(th0 / 2) ** 2)
        with mp.workdps(50):
            k2 = mp.sin(mp.mpf(th0) / 2) ** 2 + mp.mpf(v0) ** 2 / (4 * mp.mpf(eps))
            if k2 <= 1:
                continue
            turn = 2 * mp.ellipk(1 / k2) / (mp.sqrt(k2) * mp.sqrt(mp.mpf(eps)))
        t = float(rng.uniform(-1, 1)) * float(turn) * 10 ** rng.uniform(0, 3)
        add_exact(rows, "hunt", cls, th0, v0, eps, t, None)


def gen_periodic(rng, rows, n):
    cls = "periodic_exact"
    add_density_rotation(rows, "reproducer", cls, "uniform", 0.0, 1.0743354960943294, -0.14321751656170978,
                         2.067690416206293, -908.1340606637546)
    for i in range(n):
        big = float(rng.choice([-1, 1])) * loguni(rng, 10.0, 2.0 ** 52)
        which = i % 5
        kind = ["uniform", "inverse-square", "linear"][i % 3]
        par = {"uniform": 0.0, "inverse-square": loguni(rng, 1.1, 100.0), "linear": float(rng.uniform(-2, 0.45))}[kind]
        eps = loguni(rng, 1e-2, 1e2)
        if which in (0, 1):
            # a rotation: v0 beyond the separatrix speed of the field
            th0 = float(rng.uniform(-math.pi, math.pi))
            with mp.workdps(40):
                from gen_model_grids import f_mp
                f1 = f_mp(KINDS[kind], mp.mpf(par), mp.mpf(eps), 1)
                w0 = mp.sin(mp.mpf(th0) / 2) ** 2
                vmin = float(mp.sqrt(2 * (f1 - f_mp(KINDS[kind], mp.mpf(par), mp.mpf(eps), w0))))
            v0 = float(rng.choice([-1, 1])) * vmin * (1 + loguni(rng, 1e-3, 3.0))
            add_density_rotation(rows, "hunt", cls, kind, par, eps, th0, v0, big)
        elif which == 2:
            v = float(rng.normal())
            with mp.workdps(40 + 16):
                ref = mp.mpf(v) ** 2 / 2 + 2 * mp.mpf(eps) * mp.sin(mp.mpf(big) / 2) ** 2
            rows.add("hunt", cls, "energy", [big, v, eps], {"energy": ref}, {"energy": 1.0})
        elif which == 3:
            v0 = float(rng.normal()) * 0.3
            add_gravity(rows, "hunt", cls, kind, par, eps, big, v0, 1.0, dps=40 + 16)
        else:
            mc = float(rng.uniform(0.01, 1.0)) if rng.random() < 0.7 else -float(rng.uniform(0.0, 0.5))
            add_einc(rows, "hunt", cls, big, mc)


GENERATORS = (("tiny", gen_tiny), ("einc", gen_einc), ("inverse-square", gen_inverse_square),
              ("separatrix", gen_separatrix), ("periodic", gen_periodic),
              ("huge-m-edge", gen_huge_m_edge), ("tiny-phi", gen_tiny_phi), ("jacobi-far", gen_jacobi_far))


def main():
    """All classes; or, with class names as arguments (e.g. ``jacobi-far``), only those, their rows
    replacing that class's rows in the stored file and the others kept as they are (each class
    draws from its own stream, so the result is the same as a whole run)."""
    only = sys.argv[1:]
    unknown = set(only) - {name for name, _ in GENERATORS}
    if unknown:
        sys.exit(f"unknown classes {sorted(unknown)}; known: {[name for name, _ in GENERATORS]}")
    rows = Rows()
    n = int(os.environ.get("HARD_CASES_N", "300"))
    made = set()
    for k, (name, gen) in enumerate(GENERATORS):
        if only and name not in only:
            continue
        rng = np.random.default_rng([SEED, k])     # each class its own stream
        before = len(rows.rows)
        gen(rng, rows, n if name not in ("inverse-square",) else n // 3)
        made |= {r[1] for r in rows.rows[before:]}
        print(f"{name}: {len(rows.rows) - before} rows", file=sys.stderr)
    out = rows.rows
    if only:
        with gzip.open(OUT, "rt", newline="") as fh:
            kept = [r for r in list(csv.reader(fh))[1:] if r[1] not in made]
        cls_rank = {}
        for r in kept + out:
            cls_rank.setdefault(r[1], len(cls_rank))
        out = sorted(kept + out, key=lambda r: cls_rank[r[1]])   # stable: the rows' own order kept
    with gzip.open(OUT, "wt", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(COLUMNS)
        w.writerows(out)
    print(f"{len(rows.rows)} rows -> {OUT}", file=sys.stderr)


if __name__ == "__main__":
    main()

"""Generate data/spherical_reference.csv: the spherical pendulum's path and
orbit facts computed with mpmath, independently of pendula.

The reference knows nothing of Jacobi functions or Carlson's integrals.  From
the exact double inputs (theta0, theta_dot0, phi_dot0, eps) it forms, at 40
digits, the energy above the bottom e and the vertical angular momentum L
(scaled time tau = sqrt(eps) t), and the roots xa <= xb <= xc of
Q(x) = 2 (e - x) x (2 - x) - L^2 (mpmath's polyroots), x = 1 - cos(theta).
With x = xa + d sin^2(psi), d = xb - xa, the first integrals become smooth
quadratures in psi (no endpoint singularity):

    d tau / d psi = sqrt(2) / sqrt(xc - xa - d sin^2 psi)
    d phi / d psi = L (1/x + 1/(2 - x)) / 2  *  d tau / d psi

integrated by mpmath.quad (tanh-sinh) on pieces of length pi/2 at most.  A
time t (a double) is located by Newton's method on tau(psi) - tau(psi0) =
sqrt(eps) t, whole half turns of psi (one polar period each) counted
exactly, so that t = 1e12 costs no more than t = 10.  Then

    theta = 2 asin(sqrt(x / 2)),  theta' = sqrt(eps) sign(sin 2 psi) sqrt(Q(x)) / sin(theta),
    phi' = sqrt(eps) L / (x (2 - x)).

The polar period is 2 tau(pi/2) / sqrt(eps) and the azimuth advance per
polar period 2 phi(pi/2) (from psi = 0); the apsidal angle is half of it.

Rows (kind):
* 'fact': the orbit between 30 and 60 degrees (g = l = 1), from the exact
  turning heights; checks the published values, polar period 3.3829713541618,
  apsidal angle 111.683552423557 degrees.
* 'path': seeded random states in every region (generic; next to the
  conical orbit; reaching the upper hemisphere and near the top; tiny and
  huge L; eps from 1e-2 to 1e2), several times each, some at t = 1e12.

Usage:  python data/gen_spherical_reference.py   (a few minutes)
"""

from __future__ import annotations

import csv
import math
import pathlib
import random

import mpmath as mp

OUT = pathlib.Path(__file__).with_name("spherical_reference.csv")
DPS = 40


class Orbit:
    """The orbit of exact double inputs, in mpmath."""

    def __init__(self, theta0, theta_dot0, phi_dot0, eps):
        self.inputs = (theta0, theta_dot0, phi_dot0, eps)
        th0 = mp.mpf(theta0)
        self.sq = mp.sqrt(mp.mpf(eps))
        w = mp.mpf(theta_dot0) / self.sq
        p = mp.mpf(phi_dot0) / self.sq
        x0 = 2 * mp.sin(th0 / 2) ** 2
        s = mp.sin(th0) ** 2
        self.L = s * p
        self.e = (w * w + s * p * p) / 2 + x0
        e, L = self.e, self.L
        # Q(x) = 2 (e - x) x (2 - x) - L^2 = 2x^3 - 2(e + 2)x^2 + 4e x - L^2
        roots = mp.polyroots([2, -2 * (e + 2), 4 * e, -L * L], maxsteps=400, extraprec=4 * DPS)
        roots = sorted(mp.re(r) for r in roots)
        self.xa, self.xb, self.xc = roots
        # a start at a turning point: that root is x0 itself
        if theta_dot0 == 0:
            if abs(self.xa - x0) < abs(self.xb - x0):
                self.xa = x0
            else:
                self.xb = x0
        self.d = self.xb - self.xa
        sarg = (x0 - self.xa) / self.d if self.d else mp.mpf(0)
        sarg = min(max(sarg, mp.mpf(0)), mp.mpf(1))
        self.psi0 = mp.asin(mp.sqrt(sarg)) * (-1 if theta_dot0 < 0 else 1)
        self.half_tau = self._tau(0, mp.pi / 2) * 2      # tau over psi in [0, pi]: one polar period
        self.half_phi = self._phi(0, mp.pi / 2) * 2

    def dtau(self, psi):
        return mp.sqrt(2) / mp.sqrt(self.xc - self.xa - self.d * mp.sin(psi) ** 2)

    def dphi(self, psi):
        x = self.xa + self.d * mp.sin(psi) ** 2
        y = (2 - self.xb) + self.d * mp.cos(psi) ** 2
        return self.L * (1 / x + 1 / y) / 2 * self.dtau(psi)

    def _quad(self, f, a, b):
        """The integral of f from a to b on pieces ending at the multiples of pi/2 (where
        the integrands peak: 1/x at psi = 0 mod pi, 1/(2 - x) and d tau / d psi at pi/2)."""
        lo, hi = min(a, b), max(a, b)
        k0, k1 = int(mp.floor(lo / (mp.pi / 2))), int(mp.ceil(hi / (mp.pi / 2)))
        inner = [mp.pi / 2 * k for k in range(k0, k1 + 1) if lo < mp.pi / 2 * k < hi]
        val = mp.quad(f, [lo] + inner + [hi])
        return val if b >= a else -val

    def _tau(self, a, b):
        return self._quad(self.dtau, a, b)

    def _phi(self, a, b):
        return self._quad(self.dphi, a, b)

    def tau_of(self, psi):
        """tau(psi) - tau(psi0), whole half turns counted exactly."""
        n = mp.floor(psi / mp.pi)
        r = psi - n * mp.pi
        return n * self.half_tau + self._tau(0, r) - self._tau(0, self.psi0)

    def phi_of(self, psi):
        n = mp.floor(psi / mp.pi)
        r = psi - n * mp.pi
        return n * self.half_phi + self._phi(0, r) - self._phi(0, self.psi0)

    def psi_at(self, t):
        """psi with tau(psi) - tau(psi0) = sqrt(eps) t: Newton's method kept inside a
        bracket of one half turn (bisection where a step would leave it)."""
        target = mp.mpf(t) * self.sq
        n = mp.floor((target + self._tau(0, self.psi0)) / self.half_tau)
        lo, hi = n * mp.pi, (n + 1) * mp.pi
        psi = (lo + hi) / 2
        for _ in range(400):
            f = self.tau_of(psi) - target
            if f > 0:
                hi = psi
            else:
                lo = psi
            new = psi - f / self.dtau(psi)
            if not lo < new < hi:
                new = (lo + hi) / 2
            if abs(new - psi) < mp.mpf(10) ** (-DPS + 6) * max(1, abs(psi)):
                psi = new
                break
            psi = new
        else:
            raise RuntimeError(f"no convergence for t = {t}")
        assert abs(self.tau_of(psi) - target) < mp.mpf(10) ** (-DPS + 10) * max(1, abs(target))
        return psi

    def state(self, t):
        psi = self.psi_at(t)
        x = self.xa + self.d * mp.sin(psi) ** 2
        y = (2 - self.xb) + self.d * mp.cos(psi) ** 2
        theta = 2 * mp.atan2(mp.sqrt(x), mp.sqrt(y))
        q = 2 * (self.e - x) * x * (2 - x) - self.L ** 2
        sin_t = mp.sqrt(x * y)
        theta_dot = self.sq * mp.sign(mp.sin(2 * psi)) * mp.sqrt(max(q, 0)) / sin_t
        phi_dot = self.sq * self.L / (x * y)
        return theta, self.phi_of(psi), theta_dot, phi_dot

    def facts(self):
        period = self.half_tau / self.sq
        return period, self.half_phi


def fnum(x) -> str:
    return repr(float(x))


def conical_rate(theta0, eps):
    """phi' of the circular orbit at theta0: phi'^2 = eps / cos(theta0)."""
    return math.sqrt(eps / math.cos(theta0))


def states(rng: random.Random):
    """(case, theta0, theta_dot0, phi_dot0, eps, times) over every region."""
    out = []
    for _ in range(10):
        th = rng.uniform(0.05, 3.0)
        out.append(("generic", th, rng.gauss(0, 1), rng.gauss(0, 1.5), 1.0, 4))
    for _ in range(6):
        th = rng.uniform(0.1, 1.4)
        rel = 10 ** rng.uniform(-12, -3) * rng.choice([-1, 1])
        out.append(("near_conical", th, 0.0, conical_rate(th, 1.0) * (1 + rel), 1.0, 3))
    for _ in range(2):
        th = rng.uniform(0.2, 1.3)
        out.append(("near_conical_moving", th, 10 ** rng.uniform(-10, -4), conical_rate(th, 1.0), 1.0, 3))
    for _ in range(6):
        th = rng.uniform(math.pi / 2, 3.1)
        out.append(("upper_hemisphere", th, rng.gauss(0, 0.5), rng.gauss(0, 0.5), 1.0, 3))
    for _ in range(3):
        th = math.pi - 10 ** rng.uniform(-3, -1.5)
        out.append(("near_top", th, 0.0, 10 ** rng.uniform(-1.5, 0), 1.0, 3))
    for _ in range(5):
        th = rng.uniform(0.2, 2.5)
        out.append(("tiny_lz", th, rng.gauss(0, 1), 10 ** rng.uniform(-14, -4) * rng.choice([-1, 1]), 1.0, 3))
    for _ in range(3):
        th = rng.uniform(0.2, 2.5)
        out.append(("huge_lz", th, rng.gauss(0, 1), 10 ** rng.uniform(2, 5) * rng.choice([-1, 1]), 1.0, 3))
    for _ in range(4):
        eps = 10 ** rng.uniform(-2, 2)
        th = rng.uniform(0.1, 2.8)
        out.append(("eps", th, rng.gauss(0, 1) * math.sqrt(eps), rng.gauss(0, 1) * math.sqrt(eps), eps, 3))
    return out


def main() -> None:
    mp.mp.dps = DPS
    rng = random.Random(20240917)
    rows = []
    # the orbit between 30 and 60 degrees: e and L from the two turning heights
    xa, xb = 1 - mp.cos(mp.pi / 6), 1 - mp.cos(mp.pi / 3)
    sa, sb = xa * (2 - xa), xb * (2 - xb)
    e = (xa * sa - xb * sb) / (sa - sb)
    L = mp.sqrt(2 * (e - xa) * sa)
    o = Orbit.__new__(Orbit)
    o.sq, o.L, o.e = mp.mpf(1), L, e
    o.xa, o.xb = xa, xb
    o.xc = e + 2 - xa - xb
    o.d, o.psi0 = xb - xa, mp.mpf(0)
    o.half_tau = o._tau(0, mp.pi / 2) * 2
    o.half_phi = o._phi(0, mp.pi / 2) * 2
    period, adv = o.facts()
    apsidal_deg = adv / 2 * 180 / mp.pi
    assert abs(period - mp.mpf("3.3829713541618")) < 1e-12, period
    assert abs(apsidal_deg - mp.mpf("111.683552423557")) < 1e-11, apsidal_deg
    th0 = math.pi / 6
    pd0 = float(L / mp.sin(mp.mpf(th0)) ** 2)
    # the same orbit from double inputs (the start at 30 degrees, at rest in theta)
    od = Orbit(th0, 0.0, pd0, 1.0)
    p2, a2 = od.facts()
    rows.append(("fact", "thirty_sixty_exact", "", "", "", "1.0", "", "", "", "", "",
                 fnum(period), fnum(adv)))
    rows.append(("fact", "thirty_sixty_doubles", fnum(th0), "0.0", fnum(pd0), "1.0", "", "", "", "", "",
                 fnum(p2), fnum(a2)))
    for case, th, td, pd, eps, ntimes in states(rng):
        o = Orbit(th, td, pd, eps)
        per, adv = o.facts()
        times = [rng.uniform(-3, 8) * float(per) for _ in range(ntimes)]
        if case in ("generic", "near_conical", "tiny_lz"):
            times.append(1.0e12 * rng.choice([-1, 1]))
        for t in times:
            theta, phi, thd, phd = o.state(t)
            rows.append(("path", case, fnum(th), fnum(td), fnum(pd), fnum(eps), fnum(t), fnum(theta),
                         fnum(phi), fnum(thd), fnum(phd), fnum(per), fnum(adv)))
        print(case, th, td, pd, eps, float(per), float(adv), flush=True)
    with OUT.open("w", newline="") as f:
        f.write(f"# generated by data/gen_spherical_reference.py with mpmath {mp.__version__}\n")
        w = csv.writer(f)
        w.writerow(["kind", "case", "theta0", "theta_dot0", "phi_dot0", "eps", "t", "theta", "phi",
                    "theta_dot", "phi_dot", "period", "advance"])
        w.writerows(rows)
    print(f"wrote {len(rows)} rows to {OUT}")


if __name__ == "__main__":
    main()

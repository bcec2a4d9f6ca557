"""Switching-current distributions of linear ramps: an independent mpmath reference.

The Fulton-Dunkleberger integral (Phys. Rev. B 9 (1974) 4760) of the escape
rate of a current-biased junction, written here from the formulas and the
CODATA 2018 constants alone (pendula is not imported):

* thermal activation, Mel'nikov and Meshkov's turnover formula (Hanggi,
  Talkner and Borkovec, Rev. Mod. Phys. 62 (1990) 251, eq. 6.26):
  Gamma = A(Delta) (sqrt(1 + alpha^2) - alpha) (omega_a / 2 pi) exp(-dU / kT),
  A(Delta) = exp((1/pi) int_0^inf ln(1 - exp(-Delta (x^2 + 1/4))) / (x^2 + 1/4) dx),
  Delta = S_b / (omega_p R C kT) with S_b the action of the orbit at the
  barrier's energy (mpmath.quad after mpmath.findroot of the turning point);
* tunnelling, the Caldeira-Leggett rate as in Martinis, Devoret and Clarke,
  Phys. Rev. B 35 (1987) 4682, section II:
  Gamma_q = sqrt(120 pi B) (omega_a / 2 pi) exp(-B (1 + 0.87 / Q)),
  B = 7.2 dU / (hbar omega_a), Q = omega_a R C;
* the rate: the larger of the two.

The integral: with the survival S(i) = exp(-Phi(i)), Phi(i) = int_0^i
Gamma / (di/dt), the mean is E[i] = int_0^1 S and the variance
(a - m)^2 + int_a^c 2 (i - m) S(i) di (S = 1 to 1e-17 below a, S < e^-300
above c), both by composite 24-point Gauss-Legendre (mpmath's nodes) on
120 equal panels of [a, c], Phi at each node by the same rule from its
panel's edge.  The thermal rate's slowly varying prefactor is a Chebyshev
fit (mpmath.chebyfit, degree 39, fitted and evaluated at 60 digits: its
monomial form needs them; its error stored) on [a, c], the exponent exact;
at 20 mK the thermal rate's bound (omega_a / 2 pi) exp(-dU / kT) is below
the tunnelling rate on [a, c], which is then the larger of the two exactly
(checked on 400 points).
Done at 20 digits on 120 panels and again on 180: the spread is stored.

Run: python data/gen_switching_reference.py   (about a CPU minute a case)
"""

import json
import pathlib
import platform
import sys
import time

import mpmath as mp
from mpmath.calculus.quadrature import GaussLegendre

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE / "junction" / "switching_reference.json"

mp.mp.dps = 20
H = mp.mpf("6.62607015e-34")
E = mp.mpf("1.602176634e-19")
KB = mp.mpf("1.380649e-23")
HBAR = H / (2 * mp.pi)


class Case:
    def __init__(self, ic, r, c, t, ramp):
        self.ic, self.r, self.c, self.t, self.ramp = (mp.mpf(x) for x in (ic, r, c, t, ramp))
        self.wp = mp.sqrt(2 * E * self.ic / (HBAR * self.c))
        self.ej = HBAR * self.ic / (2 * E)
        self.beta = 1 / (self.wp * self.r * self.c)
        self.temp = KB * self.t / self.ej
        self.hw = HBAR * self.wp / self.ej
        self.shift = mp.log(self.wp * self.ic / self.ramp)       # hazard per unit i over Gamma / omega_p
        self.fit = None

    @staticmethod
    def du(i):
        return 2 * (mp.sqrt(1 - i * i) - i * mp.acos(i))

    @staticmethod
    def action(i):
        top = mp.pi - mp.asin(i)
        ub = -mp.cos(top) - i * top

        def u(p):
            return -mp.cos(p) - i * p
        f = lambda p: u(p) - ub  # noqa: E731
        turn = mp.findroot(f, (top - 2 * mp.pi, mp.asin(i)), solver="illinois", verify=False)
        turn = mp.findroot(f, turn, solver="newton", verify=False)
        assert abs(f(turn)) < 16 * mp.eps, (i, turn, f(turn))
        return 2 * mp.quad(lambda p: mp.sqrt(max(2 * (ub - u(p)), 0)), [turn, mp.asin(i), top])

    @staticmethod
    def melnikov(delta):
        f = lambda x: mp.log(-mp.expm1(-delta * (x * x + mp.mpf(1) / 4))) / (x * x + mp.mpf(1) / 4)  # noqa: E731
        return mp.exp(mp.quad(f, [0, mp.inf]) / mp.pi)

    def thermal_prefactor_log(self, i):
        wa = (1 - i * i) ** mp.mpf(0.25)
        alpha = self.beta / (2 * wa)
        a = self.melnikov(self.beta * self.action(i) / self.temp)
        return mp.log(wa / (2 * mp.pi) * (mp.sqrt(1 + alpha ** 2) - alpha) * a)

    def quantum_log(self, i):
        wa = (1 - i * i) ** mp.mpf(0.25)
        b = mp.mpf("7.2") * self.du(i) / (self.hw * wa)
        return mp.log(wa / (2 * mp.pi) * mp.sqrt(120 * mp.pi * b)) - b * (1 + mp.mpf("0.87") * self.beta / wa)

    def log_g_exact(self, i):
        return max(self.thermal_prefactor_log(i) - self.du(i) / self.temp, self.quantum_log(i)) + self.shift

    def log_g(self, i):
        """On [a, c]: the thermal prefactor from the Chebyshev fit (or no thermal part)."""
        q = self.quantum_log(i)
        if self.fit is None:
            return q + self.shift
        with mp.workdps(60):              # the monomial form of the fit needs the digits
            pref = +mp.polyval(self.fit, i)
        return max(pref - self.du(i) / self.temp, q) + self.shift

    @staticmethod
    def bisect(above, lo, hi):
        """The x in [lo, hi] where the increasing condition above(x) turns true (to 1e-10: a and c are
        only the ends of the integrals, placed with room to spare; found at 15 digits)."""
        for _ in range(36):
            mid = (lo + hi) / 2
            if above(mid):
                hi = mid
            else:
                lo = mid
        return (lo + hi) / 2

    def run(self, pieces_list):
        top = 1 - mp.mpf("1e-12")
        with mp.workdps(15):
            # a: Phi(a) <= a g(a) = 1e-18 (g increases)
            a = self.bisect(lambda x: self.log_g_exact(x) + mp.log(x) > mp.log(mp.mpf("1e-18")), mp.mpf(0), top)
            # c: the left Riemann sum of the increasing g, a lower bound of Phi, passes 300
            c, total, xs = None, mp.mpf(0), mp.linspace(a, top, 120)
            for x0, x1 in zip(xs, xs[1:]):
                total += mp.exp(self.log_g_exact(x0)) * (x1 - x0)
                if total > 300:
                    c = x1
                    break
        assert c is not None, "the ramp reaches I_c unswitched: not a case of this reference"
        a, c = +a, +c
        check = {}
        # the thermal rate is below its bound (wa / 2 pi) exp(-dU / kT) (Kramers' and Mel'nikov's factors are
        # <= 1); where that bound is below the tunnelling rate on a dense grid of [a, c], the larger of the
        # two is the tunnelling rate exactly and the thermal one is not needed
        grid = mp.linspace(a, c, 400)
        thermal_matters = any(mp.log((1 - x * x) ** mp.mpf(0.25) / (2 * mp.pi)) - self.du(x) / self.temp
                              > self.quantum_log(x) - 1 for x in grid)
        if thermal_matters:
            with mp.workdps(60):
                self.fit, err = mp.chebyfit(self.thermal_prefactor_log, [a, c], 40, error=True)
            check["chebyfit_error"] = float(err)
        else:
            check["thermal_left_out"] = "its bound is below the tunnelling rate by e^-1 or more on [a, c]"
        # composite 24-point Gauss-Legendre (mpmath's nodes at 20 digits) on `pieces` equal panels of [a, c]:
        # Phi at the panel edges by the panels' sums, at each node by the same rule on [edge, node]
        rule = GaussLegendre(mp.mp).calc_nodes(4, mp.mp.prec)

        def gl(f, lo, hi):
            h = (hi - lo) / 2
            return h * mp.fsum(w * f(lo + h * (x + 1)) for x, w in rule)

        def g(x):
            return mp.exp(self.log_g(x))
        out = []
        for pieces in pieces_list:
            edges = mp.linspace(a, c, pieces + 1)
            phi_edge = mp.mpf(0)       # Phi(a) <= a g(a) = 1e-18: taken as 0
            nodes, weights, survival = [], [], []
            for lo, hi in zip(edges, edges[1:]):
                h = (hi - lo) / 2
                for x, w in rule:
                    node = lo + h * (x + 1)
                    nodes.append(node)
                    weights.append(h * w)
                    survival.append(mp.exp(-(phi_edge + gl(g, lo, node))))
                phi_edge += gl(g, lo, hi)
            mean = a + mp.fsum(w * sv for w, sv in zip(weights, survival))
            var = (a - mean) ** 2 + mp.fsum(2 * w * (x - mean) * sv for x, w, sv in zip(nodes, weights, survival))
            out.append((mean, var))
        check["survival_at_c"] = float(mp.exp(-phi_edge))
        return a, c, out, check


CASES = [  # (I_c A, R ohm, C F, T K, ramp A/s)
    (10e-6, 30.0, 1e-12, 0.02, 1.0),
    (10e-6, 30.0, 1e-12, 0.02, 1e-3),
    (10e-6, 30.0, 1e-12, 4.2, 1.0),
    (10e-6, 30.0, 1e-12, 4.2, 1e-3),
    # a junction, temperature and ramp off the grid above (drawn once at random, written out)
    (3.1e-6, 120.0, 4.7e-13, 1.3, 2.5e-2),
]


def main():
    """Each case appended to the record as it is done (a run resumes: cases already stored are kept)."""
    rows = json.loads(OUT.read_text())["cases"] if OUT.exists() else []
    done = {(r["critical_current"], r["resistance"], r["capacitance"], r["temperature"], r["ramp_rate"]) for r in rows}
    for ic, r, c, t, ramp in CASES:
        if (ic, r, c, t, ramp) in done:
            continue
        t0 = time.time()
        case = Case(ic, r, c, t, ramp)
        a, cc, ((mean, var), (mean2, var2)), check = case.run((120, 180))
        row = {"critical_current": ic, "resistance": r, "capacitance": c, "temperature": t, "ramp_rate": ramp,
               "mean": float(mean * case.ic), "width": float(mp.sqrt(var) * case.ic),
               "mean_reduced": mp.nstr(mean, 20), "width_reduced": mp.nstr(mp.sqrt(var), 20),
               "spread_mean_120_180": float(abs(mean - mean2) / mean),
               "spread_width_120_180": float(abs(mp.sqrt(var) - mp.sqrt(var2)) / mp.sqrt(var)),
               "range_reduced": [float(a), float(cc)], **check, "seconds": round(time.time() - t0, 1)}
        print(row, flush=True)
        rows.append(row)
        OUT.write_text(json.dumps({
            "what": "mean and width (standard deviation) of the switching current of a linear ramp from 0, by "
                    "the Fulton-Dunkleberger integral of the larger of the Mel'nikov-Meshkov thermal rate and "
                    "the Caldeira-Leggett tunnelling rate; mpmath, 20 digits (gen_switching_reference.py)",
            "generated": time.strftime("%Y-%m-%d"), "mpmath": mp.__version__, "python": sys.version.split()[0],
            "machine": platform.machine(), "cases": rows}, indent=1) + "\n")


if __name__ == "__main__":
    main()

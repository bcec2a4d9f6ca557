"""The dc SQUID's static critical current Ic(Φ) against a brute-force constrained maximisation.

The reference, written here from the SQUID's equations alone: the rest points of the symmetric SQUID
form, at fixed flux, a curve parametrised by x = φ₁ − φ₂ (the circulating current is fixed by x,
sin φ₁ − sin φ₂ = −2K(x − 2πΦ/Φ₀), K = 1/(πβ_L)); along it the bias is
i(x) = 2 |cos(x/2)| √(1 − c²), c = −K(x − 2πΦ/Φ₀)/sin(x/2).  Ic is the maximum of i over the curve:
a grid of 40001 points, then SciPy's bounded Brent on the best cell to xatol 1e-13 (i is flat at its
maximum, so i is then exact to rounding).
"""

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

import pendula
from pendula.squid import DCSquid, squid_critical_current


def _reference(beta_l, flux):
    k = 1 / (math.pi * beta_l)
    x0 = 2 * math.pi * flux

    def bias(x):
        s = math.sin(x / 2)
        if s == 0:
            return -1.0
        c = -k * (x - x0) / s
        return 2 * abs(math.cos(x / 2)) * math.sqrt(1 - c * c) if abs(c) <= 1 else -1.0

    if flux == round(flux):
        # x = x0 = 2πm: sin(x/2) = 0, and the branch φ₁ = φ₂ (+2πm) carries any bias up to 2
        return 2.0
    xs = np.linspace(x0 - math.pi * beta_l, x0 + math.pi * beta_l, 40001)
    vals = np.array([bias(x) for x in xs])
    j = int(np.argmax(vals))
    lo, hi = xs[max(j - 1, 0)], xs[min(j + 1, xs.size - 1)]
    r = minimize_scalar(lambda x: -bias(x), bounds=(lo, hi), method="bounded", options={"xatol": 1e-13})
    return max(-r.fun, vals[j])


@pytest.mark.parametrize("beta_l", [0.1, 0.5, 1.0, 2.0])
def test_critical_current_matches_brute_force_maximisation(beta_l):
    rng = np.random.default_rng(int(beta_l * 10))
    for flux in [0.0, 0.1, 0.25, 0.4, 0.45, *rng.uniform(0, 0.5, 3)]:
        ic = squid_critical_current(beta_l, flux)
        ref = _reference(beta_l, flux)
        assert abs(ic / ref - 1) < 1e-10, (beta_l, flux, ic, ref)


def test_critical_current_is_even_and_periodic_in_the_flux():
    for flux in (0.13, 0.37):
        a = squid_critical_current(1.0, flux)
        assert abs(squid_critical_current(1.0, -flux) / a - 1) < 1e-12
        assert abs(squid_critical_current(1.0, flux + 1) / a - 1) < 1e-12


@pytest.mark.parametrize("flux", [0.0, 0.1, 0.25, 0.4])
def test_small_screening_tends_to_the_two_junction_interference_law(flux):
    """β_L → 0: Ic → 2 I₀ |cos(πΦ/Φ₀)|, with a correction of order β_L (here 1e-6)."""
    assert abs(squid_critical_current(1e-6, flux) - 2 * abs(math.cos(math.pi * flux))) < 1e-5


def test_half_flux_quantum_at_small_screening_is_a_hard_case():
    """At Φ = Φ₀/2 the two junctions' currents cancel: Ic ~ β_L, the fold at a tiny bias."""
    ic = squid_critical_current(0.01, 0.5)
    assert abs(ic / _reference(0.01, 0.5) - 1) < 1e-9


def test_laboratory_units():
    sq = DCSquid(10e-6, 2.0, 1e-13, 1.0e-10)
    assert abs(sq.beta_l - 2 * 1e-10 * 10e-6 / pendula.junction.FLUX_QUANTUM) < 1e-15
    assert abs(sq.critical_current(0.3) / (10e-6 * squid_critical_current(sq.beta_l, 0.3)) - 1) < 1e-15


def test_negative_inductance_is_refused():
    with pytest.raises(ValueError, match="inductance must be > 0"):
        DCSquid(10e-6, 2.0, 1e-13, -1e-10)
    with pytest.raises(ValueError, match="beta_l must be > 0"):
        squid_critical_current(0.0, 0.1)


def test_static_critical_current_separates_rest_from_running():
    """The SQUID as a network with its damping (β = 9, overdamped): biased 2 % below Ic(Φ) it stays
    trapped and settles, 2 % above it runs (its phases slip turn after turn, slowly: the passage by the
    fold's ghost takes a few hundred time units): the fold is where the dynamics says it is."""
    sq = DCSquid(10e-6, 2.0, 1e-13, 103.4e-12)
    flux = 0.25
    ic = sq.critical_current(flux)
    t = np.linspace(0, 3000, 7)
    below = sq.network(0.98 * ic, flux).simulate(t, rtol=1e-9, atol=1e-11)
    above = sq.network(1.02 * ic, flux).simulate(t, rtol=1e-9, atol=1e-11)
    assert np.max(np.abs(below.phi.values)) < np.pi            # no phase slip: trapped
    assert np.max(np.abs(below.v.values[-1])) < 1e-3           # and settling (slowly, next to the fold)
    assert np.min(above.phi.values[-1]) > 2 * np.pi * 2        # running: turn after turn

"""The rf SQUID's static flux states against SciPy's brentq on φ + β_L sin φ = 2πΦₑ/Φ₀.

The reference, written here from the loop's equation alone: every sign change of
g(φ) = φ + β_L sin φ − φₑ on a grid of 20001 points over [φₑ − β_L − 0.1, φₑ + β_L + 0.1] (all roots lie
within β_L of φₑ), each polished by brentq to xtol 1e-15; a root is stable where the loop's energy
(φ − φₑ)²/2β_L − cos φ is convex, 1 + β_L cos φ > 0.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

import pendula
from pendula.junction import FLUX_QUANTUM

I0 = 1e-6


def _squid(beta_l):
    return pendula.RFSquid(I0, beta_l * FLUX_QUANTUM / (2 * math.pi * I0))


def _reference_states(beta_l, flux):
    phie = 2 * math.pi * flux

    def g(x):
        return x + beta_l * math.sin(x) - phie
    xs = np.linspace(phie - beta_l - 0.1, phie + beta_l + 0.1, 20001)
    gs = xs + beta_l * np.sin(xs) - phie
    roots = []
    for j in np.flatnonzero(np.sign(gs[:-1]) != np.sign(gs[1:])):
        r = brentq(g, xs[j], xs[j + 1], xtol=1e-15, rtol=4 * np.finfo(float).eps)
        if not roots or r - roots[-1] > 1e-12:     # a root on a grid point ends two cells
            roots.append(r)
    return np.array(roots), np.array([1 + beta_l * math.cos(r) > 0 for r in roots])


@pytest.mark.parametrize("beta_l", [0.3, 0.95, 1.5, 3.04, 7.0])
def test_flux_states_match_brentq(beta_l):
    rng = np.random.default_rng(int(beta_l * 100))
    sq = _squid(beta_l)
    for flux in [0.0, 0.25, 0.5, -0.7, *rng.uniform(-2, 2, 6)]:
        r = sq.flux_states(flux)
        ref, ref_stable = _reference_states(beta_l, flux)
        assert r.flux.size == ref.size, (beta_l, flux)
        assert np.max(np.abs(2 * np.pi * r.flux.values - ref)) < 1e-13 * (1 + abs(2 * np.pi * flux))
        assert r.stable.values.tolist() == ref_stable.tolist()
        assert r.flux.attrs["units"] == "Phi0" and r.screening_current.attrs["units"] == "A"


def test_switching_flux_is_the_fold_of_the_zero_flux_branch():
    """The largest applied flux the branch through φ = 0 holds: the maximum of φ + β_L sin φ on it, by
    SciPy's bounded minimiser (xatol 1e-12; the maximum is flat, so the value is exact to rounding)."""
    for beta_l in (1.2, 3.04, 7.0):
        r = minimize_scalar(lambda x: -(x + beta_l * math.sin(x)), bounds=(0, math.pi), method="bounded",
                            options={"xatol": 1e-12})
        assert abs(_squid(beta_l).switching_flux - (-r.fun) / (2 * math.pi)) < 1e-13
    assert math.isnan(_squid(0.5).switching_flux) and not _squid(0.5).hysteretic


def test_hysteretic_flux_curve_follows_its_branch_and_jumps_past_the_fold():
    """β_L = 3.04: swept up from Φₑ = 0 the loop stays on the state continued from φ = 0 (brentq's root on
    that branch) until the fold at Φₑ = switching_flux, then jumps to the next stable state; swept down it
    jumps at −switching_flux (mod 1): a loop of hysteresis."""
    beta_l = 3.04
    sq = _squid(beta_l)
    fe = np.linspace(0, 2, 81)
    r = sq.flux_curve(fe)
    fs = sq.switching_flux
    up, down = r.flux.sel(direction="up").values, r.flux.sel(direction="down").values
    for j, f in enumerate(fe):
        ref, st = _reference_states(beta_l, f)
        stable = ref[st]
        k_up = np.sum(f > fs + np.arange(0, 3))           # jumps the up sweep has made by f
        # the up sweep's state: the stable one on the branch through 2πk_up
        want = stable[np.argmin(np.abs(stable - 2 * np.pi * k_up))]
        assert abs(2 * np.pi * up[j] - want) < 1e-13 * (1 + abs(want)), (f, up[j], want)
        k_down = 2 - np.sum(f < 2 - fs - np.arange(0, 3))  # the down sweep starts on the branch through 4π
        want = stable[np.argmin(np.abs(stable - 2 * np.pi * k_down))]
        assert abs(2 * np.pi * down[j] - want) < 1e-13 * (1 + abs(want)), (f, down[j], want)
    jumps_up = fe[r.jump.sel(direction="up").values]
    assert np.all(np.abs(jumps_up - (fs + np.array([0, 1]))) < fe[1] - fe[0])
    # hysteresis: at Φₑ = 0.5 the two sweeps hold different states
    j = int(np.argmin(np.abs(fe - 0.5)))
    assert up[j] < 0.5 < down[j]


def test_non_hysteretic_flux_curve_is_one_valued():
    sq = _squid(0.8)
    fe = np.linspace(-1, 1, 41)
    r = sq.flux_curve(fe)
    assert not r.jump.values.any()
    assert np.array_equal(r.flux.sel(direction="up").values, r.flux.sel(direction="down").values)
    for f, phi in zip(fe, r.flux.sel(direction="up").values):
        assert abs(2 * np.pi * phi - _reference_states(0.8, f)[0][0]) < 1e-13 * (1 + abs(2 * np.pi * f))


def test_flux_at_the_fold_is_a_hard_case():
    """At Φₑ = switching_flux the branch ends in a double root: every state returned solves the loop's
    equation to rounding and the stable one of the other branch is among them."""
    beta_l = 3.04
    sq = _squid(beta_l)
    fs = sq.switching_flux
    r = sq.flux_states(fs)
    phi = 2 * np.pi * r.flux.values
    assert np.all(np.abs(phi + beta_l * np.sin(phi) - 2 * np.pi * fs) < 1e-14 * 2 * np.pi * 4)
    ref, st = _reference_states(beta_l, fs)
    assert np.min(np.abs(phi - ref[st][-1])) < 1e-13


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="inductance"):
        pendula.RFSquid(I0, -1e-12)
    with pytest.raises(ValueError, match="critical_current"):
        pendula.RFSquid(0.0, 1e-12)
    with pytest.raises(ValueError, match="resistance"):
        pendula.RFSquid(I0, 1e-12, resistance=-1.0)
    with pytest.raises(ValueError, match="capacitance"):
        pendula.RFSquid(I0, 1e-12, capacitance=-1e-15)
    with pytest.raises(ValueError, match="external_flux"):
        _squid(2.0).flux_states(float("nan"))
    with pytest.raises(ValueError, match="external_fluxes"):
        _squid(2.0).flux_curve([0.5, 0.1])

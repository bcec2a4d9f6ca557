"""The driven, damped long Josephson junction as a ring of pendula: the fluxon's velocity against the bias.

The reference: McLaughlin and Scott's power balance for the perturbed sine-Gordon equation
φ_tt − φ_xx + sin φ = γ − α φ_t (Phys. Rev. A 18, 1652 (1978)): the energy the bias feeds a
kink, 2πγ u, equals what the damping takes, 8α u /√(1 − u²), so u = 1/√(1 + (4α/πγ)²) (in units of the
Swihart velocity).  The ring of N pendula with springs K = 1/a² is the equation discretised with the
spacing a (lengths in λ_J); one kink trapped by a 2π twist on the closing spring.  Each site's phase
rises by 2π when the kink passes it, so the kink's speed in sites per unit time is the rise of Σφ_n over
2π per unit time, and u = a × that.
"""

import math

import numpy as np
import pytest

import pendula


def _fluxon_velocity(k, alpha, gamma, length=40.0, t_win=200.0):
    n = int(round(length * math.sqrt(k)))
    off = np.zeros((n, n))
    off[n - 1, 0], off[0, n - 1] = -2 * np.pi, 2 * np.pi
    ring = pendula.Network(n, topology="ring", strength=k, offset=off, damping=alpha, bias=gamma)
    i = np.arange(n)
    kink = 4 * np.arctan(np.exp((i - n / 2) / math.sqrt(k)))
    t_tr = 10 / alpha        # the kink reaches its terminal speed at the rate α: e^-10 left
    run = ring.simulate([t_tr, t_tr + t_win], phi0=kink, rtol=1e-9, atol=1e-11)
    s = run.phi.values.sum(axis=1)
    return abs(s[1] - s[0]) / t_win / (2 * np.pi) / math.sqrt(k)


def _power_balance(alpha, gamma):
    return 1 / math.sqrt(1 + (4 * alpha / (math.pi * gamma)) ** 2)


_RNG = np.random.default_rng(11)
CASES = [(0.1, 0.2), (0.05, 0.1), (0.1, 0.05), (float(_RNG.uniform(0.05, 0.1)), float(_RNG.uniform(0.05, 0.2)))]


@pytest.mark.parametrize("alpha, gamma", CASES)
def test_fluxon_velocity_tends_to_the_mclaughlin_scott_power_balance(alpha, gamma):
    """At a = 1/8 (K = 64) the fluxon's speed is within 3e-3 of the power balance (measured 4e-4 to 2e-3:
    the lattice's discreteness and the perturbation theory's neglect of the kink's distortion), and the
    deviation at a = 1/4 (K = 16) is at least four times larger (the discretisation error falls at least
    as a², measured six to seventeen times)."""
    ms = _power_balance(alpha, gamma)
    fine = abs(_fluxon_velocity(64.0, alpha, gamma) / ms - 1)
    coarse = abs(_fluxon_velocity(16.0, alpha, gamma) / ms - 1)
    assert fine < 3e-3, (fine, coarse)
    assert coarse > 4 * fine, (fine, coarse)


def test_fluxon_velocity_helper_against_the_power_balance():
    """pendula.fluxon_velocity at α = 0.1, γ = 0.2 and a seeded random γ (either sign): within 3e-3 of the
    power balance written here at a = 1/8, and at least four times further at a = 1/4 (the lattice's
    error falls at least as a²)."""
    gam = [0.2, float(np.random.default_rng(5).uniform(-0.2, -0.05))]
    ms = np.array([_power_balance(0.1, abs(g)) for g in gam])
    fine = pendula.fluxon_velocity(gam, 0.1, spacing=0.125, length=30.0)
    coarse = pendula.fluxon_velocity(gam, 0.1, spacing=0.25, length=30.0)
    assert fine.speed.attrs["units"] == "1" and fine.attrs["sites"] == 240
    assert np.allclose(fine.power_balance.values, ms, rtol=1e-15, atol=0)
    dev_fine = np.abs(fine.speed.values / ms - 1)
    dev_coarse = np.abs(coarse.speed.values / ms - 1)
    assert np.all(dev_fine < 3e-3), dev_fine
    assert np.all(dev_coarse > 4 * dev_fine), (dev_fine, dev_coarse)


def test_two_trapped_fluxons_each_move_at_one_fluxons_speed():
    """Two fluxons half a ring of 40 λ_J apart barely interact (their tails overlap as e^-20): each moves
    at the single fluxon's power-balance speed, within 3e-3 at a = 1/8."""
    r = pendula.fluxon_velocity([0.1], 0.1, fluxons=2)
    assert abs(float(r.speed[0]) / _power_balance(0.1, 0.1) - 1) < 3e-3


def test_fluxon_velocity_bad_arguments_are_named():
    with pytest.raises(ValueError, match="damping"):
        pendula.fluxon_velocity([0.1], 0.0)
    with pytest.raises(ValueError, match="spacing"):
        pendula.fluxon_velocity([0.1], 0.1, spacing=-0.1)
    with pytest.raises(ValueError, match="fluxons"):
        pendula.fluxon_velocity([0.1], 0.1, fluxons=0)
    with pytest.raises(ValueError, match="sites"):
        pendula.fluxon_velocity([0.1], 0.1, length=1.0, spacing=0.25)
    with pytest.raises(ValueError, match="sites, more than"):
        pendula.fluxon_velocity([0.1], 0.1, length=1e6)
    with pytest.raises(ValueError, match="biases"):
        pendula.fluxon_velocity([np.nan], 0.1)


def test_zero_bias_leaves_the_fluxon_at_rest():
    """γ = 0: no drive, the power balance's speed is 0 and the damped fluxon stops (speed below 1e-6 after
    10/α = 100: its start at rest stays at rest up to the lattice's pinning, which is exponentially small)."""
    r = pendula.fluxon_velocity([0.0], 0.1)
    assert float(r.power_balance[0]) == 0.0
    assert float(r.speed[0]) < 1e-6

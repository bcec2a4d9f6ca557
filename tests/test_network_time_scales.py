"""The network's time scales (the kernel's one rule) and the default steps of Network.simulate.

References are independent of pendula: NumPy's symmetric eigensolver for the normal modes the rates
bound, SciPy's DOP853 at rtol 1e-12 for the paths, equipartition (⟨C v²⟩ = T) for the noisy runs.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pendula
from pendula import _interrupt


def _modes_omega2(net):
    """The largest ω² of the network linearised at the bottom (no torque): C^-1/2 (L + diag eps) C^-1/2."""
    k = net.coupling
    lap = np.diag(k.sum(axis=1)) - k
    s = 1.0 / np.sqrt(net.mass)
    return float(np.linalg.eigvalsh(s[:, None] * (lap + np.diag(net.eps)) * s[None, :])[-1])


def _scipy_path(net, t, phi0, v0):
    """The network's path by SciPy's DOP853 at rtol 1e-12 (the force written out here from K)."""
    k, n = net.coupling, net.n

    def rhs(tt, y):
        q, v = y[:n], y[n:]
        f = net.bias - net.eps * np.sin(q) + k @ q - k.sum(axis=1) * q \
            + net.drive_amplitude * np.cos(net.drive_frequency * tt + net.drive_phase)
        return np.concatenate([v, (f - net.damping * v) / net.mass])

    sol = solve_ivp(rhs, (0.0, float(t[-1])), np.concatenate([phi0, v0]), method="DOP853", t_eval=t,
                    rtol=1e-12, atol=1e-12)
    return sol.y[:n].T, sol.y[n:].T


def test_mode_rate_bounds_the_fastest_normal_mode_of_random_networks():
    """Gershgorin: the 'modes' rate² lies between the linearised network's largest ω² and twice it (the
    largest ω² is at least the largest diagonal entry, (eps_i + k_i) / C_i).  20 seeded random dense
    networks with unequal masses, eps and springs over four decades."""
    rng = np.random.default_rng(47)
    for _ in range(20):
        n = int(rng.integers(2, 8))
        k = np.triu(10 ** rng.uniform(-2, 2, (n, n)), 1)
        k[rng.random((n, n)) < 0.3] = 0.0
        k = np.triu(k, 1)
        net = pendula.Network(n, coupling=k + k.T, mass=10 ** rng.uniform(-1, 1, n), eps=rng.uniform(0, 2, n))
        w2 = _modes_omega2(net)
        r = net.time_scales().rates["modes"] ** 2
        assert w2 * (1 - 1e-12) <= r <= 2 * w2 * (1 + 1e-12), (w2, r)


def test_rates_of_a_pair_are_its_closed_forms():
    """Two equal pendula (C = 2, eps = 1) joined by K = 3, damping 0.4, bias 0.5, drive 0.2 cos(5 t): the
    opposite-phase mode ω² = (eps + 2K)/C is the 'modes' rate exactly (the bound is tight for a pair)."""
    net = pendula.Network(2, topology="pair", strength=3.0, mass=2.0, damping=0.4, bias=0.5,
                          drive_amplitude=0.2, drive_frequency=5.0)
    r = net.time_scales(v0=[0.0, -7.0]).rates
    assert r["modes"] == pytest.approx(math.sqrt(_modes_omega2(net)), rel=1e-15)
    assert r["modes"] == pytest.approx(math.sqrt(7.0 / 2.0), rel=1e-15)
    assert r["oscillation"] == pytest.approx(math.sqrt(0.5), rel=1e-15)
    assert r["coupling"] == pytest.approx(math.sqrt(3.0), rel=1e-15)
    assert r["damping"] == pytest.approx(0.2, rel=1e-15)
    assert r["drive"] == 5.0 and r["rotation"] == 7.0
    assert r["running"] == pytest.approx(0.7 / 0.4, rel=1e-15)   # (tau + A) / beta, the terminal speed


def test_an_undriven_drive_frequency_creates_no_scale():
    r = pendula.Network(2, topology="pair", drive_frequency=50.0).time_scales().rates
    assert r["drive"] == 0.0 and r["drive_force"] == 0.0


def test_default_steps_divide_two_pi_over_the_fastest_rate_by_each_methods_steps_per_period():
    ts = pendula.Network(3, topology="chain", strength=1e4).time_scales()
    assert ts.fastest == pytest.approx(math.sqrt(1 + 4e4), rel=1e-15)
    for method, per_period in (("gauss4", 100), ("gauss6", 100), ("baoab", 100)):
        assert ts.default_dt[method] == pytest.approx(2 * math.pi / ts.fastest / per_period, rel=1e-15)


def test_stiff_coupling_default_step_keeps_gauss6_on_the_reference_path():
    """A chain of 3 springs K = 1e4 without a sine (eps = 0: a linear chain, whose path is the closed form
    U cos(Ω t) Uᵀ φ₀ from its normal modes, NumPy's eigh): its fastest mode is 173 rad per unit time.  With
    no dt, gauss6 follows the closed form to 1e-6 rad over 55 periods of the fast mode (measured 1.5e-7)
    and keeps the energy to 3e-5 relative.  A step fit for a unit pendulum (0.01, 1/600 of its period)
    misses the fast mode: its error is 1e4 times larger."""
    net = pendula.Network(3, topology="chain", strength=1e4, eps=0.0)
    t = np.linspace(0.0, 2.0, 5)
    phi0, v0 = np.array([0.1, -0.05, 0.02]), np.zeros(3)
    k = net.coupling
    w2, u = np.linalg.eigh(np.diag(k.sum(axis=1)) - k)
    ref_phi = np.stack([u @ (np.cos(np.sqrt(np.maximum(w2, 0.0)) * tt) * (u.T @ phi0)) for tt in t])
    run = net.simulate(t, phi0, v0, method="gauss6")
    assert run.attrs["dt"] <= net.time_scales().default_dt["gauss6"]
    err = float(np.max(np.abs(run.phi.values - ref_phi)))
    assert err < 1e-6, err
    en = run.energy.values
    assert float(np.max(np.abs(en - en[0]))) < 3e-5 * en[0]
    coarse = net.simulate(t, phi0, v0, method="gauss6", dt=0.01)
    assert float(np.max(np.abs(coarse.phi.values - ref_phi))) > 1e4 * err


@pytest.mark.parametrize("method", ["gauss4", "gauss6", "baoab"])
def test_simulate_without_dt_works_for_each_fixed_step_method(method):
    """A damped, driven pair with no dt: each fixed-step method follows SciPy's DOP853 (rtol 1e-12); BAOAB
    at zero temperature is a second-order method (error ~ (h ω)² ~ 4e-3 of the amplitude), the
    Gauss-Legendre methods of order 4 and 6 far closer."""
    net = pendula.Network(2, topology="pair", strength=0.5, damping=0.1, drive_amplitude=0.3,
                          drive_frequency=1.3)
    t = np.linspace(0.0, 10.0, 11)
    phi0, v0 = np.array([0.5, -0.2]), np.array([0.0, 0.3])
    ref_phi, _ = _scipy_path(net, t, phi0, v0)
    run = net.simulate(t, phi0, v0, method=method)
    assert run.attrs["dt"] <= net.time_scales(v0).default_dt[method]
    tol = {"gauss4": 1e-7, "gauss6": 1e-10, "baoab": 5e-3}[method]
    phi = run.phi.values[0] if method == "baoab" else run.phi.values
    assert float(np.max(np.abs(phi - ref_phi))) < tol


def test_default_step_shortened_to_divide_the_output_spacing():
    net = pendula.Network(2, topology="pair")
    run = net.simulate([0.0, 0.3, 0.9], method="gauss6")
    k = 0.3 / run.attrs["dt"]
    assert k == pytest.approx(round(k), abs=1e-9) and run.attrs["dt"] <= net.time_scales().default_dt["gauss6"]


def test_default_step_refused_for_times_on_no_grid():
    with pytest.raises(ValueError, match="dt: the times t are not on a grid"):
        pendula.Network(2, topology="pair").simulate([0.0, 1.0, math.sqrt(3.0)], method="gauss6")


def test_stiff_coupling_default_step_keeps_baoab_equipartition():
    """A damped pair (β = 1, C = 1) with K = 1e4 at temperature 0.5: with the default step (hω = 2π/100)
    each element's ⟨C v²⟩ is T within 5 standard errors (seeded; 4 paths of 190 time units, 40 batch
    means) plus BAOAB's bias (hω)²/4 = 1e-3; the step of the soft network's test (0.02, hω = 2.8 > 2)
    is beyond BAOAB's stability and is refused as a non-finite state."""
    net = pendula.Network(2, topology="pair", strength=1e4, damping=1.0)
    t = np.arange(0.0, 200.0 + 0.5, 0.5)
    run = net.simulate(t, temperature=0.5, paths=4, seed=5)
    kin = net.mass * run.v.values[:, 21:, :] ** 2     # the first 10 time units (10 relaxation times) dropped
    batches = kin[:, :380].reshape(4, 10, 38, 2).mean(axis=2).reshape(-1, 2)
    mean = batches.mean(axis=0)
    se = batches.std(axis=0, ddof=1) / math.sqrt(batches.shape[0])
    assert np.all(np.abs(mean - 0.5) < 5 * se + 1e-3 * 0.5), (mean, se)
    assert np.all(se < 0.05 * 0.5)
    with pytest.raises(ValueError, match="non-finite"):
        net.simulate(t[:21], temperature=0.5, dt=0.02, seed=5)


def test_huge_span_with_the_default_step_is_refused_before_any_work():
    net = pendula.Network(2, topology="pair", strength=1e4)
    with pytest.raises(ValueError, match="work limit"):
        net.simulate([0.0, 1e7], method="gauss6")


def test_interruptible_run_chosen_by_the_networks_fastest_scale(monkeypatch):
    """The same span is a short call for a soft pair and a long (interruptible) one when K = 1e4 makes
    the fast mode 141 times faster."""
    seen = []
    real = _interrupt.call

    def spy(fn, *args, cancel, long=True):
        seen.append(long)
        return real(fn, *args, cancel=cancel, long=long)

    monkeypatch.setattr(_interrupt, "call", spy)
    t = np.linspace(0.0, 200.0, 3)
    pendula.Network(2, topology="pair", strength=0.5).simulate(t, phi0=[0.1, 0.0])
    pendula.Network(2, topology="pair", strength=1e4).simulate(t, phi0=[0.1, 0.0], rtol=1e-6, atol=1e-9)
    assert seen == [False, True]


def test_squid_noisy_default_step_is_the_network_rules():
    """A DC SQUID (β_L = 1, β_c = 0.5) at 4.2 K biased up to 2.5 I₀ is a Network in the time unit 1/ω_c
    whose fastest scale is the velocity's relaxation 1/β_c = 2 (above the loop's mode √((1 + 2/π)/β_c) =
    1.81, the torque's √(1.25/β_c) = 1.58 and the running speed 1.25): its noisy default step is
    2π β_c / 100 in 1/ω_c."""
    from pendula.junction import FLUX_QUANTUM
    from pendula.squid import DCSquid

    i0 = 10e-6
    sq = DCSquid(i0, 10.0, 0.5 * FLUX_QUANTUM / (2 * math.pi * i0 * 10.0 ** 2), FLUX_QUANTUM / (2 * i0),
                 temperature=4.2)
    assert sq.beta_c == pytest.approx(0.5, rel=1e-12) and sq.beta_l == pytest.approx(1.0, rel=1e-12)
    r = sq.iv_curve([1.0 * i0, 2.5 * i0], flux=0.25, paths=2, t_max=50 / sq.characteristic_frequency,
                    transient=10 / sq.characteristic_frequency)
    assert r.attrs["dt"] * sq.characteristic_frequency == pytest.approx(2 * math.pi * 0.5 / 100, rel=1e-12)

"""The dc SQUID's dynamic curves (I-V, V-Φ, dV/dΦ) against references written here from the RCSJ equations.

The reference for the running state: SciPy's DOP853 (rtol 1e-12) on the two junctions' equations in the
time unit 1/ω_c, written out below (β_c φ_k'' + φ_k' + sin φ_k = i/2 ∓ j, j = (φ₁ − φ₂ − 2πΦ/Φ₀)/(πβ_L)),
its mean velocity from the times at which s = (φ₁ + φ₂)/2 crosses 2πk (SciPy's event location): the exact
period of the limit cycle.  The overdamped SQUID at small β_L and β_c against the single junction's closed
form V = (R/2) √(I² − Ic(Φ)²), Ic(Φ) = 2I₀ abs(cos(πΦ/Φ₀)).
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from pendula.junction import FLUX_QUANTUM
from pendula.squid import DCSquid

I0 = 10e-6
R = 10.0


def _squid(beta_l, beta_c, temperature=0.0):
    """A SQUID of the given β_L and β_c (I₀ = 10 µA, R = 10 Ω)."""
    c = beta_c * FLUX_QUANTUM / (2 * math.pi * I0 * R * R)
    return DCSquid(I0, R, c, beta_l * FLUX_QUANTUM / (2 * I0), temperature=temperature)


def _reference_mean_velocity(beta_l, beta_c, flux, bias, t_skip=400.0, span=400.0):
    k = 1 / (math.pi * beta_l)

    def rhs(t, y):
        p1, p2, v1, v2 = y
        j = k * (p1 - p2 - 2 * math.pi * flux)
        return [v1, v2, (bias / 2 - j - v1 - math.sin(p1)) / beta_c, (bias / 2 + j - v2 - math.sin(p2)) / beta_c]

    y0 = [math.pi * flux, -math.pi * flux, 0.0, 0.0]
    a = solve_ivp(rhs, (0, t_skip), y0, method="DOP853", rtol=1e-12, atol=1e-14)

    def crossing(t, y):     # zero where s = (p1 + p2)/2 is a multiple of 2π
        return math.sin((y[0] + y[1]) / 4)

    b = solve_ivp(rhs, (t_skip, t_skip + span), a.y[:, -1], method="DOP853", rtol=1e-12, atol=1e-14,
                  events=crossing)
    te, ye = b.t_events[0], b.y_events[0]
    assert te.size > 20 and np.all(ye[:, 2] + ye[:, 3] > 0)    # a running state, s rising through each level
    return 2 * math.pi * (te.size - 1) / (te[-1] - te[0])


def test_v_phi_curve_at_large_bias_matches_scipy():
    """β_L = 1, β_c = 0.5, I = 2.5 I₀ (above Ic at every flux): agreement within pendula's own error
    estimate plus 1e-10 relative (the reference's period: 30-odd turns located to ~1e-12)."""
    sq = _squid(1.0, 0.5)
    rng = np.random.default_rng(7)
    fluxes = np.array([0.0, 0.25, 0.5, *rng.uniform(0, 1, 2)])
    r = sq.v_phi_curve(2.5 * I0, fluxes)
    assert r.voltage.attrs["units"] == "V" and r.flux.attrs["units"] == "Phi0"
    for f, v, e in zip(fluxes, r.voltage.values, r.voltage_err.values):
        ref = I0 * R * _reference_mean_velocity(sq.beta_l, sq.beta_c, f, 2.5)
        assert abs(v - ref) <= e + 1e-10 * ref, (f, v, ref, e)
        assert e <= 1e-9 * ref


def test_iv_curve_of_a_hysteretic_squid_matches_scipy_on_its_running_branch():
    """β_c = 4: the running branch of the down ramp matches SciPy started from rest at a large bias."""
    sq = _squid(0.5, 4.0)
    r = sq.iv_curve([1.6 * I0, 2.4 * I0], flux=0.17, direction="both")
    for j, i in enumerate((1.6, 2.4)):
        v = float(r.voltage.sel(direction="down")[j])
        if i == 2.4:
            ref = I0 * R * _reference_mean_velocity(sq.beta_l, sq.beta_c, 0.17, i, t_skip=800.0)
            assert abs(v - ref) <= float(r.voltage_err.sel(direction="down")[j]) + 1e-10 * ref
    # hysteresis: at 1.6 I0 (below Ic(0.17) ~ 1.7 I0) the up ramp is at rest and the down ramp runs
    assert float(r.voltage.sel(direction="up")[0]) == pytest.approx(0.0, abs=1e-15)
    assert float(r.voltage.sel(direction="down")[0]) > 0.1 * I0 * R


@pytest.mark.parametrize("flux, bias", [(0.2, 2.2), (0.4, 1.0)])
def test_overdamped_small_screening_squid_tends_to_the_single_junction_law(flux, bias):
    """V = (R/2) √(I² − Ic(Φ)²) with Ic = 2I₀ abs(cos πΦ/Φ₀) is the limit β_c, β_L → 0; the corrections are of
    second order: at β = 1e-2 and 1e-3 (both) the relative deviation is below 1e-3 and 1e-5, and falls by a
    factor between 50 and 200 (100 for a second-order approach)."""
    ic = 2 * abs(math.cos(math.pi * flux))
    ref = 0.5 * I0 * R * math.sqrt(bias ** 2 - ic ** 2)
    dev = []
    for beta in (1e-2, 1e-3):
        v = float(_squid(beta, beta).v_phi_curve(bias * I0, [flux]).voltage[0])
        dev.append(abs(v / ref - 1))
    assert dev[0] < 1e-3 and dev[1] < 1e-5
    assert 50 < dev[0] / dev[1] < 200


def test_transfer_function_matches_the_derivative_of_the_closed_form_in_the_overdamped_limit():
    """dV/dΦ of V = (R/2) √(I² − 4I₀² cos²(πΦ/Φ₀)): π R I₀² sin(2πΦ/Φ₀) / √(I² − Ic²) per Φ₀; at
    β_L = β_c = 1e-2 within 1e-3 relative (the second-order corrections, 1e-4 in V, and their slope)."""
    sq = _squid(1e-2, 1e-2)
    i = 2.2
    r = sq.transfer_function(i * I0, [0.2])
    ic = 2 * math.cos(math.pi * 0.2)
    ref = R * I0 * math.pi * math.sin(2 * math.pi * 0.2) / math.sqrt(i * i - ic * ic)
    assert r.transfer.attrs["units"] == "V/Phi0"
    assert abs(float(r.transfer[0]) / ref - 1) < 1e-3
    assert float(r.transfer_err[0]) < 1e-5 * abs(ref)


def test_transfer_function_matches_a_scipy_difference_quotient():
    """β_L = 1, β_c = 0.5, I = 2.5 I₀ at Φ = 0.3 Φ₀: the Richardson-extrapolated central difference of
    the SciPy reference (step 1e-2 and 2e-2: error of order 1e-8 of the slope) within the stated error."""
    sq = _squid(1.0, 0.5)
    r = sq.transfer_function(2.5 * I0, [0.3])
    h = 1e-2
    v = {m: _reference_mean_velocity(1.0, 0.5, 0.3 + m * h, 2.5) for m in (-2, -1, 1, 2)}
    d1, d2 = (v[1] - v[-1]) / (2 * h), (v[2] - v[-2]) / (4 * h)
    ref = I0 * R * (4 * d1 - d2) / 3
    assert abs(float(r.transfer[0]) - ref) <= float(r.transfer_err[0]) + 1e-6 * abs(ref)


def test_squid_at_rest_below_its_critical_current_has_no_voltage():
    sq = _squid(1.0, 0.5)
    ic = sq.critical_current(0.25)
    r = sq.iv_curve([0.9 * ic, 1.1 * ic], flux=0.25)
    assert abs(float(r.voltage[0, 0])) < 1e-12 * I0 * R
    assert float(r.voltage[0, 1]) > 1e-3 * I0 * R


def test_noisy_curves_are_reproducible_from_their_seed():
    sq = _squid(1.0, 0.5, temperature=4.2)
    a = sq.v_phi_curve(1.9 * I0, [0.1], t_max=2e-9, seed=5, paths=3)
    b = sq.v_phi_curve(1.9 * I0, [0.1], t_max=2e-9, seed=5, paths=3, threads=1)
    c = sq.v_phi_curve(1.9 * I0, [0.1], t_max=2e-9, seed=6, paths=3)
    assert a.voltage.values[0] == b.voltage.values[0]
    assert a.voltage.values[0] != c.voltage.values[0]
    assert a.attrs["method"] == "baoab" and a.attrs["seed"] == 5


def test_bad_arguments_of_the_dynamic_curves_are_named():
    sq = _squid(1.0, 0.5)
    with pytest.raises(ValueError, match="currents"):
        sq.iv_curve([2e-5, 1e-5])
    with pytest.raises(ValueError, match="fluxes"):
        sq.v_phi_curve(2e-5, [0.1, np.nan])
    with pytest.raises(ValueError, match="step"):
        sq.transfer_function(2e-5, [0.1], step=0.0)
    with pytest.raises(ValueError, match="capacitance"):
        DCSquid(I0, R, 0.0, 1e-10)
    with pytest.raises(ValueError, match="temperature"):
        DCSquid(I0, R, 1e-13, 1e-10, temperature=-1.0)


def _stratonovich_mean_velocity(a, b, d, n=2048):
    """⟨x'⟩ of x' = a − b sin x + η, ⟨η(t)η(t')⟩ = 2d δ(t − t'): Stratonovich's formula (Risken, *The
    Fokker-Planck Equation*, section 11.5), 2πd (1 − exp(−2πa/d)) over the double integral of
    exp([V(x) − V(x − y) − a y]/d), V = −b cos x, by the trapezoid rule on a periodic grid of n² points
    (spectrally accurate for this smooth periodic integrand)."""
    x = np.arange(n) * 2 * np.pi / n
    xx, yy = np.meshgrid(x, x, indexing="ij")
    expo = (-b * np.cos(xx) + b * np.cos(xx - yy) - a * yy) / d
    m = expo.max()
    integral = np.exp(expo - m).sum() * (2 * np.pi / n) ** 2
    return 2 * np.pi * d * (1 - math.exp(-2 * math.pi * a / d)) / integral / math.exp(m)


def test_noisy_overdamped_squid_matches_the_thermally_rounded_single_junction():
    """β_c = β_L = 0.02 at 20 K (kT/E_J = 0.084): the SQUID is one overdamped junction with
    Ic(Φ) = 2I₀ cos(πΦ/Φ₀) and the two shunts' noise, s' = i/2 − cos(πΦ/Φ₀) sin s + η with
    ⟨ηη⟩ = kT/E_J δ; its mean velocity by Stratonovich's formula.  At Φ = 0.2 Φ₀ and I = 1.7 I₀ (just
    above Ic = 1.62 I₀, where the noise rounds the curve most) pendula's 16 paths of 2000/ω_c agree within
    four standard errors (seeded; a fresh seed fails with probability 6e-5) plus 5e-3 relative (the
    drift's step error, first order in dt/β_c: measured +5 % at dt = 0.5 β_c, +2.5 % at 0.25 β_c; the
    default step, the network rule's, is 2π β_c / 100 = 0.063 β_c; the deterministic corrections of order
    β² are 5e-5).  Measured: +1.8 %, 1.3 standard errors (at the former step 0.05 β_c: -0.2 %, 0.2)."""
    sq = _squid(0.02, 0.02, temperature=20.0)
    ref = _stratonovich_mean_velocity(1.7 / 2, math.cos(math.pi * 0.2), sq.junction.noise / 2)
    r = sq.v_phi_curve(1.7 * I0, [0.2], paths=16, seed=3, t_max=2000 / sq.characteristic_frequency)
    v, err = float(r.mean_velocity[0]), float(r.voltage_err[0]) / (I0 * R)
    assert err < 0.02 * ref
    assert abs(v - ref) < 4 * err + 5e-3 * ref, (v, ref, err)
    # the deterministic SQUID at the same point would be far slower: the noise's rounding is resolved
    assert ref - 0.5 * math.sqrt(1.7 ** 2 - (2 * math.cos(math.pi * 0.2)) ** 2) > 10 * err


def test_noisy_transfer_function_agrees_with_the_deterministic_one_far_above_the_critical_current():
    """At I = 2.5 I₀ (β_L = 1, β_c = 0.5) the noise of 4.2 K (kT/E_J = 0.018) barely moves the running
    state: the noisy dV/dΦ (eight paths, the same noise at Φ ± h) agrees with the noiseless one within
    four of its standard errors (measured 0.6), and the same seed gives the same number."""
    det = float(_squid(1.0, 0.5).transfer_function(2.5 * I0, [0.25]).transfer[0])
    hot = _squid(1.0, 0.5, temperature=4.2)
    a = hot.transfer_function(2.5 * I0, [0.25], paths=8, seed=2)
    b = hot.transfer_function(2.5 * I0, [0.25], paths=8, seed=2, threads=1)
    assert float(a.transfer[0]) == float(b.transfer[0])
    err = float(a.transfer_err[0])
    assert 0 < err < 0.5 * abs(det)
    assert abs(float(a.transfer[0]) - det) < 4 * err


def test_shapiro_steps_of_the_squid_lock_at_multiples_of_f_times_the_flux_quantum():
    """An rf current 1.5 I₀ at f = ω_c/2π (β_L = 1, β_c = 0.5, Φ = Φ₀/4): on its steps the SQUID's
    voltage is locked to the drive, V = (n/m) h f/2e exactly (the Josephson relation, with CODATA's exact
    h and e written here): the first step (n = 1) at 2.5 and 2.7 I₀ and the half step at 1.7 and 1.8 I₀
    (two junctions in a loop lock at fractions too), within pendula's error plus 1e-10 relative."""
    sq = _squid(1.0, 0.5)
    f = sq.characteristic_frequency / (2 * math.pi)
    h_over_2e = 6.62607015e-34 / (2 * 1.602176634e-19)
    currents = np.array([1.7, 1.8, 2.5, 2.7]) * I0
    r = sq.iv_curve(currents, flux=0.25, rf_current=1.5 * I0, rf_frequency=f)
    for v, e, n in zip(r.voltage.values[0], r.voltage_err.values[0], (0.5, 0.5, 1.0, 1.0)):
        assert abs(v - n * f * h_over_2e) <= e + 1e-10 * n * f * h_over_2e, (v / (f * h_over_2e), e)
    with pytest.raises(ValueError, match="rf_current"):
        sq.iv_curve(currents, rf_frequency=f)


def test_bias_exactly_at_the_static_critical_current_is_a_hard_case():
    """At I = Ic(Φ) the running state is born (a saddle-node on the cycle): the passage by the fold's
    ghost takes forever: started from rest the SQUID creeps towards the fold, and the voltage is zero
    within its error (no smaller than the creep's drift), finite, and below 1e-4 I₀R."""
    sq = _squid(1.0, 0.5)
    ic = sq.critical_current(0.3)
    r = sq.iv_curve([ic], flux=0.3)
    v, e = float(r.voltage[0, 0]), float(r.voltage_err[0, 0])
    assert np.isfinite(v) and np.isfinite(e)
    assert abs(v) <= e + 1e-12 * I0 * R
    assert abs(v) < 1e-4 * I0 * R


def test_noisy_shapiro_step_keeps_its_locked_voltage_at_low_temperature():
    """At 0.1 K (kT/E_J = 4e-4) the first Shapiro step (2.6 I₀, as in the noiseless test) stays locked:
    the paths' mean voltage is fΦ₀ within four standard errors plus 1e-3 (the step's noise-induced slips
    are exponentially rare at this temperature; the default step resolves the drive)."""
    sq = _squid(1.0, 0.5, temperature=0.1)
    f = sq.characteristic_frequency / (2 * math.pi)
    h_over_2e = 6.62607015e-34 / (2 * 1.602176634e-19)
    r = sq.iv_curve([2.6 * I0], flux=0.25, rf_current=1.5 * I0, rf_frequency=f, paths=4, seed=1)
    v, e = float(r.voltage[0, 0]), float(r.voltage_err[0, 0])
    assert abs(v - f * h_over_2e) < 4 * e + 1e-3 * f * h_over_2e, (v / (f * h_over_2e), e)

"""The asymmetric dc SQUID (unequal junctions, an unevenly split loop) against references written here.

The static reference is a brute-force constrained maximisation written from the circuit alone: junction k
carries I_k = I₀(1 ∓ α_I) sin φ_k at rest, I₁ + I₂ = i, and the fluxoid condition
φ₁ − φ₂ = 2πΦ/Φ₀ + (πβ_L/2)[(1 + η) i₂ − (1 − η) i₁] (arm inductances (1 ∓ η)L/2).  Eliminating i at
fixed x = φ₁ − φ₂ leaves one equation A sin φ₁ + B cos φ₁ = C with its two roots in closed form; the bias
i(x) = Σ I_k sin φ_k is maximised over x on the points whose Hessian (diag(ε_k cos φ_k) plus the loop's
spring) is positive definite: a grid of 400001 points over every flux state, then SciPy's bounded Brent
on the best cell to xatol 1e-14.  The dynamic reference is SciPy's DOP853 (rtol 1e-12) on the two RCSJ
junctions, the arm currents solved from the same two linear conditions at every step.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

from pendula.junction import FLUX_QUANTUM
from pendula.squid import DCSquid, squid_critical_current

I0 = 10e-6
R = 10.0


def _arm_currents(x, x0, i, beta_l, eta):
    """i₁, i₂ from i₁ + i₂ = i and x − x0 = (πβ_L/2)[(1 + η) i₂ − (1 − η) i₁]."""
    a = np.array([[1.0, 1.0], [-(1 - eta), 1 + eta]]) * np.array([[1.0], [math.pi * beta_l / 2]])
    return np.linalg.solve(a, [i, x - x0])


def _reference_critical_current(beta_l, flux, a_i=0.0, eta=0.0):
    k = 1 / (math.pi * beta_l)
    x0 = 2 * math.pi * flux
    e1, e2 = 1 - a_i, 1 + a_i
    # the shares of the bias when x = x0 (no circulating current), from the fluxoid condition
    b1, b2 = _arm_currents(x0, x0, 1.0, beta_l, eta)

    def points(x, branch):
        # b2 (ε₁ sin φ₁) − b1 (ε₂ sin φ₂) = −k (x − x0), φ₂ = φ₁ − x  (the bias eliminated)
        x = np.asarray(x, dtype=float)
        a = b2 * e1 - b1 * e2 * np.cos(x)
        b = b1 * e2 * np.sin(x)
        rho, psi = np.hypot(a, b), np.arctan2(b, a)
        with np.errstate(invalid="ignore", divide="ignore"):
            c = -k * (x - x0) / rho
        ok = np.abs(c) <= 1
        c = np.clip(c, -1, 1)
        p1 = (np.arcsin(c) if branch == 0 else math.pi - np.arcsin(c)) - psi
        p2 = p1 - x
        i = e1 * np.sin(p1) + e2 * np.sin(p2)
        h11, h22 = e1 * np.cos(p1) + k, e2 * np.cos(p2) + k
        return i, ok & (h11 > 0) & (h11 * h22 - k * k > 0)

    w = 4 * math.pi * beta_l + 0.1
    xs = np.linspace(x0 - w, x0 + w, 400001)
    best = -np.inf
    for br in (0, 1):
        i, stable = points(xs, br)
        iv = np.where(stable, i, -np.inf)
        j = int(np.argmax(iv))
        if iv[j] == -np.inf:
            continue
        lo, hi = xs[max(j - 1, 0)], xs[min(j + 1, xs.size - 1)]
        r = minimize_scalar(lambda x: -float(points(x, br)[0]), bounds=(lo, hi), method="bounded",
                            options={"xatol": 1e-14})
        best = max(best, iv[j], -r.fun)
    return best


def _asymmetric_cases(beta_l, n_random):
    rng = np.random.default_rng(int(beta_l * 100) + 41)
    cases = [(0.3, 0.3, 0.0), (0.5, 0.0, 0.4), (0.5, 0.3, 0.4), (0.1, -0.5, 0.2)]
    cases += [(float(f), float(a), float(e)) for f, a, e in
              zip(rng.uniform(-0.5, 0.5, n_random), rng.uniform(-0.7, 0.7, n_random), rng.uniform(-0.7, 0.7, n_random))]
    return cases


def test_asymmetric_critical_current_matches_brute_force_maximisation():
    """β_L = 1, two special and one seeded random (flux, α_I, η): 1e-10 relative (measured 3e-15; the
    sweep over β_L below, in make test-full, measured 4e-15 at worst)."""
    for flux, a_i, eta in _asymmetric_cases(1.0, 1)[2:]:
        ic = squid_critical_current(1.0, flux, current_asymmetry=a_i, inductance_asymmetry=eta)
        ref = _reference_critical_current(1.0, flux, a_i, eta)
        assert abs(ic / ref - 1) < 1e-10, (flux, a_i, eta, ic, ref)


@pytest.mark.parametrize("beta_l", [0.1, 0.5, 1.0, 2.0])
def test_asymmetric_critical_current_matches_brute_force_maximisation_sweep(beta_l):
    """β_L = 0.1, 0.5, 1, 2; four special and six seeded random (flux, α_I, η) each: 1e-10 relative."""
    for flux, a_i, eta in _asymmetric_cases(beta_l, 6):
        ic = squid_critical_current(beta_l, flux, current_asymmetry=a_i, inductance_asymmetry=eta)
        ref = _reference_critical_current(beta_l, flux, a_i, eta)
        assert abs(ic / ref - 1) < 1e-10, (beta_l, flux, a_i, eta, ic, ref)


@pytest.mark.parametrize("a_i", [0.2, -0.6])
def test_small_screening_tends_to_the_two_unequal_junctions_law(a_i):
    """β_L → 0: Ic = √(I₁² + I₂² + 2I₁I₂ cos(2πΦ/Φ₀)), I₁,₂ = I₀(1 ∓ α_I), whatever η (the loop has no
    inductance to split); the correction is of order β_L (here 1e-6)."""
    i1, i2 = 1 - a_i, 1 + a_i
    for flux in (0.15, 0.35, 0.5):
        law = math.sqrt(i1 * i1 + i2 * i2 + 2 * i1 * i2 * math.cos(2 * math.pi * flux))
        for eta in (0.0, 0.5):
            ic = squid_critical_current(1e-6, flux, current_asymmetry=a_i, inductance_asymmetry=eta)
            assert abs(ic - law) < 1e-5, (flux, eta, ic, law)


def test_swapping_the_junctions_mirrors_the_flux():
    """Junction 1 ↔ 2 is (α_I, η, Φ) → (−α_I, −η, −Φ): the same SQUID, the same Ic to rounding; the
    asymmetric SQUID's lobe is shifted off zero flux (Ic(Φ) ≠ Ic(−Φ))."""
    for flux in (0.12, 0.31):
        a = squid_critical_current(1.0, flux, current_asymmetry=0.3, inductance_asymmetry=0.4)
        b = squid_critical_current(1.0, -flux, current_asymmetry=-0.3, inductance_asymmetry=-0.4)
        assert abs(a / b - 1) < 1e-12
        c = squid_critical_current(1.0, -flux, current_asymmetry=0.3, inductance_asymmetry=0.4)
        assert abs(a / c - 1) > 1e-3


def test_nearly_equal_junctions_at_the_seam_are_a_hard_case():
    """α_I = 1e-9: the rest points' parametrisation of unequal junctions turns by π across a width of 1e-9
    at x = π; the flux states are still all found (β_L = 2 near half a quantum, two of them)."""
    for flux in (0.45, 0.5):
        ic = squid_critical_current(2.0, flux, current_asymmetry=1e-9)
        ref = _reference_critical_current(2.0, flux, 1e-9, 0.0)
        assert abs(ic / ref - 1) < 1e-10, (flux, ic, ref)


def test_asymmetries_outside_the_open_interval_are_refused_by_name():
    for name in ("current_asymmetry", "resistance_asymmetry", "inductance_asymmetry"):
        for bad in (1.0, -1.0, 1.5):
            with pytest.raises(ValueError, match=name):
                DCSquid(I0, R, 1e-13, 1e-10, **{name: bad})
        with pytest.raises(ValueError, match=name):
            DCSquid(I0, R, 1e-13, 1e-10, **{name: float("nan")})
    with pytest.raises(ValueError, match="current_asymmetry"):
        squid_critical_current(1.0, 0.1, current_asymmetry=-1.0)
    with pytest.raises(TypeError, match="inductance_asymmetry"):
        squid_critical_current(1.0, 0.1, inductance_asymmetry="0.2")


def test_laboratory_units_of_the_asymmetric_squid():
    sq = DCSquid(I0, R, 1e-13, 1.0e-10, current_asymmetry=0.2, inductance_asymmetry=-0.3)
    ref = _reference_critical_current(sq.beta_l, 0.3, 0.2, -0.3)
    assert abs(sq.critical_current(0.3) / (I0 * ref) - 1) < 1e-10
    net = sq.network(4e-6, 0.3)
    assert net.eps.tolist() == [0.8, 1.2]
    assert np.allclose(net.bias, [0.4 * 0.35, 0.4 * 0.65], rtol=1e-15, atol=0)
    assert "alpha_i=0.2" in repr(sq)


# ------------------------------------------------------------------ the dynamic curves


def _squid(beta_l, beta_c, **asym):
    c = beta_c * FLUX_QUANTUM / (2 * math.pi * I0 * R * R)
    return DCSquid(I0, R, c, beta_l * FLUX_QUANTUM / (2 * I0), **asym)


def _reference_mean_velocity(beta_l, beta_c, flux, bias, a_i, a_r, eta, t_skip=400.0, span=400.0):
    """⟨s'⟩ (time in 1/ω_c) of β_c(1 ∓ α_R) φ_k'' + (1 ∓ α_R) φ_k' + (1 ∓ α_I) sin φ_k = i_k, the arm
    currents i_k from the fluxoid condition at every step; the period from SciPy's events at s = 2πk."""
    x0 = 2 * math.pi * flux
    e, g = (1 - a_i, 1 + a_i), (1 - a_r, 1 + a_r)

    def rhs(t, y):
        p1, p2, v1, v2 = y
        i1, i2 = _arm_currents(p1 - p2, x0, bias, beta_l, eta)
        return [v1, v2, (i1 - g[0] * v1 - e[0] * math.sin(p1)) / (beta_c * g[0]),
                (i2 - g[1] * v2 - e[1] * math.sin(p2)) / (beta_c * g[1])]

    y0 = [math.pi * flux, -math.pi * flux, 0.0, 0.0]
    a = solve_ivp(rhs, (0, t_skip), y0, method="DOP853", rtol=1e-12, atol=1e-14)

    def crossing(t, y):
        return math.sin((y[0] + y[1]) / 4)

    b = solve_ivp(rhs, (t_skip, t_skip + span), a.y[:, -1], method="DOP853", rtol=1e-12, atol=1e-14,
                  events=crossing)
    te, ye = b.t_events[0], b.y_events[0]
    assert te.size > 20 and np.all(ye[:, 2] + ye[:, 3] > 0)
    return 2 * math.pi * (te.size - 1) / (te[-1] - te[0])


ASYM = {"current_asymmetry": 0.3, "resistance_asymmetry": -0.2, "inductance_asymmetry": 0.4}


def test_asymmetric_v_phi_curve_matches_scipy():
    """β_L = 1, β_c = 0.5, α_I = 0.3, α_R = −0.2, η = 0.4 at I = 2.5 I₀ (running at every flux), at
    Φ = 0.3 Φ₀ and a seeded random flux: within pendula's error estimate plus 1e-10 relative."""
    sq = _squid(1.0, 0.5, **ASYM)
    fluxes = np.array([0.3, np.random.default_rng(41).uniform(-0.5, 0.5)])
    r = sq.v_phi_curve(2.5 * I0, fluxes)
    for f, v, err in zip(fluxes, r.voltage.values, r.voltage_err.values):
        ref = I0 * R * _reference_mean_velocity(1.0, 0.5, f, 2.5, 0.3, -0.2, 0.4)
        assert abs(v - ref) <= err + 1e-10 * ref, (f, v, ref, err)
        assert err <= 1e-9 * ref


def test_asymmetric_iv_curve_matches_scipy_on_its_running_branch():
    """β_L = 0.5, β_c = 2, the same asymmetries, Φ = −0.2 Φ₀ (Ic = 1.994 I₀): the down ramp's running
    branch at 2.1 and 2.6 I₀ against SciPy started from rest at that bias (above Ic the running state is
    the only one: the reference's assertion of a running state checks it)."""
    sq = _squid(0.5, 2.0, **ASYM)
    r = sq.iv_curve([2.1 * I0, 2.6 * I0], flux=-0.2, direction="down")
    for j, i in enumerate((2.1, 2.6)):
        v, err = float(r.voltage[0, j]), float(r.voltage_err[0, j])
        ref = I0 * R * _reference_mean_velocity(0.5, 2.0, -0.2, i, 0.3, -0.2, 0.4, t_skip=800.0)
        assert abs(v - ref) <= err + 1e-10 * ref, (i, v, ref, err)


@pytest.mark.parametrize("a_i, eta, beta_l", [(0.1, 0.2, 1.0), (0.3, -0.1, 0.5), (-0.2, 0.4, 2.0)])
def test_full_critical_current_where_the_arms_shares_match_the_junctions(a_i, eta, beta_l):
    """Closed form: at Φ = −β_L(α_I + η)/2 Φ₀ a circulating current (α_I + η)I₀ with both phases at π/2
    satisfies the fluxoid condition, and the arms then carry (1 ± η)I₀ ∓ (α_I + η)I₀ = I₀(1 ∓ α_I), each
    junction's critical current: Ic is the largest possible, 2I₀ (to rounding)."""
    flux = -beta_l * (a_i + eta) / 2
    ic = squid_critical_current(beta_l, flux, current_asymmetry=a_i, inductance_asymmetry=eta)
    assert abs(ic - 2.0) < 4e-15

"""The elliptic kernel against mpmath (data/elliptic_reference.csv, generated at
60+ digits by data/gen_elliptic_reference.py), closed forms and identities.

Tolerances, with the reason:
- K, E, F(phi|m), E(phi|m), q: 4 eps relative -- README's promise; each is a
  short sequence of correctly rounded operations on well-conditioned terms.
- sn, cn, dn: 8 eps absolute over the whole grid, u up to 1000 periods
  included -- README's promise (absolute, because cn and dn pass through 0
  and are as small as sqrt(mc) = 1e-150 at u = K).
"""

import csv
import warnings

import numpy as np
import pytest

import pendula
from conftest import EPS


def load_reference(data_dir):
    rows = {"K": [], "E": [], "q": [], "F": [], "Einc": [], "j": []}
    with (data_dir / "elliptic_reference.csv").open() as fh:
        rd = csv.reader(fh)
        next(rd), next(rd)
        for r in rd:
            x = float(r[1]) if r[1] else np.nan
            rows[r[0]].append([x, float(r[2])] + [float(v) for v in r[3:] if v])
    return {k: np.array(v) for k, v in rows.items()}


@pytest.fixture(scope="module")
def ref(data_dir):
    return load_reference(data_dir)


def relerr(got, want):
    return np.abs(got - want) / np.abs(want)


@pytest.mark.parametrize("name,func", [("K", pendula.ellipk), ("E", pendula.ellipe), ("q", pendula.nome)])
def test_complete_integrals_and_nome_within_4_eps(ref, name, func):
    mc, want = ref[name][:, 1], ref[name][:, 2]
    got = func(None, mc=mc)
    err = relerr(got, want) / EPS
    assert err.max() <= 4.0, f"{name}: worst {err.max():.2f} eps at mc = {mc[err.argmax()]}"


@pytest.mark.parametrize("name,func", [("F", pendula.ellipf), ("Einc", pendula.ellipeinc)])
def test_incomplete_integrals_within_4_eps(ref, name, func):
    phi, mc, want = ref[name][:, 0], ref[name][:, 1], ref[name][:, 2]
    got = func(phi, None, mc=mc)
    err = relerr(got, want) / EPS
    assert err.max() <= 4.0, f"{name}: worst {err.max():.2f} eps at phi={phi[err.argmax()]}, mc={mc[err.argmax()]}"





def test_jacobi_scalar_parameter_path_agrees_with_reference(ref):
    """The fixed-m fast path (one plan for the whole array) on the same points."""
    u, mc, want = ref["j"][:, 0], ref["j"][:, 1], ref["j"][:, 2:5]
    worst = 0.0
    for value in np.unique(mc):
        sel = mc == value
        sn, cn, dn, _ = pendula.ellipj(u[sel], None, mc=value)
        scale = 1.0 if 0 <= value <= 1 else np.maximum(1.0, np.abs(want[sel]))
        worst = max(worst, (np.abs(np.stack([sn, cn, dn], axis=1) - want[sel]) / scale).max() / EPS)
    assert worst <= 8.0


def test_u_of_1000_periods_keeps_full_accuracy(ref):
    u, mc, want = ref["j"][:, 0], ref["j"][:, 1], ref["j"][:, 2:5]
    inside = (mc >= 0) & (mc <= 1)
    u, mc, want = u[inside], mc[inside], want[inside]
    K = pendula.ellipk(None, mc=mc)
    big = np.abs(u) > 3000 * K
    assert big.sum() >= 30
    sn, cn, dn, _ = pendula.ellipj(u[big], None, mc=mc[big])
    assert np.abs(np.stack([sn, cn, dn], axis=1) - want[big]).max() <= 8 * EPS


def test_mc_1e_300_is_the_separatrix_limit_to_rounding():
    # K(mc) = ln(4/sqrt(mc)) + O(mc ln mc): for mc = 1e-300 exactly ln 4 + 150 ln 10
    assert abs(pendula.ellipk(None, mc=1e-300) / (np.log(4) + 150 * np.log(10)) - 1) <= 2 * EPS
    sn, cn, dn, am = pendula.ellipj(3.0, None, mc=1e-300)
    assert abs(sn - np.tanh(3.0)) <= 2 * EPS and abs(cn - 1 / np.cosh(3.0)) <= 2 * EPS
    assert abs(am - np.arctan(np.sinh(3.0))) <= 4 * EPS


def test_dn_at_K_is_sqrt_mc_to_relative_accuracy():
    for mc in [0.5, 1e-8, 1e-100, 1e-300]:
        K = pendula.ellipk(None, mc=mc)
        sn, cn, dn, _ = pendula.ellipj(K, None, mc=mc)
        assert abs(dn / np.sqrt(mc) - 1) <= 4 * EPS
        assert sn == pytest.approx(1.0, abs=2 * EPS)


def test_identities_hold_to_a_few_eps():
    rng = np.random.default_rng(3)
    u = rng.uniform(-50, 50, 4000)
    m = rng.uniform(0, 1, 4000)
    sn, cn, dn, am = pendula.ellipj(u, m)
    assert np.abs(sn**2 + cn**2 - 1).max() <= 4 * EPS
    assert np.abs(dn**2 + m * sn**2 - 1).max() <= 4 * EPS
    assert np.abs(np.sin(am) - sn).max() <= 1e3 * EPS  # am up to ~70: sin loses |am| ulps
    # Legendre's relation E K' + E' K - K K' = pi/2
    m = np.linspace(0.01, 0.99, 99)
    K, E = pendula.ellipk(m), pendula.ellipe(m)
    Kp, Ep = pendula.ellipk(1 - m), pendula.ellipe(1 - m)
    assert np.abs(E * Kp + Ep * K - K * Kp - np.pi / 2).max() <= 8 * EPS


def test_limits_m_to_0_and_m_to_1():
    u = np.linspace(-20, 20, 401)
    sn, cn, dn, am = pendula.ellipj(u, 0.0)
    assert np.abs(sn - np.sin(u)).max() <= 2 * EPS and np.abs(cn - np.cos(u)).max() <= 2 * EPS
    assert np.abs(dn - 1.0).max() <= 2 * EPS and np.abs(am - u).max() <= 8 * EPS * 20
    sn, cn, dn, am = pendula.ellipj(u, 1.0)
    assert np.abs(sn - np.tanh(u)).max() <= 2 * EPS and np.abs(dn - 1 / np.cosh(u)).max() <= 2 * EPS
    assert pendula.ellipk(0.0) == np.pi / 2 and abs(pendula.ellipe(0.0) / (np.pi / 2) - 1) <= 4 * EPS
    assert pendula.ellipe(1.0) == 1.0 and np.isinf(pendula.ellipk(1.0))
    assert pendula.nome(0.0) == 0.0 and pendula.nome(1.0) == 1.0


def test_amplitude_is_continuous_and_monotone_for_rotation():
    u = np.linspace(0, 200, 200001)
    for m in [0.0, 0.5, 0.999, 1 - 1e-12]:
        am = pendula.ellipj(u, m)[3]
        assert np.all(np.diff(am) > 0), m


def test_closed_forms_of_the_lemniscatic_case():
    from math import gamma, pi, sqrt
    g = gamma(0.25)
    assert abs(pendula.ellipk(0.5) / (g * g / (4 * sqrt(pi))) - 1) <= 2 * EPS
    assert abs(pendula.ellipe(0.5) / (pi**1.5 / g**2 + g**2 / (8 * sqrt(pi))) - 1) <= 4 * EPS
    assert abs(pendula.nome(0.5) / np.exp(-pi) - 1) <= 4 * EPS


def test_phi_beyond_half_pi_uses_quasi_periodicity():
    m = 0.8
    K, E = pendula.ellipk(m), pendula.ellipe(m)
    for j in [1, 2, -3, 50]:
        assert pendula.ellipf(j * np.pi + 0.4, m) == pytest.approx(2 * j * K + pendula.ellipf(0.4, m), rel=4 * EPS)
        assert pendula.ellipeinc(j * np.pi + 0.4, m) == pytest.approx(2 * j * E + pendula.ellipeinc(0.4, m), rel=4 * EPS)


def test_broadcasting_and_scalars():
    sn, cn, dn, am = pendula.ellipj(np.zeros((3, 1)), np.array([0.1, 0.5]))
    assert sn.shape == (3, 2)
    assert isinstance(pendula.ellipk(0.3), np.floating)
    assert pendula.ellipf(np.ones((2, 2)), 0.5).shape == (2, 2)
    # integer and list input are converted
    assert pendula.ellipk([0, 0]).tolist() == [np.pi / 2, np.pi / 2]


# ---------------------------------------------------------------- bad input

def test_out_of_domain_gives_nan_and_one_runtime_warning():
    with pytest.warns(RuntimeWarning, match="ellipk"):
        assert np.isnan(pendula.ellipk(1.5))
    with pytest.warns(RuntimeWarning, match="ellipe"):
        assert np.isnan(pendula.ellipe(2.0))
    with pytest.warns(RuntimeWarning, match="nome"):
        assert np.isnan(pendula.nome(-0.1))
    with pytest.warns(RuntimeWarning, match="ellipf"):
        assert np.isnan(pendula.ellipf(1.2, 4.0))   # sin^2 phi > 1/m
    with pytest.warns(RuntimeWarning, match="ellipj"):
        assert np.isnan(pendula.ellipj(1e300, 0.5)[0])  # beyond 2**48 half periods


def test_nan_in_gives_nan_out_without_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert np.isnan(pendula.ellipk(np.nan))
        assert np.all(np.isnan(pendula.ellipj(np.nan, 0.5)))
        assert np.all(np.isnan(pendula.ellipj(1.0, np.nan)))


@pytest.mark.parametrize("bad", ["0.5", b"0.5", np.array(["a"]), np.array([object()]), 1 + 2j])
def test_non_numbers_are_a_type_error(bad):
    with pytest.raises(TypeError):
        pendula.ellipk(bad)
    with pytest.raises(TypeError):
        pendula.ellipj(bad, 0.5)


def test_m_and_mc_that_disagree_are_a_value_error():
    with pytest.raises(ValueError, match="mc"):
        pendula.ellipk(0.3, mc=0.5)
    with pytest.raises(ValueError, match="broadcast"):
        pendula.ellipj(np.zeros(3), np.zeros(2))
    with pytest.raises(TypeError, match="parameter"):
        pendula.ellipk(None)


def test_gsl_peer_does_not_abort_on_bad_input():
    """GSL's default handler would abort the process here; pendula switched it off."""
    from pendula import _kernel
    sn, cn, dn, bad = _kernel.gsl_elljac_v(np.array([0.5, 0.5]), np.array([0.5, 7.0]))
    assert bad == 1 and np.isnan(sn[1]) and np.isfinite(sn[0])
    k, bad = _kernel.gsl_kcomp_v(np.array([2.0]))
    assert bad == 1 and np.isnan(k[0])


def test_F_beyond_m_1_next_to_the_edge_of_its_real_domain():
    """F(phi|m) for m > 1 with |sin phi| just below 1/sqrt(m): dF/dphi = 1/D,
    D^2 = 1 - m sin^2 phi -> 0, amplified the rounding of sin and cos (up to
    4e6 eps on the random grid, at exactly representable phi and m).  With D^2
    from the double-double sine and cosine: within 4 eps relative, against
    mpmath at 40 digits, at random m in (1, 1e3) and phi within 1e-15..1e-2
    (relative) of the edge."""
    mp = pytest.importorskip("mpmath")
    mp.mp.dps = 40
    rng = np.random.default_rng(1123)
    worst = 0.0
    for _ in range(60):
        m = float(1.0 + 10 ** rng.uniform(-12, 3))
        edge = float(mp.asin(1 / mp.sqrt(m)))
        phi = float(edge * (1 - 10 ** rng.uniform(-15, -2))) * (1 if rng.uniform() < 0.5 else -1)
        got = pendula.ellipf(phi, m)
        ref = mp.re(mp.ellipf(mp.mpf(phi), mp.mpf(m)))
        worst = max(worst, abs(float((got - ref) / ref)) / EPS)
    assert worst <= 4.0, f"{worst:.3g} eps"

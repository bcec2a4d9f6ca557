"""Mathieu characteristic values and the transmon against independent references.

References: data/mathieu_reference.csv and data/transmon_reference.csv
(data/gen_mathieu_reference.py: mpmath at 50 and 40 digits, Jacobi
eigenvalues or the Hill continued fraction; Abramowitz and Stegun's Table
20.1 as printed), closed forms (q = 0, the free rotor), and pendula's own
integrated Floquet multipliers for the vibrating pivot.
"""

import csv
import math
import pathlib
import warnings

import mpmath
import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import pendula

DATA = pathlib.Path(__file__).resolve().parents[1] / "data"
EPS = np.finfo(float).eps


def _rows(name):
    with open(DATA / name) as f:
        return list(csv.DictReader(f))


MATHIEU = _rows("mathieu_reference.csv")
TRANSMON = _rows("transmon_reference.csv")


def _ours(row):
    f = pendula.mathieu_a if row["kind"] == "a" else pendula.mathieu_b
    return float(f(float(row["nu"]), float(row["q"])))


def _error(row):
    """Error in units of eps: relative where |a| > 1, absolute otherwise.

    The value's own conditioning in q (q is a double: its rounding moves the
    value by |q da/dq| eps / 2) is not subtracted; it is part of the
    measured figure."""
    ref = float(row["value"])
    return abs(_ours(row) - ref) / max(1.0, abs(ref)) / EPS


# --- the stored references ---------------------------------------------------

def test_reference_values_to_four_eps():
    errs = [(_error(r), r["kind"], r["nu"], r["q"]) for r in MATHIEU]
    worst = max(errs)
    assert worst[0] <= 4.0, f"worst {worst}"


@pytest.mark.parametrize("source", ["integer", "non-integer", "near-integer", "double-point",
                                    "large-order", "huge-q", "published"])
def test_each_region_of_the_reference_is_present(source):
    """The grid finds holes only where it has points: every region is populated."""
    assert sum(r["source"] == source for r in MATHIEU) >= 4


def test_published_values_every_printed_digit():
    for r in MATHIEU:
        if r["source"] != "published":
            continue
        printed = r["printed"]
        digits = len(printed.split(".")[1])
        assert abs(_ours(r) - float(printed)) <= 0.5 * 10.0 ** -digits + 4 * EPS * abs(float(printed)), r


def test_scipy_wrong_value_a5_21():
    """SciPy's mathieu_a(5, 21) returns a_3; the true a_5(21) is 37.462613226."""
    assert abs(pendula.mathieu_a(5, 21.0) - 37.462613226) < 5e-10


def test_double_points_stay_ordered():
    """For q > 0, a_n < b_n+1 even where the two differ by less than an ulp (large q,
    where the difference falls like exp(-4 sqrt(q))): both are correctly rounded, so
    their order survives rounding as a_n <= b_n+1."""
    for q in (60.0, 250.0, 1000.0, 4000.0, 1e5):
        for n in range(4):
            a = pendula.mathieu_a(n, q)
            b = pendula.mathieu_b(n + 1, q)
            assert a <= b, (n, q, a, b)


def test_bound_is_reported_and_small():
    for r in MATHIEU[:60]:
        f = pendula.mathieu_a if r["kind"] == "a" else pendula.mathieu_b
        v, bnd = f(float(r["nu"]), float(r["q"]), bound=True)
        assert 0.0 <= bnd <= 0.25 * EPS * max(1.0, abs(v))


# --- the transmon ---------------------------------------------------------------

def test_transmon_levels_to_1e12():
    worst = 0.0
    for r in TRANSMON:
        t = pendula.Transmon(float(r["EJ_over_EC"]), 1.0, n_g=float(r["n_g"]))
        e = t.levels(int(r["m"]) + 1)[-1]
        ref = float(r["E_over_EC"])
        worst = max(worst, abs(e - ref) / max(1.0, abs(ref)))
    assert worst <= 1e-12, worst


def test_transmon_spectrum_in_one_call_to_four_eps():
    """All six levels at all ten offset charges of each E_J/E_C in one call (the
    kernel's one window per offset charge, its starting values from QL on it)
    against the 40-digit reference: relative where the level exceeds 1, absolute
    otherwise (measured: 0.97 eps)."""
    worst = 0.0
    for ratio in sorted({r["EJ_over_EC"] for r in TRANSMON}, key=float):
        rows = [r for r in TRANSMON if r["EJ_over_EC"] == ratio]
        ngs = sorted({float(r["n_g"]) for r in rows})
        e = pendula.Transmon(float(ratio), 1.0).levels(6, ngs)
        for r in rows:
            ref = mpmath.mpf(r["E_over_EC"])
            got = e[ngs.index(float(r["n_g"])), int(r["m"])]
            worst = max(worst, float(abs(mpmath.mpf(got) - ref) / max(1, abs(ref))) / EPS)
    assert worst <= 4.0, worst


def _charge_basis_levels(ratio, ng, count, ncut=12, dps=40):
    """The lowest levels of 4 (n - n_g)^2 - (E_J/E_C)/2 (|n><n+1| + h.c.), n = -ncut..ncut,
    by mpmath's symmetric eigensolver at dps digits (E_C = 1)."""
    with mpmath.workdps(dps):
        size = 2 * ncut + 1
        h = mpmath.zeros(size, size)
        for i in range(size):
            h[i, i] = 4 * (i - ncut - mpmath.mpf(ng)) ** 2
            if i + 1 < size:
                h[i, i + 1] = h[i + 1, i] = -mpmath.mpf(ratio) / 2
        ev = sorted(mpmath.eigsy(h, eigvals_only=True))
        return ev[:count]


@pytest.mark.parametrize("ng", [0.5, 0.5 - 1e-9, 0.0])
def test_transmon_nearly_degenerate_pairs_in_one_call(ng):
    """E_J/E_C = 1e-3: at n_g = 1/2 the levels come in pairs split by (E_J/E_C)^k, the
    upper pairs closer than an ulp, where the shared certification of the spectrum
    cannot separate them and each level takes its own path.  Ten levels in one call
    against a 40-digit charge-basis diagonalisation (25 charge states: the cut-off
    coupling is 1e-3 against levels 400 apart), to 4 eps (relative above 1)."""
    ours = pendula.Transmon(1e-3, 1.0).levels(10, [ng])[0]
    ref = _charge_basis_levels("0.001", ng, 10)
    worst = max(float(abs(mpmath.mpf(o) - r) / max(1, abs(r))) / EPS for o, r in zip(ours, ref))
    assert worst <= 4.0, worst


def test_transmon_charge_dispersion_to_1e10():
    import mpmath as mp
    worst = 0.0
    with mp.workdps(45):   # the stored levels carry 40 digits: parse them all
        ref = {(r["EJ_over_EC"], r["n_g"], r["m"]): mp.mpf(r["E_over_EC"]) for r in TRANSMON}
        for ratio in ("1", "5", "20", "50", "100"):
            t = pendula.Transmon(float(ratio), 1.0)
            for m in range(6):
                exact = float(ref[(ratio, "0.5", str(m))] - ref[(ratio, "0", str(m))])
                got = float(t.charge_dispersion(m))
                worst = max(worst, abs(got - exact) / abs(exact))
    assert worst <= 1e-10, worst


def test_dispersion_where_it_is_1e12_of_the_spacing():
    """At E_J/E_C = 100 the ground band is 1e-11 of the level spacing: a difference
    of two doubles would keep no digit of it."""
    t = pendula.Transmon(100.0, 1.0)
    eps0 = float(t.charge_dispersion(0))
    assert 0 < eps0 < 1e-9 * float(t.transition())


def test_free_rotor_levels():
    for ng in (0.0, 0.1, 0.25, 0.5, 0.8):
        t = pendula.Transmon(0.0, 2.0, n_g=ng)
        k = np.arange(-10, 11)
        exact = np.sort(4 * 2.0 * (k - ng) ** 2)[:8]
        np.testing.assert_allclose(t.levels(8), exact, rtol=4 * EPS, atol=4 * EPS)


def test_harmonic_limit():
    """E_J >> E_C: E_m ~ -E_J + sqrt(8 E_J E_C)(m + 1/2) - E_C (6m^2 + 6m + 3)/12
    (Koch et al., eq. 2.11); the anharmonicity tends to -E_C, the error as sqrt(E_C/E_J)."""
    prev = None
    for ratio in (1e3, 1e4, 1e5, 1e6):
        t = pendula.Transmon(ratio, 1.0)
        alpha = float(t.anharmonicity())
        dev = abs(alpha + 1.0)
        assert dev < 2.0 / math.sqrt(ratio), (ratio, alpha)
        if prev is not None:
            assert dev < prev / 2.5
        prev = dev
        e = t.levels(3)
        for m in range(3):
            approx = -ratio + math.sqrt(8 * ratio) * (m + 0.5) - (6 * m * m + 6 * m + 3) / 12
            assert abs(e[m] - approx) < 2.0 * (m + 1) ** 3 / math.sqrt(ratio)


def test_koch_asymptotic_dispersion_approaches_the_exact_one():
    r = []
    for ratio in (20.0, 50.0, 100.0, 200.0):
        t = pendula.Transmon(ratio, 1.0)
        r.append(t.charge_dispersion_asymptotic(0) / float(t.charge_dispersion(0)))
    assert all(x > 1 for x in r) and r == sorted(r, reverse=True) and r[-1] < 1.03


def test_transmon_spectra_as_xarray():
    pytest.importorskip("xarray")
    t = pendula.Transmon(10.0, 1.0)
    da = t.spectrum_vs_ng(np.linspace(0, 1, 5), 3)
    assert da.dims == ("n_g", "level")
    np.testing.assert_array_equal(da.values[0], da.values[-1])   # period 1 in n_g
    dr = t.spectrum_vs_ratio([0.0, 10.0], 3, n_g=0.0)
    np.testing.assert_allclose(dr.sel(EJ_over_EC=10.0).values, t.levels(3), rtol=1e-15)


# --- properties -------------------------------------------------------------------

@settings(max_examples=200, deadline=None)
@given(q=st.floats(1e-6, 1e4), n=st.integers(0, 12))
def test_ordering_for_positive_q(q, n):
    a_n = pendula.mathieu_a(n, q)
    b_n1 = pendula.mathieu_b(n + 1, q)
    a_n1 = pendula.mathieu_a(n + 1, q)
    assert a_n <= b_n1 <= a_n1


@settings(max_examples=200, deadline=None)
@given(q=st.floats(1e-6, 1e5), m=st.integers(0, 10))
def test_symmetry_in_q(q, m):
    """a_2m(-q) = a_2m(q), b_2m+2(-q) = b_2m+2(q), a_2m+1(-q) = b_2m+1(q) (DLMF 28.2.26)."""
    tol = 4 * EPS * max(1.0, q)
    assert abs(pendula.mathieu_a(2 * m, -q) - pendula.mathieu_a(2 * m, q)) <= tol
    assert abs(pendula.mathieu_b(2 * m + 2, -q) - pendula.mathieu_b(2 * m + 2, q)) <= tol
    assert abs(pendula.mathieu_a(2 * m + 1, -q) - pendula.mathieu_b(2 * m + 1, q)) <= tol


@settings(max_examples=200, deadline=None)
@given(q=st.floats(1e-6, 1e4), nu=st.floats(0.001, 30.0).filter(lambda x: x != int(x)))
def test_non_integer_order_is_even_in_q_and_a_equals_b(q, nu):
    tol = 4 * EPS * max(1.0, q, nu * nu)
    assert abs(pendula.mathieu_a(nu, -q) - pendula.mathieu_a(nu, q)) <= tol
    assert pendula.mathieu_a(nu, q) == pendula.mathieu_b(nu, q)


@settings(max_examples=100, deadline=None)
@given(q=st.floats(0.01, 100.0), n=st.integers(1, 8))
def test_continuity_in_order_at_integers(q, n):
    """For q > 0, lambda_nu -> a_n as nu -> n from above and -> b_n from below."""
    d = 1e-7
    scale = max(1.0, abs(pendula.mathieu_a(n, q)))
    slope = 4 * (n + 1) + 4 * q   # |d lambda / d nu| is at most about 2 nu + 2|q|
    assert abs(pendula.mathieu_a(n + d, q) - pendula.mathieu_a(n, q)) <= slope * d + 8 * EPS * scale
    assert abs(pendula.mathieu_a(n - d, q) - pendula.mathieu_b(n, q)) <= slope * d + 8 * EPS * scale


@settings(max_examples=150, deadline=None)
@given(q=st.floats(-1e3, 1e3), nu=st.floats(0.01, 20.0).filter(lambda x: abs(x - round(x)) > 1e-3))
def test_exponent_inverts_the_characteristic_value(q, nu):
    n = int(nu)
    lo, hi = pendula.mathieu_a(n, abs(q)), pendula.mathieu_b(n + 1, abs(q))
    # a band narrower than a's rounding (large |q|, low bands: exponentially
    # narrow) cannot say which nu a double means: only resolvable bands count
    assume(hi - lo > 1e-6 * max(1.0, abs(lo), abs(q)))
    a = pendula.mathieu_a(nu, q)
    back = pendula.mathieu_exponent(a, q)
    # d nu / d a is 1 / (d lambda / d nu): the inverse loses what the band's slope loses
    lam1, lam2 = pendula.mathieu_a(nu - 1e-4, q), pendula.mathieu_a(nu + 1e-4, q)
    slope = abs(lam2 - lam1) / 2e-4
    assert abs(back - nu) <= 16 * EPS * max(1.0, abs(a), abs(q)) / slope + 4 * EPS * nu


def test_exponent_is_nan_in_the_tongues_without_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        nu = pendula.mathieu_exponent([0.0, 1.0, -10.0], 1.0)   # b_1 < 0, 1 < a_1; a < a_0
    assert np.all(np.isnan(nu))


def test_exponent_at_q_zero():
    assert pendula.mathieu_exponent(2.25, 0.0) == 1.5


# --- the vibrating pivot ------------------------------------------------------------

def _kapitza_threshold(eps_, amp):
    """The lowest pivot frequency at which the standing pendulum is stable:
    -4 eps / Omega^2 = a_0(2 amp) (the linearisation about theta = pi is
    Mathieu's equation with a = -4 eps/Omega^2, q = 2 amp, z = Omega t/2)."""
    return math.sqrt(-4.0 * eps_ / float(pendula.mathieu_a(0, 2.0 * amp)))


def _trace(eps_, amp, omega):
    sc = pendula.Scene(eps=eps_, theta0=math.pi, v0=0.0, pivot_amplitude=amp, pivot_frequency=omega)
    po = pendula.periodic_orbit(sc, guess=(math.pi, 0.0), rtol=1e-13, atol=1e-14)
    return float(np.trace(po.monodromy)) - 2.0


def test_kapitza_threshold_against_integrated_multipliers():
    """The monodromy's trace passes 2 (a multiplier +1) exactly at the a_0 boundary."""
    eps_, amp = 1.0, 0.1
    om = _kapitza_threshold(eps_, amp)
    lo, hi = om * (1 - 1e-3), om * (1 + 1e-3)
    flo, fhi = _trace(eps_, amp, lo), _trace(eps_, amp, hi)
    assert flo > 0 > fhi   # unstable (real multipliers) below, stable above
    for _ in range(6):     # secant on the trace: the root is simple
        mid = hi - fhi * (hi - lo) / (fhi - flo)
        fm = _trace(eps_, amp, mid)
        lo, flo, hi, fhi = hi, fhi, mid, fm
        if abs(hi - lo) < 1e-13 * om:
            break
    assert abs(hi - om) <= 1e-10 * om, (hi, om)


def test_chart_agrees_with_integrated_multipliers():
    """Upright pendulum on a pivot: stable (both multipliers on the unit circle) exactly
    where the characteristic exponent of a = -4 eps/Omega^2, q = 2 amp is real, over
    several tongues."""
    for amp in (0.3, 1.5, 2.7, 3.9, 5.1):
        for om in (0.8, 2.0, 4.0):
            sc = pendula.Scene(theta0=math.pi, pivot_amplitude=amp, pivot_frequency=om)
            po = pendula.periodic_orbit(sc, guess=(math.pi, 0.0))
            up = np.max(np.abs(po.multipliers)) < 1 + 1e-8
            nu = pendula.mathieu_exponent(-4 / om ** 2, 2 * amp)
            assert up == bool(np.isfinite(nu)), (amp, om, po.multipliers, nu)


# --- bad input -------------------------------------------------------------------

def test_nan_in_gives_nan_out_silently():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert np.isnan(pendula.mathieu_a(np.nan, 1.0))
        assert np.isnan(pendula.mathieu_b(2, np.nan))
        assert np.isnan(pendula.mathieu_exponent(np.nan, 1.0))


def test_negative_order_is_refused():
    """Refused, not folded: lambda_-nu = lambda_nu holds for non-integer nu, but b_-n = -b_n
    conventions differ between sources; pass abs(nu)."""
    with pytest.warns(RuntimeWarning, match="outside the domain"):
        assert np.isnan(pendula.mathieu_a(-0.5, 1.0))


def test_b0_does_not_exist():
    with pytest.warns(RuntimeWarning, match="outside the domain"):
        assert np.isnan(pendula.mathieu_b(0, 1.0))


def test_q_beyond_range():
    with pytest.warns(RuntimeWarning, match="outside the domain"):
        assert np.isnan(pendula.mathieu_a(1, 2e10))
    with pytest.warns(RuntimeWarning, match="outside the domain"):
        assert np.isnan(pendula.mathieu_a(1, np.inf))


def test_malformed_arguments():
    with pytest.raises(TypeError, match="nu"):
        pendula.mathieu_a("1", 1.0)
    with pytest.raises(TypeError, match="q"):
        pendula.mathieu_a(1, 1j)
    with pytest.raises(ValueError, match="broadcast"):
        pendula.mathieu_a([1, 2, 3], [1.0, 2.0])


@pytest.mark.parametrize("E_C", [0.0, -1.0, np.nan])
def test_transmon_E_C_not_positive(E_C):
    with pytest.raises(ValueError, match="E_C"):
        pendula.Transmon(1.0, E_C)


def test_transmon_negative_E_J():
    with pytest.raises(ValueError, match="E_J"):
        pendula.Transmon(-1.0, 1.0)


def test_transmon_level_count_must_be_whole():
    with pytest.raises(TypeError, match="n_levels"):
        pendula.Transmon(1.0, 1.0).levels(2.0)


def test_broadcasting_and_empty():
    v = pendula.mathieu_a(np.arange(3)[:, None], np.array([0.5, 1.0]))
    assert v.shape == (3, 2)
    assert pendula.mathieu_b(np.array([]), 1.0).shape == (0,)


# --- eigenfunctions and matrix elements -------------------------------------------

@pytest.mark.parametrize("ratio,ng", [(1.0, 0.3), (20.0, 0.0), (20.0, 1.3), (50.0, -0.7)])
def test_matrix_elements_by_hellmann_feynman(ratio, ng):
    """<m|n|m> = n_g - dE_m/dn_g / (8 E_C) and <m|cos phi|m> = -dE_m/dE_J: the
    diagonal elements against central differences of the levels (tested above
    to 1e-12); the difference's own error is about 1e-10."""
    t = pendula.Transmon(ratio, 1.0, n_g=ng)
    h = 1e-5
    d_ng = (pendula.Transmon(ratio, 1.0, n_g=ng + h).levels(4)
            - pendula.Transmon(ratio, 1.0, n_g=ng - h).levels(4)) / (2 * h)
    d_ej = (pendula.Transmon(ratio + h, 1.0, n_g=ng).levels(4)
            - pendula.Transmon(ratio - h, 1.0, n_g=ng).levels(4)) / (2 * h)
    np.testing.assert_allclose(np.diag(t.matrix_elements("n", 4)), ng - d_ng / 8, atol=2e-9)
    np.testing.assert_allclose(np.diag(t.matrix_elements("cos_phi", 4)), -d_ej, atol=2e-9)


def test_wavefunctions_diagonalise_the_hamiltonian():
    """H psi_m = E_m psi_m in the charge basis, the residual at rounding level."""
    t = pendula.Transmon(30.0, 1.5, n_g=0.21)
    n, psi = t.wavefunctions(5)
    e = t.levels(5)
    hpsi = 4 * 1.5 * (n - 0.21) ** 2 * psi
    hpsi[:, 1:] -= 15.0 * psi[:, :-1]
    hpsi[:, :-1] -= 15.0 * psi[:, 1:]
    assert np.max(np.abs(hpsi - e[:, None] * psi)) < 1e-12 * 30
    np.testing.assert_allclose(psi @ psi.T, np.eye(5), atol=1e-14)


def test_free_rotor_wavefunctions_are_charge_states():
    n, psi = pendula.Transmon(0.0, 1.0, n_g=0.2).wavefunctions(3)
    assert [int(n[np.argmax(psi[m])]) for m in range(3)] == [0, 1, -1]


def test_matrix_elements_unknown_operator():
    with pytest.raises(ValueError, match="operator"):
        pendula.Transmon(1.0, 1.0).matrix_elements("sin_phi")


def test_wavefunctions_n_max_too_small():
    with pytest.raises(ValueError, match="n_max"):
        pendula.Transmon(100.0, 1.0).wavefunctions(3, n_max=2)


def test_dispersion_beyond_double_double_resolution_is_nan_with_warning():
    """At E_J/E_C = 600, eps_0 ~ 1e-27 E_C is below the levels' double-double error:
    NaN with a RuntimeWarning, never a difference of rounding errors."""
    t = pendula.Transmon(600.0, 1.0)
    with pytest.warns(RuntimeWarning, match="resolution"):
        assert np.isnan(t.charge_dispersion(0))


def test_exponent_at_huge_order():
    """a near 1e16: the band edges are counted over the rows near a only."""
    nu = pendula.mathieu_exponent(pendula.mathieu_a(5e7 + 0.3, 10.0), 10.0)
    assert abs(nu - (5e7 + 0.3)) <= 4 * EPS * 5e7


# --- the periodic Mathieu functions ---------------------------------------------------

FUNCTIONS = _rows("mathieu_function_reference.csv")


def test_mathieu_functions_against_reference():
    """ce_n, se_n against 30-digit Fourier sums (data/mathieu_function_reference.csv).

    Absolute: the coefficients have unit norm.  16 eps, not 4: each term's
    cos((2m + p) z) carries the rounding of its argument, eps (2m + p) z, and the
    series reaches orders of a few times max(n, sqrt|q|) (measured: 7.5 eps for the
    values, 7.1 eps times max(1, n, sqrt|q|) for the derivatives)."""
    for r in FUNCTIONS:
        f = pendula.mathieu_ce if r["kind"] == "ce" else pendula.mathieu_se
        n, q = int(r["n"]), float(r["q"])
        v, dv = f(n, q, float(r["z"]))
        assert abs(v - float(r["value"])) <= 16 * EPS, r
        assert abs(dv - float(r["derivative"])) <= 16 * EPS * max(1, n, math.sqrt(abs(q))), r


@settings(max_examples=40, deadline=None)
@given(n=st.integers(0, 8), q=st.floats(-50, 50))
def test_mathieu_function_normalisation_and_sign(n, q):
    """The integral of ce_n^2 over [0, 2 pi] is pi (DLMF 28.2.30), ce_n(0) > 0, and
    se_n'(0) > 0: by the trapezoidal rule, exact for these trigonometric polynomials."""
    z = np.linspace(0, 2 * np.pi, 513)[:-1]
    ce, _ = pendula.mathieu_ce(n, q, z)
    assert abs(np.sum(ce ** 2) * 2 * np.pi / 512 - np.pi) < 1e-12
    assert pendula.mathieu_ce(n, q, 0.0)[0] > 0
    if n >= 1:
        se, _ = pendula.mathieu_se(n, q, z)
        assert abs(np.sum(se ** 2) * 2 * np.pi / 512 - np.pi) < 1e-12
        assert pendula.mathieu_se(n, q, 0.0)[1] > 0


def test_mathieu_function_solves_the_equation():
    """y'' + (a - 2q cos 2z) y = 0, y'' by central differences of the derivative."""
    z = np.linspace(0.1, 3.0, 30)
    h = 1e-5
    for n, q in ((2, 3.0), (3, -7.0)):
        a = float(pendula.mathieu_a(n, q))
        y, _ = pendula.mathieu_ce(n, q, z)
        ypp = (pendula.mathieu_ce(n, q, z + h)[1] - pendula.mathieu_ce(n, q, z - h)[1]) / (2 * h)
        assert np.max(np.abs(ypp + (a - 2 * q * np.cos(2 * z)) * y)) < 1e-8 * max(1.0, abs(a))


def test_se_of_order_zero_does_not_exist():
    with pytest.raises(ValueError, match="n"):
        pendula.mathieu_se(0, 1.0, 0.5)


def test_plot_levels_draws_one_line_a_level():
    pytest.importorskip("matplotlib")
    import matplotlib
    matplotlib.use("Agg")
    import pendula.plot
    t = pendula.Transmon(5.0, 1.0)
    ax = pendula.plot.levels(t, count=4, n_g=np.linspace(-1, 1, 41))
    lines = ax.get_lines()
    assert len(lines) == 4
    y0 = lines[0].get_ydata()
    assert min(y0) == 0.0   # from the bottom of the ground band
    # in units of the 0-1 transition at n_g = 1/2 (index 30 of the grid)
    np.testing.assert_allclose(lines[1].get_ydata()[30] - lines[0].get_ydata()[30], 1.0, rtol=1e-12)


def test_flux_tunable_transmon():
    """E_J(flux) = E_J_max |cos(pi flux)| sqrt(1 + d^2 tan^2(pi flux)) (Koch et al., eq. 2.16):
    E_J_max at zero flux, d E_J_max at half a flux quantum, periodic with period 1."""
    for d in (0.0, 0.3):
        assert pendula.Transmon.flux_tunable(30.0, 1.0, 0.0, d).E_J == 30.0
        assert abs(pendula.Transmon.flux_tunable(30.0, 1.0, 0.5, d).E_J - 30.0 * d) < 1e-14
        f = 0.37
        ej = 30.0 * abs(math.cos(math.pi * f)) * math.sqrt(1 + d * d * math.tan(math.pi * f) ** 2)
        assert abs(pendula.Transmon.flux_tunable(30.0, 1.0, f, d).E_J - ej) < 1e-13
        assert abs(pendula.Transmon.flux_tunable(30.0, 1.0, f + 1, d).E_J - ej) < 1e-13


def test_flux_tunable_asymmetry_out_of_range():
    with pytest.raises(ValueError, match="asymmetry"):
        pendula.Transmon.flux_tunable(30.0, 1.0, 0.1, asymmetry=1.5)


def test_phase_wavefunctions_solve_the_equation():
    """-4 E_C psi'' (with the offset charge's phase) - E_J cos(phi) psi = E psi, checked at
    n_g = 0 by spectral differentiation: psi'' = sum -n^2 c_n exp(i n phi)."""
    t = pendula.Transmon(10.0, 1.0)
    phi = np.linspace(-np.pi, np.pi, 65)[:-1]
    psi = t.wavefunctions_phase(phi, 3)
    n, c = t.wavefunctions(3)
    dd = (c * -(n ** 2.0)) @ np.exp(1j * np.outer(n, phi)) / math.sqrt(2 * math.pi)
    e = t.levels(3)
    resid = -4.0 * dd - 10.0 * np.cos(phi) * psi - e[:, None] * psi
    assert np.max(np.abs(resid)) < 1e-11
    norm = np.sum(np.abs(psi) ** 2, axis=1) * 2 * np.pi / 64
    np.testing.assert_allclose(norm, 1.0, rtol=1e-13)

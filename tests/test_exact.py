"""The exact motion of the conservative pendulum against independent references.

data/exact_reference.csv (data/gen_exact_reference.py) holds mpmath values:
'ode' rows from mpmath's Taylor ODE solver at 40 digits (independent of the
elliptic formulas), 'jac' rows from mpmath's own Jacobi functions at 60+ digits
(long times, the neighbourhood of the separatrix), 'per' rows the periods.

Tolerances, with the reason: theta within 8 eps relative to max(1, |theta|),
v within 8 eps relative to max(1, |v|), the period within 4 eps: every input
is an exact double and the kernel carries the separatrix distance, sqrt(eps)
and the phase in double-double, so nothing grows with t beyond a few roundings
of the final values (measured worst: 3 eps).
"""

import csv
import math

import numpy as np
import pytest

import pendula
from conftest import EPS


def rows(data_dir, kind):
    with (data_dir / "exact_reference.csv").open() as fh:
        rd = csv.reader(ln for ln in fh if not ln.startswith("#"))
        next(rd)
        return [tuple(map(float, r[1:])) for r in rd if r[0] == kind]


@pytest.mark.parametrize("kind", ["ode", "jac"])
def test_theta_and_v_against_mpmath(data_dir, kind):
    data = rows(data_dir, kind)
    assert len(data) >= 12
    worst = 0.0
    for th0, v0, eps, t, th, v in data:
        a, b = pendula.exact_motion(th0, v0, eps, [t])
        worst = max(worst, abs(a[0] - th) / max(1, abs(th)) / EPS, abs(b[0] - v) / max(1, abs(v)) / EPS)
    assert worst <= 8.0, worst


def test_t_of_1000_periods_is_as_accurate_as_t_of_one(data_dir):
    data = [r for r in rows(data_dir, "jac") if abs(r[3]) > 500 * pendula.orbit(*r[:3]).period]
    assert len(data) >= 15
    for th0, v0, eps, t, th, v in data:
        a, b = pendula.exact_motion(th0, v0, eps, [t])
        assert abs(a[0] - th) <= 8 * EPS * max(1, abs(th)) and abs(b[0] - v) <= 8 * EPS * max(1, abs(v))


def test_period_against_4K_over_sqrt_eps_in_mpmath(data_dir):
    for th0, v0, eps, _, per, _ in rows(data_dir, "per"):
        assert abs(pendula.orbit(th0, v0, eps).period / per - 1) <= 4 * EPS


def test_v0_2_exactly_approaches_pi_monotonically_forever():
    t = np.concatenate([np.linspace(0, 40, 4001), [1e3, 1e6, 1e12]])
    theta, v = pendula.exact_motion(0.0, 2.0, 1.0, t)
    assert pendula.orbit(0.0, 2.0).regime == "separatrix"
    assert np.all(np.diff(theta) >= 0) and np.all(theta <= np.pi) and np.all(v >= 0)
    gd = 2 * np.arctan(np.sinh(np.minimum(t, 700.0)))   # theta = 2 gd(t) in closed form
    assert np.abs(theta - gd).max() <= 4 * EPS
    assert theta[-1] == np.pi


def test_v0_2_minus_and_plus_1e_12_give_the_right_periods(data_dir):
    below, above = pendula.orbit(0.0, 2.0 - 1e-12), pendula.orbit(0.0, 2.0 + 1e-12)
    assert below.regime == "libration" and above.regime == "rotation"
    ref = {r[1]: r[4] for r in rows(data_dir, "per")}
    assert abs(below.period / ref[2.0 - 1e-12] - 1) <= 4 * EPS
    assert abs(above.period / ref[2.0 + 1e-12] - 1) <= 4 * EPS
    # the separatrix distance is formed without cancellation: mc = (1 - v0/2)(1 + v0/2) exactly
    v0 = 2.0 - 1e-12
    assert below.mc == pytest.approx((1 - v0 / 2) * (1 + v0 / 2), rel=2 * EPS)


def test_critical_behaviour_of_omega_near_v0_2():
    """omega ~ (pi/2)/ln(4/sqrt(t)) below, pi/ln(4/sqrt(t)) above (Suzuki & Suzuki 2.7, 3.3),
    with corrections O(t ln t): the tolerance is 3 t ln(4/sqrt(t))."""
    for t in [1e-6, 1e-9, 1e-12]:
        v_lo, v_hi = 2.0 - t, 2.0 + t
        t_lo, t_hi = 2.0 - v_lo, v_hi - 2.0    # the distances the doubles really have (exact)
        lo, hi = pendula.orbit(0.0, v_lo).omega, pendula.orbit(0.0, v_hi).omega
        L_lo, L_hi = math.log(4 / math.sqrt(t_lo)), math.log(4 / math.sqrt(t_hi))
        assert lo * L_lo / (math.pi / 2) == pytest.approx(1, abs=3 * t * L_lo)
        assert hi * L_hi / math.pi == pytest.approx(1, abs=3 * t * L_hi)
        assert (hi * L_hi) / (lo * L_lo) == pytest.approx(2, abs=12 * t * L_lo)


def test_released_at_the_double_nearest_pi_falls_off_the_top_like_cosh():
    """pi is not a double: np.pi lies phi0 = 1.2246e-16 below it, so the pendulum
    released there at rest is a libration with mc = sin^2(phi0/2) ~ 3.7e-33 and
    leaves the top as pi - theta = phi0 cosh(t) (the linearisation is exact to
    1e-16 relative while pi - theta < 1e-8).  The turning point is where the
    phase is most sensitive (dF/dphi ~ 1e16): it must come out exactly K."""
    phi0 = 1.2246467991473532e-16
    o = pendula.orbit(np.pi, 0.0)
    assert o.regime == "libration" and o.mc == pytest.approx(np.sin(phi0 / 2) ** 2, rel=1e-15)
    t = np.array([0.0, 5.0, 10.0, 15.0, 20.0])
    theta, v = pendula.exact_motion(np.pi, 0.0, 1.0, t)
    assert np.allclose(np.pi - theta, phi0 * np.cosh(t), rtol=1e-6, atol=2 * EPS * np.pi)


def test_energy_is_conserved_by_the_exact_path_over_a_million_periods():
    """Libration: 16 eps.  Rotation: the angle after 1e6 turns is ~6e6 rad, whose
    own spacing (1e-9) bounds what E(theta, v) can show: 4 spacings."""
    for th0, v0 in [(0.0, 1.0), (0.3, 1.9), (0.0, 1.999999), (0.3, 1.99), (0.0, 2.5)]:
        P = pendula.orbit(th0, v0).period
        t = np.random.default_rng(0).uniform(-1e6 * P, 1e6 * P, 20000)
        theta, v = pendula.exact_motion(th0, v0, 1.0, t)
        E = pendula.energy(theta, v, 1.0)
        E0 = pendula.energy(th0, v0, 1.0)
        tol = 16 * EPS * max(E0, 1) + 4 * np.spacing(np.abs(theta).max())
        assert np.abs(E - E0).max() <= tol


def test_backward_time_and_negative_v0_are_mirror_images():
    t = np.linspace(0, 20, 201)
    a, va = pendula.exact_motion(0.4, 1.3, 1.0, t)
    b, vb = pendula.exact_motion(0.4, -1.3, 1.0, -t)     # reversed motion
    assert np.abs(a - b).max() <= 8 * EPS and np.abs(va + vb).max() <= 8 * EPS
    c, vc = pendula.exact_motion(-0.4, -1.3, 1.0, t)    # reflected motion
    assert np.abs(a + c).max() <= 8 * EPS and np.abs(va + vc).max() <= 8 * EPS


def test_rotation_angle_is_continuous_and_grows():
    t = np.linspace(0, 200, 20001)
    theta, v = pendula.exact_motion(0.0, 2.0 + 1e-9, 1.0, t)
    assert np.all(np.diff(theta) > 0) and theta[-1] > 10 * np.pi


def test_theta0_anywhere_is_the_same_motion_in_another_well():
    t = np.linspace(-5, 5, 101)
    a, va = pendula.exact_motion(0.7, 0.2, 2.0, t)
    th0 = 0.7 + 6 * np.pi            # rounds by up to half a spacing of 19.5
    b, vb = pendula.exact_motion(th0, 0.2, 2.0, t)
    c, vc = pendula.exact_motion(th0 - 6 * np.pi, 0.2, 2.0, t)
    tol = 4 * np.spacing(th0)
    assert np.abs(b - c - 6 * np.pi).max() <= tol and np.abs(vb - vc).max() <= 8 * EPS
    assert np.abs(c - a).max() <= tol


def test_theta_max_matches_2_arcsin_k():
    for v0 in [0.1, 1.0, 1.9, 1.999999]:
        assert pendula.orbit(0.0, v0).theta_max == pytest.approx(2 * math.asin(v0 / 2), rel=4 * EPS)


def test_bad_states_are_value_errors():
    with pytest.raises(ValueError, match="eps"):
        pendula.orbit(0.0, 1.0, -1.0)
    with pytest.raises(ValueError, match="theta0"):
        pendula.exact_motion(np.inf, 1.0, 1.0, [0.0])
    with pytest.raises(TypeError):
        pendula.exact_motion(0.0, "fast", 1.0, [0.0])


# ---------------------------------------------------------------- series

def test_period_series_exact_fractions():
    """1 and 1/16 are printed in Prusa & Tuma (3.13), 11/3072 is the term after them; all ten are
    checked against mpmath's (numerical) Taylor expansion of (2/pi) K(sin^2(theta/2)) at 120
    digits, to 1e-20 relative (the differentiation loses digits, not the series)."""
    from fractions import Fraction as F

    import mpmath as mp
    c = pendula.period_series(9)
    assert c[:3] == (F(1), F(1, 16), F(11, 3072))
    with mp.workdps(120):
        taylor = mp.taylor(lambda x: 2 / mp.pi * mp.ellipk(mp.sin(x / 2) ** 2), 0, 18)
        for j, cj in enumerate(c):
            assert abs(mp.mpf(cj.numerator) / cj.denominator - taylor[2 * j]) < mp.mpf(10) ** -20 * abs(taylor[2 * j])


def test_period_series_converges_to_the_exact_period():
    for th0 in [0.5, 1.0, 2.0]:
        exact = pendula.orbit(th0, 0.0).period
        errs = [abs(pendula.period_from_series(th0, n) / exact - 1) for n in (2, 5, 10, 20)]
        assert errs == sorted(errs, reverse=True)
    assert abs(pendula.period_from_series(1.0, 30) / pendula.orbit(1.0, 0.0).period - 1) <= 8 * EPS


def test_poincare_lindstedt_third_order_is_the_textbook_form():
    h, f = pendula.series.poincare_lindstedt_coefficients(3)
    from fractions import Fraction as F
    # theta = (a + a^3/192) cos wt - (a^3/192) cos 3wt, w = sqrt(eps) (1 - a^2/16)
    assert h[0][1] == 1 and h[0][3] == F(1, 192) and h[1][3] == F(-1, 192)
    assert f[2] == F(-1, 16)


@pytest.mark.parametrize("order", [3, 5, 7])
def test_poincare_lindstedt_error_scales_with_the_next_power_of_a(order):
    t = np.linspace(0, 20, 2001)
    errs = []
    for a in (0.2, 0.1):
        theta, _ = pendula.exact_motion(a, 0.0, 1.0, t)
        errs.append(np.abs(pendula.poincare_lindstedt(a, t, 1.0, order) - theta).max())
    # error ~ a^(order+2) (t-growing secular part included): halving a divides it by ~2^(order+2)
    assert errs[0] / errs[1] == pytest.approx(2 ** (order + 2), rel=0.25)


def test_infinite_and_nan_times():
    """NaN in gives NaN out quietly; an infinite time has no angle (NaN and a
    RuntimeWarning), except on the separatrix, where theta -> pi."""
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        theta, v = pendula.exact_motion(0.0, 1.0, 1.0, [np.nan])
        assert np.isnan(theta[0]) and np.isnan(v[0])
        theta, _ = pendula.exact_motion(0.0, 2.0, 1.0, [np.inf])
        assert theta[0] == np.pi
    with pytest.warns(RuntimeWarning, match="infinite"):
        theta, _ = pendula.exact_motion(0.0, 1.0, 1.0, [np.inf])
    assert np.isnan(theta[0])


def test_v_next_to_its_zeros_keeps_4_eps_of_itself():
    """v = 2 k sqrt(eps) cn(u0 + sqrt(eps) t) next to a turning point, with a
    large velocity scale (eps up to 900): the starting phase u0 = F(phi0) was
    formed in double, and its rounding (eps times a phase of order K) stayed in
    v, up to 18.5 eps of a small |v| on the random grids.  Now in double-double:
    v within 4 eps relative to max(1, |v|), against mpmath (40 digits) at random
    states and at times drawn within 1e-3 K of a turning point."""
    mp = pytest.importorskip("mpmath")
    mp.mp.dps = 40
    rng = np.random.default_rng(20261123)
    worst = 0.0
    for _ in range(25):
        eps = float(10 ** rng.uniform(0.0, 3.0))
        th0 = float(rng.uniform(-3.0, 3.0))
        # a libration: |w| below cos(theta0/2)
        v0 = float(rng.uniform(-0.999, 0.999) * 2.0 * math.sqrt(eps) * math.cos(th0 / 2))
        e, t0, w0 = mp.mpf(eps), mp.mpf(th0), mp.mpf(v0) / (2 * mp.sqrt(eps))
        s0 = mp.sin(t0 / 2)
        m = s0**2 + w0**2
        k = mp.sqrt(m)
        u0 = mp.ellipf(mp.atan2(s0 / k, w0 / k), m)
        K = mp.ellipk(m)
        # a time within 1e-3 K of the turning point (2j + 1) K, j up to 50
        j = int(rng.integers(-50, 50))
        t = float(((2 * j + 1) * K * (1 + mp.mpf(rng.uniform(-1e-3, 1e-3))) - u0) / mp.sqrt(e))
        ref = 2 * k * mp.sqrt(e) * mp.ellipfun("cn", u0 + mp.sqrt(e) * mp.mpf(t), m=m)
        _, v = pendula.exact_motion(th0, v0, eps, [t])
        worst = max(worst, abs(float(v[0] - ref)) / max(1.0, abs(float(ref))) / EPS)
    assert worst <= 4.0, f"{worst:.3g} eps"


@pytest.mark.parametrize("side", ["libration", "rotation"])
def test_v_next_to_the_separatrix_keeps_its_relative_accuracy(side):
    """Next to the separatrix (mc from 1e-15 to 1e-3) v = 2 k sqrt(eps) cn(u|m)
    (dn for a rotation) is small on most of the orbit, and the duplication core
    keeps cn, dn only to 4-8 eps relative there (up to 7 eps of v on the random
    grids); the theta series of pendula_jacobi_theta keep them to ~2.  v within
    4 eps relative to max(1, |v|), against mpmath, at 40 random states with
    eps up to 900 (scales up to 60) and random times over 30 periods."""
    mp = pytest.importorskip("mpmath")
    mp.mp.dps = 50
    rng = np.random.default_rng(7 if side == "libration" else 8)
    worst = 0.0
    for _ in range(40):
        eps = float(10 ** rng.uniform(0.0, 3.0))
        mc = 10 ** rng.uniform(-15, -3)
        w = math.sqrt(1 - mc) if side == "libration" else math.sqrt(1 + mc)
        v0 = float(2 * math.sqrt(eps) * w) * (1 if rng.uniform() < 0.5 else -1)
        e, w0 = mp.mpf(eps), mp.mpf(v0) / (2 * mp.sqrt(mp.mpf(eps)))
        k2 = w0**2
        t = float(rng.uniform(-30, 30) * 4 * math.log(4 / math.sqrt(mc)) / math.sqrt(eps))
        if k2 < 1:
            u = mp.sqrt(e) * mp.mpf(t) + mp.ellipf(mp.atan2(0, w0 / mp.sqrt(k2)), k2)
            ref = 2 * mp.sqrt(k2) * mp.sqrt(e) * mp.ellipfun("cn", u, m=k2)
        else:
            u = mp.sqrt(k2) * mp.sqrt(e) * mp.mpf(t) * mp.sign(w0)
            ref = mp.sign(w0) * 2 * mp.sqrt(k2) * mp.sqrt(e) * mp.ellipfun("dn", u, m=1 / k2)
        _, v = pendula.exact_motion(0.0, v0, eps, [t])
        worst = max(worst, abs(float(v[0] - ref)) / max(1.0, abs(float(ref))) / EPS)
    assert worst <= 4.0, f"{worst:.3g} eps"


# ---------------------------------------------------------------- hard cases (data/hard_cases.csv.gz)

def test_tiny_velocity_does_not_underflow_k_squared():
    """v0 = 1e-208: k^2 = v0^2 / (4 eps) underflowed (k = 0, theta = v = 0): k, theta_max, the
    period and theta(t), v(t) within 4 eps of mpmath, relative to max(|ref|, 2^-1022)."""
    from conftest import assert_hard_cases

    assert_hard_cases("tiny", "reproducer")


def test_tiny_inputs_of_every_orbit_function_hunted():
    """Fresh random |v0|, theta0, eps down to the smallest normal and subnormal (orbit, exact_motion,
    energy, gravity_orbit in the three fields, angle_density, angle_cdf): within 4 eps of mpmath
    (relative to max(|ref|, 2^-1022): a subnormal result is held to its spacing)."""
    from conftest import assert_hard_cases

    assert_hard_cases("tiny", "hunt")


def test_velocity_just_above_the_separatrix_at_long_times():
    """exact_motion 3.6e-15 above the separatrix after 1571 turns: cos^2(theta0/2) in double-double
    (2^-106) left 2^-106 / |1 - k^2| in K and so in the phase per half period (v 5.06 eps, units of
    2 k sqrt(eps)); with it in triple-double v and theta within 4 eps of mpmath."""
    from conftest import assert_hard_cases

    assert_hard_cases("separatrix_long_time", "reproducer")


def test_just_above_the_separatrix_at_long_times_hunted():
    """Fresh random theta0, eps, k^2 - 1 from 1e-15 to 1e-3, t up to 1e3 turns."""
    from conftest import assert_hard_cases

    assert_hard_cases("separatrix_long_time", "hunt")

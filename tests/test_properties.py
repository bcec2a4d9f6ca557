"""Property tests (hypothesis, derandomized): identities and limits that must
hold to a few eps for every input, where grids cannot go.

Tolerances, with the reason:
* sn^2 + cn^2 = 1 and dn^2 + m sn^2 = 1: 4 eps (each function within ~1.5 eps,
  squared and summed);
* sn(u + 2K) = -sn(u): the shift is exact only in double-double, so u + 2K is
  formed from K's double (its rounding times the slope |cn dn| <= 1): 4 eps
  plus 2 eps per unit of |u + 2K| in ulps of the sum;
* F(am(u)) = u: F's condition number at am is 1/dn, so within 8 eps * |u| / dn;
* energy along the exact path: 16 eps relative to the energy's scale (README);
* the flow property exact(t1) then exact(t2 - t1) = exact(t2): theta within
  8 eps relative to max(1, |theta|) times the number of periods crossed + 1.
"""

import math

import numpy as np
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st

import pendula

EPS = np.finfo(float).eps
SETTINGS = dict(max_examples=150, derandomize=True, deadline=None, suppress_health_check=list(HealthCheck))

m_unit = st.one_of(st.floats(0.0, 1.0, exclude_max=True), st.floats(1e-300, 0.5).map(lambda x: 1.0 - x))
m_any = st.one_of(m_unit, st.floats(-1e4, 0.0), st.floats(1.0, 1e4, exclude_min=True))
u_any = st.floats(-1e5, 1e5)
mc_small = st.floats(1e-300, 1e-3)


@settings(**SETTINGS)
@given(u_any, m_any)
def test_pythagorean_identities(u, m):
    sn, cn, dn, am = pendula.ellipj(u, m)
    assert abs(sn * sn + cn * cn - 1.0) <= 4 * EPS
    assert abs(dn * dn + m * sn * sn - 1.0) <= 4 * EPS * max(1.0, abs(m))


@settings(**SETTINGS)
@given(u_any, mc_small)
def test_pythagorean_identities_near_one_through_mc(u, mc):
    sn, cn, dn, am = pendula.ellipj(u, None, mc=mc)
    m = 1.0 - mc
    assert abs(sn * sn + cn * cn - 1.0) <= 4 * EPS
    assert abs(dn * dn + m * sn * sn - 1.0) <= 4 * EPS


@settings(**SETTINGS)
@given(st.floats(-50.0, 50.0), st.floats(0.0, 0.999))
def test_half_period_shift_changes_the_sign_of_sn(u, m):
    K = float(pendula.ellipk(m))
    v = u + 2 * K
    sn_u = pendula.ellipj(u, m)[0]
    sn_v = pendula.ellipj(v, m)[0]
    # v carries the rounding of u + 2K (half an ulp of v) and of K (twice half an ulp of K)
    slack = 4 * EPS + (abs(v) + 2 * K) * EPS
    assert abs(sn_v + sn_u) <= slack


@settings(**SETTINGS)
@given(st.lists(st.floats(-1e3, 1e3), min_size=2, max_size=30), m_unit)
def test_amplitude_is_monotonic_in_u(us, m):
    u = np.sort(np.array(us))
    am = pendula.ellipj(u, m)[3]
    assert np.all(np.diff(am) >= -4 * EPS * np.maximum(1.0, np.abs(am[1:])))


@settings(**SETTINGS)
@given(st.floats(-30.0, 30.0), st.floats(0.0, 0.99))
def test_f_inverts_the_amplitude(u, m):
    sn, cn, dn, am = pendula.ellipj(u, m)
    f = float(pendula.ellipf(am, m))
    assert abs(f - u) <= 8 * EPS * max(1.0, abs(u)) / dn


@settings(**SETTINGS)
@given(st.floats(-1e3, 1e3), st.floats(1e-300, 1e-200))
def test_limit_m_to_zero_is_sin_cos(u, m):
    sn, cn, dn, am = pendula.ellipj(u, m)
    assert abs(sn - math.sin(u)) <= 2 * EPS + abs(u) * EPS and abs(dn - 1.0) <= EPS


@settings(**SETTINGS)
@given(st.floats(-20.0, 20.0))
def test_limit_m_to_one_through_mc_and_through_m(u):
    # mc = 1e-300: sn = tanh to within mc-sized terms; m = 1 - 2^-53 through m as well
    sn, cn, dn, am = pendula.ellipj(u, None, mc=1e-300)
    # cn = sech u to 2 eps absolute (its relative error where it is tiny grows with the
    # number of duplications, ~1.7 eps each: up to ~20 eps at m = 1 - 1e-300; README)
    assert abs(sn - math.tanh(u)) <= 2 * EPS and abs(cn - 1 / math.cosh(u)) <= 2 * EPS
    sn1, cn1, dn1, am1 = pendula.ellipj(u, 1.0)
    assert abs(sn1 - math.tanh(u)) <= 2 * EPS


@settings(**SETTINGS)
@given(mc_small)
def test_period_asymptotics_near_the_separatrix(mc):
    # K(1 - mc) = ln(4/sqrt(mc)) + O(mc ln mc): a check of the limit, not of the digits
    K = float(pendula.ellipk(None, mc=mc))
    lead = math.log(4.0) - 0.5 * math.log(mc)
    assert abs(K - lead) <= 2 * mc * (abs(math.log(mc)) + 2) + 4 * EPS * K


@settings(**SETTINGS)
@given(st.floats(1e-300, 1e-8))
def test_k_small_m_series(m):
    assert abs(float(pendula.ellipk(m)) - math.pi / 2 * (1 + m / 4)) <= 2 * EPS


theta0s = st.floats(-20.0, 20.0)
v0s = st.floats(-6.0, 6.0)
epss = st.floats(1e-2, 1e2)


@settings(**SETTINGS)
@given(theta0s, v0s, epss, st.lists(st.floats(-200.0, 200.0), min_size=1, max_size=20))
def test_exact_motion_conserves_energy(theta0, v0, eps, ts):
    theta, v = pendula.exact_motion(theta0, v0, eps, ts)
    e0 = float(pendula.energy(theta0, v0, eps))
    e = pendula.energy(theta, v, eps)
    scale = max(e0, eps, 0.5 * v0 * v0)
    # a rotation's angle grows: its own spacing (rounding of the grown angle) moves the
    # potential by eps |sin theta| per unit, 4 spacings at most (README)
    assert np.all(np.abs(e - e0) <= 16 * EPS * scale + 4 * np.spacing(np.abs(theta)) * eps)


@settings(**SETTINGS)
@given(theta0s, v0s, epss, st.floats(-100.0, 100.0), st.floats(-100.0, 100.0))
@example(16.0, 0.0, 17.70108958317422, 1.0, 29.0)    # an angle offset by turns: its rounding is eps |theta|
def test_exact_motion_is_a_flow(theta0, v0, eps, t1, t2):
    o = pendula.orbit(theta0, v0, eps)
    assume(o.regime != "separatrix")
    th1, v1 = pendula.exact_motion(theta0, v0, eps, [t1])
    th12, v12 = pendula.exact_motion(float(th1[0]), float(v1[0]), eps, [t2 - t1])
    th2, v2 = pendula.exact_motion(theta0, v0, eps, [t2])
    # the intermediate state carries its own rounding, amplified along the orbit by at most
    # the number of periods crossed (the period's sensitivity to the energy)
    periods = abs(t2 - t1) / o.period if math.isfinite(o.period) else 0.0
    dist = 1.0 - o.k ** 2 if o.regime == "libration" else 1.0 - 1.0 / o.k ** 2
    amp = (1 + periods) * max(1.0, 1e-3 / max(abs(dist), 1e-300)) ** 0.5
    tol = 64 * EPS * amp
    assert abs(th12[0] - th2[0]) <= tol * max(1.0, abs(th2[0]))
    # the intermediate angle carries its rounding eps |theta1| (turns included), not eps: the velocity it
    # gives is off by that much times sqrt(eps)
    assert abs(v12[0] - v2[0]) <= tol * max(1.0, abs(v2[0]), math.sqrt(eps)) * max(1.0, abs(float(th1[0])))


@settings(**SETTINGS)
@given(theta0s, v0s, epss, st.floats(-300.0, 300.0))
def test_exact_motion_reverses_in_time(theta0, v0, eps, t):
    th_f, v_f = pendula.exact_motion(theta0, v0, eps, [t])
    th_b, v_b = pendula.exact_motion(theta0, -v0, eps, [-t])
    assert abs(th_f[0] - th_b[0]) <= 8 * EPS * max(1.0, abs(th_f[0]))
    assert abs(v_f[0] + v_b[0]) <= 8 * EPS * max(1.0, abs(v_f[0]))

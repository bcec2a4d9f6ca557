"""The density of the angle (Prusa & Tuma, task 5): CDF and density
against mpmath's time integrals, the arcsine limit, Kolmogorov-Smirnov
distances of sampled trajectories, the cycloid's arcsine law in s."""

import math

import mpmath as mp
import numpy as np
import pytest

import pendula
from pendula import Scene, angle_cdf, angle_density, arcsine_density

from conftest import EPS

RNG = np.random.default_rng(555)


def V_ref(sc):
    eps = mp.mpf(sc.eps)
    if sc.gravity == "inverse-square":
        d = mp.mpf(sc.gravity_distance)
        return lambda th: eps * (d - 1) ** 2 * (1 / (d - 1) - 1 / mp.sqrt(mp.sin(th) ** 2 + (d - mp.cos(th)) ** 2))
    if sc.gravity == "linear":
        k = mp.mpf(sc.gravity_gradient)
        return lambda th: eps * (2 * mp.sin(th / 2) ** 2 - k * 2 * mp.sin(th / 2) ** 4)
    return lambda th: eps * 2 * mp.sin(th / 2) ** 2


def cdf_ref(sc, theta):
    """time from -theta_max (libration) or -pi (rotation) to theta over the half period / period,
    by mpmath's tanh-sinh quadrature of dtheta / sqrt(2 (E - V)) at 30 digits"""
    mp.mp.dps = 30
    V = V_ref(sc)
    E = mp.mpf(sc.v0) ** 2 / 2 + V(mp.mpf(sc.theta0))
    f = lambda th: 1 / mp.sqrt(2 * abs(E - V(th)))      # noqa: E731
    if E < V(mp.pi):
        thm = mp.mpf(abs(sc.theta0)) if sc.v0 == 0 else mp.findroot(lambda x: V(x) - E, (mp.mpf(0), mp.pi),
                                                                   solver="bisect")
        half = 2 * mp.quad(f, [0, thm])
        val = mp.quad(f, [-thm, 0, mp.mpf(theta)]) / half
    else:
        turn = mp.quad(f, [-mp.pi, 0, mp.pi])
        val = mp.quad(f, [-mp.pi, 0, mp.mpf(theta)]) / turn
    mp.mp.dps = 15
    return float(val)


SCENES = [Scene(theta0=0.3), Scene(theta0=2.9), Scene(theta0=0.0, v0=1.3, eps=0.7),
          Scene(v0=2.6),                                               # a rotation, uniform field
          Scene(gravity="inverse-square", gravity_distance=1.7, theta0=2.0),
          Scene(gravity="linear", gravity_gradient=-0.8, theta0=1.1, v0=0.4),
          Scene(gravity="linear", gravity_gradient=0.3, v0=2.5)]     # a rotation, linear field


@pytest.mark.parametrize("sc", SCENES, ids=lambda s: f"{s.gravity}-{s.theta0}-{s.v0}")
def test_cdf_against_mpmath_time_integral(sc):
    o = pendula.gravity_orbit(sc)
    lim = o.theta_max if o.regime == "libration" else math.pi
    th = np.concatenate([RNG.uniform(-lim, lim, 6), [0.0, -0.5 * lim]])
    mine = angle_cdf(sc, th)
    ref = np.array([cdf_ref(sc, x) for x in th])
    # the series of h and F are good to a few eps; 1e-13 allows the reference's quadrature
    assert np.abs(mine - ref).max() <= 1e-13


def test_cdf_is_accurate_up_to_the_turning_points():
    # theta = theta_max (1 - delta): the CDF's distance to 1 scales like sqrt(delta);
    # reference: mpmath's F at 40 digits (uniform field)
    sc = Scene(theta0=2.5)
    for delta in (1e-4, 1e-8, 1e-12):
        th = 2.5 * (1 - delta)
        mp.mp.dps = 40
        m = mp.sin(mp.mpf(2.5) / 2) ** 2
        phi = mp.asin(mp.sin(mp.mpf(th) / 2) / mp.sqrt(m))
        ref = mp.mpf(1) / 2 + mp.ellipf(phi, m) / (2 * mp.ellipk(m))
        mp.mp.dps = 15
        got = float(angle_cdf(sc, th))
        assert abs((1 - got) - float(1 - ref)) <= 8 * EPS
        assert 1 - got > 0


@pytest.mark.parametrize("sc", SCENES[:2] + SCENES[3:6], ids=lambda s: f"{s.gravity}-{s.theta0}-{s.v0}")
def test_density_is_the_derivative_of_the_cdf(sc):
    o = pendula.gravity_orbit(sc)
    lim = o.theta_max if o.regime == "libration" else math.pi
    for a, b in RNG.uniform(-lim, lim, (3, 2)):
        a, b = min(a, b), max(a, b)
        integral = mp.quad(lambda x: float(angle_density(sc, float(x))), [a, b])
        assert float(integral) == pytest.approx(float(angle_cdf(sc, b) - angle_cdf(sc, a)), abs=1e-12)


def test_arcsine_limit_difference_shrinks_as_theta0_squared():
    # p(theta) = (1/(pi sqrt(theta0^2 - theta^2))) (1 + O(theta0^2)) at fixed theta/theta0
    x = np.linspace(-0.95, 0.95, 39)
    rel = []
    for th0 in (1e-1, 1e-2, 1e-3):
        sc = Scene(theta0=th0)
        p = angle_density(sc, x * th0)
        rel.append(np.abs(p / arcsine_density(x * th0, th0) - 1).max())
    for a, b in zip(rel, rel[1:]):
        assert 90 < a / b < 110
    assert rel[0] < 0.01


def ks_distance(samples, cdf):
    s = np.sort(samples)
    n = s.size
    c = cdf(s)
    return max(np.max(np.arange(1, n + 1) / n - c), np.max(c - np.arange(n) / n))


@pytest.mark.parametrize("sc", [Scene(theta0=2.4), Scene(gravity="inverse-square", gravity_distance=2.0, theta0=1.5)],
                         ids=["uniform", "inverse-square"])
def test_histogram_ks_distance_shrinks_with_samples(sc):
    # random sampling times over many periods: sqrt(N) D stays below the KS 0.999 quantile (1.95)
    T = pendula.period(sc)
    ds = []
    for n in (1_000, 10_000, 100_000):
        t = RNG.uniform(0, 200 * T, n)
        if sc.gravity == "uniform":
            th = pendula.simulate(sc, t).theta
        else:
            th = pendula.simulate(sc.replace(method="dop853"), t).theta
        d = ks_distance(th, lambda x: angle_cdf(sc, x))
        assert math.sqrt(n) * d < 1.95
        ds.append(d)
    assert ds[-1] < ds[0] / 3


@pytest.mark.parametrize("method,kw", [("exact", {}), ("rk4", {"dt": 0.01}),
                                       ("dop853", {"rtol": 1e-10, "atol": 1e-12})])
def test_histogram_of_an_integrated_trajectory(method, kw):
    # n equally spaced samples over exactly 100 periods, n prime: the phases are n
    # equally spaced points, so the exact path gives D = 1/n (equidistribution).
    # An integrator's path adds its own error: near a turning point the CDF
    # goes like sqrt(theta_max - theta), so an energy error dE shows as
    # D ~ sqrt(dE / V'(theta_max)); measured: D n = 1.0, 1.9, 3.3 at n = 200003.
    sc = Scene(theta0=2.4)
    T = pendula.period(sc)
    run = sc.replace(method=method, **kw)
    for n in (2003, 20011, 200003):
        t = np.linspace(0, 100 * T, n, endpoint=False)
        tr = pendula.simulate(run, t)
        d = ks_distance(tr.theta, lambda x: angle_cdf(sc, x))
        if method == "exact":
            assert d * n == pytest.approx(1.0, abs=1e-4)
        else:
            de = np.abs(tr.energy - tr.energy[0]).max()
            assert d <= 1.0 / n + 2 * math.sqrt(de / (sc.eps * math.sin(2.4))), (n, d, de)
            assert d > 0.99 / n


def test_cycloid_density_is_the_arcsine_law_in_s_at_every_amplitude():
    for th0 in (1e-4, 0.5, 1.2, math.pi / 2):
        sc = Scene(guide="cycloid", theta0=th0)
        A = math.sin(th0)           # 4R = 1
        th = RNG.uniform(-th0, th0, 10)
        s = np.sin(th)
        assert np.allclose(angle_cdf(sc, th), 0.5 + np.arcsin(s / A) / math.pi, rtol=0, atol=4 * EPS)
        # and against time: the fraction of a period the exact path spends below theta
        t = np.linspace(0, pendula.period(sc), 20001)[:-1]
        if th0 == math.pi / 2:
            # at the cusp amplitude theta' has no value at the cusps: NaN there, said by a RuntimeWarning
            with pytest.warns(RuntimeWarning, match="cusp"):
                path = pendula.simulate(sc, t).theta
            path = path[np.isfinite(path)]
        else:
            path = pendula.simulate(sc, t).theta
        for x in th[:3]:
            assert np.mean(path <= x) == pytest.approx(float(angle_cdf(sc, x)), abs=2e-4)
        # density = d(cdf)/dtheta
        assert float(mp.quad(lambda z: float(angle_density(sc, float(z))), [th.min(), th.max()])) == \
            pytest.approx(float(angle_cdf(sc, th.max()) - angle_cdf(sc, th.min())), abs=1e-10)


def test_cycloid_with_torque_is_centred():
    sc = Scene(guide="cycloid", theta0=0.0, torque=0.1)   # oscillates on s in [0, 0.2]
    assert float(angle_cdf(sc, math.asin(0.1))) == pytest.approx(0.5, abs=4 * EPS)


def test_scenes_without_a_density_are_errors():
    with pytest.raises(ValueError, match="damping"):
        angle_density(Scene(theta0=1.0, damping=0.1), 0.0)
    with pytest.raises(ValueError, match="separatrix"):
        angle_cdf(Scene(v0=2.0), 0.0)
    with pytest.raises(ValueError, match="rest"):
        angle_density(Scene(), 0.0)
    with pytest.raises(NotImplementedError, match="torque"):
        angle_density(Scene(theta0=1.0, torque=0.1), 0.0)
    with pytest.raises(TypeError):
        angle_cdf("scene", 0.0)


def test_nan_and_infinite_angles():
    # NaN in, NaN out; beyond the amplitude the density is 0 and the CDF 0 or 1; nothing raises
    sc = Scene(theta0=1.0)
    assert np.array_equal(angle_cdf(sc, [-np.inf, np.inf, 5.0]), [0.0, 1.0, 1.0])
    assert np.isnan(angle_cdf(sc, np.nan)) and np.isnan(angle_density(sc, np.nan))
    assert angle_density(sc, np.array([])).size == 0
    assert np.array_equal(angle_density(sc, [np.inf, -3.0]), [0.0, 0.0])
    cy = Scene(guide="cycloid", theta0=1.0)
    assert np.isnan(angle_cdf(cy, np.nan)) and np.isnan(angle_density(cy, np.nan))


def test_cdf_with_a_sharply_peaked_field():
    # mass 1e-3 l under the circle: the time integrand needs 16k cosine terms; still 1e-12
    sc = Scene(gravity="inverse-square", gravity_distance=1.001, theta0=1.0)
    th = np.array([-0.9, 0.2, 0.99])
    assert np.abs(angle_cdf(sc, th) - [cdf_ref(sc, x) for x in th]).max() <= 1e-12


# ------------------------------------------------------------ next to the separatrix and the top

def _cdf_uniform_mp(theta0, v0, eps, theta):
    """The CDF of the uniform field in closed form (mpmath at 40 digits)."""
    mp.mp.dps = 40
    t0, v, e, th = (mp.mpf(x) for x in (theta0, v0, eps, theta))
    k2 = mp.sin(t0 / 2) ** 2 + v * v / (4 * e)
    if k2 < 1:
        phi = mp.asin(mp.sin(abs(th) / 2) / mp.sqrt(k2))
        return mp.mpf(1) / 2 + mp.sign(th) * mp.ellipf(phi, k2) / (2 * mp.ellipk(k2))
    m = 1 / k2
    return mp.mpf(1) / 2 + mp.ellipf(th / 2, m) / (2 * mp.ellipk(m))


def test_cdf_next_to_the_separatrix_in_libration():
    sc = Scene(theta0=-0.5863656862724058, v0=7.148524124932844, eps=13.939604752161001)
    th = -1.422499142852407
    ref = _cdf_uniform_mp(sc.theta0, sc.v0, sc.eps, th)
    assert abs(float(angle_cdf(sc, th)) - float(ref)) <= 4 * EPS


@pytest.mark.parametrize("theta", [-3.1358134481626974, 2.6620384923458245, 0.5])
def test_density_in_rotation_next_to_the_separatrix(theta):
    # 1 - m sin^2(theta/2) is formed as mc + m cos^2(theta/2): no cancellation next to the top
    sc = Scene(theta0=-0.41417420891317, v0=0.20927765026927084, eps=0.011432602965413334)
    mp.mp.dps = 40
    t0, v, e, th = (mp.mpf(x) for x in (sc.theta0, sc.v0, sc.eps, theta))
    E = v * v / 2 + 2 * e * mp.sin(t0 / 2) ** 2
    T = 2 * mp.ellipk(2 * e / E) / mp.sqrt(E / 2)
    ref = 1 / (T * mp.sqrt(2 * (E - 2 * e * mp.sin(th / 2) ** 2)))
    assert abs(float(angle_density(sc, theta)) / float(ref) - 1) <= 4 * EPS
    assert abs(float(angle_cdf(sc, theta)) - float(_cdf_uniform_mp(sc.theta0, sc.v0, sc.eps, theta))) <= 4 * EPS


@pytest.mark.parametrize("field", [{}, dict(gravity="inverse-square", gravity_distance=2.5),
                                   dict(gravity="linear", gravity_gradient=0.25)])
@pytest.mark.parametrize("theta0,v0", [(math.pi, 0.0), (-math.pi, 1e-12), (3.14159265358, 0.0),
                                       (math.pi - 1e-13, -1e-9)])
def test_near_top_scenes_have_a_density(field, theta0, v0):
    sc = Scene(theta0=theta0, v0=v0, **field)
    o = pendula.gravity_orbit(sc)
    assert o.regime != "separatrix"
    th = np.array([-3.0, -1.0, 0.0, 1.0, 3.0])
    c = angle_cdf(sc, th)
    p = angle_density(sc, th)
    assert np.all(np.isfinite(c)) and np.all(np.diff(c) > 0) and np.all(p > 0)


def test_cdf_next_to_the_turning_point_of_a_libration_near_the_top():
    # F from sin and cos of phi: phi next to pi/2 would lose 1/sqrt(mc) times its rounding
    sc = Scene(theta0=3.1415926510235415, eps=23.81903433409528)
    th = 3.141526426620049
    ref = _cdf_uniform_mp(sc.theta0, sc.v0, sc.eps, th)
    assert abs(float(angle_cdf(sc, th)) - float(ref)) <= 4 * EPS


def test_rotation_angle_beyond_2_52_is_nan_with_a_warning():
    sc = Scene(theta0=0.2, v0=5.0)
    with pytest.warns(RuntimeWarning, match="theta beyond 2"):
        assert math.isnan(float(angle_density(sc, 1e300)))
    with pytest.warns(RuntimeWarning, match="theta beyond 2"):
        c = angle_cdf(sc, [1e300, np.inf, -np.inf, 7.0])
    assert math.isnan(c[0]) and c[1] == np.inf and c[2] == -np.inf and 1 < c[3] < 2


def test_empty_angles_give_empty_answers():
    for sc in (Scene(theta0=1.0), Scene(theta0=0.2, v0=5.0)):
        assert angle_cdf(sc, []).shape == (0,) and angle_density(sc, []).shape == (0,)


def test_rotation_density_at_large_angles_reduced_exactly():
    """theta = -908.13 on a rotation: theta was reduced modulo 2 pi in plain double (1.19e3 eps); now
    exactly, as numpy's sin reduces: density and CDF within 4 eps of mpmath."""
    from conftest import assert_hard_cases

    assert_hard_cases("periodic_exact", "reproducer")


def test_every_periodic_input_reduced_exactly_hunted():
    """Fresh random angles up to 2^52: the rotation's density and CDF (three fields), energy,
    gravity_orbit's theta0, F and E(phi)'s phi: within 4 eps of mpmath, plus twice the condition
    number in the reduced angle for the density and the CDF (stored with each row; theta itself is
    exact, the computation at the reduced angle is what rounds)."""
    from conftest import assert_hard_cases

    assert_hard_cases("periodic_exact", "hunt")


def test_angle_cdf_counts_turns_where_angle_density_wraps():
    """A rotation: cdf(theta + 2 pi) = cdf(theta) + 1 while the density repeats, as both docstrings say."""
    sc = Scene(theta0=0.3, v0=2.5)
    th = np.array([-3.0, -1.0, 0.5, 2.9])
    two_pi = 2 * math.pi
    assert np.allclose(angle_cdf(sc, th + two_pi) - angle_cdf(sc, th), 1.0, rtol=0, atol=8 * EPS)
    assert np.allclose(angle_density(sc, th + two_pi), angle_density(sc, th), rtol=8 * EPS, atol=0)
    assert "angle_cdf(theta) + 1" in angle_cdf.__doc__ and "wraps" in angle_cdf.__doc__
    assert "2 pi periodic" in angle_density.__doc__

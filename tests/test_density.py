"""The density of the angle (Prusa & Tuma, task 5): the exact CDF against
mpmath, its density against quadrature, samples of the motion against the CDF
(the Kolmogorov-Smirnov distance shrinks like 1/sqrt(N)), the arcsine limit,
and the cycloid's arcsine law at every amplitude."""

import math

import mpmath as mp
import numpy as np
import pytest
from scipy.integrate import quad

import pendula
from pendula import Scene

EPS = np.finfo(float).eps


def mp_cdf_libration(theta0, theta):
    with mp.workdps(40):
        k2 = mp.sin(mp.mpf(theta0) / 2) ** 2
        k = mp.sqrt(k2)
        phi = mp.asin(mp.sin(mp.mpf(theta) / 2) / k)
        K = mp.ellipk(k2)
        return float((mp.ellipf(phi, k2) + K) / (2 * K))


@pytest.mark.parametrize("theta0", [0.3, 1.0, 2.5, 3.1])
def test_cdf_against_mpmath_up_to_the_turning_points(theta0):
    rng = np.random.default_rng(11)
    th = np.concatenate([rng.uniform(-theta0, theta0, 20), theta0 * (1 - 10.0 ** -rng.uniform(3, 15, 10))])
    got = pendula.angle_cdf(Scene(theta0=theta0), th)
    ref = np.array([mp_cdf_libration(theta0, x) for x in th])
    # F's few eps of K over 2K, and the rounding of theta itself near the turning point
    assert np.abs(got - ref).max() <= 8 * EPS


@pytest.mark.parametrize("scene,lo,hi", [(Scene(theta0=1.0), -1.0, 1.0), (Scene(v0=3.0), -math.pi, math.pi),
                                         (Scene(guide="cycloid", theta0=1.2, v0=0.1), -1.2, 1.2)])
def test_density_integrates_to_the_cdf(scene, lo, hi):
    for a, b in [(lo, hi), (lo * 0.3, hi * 0.8), (0.0, hi * 0.99)]:
        val, err = quad(lambda x: pendula.angle_density(scene, x), a, b, limit=400)
        d = float(pendula.angle_cdf(scene, b) - pendula.angle_cdf(scene, a))
        assert abs(val - d) < 1e-8


def _ks(samples, cdf):
    x = np.sort(samples)
    n = x.size
    c = cdf(x)
    return max(np.max(np.arange(1, n + 1) / n - c), np.max(c - np.arange(n) / n))


@pytest.mark.parametrize("scene", [Scene(theta0=2.0), Scene(v0=2.7)])
def test_samples_of_the_exact_path_follow_the_cdf(scene):
    o = pendula.orbit(scene.theta0, scene.v0, scene.eps)
    rng = np.random.default_rng(3)
    d = []
    for n in (400, 40000):
        t = rng.uniform(0, 50 * o.period, n)
        th = pendula.simulate(scene, t).theta
        if o.regime == "rotation":
            th = np.remainder(th + math.pi, 2 * math.pi) - math.pi
        d.append(_ks(th, lambda x: pendula.angle_cdf(scene, x)) * math.sqrt(n))
    # sqrt(N) D_N stays of order one (Kolmogorov's law: below 1.63 with 99 % probability)
    assert d[0] < 1.63 and d[1] < 1.63


def test_samples_of_an_integration_follow_the_cdf():
    s = Scene(theta0=2.0)
    o = pendula.orbit(2.0, 0.0, 1.0)
    rng = np.random.default_rng(4)
    t = np.sort(rng.uniform(0, 50 * o.period, 20000))
    th = pendula.simulate(s, t, method="dop853", rtol=1e-11, atol=1e-13).theta
    assert _ks(th, lambda x: pendula.angle_cdf(s, x)) * math.sqrt(t.size) < 1.63


def test_small_amplitudes_approach_the_arcsine_law_as_theta0_squared():
    diffs = []
    for a in (0.2, 0.1, 0.05):
        x = a * np.sin(np.linspace(-math.pi / 2, math.pi / 2, 401))
        lin = 0.5 + np.arcsin(np.clip(x / a, -1, 1)) / math.pi
        diffs.append(np.abs(pendula.angle_cdf(Scene(theta0=a), x) - lin).max())
    r1, r2 = diffs[0] / diffs[1], diffs[1] / diffs[2]
    assert 3.5 < r1 < 4.5 and 3.5 < r2 < 4.5


@pytest.mark.parametrize("theta0", [0.2, 0.9, 1.5])
def test_cycloid_is_the_arcsine_law_in_s_at_every_amplitude(theta0):
    s = Scene(guide="cycloid", theta0=theta0)
    T = pendula.cycloid_period(1.0)
    rng = np.random.default_rng(8)
    th = pendula.simulate(s, rng.uniform(0, 200 * T, 20000)).theta
    sarc = np.sin(th) / math.sin(theta0)                 # s / A
    law = lambda u: 0.5 + np.arcsin(np.clip(u, -1, 1)) / math.pi  # noqa: E731
    assert _ks(sarc, law) * math.sqrt(th.size) < 1.63
    # and the CDF in theta is that law exactly
    x = np.linspace(-theta0, theta0, 11)
    assert np.abs(pendula.angle_cdf(s, x) - law(np.sin(x) / math.sin(theta0))).max() <= 4 * EPS


def test_density_refuses_what_has_none():
    with pytest.raises(ValueError, match="separatrix"):
        pendula.angle_density(Scene(v0=2.0), 0.0)
    with pytest.raises(ValueError, match="conservative"):
        pendula.angle_cdf(Scene(theta0=1.0, damping=0.1), 0.0)
    with pytest.raises(ValueError, match="point mass"):
        pendula.angle_cdf(Scene(), 0.0)

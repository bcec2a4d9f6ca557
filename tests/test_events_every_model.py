"""Events and the numerical period in every model: the cycloidal guide's
events as roots of its exact path (against the harmonic oscillator's closed
form written out here), and the numerical period of the non-uniform gravity
fields and of the cycloid against independent references (mpmath's
quadrature of the period integral; Huygens' T = 4 pi sqrt(R/g))."""

import math

import mpmath
import numpy as np
import pytest

import pendula
from pendula import Scene


def test_cycloid_crossings_match_the_oscillators_closed_form():
    # undamped, untorqued: s = 4R sin(theta0) cos(w t), theta = 0 at w t = pi/2 + n pi
    r, th0 = 0.3, 1.1
    sc = Scene(guide="cycloid", cycloid_radius=r, theta0=th0)
    w = math.sqrt(1.0 / (4 * r))
    ev = pendula.find_events(sc, "theta", level=0.0, t_end=40.0)
    ref = (math.pi / 2 + math.pi * np.arange(ev.t.size)) / w
    assert ev.t.size == int(40.0 * w / math.pi + 0.5)
    np.testing.assert_allclose(ev.t, ref, rtol=8 * np.finfo(float).eps)
    assert np.all(ev.stats["rhs_evaluations"] == 0)


def test_cycloid_turning_points_of_a_damped_driven_guide():
    # s'' + beta s' + w2 s = A cos(W t): the written-out solution's velocity vanishes at the events
    r, beta, amp, om, th0 = 0.25, 0.2, 0.3, 1.7, 0.5
    sc = Scene(guide="cycloid", cycloid_radius=r, theta0=th0, damping=beta, drive_amplitude=amp,
               drive_frequency=om)
    ev = pendula.find_events(sc, "turning", t_end=30.0)
    w2 = 1.0 / (4 * r)
    mpmath.mp.dps = 40
    # particular solution C cos(W t) + D sin(W t); homogeneous part from s(0) = 4 r sin(th0), s'(0) = 0
    den = (w2 - om ** 2) ** 2 + (beta * om) ** 2
    C, D = amp * (w2 - om ** 2) / den, amp * beta * om / den
    wd = mpmath.sqrt(w2 - beta ** 2 / 4)
    s0 = 4 * r * mpmath.sin(th0) - C
    v0 = -D * om
    a1, b1 = s0, (v0 + beta / 2 * s0) / wd

    def sdot(t):
        t = mpmath.mpf(t)
        e = mpmath.exp(-beta * t / 2)
        hom = e * ((-beta / 2) * (a1 * mpmath.cos(wd * t) + b1 * mpmath.sin(wd * t))
                   + wd * (-a1 * mpmath.sin(wd * t) + b1 * mpmath.cos(wd * t)))
        return hom - C * om * mpmath.sin(om * t) + D * om * mpmath.cos(om * t)

    refs = []
    grid = np.linspace(0, 30.0, 6001)
    vals = [sdot(x) for x in grid]
    for a, b, fa, fb in zip(grid[:-1], grid[1:], vals[:-1], vals[1:]):
        if fa * fb < 0:
            refs.append(float(mpmath.findroot(sdot, (a, b), solver="anderson")))
    assert ev.t.size == len(refs)
    np.testing.assert_allclose(ev.t, refs, rtol=0, atol=1e-12 * 30.0)


def test_cycloid_numerical_period_is_huygens_at_every_amplitude():
    for th0 in (0.01, 0.7, 1.5):
        sc = Scene(guide="cycloid", cycloid_radius=0.4, theta0=th0, torque=0.05)
        T = pendula.numerical_period(sc)
        assert abs(T - 4 * math.pi * math.sqrt(0.4)) <= 1e-13 * T


def test_cycloid_level_beyond_the_cusps_is_never_crossed():
    ev = pendula.find_events(Scene(guide="cycloid", theta0=1.0), "theta", level=2.0, t_end=50.0)
    assert ev.t.size == 0


def _gravity_period_mpmath(field, par, theta0, v0, eps=1.0):
    """T = 2 int dtheta / sqrt(2 (E - V)) over the libration, or one turn of a rotation (tanh-sinh)."""
    mpmath.mp.dps = 30

    def V(th):
        w = mpmath.sin(th / 2) ** 2
        if field == "inverse-square":
            rho = mpmath.sqrt((par - 1) ** 2 + 4 * par * w)
            return eps * (par - 1) ** 2 * (1 / (par - 1) - 1 / rho)
        return 2 * eps * (w - par * w * w)

    E = mpmath.mpf(v0) ** 2 / 2 + V(mpmath.mpf(theta0))
    f = lambda th: 1 / mpmath.sqrt(2 * (E - V(th)))  # noqa: E731
    if E < V(mpmath.pi):
        tm = mpmath.findroot(lambda th: V(th) - E, (mpmath.mpf(abs(theta0)) if v0 == 0 else 1.0))
        return float(4 * mpmath.quad(f, [0, tm]))
    return float(mpmath.quad(f, [-mpmath.pi, mpmath.pi]))


@pytest.mark.parametrize("field,par,theta0,v0", [("inverse-square", 3.0, 2.0, 0.0), ("inverse-square", 1.3, 0.4, 0.0),
                                                 ("linear", 0.3, 0.0, 3.0), ("linear", -2.0, 1.3, 0.0)])
def test_gravity_numerical_period_against_mpmath_quadrature(field, par, theta0, v0):
    kw = {"gravity_distance": par} if field == "inverse-square" else {"gravity_gradient": par}
    sc = Scene(gravity=field, theta0=theta0, v0=v0, **kw)
    T = pendula.numerical_period(sc)
    ref = _gravity_period_mpmath(field, par, theta0, v0)
    assert abs(T / ref - 1) < 1e-8, (T, ref)


def test_numerical_period_refuses_effects_and_names_them():
    with pytest.raises(ValueError, match="damping"):
        pendula.numerical_period(Scene(gravity="linear", gravity_gradient=0.1, damping=0.1, theta0=1.0))
    with pytest.raises(ValueError, match="damping"):
        pendula.numerical_period(Scene(guide="cycloid", damping=0.1, theta0=1.0))


@pytest.mark.parametrize("v0", [1.5, 1.8, 1.95])
def test_cord_departure_where_and_when_the_tension_vanishes(v0):
    # tension / m = l theta'^2 + g cos(theta) = 0 with theta'^2 = v0^2 - 2 eps (1 - cos theta):
    # cos(theta) = -(v0^2 - 2) / 3 (eps = 1); reached at sin(theta/2) = k sn(t), k = v0 / 2
    ev = pendula.find_events(Scene(cord="flexible", v0=v0), "departure", t_end=30.0)
    assert ev.t.size >= 1 and ev.stats["flips"] >= 1
    mpmath.mp.dps = 40
    th = mpmath.acos(-(mpmath.mpf(v0) ** 2 - 2) / 3)
    k = mpmath.mpf(v0) / 2
    t = mpmath.ellipf(mpmath.asin(mpmath.sin(th / 2) / k), k * k)
    assert abs(ev.theta[0] - float(th)) <= 1e-12 * float(th)
    assert abs(ev.t[0] - float(t)) <= 1e-12 * float(t)
    # the velocity there: theta'^2 = -cos(theta)
    assert abs(ev.v[0] - float(mpmath.sqrt(-mpmath.cos(th)))) <= 1e-12


def test_cord_returns_follow_departures():
    sc = Scene(cord="flexible", v0=2.2)            # Garfinkel's state above 3/4: several flips
    dep = pendula.find_events(sc, "departure", t_end=50.0)
    ret = pendula.find_events(sc, "return", t_end=50.0)
    n = min(dep.t.size, ret.t.size)
    assert n >= 2 and np.all(ret.t[:n] > dep.t[:n])
    assert pendula.find_events(sc, "departure", t_end=50.0, terminal=True).t.tolist() == dep.t[:1].tolist()
    # the same flips as the trajectory's log
    log = pendula.simulate(sc.replace(t_end=50.0, n_samples=2)).flips
    np.testing.assert_array_equal(dep.t, log["t_leave"][(log["t_leave"] > 0) & (log["t_leave"] <= 50.0)])


def test_cord_that_never_slackens_has_the_rigid_period_and_one_that_does_has_none():
    taut = Scene(cord="flexible", theta0=1.0)       # |theta| <= 1 < pi/2: the tension stays positive
    assert pendula.numerical_period(taut) == pendula.numerical_period(taut.replace(cord="rigid"))
    with pytest.raises(ValueError, match="slackens"):
        pendula.numerical_period(Scene(cord="flexible", v0=1.9))


def test_cord_events_refuse_other_kinds_and_rigid_scenes():
    with pytest.raises(NotImplementedError, match="flexible cord"):
        pendula.find_events(Scene(cord="flexible", v0=1.9), "turning", t_end=10.0)
    with pytest.raises(ValueError, match="cord"):
        pendula.find_events(Scene(v0=1.9), "departure", t_end=10.0)
    with pytest.raises(ValueError, match="direction"):
        pendula.find_events(Scene(cord="flexible", v0=1.9), "departure", direction="rising", t_end=10.0)

"""Properties of the newer models (hypothesis): the uniform field through gravity_orbit is
the exact orbit, the angle CDF is a distribution whose derivative is the density, the
cycloid is isochronous, a cord that never slackens is the rigid pendulum, and a flight
conserves energy."""

from __future__ import annotations

import math
import os
import warnings

import numpy as np
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import pendula
from pendula import Scene
from pendula.systems.cycloid import cycloid_motion

EPS = 2.0 ** -52
#: 40 examples per property in `make test`; PENDULA_HYPOTHESIS_EXAMPLES=1000 for a longer run by hand
SETTINGS = settings(max_examples=int(os.environ.get("PENDULA_HYPOTHESIS_EXAMPLES", "40")), deadline=None,
                    suppress_health_check=[HealthCheck.too_slow])


def logu(lo, hi):
    return st.floats(math.log(lo), math.log(hi)).map(math.exp)


angles = st.floats(-math.pi, math.pi, allow_nan=False)
speeds = st.one_of(st.floats(-30.0, 30.0, allow_nan=False), logu(1e-12, 1.0), st.just(0.0))
epss = logu(1e-2, 1e2)


@SETTINGS
@given(theta0=st.one_of(angles, st.floats(-1e3, 1e3, allow_nan=False)), v0=speeds, eps=epss)
def test_uniform_field_through_gravity_orbit_is_the_exact_orbit(theta0, v0, eps):
    g = pendula.gravity_orbit(Scene(theta0=theta0, v0=v0, eps=eps))
    o = pendula.orbit(theta0, v0, eps)
    assert g.regime == o.regime
    # the same bits: one classifier, one set of orbit parameters
    assert (g.m, g.mc, g.period, g.theta_max) == (o.m, o.mc, o.period, o.theta_max)


def _scene(field, par, theta0, v0, eps):
    kw = dict(theta0=theta0, v0=v0, eps=eps)
    if field == "inverse-square":
        kw.update(gravity=field, gravity_distance=1.0 + par)
    elif field == "linear":
        kw.update(gravity=field, gravity_gradient=0.49 * math.tanh(par - 1.0))
    return Scene(**kw)


fields = st.sampled_from(["uniform", "inverse-square", "linear"])


@SETTINGS
@given(field=fields, par=logu(0.05, 100.0), theta0=angles, v0=st.floats(-6.0, 6.0, allow_nan=False),
       eps=logu(0.1, 10.0))
def test_angle_cdf_is_monotone_from_0_to_1_and_its_derivative_is_the_density(field, par, theta0, v0, eps):
    sc = _scene(field, par, theta0, v0, eps)
    o = pendula.gravity_orbit(sc)
    assume(o.regime != "separatrix" and o.m > 1e-6 and o.mc > 1e-6)
    if o.regime == "libration":
        lo, hi = -o.theta_max, o.theta_max
    else:
        lo, hi = -math.pi, math.pi
    th = np.linspace(lo, hi, 2001)
    c = pendula.angle_cdf(sc, th)
    assert np.all(np.diff(c) >= -4 * EPS)
    if o.regime == "libration":
        assert c[0] == 0.0 and c[-1] == 1.0
        assert pendula.angle_cdf(sc, hi * 1.5) == 1.0 and pendula.angle_cdf(sc, lo * 1.5) == 0.0
    else:
        # +-pi are not doubles: the CDF there is off by the density times the rounding of pi
        # (the condition number: next to the separatrix the density peaks at the top)
        tol = 4 * EPS + 2 * EPS * math.pi * float(pendula.angle_density(sc, math.pi))
        assert abs(c[0]) <= tol and abs(c[-1] - 1.0) <= tol
    # the derivative: central differences away from the turning points
    inner = th[(np.abs(th) < 0.8 * hi)][::50]
    h = 1e-5 * (hi - lo)
    num = (pendula.angle_cdf(sc, inner + h) - pendula.angle_cdf(sc, inner - h)) / (2 * h)
    p = pendula.angle_density(sc, inner)
    np.testing.assert_allclose(num, p, rtol=2e-6)


@SETTINGS
@given(theta0=st.floats(-1.5, 1.5, allow_nan=False), frac=st.floats(0.0, 1.0), eps=epss,
       radius=logu(0.05, 5.0))
def test_cycloid_period_does_not_depend_on_the_amplitude(theta0, frac, eps, radius):
    # any state inside the cusps: the motion returns to it after cycloid_period and is reflected
    # after half of it, whatever the amplitude (a fraction frac of what reaches the cusp)
    w = math.sqrt(eps / (4 * radius))
    s0 = 4 * radius * math.sin(theta0)
    smax = 4 * radius * (1 - 1e-9)
    assume(abs(s0) < smax)
    sd = frac * math.sqrt(smax * smax - s0 * s0) * w
    v0 = sd / (4 * radius * math.cos(theta0))
    sc = Scene(guide="cycloid", theta0=theta0, v0=v0, eps=eps, cycloid_radius=radius)
    T = pendula.cycloid_period(sc)
    assert T == pendula.period(sc)
    th, v, s, sdot = cycloid_motion(sc, [0.0, 0.5 * T, T])
    amp = math.hypot(s0, sd / w)
    assert abs(s[2] - s[0]) <= 16 * EPS * 4 * radius
    assert abs(s[1] + s[0]) <= 16 * EPS * 4 * radius
    assert abs(sdot[2] - sdot[0]) <= 16 * EPS * max(amp * w, abs(sd))


@SETTINGS
@given(theta0=st.floats(-1.4, 1.4, allow_nan=False), xi=st.one_of(st.floats(-0.66, -0.01), st.floats(1.01, 20.0)),
       eps=epss, sign=st.sampled_from([-1.0, 1.0]))
def test_cord_that_never_slackens_is_the_rigid_pendulum_bit_for_bit(theta0, xi, eps, sign):
    # Garfinkel's xi = (v^2 - 2 eps cos theta) / (3 eps) outside [0, 1]: the tension never vanishes
    v2 = 3 * eps * xi + 2 * eps * math.cos(theta0)
    assume(v2 > 0)
    v0 = sign * math.sqrt(v2)
    xi_state = (v0 * v0 - 2 * eps * math.cos(theta0)) / (3 * eps)
    assume(xi_state < -1e-9 or xi_state > 1 + 1e-9)
    cord = pendula.simulate(Scene(cord="flexible", theta0=theta0, v0=v0, eps=eps, t_end=40.0, n_samples=301))
    rigid = pendula.simulate(Scene(theta0=theta0, v0=v0, eps=eps, t_end=40.0, n_samples=301))
    assert cord.stats["flips"] == 0
    assert np.array_equal(cord.theta, rigid.theta) and np.array_equal(cord.v, rigid.v)


@SETTINGS
@given(theta0=st.floats(-1.2, 1.2, allow_nan=False), xi=st.floats(0.02, 0.98), eps=epss)
def test_energy_along_a_cord_flight_is_conserved(theta0, xi, eps):
    v0 = math.sqrt(3 * eps * xi + 2 * eps * math.cos(theta0))
    sc = Scene(cord="flexible", theta0=theta0, v0=v0, eps=eps, max_flips=1, t_end=200.0 / math.sqrt(eps),
               n_samples=2)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)   # NaN after the one-flip stop
        fl = pendula.simulate(sc).flips
    t1, t2 = float(fl["t_leave"][0]), float(fl["t_return"][0])
    th1, v1 = float(fl["theta_leave"][0]), float(fl["v_leave"][0])
    t = np.linspace(t1, t2, 41)[1:-1]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        tr = pendula.simulate(sc, t)
    assert np.all(tr.r < 1.0)
    # the flight's velocity from the departure (tangent to the circle), position from the trajectory
    tau = t - t1
    ux, uy = v1 * math.cos(th1), v1 * math.sin(th1) - eps * tau
    e_flight = 0.5 * (ux * ux + uy * uy) + eps * (1.0 + tr.y)
    e_leave = 0.5 * v1 * v1 + eps * (1.0 - math.cos(th1))
    # a few roundings of the terms: the energies and eps times the parts of y = y1 + u_y tau - eps tau^2 / 2
    bound = 8 * EPS * (e_leave + eps * (1.0 + abs(v1) * tau + eps * tau * tau))
    assert np.all(np.abs(e_flight - e_leave) <= bound)
    # and the angular velocity of the trajectory is that of the parabola: r^2 theta' = x u_y - y u_x
    np.testing.assert_allclose(tr.v * tr.r ** 2, tr.x * uy - tr.y * ux, rtol=1e-12, atol=1e-12 * abs(v1))

"""Equilibria and their linear stability, and periodic orbits of the driven
pendulum, against independent references: closed forms (asin, the quadratic's
roots by numpy), scipy's brentq on the fields' force laws written out here,
scipy's solve_ivp for the stroboscopic map and its monodromy, Liouville's
det M = exp(-beta T), and the lyapunov sweep's exponents."""

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import pendula
from pendula import Scene

ULP = np.finfo(float).eps


def _kinds_ok(e, beta, c):
    """The kind a rest point must have, from beta and c = lambda1 lambda2."""
    if c < 0:
        return e.kind == "saddle"
    if c == 0:
        return e.kind == "saddle-node"
    if beta == 0:
        return e.kind == "centre"
    spiral = beta * beta < 4 * c
    word = ("stable " if beta > 0 else "unstable ") + ("spiral" if spiral else "node")
    return e.kind == word


def test_untorqued_damped_wells_are_spirals_and_tops_saddles():
    # Suzuki & Suzuki, section 7.1: 2 n pi stable spirals, odd multiples of pi saddles
    eqs = pendula.equilibria(Scene(damping=0.3), window=(-3 * math.pi, 3 * math.pi))
    th = np.array([e.theta for e in eqs])
    np.testing.assert_allclose(th, np.arange(-2, 4) * math.pi, rtol=0, atol=4 * ULP * 3 * math.pi)
    for e in eqs:
        n = round(e.theta / math.pi)
        assert e.kind == ("stable spiral" if n % 2 == 0 else "saddle"), e
        # lambda^2 + beta lambda -+ eps = 0
        ref = np.roots([1.0, 0.3, 1.0 if n % 2 == 0 else -1.0])
        np.testing.assert_allclose(sorted(e.eigenvalues, key=lambda z: (-z.real, -z.imag)),
                                   sorted(ref, key=lambda z: (-z.real, -z.imag)), rtol=4 * ULP)


@settings(max_examples=200, deadline=None)
@given(eps=st.floats(1e-3, 1e3), r=st.floats(-1.0, 1.0), beta=st.floats(0.0, 5.0))
def test_torqued_rigid_against_asin_and_the_quadratic(eps, r, beta):
    import mpmath
    tau = r * eps
    eqs = pendula.equilibria(Scene(eps=eps, damping=beta, torque=tau))
    with mpmath.workdps(40):
        rr = mpmath.mpf(tau) / eps
        a = mpmath.asin(rr)
        cb = eps * mpmath.sqrt(1 - rr * rr)            # c at the bottom; -cb at the top
        ref = [(a, cb)] if cb == 0 else [(a, cb), (mpmath.pi - a, -cb)]
    assert len(eqs) == len(ref)
    for x, c in ref:
        # the same point modulo 2 pi (a top at +-pi may sit at either end of the turn)
        (e,) = [e for e in eqs if abs(mpmath.sin((e.theta - x) / 2)) < 1e-12]
        assert abs(float(mpmath.sin((e.theta - x) / 2))) * 2 <= 2 * ULP * max(1.0, abs(float(x)))
        lam = e.eigenvalues
        # Vieta: lambda1 + lambda2 = -beta, lambda1 lambda2 = c
        assert abs((lam[0] + lam[1]).real + beta) <= 8 * ULP * (beta + math.sqrt(abs(float(c)))) + 1e-300
        assert abs((lam[0] * lam[1]).real - float(c)) <= 1e-12 * max(abs(float(c)), beta * beta) + 1e-300
        assert _kinds_ok(e, beta, float(c))


def test_torque_above_eps_has_no_rest_point():
    assert pendula.equilibria(Scene(damping=0.1, torque=1.0000001)) == []


def test_torque_equal_to_eps_is_one_saddle_node():
    (e,) = pendula.equilibria(Scene(damping=0.1, torque=1.0))
    assert e.theta == math.pi / 2 and e.kind == "saddle-node"


def test_undamped_bottom_is_a_centre():
    bottom, top = pendula.equilibria(Scene())
    assert bottom.kind == "centre" and top.kind == "saddle" and top.theta == math.pi
    np.testing.assert_allclose(bottom.eigenvalues, [1j, -1j], atol=ULP)


def test_overdamped_bottom_is_a_node():
    bottom = pendula.equilibria(Scene(damping=3.0))[0]
    assert bottom.kind == "stable node" and bottom.stable
    np.testing.assert_allclose(sorted(bottom.eigenvalues.real), sorted(np.roots([1, 3.0, 1.0]).real), rtol=4 * ULP)


def _field_accel(kind, par, eps, th):
    """The fields' force laws, written out independently of the kernel."""
    w = math.sin(th / 2) ** 2
    if kind == "inverse-square":
        rho = math.sqrt((par - 1) ** 2 + 4 * par * w)
        return -eps * par * (par - 1) ** 2 * math.sin(th) / rho ** 3
    return -eps * (1 - 2 * par * w) * math.sin(th)


@pytest.mark.parametrize("field,par", [("inverse-square", 1.7), ("inverse-square", 40.0), ("linear", 0.3),
                                       ("linear", -4.0)])
@pytest.mark.parametrize("tau", [0.0, 0.37, -0.9])
def test_nonuniform_gravity_rest_points_against_brentq(field, par, tau):
    kw = {"gravity_distance": par} if field == "inverse-square" else {"gravity_gradient": par}
    sc = Scene(gravity=field, damping=0.2, torque=tau, **kw)
    eqs = pendula.equilibria(sc)
    g = lambda th: tau + _field_accel(field, par, 1.0, th)  # noqa: E731
    # a turn that starts off the special points 0 and pi, so that they are interior roots
    grid = np.linspace(-math.pi + 0.1, math.pi + 0.1, 20001)
    vals = np.array([g(x) for x in grid])
    ref = [brentq(g, a, b, xtol=1e-15, rtol=4 * ULP) for a, b, fa, fb in
           zip(grid[:-1], grid[1:], vals[:-1], vals[1:]) if fa * fb < 0]
    ref += [x for x, f in zip(grid, vals) if f == 0.0]
    ref = sorted({round(x - 2 * math.pi if x > math.pi + 1e-12 else x, 12) for x in ref})
    assert len(eqs) == len(ref), ([e.theta for e in eqs], ref)
    for e, x in zip(eqs, ref):
        assert abs(e.theta - x) <= 1e-11
        # c = -a'(theta*) by a central difference of the written-out force law
        h = 1e-5
        c = -(g(e.theta + h) - g(e.theta - h)) / (2 * h)
        assert abs((e.eigenvalues[0] * e.eigenvalues[1]).real - c) <= 1e-8 * max(1.0, abs(c))
        assert _kinds_ok(e, 0.2, c)


def test_cycloid_rest_point_and_frequency():
    sc = Scene(guide="cycloid", cycloid_radius=0.3, damping=0.05, torque=0.2)
    (e,) = pendula.equilibria(sc)
    assert abs(e.theta - math.asin(0.2)) <= ULP
    np.testing.assert_allclose(sorted(e.eigenvalues, key=lambda z: z.imag),
                               sorted(np.roots([1, 0.05, 1 / (4 * 0.3)]), key=lambda z: z.imag), rtol=4 * ULP)
    assert e.kind == "stable spiral"


def test_cycloid_torque_beyond_the_cusps_has_none():
    # (with damping: the conservative scene whose orbit reaches the cusps is refused when made)
    assert pendula.equilibria(Scene(guide="cycloid", torque=1.5, damping=0.1)) == []


def test_flexible_cord_rests_only_where_taut():
    eqs = pendula.equilibria(Scene(cord="flexible", damping=0.1, torque=0.2))
    assert [e.kind for e in eqs] == ["stable spiral"]
    assert abs(eqs[0].theta - math.asin(0.2)) <= ULP


def test_driven_scene_has_no_equilibria_names_the_field():
    with pytest.raises(ValueError, match="drive_amplitude"):
        pendula.equilibria(Scene(drive_amplitude=0.5, drive_frequency=1.0))


@pytest.mark.parametrize("window", [(1.0, 1.0), (0.0, math.inf), (math.nan, 1.0), "ab", (0.0, 1e6)])
def test_equilibria_bad_window_is_refused(window):
    with pytest.raises((ValueError, TypeError), match="window"):
        pendula.equilibria(Scene(), window=window)


# ---------------------------------------------------------------- periodic orbits
CLASSIC = dict(damping=0.5, drive_frequency=2.0 / 3.0)


def _flow(amp, x, T):
    """The stroboscopic map and its monodromy by scipy (independent of GSL)."""
    om, beta = CLASSIC["drive_frequency"], CLASSIC["damping"]

    def f(t, y):
        c = -math.cos(y[0])
        return [y[1], -math.sin(y[0]) - beta * y[1] + amp * math.cos(om * t),
                y[3], c * y[2] - beta * y[3], y[5], c * y[4] - beta * y[5]]

    y = solve_ivp(f, (0, T), [x[0], x[1], 1.0, 0.0, 0.0, 1.0], method="DOP853", rtol=1e-12, atol=1e-14).y[:, -1]
    return y[:2], np.array([[y[2], y[4]], [y[3], y[5]]])


def test_period1_orbit_is_a_fixed_point_of_scipys_map():
    sc = Scene(**CLASSIC, drive_amplitude=0.9)
    po = pendula.periodic_orbit(sc, guess=(0.5, 0.5))
    end, m = _flow(0.9, (po.theta, po.v), po.period)
    assert abs(end[0] - po.theta) < 1e-9 and abs(end[1] - po.v) < 1e-9
    np.testing.assert_allclose(po.monodromy, m, atol=1e-8)
    # Liouville: det M = exp(-beta T); the exponents add up to -beta
    assert abs(np.linalg.det(po.monodromy) / math.exp(-0.5 * po.period) - 1) < 1e-9
    assert abs(po.exponents.sum() + 0.5) < 1e-10
    assert po.stable


def test_period2_orbit_exponent_matches_lyapunov_sweep():
    # A = 1.07: past the first period doubling (Baker & Gollub's route to chaos at beta = 0.5, Omega = 2/3)
    amp = 1.07
    sc = Scene(**CLASSIC, drive_amplitude=amp)
    pc = pendula.sweep(sc, over={"drive_amplitude": [amp]}, measure="poincare", transient=3000.0, samples=4,
                       rtol=1e-11, atol=1e-13)
    guess = (float(pc.theta.values[0, 0]), float(pc.v.values[0, 0]))
    po = pendula.periodic_orbit(sc, guess=guess, k=2)
    assert po.stable and abs(po.theta - guess[0]) < 1e-6 and abs(po.v - guess[1]) < 1e-6
    # truly period 2: one drive period does not bring it back
    end, _ = _flow(amp, (po.theta, po.v), po.period / 2)
    assert math.hypot(end[0] - po.theta, end[1] - po.v) > 1e-2
    ds = pendula.sweep(sc, over={"drive_amplitude": [amp]}, measure="lyapunov", transient=1000.0, t_max=3000.0,
                       rtol=1e-11, atol=1e-13)
    lam, err = float(ds.lyapunov[0]), float(ds.lyapunov_err[0])
    assert abs(po.exponents[0] - lam) <= 4 * err + 1e-3, (po.exponents, lam, err)


def test_the_unstable_period1_orbit_inside_the_doubling():
    # at A = 1.07 the period-1 orbit still exists but has lost stability through -1
    po = pendula.periodic_orbit(Scene(**CLASSIC, drive_amplitude=1.07), guess=(-0.2, 1.95))
    assert not po.stable
    assert po.multipliers[0].real < -1 and abs(po.multipliers[0].imag) < 1e-9


def test_running_orbit_with_winding():
    sc = Scene(**CLASSIC, drive_amplitude=1.35)
    po = pendula.periodic_orbit(sc, guess=(0.0, 0.76), winding=-1)
    end, _ = _flow(1.35, (po.theta, po.v), po.period)
    assert abs(end[0] - (po.theta - 2 * math.pi)) < 1e-9 and abs(end[1] - po.v) < 1e-9


def test_periodic_orbit_refuses_undriven_and_other_models():
    with pytest.raises(ValueError, match="drive_amplitude"):
        pendula.periodic_orbit(Scene(damping=0.1))
    with pytest.raises(NotImplementedError, match="cycloid"):
        pendula.periodic_orbit(Scene(guide="cycloid", drive_amplitude=0.1, drive_frequency=1.0))


@pytest.mark.parametrize("kw,match", [({"guess": (1.0,)}, "guess"), ({"guess": (math.nan, 0.0)}, "guess"),
                                      ({"k": 0}, "k must"), ({"k": 1.5}, "k must"), ({"tol": -1.0}, "tol"),
                                      ({"maxit": True}, "maxit")])
def test_periodic_orbit_bad_arguments_named(kw, match):
    with pytest.raises((ValueError, TypeError), match=match):
        pendula.periodic_orbit(Scene(**CLASSIC, drive_amplitude=0.9), **kw)


def test_periodic_orbit_nonconvergence_is_an_error_not_a_number():
    # one Newton iteration from far away cannot meet tol = 1e-14
    with pytest.raises(ValueError, match="converge|stalled"):
        pendula.periodic_orbit(Scene(**CLASSIC, drive_amplitude=1.15), guess=(3.0, -2.0), maxit=1, tol=1e-14)

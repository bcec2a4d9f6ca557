"""A huge starting angle (|theta0| up to 2^52, valid input): the integrators
step the angle reduced mod 2 pi and report theta0 plus the motion relative to
the start.  Stepping the absolute angle rounded every increment to ulp(theta0)
(2.4e-4 at 2^40) and loosened the angle's tolerance to rtol |theta0|, so that
v(10) of a damped scene from theta0 = 2^40 came out 2.53 instead of 1.38.

The reference: SciPy's DOP853 at rtol 1e-12 on the equation alone, from the
angle reduced with mpmath at 60 digits.
"""

import math

import mpmath
import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pendula
from pendula.integrate import find_events, integrate_scene

T = np.linspace(0.0, 10.0, 6)


def _reduced(theta0):
    """theta0 mod 2 pi in (-pi, pi], from mpmath at 60 digits."""
    with mpmath.workdps(60):
        x = mpmath.mpf(theta0)
        r = x - 2 * mpmath.pi * mpmath.nint(x / (2 * mpmath.pi))
        return float(r)


def _scipy(theta0, v0, beta):
    sol = solve_ivp(lambda t, y: [y[1], -math.sin(y[0]) - beta * y[1]], (0.0, T[-1]), [_reduced(theta0), v0],
                    method="DOP853", t_eval=T, rtol=1e-12, atol=1e-14)
    return sol.y[0] - sol.y[0][0], sol.y[1]


@pytest.mark.parametrize("theta0", [2.0 ** 40, -2.0 ** 45 + 0.3, 1.0e6, 2.0 ** 52])
@pytest.mark.parametrize("method,knobs", [("dop853", {}), ("dopri5", {}), ("vern9", {}), ("vern8", {}),
                                          ("rk4", {"dt": 1e-3})])
def test_huge_starting_angle_gives_the_motion_of_its_reduced_angle(theta0, method, knobs):
    """v to 1e-8 (the tolerance asked, 1e-10, times the growth over the span); theta - theta0 to
    the same plus the rounding of the absolute angle, ulp(theta0)."""
    scene = pendula.Scene(theta0=theta0, v0=1.0, damping=0.1, rtol=1e-10, atol=1e-10, **knobs)
    tr = integrate_scene(scene, T, method)
    dth, v = _scipy(theta0, 1.0, 0.1)
    assert np.abs(tr.v - v).max() < 1e-8
    assert np.abs((tr.theta - theta0) - dth).max() <= 1e-8 + 2 * math.ulp(theta0)
    assert tr.theta[0] == theta0


def test_huge_starting_angle_through_simulate():
    """The fuzz case as a user meets it: simulate() on the scene (method auto)."""
    th = 2.0 ** 40
    far = pendula.simulate(pendula.Scene(theta0=th, v0=1.0, damping=0.1, t_end=10.0, n_samples=3))
    assert far.v[-1] == pytest.approx(_scipy(th, 1.0, 0.1)[1][-1], abs=1e-6)


def test_huge_starting_angle_keeps_angle_events_at_their_level():
    """An event at a level of the absolute angle (theta = theta0 + 1) is found where the motion
    relative to the start crosses +1, and reports that absolute angle."""
    th = 2.0 ** 30
    scene = pendula.Scene(theta0=th, v0=1.9, damping=0.05, rtol=1e-11, atol=1e-11)
    ev = find_events(scene, "theta", t_end=10.0, level=th + 1.0)
    sol = solve_ivp(lambda t, y: [y[1], -math.sin(y[0]) - 0.05 * y[1]], (0.0, 10.0), [_reduced(th), 1.9],
                    method="DOP853", rtol=1e-12, atol=1e-14,
                    events=lambda t, y: y[0] - _reduced(th) - 1.0)
    assert ev.t.size == sol.t_events[0].size >= 1
    assert np.abs(ev.t - sol.t_events[0]).max() < 1e-8
    assert np.abs(ev.theta - (th + 1.0)).max() <= 2 * math.ulp(th)

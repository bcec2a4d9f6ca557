"""Verner's 'most efficient' 8(7) pair with its order-8 interpolant (method 'vern8').

The orders are measured on one step of the kernel's own stepper from the exact solution of the
conservative pendulum (pendula.exact_motion: closed form, Jacobi functions): the step's end (x = 1,
the pair's 8th-order weights) has a local error C h^9, and so has the interpolant inside the step
(an interpolant of order 8); the exponents are fitted over steps where the asymptotic regime is
reached and round-off (~1e-14) stays far below.  Whole runs are checked against SciPy's DOP853 at
rtol 1e-13 on the equation written out here, and against the closed form with vern9's tests
(tests/test_integrators.py, tests/test_integrators_vern9_dense.py, parametrized over both pairs).  The coefficients are
checked against their order conditions in tests/test_verner87_coefficients.py.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pendula
from pendula import _kernel

VERN8 = 14      # the kernel's method code
PARAMS = np.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.0])
X = np.linspace(0.1, 0.9, 9)


def _one_step_error(h, theta0, v0, x):
    th, v = _kernel.verner_interpolant_v(VERN8, PARAMS, theta0, v0, h, x)
    ex_th, ex_v = pendula.exact_motion(theta0, v0, 1.0, x * h)
    return float(np.sqrt(np.sum((th - ex_th) ** 2 + (v - ex_v) ** 2)))


@pytest.mark.parametrize("theta0,v0", [(0.0, 1.9), (0.3, 1.5)])
def test_vern8_interpolant_is_of_order_eight(theta0, v0):
    """The interpolant's local error inside the step falls as h^9 (an interpolant of order 8; measured:
    fitted exponents 8.7 and 9.0, errors 3e-9 ... 2.5e-13).  Its weights reach 1.4e6: formed naively
    their rounding would add 1e-10 h^2 (a floor near 1e-11 here); the kernel's form (verner_dense)
    keeps it at 1e-10 h^3, below the interpolant's own error down to h = 0.16."""
    hs = (0.4, 0.32, 0.25, 0.2, 0.16)
    e = [_one_step_error(h, theta0, v0, X) for h in hs]
    slope = np.polyfit(np.log(hs), np.log(e), 1)[0]
    assert 8.5 < slope < 9.7, (e, slope)


@pytest.mark.parametrize("theta0,v0", [(0.0, 1.9), (0.3, 1.5)])
def test_vern8_step_is_of_order_eight(theta0, v0):
    """The step's end (x = 1: the weights b(1) = b of the pair) has a local error falling at least as
    h^9 (measured: fitted exponents 10.9 and 9.7 over h = 0.8 ... 0.4: on these arcs the h^9 term's
    coefficient is small; that the pair is of order 8 and no more is its order conditions' test)."""
    hs = (0.8, 0.64, 0.5, 0.4)
    e = [_one_step_error(h, theta0, v0, np.array([1.0])) for h in hs]
    slope = np.polyfit(np.log(hs), np.log(e), 1)[0]
    assert slope > 8.5 and max(e) < 1e-6, (e, slope)


def test_vern8_interpolant_starts_on_the_step():
    """At x = 0 the interpolant gives the step's start exactly (its weights vanish there)."""
    th, v = _kernel.verner_interpolant_v(VERN8, PARAMS, 0.3, 1.5, 0.4, np.array([0.0]))
    assert th[0] == 0.3 and v[0] == 1.5


def test_vern8_damped_torqued_driven_scene_against_scipy():
    """Every effect of the rigid pendulum's force law, outputs by the interpolant and landed."""
    beta, tau, amp, om = 0.1, 0.2, 0.4, 0.7

    def f(tt, y):
        return [y[1], -math.sin(y[0]) - beta * y[1] + tau + amp * math.cos(om * tt)]
    t = np.linspace(0.0, 30.0, 31)
    ref = solve_ivp(f, (0.0, 30.0), [0.0, 2.3], method="DOP853", t_eval=t, rtol=1e-13, atol=1e-14)
    s = pendula.Scene(v0=2.3, damping=beta, torque=tau, drive_amplitude=amp, drive_frequency=om,
                      rtol=1e-11, atol=1e-11)
    for landed in (False, True):
        tr = pendula.simulate(s, t, method="vern8", land_on_outputs=landed)
        assert tr.method == "vern8"
        assert max(np.abs(tr.theta - ref.y[0]).max(), np.abs(tr.v - ref.y[1]).max()) < 1e-8, landed


def test_vern8_has_no_events_and_names_itself_in_the_scene():
    with pytest.raises(ValueError, match="dense output"):
        pendula.find_events(pendula.Scene(v0=1.0, rtol=1e-8), method="vern8")
    tr = pendula.simulate(pendula.Scene(v0=1.0, damping=0.05, rtol=1e-11, atol=1e-11, method="vern8"), [0.0, 5.0])
    assert tr.method == "vern8" and tr.stats["rhs_evaluations"] > 12 * tr.stats["steps"]

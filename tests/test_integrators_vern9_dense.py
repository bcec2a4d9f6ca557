"""Verner's 9(8) pair with its interpolant (method 'vern9').

The interpolant's order is measured on one step of the kernel's own stepper from the exact
solution of the conservative pendulum (pendula.exact_motion: closed form, Jacobi functions):
an interpolant of order 8 has a local error C h^9 inside the step (the step's own error, h^10, is
smaller): the exponent is fitted over steps where the asymptotic regime is reached.  Its coefficients are checked against their order conditions
in tests/test_verner_coefficients.py.
"""

import numpy as np
import pytest

import pendula
from pendula import _kernel
from pendula.integrate import integrate_scene

PARAMS = np.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.0])
X = np.linspace(0.1, 0.9, 9)


def _interp_error(h, theta0, v0):
    """The interpolant's error over nine points inside one step of size h (2-norm over points and components)."""
    th, v = _kernel.verner_interpolant_v(12, PARAMS, theta0, v0, h, X)
    ex_th, ex_v = pendula.exact_motion(theta0, v0, 1.0, X * h)
    return float(np.sqrt(np.sum((th - ex_th) ** 2 + (v - ex_v) ** 2)))


@pytest.mark.parametrize("theta0,v0,hs", [(0.0, 1.9, (0.5, 0.4, 0.32, 0.25, 0.2)),
                                          (0.3, 1.5, (0.5, 0.4, 0.32, 0.25))])
def test_verner_interpolant_is_of_order_eight(theta0, v0, hs):
    """The local error of the interpolant falls as h^9 (measured: the fitted exponent 9.27 and 8.9),
    from 1e-8 to 1e-12 (the steps chosen so that round-off, ~1e-14, stays far below)."""
    e = [_interp_error(h, theta0, v0) for h in hs]
    slope = np.polyfit(np.log(hs), np.log(e), 1)[0]
    assert 8.5 < slope < 9.7, (e, slope)


def test_verner_interpolant_starts_on_the_step():
    """At x = 0 the interpolant gives the step's start exactly (its weights vanish there)."""
    th, v = _kernel.verner_interpolant_v(12, PARAMS, 0.3, 1.5, 0.4, np.array([0.0]))
    assert th[0] == 0.3 and v[0] == 1.5


@pytest.mark.parametrize("method", ["vern9", "vern8"])
def test_verner_outputs_do_not_cut_the_steps(method):
    """101 outputs cost no more steps than 2 (the steps were shortened to land on each before), and
    the outputs are as accurate as the steps (against the closed form)."""
    s = pendula.Scene(v0=1.9, rtol=1e-11, atol=1e-11)
    t = np.linspace(0.0, 20.0, 101)
    many = integrate_scene(s, t, method)
    two = integrate_scene(s, [0.0, 20.0], method)
    assert many.stats["steps"] == two.stats["steps"]
    ex, vex = pendula.exact_motion(0.0, 1.9, 1.0, t)
    assert max(np.abs(many.theta - ex).max(), np.abs(many.v - vex).max()) <= 20 * abs(two.theta[-1] - ex[-1]) + 1e-11


def test_verner_lands_on_the_outputs_when_asked():
    """land_on_outputs: a step ends on each output, which then is a step's own value (more steps)."""
    s = pendula.Scene(v0=1.0, damping=0.1, rtol=1e-10, atol=1e-10)
    t = np.linspace(0.0, 20.0, 201)
    landed = pendula.simulate(s, t, method="vern9", land_on_outputs=True)
    free = pendula.simulate(s, t, method="vern9")
    assert landed.stats["accepted"] >= 200 > free.stats["accepted"]
    ref = pendula.simulate(s.replace(rtol=1e-14, atol=1e-14), t, method="dop853")
    assert np.abs(landed.theta - ref.theta).max() < 1e-8 and np.abs(free.theta - ref.theta).max() < 1e-8


def test_landing_is_refused_for_other_methods_and_non_bools():
    s = pendula.Scene(v0=1.0, damping=0.1)
    with pytest.raises(ValueError, match="land_on_outputs"):
        pendula.simulate(s, [0.0, 1.0], method="gsl-rk8pd", land_on_outputs=True)
    with pytest.raises(TypeError, match="land_on_outputs"):
        pendula.simulate(s, [0.0, 1.0], method="vern9", land_on_outputs="yes")

"""simulate(..., land_on_outputs=True) for DOPRI5 and DOP853: the steps end on the output times
(each output a step's own value) instead of interpolating.  References: the closed form of the
conservative pendulum (pendula.exact_motion) and SciPy's DOP853 at rtol 1e-13 on the equation alone."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pendula
from pendula.integrate import integrate_scene


@pytest.mark.parametrize("method", ["dopri5", "dop853", "vern9", "vern8"])
def test_landing_pairs_end_a_step_on_each_output(method):
    s = pendula.Scene(v0=1.9, rtol=1e-10, atol=1e-10)
    t = np.linspace(0.0, 20.0, 81)
    landed = pendula.simulate(s, t, method=method, land_on_outputs=True)
    free = pendula.simulate(s, t, method=method)
    ex, vex = pendula.exact_motion(0.0, 1.9, 1.0, t)
    assert landed.stats["accepted"] >= 80 and landed.stats["accepted"] > free.stats["accepted"]
    tol = {"dopri5": 1e-7}.get(method, 1e-8)
    for tr in (landed, free):
        assert max(np.abs(tr.theta - ex).max(), np.abs(tr.v - vex).max()) < tol, method
    assert landed.theta[0] == 0.0 and landed.v[0] == 1.9


def test_landing_backwards_and_on_a_damped_driven_scene():
    """Negative times (integrated backwards) and a drive: against SciPy on the equation alone."""
    s = pendula.Scene(v0=1.2, damping=0.2, drive_amplitude=0.5, drive_frequency=0.8, rtol=1e-11, atol=1e-11)
    t = np.array([-6.0, -2.5, 0.0, 1.0, 4.5, 9.0])

    def f(tt, y):
        return [y[1], -math.sin(y[0]) - 0.2 * y[1] + 0.5 * math.cos(0.8 * tt)]
    fw = solve_ivp(f, (0.0, 9.0), [0.0, 1.2], method="DOP853", t_eval=t[2:], rtol=1e-13, atol=1e-14)
    bw = solve_ivp(f, (0.0, -6.0), [0.0, 1.2], method="DOP853", t_eval=t[1::-1], rtol=1e-13, atol=1e-14)
    ref_th = np.concatenate([bw.y[0][::-1], fw.y[0]])
    tr = pendula.simulate(s, t, method="dop853", land_on_outputs=True)
    assert np.abs(tr.theta - ref_th).max() < 1e-8


"""The double pendulum's default Gauss-Legendre step from its time scales in the kernel (the fast normal
mode, the damping, the whirl a high energy allows).  References: NumPy's eigensolver for the modes, SciPy's
DOP853 at rtol 1e-13 for the path (the equations written out here from Lagrange's)."""

import math

import numpy as np
from scipy.integrate import solve_ivp

import pendula


def _scipy_theta1(t, theta1, omega1):
    """θ₁(t) of the unit point-mass double pendulum (m = l = g = 1) started at (θ₁, 0, ω₁, 0)."""
    def rhs(_, y):
        t1, t2, w1, w2 = y
        d = t1 - t2
        mass = np.array([[2.0, math.cos(d)], [math.cos(d), 1.0]])
        f = np.array([-math.sin(d) * w2 * w2 - 2.0 * math.sin(t1), math.sin(d) * w1 * w1 - math.sin(t2)])
        return [w1, w2, *np.linalg.solve(mass, f)]

    return solve_ivp(rhs, (0.0, float(t[-1])), [theta1, 0.0, omega1, 0.0], method="DOP853", t_eval=t,
                     rtol=1e-13, atol=1e-13).y[0]


def test_default_step_at_low_energy_is_a_hundredth_of_the_fast_modes_period():
    """At rest at the bottom the step is 2π/ω₊/100, ω₊² the larger eigenvalue of M⁻¹G (M = [[2, 1], [1, 1]],
    G = diag(2, 1) for unit point masses), for point masses and rods, damped or not."""
    for kw in ({}, {"rods": True}, {"m1": 3.0, "l2": 0.4, "damping": 0.01}):
        dp = pendula.DoublePendulum(**kw)
        w2 = dp.modes().omega.max() ** 2
        a, b, c, ga, gb = _coefficients(dp)
        ref = float(np.max(np.linalg.eigvals(np.linalg.solve([[a, b], [b, c]], np.diag([ga, gb])))).real)
        assert abs(w2 - ref) < 1e-13 * ref
        assert math.isclose(dp._default_dt(), 2 * math.pi / math.sqrt(ref) / 100, rel_tol=1e-13)


def _coefficients(dp):
    m1, m2, l1, l2, g, rods = dp._p[:6]
    if rods:
        return (m1 / 3 + m2) * l1 ** 2, m2 * l1 * l2 / 2, m2 * l2 ** 2 / 3, g * (m1 / 2 + m2) * l1, g * m2 * l2 / 2
    return (m1 + m2) * l1 ** 2, m2 * l1 * l2, m2 * l2 ** 2, g * (m1 + m2) * l1, g * m2 * l2


def test_whirling_start_default_step_resolves_the_rotation():
    """Started at θ₁ = 0.3 with ω₁ = 12 (the arms whirl: 6.5 times the fast mode's rate), the default step
    follows the whirl: θ₁ agrees with SciPy's DOP853 (rtol 1e-13) to 1e-9 rad over 5 time units (measured
    4e-12); the step of the modes alone (1/100 of the fast mode's period) is off by 1.1e-4 rad, five
    orders of magnitude more."""
    dp = pendula.DoublePendulum()
    t = np.linspace(0.0, 5.0, 11)
    ref = _scipy_theta1(t, 0.3, 12.0)
    run = dp.simulate(t, 0.3, 0.0, 12.0, 0.0)
    assert run.attrs["method"] == "gauss6"
    assert float(np.max(np.abs(run.theta1.values - ref))) < 1e-9
    h_modes = float(dp.modes().period[1]) / 100
    old = dp.simulate(t, 0.3, 0.0, 12.0, 0.0, dt=0.5 / math.ceil(0.5 / h_modes))
    assert float(np.max(np.abs(old.theta1.values - ref))) > 1e-5


def test_default_step_shrinks_with_the_energy_of_the_start():
    """A small swing keeps the modes' step; a start above the energy of a flip (ω₁ >= 3 here) gets the
    whirl's, finer as the energy grows."""
    dp = pendula.DoublePendulum()
    steps = []
    for w0 in (0.0, 3.0, 6.0, 12.0):
        y = np.array([0.3, 0.0, 0.0, 0.0])
        y[2], y[3] = dp._momenta(0.3, 0.0, w0, 0.0)
        steps.append(dp._default_dt(y))
    assert math.isclose(steps[0], float(dp.modes().period[1]) / 100, rel_tol=1e-13)
    assert steps[0] > steps[1] > steps[2] > steps[3]


def test_section_default_step_follows_the_energy():
    """The Poincaré section's default step is the one simulate takes from a state of the section's
    energy (the whirl's above the flip energy, the modes' at a low energy)."""
    dp = pendula.DoublePendulum()
    low = dp.poincare(0.05, [0.0], [0.0], t_max=50.0)
    high = dp.poincare(20.0, [0.0], [0.0], t_max=50.0)
    h_modes = float(dp.modes().period[1]) / 100
    assert math.isclose(low.attrs["dt"], h_modes, rel_tol=1e-13)
    lmin = (3 - math.sqrt(5)) / 2    # the smaller eigenvalue of M = [[2, 1], [1, 1]]
    assert math.isclose(high.attrs["dt"], 2 * math.pi / math.sqrt(2 * 20.0 / lmin) / 100, rel_tol=1e-12)

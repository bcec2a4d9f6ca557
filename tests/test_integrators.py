"""Integrators, effects and events, checked against the exact solution and the
source notes' numbers.

Order checks: the error ratio when dt is halved must be 2^p within 30 %
(the asymptotic regime is reached at the steps chosen; the reference is the
exact solution, so the measured error is the method's own).
"""

import math

import numpy as np
import pytest

import pendula
from pendula.integrate import integrate_scene
from conftest import EPS

T_OUT = np.linspace(0.0, 20.0, 11)


def err(method, v0=1.0, **kw):
    s = pendula.Scene(v0=v0, **kw)
    ex, _ = pendula.exact_motion(0.0, v0, 1.0, T_OUT)
    tr = integrate_scene(s, T_OUT, method)
    return np.abs(tr.theta - ex).max(), tr


@pytest.mark.parametrize("method,order,dt", [
    ("rk4", 4, 0.05), ("verlet", 2, 0.02), ("yoshida4", 4, 0.04), ("yoshida6", 6, 0.1),
    ("yoshida8", 8, 0.25), ("gauss4", 4, 0.05), ("gauss6", 6, 0.2),
])
def test_fixed_step_methods_reach_their_order(method, order, dt):
    e1, _ = err(method, dt=dt)
    e2, _ = err(method, dt=dt / 2)
    assert e1 / e2 == pytest.approx(2**order, rel=0.3), (e1, e2)


@pytest.mark.parametrize("method", ["dopri5", "dop853", "gsl-rk8pd"])
def test_adaptive_methods_converge_with_the_tolerance(method):
    errs = [err(method, rtol=tol, atol=tol * 1e-2)[0] for tol in (1e-6, 1e-9, 1e-12)]
    assert errs[0] > errs[1] > errs[2]
    assert errs[2] < 1e-8


def test_dense_output_is_as_accurate_as_the_steps():
    """Output at 2001 points from the dense output of DOP853 is as good as at 2."""
    s = pendula.Scene(v0=1.9, rtol=1e-12, atol=1e-14)
    t = np.linspace(0, 20, 2001)
    ex, _ = pendula.exact_motion(0.0, 1.9, 1.0, t)
    tr = integrate_scene(s, t, "dop853")
    end = integrate_scene(s, [0.0, 20.0], "dop853")
    assert np.abs(tr.theta - ex).max() <= 20 * abs(end.theta[-1] - ex[-1]) + 1e-12
    assert tr.stats["steps"] == end.stats["steps"]          # steps were not shortened


def test_times_in_any_order_and_backwards():
    s = pendula.Scene(v0=1.2, rtol=1e-12, atol=1e-14)
    t = np.array([5.0, -3.0, 0.0, 2.5, -7.0])
    ex, vex = pendula.exact_motion(0.0, 1.2, 1.0, t)
    for method in ("dop853", "dopri5"):
        tr = integrate_scene(s, t, method)
        assert np.abs(tr.theta - ex).max() < 1e-9 and np.abs(tr.v - vex).max() < 1e-9
    tr = integrate_scene(s.replace(dt=0.01), t, "gauss6")
    assert np.abs(tr.theta - ex).max() < 1e-10


def test_every_method_conserves_energy_of_the_conservative_pendulum():
    """Source 003, task 1: energy along a numerical solution (100 periods)."""
    t = np.linspace(0, 100 * pendula.orbit(0, 1.5).period, 201)
    for method in ("rk4", "verlet", "yoshida4", "yoshida6", "yoshida8", "gauss4", "gauss6"):
        tr = integrate_scene(pendula.Scene(v0=1.5, dt=0.05), t, method)
        dE = np.abs(tr.energy - 1.125).max()
        assert dE < {"verlet": 2e-3, "rk4": 1e-5}.get(method, 1e-6), (method, dE)
    for method in ("dopri5", "dop853", "gsl-rk8pd"):
        tr = integrate_scene(pendula.Scene(v0=1.5, rtol=1e-11, atol=1e-13), t, method)
        assert np.abs(tr.energy - 1.125).max() < 1e-8, method


def test_symplectic_methods_do_not_drift():
    """Energy error of Yoshida and Gauss stays bounded over 2000 periods; RK4's drifts."""
    P = pendula.orbit(0, 1.5).period
    t = np.array([0.0, 10 * P, 2000 * P])
    for method in ("yoshida4", "gauss4"):
        tr = integrate_scene(pendula.Scene(v0=1.5, dt=0.1), t, method)
        e10, e2000 = np.abs(tr.energy[1:] - 1.125)
        assert e2000 < 20 * max(e10, 1e-13), (method, e10, e2000)
    tr = integrate_scene(pendula.Scene(v0=1.5, dt=0.1), t, "rk4")
    e10, e2000 = np.abs(tr.energy[1:] - 1.125)
    assert e2000 > 50 * e10


def test_gauss6_long_run_is_round_off_limited():
    """Gauss-Legendre with compensated summation: 1e4 periods, energy error a
    few eps times sqrt(steps) (Brouwer's law), far below DOP853 at rtol 1e-12."""
    P = pendula.orbit(0, 1.0).period
    t = np.array([0.0, 1e4 * P])
    g = integrate_scene(pendula.Scene(v0=1.0, dt=P / 40), t, "gauss6")
    steps = 4e5
    assert abs(g.energy[-1] - 0.5) < 20 * EPS * math.sqrt(steps)


# ------------------------------------------------------------ effects

def test_damped_pendulum_settles_in_the_published_wells():
    """Suzuki & Suzuki 7.2.1, v0 = 2.3, eps = 1: the well 2 n pi for each beta.
    The notes print n = 1 for beta = 0.04; it is n = 2 (seeds README: a misprint)."""
    published = {0.16: 0, 0.12: 1, 0.08: 1, 0.04: 2, 0.02: 3, 0.018: 4, 0.016: 4, 0.014: 5,
                 0.012: 6, 0.010: 7}
    for beta, n in published.items():
        s = pendula.Scene(v0=2.3, damping=beta, rtol=1e-10, atol=1e-12)
        tr = pendula.simulate(s, [0.0, 3000.0])
        assert tr.method in ("dop853", "vern9", "vern8")     # auto's pick: tests/test_integrators_auto.py
        assert round(tr.theta[-1] / (2 * np.pi)) == n, beta
        assert abs(tr.theta[-1] - 2 * np.pi * n) < 1e-3 and abs(tr.v[-1]) < 1e-3


def test_constant_torque_locks_below_and_runs_above():
    """Suzuki & Suzuki 8.2.2: beta = 0.16, v0 = 1.98; locked for tau <= 0.20 (theta -> asin tau,
    the Josephson junction's zero-voltage state), running for tau >= 0.22."""
    t = np.linspace(300, 400, 101)
    for tau in (0.19, 0.20):
        tr = pendula.simulate(pendula.Scene(v0=1.98, damping=0.16, torque=tau, rtol=1e-10), t)
        assert np.abs(tr.v).max() < 1e-6 and abs(tr.theta[-1] - math.asin(tau)) < 1e-6
    for tau in (0.22, 0.23, 0.24):
        tr = pendula.simulate(pendula.Scene(v0=1.98, damping=0.16, torque=tau, rtol=1e-10), t)
        assert tr.v.mean() > 0.9 and tr.theta[-1] > 300


def test_drive_enters_the_right_hand_side():
    """A weak drive on the linearised pendulum: theta'' + theta = A cos(W t) from rest
    has theta = A (cos W t - cos t) / (1 - W^2); at amplitude 1e-6 the sine's cubic term is 1e-19."""
    A, W = 1e-6, 0.5
    t = np.linspace(0, 30, 61)
    tr = pendula.simulate(pendula.Scene(drive_amplitude=A, drive_frequency=W, rtol=1e-12, atol=1e-20), t)
    want = A * (np.cos(W * t) - np.cos(t)) / (1 - W * W)
    assert np.abs(tr.theta - want).max() < 1e-14


def test_absent_effects_are_not_in_the_model():
    s = pendula.Scene(v0=1.5, damping=0.0, torque=0.0)
    assert s.effects == () and pendula.simulate(s).method == "exact"
    assert pendula.simulate(s.replace(damping=0.1)).method in ("dop853", "vern9", "vern8")   # auto's table


# ------------------------------------------------------------ events and periods

def test_numerical_period_by_event_location():
    """Source 003, task 2: the period found by event location against 4K/sqrt(eps)."""
    for th0, v0, eps in [(1.0, 0.0, 1.0), (0.0, 1.999, 1.0), (0.0, 2.5, 4.0), (2.0, -0.3, 9.81)]:
        s = pendula.Scene(theta0=th0, v0=v0, eps=eps, rtol=1e-12, atol=1e-14)
        exact = pendula.period(s)
        assert abs(pendula.numerical_period(s) / exact - 1) < 1e-9


def test_two_zeros_in_one_step_are_both_found():
    """theta grazing a level 1e-6 below its maximum crosses it twice within
    ~3e-3 time units, far inside one DOP853 step: both crossings, every period."""
    s = pendula.Scene(v0=1.0, rtol=1e-12, atol=1e-14)
    T = pendula.period(s)
    o = pendula.orbit(0.0, 1.0)
    level = o.theta_max - 1e-6
    ev = pendula.find_events(s, "theta", level=level, t_end=10 * T)
    assert ev.t.size == 20
    assert np.all(np.diff(ev.t)[0::2] < 5e-3)              # the pairs, each inside one step
    assert np.abs(ev.theta - level).max() < 1e-12
    mid = 0.5 * (ev.t[0::2] + ev.t[1::2])                   # centred on the maxima T/4 + k T
    assert np.abs(mid - (T / 4 + np.arange(10) * T)).max() < 1e-8
    turning = pendula.find_events(s.replace(rtol=1e-3, atol=1e-3), "turning", t_end=50 * T)
    assert turning.t.size == 100                            # loose tolerance: still every one


def test_an_event_that_starts_at_zero_is_not_reported_there():
    s = pendula.Scene(theta0=0.0, v0=1.0, rtol=1e-12, atol=1e-14)
    T = pendula.period(s)
    ev = pendula.find_events(s, "theta", level=0.0, t_end=1.2 * T)
    assert ev.t[0] == pytest.approx(T / 2, rel=1e-10) and ev.t.size == 2
    assert ev.t[1] == pytest.approx(T, rel=1e-10)


def test_terminal_event_and_direction():
    s = pendula.Scene(v0=1.0, rtol=1e-12, atol=1e-14)
    T = pendula.period(s)
    ev = pendula.find_events(s, "turning", direction=+1, t_end=5 * T, terminal=True)
    assert ev.t.size == 1 and ev.t[0] == pytest.approx(0.75 * T, rel=1e-10) and ev.stats["stopped_by_event"]
    assert ev.theta[0] < 0


# ------------------------------------------------------------ bad input

@pytest.mark.parametrize("kw,method,what", [
    (dict(dt=0.0), "rk4", "dt > 0"),
    (dict(), "rk5", "unknown method"),
    (dict(dt=0.1), "gsl-rk8pd", None),
])
def test_bad_method_arguments(kw, method, what):
    s = pendula.Scene(v0=1.0, **kw)
    if what is None:
        with pytest.raises(ValueError, match="forward only"):
            integrate_scene(s, [-1.0, 1.0], method)
    else:
        with pytest.raises(ValueError, match=what):
            integrate_scene(s, [0.0, 1.0], method)


def test_events_need_dense_output_and_sane_arguments():
    s = pendula.Scene(v0=1.0, dt=0.1)
    with pytest.raises(ValueError, match="dense output"):
        pendula.find_events(s, method="rk4")
    with pytest.raises(ValueError, match="kind"):
        pendula.find_events(s, kind="apex")
    with pytest.raises(ValueError, match="t_end"):
        pendula.find_events(s, t_end=-1.0)
    with pytest.raises(ValueError, match="tolerance|rtol"):
        pendula.Scene(v0=1.0, rtol=0.0)


# ------------------------------------------------------------ the Runge-Kutta-Nystrom pair

def test_nystrom_pair_converges_with_the_tolerance_forwards_and_backwards():
    t = np.array([-13.7, -2.0, 0.0, 3.3, 25.0])
    ex, vex = pendula.exact_motion(0.0, 1.9, 1.0, t)
    errs = []
    for tol in (1e-6, 1e-9, 1e-12):
        tr = integrate_scene(pendula.Scene(v0=1.9, rtol=tol, atol=tol), t, "dprkn6")
        errs.append(max(np.abs(tr.theta - ex).max(), np.abs(tr.v - vex).max()))
    assert errs[0] > errs[1] > errs[2], errs
    # near the separatrix (v0 = 1.9) the error grows along the run: 1e3 times the tolerance
    assert errs[2] < 1e-9, errs


def test_nystrom_pair_lands_on_the_output_times():
    """No dense output: the steps end on the output times, so the output count shows in the steps."""
    s = pendula.Scene(v0=1.0, rtol=1e-10, atol=1e-10)
    few = integrate_scene(s, [0.0, 20.0], "dprkn6")
    many = integrate_scene(s, np.linspace(0.0, 20.0, 401), "dprkn6")
    ex, _ = pendula.exact_motion(0.0, 1.0, 1.0, np.linspace(0.0, 20.0, 401))
    assert many.stats["steps"] > few.stats["steps"]
    assert np.abs(many.theta - ex).max() < 1e-8


def test_nystrom_pair_takes_torque_and_drive():
    """Forces that depend on t and theta only are the pair's domain: compared with DOP853 at 1e-13."""
    t = np.linspace(0.0, 30.0, 7)
    s = pendula.Scene(v0=0.3, torque=0.2, drive_amplitude=0.4, drive_frequency=0.7, rtol=1e-12, atol=1e-12)
    a = integrate_scene(s, t, "dprkn6")
    b = integrate_scene(s.replace(rtol=1e-14, atol=1e-14), t, "dop853")
    assert np.abs(a.theta - b.theta).max() < 1e-9


def test_nystrom_pair_refuses_damping_and_events():
    s = pendula.Scene(v0=1.0, damping=0.1, rtol=1e-8, atol=1e-8)
    with pytest.raises(ValueError, match="damped scene needs another method"):
        integrate_scene(s, [0.0, 1.0], "dprkn6")
    with pytest.raises(ValueError, match="dense output"):
        pendula.find_events(pendula.Scene(v0=1.0, rtol=1e-8), method="dprkn6")


def test_nystrom_pair_through_simulate():
    s = pendula.Scene(v0=1.0, rtol=1e-11, atol=1e-11, method="dprkn6")
    tr = pendula.simulate(s, [0.0, 5.0, 10.0])
    ex, _ = pendula.exact_motion(0.0, 1.0, 1.0, [0.0, 5.0, 10.0])
    assert np.abs(tr.theta - ex).max() < 1e-9
    with pytest.raises(Exception, match="dprkn6|damping|method"):
        pendula.simulate(s.replace(damping=0.2), [0.0, 1.0])


# ------------------------------------------------------------ Verner's 9(8) pair

@pytest.mark.parametrize("method", ["vern9", "vern8"])
def test_verner_pair_converges_with_the_tolerance_forwards_and_backwards(method):
    t = np.array([-13.7, -2.0, 0.0, 3.3, 25.0])
    ex, vex = pendula.exact_motion(0.0, 1.9, 1.0, t)
    errs = []
    for tol in (1e-6, 1e-9, 1e-12):
        tr = integrate_scene(pendula.Scene(v0=1.9, rtol=tol, atol=tol), t, method)
        errs.append(max(np.abs(tr.theta - ex).max(), np.abs(tr.v - vex).max()))
    assert errs[0] > errs[1] > errs[2], errs
    assert errs[2] < 1e-9, errs


def test_verner_pair_takes_damping_torque_and_drive():
    t = np.linspace(0.0, 30.0, 7)
    s = pendula.Scene(v0=2.3, damping=0.1, torque=0.2, drive_amplitude=0.4, drive_frequency=0.7,
                      rtol=1e-12, atol=1e-12)
    a = integrate_scene(s, t, "vern9")
    b = integrate_scene(s.replace(rtol=1e-14, atol=1e-14), t, "dop853")
    assert np.abs(a.theta - b.theta).max() < 1e-9


def test_verner_pair_has_no_events_and_runs_through_simulate():
    with pytest.raises(ValueError, match="dense output"):
        pendula.find_events(pendula.Scene(v0=1.0, rtol=1e-8), method="vern9")
    tr = pendula.simulate(pendula.Scene(v0=1.0, damping=0.05, rtol=1e-11, atol=1e-11, method="vern9"), [0.0, 5.0])
    ref = pendula.simulate(pendula.Scene(v0=1.0, damping=0.05, rtol=1e-14, atol=1e-14, method="dop853"), [0.0, 5.0])
    assert tr.method == "vern9" and abs(tr.theta[-1] - ref.theta[-1]) < 1e-9

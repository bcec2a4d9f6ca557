"""Huygens' cycloidal pendulum (Prusa & Tuma, section 4): closed form at every
amplitude, checked against independent integrations of theta's own equation
(scipy's solve_ivp, not pendula), geometry and the limits.

Tolerances, with the reason: the closed form's theta = asin(s / 4R) carries
a few eps of s; scipy's DOP853 at rtol 1e-13 is good to ~1e-11 over these
spans; the small-amplitude agreement with the rigid pendulum is O(theta0^2)
(the two periods differ by theta0^2/16 relative)."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pendula
from pendula import Scene

EPS = np.finfo(float).eps


def theta_rhs(eps, r, beta=0.0, tau=0.0, amp=0.0, omega=0.0, phase=0.0):
    """theta'' on the cycloid from s = 4R sin(theta), written in theta (independent of pendula)."""
    w2 = eps / (4 * r)

    def f(t, y):
        th, v = y
        force = tau + amp * math.cos(omega * t + phase)       # along the path, divided by 4R
        # s'' = 4R (cos th th'' - sin th th'^2) = -w2 s - beta s' + 4R force
        acc = (math.sin(th) * v * v - w2 * math.sin(th) - beta * math.cos(th) * v + force) / math.cos(th)
        return [v, acc]
    return f


@pytest.mark.parametrize("theta0", [1e-6, 0.1, 0.7, 1.2, 1.5, 1.5707])
def test_period_is_independent_of_the_amplitude_up_to_the_cusp(theta0):
    s = Scene(guide="cycloid", theta0=theta0, eps=2.0)
    T = pendula.cycloid_period(2.0)
    t = np.array([0.0, T, 7 * T, 1000 * T])
    tr = pendula.simulate(s, t)
    # the state returns after every whole number of periods, to a few eps; at 1000 T
    # the phase omega t carries the rounding of t = 1000 T itself (~1e-12 of a radian),
    # which moves theta only at second order next to the turning point
    # (theta = asin(s / 4R) is conditioned like 1 / cos(theta): next to the cusps the cord is
    # horizontal and a few eps of s are eps / cos(theta) of theta)
    assert np.all(np.abs(tr.theta[:3] - theta0) <= 8 * EPS / math.cos(theta0)), tr.theta - theta0
    assert abs(tr.theta[3] - theta0) <= 1e-12 + 8 * EPS / math.cos(theta0)


def test_closed_form_agrees_with_an_independent_integration_at_large_amplitude():
    th0, v0, eps, r = 1.3, 0.2, 1.5, 0.25
    t = np.linspace(0, 15, 31)
    tr = pendula.simulate(Scene(guide="cycloid", theta0=th0, v0=v0, eps=eps, guide_radius=r), t)
    ref = solve_ivp(theta_rhs(eps, r), (0, 15), [th0, v0], method="DOP853", rtol=1e-13, atol=1e-15, t_eval=t)
    assert np.abs(tr.theta - ref.y[0]).max() < 1e-10 and np.abs(tr.v - ref.y[1]).max() < 1e-9


def test_damped_driven_torqued_guide_stays_closed_form_and_agrees():
    kw = dict(damping=0.3, torque=0.05, drive_amplitude=0.1, drive_frequency=1.3, drive_phase=0.4)
    th0, v0, eps, r = 0.5, -0.3, 1.0, 0.3
    t = np.linspace(0, 25, 26)
    tr = pendula.simulate(Scene(guide="cycloid", theta0=th0, v0=v0, eps=eps, guide_radius=r, **kw), t)
    assert tr.method == "exact" and tr.stats == {}
    f = theta_rhs(eps, r, 0.3, 0.05, 0.1, 1.3, 0.4)
    ref = solve_ivp(f, (0, 25), [th0, v0], method="DOP853", rtol=1e-13, atol=1e-15, t_eval=t)
    assert np.abs(tr.theta - ref.y[0]).max() < 1e-10


def test_energy_is_conserved_without_effects():
    tr = pendula.simulate(Scene(guide="cycloid", theta0=1.4, v0=0.1), np.linspace(-500, 500, 2001))
    assert np.abs(tr.energy - tr.energy[1000]).max() <= 16 * EPS * tr.energy[1000]


@pytest.mark.parametrize("height", [0.05, 0.3, 0.8, 1.2, 1.55])
def test_tautochrone_descent_takes_a_quarter_period_from_every_height(height):
    """Abel's tautochrone (section 4.2), measured by an independent integration
    with an event at the lowest point."""
    eps, r = 1.0, 0.25
    ev = lambda t, y: y[0]  # noqa: E731
    ev.terminal, ev.direction = True, -1
    sol = solve_ivp(theta_rhs(eps, r), (0, 10), [height, 0.0], method="DOP853", rtol=1e-13, atol=1e-15,
                    events=ev)
    T = pendula.cycloid_period(eps, r)
    assert abs(sol.t_events[0][0] - T / 4) < 1e-10
    # and the closed form passes through the bottom exactly then
    tr = pendula.simulate(Scene(guide="cycloid", theta0=height, eps=eps), [T / 4])
    assert abs(tr.theta[0]) <= 4 * EPS


def test_small_amplitude_agrees_with_the_rigid_pendulum_to_second_order():
    t = np.linspace(0, 30, 61)
    diffs = []
    for a in (0.02, 0.01):
        cyc = pendula.simulate(Scene(guide="cycloid", theta0=a), t).theta
        rig = pendula.simulate(Scene(theta0=a), t).theta
        diffs.append(np.abs(cyc - rig).max() / a)
    # relative difference O(a^2): halving a quarters it
    assert 3.0 < diffs[0] / diffs[1] < 5.0 and diffs[0] < 1e-3


def test_the_involute_of_the_cheek_is_the_path():
    g = pendula.cycloid_geometry(0.25)
    for th in (-1.4, -0.6, 0.0, 0.3, 1.1, 1.5):
        x, y = g.cord(th)
        # the free cord's end is the bob on the path, and the cord's total length is l = 4R
        px = 0.25 * (2 * th + math.sin(2 * th))
        py = -0.25 * (3 + math.cos(2 * th))
        assert abs(x[-1] - px) <= 4 * EPS and abs(y[-1] - py) <= 4 * EPS
        wrapped = np.sum(np.hypot(np.diff(x[:-1]), np.diff(y[:-1])))
        free = math.hypot(x[-1] - x[-2], y[-1] - y[-2])
        assert abs(wrapped + free - 1.0) < 1e-3   # polygonal arc of 64 points: 1e-3


def test_motion_beyond_the_cusps_is_an_error_naming_the_limit():
    with pytest.raises(ValueError, match="cusp"):
        pendula.simulate(Scene(guide="cycloid", theta0=1.5, v0=3.0), [1.0])
    with pytest.raises(ValueError, match="cusp"):
        # near resonance the steady amplitude 4R A / |omega0^2 - Omega^2| = 2 / 0.21 passes the cusps
        pendula.simulate(Scene(guide="cycloid", theta0=0.1, drive_amplitude=2.0, drive_frequency=1.1), [1.0])


def test_integrators_are_never_used_on_the_guide():
    with pytest.raises(ValueError, match="closed form"):
        pendula.simulate(Scene(guide="cycloid", theta0=0.3, method="dop853"), [1.0])


def test_pendula_run_runs_the_guide(tmp_path):
    import subprocess

    from conftest import venv_bin

    f = tmp_path / "c.nml"
    f.write_text("&scene\n guide = 'cycloid', theta0 = 1.2, t_end = 3.0, n_samples = 4\n/\n")
    p = subprocess.run([venv_bin("pendula-run"), str(f)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    rows = [ln for ln in p.stdout.splitlines() if ln and not ln.startswith("#")][1:]
    th = np.array([float(r.split(",")[1]) for r in rows])
    py = pendula.simulate(Scene(guide="cycloid", theta0=1.2, t_end=3.0, n_samples=4)).theta
    assert np.allclose(th, py, rtol=0, atol=1e-15)

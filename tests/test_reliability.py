"""Bad input and hard conditions: no crash, no hang, no silent wrong
number.  Each test is named for the class it keeps fixed."""

import math
import signal
import subprocess
import sys
import warnings

import mpmath as mp
import numpy as np
import pytest

import pendula
from conftest import run_threads
from pendula import Scene
from test_reliability_sweeps import _stops_on_sigint

EPS = np.finfo(float).eps


# ------------------------------------------------------------ work limits (no hang, no wrapped count)

def test_tiny_dt_is_an_error_naming_the_limit_not_a_wrapped_step_count():
    for method in ("rk4", "verlet", "yoshida8", "gauss6"):
        with pytest.raises(ValueError, match="dt|work limit"):
            pendula.simulate(Scene(v0=1, damping=0.1, t_end=10, n_samples=3, dt=1e-18, method=method))


@pytest.mark.parametrize("scene,t", [(Scene(v0=1, damping=0.1), [1e15]),
                                     (Scene(v0=1, drive_amplitude=0.5, drive_frequency=1e300), None)])
def test_hopeless_spans_fail_at_once_with_the_work_limit(scene, t):
    with pytest.raises(ValueError, match="work limit"):
        pendula.simulate(scene, t)


def test_events_need_a_finite_end_and_a_sane_budget():
    with pytest.raises(ValueError, match="t_end"):
        pendula.find_events(Scene(v0=1), "turning", t_end=float("inf"))
    with pytest.raises(ValueError, match="work limit"):
        pendula.find_events(Scene(v0=1), "turning", t_end=1e15)
    with pytest.raises(ValueError, match="max_events"):
        pendula.find_events(Scene(v0=1), "turning", max_events=2**31)
    with pytest.raises(TypeError, match="terminal"):
        pendula.find_events(Scene(v0=1), "turning", terminal="no")


def test_numerical_period_refuses_an_absurd_number_of_periods():
    with pytest.raises(ValueError, match="periods"):
        pendula.numerical_period(Scene(v0=1), periods=1e9)


def test_long_call_stops_on_sigint():
    _stops_on_sigint("pendula.simulate(pendula.Scene(v0=1.0, damping=0.5, drive_amplitude=1.2,\n"
                     "                               drive_frequency=2 / 3), [3e6])", wait=0.5)


# ------------------------------------------------------------ extreme parameters: right values, or NaN + warning

def test_tiny_output_time_is_integrated_not_an_underflow():
    tr = pendula.simulate(Scene(v0=1, damping=0.1), [1e-15])
    assert abs(tr.theta[0] - 1e-15) <= 2 * EPS * 1e-15


def test_complete_integrals_at_subnormal_mc():
    assert pendula.ellipe(None, mc=1e-310) == 1.0
    with mp.workdps(400):   # enough digits to hold 1 - 5e-324
        q = mp.exp(-mp.pi * mp.ellipk(mp.mpf(5e-324)) / mp.ellipk(1 - mp.mpf(5e-324)))
    assert abs(pendula.nome(None, mc=5e-324) - float(q)) <= 4 * EPS * float(q)


def test_orbit_with_tiny_eps_is_a_fast_rotation_with_the_right_period():
    o = pendula.orbit(0.0, 1.0, 1e-307)
    # k^2 = 1/(4 eps) = 2.5e306: one turn takes 2 K(1/k^2) / (k sqrt(eps)) -> 2 (pi/2) / (1/2) = 2 pi
    assert o.regime == "rotation" and abs(o.period - 2 * math.pi) <= 4 * EPS * 2 * math.pi


def test_huge_theta0_is_reduced_or_refused_naming_theta0():
    th, v = pendula.exact_motion(1e15, 0.0, 1.0, [0.0, 1.0])
    with mp.workdps(60):
        r = mp.fmod(mp.mpf(1e15), 2 * mp.pi)
        r = r - 2 * mp.pi if r > mp.pi else r
    th_r, v_r = pendula.exact_motion(float(r), 0.0, 1.0, [1.0])
    assert v[0] == 0.0 and abs(v[1] - v_r[0]) <= 8 * EPS
    with pytest.raises(ValueError, match="theta0"):
        pendula.exact_motion(1e18, 0.0, 1.0, [1.0])


def test_empty_in_empty_out():
    e = np.array([])
    for f in (pendula.ellipk, pendula.ellipe, pendula.nome):
        assert f(e).shape == (0,)
    for f in (pendula.ellipf, pendula.ellipeinc):
        assert f(e, 0.5).shape == (0,)
    assert all(a.shape == (0,) for a in pendula.ellipj(e, 0.5))
    assert pendula.exact_motion(0.0, 1.0, 1.0, e)[0].shape == (0,)
    assert pendula.simulate(Scene(v0=1, damping=0.1), e).theta.shape == (0,)
    assert pendula.spectra(np.arange(64.0), np.empty((0, 64))) == []


def test_signal_without_a_line_has_no_fundamental():
    with pytest.warns(RuntimeWarning, match="no fundamental"):
        assert math.isnan(pendula.spectrum(np.arange(64.0), np.zeros(64)).fundamental)


# ------------------------------------------------------------ unclear errors

@pytest.mark.parametrize("eps", ["a", 1j, [1, [2]]])
def test_energy_names_a_bad_eps(eps):
    with pytest.raises(TypeError, match="eps"):
        pendula.energy(0.0, 1.0, eps=eps)


def test_scene_refuses_a_list_valued_method_naming_it():
    with pytest.raises(ValueError, match="method"):
        pendula.simulate(Scene(v0=1, damping=0.1), [1.0], method=["rk4"])


# ------------------------------------------------------------ accuracy cliffs

def test_numerical_period_near_the_separatrix_warns_or_is_right():
    s = Scene(v0=2 - 1e-12)
    exact = pendula.period(s)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        got = pendula.numerical_period(s)
    assert abs(got - exact) <= 1e-6 * exact or any(issubclass(x.category, RuntimeWarning) for x in w)


# ------------------------------------------------------------ threads

def test_ellipj_simulate_and_events_from_threads_match_serial():
    rng = np.random.default_rng(6)
    us = [rng.uniform(-1e3, 1e3, n) for n in (10, 1000, 50_000)]
    ref_j = [pendula.ellipj(u, 0.7) for u in us]
    scenes = [Scene(v0=1.0 + 0.1 * k, damping=0.05) for k in range(3)]
    t = np.linspace(0, 50, 201)
    ref_s = [pendula.simulate(s, t).theta for s in scenes]
    ref_e = [pendula.find_events(s, "turning", t_end=40.0).t for s in scenes]

    def go():
        for _ in range(5):
            for u, r in zip(us, ref_j):
                assert all(np.array_equal(a, b) for a, b in zip(pendula.ellipj(u, 0.7), r))
            for s, r in zip(scenes, ref_s):
                assert np.array_equal(pendula.simulate(s, t).theta, r)
            for s, r in zip(scenes, ref_e):
                assert np.array_equal(pendula.find_events(s, "turning", t_end=40.0).t, r)

    assert run_threads([go] * 4) == []


def test_events_and_density_refuse_the_flexible_cord_instead_of_answering_for_a_rigid_one():
    s = Scene(cord="flexible", v0=2.5)
    with pytest.raises(NotImplementedError, match="flexible cord"):
        pendula.find_events(s, "turning", t_end=10.0)
    # v0 = 2.5 keeps the cord taut over the top (v^2 = 2.25 > eps there): the motion is the rigid one,
    # and its period is that motion's, measured on it
    assert pendula.numerical_period(s) == pendula.numerical_period(s.replace(cord="rigid"))
    with pytest.raises(NotImplementedError, match="cord"):
        pendula.angle_density(s, 0.0)


def test_children_start_with_sigint_at_its_default():
    """However the runner was started (make test &, nohup, cron: SIGINT ignored and inherited), the
    children the tests start see SIGINT at its default (tests/conftest.py), so the Ctrl-C tests'
    signal reaches them."""
    code = "import signal; print(signal.getsignal(signal.SIGINT) is signal.default_int_handler)"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.stdout.strip() == "True", r.stdout + r.stderr

"""The adiabatic sweep, sweep(..., follow=True), against a continuation by hand with scipy.

The reference carries the state from value to value itself: scipy's solve_ivp (DOP853, rtol 1e-12) from
the end state of the value before, over the transient and the window, the measure read from that run.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pendula
from pendula import Scene


def _by_hand(rhs, values, start, span, read):
    """Up the values from start, then down from the end of the way up: read(value, solution) at each."""
    state = np.array(start, dtype=float)
    out = {}
    for direction, seq in (("up", values), ("down", values[::-1])):
        got = {}
        for x in seq:
            s = solve_ivp(rhs, (0.0, span(x)), state, args=(x,), method="DOP853", rtol=1e-12, atol=1e-12,
                          dense_output=True)
            got[x] = read(x, s)
            state = s.y[:, -1].copy()
            state[0] = math.remainder(state[0], 2 * math.pi)
        out[direction] = np.array([got[x] for x in values])
    return out


def test_retrapping_hysteresis_against_scipy_continuation_by_hand():
    beta, transient, t_max = 0.2, 100.0, 200.0
    rng = np.random.default_rng(20)
    # the special points (rest, the hysteretic band between retrapping (about 4 beta / pi = 0.25) and
    # switching (1), running) and seeded random ones inside the band, each 0.03 or more from either end
    taus = np.sort(np.concatenate([[0.1, 0.2, 0.3, 0.6, 0.9, 1.05, 1.2], rng.uniform(0.3, 0.95, 4)]))
    ds = pendula.sweep(Scene(damping=beta), {"torque": taus}, "mean_velocity", transient=transient,
                       t_max=t_max, follow=True)
    assert ds.mean_velocity.dims == ("direction", "torque")
    assert ds["direction"].values.tolist() == ["up", "down"]

    def rhs(t, y, tau):
        return [y[1], -beta * y[1] - math.sin(y[0]) + tau]

    def mean_v(tau, s):
        return (s.sol(transient + t_max)[0] - s.sol(transient)[0]) / t_max
    ref = _by_hand(rhs, taus, (0.0, 0.0), lambda tau: transient + t_max, mean_v)
    for d in ("up", "down"):
        got = ds.mean_velocity.sel(direction=d).values
        # 1e-6: a trapped orbit's leftover oscillation (amplitude e^(-beta t / 2), about 5e-5 after the
        # transient) averages to about 1e-7 over the window, which the kernel reports as 0 exactly; a running
        # one agrees to the integrators' tolerances (1e-10 and 1e-12) times the window
        np.testing.assert_allclose(got, ref[d], rtol=1e-6, atol=1e-6, err_msg=d)
    # the hysteresis: at rest up to the switching torque 1 on the way up, running down to the retrapping
    up, down = ds.mean_velocity.sel(direction="up").values, ds.mean_velocity.sel(direction="down").values
    band = (taus > 0.27) & (taus < 1.0)
    assert np.all(up[band] == 0.0) and np.all(down[band] > 1.0)
    assert np.all(up[taus > 1.0] > 1.0) and np.all(down[taus < 0.25] == 0.0)


def test_poincare_follow_keeps_one_asymmetric_orbit_against_scipy():
    # beta = 0.5, Omega = 2/3: between the pitchfork (A = 1.00432) and the doubling (1.06637) two
    # asymmetric period-1 attractors coexist (mirror images); the sweep stays on the one it starts near
    beta, om = 0.5, 2 / 3
    td = 2 * math.pi / om
    # away from both ends (where a multiplier nears +1 or -1 and the transients are slow)
    A = np.linspace(1.02, 1.05, 4)
    transient, samples = 60 * td, 3
    sc = Scene(damping=beta, drive_frequency=om, drive_amplitude=1.02, theta0=-1.3, v0=1.8)
    ds = pendula.sweep(sc, {"drive_amplitude": A}, "poincare", transient=transient, samples=samples, follow=True)

    def rhs(t, y, a):
        return [y[1], -beta * y[1] - math.sin(y[0]) + a * math.cos(om * t)]

    # the kernel's samples: at whole drive periods from ceil(transient / T) on; the last at (60 + 2) T
    last = (60 + samples - 1) * td
    ref = _by_hand(rhs, A, (-1.3, 1.8), lambda a: (60 + samples) * td, lambda a, s: s.sol(last))
    for d in ("up", "down"):
        th = ds.theta.sel(direction=d).values[:, -1]
        v = ds.v.sel(direction=d).values[:, -1]
        # the attracting fixed point: both runs settle onto it (multipliers about 0.1 per period) to far below
        # the integrators' tolerances; 1e-8 leaves their error times the map's growth
        assert np.all(np.abs(np.remainder(th - ref[d][:, 0] + math.pi, 2 * math.pi) - math.pi) < 1e-8), d
        assert np.all(np.abs(v - ref[d][:, 1]) < 1e-8), d
        # one orbit all the way: its angle moves smoothly with A (the mirror orbit lies about 1 rad away)
        assert np.all(np.abs(np.diff(th)) < 0.3), th
    np.testing.assert_allclose(ds.theta.sel(direction="up").values, ds.theta.sel(direction="down").values,
                               atol=1e-8)


@pytest.mark.parametrize("kwargs, match", [
    (dict(over={"torque": [0.1, 0.2], "damping": [0.1, 0.2]}), "one field"),
    (dict(over={"v0": [0.1, 0.2]}), "theta0, v0"),
    (dict(over={"torque": [0.1, 0.2, 0.1]}), "repeats"),
    (dict(over={"torque": [0.1, 0.2]}, measure="attractor"), "no state to carry"),
    (dict(over={"torque": [0.1, 0.2]}, out="somewhere"), "neither 'out'"),
])
def test_follow_refuses_what_it_cannot_carry(kwargs, match, tmp_path):
    kw = dict(measure="mean_velocity", transient=10.0, t_max=20.0, follow=True)
    kw.update(kwargs)
    if "out" in kw:
        kw["out"] = tmp_path / "store"
    sc = Scene(damping=0.2, drive_amplitude=0.5, drive_frequency=0.7) if kw["measure"] == "attractor" \
        else Scene(damping=0.2)
    with pytest.raises(ValueError, match=match):
        pendula.sweep(sc, **kw)


def test_follow_with_noise_is_refused():
    with pytest.raises(ValueError, match="follow"):
        pendula.sweep(Scene(damping=0.2, noise=0.01), {"torque": [0.1, 0.2]}, "mean_velocity", transient=10.0,
                      t_max=20.0, follow=True)


def test_follow_must_be_a_flag():
    with pytest.raises(TypeError, match="follow"):
        pendula.sweep(Scene(damping=0.2), {"torque": [0.1, 0.2]}, "mean_velocity", transient=10.0, t_max=20.0,
                      follow="yes")

"""Hard cases of the dynamics' one Newton core and of continuation's step, stop and bifurcation rules.

References: scipy's solve_ivp (DOP853 at rtol 1e-12) for the stroboscopic map and its variational
equations, scipy.optimize.root (MINPACK's hybrid method) from the same guesses, the closed form of the
driven damped free particle, and data/continuation_reference.json (scipy's brentq on the pitchfork).
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import root

import pendula
from pendula import Scene

REF = json.loads((Path(__file__).resolve().parents[1] / "data" / "continuation_reference.json").read_text())
ROUGH = Scene(eps=0.4626852104522593, damping=0.11949515024355797, drive_amplitude=0.41411992385694973,
              drive_frequency=0.4502883112072218, drive_phase=0.9631731737749814)


def _map(sc):
    """The stroboscopic map's residual P(x) - x and its Jacobian M - I, by scipy."""
    eps, b, A, w, ph = sc.eps, sc.damping, sc.drive_amplitude, sc.drive_frequency, sc.drive_phase

    def rhs(t, y):
        th, v, a, bb, c, d = y
        dth = -eps * math.cos(th)
        return [v, -b * v - eps * math.sin(th) + A * math.cos(w * t + ph), bb, dth * a - b * bb, d, dth * c - b * d]

    def F(x):
        s = solve_ivp(rhs, (0, 2 * math.pi / w), [x[0], x[1], 1, 0, 0, 1], method="DOP853", rtol=1e-12, atol=1e-12)
        y = s.y[:, -1]
        return y[:2] - x, np.array([[y[2], y[4]], [y[3], y[5]]]) - np.eye(2)
    return F


def _same_orbit(a, b):
    return abs(math.remainder(a[0] - b[0], 2 * math.pi)) < 1e-8 and abs(a[1] - b[1]) < 1e-8


def test_rough_guess_reaches_the_orbit_minpack_finds():
    # the orbit MINPACK's hybrid method finds from this guess, at (-2.44434941, 0.85436058)
    F = _map(ROUGH)
    ref = root(F, (-0.4238, 0.4686), jac=True, method="hybr", options=dict(xtol=1e-12))
    assert ref.success
    po = pendula.periodic_orbit(ROUGH, guess=(-0.4238, 0.4686))
    assert _same_orbit((po.theta, po.v), ref.x)
    assert np.max(np.abs(F((po.theta, po.v))[0])) < 1e-9


def test_rough_guesses_near_it_all_converge():
    # 24 seeded guesses around the rough one (the plain Newton step shortened to 1 failed on 2 in 3 of
    # them): each reaches an orbit that scipy's flow closes to 1e-9
    F = _map(ROUGH)
    rng = np.random.default_rng(48)
    for _ in range(24):
        g = (-0.4238 + 0.05 * rng.normal(), 0.4686 + 0.05 * rng.normal())
        po = pendula.periodic_orbit(ROUGH, guess=g)
        assert np.max(np.abs(F((po.theta, po.v))[0])) < 1e-9, g


def test_random_rough_guesses_against_minpack():
    # random scenes, guesses anywhere in the window: pendula converges at least as often as MINPACK's
    # hybrid method with the exact Jacobian, and every orbit it returns closes under scipy's flow
    rng = np.random.default_rng(2026)
    ours = theirs = 0
    for _ in range(16):
        sc = Scene(eps=float(rng.uniform(0.2, 2)), damping=float(rng.uniform(0.05, 0.8)),
                   drive_amplitude=float(rng.uniform(0.1, 1.5)), drive_frequency=float(rng.uniform(0.3, 2.0)),
                   drive_phase=float(rng.uniform(-math.pi, math.pi)))
        g = (float(rng.uniform(-math.pi, math.pi)), float(rng.uniform(-2, 2)))
        F = _map(sc)
        r = root(F, g, jac=True, method="hybr", options=dict(xtol=1e-12))
        theirs += bool(r.success and np.max(np.abs(r.fun)) < 1e-8)
        try:
            po = pendula.periodic_orbit(sc, guess=g)
        except ValueError:
            continue
        assert np.max(np.abs(F((po.theta, po.v))[0])) < 1e-9
        ours += 1
    assert ours >= theirs


def test_continue_orbit_refuses_dry_friction_as_periodic_orbit_does():
    sc = Scene(damping=0.3, drive_amplitude=1.0, drive_frequency=2 / 3, friction=0.05)
    # one rule of the capability table for both tools: the same reason, each naming itself
    with pytest.raises(ValueError, match="field 'friction': periodic_orbit does not honour friction.*smooth") as a:
        pendula.periodic_orbit(sc, guess=(0.1, 1.0))
    with pytest.raises(ValueError, match="field 'friction': continue_orbit does not honour friction.*smooth") as b:
        pendula.continue_orbit(sc, (0.1, 1.0), "drive_amplitude", 1.1)
    assert str(a.value).split(": ", 2)[2] == str(b.value).split(": ", 2)[2]


# ---------------------------------------------------------------- continuation's steps and stops

def test_step_or_stop_below_the_parameters_resolution_is_refused_by_name():
    sc = Scene(damping=0.1, torque=1.5)
    with pytest.raises(ValueError, match="step"):
        pendula.continue_orbit(sc, (0.0, 5.0), "torque", 2.0, step=1e-200)
    with pytest.raises(ValueError, match="step"):
        pendula.continue_orbit(sc, (0.0, 5.0), "torque", 2.0, step=1e-9)     # 1e5 points to the stop
    with pytest.raises(ValueError, match="stop"):
        pendula.continue_orbit(sc, (0.0, 5.0), "torque", math.nextafter(1.5, 2.0))


def test_branch_to_the_edge_of_eps_ends_there_on_the_free_particle():
    # eps down to 1e-300 (its edge is 0): the branch ends at the stop, where the orbit is the driven
    # damped free particle's, v(0) = A beta / (Omega^2 + beta^2)
    sc = Scene(damping=0.5, drive_amplitude=0.5, drive_frequency=1.0)
    po = pendula.periodic_orbit(sc, guess=(0.3, 0.2))
    br = pendula.continue_orbit(sc, (po.theta, po.v), "eps", 1e-300)
    assert br.end == "stop" and br.values[-1] == 1e-300 and np.all(br.values > 0)
    assert abs(br.v[-1] - 0.5 * 0.5 / (1.0 + 0.25)) < 1e-8


def test_guess_of_tiny_velocity_ends():
    br = pendula.continue_orbit(Scene(damping=0.1, torque=1.5), (0.0, 1e-300), "torque", 1.6)
    assert br.end == "stop" and br.values[-1] == 1.6


# ---------------------------------------------------------------- bifurcations: solved roots only

def test_pitchfork_met_from_its_asymmetric_child_is_the_symmetric_orbits_root():
    # down the asymmetric branch into the pitchfork: the branch turns there with no multiplier through
    # +1; reported as the pitchfork solved on the symmetric orbit (scipy's brentq value), not a fold
    sc = Scene(damping=0.5, drive_amplitude=1.03, drive_frequency=2 / 3)
    po = pendula.periodic_orbit(sc, guess=(-0.43, 1.99))
    assert abs(po.theta) > 0.1                       # the asymmetric orbit
    br = pendula.continue_orbit(sc, (po.theta, po.v), "drive_amplitude", 0.99)
    want = REF["cascade"]["points"][0]
    assert want["kind"] == "pitchfork"
    kinds = [b.kind for b in br.bifurcations]
    assert "fold" not in kinds
    (b,) = [b for b in br.bifurcations if b.kind == "pitchfork"]
    assert abs(b.value - want["value"]) < 1e-8
    assert np.min(np.abs(b.multipliers - 1.0)) < 1e-6

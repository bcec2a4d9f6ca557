"""The shared mechanisms, each through doors other than the ones that first
showed them broken: one time-scale rule, one definition of a periodic
forcing, one rule for when an answer is decided, one path checker, one reader
for both programs.  (The capability table has its own walk:
tests/test_capabilities.py.)
"""

import math
import os
import subprocess
import sys

import numpy as np
import pytest

import pendula
from pendula.systems import _long_run

BIN = os.path.dirname(sys.executable)


# ---- one time-scale rule -------------------------------------------------------------------

def test_time_scales_see_every_field():
    rates = pendula.time_scales(pendula.Scene(damping=3.0, torque=4.0, pivot_amplitude=0.25,
                                              pivot_frequency=8.0, v0=5.0)).rates
    assert rates["damping"] == 3.0 and rates["torque"] == 2.0 and rates["pivot"] == 8.0
    assert rates["pivot_force"] == 4.0 and rates["rotation"] == 5.0
    steep = pendula.time_scales(pendula.Scene(gravity="linear", gravity_gradient=-1e6))
    assert steep.rates["oscillation"] == pytest.approx(math.sqrt(1 + 3e6))


def test_langevin_default_step_resolves_strong_damping():
    # BAOAB at beta h >> 1 gives <v> = tau h/2 coth(beta h/2), not tau / beta: the default step sees beta
    for beta in (30.0, 300.0):
        ts = pendula.time_scales(pendula.Scene(damping=beta, noise=1e-3))
        assert beta * ts.langevin_dt <= 2 * math.pi / 100 * (1 + 1e-15)
    # a strongly damped, strongly torqued pendulum with (negligible) noise runs at tau / beta
    beta, tau = 40.0, 60.0
    tr = pendula.simulate(pendula.Scene(damping=beta, torque=tau, noise=1e-12, seed=3, t_end=60.0, n_samples=61))
    v = (tr.theta[-1] - tr.theta[30]) / 30.0
    assert abs(v / (tau / beta) - 1) < 1e-3       # BAOAB's bias at beta h = 0.063: (beta h)^2 / 12 = 3e-4


def test_langevin_default_step_unchanged_where_damping_is_slow():
    # below the oscillation's rate the rule is the small-oscillation and drive rule alone, to the bit
    for eps, om in ((1.0, 0.0), (2.5, 0.0), (1.0, 3.0)):
        kw = dict(drive_amplitude=0.2, drive_frequency=om) if om else {}
        ts = pendula.time_scales(pendula.Scene(eps=eps, damping=0.1, noise=0.1, **kw))
        old = min(2 * math.pi / math.sqrt(eps), 2 * math.pi / om if om else math.inf) / 100
        assert ts.langevin_dt == old


def test_interruptible_runs_decided_by_the_fastest_scale():
    t = np.linspace(0.0, 20.0, 3)
    assert _long_run(pendula.Scene(pivot_amplitude=1e6, pivot_frequency=40.0, damping=0.1), t)
    assert _long_run(pendula.Scene(gravity="linear", gravity_gradient=-1e12, damping=0.1), t)
    assert _long_run(pendula.Scene(damping=1e7, torque=1.0), t)
    # short runs stay on the direct path, however tight the tolerance
    assert not _long_run(pendula.Scene(damping=0.1, rtol=1e-14, atol=1e-16), t)


def test_attractor_map_refuses_a_window_beyond_the_work_limit():
    sc = pendula.Scene(damping=0.5, pivot_amplitude=30.0, pivot_frequency=300.0)
    with pytest.raises(ValueError, match="max_periods.*pivot_force"):
        pendula.attractor_map(sc, {"theta0": [0.0, 1.0]}, max_periods=3 * 10**5)


# ---- one definition of a periodic forcing ---------------------------------------------------

def test_pivot_alone_is_a_periodic_forcing_for_every_map_tool():
    # Kapitza: the inverted pendulum is stable on a fast vibrating pivot; its orbit is a fixed point of the
    # pivot's stroboscopic map at theta = pi
    sc = pendula.Scene(damping=0.1, pivot_amplitude=0.1, pivot_frequency=40.0)
    po = pendula.periodic_orbit(sc, guess=(math.pi, 0.0))
    assert abs(abs(po.theta) - math.pi) < 1e-9 and po.stable
    ds = pendula.sweep(sc.replace(damping=0.5), {"theta0": [3.0]}, "poincare", transient=100.0, samples=3)
    assert np.all(np.abs(np.abs(ds.theta.values) - math.pi) < 1e-6)
    br = pendula.continue_orbit(sc, (math.pi, 0.0), "pivot_amplitude", 0.12)
    end = br.to_xarray()
    T = 2 * math.pi / 40.0
    tr = pendula.simulate(sc.replace(pivot_amplitude=float(end.pivot_amplitude[-1]), theta0=float(end.theta[-1]),
                                     v0=float(end.v[-1])), [0.0, T], rtol=1e-12, atol=1e-12)
    assert abs(tr.theta[1] - tr.theta[0]) < 1e-8 and abs(tr.v[1] - tr.v[0]) < 1e-7


def test_drive_and_pivot_at_different_frequencies_refused_by_name():
    sc = pendula.Scene(damping=0.1, drive_amplitude=0.5, drive_frequency=1.0, pivot_amplitude=0.1,
                       pivot_frequency=3.0)
    with pytest.raises(ValueError, match="pivot_frequency"):
        pendula.periodic_orbit(sc, guess=(0.0, 0.0))
    with pytest.raises(ValueError, match="pivot_frequency"):
        pendula.attractor_continuation(sc, {"theta0": [0.0, 1.0]}, "damping", [0.1, 0.2])


# ---- one rule for when an answer is decided -------------------------------------------------

def test_converging_samples_are_undecided_never_chaotic():
    from pendula.dynamics.attractors import label_attractors
    j = np.arange(40)
    converging = 0.3 + 0.05 * 0.93 ** j * np.cos(2.0 * j)          # a slow spiral onto a fixed point
    rng = np.random.default_rng(5)
    chaotic = rng.uniform(-math.pi, math.pi, 40)
    labels, atts = label_attractors(np.array([converging, chaotic]), np.zeros((2, 40)))
    assert labels[0] == -2
    assert labels[1] >= 0 and atts[labels[1]].kind == "chaotic"


# ---- one path checker, one reader for both programs ------------------------------------------

def test_empty_output_folder_refused_by_every_writer(tmp_path):
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        with pytest.raises(ValueError, match="non-empty"):
            from pendula.run import run_scene
            run_scene(pendula.Scene(t_end=1.0, n_samples=3), "")
        with pytest.raises(ValueError, match="non-empty"):
            pendula.attractor_map(pendula.Scene(damping=0.5, drive_amplitude=1.35, drive_frequency=2 / 3),
                                  {"theta0": [0.0, 1.0]}, method="samples", out="")
        r = subprocess.run([os.path.join(BIN, "pendula"), "demo", "-o", ""], capture_output=True, text=True,
                           timeout=120)
        assert r.returncode == 2 and "--output" in r.stderr
        assert os.listdir(tmp_path) == []
    finally:
        os.chdir(here)


@pytest.mark.parametrize("axis", ["grid1_range = -0.2, 0.3, 3", "grid1 = 0.5, -0.1"])
def test_pendula_run_refuses_grid_ends_the_field_rules_forbid(tmp_path, axis):
    scene = tmp_path / "g.nml"
    scene.write_text("&scene\n damping = 0.5, grid = 'drag', " + axis + ", measure = 'final_well'\n/\n")
    r = subprocess.run([os.path.join(BIN, "pendula-run"), str(scene)], capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and "drag" in r.stderr, r.stderr
    with pytest.raises(ValueError, match="drag"):
        pendula.sweep(pendula.Scene.from_file(scene))


def test_batch_programs_refuse_an_argument_ending_in_a_blank(tmp_path):
    (tmp_path / "s.nml").write_text("&scene\n theta0 = 1.0, t_end = 1.0, n_samples = 3\n/\n")
    for cmd in (["pendula-run", "s.nml "], ["pendula-run", "s.nml", "-o", "x.csv "], ["pendula-ellip", "rows "]):
        r = subprocess.run([os.path.join(BIN, cmd[0])] + cmd[1:], cwd=tmp_path, capture_output=True, text=True,
                           timeout=60)
        assert r.returncode != 0 and "ends in a blank" in r.stderr, (cmd, r.stderr)
    assert sorted(os.listdir(tmp_path)) == ["s.nml"]


def test_both_programs_refuse_a_seed_beyond_two_to_the_53(tmp_path):
    # 2^53 + 1 is no double: read whole by the namelist and rounded by Python's fields, it named two seeds
    scene = tmp_path / "seed.nml"
    scene.write_text("&scene\n damping = 0.5, noise = 0.1, seed = 9007199254740993, t_end = 1.0\n/\n")
    r = subprocess.run([os.path.join(BIN, "pendula-run"), str(scene)], capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and "seed" in r.stderr
    with pytest.raises(pendula.SceneError, match="seed"):
        pendula.Scene.from_file(scene)
    scene.write_text("&scene\n damping = 0.5, noise = 0.1, seed = 9007199254740992, t_end = 1.0\n/\n")
    assert pendula.Scene.from_file(scene).seed == 2**53


def test_iv_curve_refuses_torques_out_of_order():
    # descending torques ramped 'up' in the order given were a down ramp labelled 'up'
    sc = pendula.Scene(damping=0.5)
    with pytest.raises(ValueError, match="torques"):
        pendula.iv_curve(sc, [1.2, 0.8, 0.4], direction="up", transient=10.0, t_max=20.0)
    with pytest.raises(ValueError, match="torques"):
        pendula.iv_curve(sc, [0.4, 0.4, 0.8], direction="both", transient=10.0, t_max=20.0)

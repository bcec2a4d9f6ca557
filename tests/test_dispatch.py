"""The dispatcher: scene -> model -> exact path or integrator, decided once in the kernel."""

import subprocess
import sys

import numpy as np
import pytest

import pendula
from pendula import Scene


def test_models_lists_the_registry():
    ms = {m.name: m for m in pendula.models()}
    assert list(ms)[0] == "rigid" and ms["rigid"].implemented and ms["rigid"].path == "exact"
    assert set(ms["rigid"].effects) == {"damping", "torque", "drive", "friction", "drag", "pivot", "noise",
                                          "force"}
    assert ms["rigid"].exact_with == ()  # exact only without effects
    assert {"cord", "cycloid", "gravity"} <= set(ms)


def test_models_command_prints_the_same_table():
    out = subprocess.run([sys.executable, "-m", "pendula", "models"], capture_output=True, text=True, check=True)
    lines = out.stdout.splitlines()
    assert lines[0].split()[0] == "model"
    n = len(pendula.models())
    names = [ln.split()[0] for ln in lines[2:2 + n]]
    assert names == [m.name for m in pendula.models()]
    # then the capability table, one block per model: every row of pendula.capabilities() is printed
    printed = {(m.name, ln.split()[0]) for m in pendula.models() for ln in
               out.stdout.split(f"\n{m.name}: ")[1].split("\n\n")[0].splitlines()[3:] if ln.strip()}
    assert {(c.system, c.tool) for c in pendula.capabilities()} <= printed


def test_conservative_rigid_scene_takes_the_exact_path():
    tr = pendula.simulate(Scene(v0=1.0), [0.0, 1.0, -3.0])
    th, v = pendula.exact_motion(0.0, 1.0, 1.0, [0.0, 1.0, -3.0])
    assert tr.method == "exact" and tr.stats == {}
    assert np.array_equal(tr.theta, th) and np.array_equal(tr.v, v)


def test_scene_with_effects_is_integrated_by_its_method():
    tr = pendula.simulate(Scene(v0=1.0, damping=0.1), [0.0, 2.0, 1.0])
    assert tr.method in ("dop853", "vern9", "vern8") and tr.stats["steps"] > 0   # auto: tests/test_integrators_auto.py
    one = pendula.simulate(Scene(v0=1.0, damping=0.1), [1.0])
    assert tr.theta[2] == pytest.approx(one.theta[0], rel=1e-9)


@pytest.mark.parametrize("kw,field", [(dict(method="rk4", dt=0.01), "method"), (dict(rtol=1e-6), "rtol"),
                                      (dict(atol=1e-9), "atol"), (dict(dt=0.02, method="gauss6"), "dt")])
def test_solver_knobs_as_keywords_override_the_scene(kw, field):
    s = Scene(v0=1.0, damping=0.1)
    t = np.linspace(0.0, 5.0, 11)
    by_kw = pendula.simulate(s, t, **kw)
    by_scene = pendula.simulate(s.replace(**kw), t)
    assert np.array_equal(by_kw.theta, by_scene.theta)
    assert by_kw.scene == s.replace(**kw)


def test_keyword_method_exact_refuses_effects():
    with pytest.raises(ValueError, match="exact"):
        pendula.simulate(Scene(v0=1.0, damping=0.1), [1.0], method="exact")


def test_two_models_at_once_are_refused_by_name():
    with pytest.raises((NotImplementedError, ValueError), match="cord|guide"):
        pendula.simulate(Scene(cord="flexible", guide="cycloid"), [1.0])


def test_gsl_peer_runs_through_the_dispatcher():
    s = Scene(v0=1.0, damping=0.1, rtol=1e-11, atol=1e-13)
    a = pendula.simulate(s, [0.0, 3.0], method="gsl-rk8pd")
    b = pendula.simulate(s, [0.0, 3.0], method="dop853")
    assert a.method == "gsl-rk8pd" and abs(a.theta[1] - b.theta[1]) < 1e-8


@pytest.mark.parametrize("kw", [dict(), dict(g=9.81, length=2.0, method="DOP853", rtol=1e-9),
                                dict(guide="cycloid", theta0=0.3, cycloid_radius=0.3, name="Huygens' guide"),
                                dict(gravity="linear", gravity_gradient=0.2, v0=1.0, outputs=("trajectory", "omega")),
                                dict(cord="flexible", v0=1.7, restitution=0.5, max_flips=7, min_flight=1e-3),
                                dict(grid=("v0", "damping"), grid1=(0.5, 1.0), grid2_range=(0.0, 0.2, 5.0),
                                     measure="locked", sweep_samples=17, damping=0.1)])
def test_the_checked_scene_the_kernel_keeps_rebuilds_the_same_scene(kw):
    # simulate hands the kernel these numbers and words (no text is formed or parsed at a run);
    # read back through the kernel's layout they are the scene again, field by field
    from pendula.scene import _fields_from_kernel

    s = Scene(**kw)
    x, words, wlen, nout, ngrid = s._kernel_fields
    back = _fields_from_kernel(x, words, wlen, nout, ngrid)
    for name, value in back.items():
        got = getattr(s, name)
        assert got == value or (got != got and value != value), name
    assert np.array_equal(pendula.simulate(s, [0.0, 0.5]).theta, pendula.simulate(s.replace(), [0.0, 0.5]).theta)


def test_every_model_declares_its_state_parameters_and_time_scales():
    """The registry says, for every system, its state, its parameters and the time scales they create;
    the parameters include every field the system's effects are turned on by (the refusals name them)."""
    for m in pendula.models():
        assert m.state and m.parameters and m.time_scales, m
        assert m.state.split(":")[0].strip(), m
    ms = {m.name: m for m in pendula.models()}
    assert [n for n, m in ms.items() if m.scene] == ["rigid", "cord", "cycloid", "gravity"]
    assert {"bias", "temperature", "damping", "drive_amplitude"} <= set(ms["network"].parameters)

"""simulate(scene, method=..., rtol=..., atol=..., dt=...): the integrator's knobs changed without
building and checking a new Scene first (the kernel checks the changed fields as it runs them, once
per scene and knobs).  The answers must be those of the scene built with Scene.replace, bit for
bit, and a knob that does not fit must fail as Scene.replace fails."""

import numpy as np
import pytest

import pendula
from pendula import SceneError

T = np.linspace(0.0, 10.0, 11)


@pytest.mark.parametrize("scene,knobs", [
    (pendula.Scene(theta0=1.0, v0=0.3), dict(method="exact")),
    (pendula.Scene(v0=1.0, damping=0.1), dict(method="vern9", rtol=1e-9, atol=1e-11)),
    (pendula.Scene(v0=1.0, torque=0.3, drive_amplitude=0.2, drive_frequency=0.7), dict(method="gauss6", dt=0.05)),
    (pendula.Scene(v0=0.5, gravity="linear", gravity_gradient=0.2), dict(rtol=1e-8)),
])
def test_knobs_give_what_the_replaced_scene_gives(scene, knobs):
    fast = pendula.simulate(scene, T, **knobs)
    again = pendula.simulate(scene, T, **knobs)            # the kept, checked variant
    slow = pendula.simulate(scene.replace(**knobs), T)
    for tr in (fast, again):
        assert tr.scene == scene.replace(**knobs) and tr.method == slow.method
        assert np.array_equal(tr.theta, slow.theta) and np.array_equal(tr.v, slow.v)
        assert np.array_equal(tr.energy, slow.energy) and tr.stats == slow.stats
    assert scene.method == "auto"                          # the scene itself is unchanged


@pytest.mark.parametrize("knobs,field", [
    (dict(method="rk4"), "dt"), (dict(rtol=-1.0), "rtol"), (dict(method="exact"), "method"),
    (dict(method="nope"), "method"), (dict(method="rk4", dt=-0.1), "dt"), (dict(atol=float("nan")), "atol"),
])
def test_knobs_that_do_not_fit_fail_naming_the_field(knobs, field):
    scene = pendula.Scene(v0=1.0, damping=0.1)
    with pytest.raises(SceneError, match=field):
        pendula.simulate(scene, T, **knobs)
    with pytest.raises(SceneError, match=field):       # and again: a refused variant is never marked checked
        pendula.simulate(scene, T, **knobs)


def test_knobs_of_other_types_and_sweeps_take_the_checked_path():
    """A numpy or int tolerance, a method in capitals, a scene with a sweep: Scene.replace converts and checks."""
    scene = pendula.Scene(v0=1.0, damping=0.1)
    a = pendula.simulate(scene, T, rtol=np.float32(2.0 ** -20), atol=np.float64(1e-12))
    assert a.scene.rtol == 2.0 ** -20 and type(a.scene.atol) is float
    assert pendula.simulate(scene, T, method="DOP853").scene.method == "dop853"
    swept = pendula.Scene(v0=1.0, damping=0.1, sweep="damping", sweep_values=(0.1, 0.2))
    tr = pendula.simulate(swept, T, method="vern9")
    assert tr.scene == swept.replace(method="vern9")


def test_a_scene_keeps_a_few_variants_only():
    scene = pendula.Scene(v0=1.0, damping=0.1)
    for k in range(20):
        pendula.simulate(scene, [0.0, 1.0], rtol=10.0 ** -(3 + k % 10) * 1.5)
    assert len(scene.__dict__["_knob_variants"]) <= 8

"""The capability table, walked whole: every (tool, system, effect) either
changes the tool's answer or is refused by name.

For each row of ``pendula.capabilities()`` (one tool on one system) and each
effect, the tool runs on a small base scene of that system with and without
the effect: an honoured effect must change the answer; an effect the row does
not list must raise (a ValueError naming a field the scene turns on, or the
scene itself refused by the scene rules); a planned one NotImplementedError.
A tool run on a system it has no row for raises NotImplementedError.  So no
tool can silently ignore a field, and the table cannot claim what a tool does
not do.
"""

import json
import warnings

import numpy as np
import pytest

import pendula
from pendula.systems.contract import EFFECTS

#: each effect's fields, at values that change every tool's answer
EFFECT_FIELDS = {"damping": dict(damping=0.15), "torque": dict(torque=0.2),
                 "drive": dict(drive_amplitude=0.3, drive_frequency=0.7),
                 "friction": dict(friction=0.05), "drag": dict(drag=0.1),
                 "pivot": dict(pivot_amplitude=0.05, pivot_frequency=5.0), "noise": dict(noise=0.1, seed=1)}
SYSTEMS = {"rigid": dict(theta0=1.0, v0=0.3), "cord": dict(cord="flexible", theta0=0.0, v0=2.08),
           "cycloid": dict(guide="cycloid", theta0=0.5, v0=0.2),
           "gravity": dict(gravity="linear", gravity_gradient=0.2, theta0=1.0, v0=0.3)}
DRIVEN = dict(damping=0.5, drive_amplitude=1.2, drive_frequency=2 / 3)
#: two period-1 rotations (the attractor tools' observable is an attractor's state)
ROTATING = dict(damping=0.5, drive_amplitude=1.35, drive_frequency=2 / 3)
GRID = {"theta0": [-1.0, 1.0], "v0": [0.0, 1.0]}


def _arr(x):
    return np.asarray(x, dtype=float).ravel()


def _force(t, theta, v, params):
    return 0.05 * np.cos(theta)


def _attractors(am):
    return _arr([np.r_[a.theta, a.v, a.period] for a in am.attractors][0])


def _decided(ds, names):
    """A sweep's variables; a measure that applies at no point is no answer (a refusal, not an honour)."""
    st = ds.status.values
    assert not np.all(st == 2), "every point: 'measure does not apply' (the table must refuse it at the door)"
    return _arr([ds[n].values for n in names])


def _sweep_attractors(ds):
    """The points' status, then the first attractor's samples (none while every point is still settling)."""
    atts = json.loads(ds.attrs["attractors"])
    return _arr(np.r_[ds.status.values, np.r_[atts[0]["theta"], atts[0]["v"]] if atts else []])


#: tool -> (call(scene, force) returning an array, the base fields the tool needs)
TOOLS = {
    "simulate": (lambda s, f: _arr(pendula.simulate(s, np.linspace(0, 5, 11), force=f).theta), {}),
    "find_events": (lambda s, f: _arr(pendula.find_events(s, "departure" if s.cord == "flexible" else "turning",
                                                          t_end=8.0).t), {}),
    "period": (lambda s, f: _arr(pendula.period(s)), {}),
    "numerical_period": (lambda s, f: _arr(pendula.numerical_period(s, periods=2)), {}),
    "equilibria": (lambda s, f: _arr([(e.theta, *np.real(e.eigenvalues)) for e in pendula.equilibria(s)]), {}),
    "continue_equilibria": (lambda s, f: _arr([[(e.theta, *np.real(e.eigenvalues)) for e in q]
                                               for q in pendula.continue_equilibria(s, "eps", 1.2,
                                                                                    points=3).equilibria]), {}),
    "periodic_orbit": (lambda s, f: _arr((lambda o: (o.theta, o.v, *np.abs(o.multipliers)))(
        pendula.periodic_orbit(s, guess=(-0.5, 0.5), force=f))), DRIVEN),
    "continue_orbit": (lambda s, f: _arr(pendula.continue_orbit(s, (-0.5, 0.5), "drive_amplitude",
                                                                1.21).to_xarray().theta.values), DRIVEN),
    "attractor_map": (lambda s, f: _attractors(pendula.attractor_map(s, GRID)), ROTATING),
    "attractor_continuation": (lambda s, f: _arr(pendula.attractor_continuation(
        s, GRID, "drive_amplitude", [1.35, 1.36]).theta.values), ROTATING),
    "sweep:final_well": (lambda s, f: _decided(pendula.sweep(s, {"v0": [2.55, 2.65, 2.75]}, "final_well", t_max=200,
                                                             force=f), ("well", "t_decided")),
                         dict(damping=0.3)),
    "sweep:mean_velocity": (lambda s, f: _decided(pendula.sweep(s, {"v0": [1.0, 2.5]}, "mean_velocity", t_max=50,
                                                                transient=20, force=f), ("mean_velocity",)),
                            dict(damping=0.3, torque=0.5)),
    "sweep:locked": (lambda s, f: _decided(pendula.sweep(s, {"v0": [1.6, 1.8, 2.0]}, "locked", t_max=100,
                                                         force=f), ("locked", "t_decided")),
                     dict(damping=0.3, torque=0.5)),
    "sweep:poincare": (lambda s, f: _decided(pendula.sweep(s, {"v0": [1.0, 2.5]}, "poincare", transient=10,
                                                           samples=4, force=f), ("theta",)), DRIVEN),
    "sweep:lyapunov": (lambda s, f: _decided(pendula.sweep(s, {"v0": [1.0]}, "lyapunov", t_max=60, transient=10,
                                                           force=f), ("lyapunov",)), DRIVEN),
    "sweep:attractor": (lambda s, f: _sweep_attractors(pendula.sweep(s, {"v0": [1.0, 2.5]}, "attractor")),
                        ROTATING),
    "iv_curve": (lambda s, f: _arr(pendula.iv_curve(s, [0.5, 1.2], direction="up", transient=20,
                                                    t_max=40).mean_velocity.values), dict(damping=0.3)),
    "angle_density": (lambda s, f: _arr(pendula.angle_density(s, [0.1, 0.4])), {}),
    "angle_cdf": (lambda s, f: _arr(pendula.angle_cdf(s, [0.1, 0.4])), {}),
    "gravity_orbit": (lambda s, f: _arr((lambda o: (o.period, o.theta_max))(pendula.gravity_orbit(s))), {}),
    "friction_turning_points": (lambda s, f: _arr(pendula.friction_turning_points(s).angles[:5]),
                                dict(friction=0.05)),
}
#: the tools that take a user's force (the 'force' effect is an argument of these only)
TAKES_FORCE = {"simulate", "periodic_orbit", "sweep:final_well", "sweep:mean_velocity", "sweep:locked",
               "sweep:poincare", "sweep:lyapunov"}
#: honoured effects whose answer is invariant by the physics, not ignored (checked by the reason given)
INVARIANT = {
    ("period", "cycloid", "torque"): "Huygens: the cycloid is isochronous; a torque moves the centre only",
    ("numerical_period", "cycloid", "torque"): "Huygens: the cycloid is isochronous",
    ("equilibria", "rigid", "drag"): "drag ~ v|v| vanishes at rest with its derivative",
    ("equilibria", "gravity", "drag"): "drag ~ v|v| vanishes at rest with its derivative",
    ("continue_equilibria", "rigid", "drag"): "drag ~ v|v| vanishes at rest with its derivative",
    ("continue_equilibria", "gravity", "drag"): "drag ~ v|v| vanishes at rest with its derivative",
}
ROWS = {(c.tool, c.system): c for c in pendula.capabilities()}


#: a system's base state changed for one tool (a taut cord: its motion has a period)
SYSTEM_FOR_TOOL = {("numerical_period", "cord"): dict(v0=1.2), ("sweep:final_well", "rigid"): dict(theta0=0.0),
                   ("sweep:locked", "rigid"): dict(theta0=0.0)}


def _scene(system, base, extra, tool=None):
    kw = dict(SYSTEMS[system])
    kw.update(SYSTEM_FOR_TOOL.get((tool, system), {}))
    kw.update(base)
    kw.update(extra)
    return pendula.Scene(**kw)


def test_every_tool_of_the_table_is_walked():
    assert {c.tool for c in pendula.capabilities() if c.system in SYSTEMS} == set(TOOLS)
    assert {(c.system, c.tool) for c in pendula.capabilities() if c.system not in SYSTEMS} == set(CLASS_TOOLS)
    assert {m.name for m in pendula.models()} == set(SYSTEMS) | set(CLASS_SYSTEMS)
    assert tuple(EFFECTS) == ("damping", "torque", "drive", "friction", "drag", "pivot", "noise", "force")


@pytest.mark.parametrize("tool", sorted(TOOLS))
def test_tool_honours_or_refuses_every_effect(tool):
    call, base = TOOLS[tool]
    for system in SYSTEMS:
        row = ROWS.get((tool, system))
        try:
            s0 = _scene(system, base, {}, tool)
        except pendula.SceneError:
            assert row is None or row.needs, (tool, system)     # the scene rules refuse the base itself
            continue
        if row is None:
            with pytest.raises(NotImplementedError, match=tool.split(":")[0]):
                call(s0, None)
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            a0 = call(s0, None)
        for effect in EFFECTS:
            if effect == "force" and tool not in TAKES_FORCE:
                continue
            on = dict(base)
            if effect == "noise" and "damping" not in on:
                on["damping"] = 0.15          # thermal noise comes with damping
                try:
                    s0e = _scene(system, on, {}, tool)
                except pendula.SceneError:
                    continue
            else:
                s0e = s0
            if effect != "force" and on.get(EFFECTS[effect]):
                continue                       # the base has it already (a tool's needs)
            fields = dict(EFFECT_FIELDS.get(effect, {}))
            if effect == "pivot" and on.get("drive_frequency"):
                fields["pivot_frequency"] = on["drive_frequency"]     # one forcing period
            try:
                s1 = s0e if effect == "force" else _scene(system, on, fields, tool)
            except pendula.SceneError:
                assert effect not in row.honours, f"{tool} on {system} honours {effect}, the scene refuses it"
                continue
            f = _force if effect == "force" else None
            where = f"{tool} on the {system} model with {effect}"
            if effect in row.honours:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    a1 = call(s1, f)
                    b0 = a0 if s0e is s0 else call(s0e, None)
                if (tool, system, effect) in INVARIANT:
                    continue
                assert a1.shape != b0.shape or not np.array_equal(a1, b0, equal_nan=True), \
                    f"{where}: honoured by the table, but the answer did not change"
            elif effect in row.planned:
                with pytest.raises(NotImplementedError):
                    call(s1, f)
            else:
                with pytest.raises(ValueError) as err:
                    call(s1, f)
                on_fields = [EFFECTS[e] for e in EFFECTS if e != "force" and e not in row.honours
                             and any(getattr(s1, k) for k in EFFECT_FIELDS[e] if k != "seed")]
                if effect == "force":
                    on_fields.append("force")
                assert any(name in str(err.value) for name in on_fields), \
                    f"{where}: refused, but the message names no refused field: {err.value}"


# ---------------------------------------------------------------- the systems built by their own class
#: system -> (its class or function, base arguments, effect -> the fields that turn it on)
CLASS_SYSTEMS = {
    "network": (pendula.Network, dict(n=2, topology="pair", strength=0.3),
                {"damping": dict(damping=0.2), "torque": dict(bias=0.1),
                 "drive": dict(drive_amplitude=0.3, drive_frequency=0.7)}),
    "double": (pendula.DoublePendulum, {}, {"damping": dict(damping=0.1)}),
    "foucault": (pendula.FoucaultPendulum, dict(latitude=45.0, length=10.0), {"damping": dict(damping=0.02)}),
    "spherical": (None, {}, {}),
}
_TH = np.linspace(-3.0, 3.0, 3)
#: (system, tool) -> call(the system, the tool's extra arguments) returning an array
CLASS_TOOLS = {
    ("network", "simulate"): lambda s, kw: _arr(s.simulate(np.linspace(0, 5, 6), phi0=[0.3, 0.0], **kw).phi.values),
    ("network", "equilibrium"): lambda s, kw: _arr((lambda e: np.r_[e.phi, e.eigenvalues.real, e.eigenvalues.imag])(
        s.equilibrium([0.1, 0.0]))),
    ("network", "normal_modes"): lambda s, kw: _arr(s.normal_modes().omega2),
    ("double", "simulate"): lambda s, kw: _arr(s.simulate(np.linspace(0, 5, 6), theta1=1.0, theta2=0.5).theta1.values),
    ("double", "flip_map"): lambda s, kw: _arr(s.flip_map(_TH, _TH, t_max=10.0).time),
    ("double", "lyapunov"): lambda s, kw: _arr(s.lyapunov(1.0, 0.5, t=20.0).exponents),
    ("double", "poincare"): lambda s, kw: _arr(s.poincare(1.0, [0.0], [0.0], t_max=50.0).theta2.values),
    ("foucault", "simulate"): lambda s, kw: _arr(s.simulate(np.linspace(0, 30, 4), 0.1).x.values),
    ("foucault", "precession"): lambda s, kw: _arr((lambda p: (p.measured, p.coriolis, p.airy))(
        s.precession(0.05, swings=10))),
    ("spherical", "spherical_orbit"): lambda s, kw: _arr((lambda o: (o.period, o.azimuth_advance))(
        pendula.spherical_orbit(0.5, 0.0, 0.3))),
}
#: a tool's argument that turns an effect on (noise: the network's temperature, with damping)
CLASS_ARGUMENTS = {("network", "simulate"): {"noise": (dict(damping=0.2), dict(temperature=0.1, dt=0.05, seed=1))}}


def _build(system, extra):
    cls, base, _ = CLASS_SYSTEMS[system]
    return None if cls is None else cls(**{**base, **extra})


@pytest.mark.parametrize("system, tool", sorted(CLASS_TOOLS))
def test_class_system_tool_honours_or_refuses_every_effect(system, tool):
    """The same walk for the systems built by their own class: every effect of the system either changes
    the tool's answer (honoured by its row) or is refused with a ValueError naming the field."""
    call = CLASS_TOOLS[(system, tool)]
    row = ROWS[(tool, system)]
    a0 = call(_build(system, {}), {})
    effects = dict(CLASS_SYSTEMS[system][2])
    assert set(effects) | set(CLASS_ARGUMENTS.get((system, tool), {})) >= set(row.honours), row
    for effect, fields in effects.items():
        s1 = _build(system, fields)
        where = f"{tool} on the {system} model with {effect}"
        if effect in row.honours:
            a1 = call(s1, {})
            assert a1.shape != a0.shape or not np.array_equal(a1, a0, equal_nan=True), \
                f"{where}: honoured by the table, but the answer did not change"
        else:
            with pytest.raises(ValueError) as err:
                call(s1, {})
            assert any(f"'{name}'" in str(err.value) for name in fields), \
                f"{where}: refused, but the message names no refused field: {err.value}"
    for effect, (fields, args) in CLASS_ARGUMENTS.get((system, tool), {}).items():
        assert effect in row.honours
        s0 = _build(system, fields)
        assert not np.array_equal(call(s0, args), call(s0, {**args, "temperature": 0.0}))


def test_class_system_refusal_names_the_field():
    net = pendula.Network(2, topology="pair", strength=0.3, damping=0.1)
    with pytest.raises(ValueError, match="field 'damping': normal_modes does not honour damping on the network"):
        net.normal_modes()
    net = pendula.Network(2, topology="pair", strength=0.3, drive_amplitude=0.2, drive_frequency=1.0)
    with pytest.raises(ValueError, match="field 'drive_amplitude'.*no rest points"):
        net.equilibrium([0.0, 0.0])


def test_contract_refuses_unknown_systems_tools_and_fields_as_bugs():
    from pendula.systems.contract import require_fields
    for args in (("pendulum", "simulate", []), ("network", "flip_map", []), ("network", "simulate", ["noise"])):
        with pytest.raises(RuntimeError):
            require_fields(*args)
    require_fields("network", "simulate", ["eps", "temperature"])     # a parameter with no effect is no refusal

"""print() of every public result type is short: a summary and its size, never the full arrays.

Each result is built small but with arrays long enough (dozens to hundreds of
values) that printing them whole could not pass: the repr must be under 25
lines, under 1000 characters, and hold at most 24 numbers.  Every public class
of ``pendula.__all__`` must have a case here (a new result type without one
fails test_every_public_class_has_a_case).
"""

import re

import numpy as np
import pytest

import pendula

MAX_LINES = 25
MAX_CHARS = 1000
MAX_NUMBERS = 24

#: not results: exceptions, and the argument record of the command line
NOT_RESULTS = {"SceneError", "ContinuationError"}


def _driven():
    return pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2 / 3)


def _fold_curve():
    """The fold curve of the resonance (from the upper fold through the cusp back to the lower one)."""
    br = pendula.continue_orbit(pendula.Scene(damping=0.5, drive_amplitude=0.2, drive_frequency=0.5), (0.0, 0.0),
                                "drive_amplitude", 1.0)
    return pendula.continue_bifurcation(br.bifurcations[0], "drive_frequency", 0.7)


def _switching():
    j = pendula.Junction(1e-7, 100.0, 1e-12, temperature=0.05)
    return j.switching_currents(ramp_rate=1e-3 * 1e-7 * j.plasma_frequency, n=40, seed=1)


def _wada_test():
    sc = pendula.Scene(damping=0.2, drive_amplitude=1.66, drive_frequency=1.0)
    am = pendula.attractor_map(sc, {"theta0": np.linspace(-3, 3, 12), "v0": np.linspace(-4, 4, 12)})
    return pendula.wada_test(am, max_steps=1)


def _attractor_map():
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.35, drive_frequency=2 / 3)
    return pendula.attractor_map(sc, {"theta0": np.linspace(-3, 3, 7), "v0": np.linspace(-3, 3, 7)},
                                 transient=300, samples=16)


CASES = {
    "Scene": lambda: pendula.Scene(v0=1.9, damping=0.1, drive_amplitude=0.3, drive_frequency=0.7),
    "Trajectory": lambda: pendula.simulate(pendula.Scene(v0=1.9, t_end=60.0, n_samples=601)),
    "Orbit": lambda: pendula.orbit(0.0, 1.9),
    "Events": lambda: pendula.find_events(pendula.Scene(theta0=1.0), "turning", t_end=200.0),
    "Spectrum": lambda: pendula.simulate(pendula.Scene(v0=1.0, t_end=100.0, n_samples=1024)).spectrum(),
    "FourierSeries": lambda: pendula.fourier_series(1.0, 0.0),
    "ModelInfo": lambda: pendula.models()[0],
    "Capability": lambda: pendula.capabilities()[0],
    "Transmon": lambda: pendula.Transmon(20.0, 1.0, n_g=0.25),
    "Network": lambda: pendula.Network(64, topology="chain", strength=0.5),
    "NetworkEquilibrium": lambda: pendula.Network(8, topology="ring", strength=0.5).equilibrium(np.zeros(8)),
    "NormalModes": lambda: pendula.Network(64, topology="chain", strength=0.5).normal_modes(np.zeros(64)),
    "DCSquid": lambda: pendula.DCSquid(10e-6, 30.0, 1e-12, 100e-12),
    "RFSquid": lambda: pendula.RFSquid(1e-6, 500e-12),
    "SwitchingDistribution": lambda: pendula.switching_distribution(
        pendula.Junction(10e-6, 30.0, 1e-12, temperature=4.2), 1.0),
    "SphericalOrbit": lambda: pendula.spherical_orbit(0.8, 0.1, 0.9),
    "SphericalPath": lambda: pendula.spherical_orbit(0.8, 0.1, 0.9).path(np.linspace(0.0, 100.0, 5000)),
    "DoublePendulumModes": lambda: pendula.double_pendulum_modes(1.0, 1.0, 1.0, 1.0, 9.81),
    "DoublePendulum": lambda: pendula.DoublePendulum(m1=2.0, rods=True, damping=0.1),
    "FlipMap": lambda: pendula.DoublePendulum().flip_map(np.linspace(-3, 3, 8), np.linspace(-3, 3, 8), t_max=10.0),
    "LyapunovSpectrum": lambda: pendula.DoublePendulum().lyapunov(2.0, 2.5, t=100.0),
    "FoucaultPendulum": lambda: pendula.FoucaultPendulum(latitude=48.85),
    "FoucaultPrecession": lambda: pendula.FoucaultPendulum(latitude=48.85).precession(0.05, swings=20),
    "TimeScales": lambda: pendula.time_scales(pendula.Scene(damping=0.1, pivot_amplitude=0.1, pivot_frequency=9.0)),
    "NetworkTimeScales": lambda: pendula.Network(3, topology="chain", strength=1e4, damping=0.1).time_scales(),
    "CycloidGeometry": lambda: pendula.cycloid_geometry(0.25),
    "FrictionTurningPoints": lambda: pendula.friction_turning_points(pendula.Scene(theta0=3.0, friction=0.01)),
    "Equilibrium": lambda: pendula.equilibria(pendula.Scene(damping=0.2, torque=0.5))[0],
    "PeriodicOrbit": lambda: pendula.periodic_orbit(_driven(), (0.1, 1.9)),
    "Branch": lambda: pendula.continue_orbit(_driven(), (0.1, 1.9), "drive_amplitude", 1.07),
    "Bifurcation": lambda: pendula.continue_orbit(_driven(), (0.1, 1.9), "drive_amplitude", 1.07).bifurcations[0],
    "BifurcationCurve": lambda: _fold_curve(),
    "CodimTwoPoint": lambda: _fold_curve().points[0],
    "ShapiroTongue": lambda: pendula.shapiro_tongue(
        pendula.Scene(damping=1.0, drive_amplitude=1.0, drive_frequency=2.0), 1, 1.5),
    "EquilibriumBranch": lambda: pendula.continue_equilibria(pendula.Scene(damping=0.2), "torque", 1.5),
    "BranchTree": lambda: pendula.bifurcation_tree(_driven(), (0.1, 1.9), "drive_amplitude", 1.0805, depth=3),
    "Junction": lambda: pendula.Junction(1e-6, 10.0, 1e-12, temperature=0.1),
    "SwitchingCurrents": _switching,
    "Pendulum": lambda: pendula.Pendulum(1.0, amplitude_deg=30.0),
    "Swing": lambda: pendula.Pendulum(1.0, amplitude_deg=30.0).motion(),
    # not named in pendula.__all__ but returned by public functions
    "FlipLog": lambda: pendula.simulate(pendula.Scene(cord="flexible", v0=2.2, t_end=200.0, n_samples=50)).flips,
    "AttractorMap": _attractor_map,
    "WadaTest": _wada_test,
    "Attractor": lambda: _attractor_map().attractors[0],
    "GravityOrbit": lambda: pendula.gravity_orbit(pendula.Scene(theta0=1.0, gravity="linear",
                                                                gravity_gradient=0.1)),
}


def test_every_public_class_has_a_case():
    classes = {n for n in pendula.__all__ if isinstance(getattr(pendula, n), type)} - NOT_RESULTS
    assert classes <= set(CASES), sorted(classes - set(CASES))


@pytest.mark.parametrize("name", sorted(CASES))
def test_repr_is_a_short_summary(name):
    obj = CASES[name]()
    assert type(obj).__name__ == name
    text = repr(obj)
    numbers = re.findall(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?", text)
    assert len(text.splitlines()) < MAX_LINES, text
    assert len(text) < MAX_CHARS, text
    assert len(numbers) <= MAX_NUMBERS, text
    # str() (what print shows) is the same summary
    assert len(str(obj).splitlines()) < MAX_LINES

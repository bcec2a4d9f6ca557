"""The kind of a non-periodic attractor of pendula.attractor_map: quasi-periodic or chaotic where its largest
Lyapunov exponent is resolved from 0, undecided where it is not (pendula.dynamics.attractors.
classify_aperiodic).  References: SciPy's DOP853 written from the equation alone (rotation numbers, the
absence of a recurrence) and Liouville's closed form lambda_1 + lambda_2 = -damping."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pendula
from pendula.dynamics.attractors import classify_aperiodic

pytest.importorskip("xarray")


def scipy_strobe(beta, tau, A, omega, theta, v, periods, rtol=1e-11):
    """Unwrapped (theta, v) after each drive period, by SciPy alone."""
    def rhs(t, y):
        return [y[1], -math.sin(y[0]) - beta * y[1] + tau + A * math.cos(omega * t)]
    T = 2 * math.pi / omega
    sol = solve_ivp(rhs, (0.0, periods * T), [theta, v], method="DOP853", rtol=rtol, atol=rtol,
                    t_eval=T * np.arange(1, periods + 1))
    return sol.y[0], sol.y[1]


def test_quasi_periodic_running_state_at_torque_0_5_is_named_quasi_periodic_not_chaotic():
    # beta = 0.2, torque 0.5, A = 0.2, Omega = 1: a running state on an invariant circle (largest exponent
    # about -1.5e-5, rotation number about 2.4663 turns per drive period)
    sc = pendula.Scene(damping=0.2, torque=0.5, drive_amplitude=0.2, drive_frequency=1.0)
    am = pendula.attractor_map(sc, {"theta0": np.linspace(-3, 3, 4), "v0": np.linspace(-1, 3, 4)})
    kinds = [a.kind for a in am.attractors]
    assert "chaotic" not in kinds and kinds.count("quasi-periodic") == 1
    qp = am.attractors[kinds.index("quasi-periodic")]
    l1, l2, err = qp.lyapunov
    assert abs(l1) < 1e-3 and l2 < -0.1
    assert abs(l1 + l2 + 0.2) < 1e-6                    # Liouville
    assert math.isnan(qp.dimension) and qp.period == 0
    # SciPy from a point of the attractor: the mean turns per period over 1500 periods (the angle's distance
    # from uniform rotation is bounded on an invariant circle: the window's error is a few radians / 1400
    # turns), and no recurrence of any period up to 24 (a cycle would come back to within 1e-6)
    cells = am.dataset.attrs["cell"]
    th0, v0 = float(qp.theta[0]), float(qp.v[0])
    th, v = scipy_strobe(0.2, 0.5, 0.2, 1.0, th0, v0, 1500, rtol=1e-10)
    rot = (th[-1] - th[99]) / (2 * math.pi * 1400)
    assert abs(qp.rotation_number - rot) < 5e-4
    assert abs(rot - 2.4663) < 5e-4
    w = (th[100:] + math.pi) % (2 * math.pi) - math.pi
    for k in range(1, 25):
        d = np.maximum(np.abs((w[k:] - w[:-k] + math.pi) % (2 * math.pi) - math.pi), np.abs(v[100 + k:] - v[100:-k]))
        assert d.min() > 1e-6
    # the SciPy orbit stays on the attractor's cells (an attracting set found, not a transient)
    assert np.all(np.abs(v[100:] - qp.v.mean()) < 2 * (np.ptp(qp.v) / 2 + cells))
    assert am.dataset.attractor.attrs["flag_meanings"].count("quasi_periodic") == 1


def test_chaotic_attractor_at_1_2_stays_chaotic():
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.2, drive_frequency=2 / 3)
    info = classify_aperiodic(sc, 0.3, 0.0, 1e-10, 1e-12, periods=1000)
    assert info["kind"] == "chaotic" and info["lyapunov"][0] > 10 * info["resolution"]
    assert 1 < info["dimension"] < 2


def test_periodic_orbit_is_never_called_quasi_periodic_or_chaotic():
    # from a point of the stable period-1 rotation at A = 1.35: the largest exponent is resolved below 0, so the
    # rule leaves it undecided (a periodic orbit no recurrence confirmed) rather than give it a kind
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.35, drive_frequency=2 / 3)
    orb = pendula.periodic_orbit(sc, guess=(0.0, 2.0))
    info = classify_aperiodic(sc, orb.theta, orb.v, 1e-10, 1e-12, periods=200)
    assert info["kind"] is None and info["lyapunov"][0] < -info["resolution"]


def test_exponent_not_resolved_in_a_short_window_is_undecided():
    # the quasi-periodic state over 2 drive periods: the resolution log(1e3) / (2 T) is about 0.55, more than
    # the transverse exponent's 0.2, so no kind is resolved: undecided, never a guess
    sc = pendula.Scene(damping=0.2, torque=0.5, drive_amplitude=0.2, drive_frequency=1.0)
    am = pendula.attractor_map(sc, {"theta0": [0.0], "v0": [2.5]})
    (qp,) = am.attractors
    short = classify_aperiodic(sc, float(qp.theta[0]), float(qp.v[0]), 1e-10, 1e-12, periods=2)
    assert short["resolution"] >= math.log(1e3) / (2 * 2 * math.pi)
    assert short["kind"] is None


def test_quasi_periodic_attractor_is_named_so_in_the_basin_figure():
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("agg")
    import pendula.plot
    from pendula.plot import _categories
    sc = pendula.Scene(damping=0.2, torque=0.5, drive_amplitude=0.2, drive_frequency=1.0)
    am = pendula.attractor_map(sc, {"theta0": [0.0, 1.0], "v0": [2.0, 2.5]})
    names = [c["name"] for c in _categories(am)[2]]
    assert any(n.endswith(": quasi-periodic") for n in names), names
    ax = pendula.plot.basins(am)
    assert ax is not None
    matplotlib.pyplot.close("all")


def test_kind_is_decided_at_the_scene_of_the_grid_point_that_found_the_attractor():
    # a grid over the drive amplitude: the chaotic set of A = 1.2 is classified at A = 1.2, not at the base
    # scene's 1.35 (where the orbit from its point would settle on a rotation and leave it undecided)
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.35, drive_frequency=2 / 3)
    am = pendula.attractor_map(sc, {"drive_amplitude": [1.2, 1.21], "v0": [0.0, 0.5]})
    assert [a.kind for a in am.attractors] == ["chaotic"]
    assert (am.dataset.attractor.values >= 0).all() and am.undecided == 0
    chaotic = next(a for a in am.attractors if a.kind == "chaotic")
    assert chaotic.lyapunov[0] > 0.05 and abs(sum(chaotic.lyapunov[:2]) + 0.5) < 1e-6


def test_samples_method_names_the_quasi_periodic_state_too():
    sc = pendula.Scene(damping=0.2, torque=0.5, drive_amplitude=0.2, drive_frequency=1.0)
    am = pendula.attractor_map(sc, {"theta0": [0.0, 1.0], "v0": [2.5]}, method="samples", transient=300.0)
    assert [a.kind for a in am.attractors] == ["quasi-periodic"]
    assert (am.dataset.attractor.values == 0).all() and am.undecided == 0
    assert abs(am.attractors[0].rotation_number - 2.4663) < 5e-4

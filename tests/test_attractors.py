"""Attractors of the driven damped pendulum found by recurrence, and the basin
measures: the two coexisting period-1 rotations at A = 1.35 (beta = 0.5,
Omega = 2/3) against Newton's periodic orbits, labels independent of the
chunking, the threads and storage, and the estimators on label maps whose
answers are known in closed form."""

import math

import numpy as np
import pytest

import pendula
from pendula import Scene
from pendula import attractor_map
from pendula.dynamics.attractors import basin_entropy, boundary_fraction, label_attractors, \
    uncertainty_exponent

ROT = Scene(damping=0.5, drive_amplitude=1.35, drive_frequency=2.0 / 3.0)
GRID = {"theta0": np.linspace(-math.pi, math.pi, 14), "v0": np.linspace(-3.0, 3.0, 11)}


@pytest.fixture(scope="module")
def rot_map():
    return attractor_map(ROT, GRID, transient=300.0, samples=16)


def test_two_coexisting_period1_rotations_are_both_found(rot_map):
    atts = rot_map.attractors
    assert [(a.kind, a.period) for a in atts] == [("periodic", 1), ("periodic", 1)]
    labels = rot_map.dataset.attractor.values
    assert set(np.unique(labels)) == {0, 1}
    # each is a stable periodic orbit by Newton on the monodromy, one turning each way
    windings = []
    for a in atts:
        for w in (-1, 1):
            try:
                po = pendula.periodic_orbit(ROT, guess=(a.theta[0], a.v[0]), winding=w)
            except ValueError:
                continue
            if abs(po.theta - a.theta[0]) < 1e-6 and abs(po.v - a.v[0]) < 1e-6:
                assert po.stable
                windings.append(w)
    assert sorted(windings) == [-1, 1]
    assert abs(sum(a.fraction for a in atts) - 1.0) < 1e-12


def test_labels_do_not_depend_on_chunking_threads_or_storage(rot_map, tmp_path):
    ref = rot_map.dataset.attractor.values
    other = attractor_map(ROT, GRID, transient=300.0, samples=16, chunk_points=23, threads=1)
    np.testing.assert_array_equal(other.dataset.attractor.values, ref)
    stored = attractor_map(ROT, GRID, transient=300.0, samples=16, chunk_points=40, threads=2, out=tmp_path / "s")
    np.testing.assert_array_equal(stored.dataset.attractor.values, ref)
    again = attractor_map(ROT, GRID, transient=300.0, samples=16, chunk_points=40, threads=2, out=tmp_path / "s")
    np.testing.assert_array_equal(again.dataset.attractor.values, ref)


def test_dataset_has_cf_flags(rot_map):
    a = rot_map.dataset.attractor
    assert list(a.attrs["flag_values"]) == [-1, 0, 1]
    assert len(a.attrs["flag_meanings"].split()) == 3
    assert rot_map.dataset.attrs["measure"] == "attractor"


def test_period_detection_and_cycle_merging():
    rng = np.random.default_rng(1)
    cyc = np.array([0.3, -1.2, 2.5])            # a period-3 cycle
    th = np.tile(cyc, 6)[None, :].repeat(4, axis=0)
    th[1] = np.roll(th[1], 1)                    # the same cycle, entered at another phase
    th[2] += rng.normal(0, 1e-8, th.shape[1])    # noise below tol
    th[3] = 0.7                                   # a fixed point
    labels, atts = label_attractors(th, np.zeros_like(th))
    assert [a.period for a in atts] == [1, 3]
    assert labels.tolist() == [1, 1, 1, 0]


def test_wrapped_angles_count_as_one_point():
    th = np.array([[math.pi - 1e-9, -math.pi + 1e-9] * 4])
    labels, atts = label_attractors(th, np.zeros_like(th))
    assert atts[0].period == 1 and labels.tolist() == [0]


def test_two_chaotic_sets_are_told_apart_by_their_cells():
    rng = np.random.default_rng(2)
    a = rng.uniform(-0.5, 0.5, (5, 64))
    b = rng.uniform(1.5, 2.5, (5, 64))
    th = np.vstack([a, b])
    labels, atts = label_attractors(th, th.copy())
    assert [x.kind for x in atts] == ["chaotic", "chaotic"]
    assert len(set(labels[:5])) == 1 and len(set(labels[5:])) == 1 and labels[0] != labels[5]


def test_smooth_boundary_has_uncertainty_exponent_one():
    x, y = np.meshgrid(np.linspace(-1, 1, 512), np.linspace(-1, 1, 512))
    alpha, e, f = uncertainty_exponent((np.hypot(x, y - 0.1) < 0.6).astype(int))
    assert abs(alpha - 1.0) < 0.05


def test_fractal_boundary_has_uncertainty_exponent_below_one():
    # a Weierstrass-type boundary y = sum 2^(-j s) cos(2^j x): box dimension 2 - s, alpha = 2 - D = s
    x, y = np.meshgrid(np.linspace(0, 2 * math.pi, 1024), np.linspace(-2.5, 2.5, 1024))
    s = 0.5
    w = sum(2.0 ** (-j * s) * np.cos(2.0 ** j * x) for j in range(12))
    alpha = uncertainty_exponent((y < w).astype(int))[0]
    assert 0.3 < alpha < 0.8


def test_basin_entropy_of_a_checkerboard_is_log2_per_box():
    lab = (np.add.outer(np.arange(20), np.arange(20)) % 2)
    sb, sbb = basin_entropy(lab, box=4)
    assert abs(sb - math.log(2)) < 1e-12 and abs(sbb - math.log(2)) < 1e-12
    assert boundary_fraction(lab) == 1.0


def test_attractor_map_refuses_undriven_scene():
    with pytest.raises(ValueError, match="drive"):
        attractor_map(Scene(damping=0.1), GRID)


def test_sweep_measure_attractor_is_the_attractor_map(rot_map):
    ds = pendula.sweep(ROT, over=GRID, measure="attractor", transient=300.0, samples=16)
    np.testing.assert_array_equal(ds.attractor.values, rot_map.dataset.attractor.values)
    assert ds.attrs["basin_entropy"] == rot_map.basin_entropy
    import json
    assert [a["period"] for a in json.loads(ds.attrs["attractors"])] == [1, 1]

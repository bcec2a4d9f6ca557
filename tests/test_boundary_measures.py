"""Measures of basin boundaries and attractors: the Wada grid test, the Kaplan-Yorke dimension, and the
basin entropy and uncertainty exponent of pendula.dynamics.attractors checked against implementations
written here from the published definitions.

References: Daza, Wagemakers, Georgeot, Guery-Odelin & Sanjuan, "Basin entropy: a new tool to analyze
uncertainty in dynamical systems", Sci. Rep. 6, 31416 (2016) (S_b, S_bb and the log 2 criterion);
Daza et al., "Testing for basins of Wada", Sci. Rep. 5, 16579 (2015) (the grid test; the forced pendulum
x'' + 0.2 x' + sin x = 1.66 cos t has Wada basins); Grebogi, McDonald, Ott & Yorke, Phys. Lett. A 99, 415
(1983) (the uncertainty exponent); Kaplan & Yorke (1979) and Sprott, "Chaos and time-series analysis"
(2003), appendix A (published spectra and Kaplan-Yorke dimensions of the Henon map and the Lorenz flow).
"""

import math
import warnings

import numpy as np
import pytest

import pendula
from pendula.dynamics.attractors import basin_entropy, kaplan_yorke_dimension, uncertainty_exponent
from pendula.dynamics.boundary_measures import WadaTest, wada_test

pytest.importorskip("xarray")


# ---- independent implementations from the published definitions ----------------------------------------

def entropy_by_definition(labels, n):
    """Daza et al. 2016, eqs. (1)-(3): boxes of n x n points; S_i = sum_j p_ij log(1/p_ij); S_b the mean of
    S_i over all N boxes, S_bb over the N_b boxes on a boundary (S_i > 0)."""
    lab = np.asarray(labels)
    S = []
    for i in range(0, lab.shape[0] - n + 1, n):
        for j in range(0, lab.shape[1] - n + 1, n):
            box = lab[i:i + n, j:j + n].ravel().tolist()
            s = 0.0
            for c in set(box):
                p = box.count(c) / len(box)
                s += p * math.log(1.0 / p)
            S.append(s)
    S = np.array(S)
    return S.mean(), (S[S > 0].mean() if (S > 0).any() else 0.0)


def uncertainty_by_definition(label_of, lo, hi, eps_list, n, rng):
    """Grebogi et al. 1983: the fraction f(eps) of random initial points x whose attractor differs from that
    of x + eps d (d a random unit step along one axis, either side); alpha the slope of log f against
    log eps."""
    f = []
    for eps in eps_list:
        x = rng.uniform(lo, hi, size=(n, 2))
        ax = rng.integers(0, 2, n)
        sgn = rng.choice([-1.0, 1.0], n)
        y = x.copy()
        y[np.arange(n), ax] += sgn * eps
        f.append(np.mean(label_of(x) != label_of(y)))
    return np.polyfit(np.log(eps_list), np.log(f), 1)[0], np.array(f)


def disc(x):
    """A smooth boundary: the disc of radius 0.8 (label 1) in the square [-1, 1]^2."""
    return (x[..., 0] ** 2 + x[..., 1] ** 2 < 0.64).astype(int)


# ---- Kaplan-Yorke ----------------------------------------------------------------------------------------

def test_kaplan_yorke_dimension_of_published_spectra():
    # Henon map (a = 1.4, b = 0.3): 0.41922, -1.62319 nats per iterate, D_KY = 1.2583 (Sprott, appendix A)
    assert abs(kaplan_yorke_dimension([0.41922, -1.62319]) - 1.2583) < 1e-4
    # Lorenz flow (sigma 10, r 28, b 8/3): 0.9056, 0, -14.5723, D_KY = 2.0621; the order given does not matter
    assert abs(kaplan_yorke_dimension([-14.5723, 0.9056, 0.0]) - 2.0621) < 1e-4
    # the sum of the exponents of a 2-D map is log |det|: D = 1 + l1 / |log|det| - l1| (closed form)
    assert kaplan_yorke_dimension([0.2, math.log(0.5) - 0.2]) == pytest.approx(1 + 0.2 / (0.2 - math.log(0.5)),
                                                                               rel=4e-16)


def test_kaplan_yorke_dimension_edges_and_bad_input():
    assert kaplan_yorke_dimension([-0.1, -0.3]) == 0.0          # a stable fixed point
    assert kaplan_yorke_dimension([0.2, 0.1]) == 2.0            # no contraction: the whole space
    assert kaplan_yorke_dimension([0.0, -1.0]) == 1.0           # a limit cycle of a flow, or a circle
    with pytest.warns(RuntimeWarning, match="not finite"):
        assert math.isnan(kaplan_yorke_dimension([math.nan, -1.0]))
    for bad in ([], [[0.1, -0.2]]):
        with pytest.raises(ValueError, match="exponents"):
            kaplan_yorke_dimension(bad)


def test_chaotic_attractor_carries_its_spectrum_and_kaplan_yorke_dimension():
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.2, drive_frequency=2 / 3)
    am = pendula.attractor_map(sc, {"theta0": np.linspace(-math.pi, math.pi, 6), "v0": np.linspace(-3, 3, 6)})
    (a,) = am.attractors
    assert a.kind == "chaotic"
    l1, l2, err = a.lyapunov
    assert l1 > 10 * err and l1 > 0.05
    # Liouville: l1 + l2 = -damping (closed form: the trace of the variational matrix)
    assert abs(l1 + l2 + 0.5) < 1e-6
    assert a.dimension == pytest.approx(1 + l1 / abs(l2), rel=1e-15)
    assert 1.0 < a.dimension < 2.0


# ---- basin entropy and uncertainty exponent against the definitions -------------------------------------

@pytest.mark.parametrize("box", [5, 8])
def test_basin_entropy_matches_the_definition_on_smooth_and_random_maps(box):
    xs = np.linspace(-1, 1, 200)
    grid = np.stack(np.meshgrid(xs, xs, indexing="ij"), axis=-1)
    smooth = disc(grid)
    sb, sbb = basin_entropy(smooth, box)
    ref_b, ref_bb = entropy_by_definition(smooth, box)
    assert sb == pytest.approx(ref_b, rel=1e-12) and sbb == pytest.approx(ref_bb, rel=1e-12)
    assert 0 < sbb < math.log(2)       # a smooth boundary: below the log 2 criterion
    rng = np.random.default_rng(44)
    for k in (2, 3, 5):
        lab = rng.integers(0, k, size=(60, 75))
        got = basin_entropy(lab, box)
        ref = entropy_by_definition(lab, box)
        assert got[0] == pytest.approx(ref[0], rel=1e-12) and got[1] == pytest.approx(ref[1], rel=1e-12)


def test_uncertainty_exponent_of_a_smooth_boundary_is_one_both_ways():
    rng = np.random.default_rng(1983)
    alpha_ref, f = uncertainty_by_definition(disc, -1.0, 1.0, np.array([1e-3, 4e-3, 1.6e-2, 6.4e-2]), 40000,
                                             rng)
    # closed form: f(eps) = eps (perimeter) (mean |d . n| over the circle) / area = eps 2 pi 0.8 (2 / pi) / 4
    assert abs(alpha_ref - 1) < 0.05
    assert f == pytest.approx(0.8 * np.array([1e-3, 4e-3, 1.6e-2, 6.4e-2]), rel=0.15)
    xs = np.linspace(-1, 1, 400)
    alpha = uncertainty_exponent(disc(np.stack(np.meshgrid(xs, xs, indexing="ij"), axis=-1)))[0]
    assert abs(alpha - 1) < 0.05 and abs(alpha - alpha_ref) < 0.07


# ---- the forced pendulum with Wada basins ---------------------------------------------------------------

@pytest.fixture(scope="module")
def wada_map():
    sc = pendula.Scene(damping=0.2, drive_amplitude=1.66, drive_frequency=1.0)
    return pendula.attractor_map(sc, {"theta0": np.linspace(-math.pi, math.pi, 64), "v0": np.linspace(-4, 4, 64)})


def test_forced_pendulum_at_1_66_has_three_attractors_and_wada_basins(wada_map):
    assert len(wada_map.attractors) == 3 and wada_map.undecided == 0
    w = wada_test(wada_map)
    assert isinstance(w, WadaTest) and w.attractors == 3
    assert w.wada is True
    assert w.fractions[-1, -1] >= 0.99
    # the grid alone already shows most boxes with all three colours; refinement adds the rest
    assert w.fractions[0, -1] < w.fractions[-1, -1]
    assert np.allclose(w.fractions.sum(axis=1), 1.0)
    assert w.uncounted <= 0.01 * w.new_orbits


def test_measures_of_the_wada_map_match_the_definitions(wada_map):
    lab = wada_map.dataset.attractor.values
    sb, sbb = basin_entropy(lab)
    ref_b, ref_bb = entropy_by_definition(lab, 5)
    assert sb == pytest.approx(ref_b, rel=1e-12) and sbb == pytest.approx(ref_bb, rel=1e-12)
    assert (sb, sbb) == (wada_map.basin_entropy, wada_map.boundary_basin_entropy)
    # a fractal boundary: S_bb above log 2 (Daza et al. 2016's sufficient criterion)
    assert sbb > math.log(2)
    # the uncertainty exponent by Grebogi's definition on the same map (random grid points, shifts along a
    # random axis) against pendula's (every grid point, both axes): a fractal boundary, alpha well below 1
    rng = np.random.default_rng(1983)
    n = lab.shape[0]

    def label_of(x):
        i = np.clip(np.rint(x).astype(int), 0, n - 1)
        return lab[i[:, 0], i[:, 1]]
    alpha_ref, _ = uncertainty_by_definition(label_of, 4.0, n - 5.0, np.array([1.0, 2.0, 4.0]), 40000, rng)
    alpha = uncertainty_exponent(lab)[0]
    assert alpha < 0.5 and abs(alpha - alpha_ref) < 0.1


def test_wada_test_refuses_maps_it_cannot_test(wada_map):
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.35, drive_frequency=2 / 3)
    two = pendula.attractor_map(sc, {"theta0": np.linspace(-2, 2, 5), "v0": np.linspace(-3, 3, 5)})
    with pytest.raises(ValueError, match="three attractors"):
        wada_test(two)
    with pytest.raises(TypeError, match="amap"):
        wada_test(wada_map.dataset)
    for kw in ({"max_steps": 0}, {"tol": 0.0}, {"tol": 0.9}):
        with pytest.raises(ValueError, match=next(iter(kw))):
            wada_test(wada_map, **kw)
    with pytest.raises(TypeError, match="max_steps"):
        wada_test(wada_map, max_steps=2.5)


def test_wada_test_not_converged_within_its_steps_is_undecided(wada_map):
    # one refinement moves W_3 by more than tol: no verdict is given (None), never a guess
    w = wada_test(wada_map, max_steps=1)
    assert w.fractions.shape == (2, 3)
    assert abs(w.fractions[1, -1] - w.fractions[0, -1]) >= 0.01
    assert w.wada is None

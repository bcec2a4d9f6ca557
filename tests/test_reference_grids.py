"""Every public function against the stored random reference grids, mpmath at
40+ digits on the exact doubles (data/gen_reference_grids.py writes both):

* data/reference_grids.csv.gz: every function in every regime, 2000
  log-uniform random draws per class;
* data/reference_grids_edges.csv.gz: the ill-conditioned places, 1000 draws
  per class: am(u|m) in every class of m and next to sn = +-1/k for m > 1,
  sn cn dn far below m = 0, F and E(phi) next to multiples of pi/2 (mc down to
  1e-300) and next to the edge of the real domain for m > 1 (beyond it the
  reference is NaN), the exact motion from |theta0| up to 2^52.

The error of a point is max over outputs of |got - ref| / max(1, |ref|), in
eps; a NaN where the reference is finite, or the reverse, is an infinite
error.  The bound is 4 eps for every class (README's promise), unless
pendula.studies.accuracy.GRID_LIMITS states a measured, explained limit (none does).
"""

import pathlib

import numpy as np
import pytest

from pendula.studies.accuracy import grid_bound, grid_errors, grid_paths, load_grids

PATH = pathlib.Path(__file__).resolve().parents[1] / "data" / "reference_grids.csv.gz"
EDGES = PATH.with_name("reference_grids_edges.csv.gz")
MAIN = load_grids(PATH)
EDGE = load_grids(EDGES)
GRIDS = {**MAIN, **EDGE}


def test_the_grids_have_every_class_at_full_size():
    assert {c.split("_")[0] for c in MAIN} == {"jac", "k", "e", "nome", "f", "einc", "exact", "period"}
    assert all(len(a) >= 1900 for a in MAIN.values())
    assert set(EDGE) == {
        "am_m_small", "am_m_mid", "am_m_near1_mc", "am_m_neg", "am_m_gt1_m", "am_m_gt1_mc", "am_edge_m",
        "am_edge_mc", "jac_m_neg_far", "f_halfpi_m", "f_halfpi_mc", "einc_halfpi_m", "einc_halfpi_mc",
        "f_edge_m", "f_edge_mc", "einc_edge_m", "einc_edge_mc", "exact_huge_theta0_fwd", "exact_huge_theta0_bwd"}
    assert all(len(a) >= 950 for a in EDGE.values())
    assert not set(MAIN) & set(EDGE)
    assert grid_paths(PATH) == [PATH, EDGES]


def test_the_edge_grid_reaches_the_places_it_is_for():
    """The draws are where the classes say: next to N pi/2 to 1e-15 and
    closer, both sides of the m > 1 edge (NaN references beyond it), am
    within 1e-6 of +-pi/2 (sn next to +-1/k with k -> 1), theta0 beyond 1e15."""
    phi = EDGE["f_halfpi_mc"][:, 0]
    dist = np.abs(phi - np.round(phi / (np.pi / 2)) * (np.pi / 2)) / np.abs(phi)
    assert (dist < 1e-15).sum() > 50
    for cls in ("f_edge_m", "einc_edge_mc"):
        ref = EDGE[cls][:, 4]
        assert np.isnan(ref).sum() > 100 and np.isfinite(ref).sum() > 100
    am = EDGE["am_edge_mc"][:, 4]
    assert (np.pi / 2 - np.abs(am) < 1e-6).sum() > 50
    assert np.abs(EDGE["exact_huge_theta0_fwd"][:, 0]).max() > 1e15


@pytest.mark.parametrize("cls", sorted(GRIDS))
def test_worst_error_of_the_class(cls):
    a = GRIDS[cls]
    err = grid_errors(cls, a)
    over = err / grid_bound(cls)
    worst = int(np.argmax(over))
    assert over[worst] <= 1.0, f"{cls}: {err[worst]:.3g} eps at {a[worst, :4].tolist()}"


@pytest.mark.parametrize("cls", [c for c in sorted(GRIDS) if c.startswith("exact")])
def test_theta_of_the_exact_motion_within_4_eps(cls):
    a = GRIDS[cls]
    from pendula.systems.rigid import exact_motion

    th = np.array([exact_motion(*row[:3], [row[3]])[0][0] for row in a])
    err = np.abs(th - a[:, 4]) / np.maximum(1.0, np.abs(a[:, 4])) / np.finfo(float).eps
    assert err.max() <= 4.0, f"{cls}: theta {err.max():.3g} eps"


def test_accuracy_page_grid_table_is_the_generated_one():
    """The accuracy report's worst-error table (docs/source/reports/accuracy.md)
    is what `pendula accuracy grids` prints for the stored grid and the code as
    it is (a table that drifted from the code would be a claim nobody measured)."""
    from pendula.studies.accuracy import grids_markdown

    page = (PATH.parents[1] / "docs" / "source" / "reports" / "accuracy.md").read_text()
    table = grids_markdown(PATH)
    assert table in page, "the accuracy report's grid table differs: regenerate it with `pendula accuracy grids`"

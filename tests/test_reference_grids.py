"""Every public function against the stored random reference grids
(data/reference_grids.csv.gz, mpmath at 40+ digits, 2000 log-uniform random
draws per class; data/gen_reference_grids.py writes it).

The error of a point is max over outputs of |got - ref| / max(1, |ref|), in
eps.  The bound is 4 eps for every class (the promise of README), except
where a measured, explained limit is stated beside it:
"""

import pathlib

import numpy as np
import pytest

from pendula.accuracy import grid_errors, load_grids

PATH = pathlib.Path(__file__).resolve().parents[1] / "data" / "reference_grids.csv.gz"
GRIDS = load_grids(PATH)
# measured limits above 4 eps, with the reason in the module docstring
LIMITS: dict[str, float] = {}


def test_the_grid_has_every_class_at_full_size():
    kinds = {c.split("_")[0] for c in GRIDS}
    assert kinds == {"jac", "k", "e", "nome", "f", "einc", "exact", "period"}
    assert all(len(a) >= 1900 for a in GRIDS.values())


def bounds(cls, a):
    """The bound of each point: 4 eps, or the class's measured limit."""
    return np.full(len(a), float(LIMITS.get(cls, 4.0)))


@pytest.mark.parametrize("cls", sorted(GRIDS))
def test_worst_error_of_the_class(cls):
    a = GRIDS[cls]
    err = grid_errors(cls, a)
    over = err / bounds(cls, a)
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
    from pendula.accuracy import grids_markdown

    page = (PATH.parents[1] / "docs" / "source" / "reports" / "accuracy.md").read_text()
    table = grids_markdown(PATH)
    assert table in page, "the accuracy report's grid table differs: regenerate it with `pendula accuracy grids`"

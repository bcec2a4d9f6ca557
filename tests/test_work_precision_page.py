"""The work-precision page answers first: a figure per problem with the best of each family
(at most 8 curves), tables narrow enough for the column, and no cell RST would turn into a bullet."""

import json
import pathlib
import re

import pytest

from pendula.studies import workprecision as wp
from pendula.studies import workprecision_report as wpr

ROOT = pathlib.Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "source" / "work_precision.rst"


@pytest.fixture(scope="module")
def record():
    return json.loads((ROOT / "data" / "bench" / "work_precision.json").read_text())


@pytest.mark.parametrize("problem", sorted(wp.PROBLEMS))
def test_each_figure_draws_at_most_eight_curves_one_per_family(record, problem):
    curves = wpr.best_of_families([r for r in record["rows"] if r["problem"] == problem])
    assert len(curves) + 1 <= 8                     # and the exact path's star
    families = [f for f, _, _ in curves if "auto" not in f]
    assert len(families) == len(set(families))


def test_best_of_a_family_is_the_fastest_at_most_levels():
    rows = [dict(package="pendula", method=m, error_max=e, seconds=s)
            for m, e, s in (("dopri5", 1e-6, 3.0), ("dopri5", 1e-9, 9.0), ("vern9", 1e-6, 1.0), ("vern9", 1e-9, 2.0),
                            ("dop853", 1e-6, 2.0), ("dop853", 1e-9, 4.0), ("auto", 1e-6, 1.0))]
    assert wpr.best_of_families(rows) == [("pendula, adaptive", "pendula", "vern9"),
                                         ("pendula, method='auto'", "pendula", "auto")]


def test_answer_comes_before_the_method_notes():
    text = PAGE.read_text()
    assert text.index("The answer") < text.index("How it was measured") < text.index("Errors and timing")
    assert text.index(".. image:: ../figures/work_precision_libration.png") < text.index("Problems\n~")


def test_answer_tables_have_four_columns_and_no_lone_dash(record):
    rst = wpr.answer_rst(record)
    for table in rst.split(".. list-table::")[1:]:
        first_row = table.split("   * - ")[1]
        assert first_row.count("\n     - ") == 3
    assert not re.search(r"^\s+[*]? ?- -\s*$", rst, re.M)


def test_page_title_differs_from_the_cost_report():
    cost = (ROOT / "docs" / "source" / "reports" / "cost.md").read_text().splitlines()[0].lstrip("# ").strip()
    assert PAGE.read_text().splitlines()[0].strip() != cost

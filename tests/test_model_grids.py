"""The models against their stored random mpmath grids (data/model_grids.csv.gz, written by
data/gen_model_grids.py): every class within its stated tolerance A + B cond eps
(pendula.studies.model_grids.TOLERANCES gives A, B and the reason of each family)."""

from __future__ import annotations

import math
import pathlib

import pytest

from pendula.studies import model_grids as mg

PATH = pathlib.Path(__file__).resolve().parents[1] / "data" / "model_grids.csv.gz"
ROWS = mg.load(PATH)
CLASSES = sorted({(r["cls"], r["quantity"]) for r in ROWS})


@pytest.fixture(scope="module")
def results():
    out: dict = {}
    for e in mg.evaluate(ROWS):
        out.setdefault((e["cls"], e["quantity"]), []).append(e)
    return out


@pytest.mark.parametrize("cls,quantity", CLASSES, ids=[f"{c}:{q}" for c, q in CLASSES])
def test_model_grid_class_within_tolerance(results, cls, quantity):
    es = results[(cls, quantity)]
    bad = [e for e in es if not e["err"] <= e["tol"]]
    worst = max(es, key=lambda e: e["err"])
    assert not bad, (f"{len(bad)} of {len(es)} points beyond tolerance; first at "
                     f"{ {k: v for k, v in bad[0]['row'].items() if v} }: error {bad[0]['err']:.3g} eps, "
                     f"tolerance {bad[0]['tol']:.3g} eps")
    assert math.isfinite(worst["err"])


def test_model_grid_covers_every_model_and_region():
    have = {c for c, _ in CLASSES}
    for field in ("uniform", "inverse-square", "linear"):
        for region in ("libration", "rotation", "near-separatrix", "near-top"):
            assert f"gravity_orbit/{field}/{region}" in have
        for q in ("cdf", "density"):
            for sub in ("libration", "libration-turning", "rotation"):
                assert f"angle_{q}/{field}/{sub}" in have
    for c in ("cycloid_period", "cycloid_geometry", "cycloid_motion/over-damped", "cord_flip",
              "find_events/turning", "find_events/theta", "numerical_period"):
        assert c in have
    # the grids are random points in every class, not a handful (the density's classes are split
    # further by where the orbit lies: next to the separatrix, next to the top)
    counts: dict = {}
    for r in ROWS:
        base = r["cls"].split("-near-")[0]
        counts[base] = counts.get(base, 0) + 1
    assert min(counts.values()) >= 5, sorted(counts.items(), key=lambda kv: kv[1])[:3]


def test_model_grid_uniform_limit_of_inverse_square_is_in_the_grid():
    # the inverse-square field with the mass 1e16 to 1e300 lengths away: the uniform limit
    far = [r for r in ROWS if r["cls"].startswith("gravity_orbit/inverse-square") and float(r["x1"]) > 1e15]
    assert far

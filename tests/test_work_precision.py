"""The work-precision study (pendula.studies.workprecision): its references, its clock, its record
and the report page made from the record.  Timings are never asserted (benchmarks are not
tests); what is checked is that the numbers the study reports are the ones it measured."""

import json
import math
import pathlib

import numpy as np
import pytest

import pendula
from pendula import _kernel
from pendula.studies import workprecision as wp
from pendula.studies import workprecision_report as wpr

ROOT = pathlib.Path(__file__).resolve().parents[1]
RECORD = ROOT / "data" / "bench" / "work_precision.json"


@pytest.fixture(scope="module")
def reference():
    return wp.load_reference(ROOT / "data" / "work_precision_reference.json")


@pytest.fixture(scope="module")
def record():
    return json.loads(RECORD.read_text())


def test_reference_two_taylor_integrations_agree_below_1e20(reference):
    assert set(reference) == set(wp.PROBLEMS)
    for name, r in reference.items():
        assert r["reference_check"] < 1e-20, name
        assert r["t"].size == wp.N_OUT + 1 and r["t"][-1] == wp.PROBLEMS[name]["t_end"]


def test_reference_agrees_with_the_closed_form_on_the_conservative_problems(reference):
    """Two independent references: the Taylor integration and the exact path (Jacobi
    functions), within a few ulp of theta (theta reaches 200 on the rotation)."""
    for name in ("libration", "rotation"):
        p, r = wp.PROBLEMS[name], reference[name]
        th, v = pendula.exact_motion(p["theta0"], p["v0"], p["eps"], r["t"])
        scale = np.maximum(1.0, np.abs(r["theta"]))
        assert np.max(np.abs(th - r["theta"]) / scale) < 8 * np.finfo(float).eps, name
        assert np.max(np.abs(v - r["v"])) < 8 * np.finfo(float).eps, name


def test_reference_starts_from_the_problem_initial_state(reference):
    for name, r in reference.items():
        assert r["theta"][0] == wp.PROBLEMS[name]["theta0"] and r["v"][0] == wp.PROBLEMS[name]["v0"]


def test_double_precision_floor_grows_with_the_chaos_of_the_driven_pendulum(reference):
    """The driven pendulum's floor at t = 50 is far above one ulp (a few Lyapunov times)
    while the damped one, which settles, forgets the perturbation."""
    assert reference["driven"]["floor_error_max"] > 30 * np.finfo(float).eps
    assert reference["damped"]["floor_error_final"] < 4 * np.finfo(float).eps


@pytest.mark.parametrize("method,code", [("dop853", 9), ("gsl-rk8pd", 10), ("dprkn6", 11), ("gauss6", 7)])
def test_kernel_clock_runs_the_same_integration_as_the_binding(method, code):
    """integrate_timed_v times exactly the integration integrate_v runs: same outputs to the bit."""
    p = wp.PROBLEMS["rotation"]
    t = np.linspace(0.0, 10.0, 11)
    prm = wp._params(p)
    dt = 0.05 if method == "gauss6" else 0.0
    th, v, stats, sec, status = _kernel.integrate_timed_v(3, code, prm, p["theta0"], p["v0"], t, 1e-9, 1e-9, dt)
    assert status == 0 and sec > 0
    cancel = np.zeros(1, dtype=np.int32)
    scene = pendula.Scene(eps=p["eps"], theta0=p["theta0"], v0=p["v0"], rtol=1e-9, atol=1e-9, dt=dt)
    th2, v2, stats2, status2, *_ = _kernel.integrate_v(*scene._kernel_fields, code, t, 0, 0.0, 0, 0, 1, cancel)
    assert status2 == 0
    assert np.array_equal(th, th2) and np.array_equal(v, v2) and np.array_equal(stats, stats2)


def test_kernel_clock_times_the_exact_path():
    t = np.linspace(0.0, 10.0, 11)
    th, v, stats, sec, status = _kernel.integrate_timed_v(5, 0, wp._params(wp.PROBLEMS["libration"]), 0.0, 1.999,
                                                          t, 0.0, 0.0, 0.0)
    ex, vex = pendula.exact_motion(0.0, 1.999, 1.0, t)
    assert status == 0 and np.array_equal(th, ex) and np.array_equal(v, vex)


def test_kernel_clock_refuses_no_repetitions():
    t = np.linspace(0.0, 1.0, 3)
    *_, status = _kernel.integrate_timed_v(0, 9, wp._params(wp.PROBLEMS["damped"]), 0.0, 1.0, t, 1e-6, 1e-6, 0.0)
    assert status != 0


def test_best_time_repeats_until_the_spread_is_small():
    # the stopping rule on a fake clock (a fixed sequence of batch results; nothing is timed):
    # a first (calibration) run, then batches until the best three are within 3 %
    seq = iter([0.1, 0.05, 0.09, 0.08, 0.051, 0.0505, 0.2])
    tm = wp.best_time(lambda n: next(seq), batch_seconds=0.1, max_batches=10)
    best_of_sequence, spread = tm["seconds"], tm["spread"]
    assert best_of_sequence == 0.05 and spread == pytest.approx(0.02)
    assert tm["repeats"] == 5   # five batches of one run each (a run is as long as a batch)


def test_errors_measure_the_state_against_the_reference(reference):
    p, r = wp.PROBLEMS["libration"], reference["libration"]
    th = r["theta"].copy()
    th[40] += 3e-7
    v = r["v"].copy()
    v[-1] -= 2e-9
    e = wp.errors(p, r, th, v)
    assert e["error_max"] == pytest.approx(3e-7, rel=1e-6)
    assert e["error_final"] == pytest.approx(2e-9, rel=1e-4)
    energy = 0.5 * v ** 2 - np.cos(th)
    assert e["error_energy"] == np.max(np.abs(energy - (0.5 * 1.999 ** 2 - 1.0)))


def test_short_study_records_every_field(reference):
    rec = wp.run_study(problems=("damped",), tols=[1e-6], quick=True, progress=False)
    assert {r["package"] for r in rec["rows"]} >= {"pendula", "gsl", "scipy"}
    for r in rec["rows"]:
        for key in ("problem", "package", "method", "setting", "error_final", "error_max", "error_energy",
                    "seconds", "repeats", "spread"):
            assert key in r
        assert math.isfinite(r["error_max"]) and r["repeats"] >= 3
        # every method at rtol = 1e-6 on the damped pendulum: an error of the order of the tolerance
        assert 1e-12 < r["error_max"] < 1e-3, r


def test_report_page_tables_are_the_ones_generated_from_the_recorded_run(record):
    text = (ROOT / "docs" / "source" / "work_precision.rst").read_text()
    for key, body in wpr.generated_parts(record).items():
        assert wpr.page_part(text, key) == body, key


def test_record_has_every_problem_and_package(record):
    assert {r["problem"] for r in record["rows"]} == set(wp.PROBLEMS)
    assert {"pendula", "gsl", "scipy"} <= {r["package"] for r in record["rows"]}
    assert set(record["floors"]) == set(wp.PROBLEMS)


def test_auto_picks_what_the_recorded_table_says(record):
    """'auto' integrates a non-conservative scene by the recorded study's pick for its class and rtol
    (auto_picks, read from the stored record, not timed here; the whole table in
    tests/test_integrators_auto.py), and answers a conservative one by the exact path."""
    picks = wpr.auto_picks(record["rows"])
    scene = pendula.Scene(v0=2.3, damping=0.1, rtol=1e-9, atol=1e-9)
    assert pendula.simulate(scene, [0.0, 1.0]).method == picks["damped", 9]["method"]
    assert pendula.simulate(pendula.Scene(v0=2.5), [0.0, 1.0]).method == "exact"


def test_docstring_examples_run():
    import doctest

    failures, tried = doctest.testmod(wp, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert failures == 0 and tried > 0

"""The attractor map by recurrence (pendula.attractor_map, the default method) and the continuation of
basin fractions (pendula.attractor_continuation) on the driven damped pendulum
theta'' = -sin(theta) - 0.5 theta' + A cos(2 t / 3), grids over theta0 in [-pi, pi], v0 in [-3, 3].

The references are independent of the recurrence finder: the long-run labels of
data/attractors/reference_labels.json (1200 time units, 64 samples, no early stopping; their cycles
checked against SciPy by data/gen_attractor_reference.py), SciPy's DOP853 written from the equation
alone for the cycles and the chaotic set found here, and Liouville's closed form for the multipliers.
"""

import json
import math
import pathlib

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pendula
from pendula import Scene, attractor_continuation, attractor_map
from pendula.dynamics.attractors import cell_ids

pytest.importorskip("xarray")

BETA, OMEGA = 0.5, 2.0 / 3.0
REF = json.loads((pathlib.Path(__file__).resolve().parents[1] / "data" / "attractors" /
                  "reference_labels.json").read_text())


def scene(A):
    return Scene(damping=BETA, drive_amplitude=A, drive_frequency=OMEGA)


def grid(n, m=None):
    return {"theta0": np.linspace(-math.pi, math.pi, n), "v0": np.linspace(-3.0, 3.0, m or n)}


def scipy_strobe(A, theta, v, periods, rtol=1e-12):
    """The state after each of `periods` drive periods, by SciPy from the equation alone."""
    def rhs(t, y):
        return [y[1], -math.sin(y[0]) - BETA * y[1] + A * math.cos(OMEGA * t)]
    T = 2 * math.pi / OMEGA
    sol = solve_ivp(rhs, (0.0, periods * T), [theta, v], method="DOP853", rtol=rtol, atol=rtol,
                    t_eval=T * np.arange(1, periods + 1))
    th = (sol.y[0] + math.pi) % (2 * math.pi) - math.pi
    return th, sol.y[1]


def section_dist(t1, v1, t2, v2):
    return max(abs((t1 - t2 + math.pi) % (2 * math.pi) - math.pi), abs(v1 - v2))


@pytest.fixture(scope="module")
def map_107():
    return attractor_map(scene(1.07), grid(REF["cases"]["1.07"]["n"]))


def test_default_map_at_1_07_finds_exactly_the_two_period2_attractors(map_107):
    atts = map_107.attractors
    assert [(a.kind, a.period) for a in atts] == [("periodic", 2), ("periodic", 2)]
    assert map_107.undecided == 0
    for a in atts:
        # each is a stable cycle: SciPy from the equation alone returns to the point after 2 periods
        th, v = scipy_strobe(1.07, float(a.theta[0]), float(a.v[0]), 2)
        assert section_dist(th[-1], v[-1], a.theta[0], a.v[0]) < 1e-8
        assert section_dist(th[0], v[0], a.theta[1], a.v[1]) < 1e-8
        assert np.all(np.abs(a.multipliers) < 1)
        # Liouville: the product of the multipliers is exp(-beta * 2 T)
        prod = np.prod(a.multipliers).real
        assert abs(prod - math.exp(-BETA * 2 * 2 * math.pi / OMEGA)) < 1e-8 * math.exp(-BETA * 4 * math.pi / OMEGA) \
            + 1e-12


def test_labels_match_the_long_transient_run_on_995_permille_of_stable_points(map_107):
    for A, m in (("1.07", map_107), ("1.35", attractor_map(scene(1.35), grid(REF["cases"]["1.35"]["n"])))):
        assert_matches_long_run(A, m)


@pytest.mark.parametrize("case", ["1.35 150", "1.07 150"])
def test_coarse_to_fine_map_matches_the_long_transient_run_on_995_permille_of_stable_points(case):
    # 150 x 150: four levels (strides 8, 4, 2, 1); at 1.35 most points inherit their label, at 1.07 (intermixed
    # basins, uncertainty exponent about 0.14) the 4 x 4 blocks of the level above rarely agree
    A = float(case.split()[0])
    m = attractor_map(scene(A), grid(REF["cases"][case]["n"]))
    assert json.loads(m.dataset.attrs["levels"]) == [8, 4, 2, 1]
    assert m.dataset.attrs["inherited"] == int(m.dataset.inherited.values.sum()) > 0
    assert_matches_long_run(case, m)


def assert_matches_long_run(case_name, m):
    """At least 99.5 % of the points whose long-run label is stable under rtol 1e-12 get that label."""
    case = REF["cases"][case_name]
    ref = np.array(case["labels"])
    stable = np.array(case["stable"], dtype=bool)
    # our labels in the reference's numbering: match the cycles by position
    ours = np.full(ref.shape, -9)
    for a in m.attractors:
        for j, c in enumerate(case["cycles"]):
            if c["period"] == a.period and min(section_dist(c["theta"][0], c["v"][0], t, v)
                                               for t, v in zip(a.theta, a.v)) < 1e-6:
                ours[m.dataset.attractor.values == a.label] = j
    agree = (ours == ref)[stable].mean()
    assert agree >= 0.995, f"{case_name}: {agree:.4f} of the stable points agree"


def test_chaotic_attractor_at_1_2_is_one_and_holds_an_independent_orbit():
    am = attractor_map(scene(1.2), grid(8))
    assert [a.kind for a in am.attractors] == ["chaotic"]
    assert am.attractors[0].fraction == 1.0 and am.undecided == 0
    # an orbit computed by SciPy alone, after a transient, lies in the attractor's cells (or next to them)
    th, v = scipy_strobe(1.2, 0.3, 0.0, 400, rtol=1e-9)     # a chaotic orbit: any accurate one will do
    cell = am.dataset.attrs["cell"]
    mine = set(cell_ids(am.attractors[0].theta, am.attractors[0].v, cell).tolist())
    ni = math.ceil(2 * math.pi / cell)
    hits = 0
    for c in cell_ids(th[100:], v[100:], cell).tolist():
        j, i = divmod(c, ni)
        hits += any(((j + dj) * ni + (i + di) % ni) in mine for dj in (-1, 0, 1) for di in (-1, 0, 1))
    assert hits >= 0.95 * 300


def test_default_map_at_1_35_finds_the_two_period1_rotations():
    am = attractor_map(scene(1.35), grid(9))
    assert [(a.kind, a.period) for a in am.attractors] == [("periodic", 1), ("periodic", 1)]
    assert sorted(a.winding for a in am.attractors) == [-1, 1]
    for a in am.attractors:
        th, v = scipy_strobe(1.35, float(a.theta[0]), float(a.v[0]), 1)
        assert section_dist(th[0], v[0], a.theta[0], a.v[0]) < 1e-8


def test_grid_of_levels_gives_the_same_labels_whatever_the_threads_chunking_or_resume(tmp_path):
    # 66 x 64: levels of strides 4, 2, 1, each inheriting from the one above; chunks of one row (7 points)
    sc, g = scene(1.35), grid(66, 64)
    ref = attractor_map(sc, g)
    assert json.loads(ref.dataset.attrs["levels"]) == [4, 2, 1] and ref.dataset.attrs["inherited"] > 0
    for kw in ({"chunk_points": 7, "threads": 1}, {"chunk_points": 500, "threads": 2},
               {"chunk_points": 1000, "out": tmp_path / "s"}, {"chunk_points": 1000, "out": tmp_path / "s"}):
        other = attractor_map(sc, g, **kw)
        np.testing.assert_array_equal(other.dataset.attractor.values, ref.dataset.attractor.values)
        np.testing.assert_array_equal(other.dataset.inherited.values, ref.dataset.inherited.values)
        np.testing.assert_array_equal(other.dataset.recheck.values, ref.dataset.recheck.values)


def test_map_of_a_small_window_inherits_only_inside_it_and_keeps_the_labels():
    # the orbits leave the window (|v| > 0.5, |theta| > 1) at once: only samples that fall back inside it
    # may inherit, and the labels stay those of the orbit-by-orbit map
    sc = scene(1.35)
    g = {"theta0": np.linspace(-1.0, 1.0, 64), "v0": np.linspace(-0.5, 0.5, 64)}
    on, off = attractor_map(sc, g), attractor_map(sc, g, inherit=False)
    assert json.loads(on.dataset.attrs["levels"]) == [4, 2, 1] and on.dataset.attrs["inherited"] > 0
    assert (on.dataset.attractor.values == off.dataset.attractor.values).mean() >= 0.995


def test_grid_not_over_theta0_and_v0_is_one_level_without_inheritance():
    sc = scene(1.35)
    m = attractor_map(sc, {"theta0": np.linspace(-3, 3, 80)})
    assert json.loads(m.dataset.attrs["levels"]) == [1] and m.dataset.attrs["inherited"] == 0
    off = attractor_map(sc, grid(40, 40), inherit=False)
    assert json.loads(off.dataset.attrs["levels"]) == [1] and off.dataset.attrs["inherited"] == 0


def test_inheriting_costs_fewer_drive_periods_and_keeps_the_labels_of_smooth_basins():
    # at 1.35 the basins are smooth on the grid's scale: inherited labels equal the orbit-by-orbit ones
    sc, g = scene(1.35), grid(64, 64)
    on, off = attractor_map(sc, g), attractor_map(sc, g, inherit=False)
    assert on.dataset.attrs["mean_periods"] < 0.6 * off.dataset.attrs["mean_periods"]
    assert (on.dataset.attractor.values != off.dataset.attractor.values).mean() < 0.005


@pytest.mark.parametrize("pilot", [64, 1])
def test_labels_do_not_depend_on_threads_chunking_or_resume(pilot, tmp_path):
    # pilot=1: most attractors are found in the labelling pass and run again (the deterministic rerun)
    sc, g = scene(1.35), grid(12, 10)
    ref = attractor_map(sc, g, pilot=pilot)
    if pilot == 1:
        assert ref.dataset.attrs["new_in_labelling"] > 0
    for kw in ({"chunk_points": 23, "threads": 1}, {"chunk_points": 7, "threads": 2},
               {"chunk_points": 40, "out": tmp_path / "s"}, {"chunk_points": 40, "out": tmp_path / "s"}):
        other = attractor_map(sc, g, pilot=pilot, **kw)
        np.testing.assert_array_equal(other.dataset.attractor.values, ref.dataset.attractor.values)
        np.testing.assert_array_equal(other.dataset.recheck.values, ref.dataset.recheck.values)
        assert [(a.period, a.winding) for a in other.attractors] == [(a.period, a.winding) for a in ref.attractors]


def test_resume_after_a_lost_chunk_gives_the_same_labels(tmp_path):
    sc, g = scene(1.35), grid(10, 6)
    ref = attractor_map(sc, g, chunk_points=12, out=tmp_path / "s")
    # a chunk's commit record lost (a run killed before it committed): computed again on resume
    recs = sorted((tmp_path / "s" / "sweep.zarr" / "commits").glob("c*/zarr.json"))
    assert recs
    recs[0].unlink()
    again = attractor_map(sc, g, chunk_points=12, out=tmp_path / "s")
    np.testing.assert_array_equal(again.dataset.attractor.values, ref.dataset.attractor.values)


def test_boundary_points_are_rechecked_and_counted():
    am = attractor_map(scene(1.35), grid(12, 10))
    r = am.dataset.recheck.values
    lab = am.dataset.attractor.values
    assert am.rechecked == int((r > 0).sum()) > 0
    assert am.recheck_changed == int((r == 2).sum())
    # every point with a neighbour of another final label was rechecked, unless the recheck moved a neighbour
    interior = np.ones(lab.shape, dtype=bool)
    interior[1:] &= lab[1:] == lab[:-1]
    interior[:-1] &= lab[1:] == lab[:-1]
    interior[:, 1:] &= lab[:, 1:] == lab[:, :-1]
    interior[:, :-1] &= lab[:, 1:] == lab[:, :-1]
    assert np.all(r[~interior] > 0) or am.recheck_changed > 0


def test_limit_reached_everywhere_is_undecided_never_chaotic():
    with pytest.warns(RuntimeWarning, match="max_periods"):
        am = attractor_map(scene(1.2), grid(4), max_periods=2)
    assert am.attractors == [] and am.undecided == 16
    assert np.all(am.dataset.attractor.values == -1) and np.all(am.dataset.status.values == 1)


def test_undecided_points_are_counted_not_labelled():
    # a limit that a slowly converging period-2 orbit cannot meet, but a few points can
    am = attractor_map(scene(1.07), grid(6), max_periods=6)
    lab = am.dataset.attractor.values
    assert am.undecided == int((lab == -1).sum()) > 0
    assert all(a.kind == "periodic" for a in am.attractors)
    assert np.all(am.dataset.status.values[lab == -1] == 1)


def test_cell_too_coarse_to_tell_attractors_apart_is_refused():
    with pytest.raises(ValueError, match="cell"):
        attractor_map(scene(1.35), grid(5), cell=8.0)


def test_one_point_grid_is_labelled():
    am = attractor_map(scene(1.35), {"theta0": [0.5]})
    assert am.dataset.attractor.shape == (1,) and am.dataset.attractor.values[0] == 0
    assert am.attractors[0].fraction == 1.0


def test_undriven_scene_is_refused():
    with pytest.raises(ValueError, match="drive"):
        attractor_map(Scene(damping=0.5), grid(4))
    with pytest.raises(ValueError, match="drive"):
        attractor_continuation(Scene(damping=0.5), grid(4), "torque", [0.1, 0.2])


@pytest.mark.parametrize("kw", [{"max_period": 2.5}, {"consecutive": True}, {"recurrences": 10.0},
                                {"cell": True}, {"near": "0.1"}, {"pilot": 1.5}, {"max_periods": np.float64(9)},
                                {"inherit": 1}, {"inherit": "yes"}, {"margin": 1.0}])
def test_arguments_of_the_wrong_kind_are_type_errors_naming_them(kw):
    with pytest.raises(TypeError, match=next(iter(kw))):
        attractor_map(scene(1.35), grid(3), **kw)


@pytest.mark.parametrize("kw", [{"max_period": 0}, {"cell": -0.1}, {"near": math.nan}, {"rtol": 2.0},
                                {"method": "fast"}, {"margin": -1}])
def test_arguments_out_of_range_are_value_errors(kw):
    with pytest.raises(ValueError):
        attractor_map(scene(1.35), grid(3), **kw)


def test_dataset_title_names_the_attractor_map():
    am = attractor_map(scene(1.35), grid(3))
    assert "attractor map" in am.dataset.attrs["title"]
    assert am.dataset.attrs["method"] == "recurrence"


# ---- continuation ----------------------------------------------------------------------------------------

def test_continuation_follows_the_rotations_and_is_nan_where_absent(tmp_path):
    g = grid(8)
    vals = [1.07, 1.35]
    ds = attractor_continuation(scene(1.0), g, "drive_amplitude", vals)
    assert ds.fraction.dims == ("drive_amplitude", "attractor")
    # four attractors: two period-2 (only at 1.07), two period-1 rotations (only at 1.35)
    assert sorted(ds.period.values.tolist()) == [1, 1, 2, 2]
    f = ds.fraction.values
    assert np.all(np.isnan(f[0, ds.period.values == 1])) and np.all(np.isnan(f[1, ds.period.values == 2]))
    np.testing.assert_allclose(np.nansum(f, axis=1) + ds.undecided.values, 1.0)
    # each value's fractions are those of its own attractor map
    am = attractor_map(scene(1.35), g)
    got = sorted(f[1][~np.isnan(f[1])].tolist())
    assert got == sorted(a.fraction for a in am.attractors)


def test_continuation_matches_attractors_that_move_a_little():
    ds = attractor_continuation(scene(1.0), grid(6), "drive_amplitude", [1.34, 1.345, 1.35])
    assert ds.sizes["attractor"] == 2 and not np.isnan(ds.fraction.values).any()


def test_continuation_resumes_from_its_folder(tmp_path):
    args = (scene(1.0), grid(6), "drive_amplitude", [1.34, 1.35])
    first = attractor_continuation(*args, out=tmp_path / "c")
    (tmp_path / "c" / "value_0001" / "summary.json").unlink()       # the second value not finished
    again = attractor_continuation(*args, out=tmp_path / "c")
    np.testing.assert_array_equal(first.fraction.values, again.fraction.values)
    with pytest.raises(ValueError, match="another continuation"):
        attractor_continuation(scene(1.0), grid(6), "drive_amplitude", [1.3, 1.35], out=tmp_path / "c")


@pytest.mark.parametrize("values", [[1.1, 1.3, 1.2], [1.2, 1.2], [], [1.1, math.nan]])
def test_continuation_values_not_monotonic_or_bad_are_refused(values):
    with pytest.raises(ValueError, match="values"):
        attractor_continuation(scene(1.0), grid(3), "drive_amplitude", values)


def test_continuation_param_must_be_a_scene_field_off_the_grid():
    with pytest.raises(ValueError, match="param"):
        attractor_continuation(scene(1.0), grid(3), "theta0", [0.1, 0.2])
    with pytest.raises(ValueError, match="param"):
        attractor_continuation(scene(1.0), grid(3), "length", [0.1, 0.2])


def test_labels_on_a_dask_cluster_equal_the_local_run():
    distributed = pytest.importorskip("dask.distributed")
    import logging
    sc, g = scene(1.35), grid(36, 34)      # levels of strides 2 and 1: both on the cluster
    ref = attractor_map(sc, g, pilot=1)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None,
                                  silence_logs=logging.CRITICAL) as cluster, distributed.Client(cluster) as client:
        other = attractor_map(sc, g, pilot=1, client=client, chunk_points=20)
    np.testing.assert_array_equal(other.dataset.attractor.values, ref.dataset.attractor.values)


def test_sweep_measure_attractor_goes_through_the_sweep_checks_and_scene_defaults():
    sc = scene(1.35).replace(sweep_transient=50.0, sweep_samples=8)
    with pytest.raises(ValueError, match="t_max"):
        pendula.sweep(sc, {"theta0": [0.0]}, "attractor", t_max=1e15)
    with pytest.raises(TypeError, match="samples"):
        pendula.sweep(sc, {"theta0": [0.0]}, "attractor", samples=8.0)
    ds = pendula.sweep(sc, {"theta0": [0.0]}, "attractor")
    assert (ds.attrs["transient"], ds.attrs["samples"], ds.attrs["method"]) == (50.0, 8, "samples")


@pytest.mark.parametrize("kw", [{"max_period": 2.5}, {"tol": True}, {"samples": 8.0}, {"merge_tol": "1e-3"}])
def test_samples_method_arguments_of_the_wrong_kind_are_type_errors(kw):
    with pytest.raises(TypeError, match=next(iter(kw))):
        attractor_map(scene(1.35), {"theta0": [0.0, 1.0]}, transient=20.0, **({"samples": 8} | kw))


def test_max_periods_beyond_the_time_limit_is_refused_before_work():
    with pytest.raises(ValueError, match="max_periods"):
        attractor_map(scene(1.35).replace(drive_frequency=1e-4), grid(3), max_periods=10**6)


def test_thin_chaotic_set_after_the_cascade_is_found_not_left_undecided():
    # A = 1.10: a period-3 cycle and a chaotic set in a few thin bands (few recurrence cells)
    am = attractor_map(scene(1.10), grid(8))
    assert am.undecided == 0
    kinds = sorted((a.kind, a.period) for a in am.attractors)
    assert ("chaotic", 0) in kinds and ("periodic", 3) in kinds
    # a point labelled chaotic has an orbit (SciPy, from the equation alone) that recurs with no period <= 12
    chaotic = next(a.label for a in am.attractors if a.kind == "chaotic")
    i, j = np.argwhere(am.dataset.attractor.values == chaotic)[0]
    th, v = scipy_strobe(1.10, float(am.dataset.theta0[i]), float(am.dataset.v0[j]), 260, rtol=1e-9)
    th, v = th[200:], v[200:]
    for k in range(1, 13):
        d = max(section_dist(th[n], v[n], th[n - k], v[n - k]) for n in range(k, len(th)))
        assert d > 1e-3, f"period {k}"


def test_sweep_figure_of_an_attractor_map_is_drawn(tmp_path):
    pytest.importorskip("matplotlib")
    from pendula.demos.sweeps import plot_sweep
    ds = pendula.sweep(scene(1.35), {"theta0": np.linspace(-3, 3, 5), "v0": np.linspace(-3, 3, 4)}, "attractor",
                       transient=100.0, samples=8)
    assert plot_sweep(ds, tmp_path / "map.png").stat().st_size > 0


def test_ctrl_c_stops_a_long_attractor_map_within_seconds():
    import signal
    import subprocess
    import sys
    import time
    code = ("import pendula, numpy as np\nprint('start', flush=True)\n"
            "sc = pendula.Scene(damping=0.5, drive_amplitude=1.2, drive_frequency=2/3)\n"
            "pendula.attractor_map(sc, {'theta0': np.linspace(-3, 3, 4)}, recurrences=10**6, max_periods=2 * 10**5, "
            "threads=1)\nprint('finished', flush=True)")
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        assert p.stdout.readline().strip() == "start"
        time.sleep(1.5)
        t0 = time.monotonic()
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=30)
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
    assert "finished" not in out and "KeyboardInterrupt" in err, err[-300:]
    assert time.monotonic() - t0 < 10

"""One vocabulary for results and keywords: what each public result is, its
xarray form with CF attributes, the plot functions' ax= and Figure, and the
keywords that mean the same thing everywhere (docs/source/vocabulary.rst)."""

import inspect
import math

import numpy as np
import pytest

import pendula
from pendula import Scene, run_figures


def _cf(ds):
    for name, var in ds.variables.items():
        assert "units" in var.attrs or "flag_values" in var.attrs or name in ds.dims and name in ("event", "flip"), \
            (name, var.attrs)


def test_trajectory_to_xarray_has_cf_units_and_the_same_numbers():
    tr = pendula.simulate(Scene(v0=1.3, t_end=5.0, n_samples=11))
    ds = tr.to_xarray()
    np.testing.assert_array_equal(ds.theta.values, tr.theta)
    np.testing.assert_array_equal(ds.t.values, tr.t)
    assert ds.attrs["method"] == tr.method == "exact"
    _cf(ds)


def test_cord_flip_log_is_a_dict_with_to_xarray():
    tr = pendula.simulate(Scene(cord="flexible", v0=2.2, t_end=20.0, n_samples=5))
    assert isinstance(tr.flips, dict) and isinstance(tr.flips, pendula.trajectory.FlipLog)
    ds = tr.flips.to_xarray()
    assert set(ds.data_vars) == set(tr.flips)
    assert ds.sizes["flip"] == tr.flips["t_leave"].size
    _cf(ds)


def test_spectrum_and_events_to_xarray():
    t = np.arange(256) * 0.05
    sp = pendula.spectrum(t, np.sin(3.0 * t))
    ds = sp.to_xarray()
    np.testing.assert_array_equal(ds.omega.values, sp.omega)
    _cf(ds)
    ev = pendula.find_events(Scene(theta0=1.0), "turning", t_end=20.0)
    de = ev.to_xarray()
    np.testing.assert_array_equal(de.t.values, ev.t)
    _cf(de)


@pytest.mark.parametrize("word,number", [("rising", 1), ("falling", -1), ("both", 0)])
def test_find_events_direction_by_name_equals_by_number(word, number):
    sc = Scene(theta0=1.0)
    a = pendula.find_events(sc, "theta", level=0.0, direction=word, t_end=20.0)
    b = pendula.find_events(sc, "theta", level=0.0, direction=number, t_end=20.0)
    np.testing.assert_array_equal(a.t, b.t)


def test_find_events_bad_direction_is_named():
    with pytest.raises(ValueError, match="direction"):
        pendula.find_events(Scene(theta0=1.0), "turning", direction="up", t_end=5.0)
    with pytest.raises(ValueError, match="direction"):
        pendula.find_events(Scene(theta0=1.0), "turning", direction=True, t_end=5.0)


def test_plot_functions_take_ax_and_return_the_figure(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure
    sc = Scene(v0=1.5, t_end=10.0, n_samples=101)
    runs = [(1.5, pendula.simulate(sc))]
    fig, ax = plt.subplots()
    out = run_figures.phase_portrait(sc, runs, ax=ax)
    assert out is fig and ax.lines
    f2 = run_figures.time_series(sc, runs, tmp_path / "t.png", which="v")
    assert isinstance(f2, Figure) and (tmp_path / "t.png").stat().st_size > 0
    plt.close("all")


def test_every_run_figure_has_path_and_ax():
    names = ["time_series", "phase_portrait", "energy_drift", "orbit_curves", "critical_omega",
             "period_series_figure", "lindstedt_figure", "spectra_figure"]
    for n in names:
        sig = inspect.signature(getattr(run_figures, n))
        assert sig.parameters["path"].default is None, n
        assert sig.parameters["ax"].kind is inspect.Parameter.KEYWORD_ONLY, n


def test_shared_keywords_mean_the_same_everywhere():
    # the tolerance words, the progress switch and the averaging time, wherever a function takes them
    for fn in (pendula.simulate, pendula.sweep, pendula.iv_curve):
        p = inspect.signature(fn).parameters
        assert {"rtol", "atol"} <= set(p), fn.__name__
    for fn in (pendula.sweep, pendula.iv_curve):
        p = inspect.signature(fn).parameters
        assert "transient" in p, fn.__name__


def test_progress_is_tqdm():
    from pendula._progress import Progress
    import io
    buf = io.StringIO()
    import time
    with Progress(3, "work", stream=buf) as bar:
        for _ in range(3):
            time.sleep(0.8)       # work longer than the two seconds before a bar appears
            bar.update()
    assert "work" in buf.getvalue() and "3/3" in buf.getvalue()
    with Progress(3, "quiet", stream=buf, enabled=False) as bar:
        bar.update(3)
    assert "quiet" not in buf.getvalue() and bar.done == 3


def test_orbit_and_gravity_orbit_share_the_names_of_shared_facts():
    import math
    s = Scene(theta0=1.0)
    o, g = pendula.orbit(s.theta0, s.v0, s.eps), pendula.gravity_orbit(s)
    for name in ("regime", "m", "mc", "period", "omega", "theta_max"):
        assert getattr(o, name) == getattr(g, name), name    # the uniform field: the same orbit, to the bit
    assert pendula.gravity_orbit(Scene(v0=2.0)).omega == 0.0 and math.isinf(pendula.gravity_orbit(Scene(v0=2.0)).period)

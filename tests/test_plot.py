"""pendula.plot: one function per result, each drawing what the result holds and returning the Axes.

Each test draws a result the library computed (or, for the basin fractions, a
Dataset built here to the documented contract) and reads back what was drawn:
the data on the lines, the colours per attractor, the labels.
"""

import math
import warnings

import numpy as np
import pytest

import pendula

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
xr = pytest.importorskip("xarray")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.axes import Axes  # noqa: E402

import pendula.plot as pp  # noqa: E402


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def libration():
    return pendula.simulate(pendula.Scene(v0=1.9, t_end=30.0, n_samples=601))


def test_trajectory_draws_theta_of_t_and_returns_the_axes(libration):
    ax = pp.trajectory(libration)
    assert isinstance(ax, Axes)
    x, y = ax.lines[0].get_data()
    assert np.array_equal(x, libration.t) and np.array_equal(y, libration.theta)


def test_trajectory_draws_into_the_axes_given(libration):
    fig, (a, b) = plt.subplots(1, 2)
    assert pp.trajectory(libration, ax=b, which="v") is b
    assert not a.lines and np.array_equal(b.lines[0].get_ydata(), libration.v)


def test_trajectory_refuses_an_unknown_column(libration):
    with pytest.raises(ValueError, match="which"):
        pp.trajectory(libration, which="omega")


def test_phase_folds_theta_and_draws_the_separatrix():
    tr = pendula.simulate(pendula.Scene(v0=2.5, t_end=20.0, n_samples=801))   # a rotation: theta grows
    ax = pp.phase(tr)
    th = ax.lines[0].get_xdata()
    assert np.nanmax(th) < math.pi and np.nanmin(th) >= -math.pi
    sep = [ln for ln in ax.lines if ln.get_label() == "separatrix"][0]
    xs, ys = sep.get_data()
    assert np.allclose(ys, 2 * np.abs(np.cos(xs / 2)))        # eps = 1: v = 2 cos(theta/2)


def test_spectrum_marks_the_fundamental_of_the_exact_orbit():
    T = pendula.orbit(0.0, 1.9).period
    tr = pendula.simulate(pendula.Scene(v0=1.9), np.arange(4096) * (8 * T / 4096))
    ax = pp.spectrum(tr.spectrum(), harmonics=9)
    marks = [ln for ln in ax.lines if ln.get_label().startswith("fundamental")]
    assert marks and math.isclose(marks[0].get_xdata()[0], 2 * math.pi / T, rel_tol=1e-12)
    assert ax.lines[0].get_xdata().max() <= 9 * 2 * math.pi / T


@pytest.fixture(scope="module")
def poincare():
    sc = pendula.Scene(damping=0.5, drive_frequency=2 / 3)
    return pendula.sweep(sc, {"drive_amplitude": np.linspace(1.0, 1.5, 6)}, "poincare", transient=100.0,
                         samples=10)


def test_bifurcation_draws_every_stroboscopic_sample(poincare):
    ax = pp.bifurcation(poincare)
    x, y = ax.lines[0].get_data()
    assert x.size == 6 * 10
    assert np.array_equal(np.sort(y), np.sort(poincare.theta.values.ravel()))


def test_bifurcation_draws_the_lyapunov_exponent_on_a_twin_axis(poincare):
    sc = pendula.Scene(damping=0.5, drive_frequency=2 / 3)
    ly = pendula.sweep(sc, {"drive_amplitude": poincare.drive_amplitude.values}, "lyapunov", transient=100.0,
                       t_max=200.0)
    ax = pp.bifurcation(poincare, lyapunov=ly)
    assert np.array_equal(ax.lyapunov_axes.lines[0].get_ydata(), ly.lyapunov.values)


def test_bifurcation_refuses_a_sweep_without_samples():
    ds = pendula.sweep(pendula.Scene(damping=0.04), {"v0": [1.0, 2.3]}, "final_well")
    with pytest.raises(ValueError, match="poincare"):
        pp.bifurcation(ds)


@pytest.fixture(scope="module")
def attractor_map():
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.35, drive_frequency=2 / 3)
    return pendula.attractor_map(sc, {"theta0": np.linspace(-3, 3, 9), "v0": np.linspace(-3, 3, 9)},
                                 transient=300, samples=16)


def test_basins_one_categorical_colour_per_attractor(attractor_map):
    ax = pp.basins(attractor_map)
    mesh = ax.collections[0]
    n = len(attractor_map.attractors)
    assert mesh.cmap.N == n + 1                                   # undecided + one per attractor
    assert len(ax.get_legend().get_texts()) == n
    # the integer labels land in their own colour bins: no colour bar of a continuous scale
    assert not ax.figure.axes[1:]
    rgba = mesh.cmap(mesh.norm(np.arange(n)))
    assert len({tuple(c) for c in rgba}) == n


def test_basins_draws_the_attractors_on_the_map(attractor_map):
    ax = pp.basins(attractor_map)
    for a, line in zip(attractor_map.attractors, ax.lines):
        assert np.array_equal(line.get_xdata(), a.theta) and np.array_equal(line.get_ydata(), a.v)


def test_basins_takes_the_dataset_of_an_attractor_sweep(attractor_map):
    ax = pp.basins(attractor_map.dataset)
    assert len(ax.get_legend().get_texts()) == len(attractor_map.attractors)


def test_basins_refuses_a_one_axis_map():
    ds = xr.Dataset({"attractor": ("v0", np.zeros(3, dtype=int))}, coords={"v0": [0.0, 1.0, 2.0]})
    with pytest.raises(ValueError, match="two axes"):
        pp.basins(ds)


@pytest.fixture(scope="module")
def iv_loop():
    return pendula.iv_curve(pendula.Scene(damping=0.3), np.linspace(0.0, 1.2, 13), transient=50, t_max=100)


def test_iv_draws_both_directions(iv_loop):
    ax = pp.iv(iv_loop)
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["torque up", "torque down"]
    assert np.array_equal(ax.lines[1].get_ydata(), iv_loop.mean_velocity.sel(direction="down").values,
                          equal_nan=True)


def test_iv_labels_the_steps_when_the_dataset_has_them(iv_loop):
    ds = iv_loop.copy()
    step = np.full(ds.mean_velocity.shape, np.nan)
    step[:, :3] = 0.0          # locked at the lowest torques (the zero-voltage step)
    step[0, 5:8] = 1.0
    ds["step"] = (("direction", "torque"), step)
    ax = pp.iv(ds)
    assert sorted(t.get_text() for t in ax.texts) == ["n = 0", "n = 1"]


def test_iv_without_steps_labels_none(iv_loop):
    assert len(pp.iv(iv_loop).texts) == 0


def test_fractions_stacks_one_area_per_attractor():
    f = np.array([[1.0, 0.0, 0.0], [0.5, 0.5, 0.0], [0.2, 0.3, 0.5], [0.0, 0.4, 0.6]])
    ds = xr.Dataset({"fraction": (("drive_amplitude", "attractor"), f)},
                    coords={"drive_amplitude": [1.0, 1.1, 1.2, 1.3], "attractor": [0, 1, 2],
                            "period": ("attractor", [1, 2, 0])})
    ax = pp.fractions(ds)
    assert len(ax.collections) == 3
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert texts == ["attractor 0: periodic, one drive period", "attractor 1: periodic, two drive periods",
                     "attractor 2: no period found"]
    # the top of the stack is the whole
    top = ax.collections[-1].get_paths()[0].vertices[:, 1].max()
    assert math.isclose(top, 1.0)


def test_fractions_takes_the_dimensions_in_either_order():
    f = np.array([[1.0, 0.5], [0.0, 0.5]])
    ds = xr.Dataset({"fraction": (("attractor", "damping"), f)}, coords={"damping": [0.1, 0.2], "attractor": [0, 1]})
    assert pp.fractions(ds).get_xlabel() == "damping"


def test_fractions_refuses_a_dataset_without_fraction():
    with pytest.raises(ValueError, match="fraction"):
        pp.fractions(xr.Dataset({"x": ("a", [1.0])}))


def test_the_figures_of_pendula_run_still_return_a_figure(libration):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        from pendula import run_figures
        fig = run_figures.time_series(libration.scene, [(1.9, libration)])
    assert isinstance(fig, matplotlib.figure.Figure)


def test_basins_of_a_final_well_map_one_colour_per_well():
    ds = pendula.sweep(pendula.Scene(damping=0.1), {"v0": np.linspace(0, 4, 12), "damping": [0.05, 0.1, 0.2]},
                       "final_well")
    ax = pp.basins(ds)
    wells = np.unique(ds.well.values[np.isfinite(ds.well.values)])
    assert [t.get_text().split(" (")[0] for t in ax.get_legend().get_texts()][:wells.size] == \
        [f"well {w:g}" for w in wells]
    assert ax.collections[0].cmap.N == wells.size + 1


def test_basins_of_many_wells_gets_one_tick_per_well():
    ds = pendula.sweep(pendula.Scene(damping=0.02), {"v0": np.linspace(0, 4, 40), "damping": [0.02, 0.03]},
                       "final_well")
    wells = np.unique(ds.well.values[np.isfinite(ds.well.values)])
    assert wells.size > 8
    ax = pp.basins(ds)
    labels = [t.get_text() for t in ax.basins_colorbar.ax.get_yticklabels()]
    assert labels == ["undecided"] + [f"well {w:g}" for w in wells]
    assert list(ax.basins_colorbar.get_ticks()) == list(range(-1, wells.size))   # at the centres, integers


def test_basins_draws_the_attractors_when_the_axes_are_swapped(attractor_map):
    ax = pp.basins(attractor_map.dataset.transpose("v0", "theta0"))
    for a, line in zip(attractor_map.attractors, ax.lines):
        assert np.array_equal(line.get_xdata(), a.v) and np.array_equal(line.get_ydata(), a.theta)


def test_fractions_legend_names_kind_and_period_in_words():
    f = np.full((2, 3), 1 / 3)
    ds = xr.Dataset({"fraction": (("drive_amplitude", "attractor"), f)},
                    coords={"drive_amplitude": [1.0, 1.1], "attractor": [0, 8, 9],
                            "kind": ("attractor", ["periodic", "chaotic", "periodic"]),
                            "period": ("attractor", [3, 0, 16])})
    texts = [t.get_text() for t in pp.fractions(ds).get_legend().get_texts()]
    assert texts == ["attractor 0: periodic, three drive periods", "attractor 8: chaotic",
                     "attractor 9: periodic, 16 drive periods"]


@pytest.mark.parametrize("n", [1, 10, 11, 20, 21, 60, 61, 150])
def test_categorical_colours_never_repeat(n):
    colours = pp._categorical(n)
    assert len(colours) == n
    assert len({tuple(round(float(x), 6) for x in c[:3]) for c in colours}) == n


def test_fractions_of_21_attractors_have_21_colours():
    f = np.full((2, 21), 1 / 21)
    ds = xr.Dataset({"fraction": (("drive_amplitude", "attractor"), f)},
                    coords={"drive_amplitude": [1.0, 1.1], "attractor": np.arange(21)})
    ax = pp.fractions(ds)
    faces = {tuple(np.round(c.get_facecolor()[0][:3], 6)) for c in ax.collections}
    assert len(faces) == 21


def test_velocity_label_is_in_reduced_units_when_eps_is_1(libration):
    assert pp.phase(libration).get_ylabel() == "v (rad per time unit 1/ω₀, ε = 1)"
    assert pp.trajectory(libration, which="v").get_ylabel() == "v (rad per time unit 1/ω₀, ε = 1)"
    lab = pendula.Pendulum(1.0, amplitude_deg=20).motion().trajectory
    assert pp.phase(lab).get_ylabel() == "v (rad per unit of t)"


# ---------------------------------------------------------------- branches (bifurcation_tree, continue_orbit)

@pytest.fixture(scope="module")
def small_tree():
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2 / 3)
    # the symmetric orbit, its two asymmetric children (pitchfork at 1.00432) and their period-2 children
    # (doubling at 1.06637)
    return pendula.bifurcation_tree(sc, (0.1, 1.9), "drive_amplitude", 1.072, depth=2)


def _branch_lines(ax):
    return [ln for ln in ax.get_lines() if ln.get_label() not in ("_marks", "stable", "unstable")]


def test_branches_draws_stable_solid_and_unstable_dashed(small_tree):
    ax = pp.branches(small_tree)
    lines = _branch_lines(ax)
    brs = small_tree.branches()
    # a solid line per branch with a stable part, a dashed one per branch with an unstable part
    want = sum(bool(np.any(b.stable)) for b in brs) + sum(bool(np.any(~b.stable)) for b in brs)
    assert len(lines) == want == 8          # root: both; children: both; grandchildren: stable only
    solid = [ln for ln in lines if ln.get_linestyle() == "-"]
    dashed = [ln for ln in lines if ln.get_linestyle() == "--"]
    assert len(solid) == 5 and len(dashed) == 3
    # the solid lines hold the stable points: every point of the root's solid line lies before the pitchfork
    # (and the one next to it), every point of its dashed line from the pitchfork on
    pf = small_tree.branch.bifurcations[0].value
    root_solid, root_dashed = solid[0], dashed[0]
    xs = np.asarray(root_solid.get_xdata(), float)
    assert np.nanmax(xs) <= small_tree.branch.values[np.searchsorted(small_tree.branch.values, pf)] + 1e-12
    assert np.nanmin(np.asarray(root_dashed.get_xdata(), float)) >= pf - 0.01
    # a period-2 branch draws both points of its 2-cycle: twice its points, plus the breaks
    grand = small_tree.children[0].children[0].branch
    gl = [ln for ln in solid if ln.get_color() != solid[0].get_color()][0]
    assert np.sum(np.isfinite(np.asarray(gl.get_ydata(), float))) == 2 * int(np.sum(grand.stable))


def test_branches_marks_and_names_the_bifurcations_in_words(small_tree):
    ax = pp.branches(small_tree)
    marks = [ln for ln in ax.get_lines() if ln.get_label() == "_marks"]
    assert len(marks) == sum(len(b.bifurcations) for b in small_tree.branches()) == 3
    words = sorted(t.get_text() for t in ax.texts)
    # each value labelled once: the pitchfork, and the two children's doublings at one amplitude
    assert words == ["period doubling", "pitchfork"]
    assert ax.get_xlabel() == "drive_amplitude"
    assert "theta" in ax.get_ylabel()
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert {"stable", "unstable", "one drive period", "two drive periods"} <= set(legend)


def test_branches_takes_a_branch_and_draws_v():
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2 / 3)
    br = pendula.continue_orbit(sc, (0.1, 1.9), "drive_amplitude", 1.01)
    ax = pp.branches(br, which="v")
    lines = _branch_lines(ax)
    assert sorted(ln.get_linestyle() for ln in lines) == ["-", "--"]
    ys = np.concatenate([np.asarray(ln.get_ydata(), float) for ln in lines])
    assert set(np.round(ys[np.isfinite(ys)], 12)) == set(np.round(br.v, 12))
    assert ax.get_ylabel().startswith("v")


def test_branches_refuses_what_it_cannot_draw():
    with pytest.raises(TypeError, match="tree"):
        pp.branches([1, 2, 3])
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2 / 3)
    br = pendula.continue_orbit(sc, (0.1, 1.9), "drive_amplitude", 1.001)
    with pytest.raises(ValueError, match="which"):
        pp.branches(br, which="energy")


def test_bifurcation_of_an_adiabatic_sweep_draws_both_ways():
    sc = pendula.Scene(damping=0.5, drive_frequency=2 / 3, drive_amplitude=1.02, theta0=-1.3, v0=1.8)
    A = np.array([1.02, 1.03, 1.04])
    ds = pendula.sweep(sc, {"drive_amplitude": A}, "poincare", transient=100.0, samples=4, follow=True)
    ax = pp.bifurcation(ds)
    lines = ax.get_lines()
    assert [ln.get_label() for ln in lines] == ["drive_amplitude up", "drive_amplitude down"]
    for ln, d in zip(lines, ("up", "down")):
        np.testing.assert_array_equal(np.asarray(ln.get_ydata()), ds.theta.sel(direction=d).values.ravel())
    assert lines[0].get_color() != lines[1].get_color()
    assert ax.get_xlabel() == "drive_amplitude"


def _smallest_text_pt(fig):
    """The smallest font size (points) of any visible text in the figure, tick labels included."""
    fig.canvas.draw()
    sizes = [t.get_fontsize() for t in fig.findobj(matplotlib.text.Text) if t.get_visible() and t.get_text()]
    return min(sizes)


def test_text_drawn_by_pendula_plot_is_at_least_9_points(libration, attractor_map, iv_loop):
    """The docs' rule (axis text at least 9 px at the column width) holds at full size only if the
    figures' own text is no smaller than 9 pt: legends, colour-bar ticks and annotations included."""
    from pendula import run_figures
    f = np.array([[1.0, 0.0], [0.5, 0.5]])
    ds = xr.Dataset({"fraction": (("drive_amplitude", "attractor"), f)},
                    coords={"drive_amplitude": [1.0, 1.1], "attractor": [0, 1], "period": ("attractor", [1, 2])})
    figures = {
        "trajectory": pp.trajectory(libration).figure,
        "phase": pp.phase(libration).figure,
        "basins": pp.basins(attractor_map).figure,
        "iv": pp.iv(iv_loop).figure,
        "fractions": pp.fractions(ds).figure,
        "run time series": run_figures.time_series(libration.scene, [(1.9, libration)]),
    }
    small = {name: _smallest_text_pt(fig) for name, fig in figures.items() if _smallest_text_pt(fig) < 9}
    assert not small, f"text under 9 pt: {small}"

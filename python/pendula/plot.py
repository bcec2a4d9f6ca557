"""Figures (matplotlib): what a person would rather look at than read.

One function per result, each taking what the library returns and an optional
``ax`` (a new figure when it is None), and returning the
:class:`matplotlib.axes.Axes` it drew on:

- :func:`trajectory` -- theta(t) (or v(t)) of a :class:`~pendula.Trajectory`;
- :func:`phase` -- its phase portrait, with the separatrix;
- :func:`spectrum` -- a :class:`~pendula.Spectrum`, the fundamental marked;
- :func:`bifurcation` -- a ``poincare`` sweep over one parameter (optionally
  with the Lyapunov exponent of a ``lyapunov`` sweep beside it);
- :func:`branches` -- continued branches (a :class:`~pendula.BranchTree` or a :class:`~pendula.Branch`),
  stable solid, unstable dashed, the bifurcations marked;
- :func:`basins` -- an attractor map, one colour per attractor, the attractors drawn;
- :func:`iv` -- an I-V curve, both directions, the Shapiro steps labelled;
- :func:`fractions` -- basin fractions over a parameter, as stacked areas;
- :func:`flip_map` -- a double pendulum's flip-time map, forbidden and unresolved pixels marked;
- :func:`spherical` -- a spherical pendulum's path from above and from the side, its apsidal angle marked;
- :func:`animate` -- the pendulum swinging, written as a GIF (Pillow's
  writer, nothing else needed) or an MP4 (FFmpeg's writer: ``ffmpeg`` on the PATH).

The figures of ``pendula run`` (:func:`time_series`, :func:`phase_portrait`,
:func:`spectra_figure` ...) take a scene and its runs, return the
:class:`matplotlib.figure.Figure` and, given a ``path``, write it as a PNG.
matplotlib is needed only here (``pip install 'pendula[plot]'``).

Examples
--------
>>> import pendula, pendula.plot
>>> tr = pendula.simulate(pendula.Scene(v0=1.9, t_end=30.0))
>>> ax = pendula.plot.trajectory(tr)
>>> ax.get_xlabel()
't'
"""

from __future__ import annotations

import json
import math
from typing import TYPE_CHECKING, Any

import numpy as np
from . import _checks
from ._plot_common import _ax, _categorical, _dataset, _result, _scene_label, _v_label, _wrapped
# the figures of the junction, the transmon and the double pendulum (pendula.plot.iv, ...)
from ._plot_systems import flip_map, iv, levels, spherical, steps  # noqa: F401
from .animation import animate  # noqa: F401  (pendula.plot.animate: GIF or MP4 through matplotlib's writers)

__all__ = ["trajectory", "phase", "spectrum", "bifurcation", "branches", "basins", "iv", "steps", "fractions",
           "flip_map", "spherical", "levels", "animate"]

if TYPE_CHECKING:   # matplotlib and xarray are optional: named in annotations only
    import matplotlib.axes
    import xarray

    from .dynamics.attractors import AttractorMap
    from .spectrum import Spectrum
    from .trajectory import Trajectory


def trajectory(tr: Trajectory, ax: matplotlib.axes.Axes | None = None, *, which: str = "theta",
               **kwargs: Any) -> matplotlib.axes.Axes:
    """theta(t) (or v(t)) of one trajectory, with the upright angles (odd multiples of pi) dotted.

    Parameters
    ----------
    tr : Trajectory
        What :func:`pendula.simulate` returns.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default: a new figure).
    which : {'theta', 'v', 'energy'}
        The column drawn.
    **kwargs
        Passed to matplotlib's ``Axes.plot`` (``label``, ``color`` ...).

    Returns
    -------
    matplotlib.axes.Axes

    Raises
    ------
    ValueError
        For an unknown `which`.

    Examples
    --------
    >>> import pendula, pendula.plot
    >>> tr = pendula.simulate(pendula.Scene(v0=1.9, damping=0.1, t_end=40.0))
    >>> ax = pendula.plot.trajectory(tr, which="v")
    >>> ax.get_ylabel()
    'v (rad per time unit 1/ω₀, ε = 1)'
    """
    from .trajectory import Trajectory
    _result(tr, "tr", Trajectory, "a pendula.Trajectory (what pendula.simulate returns)")
    _checks.choice(which, "which", ("theta", "v", "energy"))
    ax = _ax(ax)
    kwargs.setdefault("lw", 1.0)
    ax.plot(tr.t, getattr(tr, which), **kwargs)
    ax.set_xlabel("t")
    ax.set_ylabel({"theta": "theta (rad)", "v": _v_label(tr.scene), "energy": "energy"}[which])
    if which == "theta":
        lo, hi = ax.get_ylim()
        for k in range(math.floor(lo / math.pi), math.ceil(hi / math.pi) + 1):
            if k % 2:
                ax.axhline(k * math.pi, color="k", lw=0.5, ls=":")
    ax.set_title(f"{_scene_label(tr.scene)}  [{tr.method}]", fontsize=9)
    ax.grid(True, alpha=0.3)
    return ax


def phase(tr: Trajectory, ax: matplotlib.axes.Axes | None = None, *, separatrix: bool = True,
          **kwargs: Any) -> matplotlib.axes.Axes:
    """The phase portrait v against theta (folded into [-pi, pi)) of one trajectory.

    Parameters
    ----------
    tr : Trajectory
        What :func:`pendula.simulate` returns.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default: a new figure).
    separatrix : bool
        Draw the separatrix v = +-2 sqrt(eps) cos(theta/2) of the rigid pendulum.
    **kwargs
        Passed to matplotlib's ``Axes.plot``.

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import pendula, pendula.plot
    >>> ax = pendula.plot.phase(pendula.simulate(pendula.Scene(v0=2.2, t_end=20.0)))
    >>> [float(x) for x in ax.get_xlim()]
    [-3.141592653589793, 3.141592653589793]
    """
    from .trajectory import Trajectory
    _result(tr, "tr", Trajectory, "a pendula.Trajectory (what pendula.simulate returns)")
    separatrix = _checks.flag(separatrix, "separatrix")
    ax = _ax(ax, figsize=(6, 4.5))
    w, v = _wrapped(tr.theta, tr.v)
    kwargs.setdefault("lw", 1.0)
    ax.plot(w, v, **kwargs)
    if separatrix:
        th = np.linspace(-math.pi, math.pi, 721)
        sep = 2 * math.sqrt(tr.scene.eps) * np.abs(np.cos(th / 2))
        ax.plot(th, sep, "k--", lw=0.7, label="separatrix")
        ax.plot(th, -sep, "k--", lw=0.7)
    ax.set_xlim(-math.pi, math.pi)
    ax.set_xlabel("theta (rad, folded into [-pi, pi))")
    ax.set_ylabel(_v_label(tr.scene))
    ax.set_title(_scene_label(tr.scene), fontsize=9)
    ax.grid(True, alpha=0.3)
    return ax


def spectrum(sp: Spectrum, ax: matplotlib.axes.Axes | None = None, *, harmonics: int = 15,
             **kwargs: Any) -> matplotlib.axes.Axes:
    """A power spectrum on a log scale, up to a number of harmonics of its fundamental.

    Parameters
    ----------
    sp : Spectrum
        What :func:`pendula.spectrum` or :meth:`Trajectory.spectrum <pendula.Trajectory.spectrum>` returns.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default: a new figure).
    harmonics : int
        The frequency axis runs to this many times the fundamental (all of it
        when the spectrum has no fundamental).
    **kwargs
        Passed to matplotlib's ``Axes.semilogy``.

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import numpy as np, pendula, pendula.plot
    >>> T = pendula.orbit(0.0, 1.9).period
    >>> tr = pendula.simulate(pendula.Scene(v0=1.9), np.arange(4096) * (8 * T / 4096))
    >>> ax = pendula.plot.spectrum(tr.spectrum())
    >>> ax.get_yscale()
    'log'
    """
    import warnings

    from .spectrum import Spectrum
    _result(sp, "sp", Spectrum, "a pendula.Spectrum (what pendula.spectrum returns)")
    harmonics = _checks.count(harmonics, "harmonics", 1)
    ax = _ax(ax)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        w0 = sp.fundamental
    sel = sp.omega <= harmonics * w0 if math.isfinite(w0) else np.ones(sp.omega.size, dtype=bool)
    floor = np.finfo(float).tiny
    kwargs.setdefault("lw", 0.9)
    ax.semilogy(sp.omega[sel], np.maximum(sp.power[sel], floor), **kwargs)
    top = float(np.max(sp.power)) if sp.power.size else 1.0
    if math.isfinite(top) and top > 0:
        ax.set_ylim(top * 1e-32, top * 10)
    if math.isfinite(w0):
        ax.axvline(w0, color="C3", lw=0.7, ls=":", label=f"fundamental {w0:.6g}")
        ax.legend(fontsize=9, loc="upper right")
    ax.set_xlabel("omega (rad/s)")
    ax.set_ylabel("power |A|^2")
    ax.grid(True, alpha=0.3)
    return ax


def _one_axis(ds, what: str) -> str:
    dims = [d for d in ds.theta.dims if d not in ("sample", "direction")] if "theta" in ds else list(ds.dims)
    if len(dims) != 1:
        raise ValueError(f"{what} needs a sweep over one parameter, got the axes {dims}")
    return dims[0]


def bifurcation(ds: xarray.Dataset, ax: matplotlib.axes.Axes | None = None, *,
                lyapunov: xarray.Dataset | None = None, **kwargs: Any) -> matplotlib.axes.Axes:
    """The bifurcation diagram: the stroboscopic angles of a ``poincare`` sweep over one parameter.

    Parameters
    ----------
    ds : xarray.Dataset
        What ``pendula.sweep(scene, {name: values}, measure='poincare')``
        returns (``theta`` on the parameter and ``sample``); with ``follow=True``
        (the dimension ``direction``) the way up and the way down are drawn in
        two colours, so that hysteresis shows where they part.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default: a new figure).
    lyapunov : xarray.Dataset, optional
        A ``lyapunov`` sweep over the same parameter: its largest exponent is
        drawn on a second y axis (right), with its zero line.
    **kwargs
        Passed to matplotlib's ``Axes.plot`` for the points.

    Returns
    -------
    matplotlib.axes.Axes
        The diagram's axes (the exponent's twin axes are ``ax.lyapunov_axes``).

    Raises
    ------
    ValueError
        When `ds` is not a poincare sweep over one parameter.

    Examples
    --------
    >>> import numpy as np, pendula, pendula.plot
    >>> sc = pendula.Scene(damping=0.5, drive_frequency=2 / 3)
    >>> ds = pendula.sweep(sc, {"drive_amplitude": np.linspace(1.0, 1.5, 6)}, "poincare",
    ...                    transient=100.0, samples=10)
    >>> pendula.plot.bifurcation(ds).get_xlabel()
    'drive_amplitude'
    """
    _dataset(ds, "ds")
    if lyapunov is not None:
        _dataset(lyapunov, "lyapunov")
    if "theta" not in ds or "sample" not in ds.theta.dims:
        raise ValueError("bifurcation needs a 'poincare' sweep (theta on the dimensions (parameter, sample))")
    p = _one_axis(ds, "bifurcation")
    ax = _ax(ax, figsize=(7, 4.5))
    kwargs.setdefault("ms", 1.0)
    kwargs.setdefault("alpha", 0.6)
    if "direction" in ds.theta.dims:
        # an adiabatic sweep (follow=True): the way up and the way down, apart where they differ (hysteresis)
        for d, colour, mark in zip(ds["direction"].values, ("C0", "C3"), (".", "x")):
            th = ds.theta.sel(direction=d).transpose(p, "sample").values
            kw = dict(kwargs, color=kwargs.get("color", colour))
            ax.plot(np.repeat(ds[p].values, th.shape[1]), th.ravel(), mark, label=f"{p} {d}", **kw)
        ax.legend(fontsize=9, loc="best", markerscale=6)
    else:
        th = ds.theta.transpose(p, "sample").values
        kwargs.setdefault("color", "k")
        ax.plot(np.repeat(ds[p].values, th.shape[1]), th.ravel(), ".", **kwargs)
    ax.set_xlabel(p)
    ax.set_ylabel("theta at t = 2 pi n / Omega (rad)")
    ax.set_ylim(-math.pi, math.pi)
    if lyapunov is not None:
        q = _one_axis(lyapunov, "bifurcation(lyapunov=)")
        tw = ax.twinx()
        tw.plot(lyapunov[q].values, lyapunov["lyapunov"].values, color="C3", lw=1.0)
        tw.axhline(0.0, color="C3", lw=0.6, ls=":")
        tw.set_ylabel("largest Lyapunov exponent", color="C3")
        tw.tick_params(axis="y", colors="C3")
        ax.lyapunov_axes = tw
    ax.grid(True, alpha=0.3)
    return ax


#: markers of the bifurcations on a branch diagram, and their names in words
_BIFURCATION_MARKS = {"pitchfork": ("s", "pitchfork"), "period-doubling": ("o", "period doubling"),
                      "fold": ("^", "fold"), "neimark-sacker": ("D", "Neimark-Sacker"),
                      "homoclinic": ("X", "homoclinic"), "saddle-node": ("v", "saddle-node")}


def _branch_lines(b, column: int, stable: bool):
    """x, y of one branch's k-cycle points where its stability is ``stable``: each point of the cycle
    one run, joined across the points next to a change of stability, broken (NaN) at a change of
    segment and where the angle wraps."""
    keep = b.stable if stable else ~b.stable
    near = keep.copy()
    near[1:] |= keep[:-1]
    near[:-1] |= keep[1:]
    xs, ys = [], []
    for j in range(b.cycle.shape[1]):
        y = np.where(near, b.cycle[:, j, column], np.nan)
        x = np.where(near, np.asarray(b.values, dtype=float), np.nan)
        cut = np.zeros(len(y), dtype=bool)
        cut[1:] = (np.diff(b.segment) != 0) | ((np.abs(np.diff(y)) > np.pi) if column == 0 else False)
        idx = np.nonzero(cut)[0]
        xs.append(np.insert(x, idx, np.nan))
        ys.append(np.insert(y, idx, np.nan))
        xs.append([np.nan])
        ys.append([np.nan])
    return np.concatenate(xs), np.concatenate(ys)


def branches(tree: Any, ax: matplotlib.axes.Axes | None = None, *, which: str = "theta",
             **kwargs: Any) -> matplotlib.axes.Axes:
    """A bifurcation diagram of continued branches: stable solid, unstable dashed, the bifurcations marked.

    Every point of each branch's k-cycle is drawn against the parameter (a
    period-4 branch draws four curves), one colour per period; the
    bifurcations are marked and labelled in words (``pitchfork``, ``period
    doubling``, ``fold`` ...), a kind once where its points crowd together (within 20 % of
    the parameter's span).

    Parameters
    ----------
    tree : BranchTree or Branch
        What :func:`pendula.bifurcation_tree` or :func:`pendula.continue_orbit` returns.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default: a new figure).
    which : {'theta', 'v'}, optional
        The coordinate of the section points drawn (default the angle).
    **kwargs
        Passed to matplotlib's ``Axes.plot`` for the branches.

    Returns
    -------
    matplotlib.axes.Axes
        The diagram's axes: per branch one solid line (its stable part) and one dashed (its
        unstable part), where it has one.

    Raises
    ------
    TypeError
        When ``tree`` is neither a BranchTree nor a Branch.
    ValueError
        When ``which`` is neither 'theta' nor 'v'.

    Examples
    --------
    >>> import pendula, pendula.plot
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2/3)
    >>> tree = pendula.bifurcation_tree(sc, (0.1, 1.9), "drive_amplitude", 1.07, depth=1)
    >>> ax = pendula.plot.branches(tree)
    >>> ax.get_xlabel(), sorted({line.get_linestyle() for line in ax.get_lines() if line.get_label() != "_marks"})
    ('drive_amplitude', ['-', '--'])
    """
    from .dynamics.branch_tree import BranchTree
    from .dynamics.branches import Branch
    _result(tree, "tree", (BranchTree, Branch), "a BranchTree or a Branch")
    if which not in ("theta", "v"):
        raise ValueError(f"which must be 'theta' or 'v', got {which!r:.40}")
    col = 0 if which == "theta" else 1
    brs = tree.branches() if isinstance(tree, BranchTree) else [tree]
    ax = _ax(ax, figsize=(7, 4.5))
    periods = sorted({int(p) for b in brs for p in np.unique(b.period)})
    colours = dict(zip(periods, _categorical(len(periods))))
    named: set = set()
    kwargs.setdefault("lw", 1.2)
    for b in brs:
        if not len(b):
            continue
        k = int(b.period[0])
        for stable, style in ((True, "-"), (False, "--")):
            if not np.any(b.stable if stable else ~b.stable):
                continue
            x, y = _branch_lines(b, col, stable)
            label = _period_words(k) if k not in named else None
            named.add(k)
            ax.plot(x, y, ls=style, color=colours.get(k, "k"), label=label or "_nolegend_", **kwargs)
    # each kind named once per place: not again within 20 % of the parameter's span (a cascade's
    # doublings crowd together; their marks stay)
    span = max((float(np.ptp(b.values)) for b in brs if len(b)), default=0.0)
    labelled: list = []
    for b in brs:
        for bif in b.bifurcations:
            marker, word = _BIFURCATION_MARKS.get(bif.kind, ("x", bif.kind))
            y = bif.theta if col == 0 else bif.v
            ax.plot([bif.value], [y], marker, color="k", ms=5, mfc="white", label="_marks")
            if not any(kind == bif.kind and abs(value - bif.value) <= 0.2 * span for kind, value in labelled):
                labelled.append((bif.kind, bif.value))
                ax.annotate(word, (bif.value, y), xytext=(4, 6), textcoords="offset points", fontsize=9)
    ax.set_xlabel(brs[0].param)
    ax.set_ylabel("theta on the section (rad)" if col == 0 else "v on the section (rad per time unit)")
    ax.margins(y=0.1)            # room for the names above the top branch
    ax.plot([], [], "k-", label="stable")
    ax.plot([], [], "k--", label="unstable")
    ax.legend(fontsize=9, loc="best")
    ax.grid(True, alpha=0.3)
    return ax


def _categories(am) -> tuple[Any, str, list[dict]]:
    """(dataset, label variable, categories) of an AttractorMap, its Dataset or a final-well map.

    Each category: value (the label in the map), name, fraction, and for attractors
    kind, theta and v (the attractor on the stroboscopic section).
    """
    if hasattr(am, "dataset") and hasattr(am, "attractors"):
        cats = [{"value": a.label, "name": _attractor_name(a.label, a.kind, a.period), "fraction": a.fraction,
                 "kind": a.kind, "theta": np.asarray(a.theta), "v": np.asarray(a.v)} for a in am.attractors]
        return am.dataset, "attractor", cats
    if "attractor" in am:
        cats = [{"value": a["label"], "name": _attractor_name(a["label"], a["kind"], a["period"]),
                 "fraction": a["fraction"], "kind": a["kind"], "theta": np.asarray(a["theta"]),
                 "v": np.asarray(a["v"])} for a in json.loads(am.attrs.get("attractors", "[]"))]
        if not cats:   # a map without its attractors' record: one category per label found
            vals = np.unique(am["attractor"].values)
            cats = [{"value": int(k), "name": f"attractor {int(k)}",
                     "fraction": float(np.mean(am["attractor"].values == k))} for k in vals[vals >= 0]]
        return am, "attractor", cats
    if "well" in am:
        w = am["well"].values
        vals = np.unique(w[np.isfinite(w)])
        return am, "well", [{"value": k, "name": f"well {k:g}", "fraction": float(np.mean(w == k))} for k in vals]
    raise ValueError("basins needs an AttractorMap, or a Dataset with the variable 'attractor' or 'well'")


#: small numbers in words, for the legends ("periodic, two drive periods")
_NUMBER_WORDS = ("no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten",
                 "eleven", "twelve")


def _period_words(period) -> str:
    """'one drive period', 'two drive periods', ... '16 drive periods'."""
    k = int(period)
    word = _NUMBER_WORDS[k] if 0 <= k < len(_NUMBER_WORDS) else str(k)
    return f"{word} drive period{'' if k == 1 else 's'}"


def _attractor_name(label: int, kind: str | None, period) -> str:
    """'3: periodic, two drive periods', '5: chaotic', '6: quasi-periodic'; without a kind, a period of 0 is
    'no period found'."""
    if kind in ("chaotic", "quasi-periodic"):
        return f"{label}: {kind}"
    if kind is None and not int(period):
        return f"{label}: no period found"
    return f"{label}: periodic, {_period_words(period)}"


def basins(am: AttractorMap | xarray.Dataset, ax: matplotlib.axes.Axes | None = None, *,
           draw_attractors: bool = True) -> matplotlib.axes.Axes:
    """A basin map: one colour per attractor (or final well), undecided points grey, the attractors drawn on it.

    Parameters
    ----------
    am : AttractorMap or xarray.Dataset
        What :func:`pendula.attractor_map` returns (or its ``dataset``, or a
        ``sweep(..., measure='attractor')``), or a ``final_well`` sweep (one
        colour per well), over two axes.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default: a new figure).
    draw_attractors : bool
        Mark each attractor's points on the stroboscopic section (white-edged
        markers in its colour) when the axes are the initial state
        (``theta0`` and ``v0``, in either order).

    Returns
    -------
    matplotlib.axes.Axes
        With a legend naming each attractor (or well) and its share of the grid;
        beyond 8 of them, a colour bar with one tick and name per colour
        (``ax.basins_colorbar``).

    Raises
    ------
    ValueError
        When the map does not have two axes, or is not a map of attractors or wells.

    Examples
    --------
    >>> import numpy as np, pendula, pendula.plot
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.35, drive_frequency=2 / 3)
    >>> am = pendula.attractor_map(sc, {"theta0": np.linspace(-3, 3, 7), "v0": np.linspace(-3, 3, 7)},
    ...                            transient=300, samples=16)
    >>> ax = pendula.plot.basins(am)
    >>> len(ax.get_legend().get_texts()) == len(am.attractors)
    True
    """
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from matplotlib.patches import Patch

    from .dynamics.attractors import AttractorMap
    if not isinstance(am, AttractorMap):
        _dataset(am, "am")
    draw_attractors = _checks.flag(draw_attractors, "draw_attractors")
    ds, var, cats = _categories(am)
    lab = ds[var]
    if lab.ndim != 2:
        raise ValueError(f"basins needs a map over two axes, got {lab.dims}")
    xd, yd = lab.dims
    ax = _ax(ax, figsize=(6.5, 5))
    n = len(cats)
    colours = _categorical(n)
    grey = (0.85, 0.85, 0.85)
    # each point's category index, -1 where undecided (a label outside the categories, or NaN)
    values = np.array([c["value"] for c in cats], dtype=float)
    z = lab.transpose(yd, xd).values.astype(float)
    idx = np.full(z.shape, -1)
    for i, v in enumerate(values):
        idx[z == v] = i
    cmap = ListedColormap([grey] + colours)
    norm = BoundaryNorm(np.arange(-1.5, n + 0.5), cmap.N)
    ax.pcolormesh(ds[xd].values, ds[yd].values, idx, cmap=cmap, norm=norm, shading="nearest", rasterized=True)
    handles = [Patch(color=colours[i], label=f"{c['name']} ({c['fraction']:.0%})") for i, c in enumerate(cats)]
    if draw_attractors and {xd, yd} == {"theta0", "v0"}:
        for i, c in enumerate(cats):
            if "theta" in c:
                pts = slice(None) if c["kind"] == "periodic" else slice(None, 200)
                x, y = (c["theta"][pts], c["v"][pts]) if xd == "theta0" else (c["v"][pts], c["theta"][pts])
                ax.plot(x, y, "o", ms=6 if c["kind"] == "periodic" else 2,
                        mfc=colours[i], mec="white", mew=1.2, ls="none")
    if np.any(idx < 0):
        handles.append(Patch(color=grey, label="undecided"))
    if n <= 8:
        ax.legend(handles=handles, fontsize=9, loc="upper right", framealpha=0.85)
    else:   # many wells: a colour bar of the categories, one tick (and name) per colour
        from matplotlib.cm import ScalarMappable
        bar = ax.figure.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=ax, ticks=np.arange(-1, n))
        bar.ax.set_yticklabels(["undecided"] + [c["name"] for c in cats], fontsize=9)
        ax.basins_colorbar = bar
    ax.set_xlabel(xd)
    ax.set_ylabel(yd)
    return ax


def fractions(ds: xarray.Dataset, ax: matplotlib.axes.Axes | None = None) -> matplotlib.axes.Axes:
    """Basin fractions over a parameter: stacked areas, one colour per attractor.

    Parameters
    ----------
    ds : xarray.Dataset
        A variable ``fraction`` on the dimensions (parameter, ``attractor``):
        the share of initial states ending on each attractor at each value of
        the parameter.  The attractor's name comes from the coordinates on
        ``attractor`` (``kind`` and ``period`` when present, in words: "attractor 1:
        periodic, two drive periods", else its label).
    ax : matplotlib.axes.Axes, optional
        Where to draw (default: a new figure).

    Returns
    -------
    matplotlib.axes.Axes

    Raises
    ------
    ValueError
        When `ds` has no ``fraction`` over a parameter and ``attractor``.

    Examples
    --------
    >>> import numpy as np, xarray as xr, pendula.plot
    >>> f = np.array([[1.0, 0.0], [0.6, 0.4], [0.2, 0.8]])
    >>> ds = xr.Dataset({"fraction": (("drive_amplitude", "attractor"), f)},
    ...                 coords={"drive_amplitude": [1.0, 1.1, 1.2], "attractor": [0, 1]})
    >>> ax = pendula.plot.fractions(ds)
    >>> [t.get_text() for t in ax.get_legend().get_texts()]
    ['attractor 0', 'attractor 1']
    """
    _dataset(ds, "ds")
    if "fraction" not in ds or "attractor" not in ds.fraction.dims or ds.fraction.ndim != 2:
        raise ValueError("fractions needs a variable 'fraction' on the dimensions (parameter, 'attractor')")
    p = next(d for d in ds.fraction.dims if d != "attractor")
    f = np.nan_to_num(ds.fraction.transpose("attractor", p).values)
    ax = _ax(ax)
    labels = []
    coord = {name: ds.coords[name].values for name in ("kind", "period")
             if name in ds.coords and ds.coords[name].dims == ("attractor",)}
    for i, a in enumerate(ds["attractor"].values):
        if coord:   # named by kind and period in words: 'attractor 3: periodic, two drive periods'
            kind = str(coord["kind"][i]) if "kind" in coord else None
            period = coord["period"][i] if "period" in coord else 0
            if kind == "periodic" and "period" not in coord:
                labels.append(f"attractor {a}: periodic")
            else:
                labels.append("attractor " + _attractor_name(a, kind, period))
        else:
            labels.append(f"attractor {a}")
    ax.stackplot(ds[p].values, f, labels=labels, colors=_categorical(f.shape[0]), alpha=0.9)
    ax.set_xlim(float(ds[p].values.min()), float(ds[p].values.max()))
    ax.set_ylim(0.0, 1.0)
    ax.set_xlabel(p)
    ax.set_ylabel("fraction of initial states")
    ax.legend(fontsize=9, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return ax

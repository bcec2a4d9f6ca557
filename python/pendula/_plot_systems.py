"""The figures of the systems beside the one pendulum: a junction's I-V curve and step map, a
transmon's levels, a double pendulum's flip-time map, a spherical pendulum's path (public as
:func:`pendula.plot.iv`, :func:`pendula.plot.steps`, :func:`pendula.plot.levels`, :func:`pendula.plot.flip_map`
and :func:`pendula.plot.spherical`)."""

from __future__ import annotations

from fractions import Fraction
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from . import _checks
from ._plot_common import _ax, _categorical, _dataset, _plt, _result

if TYPE_CHECKING:   # matplotlib and xarray are optional: named in annotations only
    import matplotlib.axes
    import xarray

    from .systems.double_motion import FlipMap
    from .systems.spherical import SphericalOrbit


def iv(ds: xarray.Dataset, ax: matplotlib.axes.Axes | None = None) -> matplotlib.axes.Axes:
    """An I-V curve: mean velocity against torque, or volts against amperes, up and down, the steps labelled.

    Parameters
    ----------
    ds : xarray.Dataset
        What :func:`pendula.iv_curve` returns (``mean_velocity`` on
        ``(direction, torque)``, drawn in reduced units) or
        :meth:`pendula.Junction.iv_curve` (``voltage`` on ``(direction,
        current)``, drawn in µV against µA).  When it has a variable
        ``step`` (the Shapiro step number where the junction is locked, NaN
        elsewhere), each step is labelled n = ... at its plateau.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default: a new figure).

    Returns
    -------
    matplotlib.axes.Axes

    Raises
    ------
    ValueError
        When `ds` has neither ``mean_velocity`` over ``torque`` nor
        ``voltage`` over ``current``.

    Examples
    --------
    >>> import numpy as np, pendula, pendula.plot
    >>> r = pendula.iv_curve(pendula.Scene(damping=0.3), np.linspace(0, 1.2, 7), transient=50, t_max=100)
    >>> ax = pendula.plot.iv(r)
    >>> [t.get_text() for t in ax.get_legend().get_texts()]
    ['torque up', 'torque down']

    A junction's curve in the laboratory's units:

    >>> j = pendula.Junction(1e-6, 18.0, 1e-12)
    >>> ax = pendula.plot.iv(j.iv_curve(np.linspace(0, 2e-6, 5)))
    >>> ax.get_xlabel(), ax.get_ylabel()
    ('bias current I (µA)', 'dc voltage V (µV)')
    """
    _dataset(ds, "ds")
    if "voltage" in ds and "current" in ds.voltage.dims:
        y, x, ys, xs = "voltage", "current", 1e6, 1e6
        xlabel, ylabel, what = "bias current I (µA)", "dc voltage V (µV)", "current"
    elif "mean_velocity" in ds and "torque" in ds.mean_velocity.dims:
        y, x, ys, xs = "mean_velocity", "torque", 1.0, 1.0
        xlabel, ylabel, what = "torque tau (bias current)", "<v> (voltage)", "torque"
    else:
        raise ValueError("iv needs an I-V curve: 'mean_velocity' over 'torque' (pendula.iv_curve) or 'voltage' "
                         "over 'current' (pendula.Junction.iv_curve)")
    ax = _ax(ax)
    dirs = list(ds["direction"].values) if "direction" in ds[y].dims else [None]
    style = {"up": ("C0", "-", ">", f"{what} up"), "down": ("C1", "--", "<", f"{what} down")}
    xv = ds[x].values * xs
    for d in dirs:
        mv = ds[y] if d is None else ds[y].sel(direction=d)
        c, ls, mk, lab = style.get(str(d), ("C0", "-", ".", "mean velocity"))
        ax.plot(xv, mv.values * ys, color=c, ls=ls, marker=mk, ms=3, lw=1.0, label=lab)
    if "step" in ds:
        _label_steps(ax, ds, dirs, x, y, xs, ys)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=9, loc="upper left")
    return ax


def _label_steps(ax, ds, dirs, x="torque", y="mean_velocity", xs=1.0, ys=1.0) -> None:
    """n = k at the middle of each plateau of the variable 'step' (one label per step and height)."""
    done = set()
    tau = ds[x].values * xs
    for d in dirs:
        st = ds.step if d is None or "direction" not in ds.step.dims else ds.step.sel(direction=d)
        mv = ds[y] if d is None else ds[y].sel(direction=d)
        st, mv = st.values, mv.values * ys
        for k in np.unique(st[np.isfinite(st)]):
            where = np.flatnonzero(st == k)
            if k in done or where.size == 0:
                continue
            done.add(k)
            mid = where[where.size // 2]
            ax.annotate(f"n = {Fraction(float(k)).limit_denominator(8)}", (tau[mid], mv[mid]), xytext=(0, 6),
                        textcoords="offset points", ha="center", fontsize=9)


def steps(ds: xarray.Dataset, ax: matplotlib.axes.Axes | None = None, *, max_order: int = 8
          ) -> matplotlib.axes.Axes:
    """A step map: the Shapiro step over (dc bias, rf drive), each plateau coloured, its edges drawn.

    Parameters
    ----------
    ds : xarray.Dataset
        What :meth:`pendula.Junction.sweep` returns over ``bias`` and one of
        ``rf_current`` (drawn in µA) or ``rf_power`` (dBm): ``step`` (NaN
        where not locked) and ``status``.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default: a new figure).
    max_order : int
        Steps n = 0 ... max_order get a colour each (higher and fractional
        steps one more, unlocked points white).

    Returns
    -------
    matplotlib.axes.Axes

    Raises
    ------
    ValueError
        When `ds` is not a sweep over ``bias`` and ``rf_current`` or
        ``rf_power`` with a ``step``.

    Examples
    --------
    >>> import numpy as np, pendula, pendula.plot
    >>> j = pendula.Junction(1e-6, 18.0, 1e-12)
    >>> f = j.plasma_frequency / (2 * 3.141592653589793)
    >>> m = j.sweep({"bias": np.linspace(0, 1.5e-6, 4), "rf_current": [0.5e-6, 1e-6]}, rf_frequency=f)
    >>> ax = pendula.plot.steps(m)
    >>> ax.get_xlabel()
    'dc bias current I (µA)'
    """
    _dataset(ds, "ds")
    max_order = _checks.count(max_order, "max_order", 0, 100)
    rf = "rf_current" if "rf_current" in ds.dims else "rf_power" if "rf_power" in ds.dims else None
    if "step" not in ds or "bias" not in ds.dims or rf is None:
        raise ValueError("steps needs a step map: 'step' over 'bias' and 'rf_current' or 'rf_power' "
                         "(pendula.Junction.sweep)")
    plt = _plt()
    from matplotlib.colors import BoundaryNorm, ListedColormap
    ax = _ax(ax)
    st = ds.step.transpose(rf, "bias").values
    locked = np.isfinite(st)
    whole = locked & (st == np.round(st)) & (st >= 0) & (st <= max_order)
    code = np.full(st.shape, np.nan)
    code[whole] = st[whole]
    code[locked & ~whole] = max_order + 1
    colours = [plt.get_cmap("tab10")(k % 10) for k in range(max_order + 1)] + [(0.5, 0.5, 0.5, 1.0)]
    cmap = ListedColormap(colours).with_extremes(bad="white")
    norm = BoundaryNorm(np.arange(-0.5, max_order + 1.6), cmap.N)
    xb = ds["bias"].values * 1e6
    yr = ds[rf].values * (1e6 if rf == "rf_current" else 1.0)
    mesh = ax.pcolormesh(xb, yr, np.ma.masked_invalid(code), cmap=cmap, norm=norm, shading="nearest")
    # the plateaus' edges: where the step changes between neighbouring biases
    if xb.size > 1:
        change = np.zeros(code.shape, bool)
        change[:, 1:] = ~((code[:, 1:] == code[:, :-1]) | (np.isnan(code[:, 1:]) & np.isnan(code[:, :-1])))
        xm = 0.5 * (xb[1:] + xb[:-1])
        for i in range(code.shape[0]):
            where = np.flatnonzero(change[i, 1:])
            if where.size:
                ax.plot(xm[where], np.full(where.size, yr[i]), "|", color="k", ms=4, mew=0.6)
    bar = ax.figure.colorbar(mesh, ax=ax, ticks=np.arange(max_order + 2))
    bar.ax.set_yticklabels([f"{k}" for k in range(max_order + 1)] + ["other"], fontsize=9)
    bar.set_label("Shapiro step n (white: not locked)", fontsize=9)
    ax.set_xlabel("dc bias current I (µA)")
    ax.set_ylabel("rf current I_rf (µA)" if rf == "rf_current" else "rf power (dBm)")
    return ax


def levels(transmon, ax: matplotlib.axes.Axes | None = None, *, count: int = 5,
           n_g: Any = None, relative: bool = True) -> matplotlib.axes.Axes:
    """A transmon's levels against the offset charge (Koch et al. 2007, Fig. 2).

    Parameters
    ----------
    transmon : pendula.Transmon
        The quantum pendulum.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default: a new figure).
    count : int, optional
        How many levels (default 5).
    n_g : array_like, optional
        The offset charges (default 401 points over [-1, 1]).
    relative : bool, optional
        Energies from the bottom of the ground band in units of the 0-1
        transition at n_g = 1/2, as Koch et al. draw them (default); else in
        the units of E_J, E_C.

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import pendula, pendula.plot
    >>> ax = pendula.plot.levels(pendula.Transmon(5.0, 1.0), count=3)
    >>> len(ax.get_lines()), ax.get_xlabel()
    (3, 'n_g')
    """
    ng = np.linspace(-1.0, 1.0, 401) if n_g is None else np.asarray(n_g, dtype=float)
    e = transmon.levels(count, ng)
    ylabel = "E_m"
    if relative:
        e = (e - e[:, 0].min()) / float(transmon.transition(1, 0.5))
        ylabel = "E_m / E_01 (n_g = 1/2)"
    ax = _ax(ax)
    colours = _categorical(e.shape[1])
    for m in range(e.shape[1]):
        ax.plot(ng, e[:, m], color=colours[m], label=f"m = {m}")
    ax.set_xlabel("n_g")
    ax.set_ylabel(ylabel)
    ax.set_title(f"E_J / E_C = {transmon.E_J / transmon.E_C:g}")
    return ax


def flip_map(fm: FlipMap | xarray.Dataset, ax: matplotlib.axes.Axes | None = None, *,
             colorbar: bool = True) -> matplotlib.axes.Axes:
    """A double pendulum's flip-time map: log10 of the flip time over the initial angles.

    Parameters
    ----------
    fm : FlipMap or xarray.Dataset
        What :meth:`pendula.DoublePendulum.flip_map` returns, or the Dataset
        of :meth:`pendula.DoublePendulum.flip_sweep`.
    ax : matplotlib.axes.Axes, optional
        Where to draw (default: a new figure).
    colorbar : bool
        Draw a colour bar of log10(flip time) (default True).

    Returns
    -------
    matplotlib.axes.Axes
        The map: the energy-forbidden region white, the pixels with no flip
        by t_max black, the unresolved pixels (their answer moved when the
        tolerance was tightened tenfold) grey.

    Examples
    --------
    >>> import numpy as np, pendula, pendula.plot
    >>> th = np.linspace(-3, 3, 9)
    >>> ax = pendula.plot.flip_map(pendula.DoublePendulum().flip_map(th, th, t_max=10.0))
    >>> ax.get_xlabel()
    'theta1 (rad)'
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    from .systems.double_motion import FlipMap
    if hasattr(fm, "data_vars") and {"time", "check", "forbidden", "unresolved"} <= set(fm.data_vars):
        # a flip_sweep's Dataset (loaded here: a figure holds the whole map anyway)
        fm = FlipMap(fm.theta1.values, fm.theta2.values, fm.time.values, fm.check.values,
                     fm.forbidden.values.astype(bool), fm.unresolved.values.astype(bool), float(fm.attrs["t_max"]),
                     float(fm.attrs["rtol"]), float(fm.attrs["agree"]))
    fm = _result(fm, "fm", FlipMap, "a FlipMap (DoublePendulum.flip_map) or a DoublePendulum.flip_sweep Dataset")
    colorbar = _checks.flag(colorbar, "colorbar")
    ax = _ax(ax, figsize=(6.0, 5.0))
    with np.errstate(divide="ignore"):
        z = np.log10(np.where(np.isfinite(fm.time), fm.time, np.nan)).T
    x, y = fm.theta1, fm.theta2
    # the pixels with no answer first: black (no flip by t_max), white (forbidden), grey (unresolved)
    cls = np.where(fm.forbidden, 1.0, np.where(np.isinf(fm.time), 0.0, np.nan)).T
    ax.pcolormesh(x, y, cls, cmap=ListedColormap(["black", "white"]), vmin=0, vmax=1, shading="nearest",
                  rasterized=True)
    mesh = ax.pcolormesh(x, y, np.where(fm.unresolved.T, np.nan, z), cmap="viridis", shading="nearest",
                         rasterized=True)
    grey = np.where(fm.unresolved.T, 1.0, np.nan)
    ax.pcolormesh(x, y, grey, cmap=ListedColormap([(0.6, 0.6, 0.6)]), shading="nearest", rasterized=True)
    if colorbar:
        bar = ax.figure.colorbar(mesh, ax=ax)
        bar.set_label("log10 flip time", fontsize=10)
    ax.legend(handles=[Patch(facecolor="white", edgecolor="k", label="cannot flip (energy)"),
                       Patch(color="black", label=f"no flip by t = {fm.t_max:g}"),
                       Patch(color=(0.6, 0.6, 0.6), label="unresolved")],
              fontsize=9, loc="lower left", framealpha=0.85)
    ax.set_xlabel("theta1 (rad)")
    ax.set_ylabel("theta2 (rad)")
    ax.set_aspect("equal")
    return ax


def _lowest_time(orbit) -> float:
    """A time of the orbit's lowest point in [0, period]: the least theta^2 of a sampled period, then
    bisection on the sign of its rate theta theta' (from - to +), to the last bit of the time."""
    t = np.linspace(0.0, orbit.period, 257)
    k = int(np.argmin(orbit.path(t).theta ** 2))
    lo, hi = t[max(k - 1, 0)], t[min(k + 1, t.size - 1)]
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if not lo < mid < hi:
            break
        p = orbit.path([mid])
        if p.theta[0] * p.theta_dot[0] < 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def spherical(orbit: SphericalOrbit, axs: Sequence[matplotlib.axes.Axes] | None = None, *,
              periods: float = 3.0, samples: int = 1500) -> tuple[matplotlib.axes.Axes, matplotlib.axes.Axes]:
    """A spherical pendulum's path in two views, its apsidal angle marked.

    Parameters
    ----------
    orbit : SphericalOrbit
        What :func:`pendula.spherical_orbit` returns.
    axs : pair of matplotlib.axes.Axes, optional
        Where to draw the view from above and the view from the side
        (default: a new figure with the two side by side).
    periods : float, optional
        How many polar periods of the path to draw (default 3), > 0.
    samples : int, optional
        Points of the exact path drawn (default 1500), >= 2.

    Returns
    -------
    tuple of matplotlib.axes.Axes
        The view from above (x, y: the rosette, with the rays to a lowest
        point and to the next highest point and the arc of the apsidal angle
        between them) and the view from the side (x, z, with the two turning
        heights dashed).  Lengths in units of the rod's.

    Raises
    ------
    TypeError
        For an orbit that is not a SphericalOrbit.
    ValueError
        Naming periods or samples out of range.

    See Also
    --------
    pendula.spherical_orbit : the orbit, exactly.

    Examples
    --------
    >>> import pendula, pendula.plot
    >>> o = pendula.spherical_orbit(0.6, 0.0, 1.0)
    >>> top, side = pendula.plot.spherical(o)
    >>> top.get_xlabel(), side.get_ylabel()
    ('x / l', 'z / l')
    """
    from .systems.spherical import SphericalOrbit
    orbit = _result(orbit, "orbit", SphericalOrbit, "a SphericalOrbit (pendula.spherical_orbit)")
    periods = _checks.real(periods, "periods", 0.0, lo_open=True)
    samples = _checks.count(samples, "samples", 2)
    if axs is None:
        fig, axs = _plt().subplots(1, 2, figsize=(8.0, 4.0), layout="constrained")
    else:
        if not isinstance(axs, (list, tuple, np.ndarray)) or len(axs) != 2:
            raise TypeError("axs must be a pair of matplotlib Axes (above, side) or None")
        axs = [_ax(a) for a in axs]
    top, side = axs
    x, y, z = orbit.path(np.linspace(0.0, periods * orbit.period, samples)).position()
    top.plot(x, y, lw=0.8, color="C0")
    top.plot([0.0], [0.0], "k+", ms=8)
    # a lowest point and the next highest one, half a polar period on (theta's turning points)
    t_low = _lowest_time(orbit)
    (px, qx), (py, qy), _ = orbit.path([t_low, t_low + 0.5 * orbit.period]).position()
    top.plot([0.0, px], [0.0, py], color="C1", lw=1.5, label="to a lowest point")
    top.plot([0.0, qx], [0.0, qy], color="C2", lw=1.5, label="to the next highest point")
    a0 = float(np.arctan2(py, px))
    arc = a0 + np.linspace(0.0, orbit.apsidal_angle, 60)     # signed as L_z
    rad = 0.3 * float(np.hypot(px, py)) if np.hypot(px, py) > 0 else 0.1
    top.plot(rad * np.cos(arc), rad * np.sin(arc), color="k", lw=1, label="_apsidal angle")
    top.set_title(f"apsidal angle {np.degrees(abs(orbit.apsidal_angle)):.4f}°", fontsize=10)
    top.set(aspect="equal", xlabel="x / l", ylabel="y / l")
    top.legend(fontsize=9, loc="lower left", framealpha=0.85)
    side.plot(x, z, lw=0.8, color="C0")
    side.plot([0.0], [0.0], "k+", ms=8)
    for th, c in ((orbit.theta_min, "C1"), (orbit.theta_max, "C2")):
        side.axhline(-np.cos(th), color=c, ls="--", lw=1)
    side.set(aspect="equal", xlabel="x / l", ylabel="z / l")
    side.set_title("from the side: the turning heights", fontsize=10)
    return top, side

"""What every figure of :mod:`pendula.plot` shares: matplotlib on demand, the axes to draw on, the checks of
what a figure is given, distinct colours and the labels of a scene's velocity."""

from __future__ import annotations

import numpy as np

from . import _checks
from ._optional import require


def _plt():
    require("matplotlib", "plot", "pendula.plot (figures)")
    import matplotlib.pyplot as plt

    return plt


def _wrapped(theta, v):
    """theta folded into [-pi, pi), with a break (NaN) wherever it wraps."""
    w = np.mod(theta + np.pi, 2 * np.pi) - np.pi
    jump = np.abs(np.diff(w)) > np.pi
    w = np.insert(w, np.nonzero(jump)[0] + 1, np.nan)
    v = np.insert(v, np.nonzero(jump)[0] + 1, np.nan)
    return w, v


def _ax(ax, figsize=(7, 4)):
    """The caller's axes (checked: a matplotlib Axes), or the axes of a new figure."""
    if ax is not None:
        from matplotlib.axes import Axes
        return _checks.instance(ax, "ax", Axes, "a matplotlib Axes or None")
    return _plt().subplots(figsize=figsize, layout="constrained")[1]


def _result(x, name: str, cls, what: str):
    """A result of the library as one of the plot functions takes it; a TypeError naming ``name``."""
    return _checks.instance(x, name, cls, what)


def _dataset(x, name: str):
    """An xarray Dataset (what the sweeps return); a TypeError naming ``name``."""
    xr = require("xarray", "plot", "pendula.plot")
    return _checks.instance(x, name, xr.Dataset, "an xarray.Dataset")


def _categorical(n: int) -> list:
    """n distinct colours for n categories, never one twice: matplotlib's tab10 up to ten, tab20 up to
    twenty, then tab20, tab20b and tab20c (60), then hues spaced evenly around the colour wheel at
    three lightnesses for as many more as needed."""
    plt = _plt()
    if n <= 10:
        return list(plt.get_cmap("tab10").colors[:n])
    names = ("tab20",) if n <= 20 else ("tab20", "tab20b", "tab20c")
    out = list(dict.fromkeys(tuple(c) for name in names for c in plt.get_cmap(name).colors))
    if len(out) < n:
        from matplotlib.colors import hsv_to_rgb
        more = n - len(out)
        per = -(-more // 3)
        for i in range(more):
            hue, shade = (i % per) / per, i // per
            out.append(tuple(float(x) for x in hsv_to_rgb((hue, 0.75, (0.95, 0.7, 0.45)[shade]))))
        out = list(dict.fromkeys(out))
    return out[:n]


def _v_label(scene) -> str:
    """The angular velocity's label: in reduced units (the time unit 1/ω₀ = 1/√ε) when ε = 1, else per
    unit of the scene's t (seconds when ε = g/l is in 1/s², as pendula.Pendulum's scene)."""
    return "v (rad per time unit 1/ω₀, ε = 1)" if scene.eps == 1.0 else "v (rad per unit of t)"


def _scene_label(scene) -> str:
    return scene.name or repr(scene)

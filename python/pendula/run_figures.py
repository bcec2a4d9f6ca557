"""The figures of ``pendula run``: a scene's runs drawn to files (time
series, phase portraits, energy drift, the orbit tables' curves, the period
series and Poincaré–Lindstedt errors, spectra).  The Axes-returning figures of
the library are :mod:`pendula.plot`.
"""

from __future__ import annotations

import math

import numpy as np

from ._files import save_figure  # the one writer: regular files only, whole or absent
from ._plot_common import _plt, _wrapped


def _axes(ax, n=None, figsize=(8, 4.5)):
    """(figure, axes): the caller's axes, or a new figure with one (n None) or n stacked panels."""
    plt = _plt()
    if ax is not None:
        if n is None:
            return ax.figure, ax
        axes = np.atleast_1d(np.asarray(ax, dtype=object)).ravel()
        if axes.size != n:
            raise ValueError(f"ax: this figure has {n} panels; got {axes.size} axes")
        return axes[0].figure, axes
    if n is None:
        return plt.subplots(figsize=figsize)
    fig, axes = plt.subplots(n, 1, figsize=figsize, sharex=True, squeeze=False)
    return fig, axes[:, 0]


def _save(fig, path, made_here):
    """Write the figure to path (if any); close it when this module made it and saved it."""
    if path is not None:
        save_figure(fig, path, dpi=110)   # staged, then renamed: whole or absent
        if made_here:
            _plt().close(fig)
    return fig


def _label(scene, value):
    return f"{scene.sweep} = {value:.10g}" if scene.sweep else ""


def _finish(fig, ax, title, path, made_here):
    ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=9, loc="best")
    if made_here:
        fig.tight_layout()
    return _save(fig, path, made_here)


def time_series(scene, runs, path=None, which="theta", *, ax=None):
    """theta(t) (or v(t)) of every member of a sweep, like the source's Fig. 5."""
    made_here = ax is None
    fig, ax = _axes(ax, figsize=(8, 4.5))
    for value, tr in runs:
        ax.plot(tr.t, getattr(tr, which), lw=1.0, label=_label(scene, value))
    ax.set_xlabel("t")
    ax.set_ylabel("theta (rad)" if which == "theta" else "v = dtheta/dt (rad/s)")
    if which == "theta":
        lim = ax.get_ylim()
        for k in range(math.floor(lim[0] / math.pi), math.ceil(lim[1] / math.pi) + 1):
            if k % 2:
                ax.axhline(k * math.pi, color="k", lw=0.5, ls=":")
    method = runs[0][1].method if runs else ""
    return _finish(fig, ax, f"{scene.name or which + '(t)'}   [eps = {scene.eps:g}, {method}]", path, made_here)


def phase_portrait(scene, runs, path=None, *, ax=None):
    """v against theta (folded into [-pi, pi)) for every member and its mirror
    image (-theta, -v), with the separatrix v = +-2 sqrt(eps) cos(theta/2)."""
    made_here = ax is None
    fig, ax = _axes(ax, figsize=(8, 5))
    for value, tr in runs:
        w, v = _wrapped(tr.theta, tr.v)
        line, = ax.plot(w, v, lw=1.0, label=_label(scene, value))
        if np.any(np.abs(tr.theta) > np.pi):
            ax.plot(-w, -v, lw=1.0, color=line.get_color())
    th = np.linspace(-math.pi, math.pi, 2000)
    sep = 2 * math.sqrt(scene.eps) * np.abs(np.cos(th / 2))
    ax.plot(th, sep, "k--", lw=0.8, label="separatrix")
    ax.plot(th, -sep, "k--", lw=0.8)
    ax.set_xlim(-math.pi, math.pi)
    ax.set_xlabel("theta (rad)")
    ax.set_ylabel("v (rad/s)")
    return _finish(fig, ax, scene.name or "phase portrait", path, made_here)


def energy_drift(scene, runs, path=None, *, ax=None):
    """Relative energy error (E - E0)/E0 along each run."""
    made_here = ax is None
    fig, ax = _axes(ax, figsize=(8, 4))
    for value, tr in runs:
        e0 = tr.energy[np.argmin(np.abs(tr.t))]
        ax.plot(tr.t, (tr.energy - e0) / (abs(e0) or 1.0), lw=0.8, label=_label(scene, value))
    ax.set_xlabel("t")
    ax.set_ylabel("(E - E0) / E0")
    return _finish(fig, ax, scene.name or "energy", path, made_here)


def orbit_curves(scene, values, table, path=None, *, ax=None):
    """omega, theta_max and period against the swept field (Figs. 8, 10, 13), one panel each."""
    cols = [c for c in ("omega", "theta_max", "period") if c in table]
    made_here = ax is None
    fig, axes = _axes(ax, len(cols), figsize=(8, 2.8 * len(cols)))
    for ax, c in zip(axes, cols):
        y = np.asarray(table[c], dtype=float)
        ax.plot(values, np.where(np.isfinite(y), y, np.nan), "o-", ms=2.5, lw=1.0, label=c)
        if c == "theta_max" and scene.sweep == "v0":
            ax.plot(values, 2 * np.asarray(values) / math.sqrt(scene.eps), "b:", lw=0.8,
                    label="small-angle 2 v0/sqrt(eps)")
            ax.set_ylim(0, 3.5)
        ax.set_ylabel(c)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=9)
    axes[-1].set_xlabel(scene.sweep)
    axes[0].set_title(scene.name or "orbits", fontsize=10)
    if made_here:
        fig.tight_layout()
    return _save(fig, path, made_here)


def critical_omega(scene, values, omega, path=None, *, ax=None):
    """omega against |v0 - 2 sqrt(eps)| near the separatrix (Figs. 9 and 12) with the asymptotes
    (pi/2)/ln(4/sqrt(t)) below and pi/ln(4/sqrt(t)) above, t = |v0/sqrt(eps) - 2|."""
    made_here = ax is None
    fig, ax = _axes(ax, figsize=(8, 4.5))
    v = np.asarray(values) / math.sqrt(scene.eps)
    t = np.abs(v - 2.0)
    om = np.asarray(omega) / math.sqrt(scene.eps)
    below, above = v < 2, v > 2
    tt = np.logspace(np.log10(max(t[t > 0].min(), 1e-300)), np.log10(t.max()), 200)
    ax.semilogx(t[below], om[below], "o", ms=4, label="exact, v0 < 2 (libration)")
    ax.semilogx(t[above], om[above], "s", ms=4, label="exact, v0 > 2 (rotation)")
    ax.semilogx(tt, (math.pi / 2) / np.log(4 / np.sqrt(tt)), "-", lw=0.8, label="(pi/2) / ln(4/sqrt(t))")
    ax.semilogx(tt, math.pi / np.log(4 / np.sqrt(tt)), "-", lw=0.8, label="pi / ln(4/sqrt(t))")
    ax.set_xlabel("t = |v0/sqrt(eps) - 2|")
    ax.set_ylabel("omega / sqrt(eps)")
    return _finish(fig, ax, scene.name or "critical behaviour of omega", path, made_here)


def period_series_figure(theta0, exact, approximations, path=None, *, ax=None):
    """Relative error of the truncated period series against the exact period."""
    made_here = ax is None
    fig, ax = _axes(ax, figsize=(8, 4.5))
    for n, approx in approximations.items():
        err = np.abs(approx / exact - 1)
        ax.semilogy(theta0, np.where(err > 0, err, np.nan), lw=1.0, label=f"series to theta0^{2 * n}")
    ax.set_xlabel("theta0 (rad), released from rest")
    ax.set_ylabel("|T_series / T_exact - 1|")
    return _finish(fig, ax, "period series against the exact period 4K/sqrt(eps)", path, made_here)


def lindstedt_figure(amplitudes, errors, path=None, *, ax=None):
    """Max |theta_PL - theta_exact| over the run against the amplitude, per order."""
    made_here = ax is None
    fig, ax = _axes(ax, figsize=(8, 4.5))
    for order, err in errors.items():
        ax.loglog(amplitudes, err, "o-", ms=3, lw=1.0, label=f"Poincare-Lindstedt order {order}")
    ax.set_xlabel("amplitude a (rad)")
    ax.set_ylabel("max |theta_PL(t) - theta(t)|, 0 <= t <= t_end")
    return _finish(fig, ax, "Poincare-Lindstedt against the exact solution", path, made_here)


def spectra_figure(scene, specs, labels, path=None, *, ax=None):
    """Log power against omega, one panel per member (the source's Fig. 6 family)."""
    k = len(specs)
    made_here = ax is None
    fig, axes = _axes(ax, k, figsize=(8, 1.6 + 1.5 * k))
    wmax = 16 * max(s.fundamental for s in specs)
    for ax, s, lab in zip(axes, specs, labels):
        sel = s.omega <= wmax
        ax.semilogy(s.omega[sel], np.maximum(s.power[sel], 1e-32), lw=0.8)
        ax.set_ylim(1e-30, 10)
        ax.set_ylabel("|A|^2", fontsize=9)
        ax.text(0.99, 0.85, lab, transform=ax.transAxes, ha="right", fontsize=9)
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel("omega (rad/s)")
    axes[0].set_title(scene.name or "power spectra of theta(t)", fontsize=10)
    if made_here:
        fig.tight_layout()
    return _save(fig, path, made_here)


# ------------------------------------------------------------- one result, one Axes

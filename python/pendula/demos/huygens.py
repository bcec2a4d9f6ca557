"""Gallery demo: Huygens' clock, non-uniform gravity, the density of the angle.

``huygens_gallery(outdir)`` writes (in seconds):

- huygens_clock.png: the cheeks, the cord wrapping them at several instants,
  the bob's cycloid and the rigid pendulum's circle (Prusa & Tuma, Figures 3/4);
  huygens_period.csv/png: the period against amplitude, cycloid and rigid.
- gravity_period.csv/png: the period against amplitude for a few strengths of
  both non-uniform fields, with the uniform (elliptic) period.
- angle_density_gallery.png/csv: densities for a few amplitudes, the arcsine law and a
  histogram of a long exact run on top.
"""

from __future__ import annotations

import math
import pathlib

import numpy as np

from ..density import angle_cdf, angle_density, arcsine_density
from ..systems.cycloid import cycloid_geometry, cycloid_motion, cycloid_period
from ..motion import period, simulate
from ..scene import Scene
from .._files import save_figure, open_text  # the one writer: regular files only, whole or absent

__all__ = ["huygens_gallery", "gravity_period_table"]



def _finish(plt, fig, ax, title, path, legend_size=8):
    """Legend, grid, title; save the figure to path and close it; return the path."""
    ax.legend(fontsize=legend_size)
    ax.grid(alpha=0.3)
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return path

def _plt():
    from .._plot_common import _plt as p

    return p()


def gravity_period_table(amplitudes=None):
    """Rows (field, parameter, theta0, T / T_uniform(theta0), T * omega0 / 2 pi)."""
    from ..systems.gravity import small_oscillation_omega

    amps = np.linspace(0.05, 3.1, 40) if amplitudes is None else np.asarray(amplitudes, dtype=float)
    rows = []
    fields = [("uniform", 0.0), ("inverse-square", 1.5), ("inverse-square", 3.0), ("inverse-square", 10.0),
              ("linear", -0.5), ("linear", 0.2), ("linear", 0.45)]
    for field, par in fields:
        kw = {"inverse-square": {"gravity_distance": par}, "linear": {"gravity_gradient": par}}.get(field, {})
        for a in amps:
            sc = Scene(gravity=field, theta0=float(a), **kw)
            T = period(sc)
            T0 = period(Scene(theta0=float(a)))
            rows.append((field, par, float(a), T, T / T0, T * small_oscillation_omega(sc) / (2 * math.pi)))
    return rows


def _measured_period(sc) -> float:
    """The cycloid's period measured on its path: the return of s' to 0 from below
    (bisection on the closed form's s' near the nominal period)."""
    T = cycloid_period(sc)
    lo, hi = 0.75 * T, 1.25 * T
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if cycloid_motion(sc, [mid])[3][0] < 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def huygens_gallery(outdir) -> list[pathlib.Path]:
    """Write the figures and tables of Huygens' clock, non-uniform gravity and the angle
    density into outdir; return the paths."""
    plt = _plt()
    out = pathlib.Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    files = []

    # --- Huygens' clock: cheeks, cord at several instants, cycloid, circle
    R = 0.25
    geo = cycloid_geometry(R)
    fig, ax = plt.subplots(figsize=(5.5, 5.5))
    ax.plot(*geo.cheek_left, "k", lw=2.5)
    ax.plot(*geo.cheek_right, "k", lw=2.5, label="cheeks (cycloids)")
    ax.plot(*geo.path, "C0", lw=1.2, label="bob's path (cycloid, s = 4R sin theta)")
    ax.plot(*geo.circle, "C3--", lw=1, label="rigid pendulum's circle (l = 4R)")
    sc = Scene(guide="cycloid", theta0=1.3, cycloid_radius=R)
    T = cycloid_period(sc)
    for t in np.linspace(0, T / 2, 7):
        th = float(cycloid_motion(sc, [t])[0][0])
        wrapped, contact, bob = geo.cord(th)
        ax.plot(*wrapped, "C1", lw=1.8)
        ax.plot([contact[0], bob[0]], [contact[1], bob[1]], "C1", lw=0.8)
        ax.plot(*bob, "o", color="C2", ms=5)
    ax.plot(0, 4 * R, "ks")
    ax.set_aspect("equal")
    ax.set_xlabel("x / l")
    ax.set_ylabel("y / l")
    ax.set_ylim(-0.05, 1.45)
    ax.legend(fontsize=7, loc="upper center", ncol=2)
    ax.set_title("Huygens' clock: the cord wraps on the cheeks (7 instants over half a period)", fontsize=9)
    fig.tight_layout()
    files.append(out / "huygens_clock.png")
    save_figure(fig, files[-1], dpi=110)
    plt.close(fig)

    # --- period against amplitude: cycloid (measured from the closed form) and rigid
    amps = np.linspace(1e-3, math.pi / 2, 60)
    Tc = [_measured_period(Scene(guide="cycloid", theta0=float(a))) for a in amps]
    Tr = [period(Scene(theta0=float(a))) for a in amps]
    np.savetxt(out / "huygens_period.csv", np.column_stack([amps, Tc, Tr]), delimiter=",",
               header="theta0,T_cycloid,T_rigid", comments="")
    files.append(out / "huygens_period.csv")
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(amps, np.array(Tc) / (2 * math.pi), label="cycloid (R = l/4)")
    ax.plot(amps, np.array(Tr) / (2 * math.pi), label="rigid pendulum (exact)")
    ax.set_xlabel("amplitude theta0 (rad; the cusp at pi/2)")
    ax.set_ylabel("T sqrt(g/l) / 2 pi")
    files.append(_finish(plt, fig, ax, "The cycloid is isochronous; the circle is not",
                         out / "huygens_period.png", legend_size=8))

    # --- non-uniform gravity: period against amplitude
    rows = gravity_period_table()
    with open_text(out / "gravity_period.csv") as f:
        f.write("field,parameter,theta0,period,period_over_uniform,period_times_omega0_over_2pi\n")
        for r in rows:
            f.write(",".join(str(x) for x in r) + "\n")
    files.append(out / "gravity_period.csv")
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    keys = sorted({(r[0], r[1]) for r in rows}, key=lambda k: (k[0], k[1]))
    for field, par in keys:
        sel = [r for r in rows if r[0] == field and r[1] == par]
        lab = {"uniform": "uniform (elliptic)", "inverse-square": f"inverse-square, D = {par:g} l",
               "linear": f"linear, kappa = {par:g}"}[field]
        ax.plot([r[2] for r in sel], [r[5] for r in sel], "-" if field != "linear" else "--", label=lab)
    ax.set_yscale("log")
    ax.set_xlabel("amplitude theta0 (rad)")
    ax.set_ylabel("T omega0 / 2 pi  (omega0^2 = V''(0))")
    files.append(_finish(plt, fig, ax, "Period against amplitude in non-uniform gravity (exact quadrature)",
                         out / "gravity_period.png", legend_size=7))

    # --- the density of the angle: a few amplitudes, the arcsine law, a histogram on top
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    table = []
    for a in (0.2, 1.5, 2.5, 3.0):
        sc = Scene(theta0=a)
        x = np.linspace(-a, a, 801)[1:-1]
        p = angle_density(sc, x)
        ax.plot(x / a, p * a, label=f"theta0 = {a:g}")
        table += [(a, xi, pi, ci) for xi, pi, ci in zip(x[::20], p[::20], angle_cdf(sc, x[::20]))]
    xs = np.linspace(-1, 1, 801)[1:-1]
    ax.plot(xs, arcsine_density(xs, 1.0), "k:", label="arcsine law (linear limit)")
    sc = Scene(theta0=2.5)
    T = period(sc)
    t = np.random.default_rng(7).uniform(0, 500 * T, 200_000)
    th = simulate(sc, t).theta
    ax.hist(th / 2.5, bins=80, density=True, histtype="step", color="C2", lw=1.5, label="histogram, theta0 = 2.5 (exact run)")
    ax.set_ylim(0, 3)
    ax.set_xlabel("theta / theta0")
    ax.set_ylabel("theta0 p(theta)")
    files.append(_finish(plt, fig, ax, "The density of the angle over a period",
                         out / "angle_density_gallery.png", legend_size=7))
    np.savetxt(out / "angle_density_gallery.csv", np.array(table), delimiter=",", header="theta0,theta,density,cdf",
               comments="")
    files.append(out / "angle_density_gallery.csv")
    return files

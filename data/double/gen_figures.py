"""The figures of docs/source/guide/double.md, written to docs/figures/.

* double_flip_map.png: the flip-time map of data/double/flip_map.npz (made by
  gen_flip_map.py), drawn by pendula.plot.flip_map;
* foucault_precession.png: a 67 m Foucault pendulum's measured precession
  against latitude, released from rest and opened into an ellipse, beside the
  Coriolis rate -Omega_E sin(latitude) (FoucaultPendulum.precession; seconds);
* foucault_budget.png: a builder's budget, the exact Airy precession
  (spherical_orbit) over the amplitude and the ellipse's axis ratio b/a, in
  percent of the Coriolis rate at the Pantheon's latitude.

Run: python data/double/gen_figures.py
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pendula  # noqa: E402
import pendula.plot  # noqa: E402

HERE = Path(__file__).resolve().parent
FIG = HERE.parent.parent / "docs" / "figures"


def flip_map_figure() -> None:
    d = np.load(HERE / "flip_map.npz")
    t_max, rtol, agree = (float(x) for x in d["meta"])
    fm = pendula.FlipMap(d["theta1"], d["theta2"], d["time"].astype(float), d["check"].astype(float),
                         d["forbidden"], d["unresolved"], t_max, rtol, agree)
    fig, ax = plt.subplots(figsize=(7.0, 5.6), layout="constrained")
    pendula.plot.flip_map(fm, ax=ax)
    ax.set_title(f"double pendulum from rest: time to the first flip\n"
                 f"{fm.time.shape[0]} x {fm.time.shape[1]} pixels, t_max = {t_max:g} sqrt(l/g), "
                 f"{int(fm.unresolved.sum())} unresolved", fontsize=11)
    ax.tick_params(labelsize=10)
    fig.savefig(FIG / "double_flip_map.png", dpi=100)
    print(fm)


def foucault_figure() -> None:
    lat = np.linspace(-90.0, 90.0, 37)
    day = 86400.0 * 180.0 / np.pi
    rows = []
    for phd in (0.0, 2e-3):
        meas, airy = [], []
        for la in lat:
            pr = pendula.FoucaultPendulum(latitude=float(la), length=67.0).precession(0.05, phi_dot0=phd, swings=60)
            meas.append(pr.measured * day)
            airy.append(pr.airy * day)
        rows.append((phd, np.array(meas), np.array(airy)))
    fig, axs = plt.subplots(1, 2, figsize=(7.2, 3.4), layout="constrained")
    cor = -pendula.systems.foucault.EARTH_RATE * np.sin(np.radians(lat)) * day
    ax = axs[0]
    ax.plot(lat, cor, "k-", lw=1, label="Coriolis -Ω sin(lat)")
    for (phd, meas, _), mk in zip(rows, ("o", "s")):
        lab = "released from rest" if phd == 0 else f"ellipse (φ' = {phd:g}/s)"
        ax.plot(lat, meas, mk, ms=3.5, mfc="none", label=lab)
    ax.set(xlabel="latitude (deg)", ylabel="precession (deg/day)")
    ax.legend(fontsize=9)
    ax = axs[1]
    for (phd, meas, airy), mk in zip(rows, ("o", "s")):
        who = "from rest" if phd == 0 else "ellipse"
        ax.plot(lat, meas - cor, mk, ms=3.5, mfc="none", label=f"{who}: measured - Coriolis")
        ax.plot(lat, airy, "-", lw=1, label="Airy (exact)" if phd else None, color="C3")
    ax.set(xlabel="latitude (deg)", ylabel="the rest (deg/day)")
    ax.legend(fontsize=9, loc="center right")
    for a in axs:
        a.tick_params(labelsize=10)
        a.xaxis.label.set_size(10)
        a.yaxis.label.set_size(10)
    fig.savefig(FIG / "foucault_precession.png", dpi=100)


def budget_figure(length: float = 67.0, g: float = 9.81, latitude: float = 48.85) -> None:
    w = np.sqrt(g / length)
    amp = np.linspace(0.5, 10.0, 60)                 # degrees
    ratio = np.logspace(-4, -1, 61)                  # b / a
    # a small ellipse x = a cos(wt), y = b sin(wt): from the far end with the azimuthal rate w b / a
    airy = np.array([[pendula.spherical_orbit(np.radians(a), 0.0, w * r, g / length).precession_rate
                      for a in amp] for r in ratio])
    cor = pendula.systems.foucault.EARTH_RATE * np.sin(np.radians(latitude))
    pct = 100.0 * np.abs(airy) / cor
    fig, ax = plt.subplots(figsize=(6.4, 4.4), layout="constrained")
    levels = [0.3, 1, 3, 10, 30, 100]
    cs = ax.contour(amp, ratio, pct, levels=levels, colors="k", linewidths=1)
    ax.clabel(cs, fmt=lambda v: f"{v:g} %", fontsize=9)
    ax.contourf(amp, ratio, pct, levels=[100, 1e9], colors=["0.8"])
    ax.set_yscale("log")
    ax.set_xlabel("amplitude (degrees)", fontsize=10)
    ax.set_ylabel("ellipse axis ratio b / a", fontsize=10)
    ax.set_title(f"Airy precession in % of the Coriolis rate ({length:g} m, latitude {latitude:g})", fontsize=10)
    ax.tick_params(labelsize=10)
    fig.savefig(FIG / "foucault_budget.png", dpi=100)


if __name__ == "__main__":
    budget_figure()
    foucault_figure()
    if (HERE / "flip_map.npz").exists():
        flip_map_figure()

"""The figures of docs/source/guide/attractors.md, written to docs/figures/.

* attractor_map_1p07.png: the default attractor map at A = 1.07 (beta = 0.5, Omega = 2/3) on a 150 x 150
  grid over theta0 in [-pi, pi], v0 in [-3, 3], with the attractors' cycle points and the drive periods
  each point took before it was decided.
* attractor_continuation.png: basin fractions over drive_amplitude 1.0 .. 1.5 (21 values, a 40 x 40 grid),
  stacked, from pendula.attractor_continuation (its resumable folder in the system's temporary folder).
* The figures' numbers go to data/attractors/guide_figures.json (quoted by the page).

    python data/attractors/gen_guide_figures.py [--redraw | --map-only]      (a few minutes on 2 cores; --redraw: the
    continuation figure again from data/attractors/guide_figures.json)
"""

import json
import pathlib
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pendula  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
FIG = ROOT / "docs" / "figures"


def draw_continuation(c: dict) -> None:
    """The stacked basin fractions: one colour family per kind and period (blues period 1, greens 2,
    purples 3, oranges 4 and longer, greys chaotic), one shade per continued attractor."""
    vals = np.array(c["values"])
    f = np.nan_to_num(np.array(c["fraction"], dtype=float))
    fams = {1: "Blues", 2: "Greens", 3: "Purples", 0: "Greys"}
    keys = [(k, p) for k, p in zip(c["kinds"], c["periods"])]
    order = sorted(range(len(keys)), key=lambda i: (keys[i][0] == "chaotic", keys[i][1], i))
    colours, seen, handles = [], {}, {}
    for i in order:
        k, p = keys[i]
        fam = fams[0] if k == "chaotic" else fams.get(p, "Oranges")
        j = seen.get(fam, 0)
        seen[fam] = j + 1
        colours.append(plt.get_cmap(fam)(0.45 + 0.4 * ((j * 0.37) % 1.0)))
    fig, ax = plt.subplots(figsize=(8.5, 4.6))
    polys = ax.stackplot(vals, np.vstack([f[:, i] for i in order] + [np.array(c["undecided"])]),
                         colors=colours + ["white"], step="mid", edgecolor="k", linewidth=0.2)
    for i, poly in zip(order, polys):
        k, p = keys[i]
        name = "chaotic" if k == "chaotic" else f"period {p}" if p < 4 else "period 4 and longer"
        handles.setdefault(name, poly)
    ax.legend(list(handles.values()), list(handles.keys()), fontsize=8, loc="center left", bbox_to_anchor=(1.0, 0.5),
              title="one shade per attractor")
    ax.set(xlabel="drive amplitude A", ylabel="fraction of the (θ0, v0) grid", xlim=(vals[0], vals[-1]), ylim=(0, 1),
           title="basin fractions of the attractors, continued over A (β = 0.5, Ω = 2/3)")
    fig.tight_layout()
    fig.savefig(FIG / "attractor_continuation.png", dpi=110)
    plt.close(fig)


def main():
    if "--redraw" in sys.argv:      # the continuation figure again, from the recorded numbers
        draw_continuation(json.loads((ROOT / "data" / "attractors" / "guide_figures.json").read_text())["continuation"])
        return
    rec = {}
    n = 150
    grid = {"theta0": np.linspace(-np.pi, np.pi, n), "v0": np.linspace(-3.0, 3.0, n)}
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.07, drive_frequency=2 / 3)
    am = pendula.attractor_map(sc, grid, threads=2)
    lab = am.dataset.attractor.values
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6))
    k = max(len(am.attractors), 1)
    from matplotlib.colors import ListedColormap, to_rgba
    base = [to_rgba(f"C{i}") for i in range(k)]
    light = ListedColormap([tuple(0.45 * np.array(c[:3]) + 0.55) for c in base])    # the basins, pale
    axes[0].imshow(lab.T, origin="lower", extent=[-np.pi, np.pi, -3, 3], aspect="auto",
                   cmap=light, vmin=-0.5, vmax=k - 0.5, interpolation="nearest")
    for a in am.attractors:
        axes[0].plot(a.theta, a.v, "o", ms=8, mec="k", color=base[a.label],
                     label=f"{a.kind}, period {a.period}: {a.fraction:.1%} of the grid")
    axes[0].set(xlabel="θ0", ylabel="v0", title=f"A = 1.07: {len(am.attractors)} attractors "
                f"({am.undecided} undecided of {lab.size})")
    axes[0].legend(fontsize=8, loc="upper right")
    im = axes[1].imshow(am.dataset.periods.values.T, origin="lower", extent=[-np.pi, np.pi, -3, 3], aspect="auto",
                        cmap="viridis", interpolation="nearest")
    fig.colorbar(im, ax=axes[1], label="drive periods integrated")
    axes[1].set(xlabel="θ0", ylabel="v0", title="the work: drive periods until decided (rechecks included)")
    fig.tight_layout()
    fig.savefig(FIG / "attractor_map_1p07.png", dpi=110)
    plt.close(fig)
    rec["map_1p07"] = {"n": n, "attractors": [[a.kind, a.period, a.fraction, np.abs(a.multipliers).tolist()]
                                              for a in am.attractors],
                       "undecided": am.undecided, "rechecked": am.rechecked, "recheck_changed": am.recheck_changed,
                       "mean_periods": float(am.dataset.periods.mean()),
                       "boundary_fraction": am.boundary_fraction}

    if "--map-only" in sys.argv:
        old = json.loads((ROOT / "data" / "attractors" / "guide_figures.json").read_text())
        old["map_1p07"] = rec["map_1p07"]
        (ROOT / "data" / "attractors" / "guide_figures.json").write_text(json.dumps(old, indent=1) + "\n")
        return
    small = {"theta0": np.linspace(-np.pi, np.pi, 40), "v0": np.linspace(-3.0, 3.0, 40)}
    vals = np.round(np.linspace(1.0, 1.5, 21), 6)
    ds = pendula.attractor_continuation(pendula.Scene(damping=0.5, drive_frequency=2 / 3), small, "drive_amplitude",
                                        vals, threads=2,
                                        out=pathlib.Path(tempfile.gettempdir()) / "pendula_attractor_continuation")
    rec["continuation"] = {"values": vals.tolist(), "kinds": ds.kind.values.tolist(),
                           "periods": ds.period.values.tolist(), "fraction": ds.fraction.values.tolist(),
                           "undecided": ds.undecided.values.tolist()}
    (ROOT / "data" / "attractors" / "guide_figures.json").write_text(json.dumps(rec, indent=1) + "\n")
    draw_continuation(rec["continuation"])
    print(json.dumps(rec["map_1p07"]), rec["continuation"]["kinds"], rec["continuation"]["periods"])


if __name__ == "__main__":
    main()

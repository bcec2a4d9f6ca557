"""Gallery of the flexible cord (Garfinkel 1957): every number from simulated flips.

``cord_demo(outdir)`` writes, for the scenes ``data/scenes/cord_*.nml``, the
bob's path (circle and flight drawn differently) and the flip log; the graph
of f(x) with the points of simulated flips on it; Tables 1 and 2 regenerated
from runs (CSV, and printed); the sequence x_k; the xi(0) = 0.777 history.
"""

from __future__ import annotations

import csv
import math
import pathlib
import warnings

import numpy as np

from ..systems.cord import cord_state, flip_map, flip_sequence
from ..motion import simulate
from ..scene import Scene
from .._files import save_figure, open_text  # the one writer: regular files only, whole or absent

__all__ = ["cord_demo", "one_flip", "table1", "table2"]


def _v0(xi, eps=1.0):
    return math.sqrt(eps * (3.0 * xi + 2.0))


def one_flip(xi: float) -> dict:
    """Simulate one flip from the bottom at energy xi; the flip log's first entry."""
    sc = Scene(cord="flexible", v0=_v0(xi), t_end=100.0, n_samples=2, max_flips=1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # NaN after the max_flips stop: wanted
        fl = simulate(sc).flips
    return {k: float(v[0]) for k, v in fl.items()}


def table1(xs=np.round(np.arange(0.0, 1.01, 0.1), 10)):
    """Garfinkel's Table 1 from simulated flips: x, f(x), theta1, theta2 (degrees).

    x = 0 and x = 1 have no flight (zero length): their rows are the limits
    from x = 1e-12 and 1 - 1e-12."""
    rows = []
    for x in xs:
        xr = min(max(float(x), 1e-12), 1 - 1e-12)
        f = one_flip(xr)
        rows.append((float(x), f["xi_after"], math.degrees(f["theta_leave"]),
                     math.degrees(math.remainder(f["theta_return"], 2 * math.pi))))
    return rows


def table2(kmax: int = 12, odd_extra: int = 30):
    """Garfinkel's Table 2 from runs: for each k(0) a run started inside I_k.

    Returns rows (k0, xi0, flips to reach the final state, final state, flips
    seen afterwards in the run, ultimate state)."""
    xs = flip_sequence(kmax + 2)
    rows = []
    for k in range(kmax + 1):
        x = 0.5 * (xs[k] + xs[k + 1]) if k else -0.3
        sc = Scene(cord="flexible", v0=_v0(x), t_end=2e4, n_samples=2, max_flips=k // 2 + odd_extra)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            fl = simulate(sc).flips
        states = cord_state(np.concatenate([[x], fl["xi_after"]]))
        final = 0 if k % 2 == 0 else 1
        n = int(np.argmax(states == final))
        rows.append((k, float(x), n, int(states[n]), fl["xi_after"].size - n,
                     "oscillation" if final == 0 else "flipping"))
    sc = Scene(cord="flexible", v0=_v0(1.2), t_end=200.0, n_samples=2)
    nflip = simulate(sc).flips["xi_after"].size
    rows.append(("inf", 1.2, nflip, "inf", 0, "circulation"))
    return rows


def _write(path, header, rows):
    with open_text(path, newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        w.writerows(rows)
    return path


def _path_png(tr, title, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5.5, 5.5))
    a = np.linspace(0, 2 * np.pi, 400)
    ax.plot(np.cos(a), np.sin(a), color="0.85", lw=0.8)
    fly = tr.r < 1 - 1e-12
    xc = np.where(fly, np.nan, tr.x)
    yc = np.where(fly, np.nan, tr.y)
    xf = np.where(fly, tr.x, np.nan)
    yf = np.where(fly, tr.y, np.nan)
    ax.plot(xc, yc, color="tab:blue", lw=1.0, label="on the circle (taut)")
    ax.plot(xf, yf, color="tab:red", lw=1.0, ls="--", label="free flight (slack)")
    ax.plot([0], [0], "k+")
    ax.set_aspect("equal")
    ax.set_xlabel("x / l")
    ax.set_ylabel("y / l")
    ax.set_title(title, fontsize=8)
    ax.legend(fontsize=7, loc="lower right")
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return path


def cord_demo(outdir, scenes_dir=None, quiet: bool = False, verbose: bool = True) -> list[pathlib.Path]:
    """Write the flexible-cord gallery into ``outdir``; return the files written.

    Prints every table with ``verbose``, two lines of figures without it, nothing when ``quiet``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = pathlib.Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    say = (lambda *a: None) if quiet or not verbose else print
    brief = (lambda *a: None) if quiet or verbose else print
    files = []
    if scenes_dir is None:
        from .._files import gallery_dir

        scenes_dir = gallery_dir()
    say("\nthe flexible cord (Garfinkel 1957): every number from simulated flips")
    for p in sorted(q for q in scenes_dir.iterdir() if q.name.startswith("cord_") and q.name.endswith(".nml")):
        sc = Scene.from_namelist(p.read_text(), source=p.name)
        tr = simulate(sc)
        stem = p.name[:-4]
        files.append(_path_png(tr, sc.name, out / f"{stem}_path.png"))
        fl = tr.flips
        keys = list(fl)
        files.append(_write(out / f"{stem}_flips.csv", keys, zip(*(fl[k] for k in keys))))
        say(f"  {p.name:32s} {tr.stats['flips']} flip(s), stop: {tr.stats['stop_reason']}")

    # the map f from simulated flips (random points plus a grid), on the graph of f
    rng = np.random.default_rng(1957)
    xs = np.sort(np.concatenate([rng.uniform(0, 1, 120), np.linspace(0.005, 0.995, 60)]))
    sim = np.array([one_flip(float(x))["xi_after"] for x in xs])
    err = np.max(np.abs(sim - flip_map(xs)) / np.maximum(np.abs(flip_map(xs)), 1e-3))
    say(f"  the map from {xs.size} simulated flips against Garfinkel's f: worst relative difference {err:.1e}")
    fig, ax = plt.subplots(figsize=(6, 4.5))
    xx = np.linspace(-2 / 3, 1.2, 2000)
    ax.plot(xx, flip_map(xx), color="0.3", lw=1, label="f(x), closed form (eqs. 14-15)")
    ax.plot(xs, sim, "o", ms=3, mfc="none", color="tab:red", label="simulated flips")
    ax.plot(xx, xx, color="0.8", lw=0.6)
    ax.axhline(0, color="0.8", lw=0.6)
    ax.set_xlabel("x (energy before the flip)")
    ax.set_ylabel("f(x) (energy after)")
    ax.legend(fontsize=8)
    ax.set_title("Garfinkel's flip map (Fig. 1)")
    save_figure(fig, out / "cord_flip_map.png", dpi=110)
    plt.close(fig)
    files.append(out / "cord_flip_map.png")
    files.append(_write(out / "cord_flip_map.csv", ["x", "f_simulated", "f_closed_form"],
                        zip(xs, sim, flip_map(xs))))

    t1 = table1()
    files.append(_write(out / "cord_table1.csv", ["x", "f", "theta1_deg", "theta2_deg"], t1))
    say("  Table 1 (from simulated flips)\n     x       f(x)   theta1   theta2")
    for x, f, a, b in t1:
        say(f"    {x:.1f}  {f:8.3f}  {a:6.1f}  {b:7.1f}")
    seq = flip_sequence(12)
    files.append(_write(out / "cord_sequence.csv", ["k", "x_k"], enumerate(seq)))
    say("  the sequence x_k: " + ", ".join(f"{x:.3f}" for x in seq))
    t2 = table2()
    files.append(_write(out / "cord_table2.csv",
                        ["k0", "xi0", "flips_to_final", "final_state", "flips_after_in_run", "ultimate"], t2))
    say("  Table 2 (from runs started in each state)\n    k(0)   xi(0)    N  k(inf)  then   ultimate state")
    for k, x, n, kf, after, ult in t2:
        say(f"    {k!s:>4}  {x:7.4f}  {n:3d}  {kf!s:>5}  {after:4d}   {ult}"
            + ("" if k == "inf" else f"   ([k/2] = {int(k) // 2})"))

    # the xi(0) = 0.777 history
    sc = Scene(cord="flexible", v0=_v0(0.777), t_end=1e9, n_samples=2, max_flips=2000)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        fl = simulate(sc).flips
    xi = np.concatenate([[0.777], fl["xi_after"]])
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.semilogx(np.arange(1, xi.size + 1), xi, ".-", ms=3)
    for x in seq[1:5]:
        ax.axhline(x, color="0.8", lw=0.6)
    ax.set_xlabel("1 + flip number")
    ax.set_ylabel("xi")
    ax.set_title("xi(0) = 0.777: one flip to state k = 1, then xi -> 0")
    save_figure(fig, out / "cord_history_0777.png", dpi=110)
    plt.close(fig)
    files.append(out / "cord_history_0777.png")
    files.append(_write(out / "cord_history_0777.csv", ["flip", "xi", "state"],
                        zip(range(xi.size), xi, cord_state(xi))))
    say(f"  xi(0) = 0.777: states {int(cord_state(xi[0]))} -> {int(cord_state(xi[1]))}, "
        f"xi after {xi.size - 1} flips = {xi[-1]:.4f}")
    brief("the flexible cord (Garfinkel 1957):\n"
          f"  the flips of the simulated bob agree with his closed-form flip map f to {err:.0e}"
          " (largest relative difference)\n"
          "  his Tables 1 and 2, recomputed: cord_table1.csv, cord_table2.csv\n"
          f"  released at xi = 0.777 (his example): one flip takes it from state {int(cord_state(xi[0]))} to state "
          f"{int(cord_state(xi[1]))};\n    after {xi.size - 1} flips xi = {xi[-1]:.3f} (settling towards 0)")
    return files

"""Sweep gallery: basins of the damped pendulum with the
energy-balance prediction, Suzuki & Suzuki's section 8.2 (wells against torque), the
I-V loop of the RCSJ junction with its retrapping torque, the bifurcation
diagram of the driven damped pendulum and, beside it, its largest Lyapunov
exponent against the drive amplitude.  ``run(out, small=True)`` is what
``pendula demo`` calls; the full-size scenes are data/scenes/sweeps/*.nml."""

from __future__ import annotations

import math
import pathlib

import numpy as np

from ..elliptic import ellipe
from ..scene import Scene
from ..ivcurve import iv_curve
from ..sweeps import sweep
from .._files import save_figure, open_text  # the one writer: regular files only, whole or absent
from .._optional import require

#: Suzuki & Suzuki, section 8.2: v0 -> the wells n (theta ~ 2 pi n) the text lists
SUZUKI_8_2 = {2.01: {0, 1}, 2.05: {0, 1, 2}, 2.10: {0, 1, 3}, 2.14: {0, 1, 2, 3}, 2.27: {0, 1, 2, 4},
            2.40: {0, 1, 2, 3, 4}, 2.60: {0, 1, 2, 3, 5}, 2.80: {0, 1, 2, 3, 4, 5},
            2.95: {0, 1, 2, 3, 4, 6}, 3.15: {0, 1, 2, 3, 4, 5, 6}}


def energy_balance_well(v0, beta, eps=1.0):
    """Predicted final well from theta0 = 0: energy lost per half turn
    beta * integral of v dtheta along the conservative orbit of the current
    energy, 2 sqrt(2E) E(2 eps / E) (8 beta sqrt(eps) per turn on the separatrix)."""
    v0, beta = np.broadcast_arrays(np.asarray(v0, float), np.asarray(beta, float))
    n = np.zeros(v0.shape)
    e = 0.5 * v0**2
    alive = e > 2 * eps
    half = True
    for _ in range(400):
        if not alive.any():
            break
        m = np.where(alive, 2 * eps / np.maximum(e, 2 * eps), 0.5)
        ihalf = 2 * np.sqrt(2 * np.maximum(e, 0)) * ellipe(m)
        e = np.where(alive, e - beta * (ihalf if half else 2 * ihalf), e)
        passed = alive & (e > 2 * eps)
        n = n + passed
        alive = passed
        half = False
    return n


def _basins(out, small):
    nv, nb = (80, 50) if small else (1000, 1000)
    s = Scene(damping=0.1, grid=("v0", "damping"), grid1_range=(0.0, 4.0, nv), grid2_range=(0.02, 0.3, nb),
              measure="final_well", rtol=1e-8, atol=1e-10)
    ds = sweep(s)
    pred = energy_balance_well(ds.v0.values[:, None], ds.damping.values[None, :])
    ok = ds.status.values == 0
    dis = float(np.mean(pred[ok] != ds.well.values[ok]))
    png = plot_sweep(ds, out / "sweep_basins_v0_beta.png")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    w = ds.well.values
    hi = int(np.nanmax(w))
    im = ax.imshow(w.T, origin="lower", aspect="auto", cmap=plt.get_cmap("tab20", hi + 1), vmin=-0.5,
                   vmax=hi + 0.5, extent=[0, 4, 0.02, 0.3], interpolation="nearest")
    ax.contour(ds.v0.values, ds.damping.values, pred.T, levels=np.arange(0.5, hi + 1), colors="k",
               linewidths=0.8)
    fig.colorbar(im, ax=ax, label="final well n")
    ax.set_xlabel("v0"); ax.set_ylabel("damping beta")
    ax.set_title(f"final well; black: energy balance (disagrees at {100 * dis:.1f} % of points)")
    fig.tight_layout(); save_figure(fig, out / "sweep_basins_energy_balance.png", dpi=120); plt.close(fig)
    s2 = Scene(damping=0.1, grid=("theta0", "v0"), grid1_range=(-math.pi, math.pi, nv // 2),
               grid2_range=(-4.0, 4.0, nb), measure="final_well", rtol=1e-8, atol=1e-10)
    ds2 = sweep(s2)
    plot_sweep(ds2, out / "sweep_basins_theta0_v0.png")
    return {"points": int(ds.status.size), "decided": float(np.mean(ok)),
            "uncertain": int(np.sum(ds.status.values == 4)), "energy_balance_disagreement": dis, "png": png}


def _suzuki_8_2(out, t_max=300.0):
    v0s = sorted(SUZUKI_8_2)
    taus = np.round(np.arange(-0.01, 0.4001, 0.01), 10)
    s = Scene(damping=0.16)
    ds = sweep(s, over={"v0": v0s, "torque": taus}, measure="final_well", t_max=t_max)
    lk = sweep(s, over={"v0": v0s, "torque": taus}, measure="locked", t_max=t_max)
    rows = []
    for i, v in enumerate(v0s):
        st = ds.status.values[i]
        got = {int(x) for x in ds.well.values[i][st == 0]}
        run = taus[lk.locked.values[i] == 0]
        rows.append((v, sorted(got), sorted(SUZUKI_8_2[v]), float(run.min()) if run.size else math.nan))
    with open_text(out / "sweep_suzuki_8_2.csv") as f:
        f.write("v0,wells_pendula,wells_suzuki,first_running_tau\n")
        for v, g, sd, r in rows:
            f.write(f"{v},{' '.join(map(str, g))},{' '.join(map(str, sd))},{r}\n")
    return rows


def _suzuki_8_2_1():
    """Suzuki & Suzuki, section 8.2.1: beta = 0.16, v0 = 0.2, tau = 0 ... 0.8: where locking gives way to
    running, and the resting angle of locked orbits (single simulate runs) against asin(tau)."""
    from ..motion import simulate
    taus = np.round(np.arange(0.0, 0.8001, 0.01), 10)
    s = Scene(damping=0.16, v0=0.2)
    lk = sweep(s, over={"torque": taus}, measure="locked", t_max=500.0)
    locked = lk.locked.values == 1
    dev = max(abs(simulate(s.replace(torque=float(t), t_end=300.0, n_samples=2)).theta[-1] - math.asin(t))
              for t in taus[locked][::10])
    return {"last_locked": float(taus[locked].max()), "first_running": float(taus[lk.locked.values == 0].min()),
            "theta_s_vs_asin_tau": float(dev)}


def _iv(out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    taus = np.round(np.arange(0.0, 1.3001, 0.01), 10)
    r = iv_curve(Scene(damping=0.1), taus, "both", transient=100.0, t_max=200.0)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.5))
    a1.plot(r.torque, r.mean_velocity.sel(direction="up"), ".-", label="up")
    a1.plot(r.torque, r.mean_velocity.sel(direction="down"), ".-", label="down")
    a1.set_xlabel("torque tau (current)"); a1.set_ylabel("<v> (voltage)"); a1.legend()
    a1.set_title("RCSJ I-V loop, beta = 0.1, eps = 1")
    betas = np.array([0.02, 0.04, 0.08, 0.16, 0.3])
    tr = []
    for b in betas:
        t2 = np.round(np.arange(0.0, 1.0, 0.005), 10)   # run downwards from 0.995
        # a transient of several damping times 1/beta
        rr = iv_curve(Scene(damping=b, v0=1.0 / b), t2, "down", transient=max(60.0, 6.0 / b), t_max=120.0,
                      start="scene").sel(direction="down")
        running = rr.torque.values[rr.mean_velocity.values > 0]
        tr.append(running.min() if running.size else math.nan)
    tr = np.array(tr)
    a2.plot(betas, tr, "o", label="pendula (retrapping torque)")
    bb = np.linspace(0, 0.32, 50)
    a2.plot(bb, 4 * bb / math.pi, "-", label="Stewart-McCumber 4 beta / pi")
    a2.set_xlabel("beta"); a2.set_ylabel("tau_r"); a2.legend()
    fig.tight_layout(); save_figure(fig, out / "sweep_iv_loop.png", dpi=120); plt.close(fig)
    up = r.mean_velocity.sel(direction="up")
    switch = float(r.torque.values[up.values > 0].min())
    return {"switch_up": switch, "retrap": dict(zip(betas.tolist(), tr.tolist()))}


def _lyapunov_scene(na, n_tr, n_avg):
    tp = 2 * math.pi / (2.0 / 3.0)
    return Scene(damping=0.5, drive_frequency=2.0 / 3.0, drive_amplitude=1.0,
                 grid=("drive_amplitude",), grid1_range=(0.9, 1.5, na), measure="lyapunov",
                 sweep_transient=n_tr * tp, sweep_t_max=n_avg * tp, rtol=1e-9, atol=1e-11)


#: the gallery's Lyapunov sweep (data/scenes/sweeps/driven_lyapunov_small.nml) and the
#: full-size one (driven_lyapunov.nml): transient and window in drive periods
LYAPUNOV_SMALL = _lyapunov_scene(61, 200, 400)
LYAPUNOV_FULL = _lyapunov_scene(601, 300, 2000)


def _bifurcation(out, small):
    na, ns = (61, 32) if small else (601, 128)
    s = Scene(damping=0.5, drive_frequency=2.0 / 3.0, drive_amplitude=1.0,
              grid=("drive_amplitude",), grid1_range=(0.9, 1.5, na), measure="poincare",
              sweep_transient=300.0 * 2 * math.pi / (2 / 3), sweep_samples=ns, rtol=1e-9, atol=1e-11)
    ds = sweep(s)
    plot_sweep(ds, out / "sweep_bifurcation.png")
    counts = []
    for k in range(na):
        th = np.sort(ds.theta.values[k])
        counts.append(1 + int(np.sum(np.diff(th) > 1e-4)))
    counts = np.array(counts)
    amps = ds.drive_amplitude.values
    doubling = [(float(amps[k]), int(counts[k]), int(counts[k + 1])) for k in range(na - 1)
                if counts[k] in (1, 2, 4) and counts[k + 1] == 2 * counts[k]]
    return {"amplitudes": amps, "period": counts, "doublings": doubling, "dataset": ds}


def _lyapunov(out, small, bif):
    """The largest Lyapunov exponent against A (beta = 0.5, Omega = 2/3, eps = 1,
    A = 0.9 ... 1.5), drawn under the bifurcation diagram; the chaotic bands
    (lambda_1 > 3 err and > 0.01) against the diagram's (no stroboscopic point
    repeats among the samples)."""
    import time

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scene = LYAPUNOV_SMALL if small else LYAPUNOV_FULL
    t0 = time.perf_counter()
    ds = sweep(scene)
    seconds = time.perf_counter() - t0
    amps = ds.drive_amplitude.values
    lam, err = ds.lyapunov.values, ds.lyapunov_err.values
    chaotic = (lam > 3 * err) & (lam > 0.01)
    # the bifurcation diagram's verdict at the same amplitudes (its grid is the same A range)
    b = bif["dataset"]
    ns = b.sizes["sample"]
    per = np.interp(amps, b.drive_amplitude.values, bif["period"].astype(float))
    strobe_chaotic = per >= ns
    agree = float(np.mean(chaotic == strobe_chaotic))
    sum_rule = float(np.nanmax(np.abs(lam + ds.lyapunov2.values + scene.damping)))
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7.5, 7.0), sharex=True, gridspec_kw={"height_ratios": [3, 2]})
    x = np.repeat(b.drive_amplitude.values, ns)
    a1.plot(x, b.theta.values.ravel(), ".k", markersize=1.2, alpha=0.6)
    a1.set_ylabel("stroboscopic theta (mod 2 pi)")
    a1.set_title("driven damped pendulum, beta = 0.5, Omega = 2/3, eps = 1")
    a2.axhline(0.0, color="0.6", linewidth=0.8)
    a2.axhline(-scene.damping / 2, color="0.6", linewidth=0.8, linestyle=":")
    a2.errorbar(amps, lam, yerr=err, fmt=".-", markersize=3, linewidth=0.8, elinewidth=0.8,
                label="largest Lyapunov exponent (+- block standard error)")
    a2.fill_between(amps, -0.3, 0.2, where=chaotic, color="tab:red", alpha=0.15, step="mid",
                    label="chaotic: lambda_1 > 0")
    a2.set_ylim(-0.3, 0.2)
    a2.set_xlabel("drive amplitude A"); a2.set_ylabel("lambda_1")
    a2.legend(loc="upper left", fontsize=8)
    fig.tight_layout(); save_figure(fig, out / "sweep_lyapunov.png", dpi=120); plt.close(fig)
    bands = []
    for k, c in enumerate(chaotic):
        if c and (k == 0 or not chaotic[k - 1]):
            start = amps[k]
        if c and (k == len(amps) - 1 or not chaotic[k + 1]):
            bands.append((float(start), float(amps[k])))
    return {"points": int(amps.size), "seconds": seconds, "bands": bands, "agree_with_bifurcation": agree,
            "disagree_at": [float(a) for a in amps[chaotic != strobe_chaotic]],
            "max_sum_rule_error": sum_rule, "max_lambda": float(np.nanmax(lam)),
            "A_max": float(amps[np.nanargmax(lam)])}


def _band(a: float, b: float) -> str:
    return f"{a:.3f}" if a == b else f"{a:.3f}-{b:.3f}"


def report(res: dict, verbose: bool = False) -> list[str]:
    """The measured figures of the sweep gallery as lines of text: a few lines (every one
    named for its source text), or with ``verbose`` each Suzuki & Suzuki row as well."""
    b = res["basins"]
    lines = [f"  basins of the damped pendulum: {b['points']} points, {100 * b['decided']:.1f} % decided, "
             f"{b['uncertain']} uncertain;\n    a first-order energy balance misplaces "
             f"{100 * b['energy_balance_disagreement']:.0f} % of them"]
    rows = res["suzuki_8_2"]
    same = [v for v, g, sd, _ in rows if set(g) == set(sd)]
    differ = [v for v, g, sd, _ in rows if set(g) != set(sd)]
    if verbose:
        for v, g, sd, r in rows:
            flag = "" if set(g) == set(sd) else "  <- differs from the text"
            lines.append(f"  Suzuki & Suzuki 8.2, v0 = {v:4.2f}: wells {g} (the text {sd}); running from tau = {r:.2f}{flag}")
    else:
        lines.append(f"  Suzuki & Suzuki 8.2 (beta = 0.16): the wells agree with the text for v0 = "
                     + ", ".join(f"{v:g}" for v in same)
                     + (f";\n    for v0 = {', '.join(f'{v:g}' for v in differ)} the text also lists well 0, "
                        "which no torque reaches (a slip)" if differ else ""))
    r1 = res["suzuki_8_2_1"]
    lines.append(f"  Suzuki & Suzuki 8.2.1 (v0 = 0.2): locked up to tau = {r1['last_locked']:.2f}, running from "
                 f"{r1['first_running']:.2f} (the text: around 0.6-0.8);\n    rest angle = asin(tau) to "
                 f"{r1['theta_s_vs_asin_tau']:.0e}")
    lines.append(f"  I-V loop (beta = 0.1): runs from tau = {res['iv']['switch_up']:.2f}, the first torque above eps; "
                 "retrapped at "
                 + ", ".join(f"{v:.3f}" for v in res["iv"]["retrap"].values())
                 + "\n    for beta = " + ", ".join(f"{k:g}" for k in res["iv"]["retrap"])
                 + " (Stewart-McCumber's 4 beta/pi: " + ", ".join(f"{4 * k / math.pi:.3f}" for k in res["iv"]["retrap"])
                 + ")")
    d = res["bifurcation"]["doublings"]
    lines.append("  driven pendulum (beta = 0.5, Omega = 2/3): period doublings at A = "
                 + ", ".join(f"{a:.2f} ({p} -> {q})" for a, p, q in d))
    ly = res["lyapunov"]
    lines.append(f"  Lyapunov exponent over {ly['points']} amplitudes: chaotic (lambda_1 > 0) at A = "
                 + ", ".join(_band(a, b) for a, b in ly["bands"])
                 + f";\n    largest {ly['max_lambda']:.3f} at A = {ly['A_max']:.2f}")
    if verbose:
        lines.append(f"    agrees with the bifurcation diagram at {100 * ly['agree_with_bifurcation']:.0f} % of the "
                     f"amplitudes (not at A = {', '.join(f'{a:.3f}' for a in ly['disagree_at'])}); "
                     f"|lambda_1 + lambda_2 + beta| <= {ly['max_sum_rule_error']:.0e}; {ly['seconds']:.1f} s")
    return lines


def run(out, small: bool = True, quiet: bool = False, verbose: bool = True) -> dict:
    """Run the sweep gallery into folder ``out``; print its figures (all of them with
    ``verbose``, a few lines without; nothing when ``quiet``) and return them."""
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    res = {"basins": _basins(out, small), "suzuki_8_2": _suzuki_8_2(out), "suzuki_8_2_1": _suzuki_8_2_1(), "iv": _iv(out),
           "bifurcation": _bifurcation(out, small)}
    res["lyapunov"] = _lyapunov(out, small, res["bifurcation"])
    if not quiet:
        print("sweeps (Suzuki & Suzuki, sections 7-8; the driven pendulum, Baker & Gollub's parameters):")
        print("\n".join(report(res, verbose)))
    return res


def plot_sweep(ds, path) -> pathlib.Path:
    """A figure of a sweep: a map (2 axes; discrete colours for wells), a curve
    (1 axis), or a bifurcation diagram (poincare over 1 axis)."""
    matplotlib = require("matplotlib", "plot", "pendula.demos.sweeps.plot_sweep (figures)")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path = pathlib.Path(path)
    measure = ds.attrs["measure"]
    dims = [d for d in ds.dims if d != "sample"]
    var = {"final_well": "well", "locked": "locked", "mean_velocity": "mean_velocity", "poincare": "theta",
           "lyapunov": "lyapunov", "attractor": "attractor"}[measure]
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    if measure == "poincare":
        x = np.repeat(ds[dims[0]].values, ds.sizes["sample"])
        th = ds.theta.values.reshape(-1) if len(dims) == 1 else ds.theta.isel({d: 0 for d in dims[1:]}).values.ravel()
        ax.plot(x, th, ".k", markersize=1.5, alpha=0.6)
        ax.set_xlabel(_cf_label(ds, dims[0])); ax.set_ylabel("θ once per drive period, modulo 2π (rad)")
    elif len(dims) == 1:
        ax.plot(ds[dims[0]].values, ds[var].values, ".-")
        ax.set_xlabel(_cf_label(ds, dims[0])); ax.set_ylabel(_cf_label(ds, var))
    else:
        z = ds[var]
        if len(dims) > 2:
            z = z.isel({d: 0 for d in dims[2:]})
        z = z.transpose(dims[0], dims[1]).values
        x, y = ds[dims[0]].values, ds[dims[1]].values
        if measure in ("final_well", "locked", "attractor"):
            lo, hi = np.nanmin(z), np.nanmax(z)
            lo, hi = (0, 1) if not np.isfinite(lo) else (int(lo), int(hi))
            cmap = plt.get_cmap("tab20", hi - lo + 1)
            im = ax.imshow(z.T, origin="lower", aspect="auto", cmap=cmap, vmin=lo - 0.5, vmax=hi + 0.5,
                           extent=[x[0], x[-1], y[0], y[-1]], interpolation="nearest")
            fig.colorbar(im, ax=ax, ticks=range(lo, hi + 1), label=_cf_label(ds, var))
        else:
            im = ax.imshow(z.T, origin="lower", aspect="auto", extent=[x[0], x[-1], y[0], y[-1]])
            fig.colorbar(im, ax=ax, label=_cf_label(ds, var))
        ax.set_xlabel(_cf_label(ds, dims[0])); ax.set_ylabel(_cf_label(ds, dims[1]))
    from .._sweep_engine import MEASURE_TABLE
    words = MEASURE_TABLE[measure].words if measure in MEASURE_TABLE else "the attractor of each start"
    ax.set_title(words[:1].upper() + words[1:])
    fig.tight_layout()
    try:
        save_figure(fig, path, dpi=120)     # whole under its name, or absent
    finally:
        plt.close(fig)
    return path


def _cf_label(ds, name: str) -> str:
    """An axis label from a dataset's CF attributes: the long name and its units (none for '1')."""
    attrs = ds[name].attrs if name in ds.variables else {}
    text = str(attrs.get("long_name", name))
    units = str(attrs.get("units", "1"))
    return text if units in ("1", "") else f"{text} ({units})"

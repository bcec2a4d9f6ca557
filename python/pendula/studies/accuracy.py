"""Accuracy reports: measured worst errors against an independent reference.

``pendula accuracy elliptic [--reference data/elliptic_reference.csv]`` reads
the mpmath reference that data/gen_elliptic_reference.py stored and prints,
per function and region, the worst error of pendula, scipy.special and GSL on
exactly the same points (in units of eps; relative for K, E, F, E(phi), q,
absolute for sn, cn, dn).  Peers get the parameter the way their API takes it:
scipy.special.ellipj(u, m) and GSL take m, so for mc below 1e-16 they see
m = 1 and cannot know how close to the separatrix the point is; scipy's
ellipkm1 takes mc and is used for K there.
"""

from __future__ import annotations

import csv
import pathlib

import numpy as np
from .._optional import require
from .._files import save_figure, open_text  # the one writer: regular files only, whole or absent

EPS = np.finfo(np.float64).eps


#: the functions a reference file must hold (data/gen_elliptic_reference.py writes them all)
REFERENCE_FUNCTIONS = ("K", "E", "q", "F", "Einc", "j")


def _load(path):
    """The reference rows by function; a ValueError naming the file (and the line) when it is not one."""
    rows = {}
    line = 0
    try:
        with open(path, newline="") as fh:
            rd = csv.reader(fh)
            next(rd), next(rd)
            for r in rd:
                line = rd.line_num
                x = float(r[1]) if r[1] else np.nan
                rows.setdefault(r[0], []).append([x, float(r[2])] + [float(v) for v in r[3:] if v])
        table = {k: np.array(v, dtype=float) for k, v in rows.items()}
    except StopIteration:
        raise ValueError(f"{path}: not a reference file (empty, or without its two header lines)") from None
    except (ValueError, IndexError, csv.Error) as exc:    # UnicodeDecodeError is a ValueError
        where = f"line {line}: " if line else ""
        raise ValueError(f"{path}: {where}not a reference row ({type(exc).__name__}: {str(exc)[:80]})") from None
    missing = [k for k in REFERENCE_FUNCTIONS if k not in table or table[k].ndim != 2 or table[k].shape[1] < 3]
    if missing:
        raise ValueError(f"{path}: no rows of {', '.join(missing)} (a truncated or foreign file; "
                         "data/gen_elliptic_reference.py writes the reference)")
    return table


REGIONS = [
    ("m = 0", lambda mc, x: mc == 1.0),
    ("0 < m <= 0.99", lambda mc, x: (mc < 1.0) & (mc >= 0.01)),
    ("m near 1: 1e-16 <= mc < 0.01", lambda mc, x: (mc < 0.01) & (mc >= 1e-16)),
    ("m near 1: mc < 1e-16", lambda mc, x: (mc < 1e-16) & (mc > 0)),
]


def _worst(err):
    err = np.asarray(err, dtype=float)
    if err.size == 0:
        return "-"
    if np.any(~np.isfinite(err)):
        return "NaN/inf"
    w = err.max() / EPS
    return f"{w:.3g}" if w < 1e6 else f"{w:.1e}"


def elliptic_report(reference: str | pathlib.Path) -> list[dict]:
    """Worst errors per function and region: pendula, scipy.special, GSL."""
    sc = require("scipy.special", "accuracy", "pendula accuracy elliptic")

    from .. import _kernel
    from ..elliptic import ellipe, ellipeinc, ellipf, ellipj, ellipk, nome

    ref = _load(reference)
    out = []

    def add(func, region, pend, scipy_err, gsl_err, unit):
        out.append({"function": func, "region": region, "pendula": _worst(pend),
                    "scipy": _worst(scipy_err), "GSL": _worst(gsl_err), "unit": unit})

    with np.errstate(all="ignore"):
        import warnings
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for name, region, sel in [(n, r, f) for n in ("K", "E") for r, f in REGIONS]:
                data = ref[name]
                s = sel(data[:, 1], data[:, 0])
                mc, want = data[s, 1], data[s, 2]
                m = 1.0 - mc
                rel = lambda got: np.abs(got - want) / np.abs(want)  # noqa: E731
                if name == "K":
                    g, _ = _kernel.gsl_kcomp_v(np.ascontiguousarray(m))
                    add("K", region, rel(ellipk(None, mc=mc)), rel(sc.ellipkm1(mc)), rel(g), "eps rel")
                else:
                    add("E", region, rel(ellipe(None, mc=mc)), rel(sc.ellipe(m)), [], "eps rel")
            data = ref["q"]
            for region, sel in REGIONS[1:]:
                s = sel(data[:, 1], data[:, 0])
                mc, want = data[s, 1], data[s, 2]
                add("nome q", region, np.abs(nome(None, mc=mc) - want) / want, [], [], "eps rel")
            for name, fn, sfn in (("F(phi|m)", ellipf, sc.ellipkinc), ("E(phi|m)", ellipeinc, sc.ellipeinc)):
                data = ref["F" if name.startswith("F") else "Einc"]
                for region, sel in REGIONS:
                    s = sel(data[:, 1], data[:, 0])
                    phi, mc, want = data[s, 0], data[s, 1], data[s, 2]
                    rel = lambda got: np.abs(got - want) / np.abs(want)  # noqa: E731
                    add(name, region, rel(fn(phi, None, mc=mc)), rel(sfn(phi, 1.0 - mc)), [], "eps rel")
            data = ref["j"]
            inside = (data[:, 1] >= 0) & (data[:, 1] <= 1)
            for region, sel in REGIONS:
                for span, spansel in (("|u| <= 2 periods", lambda u, K: np.abs(u) <= 8 * K),
                                      ("u ~ 1000 periods", lambda u, K: np.abs(u) > 8 * K)):
                    mcall = data[:, 1]
                    K = ellipk(None, mc=np.where(inside, mcall, 0.5))
                    s = inside & sel(mcall, data[:, 0]) & spansel(data[:, 0], K)
                    if not np.any(s):
                        continue
                    u, mc, want = data[s, 0], data[s, 1], data[s, 2:5]
                    m = 1.0 - mc
                    absmax = lambda a, b, c: np.max(np.abs(np.stack([a, b, c], 1) - want), axis=1)  # noqa: E731
                    p = ellipj(u, None, mc=mc)
                    q = sc.ellipj(u, m)
                    g = _kernel.gsl_elljac_v(np.ascontiguousarray(u), np.ascontiguousarray(m))
                    add("sn, cn, dn", f"{region}, {span}", absmax(*p[:3]), absmax(*q[:3]), absmax(*g[:3]),
                        "eps abs")
    return out


def print_report(rows: list[dict], markdown: bool = False) -> None:
    if markdown:
        print("| function | region | pendula | scipy.special | GSL | unit |")
        print("|---|---|---:|---:|---:|---|")
        for r in rows:
            print(f"| {r['function']} | {r['region']} | {r['pendula']} | {r['scipy']} | {r['GSL']} | {r['unit']} |")
        return
    print(f"{'function':12s} {'region':52s} {'pendula':>9s} {'scipy':>9s} {'GSL':>9s}  unit")
    for r in rows:
        print(f"{r['function']:12s} {r['region']:52s} {r['pendula']:>9s} {r['scipy']:>9s} {r['GSL']:>9s}  {r['unit']}")


# ====================================================================
# What accuracy costs in time: the work-precision study of the integrators
# ====================================================================

def work_precision(outdir, quick: bool = False, progress: bool = True, record_to=None,
                   problems=None) -> list[pathlib.Path]:
    """The work-precision study of the integrators against the peers (pendula.studies.workprecision):
    the record work_precision.json and one figure per problem into outdir; quick: the short form
    of ``make demo`` (one problem, four tolerances)."""
    from .workprecision_report import study_main

    return study_main(outdir, quick=quick, progress=progress, record_to=record_to, problems=problems)


def long_run_energy(periods: float = 1e5, methods=("gauss6", "dop853"), progress: bool = True) -> dict:
    """Energy error of a long run (v0 = 1, eps = 1: a libration of period 6.743) at
    log-spaced times; returns per method the times, |E - E0| and the fitted growth
    exponent of its RMS in log bins (Brouwer's law: 1/2 for Gauss with
    compensated summation; 1 for the linear drift of a non-symplectic method)."""
    import time

    from ..integrate import integrate_scene
    from ..motion import orbit
    from ..scene import Scene

    P = orbit(0.0, 1.0, 1.0).period
    t = np.unique(np.concatenate([np.geomspace(P, periods * P, 400), [0.0]]))
    out = {}
    for method in methods:
        if method == "gauss6":
            # P/200: truncation (~3e-14) below the round-off the long run accumulates
            scene = Scene(v0=1.0, dt=P / 200, method=method, t_end=t[-1])
        else:
            scene = Scene(v0=1.0, rtol=1e-12, atol=1e-14, method=method, t_end=t[-1])
        t0 = time.perf_counter()
        tr = integrate_scene(scene, t, method)
        el = time.perf_counter() - t0
        dE = np.abs(tr.energy - 0.5)
        # RMS of |dE| in 10 log bins of t, fitted against t on log-log axes
        edges = np.geomspace(P, t[-1] * 1.0001, 11)
        tc, rms = [], []
        for a, b in zip(edges[:-1], edges[1:]):
            sel = (t >= a) & (t < b)
            if sel.any() and np.any(dE[sel] > 0):
                tc.append(np.sqrt(a * b))
                rms.append(np.sqrt(np.mean(dE[sel] ** 2)))
        slope = float(np.polyfit(np.log(tc), np.log(rms), 1)[0]) if len(tc) > 2 else float("nan")
        out[method] = {"t": t, "dE": dE, "exponent": slope, "seconds": el, "stats": tr.stats}
        if progress:
            print(f"long run {method}: {periods:.0e} periods in {el:.1f} s, |dE| max {dE.max():.2e}, "
                  f"fitted growth exponent {slope:.2f}")
    return out


def write_long_run(res: dict, outdir, periods: float) -> list[pathlib.Path]:
    matplotlib = require("matplotlib", "accuracy", "pendula accuracy integrators (figures)")

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    outdir = pathlib.Path(outdir)
    fig, ax = plt.subplots(figsize=(8, 5))
    for method, r in res.items():
        sel = r["t"] > 0
        ax.loglog(r["t"][sel], np.maximum(r["dE"][sel], 1e-18), ".", ms=2,
                  label=f"{method}: growth exponent {r['exponent']:.2f}")
    ax.set_xlabel("t")
    ax.set_ylabel("|E(t) - E0|")
    ax.set_title(f"energy error over {periods:.0e} periods (v0 = 1): Brouwer's law vs drift", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path = outdir / "long_run_energy.png"
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    csv_path = outdir / "long_run_energy.csv"
    with open_text(csv_path, newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["method", "t", "abs_energy_error"])
        for method, r in res.items():
            for ti, e in zip(r["t"], r["dE"]):
                w.writerow([method, repr(float(ti)), repr(float(e))])
    return [path, csv_path]


# ---------------------------------------------------------------- random reference grids

#: the error measure of the grids: max over outputs of |got - ref| / max(1, |ref|)
#: (absolute for values below 1, relative above), in units of eps
GRID_CLASSES = {
    "jac": "sn, cn, dn", "am": "am(u|m)", "k": "K(m)", "e": "E(m)", "nome": "q(m)", "f": "F(phi|m)", "einc": "E(phi|m)",
    "exact": "theta(t), v(t)", "period": "period",
}


def load_grids(path) -> dict[str, np.ndarray]:
    """The stored grid (data/reference_grids.csv.gz): class -> rows of inputs and reference values."""
    import gzip

    rows: dict[str, list] = {}
    with gzip.open(path, "rt") as fh:
        rd = csv.reader(line for line in fh if not line.startswith("#"))
        next(rd)
        for r in rd:
            rows.setdefault(r[0], []).append([float(v) if v else np.nan for v in r[1:]])
    return {k: np.array(v) for k, v in rows.items()}


def grid_errors(cls: str, a: np.ndarray) -> np.ndarray:
    """pendula's error (in eps) at every point of one class of the grid."""
    import warnings

    from ..elliptic import ellipe, ellipeinc, ellipf, ellipj, ellipk, nome
    from ..systems.rigid import exact_motion, orbit

    kind = cls.split("_")[0]
    via_mc = cls.endswith("_mc")

    def par(x):
        return (None, x) if via_mc else (x, None)

    def err(got, ref):
        got = np.atleast_2d(np.asarray(got, dtype=float))
        ref = np.atleast_2d(np.asarray(ref, dtype=float))
        e = np.abs(got - ref) / np.maximum(1.0, np.abs(ref))
        e[np.isnan(got) != np.isnan(ref)] = np.inf
        return np.nan_to_num(e, nan=0.0).max(axis=0) / EPS

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        if kind == "jac":
            res = []
            for u, x in a[:, :2]:
                m, mc = par(x)
                res.append(ellipj(u, m, mc=mc)[:3])
            return err(np.array(res).T, a[:, 4:7].T)
        if kind == "am":
            got = [ellipj(u, *par(x)[:1], mc=par(x)[1])[3] for u, x in a[:, :2]]
            return err(got, a[:, 4])
        if kind in ("k", "e", "nome"):
            f = {"k": ellipk, "e": ellipe, "nome": nome}[kind]
            got = [f(*par(x)[:1], mc=par(x)[1]) if via_mc else f(x) for x in a[:, 0]]
            return err(got, a[:, 4])
        if kind in ("f", "einc"):
            f = ellipf if kind == "f" else ellipeinc
            got = [f(phi, None, mc=x) if via_mc else f(phi, x) for phi, x in a[:, :2]]
            return err(got, a[:, 4])
        if kind == "exact":
            res = [np.concatenate(exact_motion(th0, v0, eps, [t])) for th0, v0, eps, t in a[:, :4]]
            return err(np.array(res).T, a[:, 4:6].T)
        if kind == "period":
            return err([orbit(th0, v0, eps).period for th0, v0, eps in a[:, :3]], a[:, 4])
    raise ValueError(f"unknown class {cls!r}")


def grid_paths(path) -> list[pathlib.Path]:
    """The stored grids: `path` (data/reference_grids.csv.gz) and, when it is
    there, the set of ill-conditioned places beside it (reference_grids_edges.csv.gz)."""
    path = pathlib.Path(path)
    edges = path.with_name("reference_grids_edges.csv.gz")
    return [path] + ([edges] if edges.is_file() and edges != path else [])


#: the bound of every class, in eps: 4 (README's promise) unless a measured,
#: explained limit is stated here
GRID_BOUND = 4.0
GRID_LIMITS: dict[str, float] = {}


def grid_bound(cls: str) -> float:
    """The bound (eps) a class of the grids is held to."""
    return float(GRID_LIMITS.get(cls, GRID_BOUND))


def grids_report(path) -> list[dict]:
    """Worst error (eps) per class of the stored random grids (`path` and the
    edge set beside it, see grid_paths)."""
    out = []
    for p in grid_paths(path):
        for cls, a in sorted(load_grids(p).items()):
            e = grid_errors(cls, a)
            k = int(np.argmax(e))
            out.append({"class": cls, "what": GRID_CLASSES[cls.split("_")[0]], "points": len(a),
                        "worst_eps": float(e[k]), "bound_eps": grid_bound(cls), "at": a[k, :4].tolist()})
    return out


#: README's rows of the grid table: (function, class as README words it, class key)
GRID_ROWS = [("sn, cn, dn", "m > 1 via m", "jac_m_gt1_m"), ("sn, cn, dn", "m > 1 via mc < 0", "jac_m_gt1_mc"),
        ("sn, cn, dn", "0.5 ≤ m < 1 via m", "jac_m_mid"), ("sn, cn, dn", "m = 1 − 10^−x via m (x ≤ 16)", "jac_m_near1_m"),
        ("sn, cn, dn", "mc in [1e-300, 0.5] via mc", "jac_m_near1_mc"), ("sn, cn, dn", "m < 0 via m (\\|m\\| to 1e4)", "jac_m_neg"),
        ("sn, cn, dn", "m from −1e3 to −1e100 (theta series of the core)", "jac_m_neg_far"),
        ("sn, cn, dn", "0 ≤ m < 0.5 via m, \\|u\\| to 1e4 periods", "jac_m_small"),
        ("am", "0 ≤ m < 0.5 via m, \\|u\\| to 1e4 periods", "am_m_small"), ("am", "0.5 ≤ m < 1 via m", "am_m_mid"),
        ("am", "mc in [1e-300, 0.5] via mc", "am_m_near1_mc"), ("am", "m < 0 via m (\\|m\\| to 1e12)", "am_m_neg"),
        ("am", "m > 1 via m", "am_m_gt1_m"), ("am", "m > 1 via mc < 0", "am_m_gt1_mc"),
        ("am", "m > 1 via m, next to sn = ±1/k", "am_edge_m"),
        ("am", "m − 1 down to 1e-100 via mc, next to sn = ±1/k", "am_edge_mc"),
        ("K", "0.5 ≤ m < 1", "k_mid"), ("K", "mc in [1e-300, 0.5] via mc", "k_near1_mc"), ("K", "m < 0", "k_neg"),
        ("K", "0 ≤ m < 0.5", "k_small"), ("E", "0.5 ≤ m < 1", "e_mid"), ("E", "mc in [1e-300, 0.5] via mc", "e_near1_mc"),
        ("E", "m < 0", "e_neg"), ("E", "0 ≤ m < 0.5", "e_small"), ("nome q", "0 ≤ m ≤ 1 via m", "nome_m"),
        ("nome q", "via mc down to 1e-300", "nome_mc"), ("F(φ|m)", "m > 1, φ up to the domain's edge", "f_gt1_m"),
        ("F(φ|m)", "m > 1 via m, φ next to the edge (both sides)", "f_edge_m"),
        ("F(φ|m)", "m > 1 via mc < 0, φ next to the edge (both sides)", "f_edge_mc"),
        ("F(φ|m)", "m ≤ 1 via m, \\|φ\\| to 1e4 π", "f_m"), ("F(φ|m)", "via mc", "f_near1_mc"),
        ("F(φ|m)", "φ next to N π/2, m in [−10, 1) via m", "f_halfpi_m"),
        ("F(φ|m)", "φ next to N π/2, mc down to 1e-300", "f_halfpi_mc"),
        ("E(φ|m)", "m > 1, φ up to the domain's edge", "einc_gt1_m"),
        ("E(φ|m)", "m > 1 via m, φ next to the edge (both sides)", "einc_edge_m"),
        ("E(φ|m)", "m > 1 via mc < 0, φ next to the edge (both sides)", "einc_edge_mc"),
        ("E(φ|m)", "m ≤ 1 via m", "einc_m"), ("E(φ|m)", "via mc", "einc_near1_mc"),
        ("E(φ|m)", "φ next to N π/2, m in [−10, 1) via m", "einc_halfpi_m"),
        ("E(φ|m)", "φ next to N π/2, mc down to 1e-300", "einc_halfpi_mc"),
        ("θ(t), v(t)", "libration, backward", "exact_libration_bwd"),
        ("θ(t), v(t)", "libration, forward (t to 1e4 periods)", "exact_libration_fwd"),
        ("θ(t), v(t)", "near the separatrix, backward", "exact_near_separatrix_bwd"),
        ("θ(t), v(t)", "1 ∓ 1e-15…1e-3 from the separatrix, forward", "exact_near_separatrix_fwd"),
        ("θ(t), v(t)", "near the top, backward", "exact_near_top_bwd"),
        ("θ(t), v(t)", "at rest or slow just below the top, forward", "exact_near_top_fwd"),
        ("θ(t), v(t)", "rotation, backward", "exact_rotation_bwd"), ("θ(t), v(t)", "rotation, forward", "exact_rotation_fwd"),
        ("θ(t), v(t)", "wrapped, backward", "exact_wrapped_bwd"),
        ("θ(t), v(t)", "\\|θ0\\| up to 1e3 (wrapped), forward", "exact_wrapped_fwd"),
        ("θ(t), v(t)", "\\|θ0\\| from 1e3 to 2^52, backward", "exact_huge_theta0_bwd"),
        ("θ(t), v(t)", "\\|θ0\\| from 1e3 to 2^52, forward", "exact_huge_theta0_fwd"),
        ("period", "librations", "period_libration"), ("period", "rotations", "period_rotation")]


def grids_markdown(path) -> str:
    """The accuracy report's table (docs/source/reports/accuracy.md) of the worst error per class of
    the stored random grids (``pendula accuracy grids``): the points of each class, its worst error and
    the bound the tests hold it to, in eps."""
    rep = {r["class"]: r for r in grids_report(path)}
    missing = {c for *_, c in GRID_ROWS} ^ set(rep)
    if missing:
        raise ValueError(f"grid classes and README rows disagree: {sorted(missing)}")
    lines = ["| function | class (random draws) | points | worst (eps) | bound (eps) |", "|---|---|---:|---:|---:|"]
    lines += [f"| {f} | {d} | {rep[c]['points']} | {rep[c]['worst_eps']:.3g} | {rep[c]['bound_eps']:.3g} |"
              for f, d, c in GRID_ROWS]
    return "\n".join(lines)


def model_grids_markdown(path) -> str:
    """The models' grid table (data/model_grids.csv.gz: gravity, the angle density, the
    cycloid, the cord's flips, the events): worst error per class and its tolerance
    (see pendula.studies.model_grids)."""
    from .model_grids import markdown

    return markdown(path)


# ------------------------------------------------------------ the hard cases (data/hard_cases.csv.gz)

#: class -> (what it is, the bound the tests hold its worst error to, in eps)
HARD_CASES = {
    "tiny": ("|v0|, theta0, eps down to the smallest normal and subnormal (every public function of "
             "an orbit); relative to max(|ref|, 2^-1022)", 4.0),
    "einc_above_one": ("E(phi|m), F(phi|m) next to odd multiples of pi/2, m - 1 from 1e-16 to 1e-300", 4.0),
    "inverse_square_near_one": ("gravity_orbit, inverse-square field, d - 1 from 0.3 to 1e-4", 4.0),
    "separatrix_long_time": ("exact_motion 1e-15 to 1e-3 above the separatrix, up to 1e3 turns "
                             "(v relative to 2 k sqrt(eps))", 4.0),
    "ellip_huge_m_edge": ("F(phi|m), E(phi|m) for m from 1e270 to 1.7e308 next to the edge "
                          "(m sin^2 phi in (1/2, 1]), relative", 4.0),
    "ellip_tiny_phi_huge_m": ("F(phi|m), E(phi|m) for |m| from 1e200 to 1.7e308 and tiny phi "
                              "(|m| phi^2 from 1e-6 to 1e6), relative", 4.0),
    "jacobi_m_far_below_zero": ("sn, cn, dn(u|m) for m from -2 to -1e300 at 1e3 to 3e13 quarter "
                                "periods (dn relative)", 4.0),
    "periodic_exact": ("periodic inputs up to 2^52: angle density and CDF of a rotation, energy, "
                       "gravity_orbit's theta0, F and E(phi)'s phi", 4.0),
}


def hard_case_values(func: str, args: list) -> dict:
    """pendula's outputs for one row of data/hard_cases.csv.gz (func and its arguments)."""
    import types
    import warnings

    from ..density import angle_cdf, angle_density
    from ..elliptic import ellipeinc, ellipf, ellipj
    from ..scene import Scene
    from ..systems.gravity import gravity_orbit
    from ..systems.rigid import energy, exact_motion, orbit

    pendula = types.SimpleNamespace(orbit=orbit, exact_motion=exact_motion, energy=energy,
                                    gravity_orbit=gravity_orbit, angle_density=angle_density,
                                    angle_cdf=angle_cdf, ellipeinc=ellipeinc, ellipf=ellipf,
                                    ellipj=ellipj)

    def scene(kind, par, eps, theta0, v0):
        kw = {"gravity_distance": par} if kind == "inverse-square" else \
            {"gravity_gradient": par} if kind == "linear" else {}
        return Scene(gravity=kind, eps=eps, theta0=theta0, v0=v0, **kw)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        if func == "orbit":
            o = pendula.orbit(*args)
            return {"k": o.k, "theta_max": o.theta_max, "period": o.period}
        if func == "exact_motion":
            th, v = pendula.exact_motion(args[0], args[1], args[2], [args[3]])
            return {"theta": th[0], "v": v[0]}
        if func == "energy":
            return {"energy": float(pendula.energy(*args))}
        if func == "gravity_orbit":
            o = pendula.gravity_orbit(scene(*args))
            return {"energy": o.energy, "theta_max": o.theta_max, "period": o.period}
        if func == "angle_density":
            return {"density": float(pendula.angle_density(scene(*args[:5]), args[5]))}
        if func == "angle_cdf":
            return {"cdf": float(pendula.angle_cdf(scene(*args[:5]), args[5]))}
        if func == "ellip_m":
            phi, m = args
            return {"ellipeinc": float(pendula.ellipeinc(phi, m)), "ellipf": float(pendula.ellipf(phi, m))}
        if func == "ellipj":
            sn, cn, dn = pendula.ellipj(args[0], args[1])[:3]
            return {"sn": float(sn), "cn": float(cn), "dn": float(dn)}
        if func == "ellip":
            phi, mc = args
            return {"ellipeinc": float(pendula.ellipeinc(phi, None, mc=mc)),
                    "ellipf": float(pendula.ellipf(phi, None, mc=mc))}
    raise ValueError(f"hard case: unknown function {func!r}")


def load_hard_cases(path) -> list[dict]:
    """The rows of data/hard_cases.csv.gz: set, cls, func, args (decoded), quantity, ref, floor."""
    import gzip
    import json

    with gzip.open(path, "rt") as fh:
        rd = csv.DictReader(fh)
        rows = []
        for r in rd:
            r["args"] = [float(a) if isinstance(a, str) and a not in ("uniform", "inverse-square", "linear")
                         else a for a in json.loads(r["args"])]
            rows.append(r)
    return rows


def hard_case_errors(rows: list[dict]) -> list[dict]:
    """Each row with pendula's value and its error in eps: |got - ref| / max(|ref|, floor) / eps
    (a NaN or a missing value where the reference is finite counts as inf)."""
    from decimal import Decimal

    cache = {}
    out = []
    for r in rows:
        key = (r["func"], tuple(r["args"]))
        if key not in cache:
            try:
                cache[key] = hard_case_values(r["func"], list(r["args"]))
            except (ValueError, ArithmeticError) as e:      # refused: no value to compare
                cache[key] = {"error": str(e)}
        got = cache[key].get(r["quantity"], float("nan"))
        ref = Decimal(r["ref"])
        floor = Decimal(r["floor"])
        if abs(ref) > Decimal(np.finfo(np.float64).max) and np.isinf(got) and (got > 0) == (ref > 0):
            err = 0.0                                       # beyond double: inf is the right answer
        elif not np.isfinite(got):
            err = float("inf")
        else:
            err = float(abs(Decimal(got) - ref) / max(abs(ref), floor) / Decimal(EPS))
        out.append({**r, "got": got, "err_eps": err, "cond": float(r.get("cond") or 0.0)})
    return out


def hard_case_tolerance(e: dict) -> float:
    """The bound a hard case is held to, in eps: its class's (4) plus twice the condition number stored
    with the row (nonzero for the rotation's density and CDF: the conditioning in the reduced angle)."""
    return HARD_CASES[e["cls"]][1] + 2.0 * e["cond"]


def hard_cases_report(path) -> list[dict]:
    """Worst error per (set, class, function, quantity) of the stored hard cases."""
    worst: dict = {}
    for e in hard_case_errors(load_hard_cases(path)):
        k = (e["set"], e["cls"], e["func"], e["quantity"])
        w = worst.setdefault(k, {"set": k[0], "class": k[1], "function": k[2], "quantity": k[3],
                                 "points": 0, "worst_eps": 0.0, "bound_eps": 0.0, "worst_ratio": 0.0})
        w["points"] += 1
        if e["err_eps"] >= w["worst_eps"]:
            w["worst_eps"], w["bound_eps"] = e["err_eps"], hard_case_tolerance(e)
        w["worst_ratio"] = max(w["worst_ratio"], e["err_eps"] / hard_case_tolerance(e))
    return sorted(worst.values(), key=lambda w: (w["set"] != "reproducer", w["class"], w["function"],
                                                  w["quantity"]))


def hard_cases_markdown(path) -> str:
    """The accuracy report's table of the hard cases: the reproducers and the hunt around each."""
    lines = ["| set | class | function | quantity | points | worst (eps) | bound there (eps) | worst error / bound |",
             "|---|---|---|---|---:|---:|---:|---:|"]
    lines += [f"| {w['set']} | {w['class']} | {w['function']} | {w['quantity']} | {w['points']} | "
              f"{w['worst_eps']:.3g} | {w['bound_eps']:.3g} | {w['worst_ratio']:.2g} |"
              for w in hard_cases_report(path)]
    return "\n".join(lines)

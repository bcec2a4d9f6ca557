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

EPS = np.finfo(np.float64).eps


def _load(path):
    rows = {}
    with open(path) as fh:
        rd = csv.reader(fh)
        next(rd), next(rd)
        for r in rd:
            x = float(r[1]) if r[1] else np.nan
            rows.setdefault(r[0], []).append([x, float(r[2])] + [float(v) for v in r[3:] if v])
    return {k: np.array(v) for k, v in rows.items()}


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
    import scipy.special as sc

    from . import _kernel, ellipe, ellipeinc, ellipf, ellipj, ellipk, nome

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

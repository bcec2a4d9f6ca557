"""The models' random reference grids (data/model_grids.csv.gz, written by
data/gen_model_grids.py): pendula's error at every point, and the tolerance
of every class.

The error of one output is |got - ref| / (eps max(|ref|, scale)) with
eps = 2^-52 (scale 0: relative; the CDF has scale 1; the geometry the radius
R).  Each row carries the condition number ``cond`` of its quantity: the sum
over the exact double inputs x_i of |dy/d ln x_i| / max(|y|, scale), so that a
perturbation of every input by one rounding moves the quantity by about
cond eps.  A class's tolerance is ``A + B cond`` eps (TOLERANCES: A, B and
the reason); a regime must be the same word.
"""

from __future__ import annotations

import csv
import gzip
import math
import warnings

import numpy as np

EPS = 2.0 ** -52

#: class family -> (A, B, reason): the tolerance A + B cond in eps
TOLERANCES = {
    "gravity_orbit": (4.0, 2.0, "the distance from the separatrix in double-double: a few roundings, plus the "
                                "condition number where the state itself is ill-conditioned (the period "
                                "next to the separatrix, theta_max next to the top)"),
    "angle_cdf": (4.0, 2.0, "absolute (scale 1); F from sin and cos of phi: a few roundings plus the condition "
                            "number (next to a turning point the CDF moves by the density times the "
                            "amplitude's rounding)"),
    "angle_density": (4.0, 2.0, "relative; next to a turning point the density ~ 1/sqrt(theta_max - theta) is "
                                "as ill-conditioned as theta_max - theta"),
    "cycloid_period": (4.0, 0.0, "2 pi / sqrt(eps / (4 R)): four roundings"),
    "cycloid_geometry": (4.0, 1.0, "absolute in units of R; the nodes' rounding times the slope"),
    "cycloid_motion": (4.0, 2.0, "the over-damped slow mode -w2 / (h + mu) without cancellation"),
    "cord_flip": (8.0, 2.0, "Garfinkel's closed forms through the exact circle motion and the closed-form "
                            "flight; the kernel forms xi from the state at departure, a few roundings more"),
    "find_events": (0.0, 0.0, "the integrator's: |dt| <= 200 rtol t (1 + cond) at rtol = 1e-12 (an adaptive "
                              "step perturbs the state by about rtol; cond, the event time's sensitivity to the "
                              "state, is large next to the separatrix)"),
    "numerical_period": (0.0, 0.0, "the integrator's: |dT| <= 100 rtol T (1 + cond) at rtol = 1e-10, the scene's "
                                   "default (numerical_period tightens it next to the separatrix)"),
}
EVENT_RTOL = 1e-12
EVENT_FACTOR = 200.0
PERIOD_FACTOR = 100.0

_FIELDS = {"uniform": {}, "inverse-square": "gravity_distance", "linear": "gravity_gradient"}


def load(path) -> list[dict]:
    """Rows of the stored grid as dicts (inputs as the exact doubles written by repr)."""
    out = []
    with gzip.open(path, "rt", newline="") as fh:
        rd = csv.DictReader(fh)
        for r in rd:
            out.append(r)
    return out


def _f(x):
    return float(x) if x not in ("", None) else math.nan


def _scene(field, eps, par, theta0, v0):
    from ..scene import Scene

    kw = dict(theta0=theta0, v0=v0, eps=eps)
    if field != "uniform":
        kw.update(gravity=field, **{_FIELDS[field]: par})
    return Scene(**kw)


def _err(got, ref, scale):
    if math.isinf(ref) or math.isinf(got):
        return 0.0 if got == ref else math.inf
    if math.isnan(got):
        return math.inf
    return abs(got - ref) / (EPS * max(abs(ref), scale))


def evaluate(rows: list[dict]) -> list[dict]:
    """pendula's error (eps) and the tolerance (eps) at every row."""
    from ..density import angle_cdf, angle_density
    from ..integrate import find_events, numerical_period
    from ..motion import simulate
    from ..scene import Scene
    from ..systems.cycloid import cycloid_geometry, cycloid_motion, cycloid_period
    from ..systems.gravity import gravity_orbit

    out = []
    cache: dict = {}
    for r in rows:
        cls, q = r["cls"], r["quantity"]
        fam = cls.split("/")[0]
        x = [_f(r[f"x{i}"]) for i in range(6)]
        cond, scale = _f(r["cond"]), _f(r["scale"])
        A, B, _ = TOLERANCES[fam]
        tol = A + B * cond
        if fam == "gravity_orbit":
            field = cls.split("/")[1]
            key = (cls, *x[:4])
            if key not in cache:
                cache[key] = gravity_orbit(_scene(field, *x[:4]))
            o = cache[key]
            if q == "regime":
                ref = {0: "libration", 1: "separatrix", 2: "rotation"}[int(r["ref"])]
                err = 0.0 if o.regime == ref else math.inf
            else:
                err = _err(getattr(o, q), _f(r["ref"]), 0.0)
        elif fam in ("angle_cdf", "angle_density"):
            field = cls.split("/")[1]
            f = angle_cdf if fam == "angle_cdf" else angle_density
            err = _err(float(f(_scene(field, *x[:4]), x[4])), _f(r["ref"]), scale)
        elif fam == "cycloid_period":
            err = _err(cycloid_period(Scene(guide="cycloid", eps=x[0], cycloid_radius=x[1])), _f(r["ref"]), 0.0)
        elif fam == "cycloid_geometry":
            R, n, j, phi = x[0], int(x[1]), int(x[2]), x[3]
            key = ("geometry", R, n)
            if key not in cache:
                cache[key] = cycloid_geometry(R, n)
            g = cache[key]
            curve, axis = q.split("_")
            arr = {"path": g.path, "cheek": g.cheek_right, "circle": g.circle}[curve]
            got = float(arr[0 if axis == "x" else 1, j])
            # the reference is at the stored node: the same double as numpy's linspace gives here
            err = _err(got, _f(r["ref"]), scale) if np.linspace(-math.pi, math.pi, n)[j] == phi else math.inf
        elif fam == "cycloid_motion":
            eps, R, beta, th0, v0, t = x
            sc = Scene(guide="cycloid", eps=eps, cycloid_radius=R, damping=beta, theta0=th0, v0=v0)
            err = _err(float(cycloid_motion(sc, [t])[0][0]), _f(r["ref"]), 0.0)
        elif fam == "cord_flip":
            eps, th0, v0 = x[:3]
            key = ("cord", eps, th0, v0)
            if key not in cache:
                sc = Scene(cord="flexible", eps=eps, theta0=th0, v0=v0, max_flips=1,
                           t_end=200.0 / math.sqrt(eps), n_samples=2)
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", RuntimeWarning)   # NaN after the one-flip stop
                    cache[key] = simulate(sc).flips
            fl = cache[key]
            ref = _f(r["ref"])
            if q == "flight":
                got = float(fl["t_return"][0] - fl["t_leave"][0])
            elif q == "theta_return":
                # theta_2 = 2 pi - 3 theta_1 modulo 2 pi (Garfinkel eq. 13)
                got = float(fl["theta_return"][0])
                got = ref + math.remainder(got - ref, 2 * math.pi)
            else:
                got = float(fl[q][0])
            err = _err(got, ref, 0.0)
        elif fam == "find_events":
            eps, th0, v0, level, j, T = x
            kind = cls.split("/")[1]
            ref = _f(r["ref"])
            sc = Scene(theta0=th0, v0=v0, eps=eps, rtol=EVENT_RTOL, atol=EVENT_RTOL * 1e-2)
            if kind == "turning":
                ev = find_events(sc, "turning", direction=-1, t_end=ref + 0.25 * T)
            else:
                ev = find_events(sc, "theta", level=level, direction=0, t_end=ref + 0.25 * T)
            got = float(ev.t[int(j)]) if ev.t.size > int(j) else math.nan
            err = abs(got - ref) / EPS if math.isfinite(got) else math.inf
            tol = EVENT_FACTOR * EVENT_RTOL * ref * (1 + cond) / EPS
        elif fam == "numerical_period":
            eps, th0, v0 = x[:3]
            ref = _f(r["ref"])
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                got = numerical_period(Scene(theta0=th0, v0=v0, eps=eps))
            err = _err(got, ref, 0.0)
            tol = PERIOD_FACTOR * 1e-10 * (1 + cond) / EPS
        else:
            raise ValueError(f"unknown class {cls!r}")
        out.append({"cls": cls, "quantity": q, "err": err, "tol": tol, "cond": cond, "row": r})
    return out


def report(path) -> list[dict]:
    """Worst error (eps), its tolerance and the worst ratio error / tolerance per class and quantity."""
    res = evaluate(load(path))
    groups: dict = {}
    for e in res:
        groups.setdefault((e["cls"], e["quantity"]), []).append(e)
    out = []
    for (cls, q), es in sorted(groups.items()):
        worst = max(es, key=lambda e: e["err"])
        ratio = max(es, key=lambda e: e["err"] / e["tol"] if e["tol"] > 0 else (0 if e["err"] == 0 else math.inf))
        out.append({"class": cls, "quantity": q, "points": len(es), "worst_eps": worst["err"],
                    "tol_at_worst": worst["tol"], "cond_at_worst": worst["cond"],
                    "worst_ratio": (ratio["err"] / ratio["tol"]) if ratio["tol"] > 0 else
                    (0.0 if ratio["err"] == 0 else math.inf),
                    "at": {k: v for k, v in worst["row"].items() if k.startswith("x") and v}})
    return out


def markdown(path) -> str:
    """The table of the worst error per class (``pendula accuracy grids``)."""
    lines = ["| class | quantity | points | worst (eps) | tolerance there (eps) | worst error / tolerance |",
             "|---|---|---:|---:|---:|---:|"]
    for r in report(path):
        lines.append(f"| {r['class']} | {r['quantity']} | {r['points']} | {r['worst_eps']:.3g} | "
                     f"{r['tol_at_worst']:.3g} | {r['worst_ratio']:.2g} |")
    lines.append("")
    lines.append("Tolerance per family: A + B cond eps (cond: the condition number stored with each point).")
    for fam, (A, B, why) in TOLERANCES.items():
        lines.append(f"- {fam}: A = {A:g}, B = {B:g}: {why}")
    return "\n".join(lines)

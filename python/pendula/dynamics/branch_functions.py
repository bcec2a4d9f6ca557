"""The functions a continued branch is watched with: the tangent, the test functions of its
bifurcations with their errors and decided signs, whether an orbit attracts, and the root finder that
solves a test function along the branch (shared by continue_orbit, the two-parameter curves and the
homoclinic curves)."""

from __future__ import annotations

import math

import numpy as np

from .periodic import MONODROMY_ERROR, multipliers_of


def _tangent(J, Fp, previous=None) -> np.ndarray:
    """The unit null vector of [J | Fp] (2 x 3: the cross product of its rows), oriented along previous."""
    t = np.cross(np.append(J[0], Fp[0]), np.append(J[1], Fp[1]))
    t = t / np.linalg.norm(t)
    if previous is not None and np.dot(t, previous) < 0:
        t = -t
    return t


def _tests(mode: str, ev) -> dict:
    """The test functions at one point: each changes sign at its bifurcation."""
    M = ev.M
    tr, det = float(np.trace(M)), float(np.linalg.det(M))
    out = {"fold": float(np.linalg.det(ev.J))}
    if mode == "section":       # the trivial multiplier 1 and det M: only the fold and the homoclinic
        return out
    out["period-doubling"] = 1.0 + tr + det
    if mode == "half":
        D = ev.DG
        out["pitchfork"] = 1.0 + float(np.trace(D)) + float(np.linalg.det(D))
    else:
        out["plus"] = 1.0 - tr + det
    out["neimark-sacker"] = det - 1.0 if tr * tr < 4.0 * det else math.nan
    return out


def _stable(mode: str, ev) -> bool:
    if mode == "section":
        return bool(abs(np.linalg.det(ev.M)) < 1.0)
    return bool(np.all(np.abs(multipliers_of(ev.M)) < 1.0))


def _root(g, a: float, ga: float, b: float, gb: float, xtol: float, maxit: int = 80):
    """The root of g in [a, b] (ga, gb of opposite signs) by Illinois regula falsi, bisecting when a
    value is not finite; g returns (value, payload).  Returns (x, payload, g(x), the last bracket's
    width) of the last evaluation: a solved root has g(x) within its error or a width within xtol."""
    side = 0
    x, payload, gx = b, None, gb
    for _ in range(maxit):
        if math.isfinite(ga) and math.isfinite(gb) and gb != ga:
            x = (a * gb - b * ga) / (gb - ga)
            if not min(a, b) < x < max(a, b):
                x = 0.5 * (a + b)
        else:
            x = 0.5 * (a + b)
        gx, payload = g(x)
        if gx == 0.0:
            break
        if (gx > 0) == (gb > 0):
            b, gb = x, gx
            if side == -1 and math.isfinite(ga):
                ga *= 0.5
            side = -1
        else:
            a, ga = x, gx
            if side == 1 and math.isfinite(gb):
                gb *= 0.5
            side = 1
        if abs(b - a) <= xtol:
            break
    return x, payload, gx, abs(b - a)


#: The error of a test function of the monodromy, in units of rtol (1 + |X|)^2 (periodic.MONODROMY_ERROR).
_TEST_ERROR = MONODROMY_ERROR


def _test_errors(mode: str, ev, rtol: float) -> dict:
    """The error of each test function at one point (below it, its sign is not decided)."""
    nM = float(np.linalg.norm(ev.M))
    eM = _TEST_ERROR * rtol * (1.0 + nM) ** 2
    out = {"fold": _TEST_ERROR * rtol * (1.0 + float(np.linalg.norm(ev.J))) ** 2}
    if mode == "section":
        return out
    out["period-doubling"] = out["neimark-sacker"] = out["plus"] = eM
    if mode == "half":
        out["pitchfork"] = _TEST_ERROR * rtol * (1.0 + float(np.linalg.norm(ev.DG))) ** 2
    return out


def _decided(mode: str, ev, tests: dict, rtol: float) -> dict:
    """The sign of each test function where it exceeds its error, 0 where it does not (undecided)."""
    err = _test_errors(mode, ev, rtol)
    return {k: (0 if not math.isfinite(v) or abs(v) <= err[k] else (1 if v > 0 else -1)) for k, v in tests.items()}

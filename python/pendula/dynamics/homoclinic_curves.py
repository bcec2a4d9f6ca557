"""The homoclinic (retrapping) point of a running autonomous orbit followed in a second field.

At the homoclinic point the saddle's unstable manifold reaches the next saddle (one turn on): the
splitting of the two manifolds on a section between them (:func:`.homoclinic._splitting`, positive
where the running orbit exists) vanishes.  In the plane of two fields these points form a curve;
here the second field is stepped and at each value the first is solved for the splitting's root by
Illinois regula falsi from a bracket around the value extrapolated from the last two points, as
:func:`.continuation.continue_orbit` locates the homoclinic end of a branch.  The curve ends where
no bracket is found (the homoclinic orbit ceases: the saddle meets the node it leaves, the
saddle-node on the invariant circle where the retrapping torque reaches eps).
"""

from __future__ import annotations

import math

import numpy as np

from ..scene import Scene, SceneError
from .branch_functions import _root
from .equilibria import equilibria
from .homoclinic import _splitting
from .periodic import FlowError

_RTOL = _ATOL = 1e-12


def _g(scene: Scene, p1: str, p2: str, a: float, b: float, w: int) -> float:
    """The splitting at (p1, p2) = (a, b); -1 where the unstable manifold falls back (no running orbit)."""
    try:
        sc = scene.replace(**{p1: float(a), p2: float(b)})
    except SceneError:
        return math.nan
    try:
        d = _splitting(sc, w, _RTOL, _ATOL)
    except FlowError:                     # a flow beyond the work limit: no decision here
        return math.nan
    return -1.0 if d is None else float(d)


def _solve(scene, p1, p2, guess: float, b: float, w: int, width: float):
    """The root in p1 of the splitting at p2 = b, bracketed around guess (widening 6 times, to 64 times the
    first width: the guess is a linear extrapolation a step long); None if none."""
    for _ in range(6):
        lo, hi = guess - width, guess + width
        glo, ghi = _g(scene, p1, p2, lo, b, w), _g(scene, p1, p2, hi, b, w)
        if math.isfinite(glo) and math.isfinite(ghi) and (glo > 0) != (ghi > 0) and math.isfinite(glo * ghi):
            if math.isinf(glo) or math.isinf(ghi):
                return None
            x, _, gx, span = _root(lambda x: (_g(scene, p1, p2, x, b, w), None), lo, glo, hi, ghi,
                                   xtol=1e-14 * max(1.0, abs(guess)), maxit=200)
            return x
        width *= 2.0
    return None


def homoclinic_rows(scene: Scene, p1: str, p2: str, p1_start: float, p2_start: float, stop: float,
                    step: float | None, w: int, max_points: int):
    """The points (p1, p2, saddle angle) of the homoclinic curve from the start to stop, and the end reason."""
    span = stop - p2_start
    h = step if step is not None else min(0.05, abs(span) / 20)
    h = math.copysign(h, span)
    rows = [(p1_start, p2_start)]
    end = "stop"
    while True:
        if len(rows) >= max_points:
            end = f"work limit: {max_points} points"
            break
        b = rows[-1][1] + h
        if (b - stop) * math.copysign(1.0, span) > 0:
            b = stop
        if len(rows) >= 2:
            (a0, b0), (a1, b1) = rows[-2], rows[-1]
            guess = a1 + (b - b1) * (a1 - a0) / (b1 - b0)
        else:
            guess = rows[-1][0]
        a = _solve(scene, p1, p2, guess, b, w, 1e-4 * max(1.0, abs(guess)) + 0.1 * abs(h))
        if a is None:
            if abs(h) > 1e-6 * max(1.0, abs(b)):
                h *= 0.5                            # closer to where the curve ends
                continue
            end = (f"the homoclinic curve ends near ({p1}, {p2}) = ({rows[-1][0]!r}, {rows[-1][1]!r}): no "
                   "homoclinic orbit beyond (the saddle meets the node: a saddle-node on the circle)")
            break
        rows.append((a, b))
        if b == stop:
            break
    thetas = []
    for a, b in rows:
        sad = [e for e in equilibria(scene.replace(**{p1: a, p2: b})) if e.kind == "saddle"]
        thetas.append(sad[0].theta if sad else math.nan)
    return np.array([r[0] for r in rows]), np.array([r[1] for r in rows]), np.array(thetas), end

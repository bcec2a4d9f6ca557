"""The homoclinic end of a running autonomous orbit: the saddle, the crossings
of its manifolds with a section, their splitting, and the first return of a
running orbit to its section (what continue_orbit's autonomous branches stand on).
"""

from __future__ import annotations

import math

import numpy as np

from ..scene import Scene
from .equilibria import equilibria
from .periodic import FlowError, flow, max_time

def _saddle(sc: Scene):
    """The saddle of one turn with its eigenvalues, and the angles of the other rest points."""
    eqs = equilibria(sc)
    sad = [e for e in eqs if e.kind == "saddle"]
    if not sad:
        return None
    e = sad[0]
    lam = np.sort(e.eigenvalues.real)
    return e.theta, float(lam[1]), float(lam[0]), [x.theta for x in eqs if x is not e]


def _crossing(sc: Scene, x0, target: float, direction: float, w: float, horizon: float, rtol, atol):
    """The velocity where the orbit from x0 (forward in time when direction > 0) first reaches
    theta = target, refined by Newton in time; None when it turns back first."""
    times = direction * horizon * np.arange(1, 401) / 400
    try:
        ends, _, _ = flow(sc, x0, times, rtol, atol)
    except FlowError:
        return None
    for i in range(len(times)):
        if w * ends[i, 1] <= 0:
            return None
        if direction * w * (ends[i, 0] - target) >= 0:
            # Newton in time inside the grid interval [times[i-1], times[i]]
            a, b = sorted((times[i - 1] if i else 0.0, times[i]))
            t = min(max(times[i] - (ends[i, 0] - target) / ends[i, 1], a), b)
            for _ in range(12):
                end, _, f = flow(sc, x0, [t], rtol, atol)
                dt = (end[0, 0] - target) / f[0, 0]
                t = min(max(t - dt, a), b)
                if abs(dt) <= 1e-15 * abs(t):
                    break
            end, _, _ = flow(sc, x0, [t], rtol, atol)
            return float(end[0, 1])
    return None


def _splitting(sc: Scene, w: int, rtol: float, atol: float, delta: float = 1e-7):
    """The splitting of the saddle's unstable manifold from the next saddle's stable manifold (one turn
    on, in the direction w), as w (v_u - v_s) on the section theta = next saddle - w Delta, Delta half
    the gap to the rest point before it (at most 1): positive where the running orbit exists, zero at
    the homoclinic orbit.  None when the unstable manifold falls back before the section, +inf when
    there is no saddle (the running orbit exists for sure)."""
    sd = _saddle(sc)
    if sd is None:
        return math.inf
    ths, lu, ls, others = sd
    nxt = ths + 2 * math.pi * w
    gaps = [(w * (nxt - th)) % (2 * math.pi) for th in others]
    gap = min([g for g in gaps if g > 0] or [2 * math.pi])
    target = nxt - w * min(1.0, 0.5 * gap)
    hu = (math.log(1 / delta) + 20) / lu
    vu = _crossing(sc, (ths + w * delta, w * delta * lu), target, 1.0, w, hu, rtol, atol)
    if vu is None:
        return None
    hs = (math.log(1 / delta) + 5) / abs(ls)
    vs = _crossing(sc, (nxt - w * delta, -w * delta * ls), target, -1.0, w, hs, rtol, atol)
    if vs is None:
        return None
    return w * (vu - vs)


def _first_return(scene: Scene, x0, w: int, rtol: float, atol: float) -> float:
    """The time the orbit from x0 takes to advance one turn (the guess of an autonomous period)."""
    # twenty turns at the guess's speed, or twenty small oscillations when that is slower: a running
    # orbit's speed never stays far below both (a guess of v = 1e-300 is not a horizon of 1e302)
    horizon = 40 * math.pi / max(abs(x0[1]), math.sqrt(scene.eps))
    if not horizon <= max_time():
        raise ValueError(f"guess: a first turn from {tuple(x0.tolist())} would take beyond the time limit "
                         f"{max_time():.0e}")
    times = horizon * np.arange(1, 801) / 800
    try:
        ends, _, _ = flow(scene, x0, times, rtol, atol)
    except FlowError as exc:
        raise ValueError(f"guess: the flow from the guess failed: {exc}") from None
    target = x0[0] + 2 * math.pi * w
    hit = np.nonzero(w * (ends[:, 0] - target) >= 0)[0]
    if len(hit) == 0:
        raise ValueError(f"guess: the orbit from {tuple(x0.tolist())} does not turn over "
                         f"within t = {horizon:.3g}; a running orbit needs a torque above the retrapping one")
    return float(times[hit[0]])


# ---------------------------------------------------------------- equilibria

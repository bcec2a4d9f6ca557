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
    theta = target, refined by Newton in time; None when it turns back first or not within the time limit.

    The orbit is followed in chunks of 64 samples whose span starts at ``horizon`` and doubles (from the
    last chunk's end) until the section is reached: a slow passage by a nearly degenerate saddle, whose
    duration no fixed horizon foresees, costs a few more chunks, not a horizon sized for the worst case;
    an orbit that stops moving (settled on a node short of the section) gives None."""
    x = np.asarray(x0, dtype=np.float64)
    elapsed, span = 0.0, float(horizon)
    while elapsed <= max_time():
        times = direction * span * np.arange(1, 65) / 64
        try:
            ends, _, _ = flow(sc, x, times, rtol, atol)
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
                    end, _, f = flow(sc, x, [t], rtol, atol)
                    dt = (end[0, 0] - target) / f[0, 0]
                    t = min(max(t - dt, a), b)
                    if abs(dt) <= 1e-15 * abs(t):
                        break
                end, _, _ = flow(sc, x, [t], rtol, atol)
                return float(end[0, 1])
        if abs(ends[-1, 0] - x[0]) <= 1e-12 * max(1.0, abs(x[0])):
            return None                 # settled (on a node short of the section)
        x = ends[-1].copy()
        elapsed += span
        span *= 2.0
    return None


#: the relative error the start of a manifold leaves at the section (below the flow's own rtol)
_START_ERROR = 1e-16
#: the farthest start of the unstable manifold from its saddle (radians)
_FARTHEST_START = 0.05


def _unstable_start(lu: float, ls: float) -> float:
    """The displacement from the saddle along its unstable eigenvector where the unstable manifold starts.

    The linear start is off the manifold by about d^2 (angles relative to 1, the scale on which the
    pendulum's force bends); while the orbit leaves the saddle, for a time log(1/d) / lu, the error across
    the manifold contracts at the stable rate |ls|, by d^(|ls| / lu).  The start d = e^(1 / (2 + |ls| / lu))
    leaves e = _START_ERROR: about 5e-5 for a saddle with lu ~ |ls|, and growing towards 1 as the saddle
    nears its birth with the node (lu -> 0), where the slow passage by the saddle-node contracts the error
    further; capped at _FARTHEST_START (checked against an angle-parametrised Radau integration of the
    manifold to 1e-12 from 1 - tau = 0.4 to 1e-13)."""
    if not lu > 0.0:                     # at the saddle-node itself (to rounding)
        return _FARTHEST_START
    return min(_FARTHEST_START, _START_ERROR ** (1.0 / (2.0 + abs(ls) / lu)))


def _splitting(sc: Scene, w: int, rtol: float, atol: float, delta: float = 1e-7):
    """The splitting of the saddle's unstable manifold from the next saddle's stable manifold (one turn
    on, in the direction w), as w (v_u - v_s) on the section theta = next saddle - w Delta (Delta = 1, halved while the stable manifold is no graph
    over the angle that far): positive where the running orbit
    exists, zero at the homoclinic orbit, negative where the unstable manifold passes below the stable one
    (and falls back).  None when the unstable manifold falls back before the section, +inf when there is
    no saddle (the running orbit exists for sure).

    The unstable manifold starts at the displacement of :func:`_unstable_start` (far enough from a nearly
    degenerate saddle that its slow passage is not integrated in full, near enough to a hyperbolic one that
    the linear start's error dies away), the stable one at ``delta`` (backwards in time the stable direction
    is the fast one); each flow's absolute tolerance is scaled to its starting velocity, so that a start at
    v = 1e-9 is resolved to the relative tolerance and not swamped by an absolute 1e-12."""
    sd = _saddle(sc)
    if sd is None:
        return math.inf
    ths, lu, ls, others = sd
    nxt = ths + 2 * math.pi * w
    # the section one radian before the next saddle, beyond the node when the node lies nearer (the one
    # manifold beside the slow passage by the node is then the stable one, integrated backwards where it
    # is fast); nearer (halving) where the stable manifold, followed backwards, turns back before it
    # (weak damping: it is a graph over the angle only near its saddle)
    vs0 = -w * delta * ls
    for halving in range(12):
        target = nxt - w * 0.5 ** halving
        vs = _crossing(sc, (nxt - w * delta, vs0), target, -1.0, w, 4.0 / abs(ls), rtol,
                       min(atol, rtol * abs(vs0)))
        if vs is not None:
            break
    else:
        return None
    du = min(_unstable_start(lu, ls), 0.25 * w * (target - ths))
    vu0 = w * du * lu
    vu = _crossing(sc, (ths + w * du, vu0), target, 1.0, w, 4.0 / abs(ls), rtol,
                   min(atol, rtol * abs(vu0)) if vu0 else atol)
    if vu is None:
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

"""Measures of a basin boundary and of a chaotic attractor: the Wada test by the grid method
(Daza, Wagemakers, Georgeot, Guery-Odelin & Sanjuan 2016, "Basin entropy", and Daza et al. 2015,
"Testing for basins of Wada", Sci. Rep. 5, 16579, section "The grid approach") and the Kaplan-Yorke
(Lyapunov) dimension from a Lyapunov spectrum (Kaplan & Yorke 1979; Ott, "Chaos in dynamical systems",
section 4.6).

The basin entropy and the uncertainty exponent of a label map are in :mod:`.attractors`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _checks
from ..scene import Scene
from .attractors import AttractorMap, AttractorSet, cell_ids, kaplan_yorke_dimension

__all__ = ["kaplan_yorke_dimension", "wada_test", "WadaTest"]

#: the 8 directions from a grid point to its neighbours (index steps along theta0, v0)
_DIRECTIONS = np.array([(di, dj) for di in (-1, 0, 1) for dj in (-1, 0, 1) if (di, dj) != (0, 0)])


@dataclass
class WadaTest:
    """The result of the Wada grid test on an attractor map.

    Attributes
    ----------
    wada : bool or None
        True: the fraction of boundary points whose box sees every attractor
        reached ``1 - tol`` once the fractions had converged; False: they
        converged below it (at most partially Wada); None: undecided (no
        convergence within ``max_steps`` refinements).
    fractions : numpy.ndarray, shape (steps + 1, attractors)
        W_m after each refinement step q = 0 .. steps (column m - 1: the
        fraction of the boundary points whose box holds m colours).
    boundary_points : int
        Grid points whose box (the point and its 8 neighbours) holds two colours or more.
    attractors : int
        The attractors (colours) of the map.
    new_orbits : int
        Orbits run by the refinements.
    uncounted : int
        Of them, those left undecided (or finding an attractor not on the map): no colour counted.

    See Also
    --------
    wada_test : makes it.

    Examples
    --------
    >>> import numpy as np, pendula
    >>> sc = pendula.Scene(damping=0.2, drive_amplitude=1.66, drive_frequency=1.0)
    >>> am = pendula.attractor_map(sc, {"theta0": np.linspace(-3, 3, 12), "v0": np.linspace(-4, 4, 12)})
    >>> w = pendula.wada_test(am, max_steps=1)
    >>> w.fractions.shape[1]                     # W_1, W_2, W_3
    3
    """

    wada: bool | None
    fractions: np.ndarray
    boundary_points: int
    attractors: int
    new_orbits: int
    uncounted: int

    def __repr__(self) -> str:
        w = self.fractions[-1, -1] if self.fractions.size else math.nan
        return (f"WadaTest(wada={self.wada}, W_{self.attractors}={w:.4f} after {self.fractions.shape[0] - 1} "
                f"steps, boundary_points={self.boundary_points}, new_orbits={self.new_orbits})")


def _labeller(amap: AttractorMap, threads: int):
    """A function labelling arbitrary initial states (theta0, v0) by the map's attractors: the recurrence
    finder run against their cells at the map's boundary-recheck tolerances."""
    from .attractor_maps import _AttractorPlan, _attractor_block, _raw, recurrence_options
    attrs = amap.dataset.attrs
    scene = Scene.from_namelist(attrs["scene"])
    keys = ("cell", "recurrence_cell", "near", "consecutive", "consecutive_chaotic", "recurrences", "collect",
            "max_periods", "max_period", "merge_tol", "pilot", "rtol", "atol", "recheck_rtol", "recheck_atol",
            "margin")
    opts = recurrence_options({k: (int(attrs[k]) if isinstance(attrs[k], (np.integer, int)) else attrs[k])
                               for k in keys})
    found = AttractorSet(opts["cell"], opts["merge_tol"], opts["consecutive"], opts["consecutive_chaotic"])
    for a in amap.attractors:           # in label order: index in the set = label
        found.items.append({"kind": a.kind, "period": a.period, "winding": a.winding,
                            "theta": np.asarray(a.theta, float), "v": np.asarray(a.v, float),
                            "cells": np.unique(cell_ids(a.theta, a.v, opts["cell"]))})
    zero = np.zeros(1)
    plan = _AttractorPlan(scene, {"theta0": zero, "v0": zero.copy()}, opts, 20000)
    table = found.table()

    def label(theta, v):
        p = plan.params_at(np.zeros(theta.size, dtype=np.int64))
        p[6], p[7] = theta, v
        out, _, _, st = _attractor_block(plan, np.asfortranarray(p), table, opts["recheck_rtol"],
                                         opts["recheck_atol"], 1, threads)
        raw = _raw(out, st)
        return np.where(raw >= 0, raw, -1)
    return label


def wada_test(amap: AttractorMap, *, max_steps: int = 6, tol: float = 0.01, threads: int = 0) -> WadaTest:
    """The Wada test by the grid method (Daza et al. 2015) on a basin map with three or more attractors.

    Each grid point's *box* is the point and its 8 neighbours; a box whose
    points carry two colours or more lies on a boundary.  At refinement step
    q = 1, 2, ... the orbits of the points dividing each segment from the
    point to a neighbour into 2^q equal parts are run (the recurrence finder
    against the map's attractors, at the map's boundary-recheck tolerances),
    and the colours they show join the box's, for the boxes that do not yet
    see every attractor.  W_m is the fraction of boundary boxes seeing m
    colours.  The refinements stop when no W_m moves by more than ``tol``
    between two steps; the boundary is Wada when W_N (N the attractors) is
    then at least ``1 - tol``.  A point whose orbit is undecided adds no colour.

    Parameters
    ----------
    amap : AttractorMap
        A map over ``theta0`` and ``v0`` (both increasing) by the recurrence method, with at least
        three attractors.
    max_steps : int, optional
        The most refinement steps (default 6: up to 8 (2^6 - 1) new orbits per unresolved box).
    tol : float, optional
        The convergence and verdict tolerance on the fractions (default 0.01).
    threads : int, optional
        OpenMP threads (0: all).

    Returns
    -------
    WadaTest

    Raises
    ------
    TypeError
        If ``amap`` is not an AttractorMap or ``max_steps`` not a whole number.
    ValueError
        If the map has fewer than three attractors, is not over (theta0, v0), or was not made by the
        recurrence method; or an argument is out of range.

    See Also
    --------
    attractor_map : makes the map.
    kaplan_yorke_dimension : the dimension of a chaotic attractor.

    Examples
    --------
    >>> import numpy as np, pendula
    >>> from pendula.dynamics.boundary_measures import wada_test
    >>> sc = pendula.Scene(damping=0.2, drive_amplitude=1.66, drive_frequency=1.0)
    >>> am = pendula.attractor_map(sc, {"theta0": np.linspace(-np.pi, np.pi, 24), "v0": np.linspace(-4, 4, 24)})
    >>> len(am.attractors)
    3
    >>> w = wada_test(am, max_steps=2)
    >>> bool(w.fractions[-1, -1] > 0.5)          # most boundary boxes already see all three
    True
    """
    if not isinstance(amap, AttractorMap):
        raise TypeError(f"parameter 'amap' must be a pendula AttractorMap, got {type(amap).__name__}")
    max_steps = _checks.count(max_steps, "max_steps", 1, 16)
    tol = _checks.real(tol, "tol", 0.0, 0.5, lo_open=True)
    threads = _checks.threads(threads)
    ds = amap.dataset
    n_att = len(amap.attractors)
    if n_att < 3:
        raise ValueError(f"parameter 'amap': the Wada test needs three attractors or more; the map has {n_att}")
    if ds.attrs.get("method") != "recurrence":
        raise ValueError("parameter 'amap': the Wada test runs new orbits by the recurrence method; the map was "
                         f"made by method {ds.attrs.get('method')!r}")
    dims = tuple(ds.attractor.dims)
    if set(dims) != {"theta0", "v0"}:
        raise ValueError(f"parameter 'amap': the Wada test needs a map over theta0 and v0; it is over {dims}")
    lab = np.asarray(ds.attractor.values if dims[0] == "theta0" else ds.attractor.values.T, dtype=np.int64)
    th_axis, v_axis = (np.asarray(ds[d].values, dtype=float) for d in ("theta0", "v0"))
    if lab.shape[0] < 3 or lab.shape[1] < 3:
        raise ValueError(f"parameter 'amap': a map of {lab.shape} points has no 3 x 3 box")
    label = _labeller(amap, threads)
    ni, nj = lab.shape
    # the colours of each interior point's box (grid edges: the boxes cut by the edge are not used)
    ii, jj = np.meshgrid(np.arange(1, ni - 1), np.arange(1, nj - 1), indexing="ij")
    ii, jj = ii.ravel(), jj.ravel()
    seen = np.zeros((ii.size, n_att), dtype=bool)
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            c = lab[ii + di, jj + dj]
            ok = c >= 0
            seen[np.flatnonzero(ok), c[ok]] = True
    boundary = seen.sum(axis=1) >= 2
    ii, jj, seen = ii[boundary], jj[boundary], seen[boundary]
    nb = ii.size
    if nb == 0:
        return WadaTest(None, np.zeros((1, n_att)), 0, n_att, 0, 0)

    def fractions():
        return np.bincount(seen.sum(axis=1) - 1, minlength=n_att)[:n_att] / nb
    hist = [fractions()]
    known: dict[tuple[int, int], int] = {}     # colour of a point at finest-scale integer coordinates
    scale = 2 ** max_steps
    new_orbits = uncounted = 0
    verdict = None
    for q in range(1, max_steps + 1):
        todo = np.flatnonzero(seen.sum(axis=1) < n_att)
        if todo.size == 0:
            hist.append(fractions())
            verdict = True
            break
        # the points k / 2^q along each segment from the box's centre to a neighbour, k odd (new at this step)
        k = np.arange(1, 2 ** q, 2)
        step = scale // 2 ** q
        ci = (ii[todo, None, None] * scale + _DIRECTIONS[None, :, 0, None] * k[None, None, :] * step)
        cj = (jj[todo, None, None] * scale + _DIRECTIONS[None, :, 1, None] * k[None, None, :] * step)
        keys = np.stack([ci.reshape(todo.size, -1), cj.reshape(todo.size, -1)], axis=-1)
        flat = keys.reshape(-1, 2)
        uniq = np.unique(flat, axis=0)
        fresh = np.array([tuple(u) not in known for u in uniq.tolist()], dtype=bool)
        run_pts = uniq[fresh]
        if run_pts.size:
            fi, fj = run_pts[:, 0] / scale, run_pts[:, 1] / scale
            th = np.interp(fi, np.arange(ni), th_axis)
            vv = np.interp(fj, np.arange(nj), v_axis)
            colours = label(th, vv)
            new_orbits += run_pts.shape[0]
            uncounted += int((colours < 0).sum())
            known.update(zip(map(tuple, run_pts.tolist()), colours.tolist()))
        col = np.array([known[tuple(x)] for x in flat.tolist()]).reshape(todo.size, -1)
        for r in range(col.shape[1]):
            ok = col[:, r] >= 0
            seen[todo[ok], col[ok, r]] = True
        hist.append(fractions())
        if np.max(np.abs(hist[-1] - hist[-2])) < tol:
            verdict = bool(hist[-1][-1] >= 1 - tol)
            break
    return WadaTest(verdict, np.array(hist), int(nb), n_att, int(new_orbits), int(uncounted))

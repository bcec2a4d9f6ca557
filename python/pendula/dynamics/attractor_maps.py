"""Attractor maps: the attractors of a driven scene's stroboscopic map over a
grid of initial states or parameters, and their basins.

Built on the sweep engine (chunks on OpenMP threads, a resumable store, Dask)
and on the kernel's attractor finder by recurrence
(``kernel/sweep/pendula_attractors.f90``); each periodic attractor found is
confirmed by Newton on its monodromy (:mod:`.periodic`).  A map over
(theta0, v0) is built coarse to fine.
"""

from __future__ import annotations

import json
import math
import os
from typing import TYPE_CHECKING, Literal

import numpy as np

from .. import _checks, _interrupt
from .._optional import require
from .._sweep_engine import (AXIS_META, PARAM_ORDER, STATUS, Plan, check_driven, check_over, check_work,
                             edge_mask, run, run_measure, status_attrs)
from ..scene import Scene
from ..systems import contract
from .attractors import AttractorMap

if TYPE_CHECKING:   # distributed is optional: named in annotations only
    import distributed

__all__ = ["attractor_map", "RECURRENCE_DEFAULTS"]

#: the recurrence finder's keywords and their defaults (pendula.attractor_map documents them)
RECURRENCE_DEFAULTS = {"cell": 0.1, "recurrence_cell": 0.25, "near": 0.01, "consecutive": 2,
                       "consecutive_chaotic": 10, "recurrences": 100, "collect": 1000, "max_periods": 3000,
                       "max_period": 12, "merge_tol": 1e-3, "pilot": 64, "rtol": 1e-7, "atol": 1e-9,
                       "recheck_rtol": 1e-10, "recheck_atol": 1e-12, "inherit": True, "margin": 1}
#: a basin map over (theta0, v0) is built coarse to fine, each level (every s-th point along both axes, s a
#: power of 2) inheriting from the finished level above it; the coarsest level has at least this many points
#: along each axis
_LEVEL_MIN_POINTS = 16
#: Newton's tolerances on the stroboscopic map of a recurrence (pendula_gsl_periodic_orbit)
_NEWTON_RTOL, _NEWTON_TOL = 1e-11, 1e-10
#: pilot points and points that found a new attractor are run in batches of 1, 1, 2, 4, 8 and then this
#: many, each against the attractors found before the batch (fixed sizes: the result never depends on the
#: threads; small first batches, so that one orbit finds an attractor, a chaotic one costing a thousand
#: periods, before its neighbours look for it again)
_DISCOVERY_BATCH = 16
#: a basin-boundary point whose label was inherited at one of its first samples is not run again at the
#: tight tolerances: its sample lay a grid step of the level above inside a block of one attractor, far
#: beyond what the loose tolerance's error (about rtol a period, grown over a few periods) can move it
_RECHECK_INHERITED_WITHIN = 3
#: the raw answer of the labelling pass: an attractor of the pilot's (>= 0) or one of these
_RAW_UNDECIDED, _RAW_NEW_PERIODIC, _RAW_NEW_CHAOTIC = -1, -2, -3
#: kernel outputs before the cycle points (pendula_attractors%at_nfixed)
_AT_NFIXED = 12


class _AttractorPlan(Plan):
    """The labelling pass of a recurrence attractor map: the grid, the options, the pilot's table."""

    def __init__(self, scene, over, opts: dict, chunk_points: int):
        super().__init__(scene, over, "attractor", opts["rtol"], opts["atol"], float(opts["max_periods"]), 0.0,
                         1, chunk_points)
        self.opts = dict(opts)
        o = self.opts
        self.cfg = np.array([o["cell"], o["recurrence_cell"], o["near"], o["max_periods"], o["max_period"],
                             o["recurrences"], o["collect"], _NEWTON_RTOL, _NEWTON_TOL, 2.0, o["margin"], 1.0],
                            dtype=float)
        self.nout = _AT_NFIXED + 2 * o["max_period"]
        self.table = None
        # the coarser level's basin map (theta0 axis, v0 axis, labels on (theta0, v0)); none: no level above
        self.basin = (np.zeros(1), np.zeros(1), np.full((1, 1), -1, dtype=np.int32))
        # the points the level above decided: {'label', 'status', 'periods', 'recheck', 'inherited'} on the
        # grid (label -9 where the point is this level's to run), or None
        self.given = None

    def key(self) -> dict:
        return {"scene": self.scene.to_namelist(), "measure": "attractor", "method": "recurrence",
                "over": {k: v.tolist() for k, v in self.over.items()}, "options": self.opts, "rows": self.rows}


def _attractor_block(plan: _AttractorPlan, p: np.ndarray, table, rtol: float, atol: float, maxc: int,
                     threads: int):
    """One kernel call of the recurrence finder (pendula_attractors) that Ctrl-C stops."""
    from .. import _kernel
    kcell, klab, need, cth, cv, catt, crad = table
    bth, bv, blab = plan.basin
    cancel = _interrupt.cancel_flag()
    out, cells, ncell, st = _interrupt.call(_kernel.attractor_block, np.asfortranarray(p), rtol, atol, plan.cfg,
                                            kcell, klab, need, cth, cv, catt, crad, bth, bv, blab, plan.nout, maxc,
                                            int(threads), cancel, cancel=cancel)
    if cancel[0]:
        raise KeyboardInterrupt
    return out, cells, ncell, st


def _raw(out: np.ndarray, st: np.ndarray) -> np.ndarray:
    """The labelling pass's answer of each point: a known attractor's index, or a _RAW_* code."""
    kind = np.where(st == 0, out[0], np.nan)
    return np.select([(kind == 0) | (kind == 3), kind == 1, kind == 2], [out[1], _RAW_NEW_PERIODIC,
                                                                          _RAW_NEW_CHAOTIC],
                     _RAW_UNDECIDED).astype(np.int64)


def _attractor_rows(plan: _AttractorPlan, lo: int, hi: int, threads: int):
    """Rows lo .. hi - 1 of a level: (raw answer, status, drive periods, inherited, recheck so far) per
    point, flat; the points the level above decided are taken from it, the others run in the kernel, at
    the loose tolerances or, where the level above predicts a basin boundary, at the tight ones (recheck 4)."""
    p, shape = plan.params_rows(lo, hi)
    n = p.shape[1]
    raw = np.full(n, _RAW_UNDECIDED, dtype=np.int64)
    st = np.zeros(n, dtype=np.int32)
    periods = np.zeros(n)
    inherited = np.zeros(n, dtype=np.int64)
    before = np.zeros(n, dtype=np.int64)
    run = np.ones(n, dtype=bool)
    tight = np.zeros(n, dtype=bool)
    if plan.given is not None:
        g = {k: np.asarray(v[lo:hi]).ravel() for k, v in plan.given.items()}
        run = g["label"] == -9
        keep = ~run
        raw[keep], st[keep], periods[keep] = g["label"][keep], g["status"][keep], g["periods"][keep]
        inherited[keep], before[keep] = g["inherited"][keep], g["recheck"][keep]
        tight = run & g["tight"]
        before[tight] = 4
    o = plan.opts
    for idx, rtol, atol in ((np.flatnonzero(run & ~tight), plan.rtol, plan.atol),
                            (np.flatnonzero(tight), o["recheck_rtol"], o["recheck_atol"])):
        if idx.size:
            out, _, _, s = _attractor_block(plan, p[:, idx], plan.table, rtol, atol, 1, threads)
            raw[idx], st[idx], periods[idx], inherited[idx] = _raw(out, s), s, out[4], (s == 0) & (out[0] == 3)
    return p, shape, raw, st, periods, inherited, before


def _predicted_boundary(coarse: np.ndarray, ran: np.ndarray, shape: tuple) -> np.ndarray:
    """The points of a level (shape) whose nearest points of the level above (its labels ``coarse``, every
    other point along both axes) do not all carry one attractor, one of them at least having run to its
    attractor rather than inherit its label (``ran``): on an intertwined basin boundary in all likelihood
    (next to a smooth boundary the points of the level above inherit their labels, and so will these)."""
    i = np.arange(shape[0])[:, None]
    j = np.arange(shape[1])[None, :]
    i0, i1 = i // 2, np.minimum((i + 1) // 2, coarse.shape[0] - 1)
    j0, j1 = j // 2, np.minimum((j + 1) // 2, coarse.shape[1] - 1)
    c = [coarse[i0, j0], coarse[i0, j1], coarse[i1, j0], coarse[i1, j1]]
    r = ran[i0, j0] | ran[i0, j1] | ran[i1, j0] | ran[i1, j1]
    return r & ((c[0] < 0) | (c[0] != c[1]) | (c[0] != c[2]) | (c[0] != c[3]))


def _attractor_chunk(plan: _AttractorPlan, i: int, threads: int):
    """Label chunk i of a level against the attractors found so far and the level above's basin map;
    points next to another answer (a grid neighbour along any axis, across chunk edges too) are computed
    again at the tight tolerances, whose answer is kept (once: a point the level above rechecked keeps
    that answer; a point that inherited its label within _RECHECK_INHERITED_WITHIN periods keeps it).
    out[..., :] = raw answer, drive periods integrated, recheck (0 no, 1 same, 2 changed, 3 inherited
    early, not run again), inherited (1: labelled from the level above's basin map)."""
    o = plan.opts
    lo = i * plan.rows
    hi = min(lo + plan.rows, plan.shape[0])
    p, shape, raw, st, periods, inherited, recheck = _attractor_rows(plan, lo, hi, threads)
    parts = [raw.reshape(shape)]
    if lo > 0:
        parts.insert(0, _attractor_rows(plan, lo - 1, lo, threads)[2].reshape((1,) + shape[1:]))
    if hi < plan.shape[0]:
        parts.append(_attractor_rows(plan, hi, hi + 1, threads)[2].reshape((1,) + shape[1:]))
    first = 1 if lo > 0 else 0
    edge = edge_mask(np.concatenate(parts, axis=0))[first:first + shape[0]].ravel()
    # inherited within the first samples: left as it is (recheck 3)
    early = edge & (recheck == 0) & (inherited > 0) & (periods <= _RECHECK_INHERITED_WITHIN)
    recheck[early] = 3
    idx = np.flatnonzero(edge & (recheck == 0))
    if idx.size:
        out2, _, _, st2 = _attractor_block(plan, p[:, idx], plan.table, o["recheck_rtol"], o["recheck_atol"], 1,
                                           threads)
        raw2 = _raw(out2, st2)
        recheck[idx] = np.where(raw2 != raw[idx], 2, 1)
        raw[idx], st[idx] = raw2, st2
        periods[idx] += out2[4]
        inherited[idx] = (st2 == 0) & (out2[0] == 3)
    res = np.stack([raw, periods, recheck, inherited], axis=-1).reshape(shape + (4,))
    return i, res, st.reshape(shape)


def _attractor_vars(plan, out, st) -> dict:
    return {"raw_attractor": out[..., 0].astype(np.int32), "periods": out[..., 1],
            "recheck": out[..., 2].astype(np.int32), "inherited": out[..., 3].astype(np.int8),
            "status": st.astype(np.int32)}


def _attractor_layout(plan: _AttractorPlan):
    from .._store import Layout, Variable
    dims = tuple(plan.over)

    def meta(name):
        long_name, units = AXIS_META[name]
        return {"long_name": long_name, "units": units}
    coords = {n: (plan.over[n], meta(n)) for n in dims}
    variables = {
        "status": Variable(dims, np.dtype(np.int32), status_attrs(), -1),
        "raw_attractor": Variable(dims, np.dtype(np.int32), {
            "long_name": "labelling pass: index of the pilot's attractor, or -1 undecided, -2 a new periodic "
                         "attractor, -3 a new chaotic attractor", "units": "1"}, -9),
        "periods": Variable(dims, np.dtype(np.float64), {
            "long_name": "drive periods integrated until the point was decided", "units": "1"}, np.nan),
        "recheck": Variable(dims, np.dtype(np.int32), {
            "long_name": "boundary recheck at the tight tolerances: 0 not rechecked, 1 same answer, 2 changed, "
                         "3 not run again (inherited within three drive periods), 4 run at the tight "
                         "tolerances from the start (a boundary predicted by the level above)",
            "units": "1"}, -1),
        "inherited": Variable(dims, np.dtype(np.int8), {
            "long_name": "1: labelled from the coarser level's basin map", "units": "1"}, -1)}
    attrs = {"Conventions": "CF-1.10", "title": "pendula attractor map (labelling pass)",
             "scene": plan.scene.to_namelist(), "measure": "attractor", "method": "recurrence",
             "status_codes": json.dumps(STATUS), **{k: v for k, v in plan.opts.items()}}
    return Layout(axes={n: plan.over[n] for n in dims}, coords=coords, variables=variables, rows=plan.rows,
                  identity=json.dumps(plan.key(), sort_keys=True), attrs=attrs)


def _discover(plan: _AttractorPlan, p: np.ndarray, found, threads: int, rtol: float | None = None,
              atol: float | None = None, kinds: tuple = ("periodic", "chaotic"), grow: bool = True):
    """Run points (columns of p, in this order) in batches of 1, 1, 2, 4, 8, 16, 16 ... (of 16 unless
    ``grow``), each batch against the attractors of these ``kinds`` found before it (at rtol, atol: default
    the plan's); new attractors join ``found``.  Returns (index in found or -1, status, drive periods) per
    point: the same for any thread count, chunking or cluster."""
    n = p.shape[1]
    labels = np.full(n, -1, dtype=np.int64)
    status = np.zeros(n, dtype=np.int32)
    periods = np.zeros(n)
    b0, k = 0, (0 if grow else 5)
    while b0 < n:
        b = slice(b0, min(n, b0 + min(_DISCOVERY_BATCH, 2 ** max(k - 1, 0))))
        b0, k = b.stop, k + 1
        out, cells, ncell, st = _attractor_block(plan, p[:, b], found.table(kinds), rtol or plan.rtol,
                                                 atol if atol is not None else plan.atol, plan.opts["collect"] * 4,
                                                 threads)
        for j in range(out.shape[1]):
            g = b.start + j
            status[g], periods[g] = st[j], out[4, j]
            if st[j] != 0:
                continue
            kind = int(out[0, j])
            if kind == 0:
                labels[g] = int(out[1, j])
            elif kind == 1:
                k = int(out[11, j])
                labels[g] = found.add_periodic(int(out[2, j]), int(out[3, j]), out[_AT_NFIXED:_AT_NFIXED + 2 * k:2, j],
                                               out[_AT_NFIXED + 1:_AT_NFIXED + 2 * k:2, j], out[5:9, j])
            else:
                fields = {n: float(p[PARAM_ORDER.index(n), g]) for n in plan.over if n not in ("theta0", "v0")}
                labels[g] = found.add_chaotic(cells[:ncell[j], j], (out[_AT_NFIXED, j], out[_AT_NFIXED + 1, j]),
                                              fields)
    return labels, status, periods


def _pilot_points(shape: tuple, target: int) -> np.ndarray:
    """The pilot: every s-th point along each axis (s the same on every axis, the smallest giving at most
    ``target`` points), in a fixed shuffled order; flat indices into the grid."""
    s = 1
    while math.prod(-(-n // s) for n in shape) > target:
        s += 1
    axes = [np.arange(0, n, s) for n in shape]
    mesh = np.meshgrid(*axes, indexing="ij")
    flat = np.ravel_multi_index(tuple(m.ravel() for m in mesh), shape)
    return flat[np.random.default_rng(20260).permutation(flat.size)]


def recurrence_options(kw: dict) -> dict:
    """The recurrence finder's options, checked (one checker, _checks) and with their defaults."""
    o = dict(RECURRENCE_DEFAULTS)
    o.update({k: v for k, v in kw.items() if v is not None})
    for name in ("cell", "recurrence_cell", "near", "merge_tol"):
        o[name] = _checks.real(o[name], name, 0.0, 10.0, lo_open=True)
    if o["cell"] < 1e-6 or o["recurrence_cell"] < 1e-6:
        raise ValueError("cell and recurrence_cell must be at least 1e-6 (the cells of one turn are counted)")
    o["consecutive"] = _checks.count(o["consecutive"], "consecutive", 1, 10**6)
    o["consecutive_chaotic"] = _checks.count(o["consecutive_chaotic"], "consecutive_chaotic", 1, 10**6)
    o["recurrences"] = _checks.count(o["recurrences"], "recurrences", 1, 10**6)
    o["collect"] = _checks.count(o["collect"], "collect", 1, 10**5)
    o["max_period"] = _checks.count(o["max_period"], "max_period", 1, 64)
    o["max_periods"] = _checks.count(o["max_periods"], "max_periods", 1, 10**7)
    o["pilot"] = _checks.count(o["pilot"], "pilot", 1, 10**5)
    o["rtol"], o["atol"] = _checks.tolerances(o["rtol"], o["atol"])
    o["recheck_rtol"], o["recheck_atol"] = _checks.tolerances(o["recheck_rtol"], o["recheck_atol"])
    o["inherit"] = _checks.flag(o["inherit"], "inherit")
    o["margin"] = _checks.count(o["margin"], "margin", 0, 1000)
    return o


def attractor_map(scene: Scene, over: dict, *, method: Literal["recurrence", "samples"] | None = None,
                  cell: float | None = None, recurrence_cell: float | None = None, near: float | None = None,
                  consecutive: int | None = None, consecutive_chaotic: int | None = None,
                  recurrences: int | None = None, collect: int | None = None, max_periods: int | None = None,
                  max_period: int | None = None, merge_tol: float | None = None, pilot: int | None = None,
                  rtol: float | None = None, atol: float | None = None, recheck_rtol: float | None = None,
                  recheck_atol: float | None = None, inherit: bool | None = None, margin: int | None = None,
                  transient: float | None = None, samples: int | None = None,
                  tol: float | None = None, threads: int = 0, out: str | os.PathLike[str] | None = None,
                  client: distributed.Client | None = None, progress: bool = False,
                  chunk_points: int = 20000) -> AttractorMap:
    """Find the attractors of a driven scene and label each grid point by the one its orbit ends on.

    The default method, ``'recurrence'``, follows each orbit on the
    stroboscopic map (one sample per drive period) and stops it as soon as it
    is decided, in the spirit of Datseris & Wagemakers' AttractorsViaRecurrences
    (Attractors.jl).  The section is cut into square cells ``cell`` wide:

    * an orbit whose samples lie in the cells of one known attractor (its
      points and their 8 neighbouring cells) for ``consecutive`` samples in a
      row (``consecutive_chaotic`` for a chaotic attractor) is labelled;
    * an orbit whose samples recur after k <= ``max_period`` drive periods to
      within ``near`` (two samples in a row) is refined by Newton on the
      stroboscopic map (the core of :func:`pendula.periodic_orbit`); when Newton
      converges to an orbit within ``near`` whose Floquet multipliers lie inside
      the unit circle, it is a new periodic attractor (a confirmed stable orbit,
      its period and multipliers exact to Newton's tolerance);
    * an orbit that falls ``recurrences`` samples in a row in cells
      (``recurrence_cell`` wide) it has visited before, over more than
      2 ``max_period`` distinct cells (or over fewer, when a second such streak
      shows no cycle closing in: a thin chaotic set), is a new non-periodic
      attractor, whose cells are collected over ``collect`` more samples;
      once the map is made it is called 'chaotic' or 'quasi-periodic' by
      its largest Lyapunov exponent where that is resolved from 0
      (``pendula.dynamics.attractors.classify_aperiodic``), and its points
      are undecided where it is not;
    * an orbit decided by none of these within ``max_periods`` drive periods
      is **undecided** (label -1, status 1): counted and reported, never called
      chaotic.

    The labels depend on the grid and the options only, never on the threads,
    the chunking, a resumed store or a cluster: a *pilot* (every s-th point on
    each axis, at most ``pilot`` points, in a fixed order) finds the
    attractors in batches of 1, 1, 2, 4, 8 and then 16 points, each batch
    against the attractors the batches before it found (the first 16 orbits
    find their periodic attractors by Newton themselves, so that a ``cell``
    too coarse to tell two apart shows as a conflict); every grid point is
    then labelled against the pilot's attractors; the points that found a new attractor are run again,
    in grid order and the same batches, against the attractors found so far.  Attractors are numbered by a rule on
    the attractors alone (periodic by period, then the angle and velocity of
    their first point; chaotic after them by basin size).

    A basin map over ``theta0`` and ``v0`` (the grid's two axes, both
    increasing) is built coarse to fine when ``inherit`` is true (the
    default): first every s-th point along both axes (s a power of 2, the
    coarsest level keeping at least 16 points on each axis), then the points
    between them, level by level.  From its first sample on, an orbit of a
    finer level takes its label from the finished level above when the sample
    lies in a rectangle of that level's grid whose corners, and ``margin``
    more grid points on each side, all carry one attractor (the stroboscopic
    map is the same every period, so the sample ends where the initial states
    around it end).  Where the basins are smooth on the grid's scale most
    orbits are then decided after one or two drive periods; where they are
    intermixed the rectangles disagree and orbits run on to their attractor.
    A level depends on the finished level above only, so the labels still
    depend on the grid and the options alone.  The result counts the points
    that ``inherited`` their label.

    The labelling runs at the loose tolerances ``rtol``, ``atol``; every point
    with a grid neighbour (along any axis, across chunks too) of another
    answer is run again at ``recheck_rtol``, ``recheck_atol``, and that answer
    is kept, unless it inherited its label within three drive periods (its
    sample lay a grid step inside a block of one attractor; ``recheck`` 3);
    a point whose nearest points of the level above disagree, one of them
    having run to its attractor rather than inherit it, runs at the tight
    tolerances from the start (``recheck`` 4).  The result says how many
    were rechecked and how many changed.

    ``method='samples'`` (the former method, used when ``transient`` or
    ``samples`` is given) integrates every point over ``transient`` and reads
    ``samples`` stroboscopic samples for recurrence
    (``pendula.dynamics.attractors.label_attractors``).

    Parameters
    ----------
    scene : Scene
        A periodically driven scene (``drive_frequency > 0`` and ``drive_amplitude != 0``, or a
        vibrating pivot).
    over : dict
        The grid, as for :func:`pendula.sweep` (e.g. ``{'theta0': ..., 'v0': ...}`` for a basin map).
    method : {'recurrence', 'samples'}, optional
        Default 'recurrence', or 'samples' when ``transient`` or ``samples`` is given.
    cell : float, optional
        Width of the labelling cells on the section (default 0.1).
    recurrence_cell : float, optional
        Width of the cells in which an orbit's own recurrence is counted (default 0.25).
    near : float, optional
        Recurrence distance (max-norm, angle modulo 2 pi) at which Newton is tried (default 0.01).
    consecutive, consecutive_chaotic : int, optional
        Samples in a row in a known attractor's cells that label a point (default 2, and 10 for a
        chaotic attractor).
    recurrences : int, optional
        Samples in a row in already-visited cells that make a chaotic attractor (default 100).
    collect : int, optional
        Samples over which a new chaotic attractor's cells are collected (default 1000).
    max_periods : int, optional
        The limit: drive periods per point before it is undecided (default 3000).
    max_period : int, optional
        The longest period looked for (default 12; 'samples': samples // 2).
    merge_tol : float, optional
        Two periodic orbits are one when each point of one lies within this of the other's (default 1e-3).
    pilot : int, optional
        Most pilot points (default 64).
    rtol, atol : float, optional
        The labelling tolerances of DOP853 (default 1e-7, 1e-9; 'samples': 1e-10, 1e-12).
    recheck_rtol, recheck_atol : float, optional
        The tolerances of the boundary recheck (default 1e-10, 1e-12).
    inherit : bool, optional
        Build a map over ``theta0`` and ``v0`` coarse to fine, finer orbits taking their label from the
        level above (default True); ignored for other grids.
    margin : int, optional
        Grid points of the level above beyond a rectangle's corners, on each side, that must carry the
        same attractor before a sample in the rectangle takes it (default 1: a 4 x 4 block).  With 0
        (the corners alone) intermixed basins are mislabelled: at drive_amplitude 1.07 a quarter of the
        points of a 150 x 150 map.
    transient, samples, tol : optional
        Method 'samples': the time skipped (rounded up to whole drive periods; default 600), the samples
        read (default 48) and the recurrence tolerance (default 1e-6).
    threads, out, client, progress, chunk_points : optional
        As for :func:`pendula.sweep` (a stored, resumable run with ``out``); the
        labels do not depend on them.

    Returns
    -------
    AttractorMap
        The label map as a Dataset (``attractor``, ``period``, ``status``;
        the recurrence method also ``periods``, the drive periods each point
        took, ``recheck`` and ``inherited``; its attributes ``levels``, the
        strides of the levels, and ``inherited``, their count), the
        attractors, the basin measures, and the counts ``undecided``,
        ``rechecked`` and ``recheck_changed``.

    Raises
    ------
    TypeError
        An argument of the wrong kind (a float or a bool where a whole number is wanted), named.
    ValueError
        If the scene is not driven, an argument is out of range, or ``cell``
        is too coarse to tell two attractors apart.

    Warns
    -----
    RuntimeWarning
        When no point is decided within ``max_periods``.

    See Also
    --------
    attractor_continuation : the attractors and their basin fractions over a parameter.
    sweep : ``measure='attractor'`` gives the 'samples' map's Dataset.
    periodic_orbit : Newton's method on one periodic orbit.

    Examples
    --------
    >>> import pendula
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.35, drive_frequency=2/3)
    >>> am = pendula.attractor_map(sc, {"theta0": [-2.0, 0.0, 2.0], "v0": [-3.0, 0.0, 3.0]})
    >>> [(a.kind, a.period, a.winding) for a in am.attractors]      # two period-1 rotations, one each way
    [('periodic', 1, -1), ('periodic', 1, 1)]
    >>> bool(max(abs(am.attractors[0].multipliers)) < 1)             # stable: a confirmed orbit
    True
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a pendula.Scene, got {type(scene).__name__}")
    if method is None:
        method = "samples" if (transient is not None or samples is not None) else "recurrence"
    if not isinstance(method, str) or method not in ("recurrence", "samples"):
        raise ValueError(f"parameter 'method' must be 'recurrence' or 'samples'; got {method!r}")
    _checks.angle(scene.theta0, "field 'theta0'")
    over = check_over(scene, over)
    contract.require(scene, "attractor_map", over=over)
    check_driven(scene, over, "attractor_map")
    threads = _checks.threads(threads)
    if out is not None:
        out = _checks.path(out, "out")    # the one checker: '' is refused, never the current folder
    chunk_points = _checks.count(chunk_points, "chunk_points", 1)
    if method == "samples":
        rec_only = {"cell": None, "recurrence_cell": recurrence_cell, "near": near, "consecutive": consecutive,
                    "consecutive_chaotic": consecutive_chaotic, "recurrences": recurrences, "collect": collect,
                    "max_periods": max_periods, "pilot": pilot, "recheck_rtol": recheck_rtol,
                    "recheck_atol": recheck_atol, "inherit": inherit, "margin": margin}
        given = [k for k, v in rec_only.items() if v is not None]
        if given:
            raise TypeError(f"attractor_map: {', '.join(given)} belong to method 'recurrence', not 'samples'")
        return _attractor_map_samples(scene, over, transient=600.0 if transient is None else transient,
                                      samples=48 if samples is None else samples, tol=1e-6 if tol is None else tol,
                                      merge_tol=1e-3 if merge_tol is None else merge_tol, max_period=max_period,
                                      cell=0.05 if cell is None else cell, rtol=1e-10 if rtol is None else rtol,
                                      atol=1e-12 if atol is None else atol, threads=threads, out=out,
                                      client=client, progress=progress, chunk_points=chunk_points)
    if tol is not None:
        raise TypeError("attractor_map: tol belongs to method 'samples' (the recurrence method refines by Newton)")
    opts = recurrence_options(dict(cell=cell, recurrence_cell=recurrence_cell, near=near, consecutive=consecutive,
                                    consecutive_chaotic=consecutive_chaotic, recurrences=recurrences,
                                    collect=collect, max_periods=max_periods, max_period=max_period,
                                    merge_tol=merge_tol, pilot=pilot, rtol=rtol, atol=atol,
                                    recheck_rtol=recheck_rtol, recheck_atol=recheck_atol, inherit=inherit,
                                    margin=margin))
    check_work(scene, over, opts["max_periods"])
    return _attractor_map_recurrence(scene, over, opts, threads, out, client, progress, chunk_points)


def _level_strides(over: dict, opts: dict) -> list[int]:
    """The levels of a basin map, coarsest first: strides s = 2^L ... 2, 1 along both axes, the coarsest
    keeping at least _LEVEL_MIN_POINTS points on each; [1] (one level, nothing inherited) unless the grid is
    over theta0 and v0 alone, both increasing, and inheriting is asked for."""
    if not opts["inherit"] or set(over) != {"theta0", "v0"} or \
            not all(np.all(np.diff(v) > 0) for v in over.values()):
        return [1]
    s = 1
    while min(-(-len(v) // (2 * s)) for v in over.values()) >= _LEVEL_MIN_POINTS:
        s *= 2
    return [2 ** k for k in range(int(math.log2(s)), -1, -1)]


def _basin(over: dict, labels: np.ndarray):
    """The kernel's basin map of a level: (theta0 axis, v0 axis, labels on (theta0, v0), Fortran order)."""
    lab = labels if list(over)[0] == "theta0" else labels.T
    return (np.ascontiguousarray(over["theta0"], dtype=float), np.ascontiguousarray(over["v0"], dtype=float),
            np.asfortranarray(lab, dtype=np.int32))


def _attractor_map_recurrence(scene, over, opts, threads, out, client, progress, chunk_points) -> AttractorMap:
    import warnings

    from .attractors import AttractorSet, classify_aperiodic
    xr = require("xarray", "sweep", "pendula.attractor_map")
    fine = _AttractorPlan(scene, over, opts, chunk_points)
    npts = math.prod(fine.shape)
    # 1. the pilot finds the attractors
    found = AttractorSet(opts["cell"], opts["merge_tol"], opts["consecutive"], opts["consecutive_chaotic"])
    pidx = _pilot_points(fine.shape, opts["pilot"])
    # (the first _DISCOVERY_BATCH pilot orbits find their own periodic attractors, confirmed by Newton, rather
    # than being labelled by a known one's cells: cells too coarse to tell two attractors apart then show as
    # a conflict; the others are labelled by the cells of all the attractors found before them)
    first = pidx[:_DISCOVERY_BATCH]
    _discover(fine, fine.params_at(first), found, threads, kinds=("chaotic",))
    _discover(fine, fine.params_at(pidx[first.size:]), found, threads, grow=False)
    n_pilot_att = len(found.items)
    # 2. level by level, coarse to fine: every point of a level labelled against the attractors found so far
    #    and the basin map of the level above (chunked, on a cluster; the finest level stored under out)
    strides = _level_strides(fine.over, opts)
    given = basin = None
    new_total = 0
    for s in strides:
        plan = fine if s == 1 else _AttractorPlan(scene, {k: v[::s] for k, v in fine.over.items()}, opts,
                                                  chunk_points)
        plan.table = found.table()
        if basin is not None:
            plan.basin, plan.given = basin, given
        desc = "attractor map" if len(strides) == 1 else f"attractor map, level {strides.index(s) + 1} of " \
                                                         f"{len(strides)}"
        ds = run(plan, _attractor_layout(plan), _attractor_chunk, _attractor_vars, out if s == 1 else None,
                  client, threads, progress, desc)
        raw = np.asarray(ds.raw_attractor.values, dtype=np.int64).ravel()
        status = np.asarray(ds.status.values, dtype=np.int32).ravel().copy()
        periods = np.asarray(ds.periods.values, dtype=float).ravel().copy()
        recheck = np.asarray(ds.recheck.values).ravel()
        inherited = np.asarray(ds.inherited.values).ravel()
        # 3. points that found a new attractor: again, in grid order, against the attractors found so far
        labels = np.where(raw >= 0, raw, -1)
        new_all = (raw == _RAW_NEW_PERIODIC) | (raw == _RAW_NEW_CHAOTIC)
        new_total += int(new_all.sum())
        # at the tolerances that gave the answer: the loose ones, then the boundary points' tight ones
        for sel, tols in ((new_all & (recheck == 0), (plan.rtol, plan.atol)),
                          (new_all & (recheck > 0), (opts["recheck_rtol"], opts["recheck_atol"]))):
            idx = np.flatnonzero(sel)
            if idx.size:
                lab_new, st_new, per_new = _discover(plan, plan.params_at(idx), found, threads, *tols)
                labels[idx], status[idx] = lab_new, st_new
                periods[idx] += per_new
        if s > 1:
            # the next level: every other point along both axes is this level's
            nxt = tuple(len(v[::s // 2]) for v in fine.over.values())
            given = {"label": np.full(nxt, -9, dtype=np.int64), "status": np.zeros(nxt, dtype=np.int32),
                     "periods": np.zeros(nxt), "recheck": np.zeros(nxt, dtype=np.int64),
                     "inherited": np.zeros(nxt, dtype=np.int64),
                     "tight": _predicted_boundary(labels.reshape(plan.shape),
                                                  (inherited == 0).reshape(plan.shape), nxt)}
            for k, vals in (("label", labels), ("status", status), ("periods", periods), ("recheck", recheck),
                            ("inherited", inherited)):
                given[k][::2, ::2] = vals.reshape(plan.shape)
            basin = _basin(plan.over, labels.reshape(plan.shape))
    counts = np.bincount(labels[labels >= 0], minlength=len(found.items))
    # 4. each non-periodic attractor: chaotic or quasi-periodic where its largest Lyapunov exponent is resolved,
    #    else its points are undecided (status 1)
    for i, a in enumerate(found.items):
        if a["kind"] != "periodic" and counts[i] > 0:
            # at the scene of the grid point that found it (a grid over scene fields holds many scenes)
            a["classified"] = classify_aperiodic(scene.replace(**a.get("fields", {})), *a["point"],
                                                 opts["recheck_rtol"], opts["recheck_atol"], threads)
            if a["classified"]["kind"] is None:
                status[labels == i] = 1
                labels[labels == i] = -1
                counts[i] = 0
            else:
                a["kind"] = a["classified"]["kind"]
    atts, remap = found.attractors(counts, npts)
    labels = remap[labels].reshape(fine.shape)     # remap[-1] = -1: undecided stays -1
    status = status.reshape(fine.shape)
    undecided = int((labels < 0).sum())
    if undecided == npts:
        warnings.warn(f"attractor_map: no point was decided within max_periods = {opts['max_periods']} drive "
                      "periods (status 1: raise max_periods)", RuntimeWarning, stacklevel=3)
    dims = tuple(fine.over)
    coords = {d: (d, fine.over[d], dict(zip(("long_name", "units"), AXIS_META[d]))) for d in dims}
    ds_out = xr.Dataset(
        {"periods": (dims, periods.reshape(fine.shape), {
            "long_name": "drive periods integrated until the point was decided", "units": "1"}),
         "recheck": (dims, recheck.reshape(fine.shape).astype(np.int32), {
             "long_name": "boundary recheck at the tight tolerances: 0 not rechecked, 1 same answer, 2 changed, "
                         "3 not run again (inherited within three drive periods), 4 run at the tight "
                         "tolerances from the start (a boundary predicted by the level above)",
             "units": "1"}),
         "inherited": (dims, inherited.reshape(fine.shape).astype(np.int8), {
             "long_name": "1: labelled from a coarser level's basin map", "units": "1"}),
         "status": (dims, status, status_attrs())}, coords=coords)
    extra = {"method": "recurrence", "pilot_points": int(pidx.size), "pilot_attractors": n_pilot_att,
             "new_in_labelling": new_total, "undecided": undecided, "rechecked": int(((recheck == 1) | (recheck == 2)).sum()),
             "boundary_inherited": int((recheck == 3).sum()), "tight_from_start": int((recheck == 4).sum()),
             "recheck_changed": int((recheck == 2).sum()), "mean_periods": float(periods.mean()),
             "levels": json.dumps(strides), "inherited": int((inherited > 0).sum()),
             **{k: (int(v) if isinstance(v, bool) else v) for k, v in opts.items()}}
    return _finish_map(ds_out, labels, atts, scene, extra)


def _finish_map(ds, labels, atts, scene, extra: dict) -> AttractorMap:
    """The map's Dataset (``attractor``, ``period`` added, CF flags, the measures and the options as
    attributes) and the AttractorMap."""
    from .attractors import basin_entropy, boundary_fraction, uncertainty_exponent
    dims = tuple(d for d in ds.status.dims)
    per = np.array([a.period for a in atts] + [-1])[labels]
    ds["attractor"] = (dims, labels.astype(np.int32), {
        "long_name": "attractor of the stroboscopic map the orbit ends on (-1 undecided)",
        "flag_values": np.arange(-1, len(atts), dtype=np.int32),
        "flag_meanings": " ".join(["undecided"] + [f"{a.kind}_period_{a.period}_{a.label}" if a.period
                                                   else f"{a.kind.replace('-', '_')}_{a.label}" for a in atts])})
    ds["period"] = (dims, per.astype(np.int32), {"long_name": "period of the attractor in drive periods "
                                                              "(0 quasi-periodic or chaotic, -1 undecided)",
                                                 "units": "1"})
    bf = boundary_fraction(labels)
    sb, sbb = basin_entropy(labels) if labels.ndim == 2 and min(labels.shape) >= 5 else (math.nan, math.nan)
    alpha = uncertainty_exponent(labels)[0] if len(atts) > 1 else math.nan
    ds.attrs.update({"Conventions": "CF-1.10", "title": "pendula attractor map: the attractor each initial state "
                                                         "ends on", "scene": scene.to_namelist(),
                     "measure": "attractor", "status_codes": json.dumps(STATUS),
                     "boundary_fraction": bf, "basin_entropy": sb, "boundary_basin_entropy": sbb,
                     "uncertainty_exponent": alpha,
                     "attractors": json.dumps([{"label": x.label, "kind": x.kind, "period": x.period,
                                                "winding": x.winding, "theta": x.theta.tolist(),
                                                "v": x.v.tolist(), "fraction": x.fraction,
                                                "multipliers_abs": np.abs(x.multipliers).tolist(),
                                                "lyapunov": list(x.lyapunov),
                                                "rotation_number": x.rotation_number,
                                                "dimension": x.dimension}
                                               for x in atts])})
    ds.attrs.update(extra)
    return AttractorMap(ds, atts, bf, sb, sbb, alpha, undecided=int(extra.get("undecided", (labels < 0).sum())),
                        rechecked=int(extra.get("rechecked", 0)), recheck_changed=int(extra.get("recheck_changed", 0)))


def _attractor_map_samples(scene, over, *, transient, samples, tol, merge_tol, max_period, cell, rtol, atol,
                           threads, out, client, progress, chunk_points) -> AttractorMap:
    """The former method: every point integrated over ``transient``, ``samples`` read for recurrence."""
    samples = _checks.count(samples, "samples", 4, 4096)
    tol = _checks.real(tol, "tol", 0.0, lo_open=True)
    merge_tol = _checks.real(merge_tol, "merge_tol", 0.0, lo_open=True)
    cell = _checks.real(cell, "cell", 0.0, lo_open=True)
    if max_period is not None:
        max_period = _checks.count(max_period, "max_period", 1, samples - 1)
    if out is not None:
        out = _checks.path(out, "out")
    if client is not None:
        from .._cluster import check_client
        check_client(client)
    if math.prod(len(v) for v in over.values()) * samples > _checks.MAX_GRID_POINTS:
        raise ValueError(f"parameter 'samples': {samples} samples at each grid point is more than "
                         f"{_checks.MAX_GRID_POINTS:.0e} values")
    rtol, atol = _checks.tolerances(rtol, atol)
    transient = _checks.duration(transient, "transient", positive=False)
    pc = run_measure(scene, over, "poincare", rtol, atol, _checks.duration(scene.sweep_t_max, "t_max"), transient,
                     samples, _checks.count(chunk_points, "chunk_points", 1), out, client, threads,
                     _checks.flag(progress, "progress"))
    from .attractors import label_attractors
    labels, atts = label_attractors(pc.theta.values, pc.v.values, tol=tol, merge_tol=merge_tol,
                                    max_period=max_period, cell=cell)
    st = pc.status.values
    # a point still settling onto a cycle is not settled (status 1): undecided, never a guess
    settling = (labels == -2) & (st == 0)
    labels = np.where(st == 0, labels, -1)
    labels[settling] = -1
    dims = tuple(d for d in pc.theta.dims if d != "sample")
    ds = pc[["status"]].load() if hasattr(pc, "load") else pc[["status"]]
    if settling.any():
        st2 = ds.status.values.copy()
        st2[settling] = 1
        ds["status"] = (ds.status.dims, st2, ds.status.attrs)
    labels, atts, unresolved = _classify_sample_attractors(scene, over, labels, atts, pc, rtol, atol, threads)
    if unresolved.any():
        st2 = ds.status.values.copy()
        st2[unresolved] = 1
        ds["status"] = (ds.status.dims, st2, ds.status.attrs)
    ds = ds.drop_vars([c for c in ds.coords if c not in dims])
    extra = {k: pc.attrs[k] for k in pc.attrs if k not in ("measure", "title")}
    extra.update({"method": "samples", "tol": tol, "merge_tol": merge_tol, "cell": cell,
                  "undecided": int((labels < 0).sum())})
    return _finish_map(ds, labels, atts, scene, extra)


def _classify_sample_attractors(scene, over, labels, atts, pc, rtol, atol, threads):
    """Each non-periodic attractor of a 'samples' map: chaotic or quasi-periodic by its resolved largest
    Lyapunov exponent (from the last sample of its first point, at that point's scene), or undecided (its
    points -1, status 1); the attractors renumbered in order.  Returns (labels, attractors, unresolved)."""
    import dataclasses

    from .attractors import classify_aperiodic
    th = np.asarray(pc.theta.values)
    vv = np.asarray(pc.v.values)
    flat = labels.ravel()
    keep, out = [], []
    for a in atts:
        if a.kind == "periodic":
            keep.append(a)
            continue
        first = int(np.flatnonzero(flat == a.label)[0])
        ix = np.unravel_index(first, labels.shape)
        fields = {n: float(np.asarray(vals)[i]) for (n, vals), i in zip(over.items(), ix)
                  if n not in ("theta0", "v0")}
        info = classify_aperiodic(scene.replace(**fields), float(th[ix][-1]), float(vv[ix][-1]), rtol, atol,
                                  threads)
        if info["kind"] is not None:
            keep.append(dataclasses.replace(a, kind=info["kind"], lyapunov=tuple(info["lyapunov"]),
                                            rotation_number=info["rotation_number"], dimension=info["dimension"]))
    remap = np.full(len(atts) + 1, -1, dtype=np.int64)
    for new, a in enumerate(keep):
        remap[a.label] = new
        out.append(dataclasses.replace(a, label=new))
    unresolved = (labels >= 0) & (remap[labels] < 0)
    return remap[labels], out, unresolved

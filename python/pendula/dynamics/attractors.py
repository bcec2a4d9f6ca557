"""Attractors of the driven damped pendulum and their basins.

The stroboscopic map of a periodically driven scene is sampled once per drive
period after a transient (the sweep measure ``poincare``, computed by the
kernel on OpenMP threads; :func:`pendula.attractor_map` and the sweep measure
``attractor`` run it and call this module); each grid point's samples are then
read for recurrence, without being told the attractors in advance (in the spirit of
Datseris & Wagemakers' AttractorsViaRecurrences):

- **periodic**: the smallest k such that every sample of the tail recurs
  after k drive periods to within ``tol`` (angles compared modulo 2 pi).  The
  cycle's k points identify the attractor; two points share it when each
  point of one cycle lies within ``merge_tol`` of a point of the other.
- **chaotic**: no period up to ``max_period``.  Such points share an
  attractor when the cells of a coarse grid (``cell`` wide) that their
  samples visit overlap, directly or through other chaotic points (connected
  components of the point-cell graph).

Labels are numbered by a rule on the attractors alone (periodic ones by
period, then by the angle and velocity of their first point; chaotic ones
after them by the size of their basin), so they depend on the grid and the
options only, never on the chunking, the thread count or a resumed run.

Measured quantities of a 2-D map (Daza et al. 2016; Grebogi, McDonald, Ott
& Yorke 1983): the basin-boundary fraction (points with a grid neighbour of
another attractor), the basin entropy S_b and the boundary basin entropy
S_bb (boxes of ``box`` x ``box`` points), and the uncertainty exponent alpha:
the fraction f(e) of points whose attractor changes within a distance e
along an axis scales as e^alpha (alpha = 1 for a smooth boundary, < 1 for a
fractal one), fitted over e = 1, 2, 4, ... grid steps.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from .._sweep_engine import edge_mask
from ..scene import Scene

__all__ = ["Attractor", "AttractorMap", "AttractorSet", "label_attractors", "basin_entropy",
           "uncertainty_exponent", "boundary_fraction", "cell_ids", "edge_mask", "kaplan_yorke_dimension",
           "classify_aperiodic", "APERIODIC_PERIODS"]

TWO_PI = 2 * math.pi
#: a periodic attractor closer than this many cells to another is confirmed by distance as well as by its
#: cells (AttractorSet.confirm_radius): a cell's 8 neighbours label too, so two attractors fewer than about
#: four cells apart have labelling regions that touch or overlap
_CLOSE_CELLS = 4


@dataclass(frozen=True)
class Attractor:
    """One attractor of the stroboscopic map.

    Attributes
    ----------
    label : int
        Its label in the map (0, 1, ...).
    kind : str
        'periodic', 'quasi-periodic' or 'chaotic' (the recurrence method tells the last two apart by the
        largest Lyapunov exponent, only where it is resolved: ``classify_aperiodic``).
    period : int
        Drive periods of the cycle (0 for a chaotic attractor).
    theta, v : numpy.ndarray
        The cycle's points on the section (theta in [-pi, pi)), from its point of
        smallest angle; for a chaotic attractor, the centres of the cells it
        visits (recurrence method) or the samples of one of its points ('samples').
    fraction : float
        The fraction of the grid in its basin.
    multipliers : numpy.ndarray
        A periodic attractor's Floquet multipliers (the eigenvalues of the
        monodromy matrix over its period, largest modulus first; all inside the
        unit circle); empty for a chaotic attractor or a map read from samples.
    winding : int
        Turns per period of a periodic attractor (0 for an oscillation or a chaotic one).
    lyapunov : tuple of float
        A quasi-periodic or chaotic attractor's Lyapunov spectrum of the flow's (theta, v) part,
        (lambda_1, lambda_2) per unit time, and the standard error of lambda_1 (recurrence method;
        empty otherwise).
    rotation_number : float
        A quasi-periodic or chaotic attractor's mean turns per drive period (NaN otherwise).
    dimension : float
        A chaotic attractor's Kaplan-Yorke dimension on the stroboscopic section, 1 + lambda_1 /
        abs(lambda_2) (``kaplan_yorke_dimension``; NaN otherwise).
    """

    label: int
    kind: str
    period: int
    theta: np.ndarray
    v: np.ndarray
    fraction: float
    multipliers: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=complex))
    winding: int = 0
    lyapunov: tuple = ()
    rotation_number: float = math.nan
    dimension: float = math.nan

    def __repr__(self) -> str:
        what = f"period={self.period}" if self.kind == "periodic" else f"{np.size(self.theta)} samples"
        return f"Attractor(label={self.label}, kind={self.kind!r}, {what}, fraction={self.fraction:.4g})"


def _wrap(x):
    return (x + math.pi) % TWO_PI - math.pi


def _dist(th1, v1, th2, v2):
    return np.maximum(np.abs(_wrap(th1 - th2)), np.abs(v1 - v2))


def label_attractors(theta, v, *, tol=1e-6, merge_tol=1e-3, max_period=None, cell=0.05):
    """Label each point's attractor from its stroboscopic samples.

    Parameters
    ----------
    theta, v : array_like, shape (..., S)
        The samples of each point (theta modulo 2 pi), S per point, after the transient.
    tol : float, optional
        Recurrence tolerance of a periodic cycle (max-norm, default 1e-6).
    merge_tol : float, optional
        Two cycles are one attractor when each point of one lies within this of the other's (default 1e-3).
    max_period : int, optional
        The longest period looked for (default S // 2).
    cell : float, optional
        Cell width of the grid on which chaotic attractors are told apart (default 0.05).

    Returns
    -------
    labels : numpy.ndarray of int, shape (...)
        The attractor of each point; -1 where the samples are not finite, -2
        where they are not settled: no cycle recurs within ``tol`` yet, but the
        distance of the samples from a cycle of some period up to
        ``max_period`` still shrinks (the later half of the samples within
        half the earlier half's distance and below 0.1): an orbit converging
        slowly to a periodic attractor is undecided, never called chaotic.
    attractors : list of Attractor

    Examples
    --------
    >>> import numpy as np
    >>> from pendula.dynamics.attractors import label_attractors
    >>> th = np.array([[0.1, 0.1, 0.1, 0.1], [1.0, 2.0, 1.0, 2.0], [0.1, 0.1, 0.1, 0.1]])
    >>> labels, atts = label_attractors(th, np.zeros_like(th))
    >>> labels.tolist(), [a.period for a in atts]
    ([0, 1, 0], [1, 2])
    """
    theta = np.asarray(theta, dtype=float)
    v = np.asarray(v, dtype=float)
    if theta.shape != v.shape or theta.ndim < 1:
        raise ValueError("theta and v must have the same shape (..., samples)")
    shape = theta.shape[:-1]
    S = theta.shape[-1]
    th = _wrap(theta.reshape(-1, S))
    vv = v.reshape(-1, S)
    n = th.shape[0]
    kmax = S // 2 if max_period is None else int(max_period)
    if not 1 <= kmax <= S - 1:
        raise ValueError(f"max_period must be between 1 and samples - 1 = {S - 1}, got {kmax}")
    finite = np.all(np.isfinite(th) & np.isfinite(vv), axis=1)
    period = np.zeros(n, dtype=np.int64)
    for k in range(1, kmax + 1):
        todo = np.flatnonzero(finite & (period == 0))
        if todo.size == 0:
            break
        # every sample of the tail recurs after k periods
        d = _dist(th[todo, k:], vv[todo, k:], th[todo, :-k], vv[todo, :-k]).max(axis=1)
        period[todo[d < tol]] = k
    labels = np.full(n, -1, dtype=np.int64)
    found = []   # (period, theta points, v points, indices)
    # not settled: no period yet, but the samples still close in on a cycle of some period k (its distances
    # after k periods fall from the earlier half of the samples to the later): undecided, not chaotic
    settling = np.zeros(n, dtype=bool)
    todo = np.flatnonzero(finite & (period == 0))
    for k in range(1, kmax + 1):
        if todo.size == 0 or S - k < 4:
            break
        d = _dist(th[todo, k:], vv[todo, k:], th[todo, :-k], vv[todo, :-k])
        h = d.shape[1] // 2
        late, early = d[:, h:].max(axis=1), d[:, :h].max(axis=1)
        settling[todo[(late < 0.5 * early) & (late < 0.1)]] = True
    labels[settling] = -2

    # periodic: one representative cycle per attractor, taken in a fixed order of the points
    per = np.flatnonzero(period > 0)
    # the cycle of each periodic point: its last k samples
    for k in np.unique(period[per]):
        idx = per[period[per] == k]
        cth = th[idx, S - k:]
        cv = vv[idx, S - k:]
        # a rotation-independent key: the cycle point of smallest angle
        first = np.argmin(cth, axis=1)
        key_th = cth[np.arange(idx.size), first]
        order = np.lexsort((cv[np.arange(idx.size), first], key_th))
        unassigned = np.ones(idx.size, dtype=bool)
        for j in order:
            if not unassigned[j]:
                continue
            rep_th, rep_v = cth[j], cv[j]
            # members: every cycle point of theirs lies within merge_tol of a point of the representative
            cand = np.flatnonzero(unassigned)
            dmin = np.full((cand.size, k), np.inf)
            for q in range(k):
                dmin = np.minimum(dmin, _dist(cth[cand], cv[cand], rep_th[q], rep_v[q]))
            members = cand[dmin.max(axis=1) < merge_tol]
            unassigned[members] = False
            found.append(("periodic", int(k), rep_th.copy(), rep_v.copy(), idx[members]))

    # chaotic: connected components of the graph point - visited cell
    cha = np.flatnonzero(finite & (period == 0) & ~settling)
    if cha.size:
        ci = np.floor((th[cha] + math.pi) / cell).astype(np.int64)
        cj = np.floor(vv[cha] / cell).astype(np.int64)
        cj -= cj.min()
        cells = ci * (int(cj.max()) + 1) + cj                       # (npts, S) cell ids
        _, cells = np.unique(cells, return_inverse=True)
        cells = cells.reshape(cha.size, S)
        comp = np.arange(cha.size)
        while True:
            # each cell takes the smallest component of its points, each point the smallest of its cells
            cell_min = np.full(cells.max() + 1, cha.size, dtype=np.int64)
            np.minimum.at(cell_min, cells, comp[:, None])
            new = cell_min[cells].min(axis=1)
            new = np.minimum(new, comp)
            new = new[new]   # pointer jumping
            if np.array_equal(new, comp):
                break
            comp = new
        for c in np.unique(comp):
            members = cha[comp == c]
            found.append(("chaotic", 0, th[members[0]].copy(), vv[members[0]].copy(), members))

    # numbering: periodic by (period, first point's angle, velocity), then chaotic by basin size
    def sort_key(f):
        kind, k, rth, rv, members = f
        if kind == "periodic":
            q = int(np.argmin(rth))
            return (0, k, round(float(rth[q]), 6), round(float(rv[q]), 6), 0)
        return (1, 0, 0.0, 0.0, -members.size)

    found.sort(key=sort_key)
    atts = []
    for lab, (kind, k, rth, rv, members) in enumerate(found):
        labels[members] = lab
        if kind == "periodic":
            q = int(np.argmin(rth))
            rth, rv = np.roll(rth, -q), np.roll(rv, -q)
        atts.append(Attractor(lab, kind, k, rth, rv, members.size / max(n, 1)))
    return labels.reshape(shape), atts


def kaplan_yorke_dimension(exponents: ArrayLike) -> float:
    """The Kaplan-Yorke (Lyapunov) dimension of an attractor from its Lyapunov spectrum.

    With the exponents sorted decreasingly, lambda_1 >= lambda_2 >= ..., and
    j the largest index whose partial sum lambda_1 + ... + lambda_j is not
    negative, D = j + (lambda_1 + ... + lambda_j) / abs(lambda_{j + 1})
    (Kaplan & Yorke 1979); 0 when lambda_1 < 0 (a stable fixed point), the
    number of exponents when no partial sum is negative (no volume
    contraction).

    Parameters
    ----------
    exponents : array_like of float
        The Lyapunov spectrum, in any order, in any one unit (per time or per
        drive period: D does not depend on it).  The flow of a driven
        pendulum has three (one of them 0, along the drive's phase); its
        stroboscopic map has two.

    Returns
    -------
    float
        The dimension; NaN with a RuntimeWarning when an exponent is not finite.

    Raises
    ------
    ValueError
        If ``exponents`` is empty or not one-dimensional.

    See Also
    --------
    attractor_map : a chaotic attractor's ``dimension`` is this, from its exponents on the section.
    wada_test : the Wada property of a basin boundary.

    Examples
    --------
    >>> from pendula.dynamics.attractors import kaplan_yorke_dimension
    >>> round(kaplan_yorke_dimension([0.1, -0.3]), 12)        # a chaotic attractor of a 2-D map: 1 + 0.1 / 0.3
    1.333333333333
    >>> round(kaplan_yorke_dimension([0.1, 0.0, -0.3]), 12)   # the same as a flow: one more dimension
    2.333333333333
    """
    lam = np.asarray(exponents, dtype=float)
    if lam.ndim != 1 or lam.size == 0:
        raise ValueError(f"parameter 'exponents' must be a non-empty 1-D sequence; got shape {lam.shape}")
    if not np.all(np.isfinite(lam)):
        warnings.warn("kaplan_yorke_dimension: an exponent is not finite", RuntimeWarning, stacklevel=2)
        return math.nan
    lam = np.sort(lam)[::-1]
    partial = np.cumsum(lam)
    if partial[0] < 0:
        return 0.0
    if partial[-1] >= 0:
        return float(lam.size)
    j = int(np.flatnonzero(partial >= 0)[-1])          # 0-based: j + 1 exponents in the sum
    return float(j + 1 + partial[j] / abs(lam[j + 1]))



#: drive periods over which a non-periodic attractor's Lyapunov exponents and rotation number are averaged
APERIODIC_PERIODS = 2000
#: a tangent vector's growth (or decay) by less than this factor over the whole window is not resolved from
#: none: the finite-time exponent of a quasi-periodic orbit is of order log(distortion) / window, with the
#: distortion of its invariant circle a bounded factor
_GROWTH_RESOLVED = 1e3


def classify_aperiodic(scene: Scene, theta: float, v: float, rtol: float, atol: float, threads: int = 0,
                       periods: int = APERIODIC_PERIODS) -> dict:
    """Tell a quasi-periodic attractor from a chaotic one by its largest Lyapunov exponent, resolved or not.

    From (theta, v) on the attractor's section, the Lyapunov exponents
    lambda_1 >= lambda_2 (the sweep measure ``lyapunov``: Benettin's method,
    standard error ``err`` from 8 blocks) and the mean velocity are averaged
    over ``periods`` drive periods (window ``t``).  The resolution is
    ``r = max(3 err, log(1e3) / t)``: an exponent within r of 0 is not told
    from 0.  The attractor is

    * 'chaotic' when lambda_1 > r;
    * 'quasi-periodic' when abs(lambda_1) <= r and lambda_2 < -r (an
      attracting invariant circle: neutral along it, contracting across);
    * undecided (None) otherwise: lambda_1 < -r (a periodic orbit that no
      recurrence confirmed: a long period or slow convergence), lambda_2 not
      resolved, or the integration failed.

    Parameters
    ----------
    scene : Scene
        The driven scene.
    theta, v : float
        A point of the attractor on the section (the state at a whole number of drive periods).
    rtol, atol : float
        The integration's tolerances.
    threads : int, optional
        OpenMP threads.
    periods : int, optional
        Drive periods of the window (default APERIODIC_PERIODS).

    Returns
    -------
    dict
        ``kind`` ('chaotic', 'quasi-periodic' or None), ``lyapunov`` (lambda_1, lambda_2, err) per unit
        time, ``resolution`` r, ``rotation_number`` (mean turns per drive period) and ``dimension`` (the
        Kaplan-Yorke dimension on the section for a chaotic attractor, else NaN).

    See Also
    --------
    pendula.sweep : the ``lyapunov`` measure computes the exponents.

    Examples
    --------
    >>> import pendula
    >>> from pendula.dynamics.attractors import classify_aperiodic
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.2, drive_frequency=2/3)
    >>> classify_aperiodic(sc, 0.3, 0.0, 1e-10, 1e-12, periods=500)["kind"]
    'chaotic'
    """
    from .._sweep_engine import PARAM_ORDER, block
    from .periodic import forcing_frequency
    tp = TWO_PI / forcing_frequency(scene)
    p = np.empty((len(PARAM_ORDER), 1), order="F")
    for j, f in enumerate(PARAM_ORDER):
        p[j] = getattr(scene, f)
    p[PARAM_ORDER.index("theta0")], p[PARAM_ORDER.index("v0")] = theta, v
    t = periods * tp
    ly, st = block(5, p, rtol, atol, 0.0, t, 3, threads)
    mv, st2 = block(2, p, rtol, atol, 0.0, t, 3, threads)
    lam1, err, lam2 = (float(x) for x in ly[:, 0])
    res = max(3.0 * err, math.log(_GROWTH_RESOLVED) / t)
    # the mean velocity is decided (0) or phase-locked to a step (6: a chaotic set whose phase stays bounded
    # on a step's line, as the oscillating chaos of the driven pendulum, is locked to step 0)
    mv_decided = st2[0] in (0, 6)
    kind = None
    if st[0] == 0 and mv_decided and all(math.isfinite(x) for x in (lam1, err, lam2)):
        if lam1 > res:
            kind = "chaotic"
        elif abs(lam1) <= res and lam2 < -res:
            kind = "quasi-periodic"
    return {"kind": kind, "lyapunov": (lam1, lam2, err), "resolution": res,
            "rotation_number": float(mv[0, 0]) * tp / TWO_PI if mv_decided else math.nan,
            "dimension": kaplan_yorke_dimension([lam1, lam2]) if kind == "chaotic" else math.nan}


def boundary_fraction(labels) -> float:
    """The fraction of points of a label map with a grid neighbour (along any axis) of another label.

    Parameters
    ----------
    labels : array_like of int
        A label map (any number of axes).

    Returns
    -------
    float

    Examples
    --------
    >>> from pendula.dynamics.attractors import boundary_fraction
    >>> boundary_fraction([[0, 0, 1, 1]])
    0.5
    """
    return float(edge_mask(np.asarray(labels)).mean())


def basin_entropy(labels, box: int = 5) -> tuple[float, float]:
    """The basin entropy S_b and boundary basin entropy S_bb of a 2-D label map (Daza et al. 2016).

    Parameters
    ----------
    labels : array_like of int, 2-D
        The label map.
    box : int, optional
        The side of the boxes in points (default 5).

    Returns
    -------
    S_b, S_bb : float
        The mean over all boxes, and over the boxes that hold more than one label,
        of -sum p log p (natural log); S_bb is 0 when no box holds two labels.

    Examples
    --------
    >>> import numpy as np
    >>> from pendula.dynamics.attractors import basin_entropy
    >>> lab = np.zeros((10, 10), int); lab[:, 5:] = 1
    >>> [round(x, 6) for x in basin_entropy(lab)]
    [0.0, 0.0]
    """
    lab = np.asarray(labels)
    if lab.ndim != 2:
        raise ValueError("basin_entropy needs a 2-D label map")
    nx, ny = lab.shape[0] // box, lab.shape[1] // box
    if nx == 0 or ny == 0:
        raise ValueError(f"the map ({lab.shape}) is smaller than one box of {box} x {box} points")
    blocks = lab[:nx * box, :ny * box].reshape(nx, box, ny, box).transpose(0, 2, 1, 3).reshape(nx * ny, -1)
    ent = np.zeros(blocks.shape[0])
    for u in np.unique(blocks):
        p = (blocks == u).mean(axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            ent -= np.where(p > 0, p * np.log(p), 0.0)
    boundary = ent > 0
    return float(ent.mean()), float(ent[boundary].mean()) if boundary.any() else 0.0


def uncertainty_exponent(labels, max_shift: int | None = None) -> tuple[float, np.ndarray, np.ndarray]:
    """The uncertainty exponent of a label map from the grid itself.

    f(e) is the fraction of points whose label differs from that of a point
    e grid steps away along some axis (either side), for e = 1, 2, 4, ...;
    alpha is the least-squares slope of log f against log e.

    Parameters
    ----------
    labels : array_like of int
        The label map.
    max_shift : int, optional
        The largest e (default a sixteenth of the smallest axis).

    Returns
    -------
    alpha : float
        NaN when the map has one label only.
    e, f : numpy.ndarray
        The shifts (grid steps) and the fractions.

    Examples
    --------
    >>> import numpy as np
    >>> from pendula.dynamics.attractors import uncertainty_exponent
    >>> x, y = np.meshgrid(np.linspace(-1, 1, 400), np.linspace(-1, 1, 400))
    >>> round(uncertainty_exponent((x**2 + y**2 < 0.5).astype(int))[0], 2)   # a smooth boundary
    1.0
    """
    lab = np.asarray(labels)
    m = max(1, min(lab.shape) // 16) if max_shift is None else int(max_shift)
    es, fs = [], []
    e = 1
    while e <= m:
        changed = np.zeros(lab.shape, dtype=bool)
        for ax in range(lab.ndim):
            if lab.shape[ax] <= e:
                continue
            d = np.take(lab, range(e, lab.shape[ax]), axis=ax) != np.take(lab, range(0, lab.shape[ax] - e), axis=ax)
            lo = [slice(None)] * lab.ndim
            hi = [slice(None)] * lab.ndim
            lo[ax] = slice(0, lab.shape[ax] - e)
            hi[ax] = slice(e, None)
            changed[tuple(lo)] |= d
            changed[tuple(hi)] |= d
        es.append(e)
        fs.append(changed.mean())
        e *= 2
    es, fs = np.array(es, dtype=float), np.array(fs)
    ok = fs > 0
    if ok.sum() < 2:
        return math.nan, es, fs
    alpha = float(np.polyfit(np.log(es[ok]), np.log(fs[ok]), 1)[0])
    return alpha, es, fs


@dataclass
class AttractorMap:
    """The attractor of each initial state on a grid, the attractors, and the basin measures.

    Attributes
    ----------
    dataset : xarray.Dataset
        ``attractor`` (int label, -1 undecided) and ``period`` on the grid's
        axes, with CF attributes; the sweep's options as attributes.
    attractors : list of Attractor
    boundary_fraction : float
    basin_entropy, boundary_basin_entropy : float
        NaN unless the grid has two axes.
    uncertainty_exponent : float
        NaN when the map holds one attractor.
    undecided : int
        Points decided by no rule within the limit (label -1), or whose integration failed.
    rechecked, recheck_changed : int
        Basin-boundary points run again at the tight tolerances, and how many of them changed label.
    """

    dataset: object
    attractors: list
    boundary_fraction: float
    basin_entropy: float
    boundary_basin_entropy: float
    uncertainty_exponent: float
    undecided: int = 0
    rechecked: int = 0
    recheck_changed: int = 0

    def __repr__(self) -> str:
        ds = self.dataset
        try:
            grid = " x ".join(f"{d} {n}" for d, n in ds.sizes.items())
        except AttributeError:
            grid = "?"
        atts = "; ".join(f"{a.label}: {a.kind}" + (f" period {a.period}" if a.kind == "periodic" else "")
                         + f" ({a.fraction:.0%})" for a in self.attractors)
        return (f"AttractorMap(grid {grid}, {len(self.attractors)} attractors [{atts}], "
                f"undecided={self.undecided}, boundary_fraction={self.boundary_fraction:.3g}, "
                f"uncertainty_exponent={self.uncertainty_exponent:.3g})")


# ---------------------------------------------------------------------------
# The attractors a recurrence search has found, and the kernel's table of their cells
# ---------------------------------------------------------------------------

def cell_ids(theta, v, width: float) -> np.ndarray:
    """The cell of width ``width`` holding each (theta, v), theta in [-pi, pi): the kernel's numbering
    (pendula_attractors%at_cell_id): ``j * ni + i`` with ``i = floor((theta + pi) / width)`` (at most
    ``ni - 1``), ``j = floor(v / width)`` and ``ni = ceil(2 pi / width)`` cells across one turn."""
    th = np.asarray(theta, dtype=float)
    ni = math.ceil(TWO_PI / width)
    i = np.clip(np.floor((th + math.pi) / width), 0, ni - 1).astype(np.int64)
    j = np.floor(np.clip(np.asarray(v, dtype=float) / width, -1e6, 1e6)).astype(np.int64)
    return j * ni + i


def _dilate(cells: np.ndarray, width: float) -> np.ndarray:
    """The cells and their 8 neighbours (the angle wraps around)."""
    ni = math.ceil(TWO_PI / width)
    j, i = np.divmod(np.asarray(cells, dtype=np.int64), ni)
    out = [((j + dj) * ni + (i + di) % ni) for dj in (-1, 0, 1) for di in (-1, 0, 1)]
    return np.unique(np.concatenate(out))


class AttractorSet:
    """The attractors found so far by the recurrence search, in the order found (indices never change).

    ``add_periodic`` and ``add_chaotic`` return the index of the attractor a
    newly found one is (an old one it matches, or a new entry): two periodic
    orbits are one when their periods and windings agree and every point of
    one lies within ``merge_tol`` of a point of the other; two chaotic sets
    are one when they share at least a tenth of the smaller set's cells (the
    cells are then united).  ``table`` gives the kernel's labelling table: each
    attractor's cells (a periodic orbit's points, a chaotic set's visited
    cells) with their 8 neighbours; a cell claimed by two attractors labels
    neither.
    """

    def __init__(self, cell: float, merge_tol: float, need_periodic: int, need_chaotic: int):
        self.cell, self.merge_tol = cell, merge_tol
        self.need = {"periodic": need_periodic, "chaotic": need_chaotic}
        self.items: list[dict] = []

    def copy(self) -> AttractorSet:
        new = AttractorSet(self.cell, self.merge_tol, self.need["periodic"], self.need["chaotic"])
        new.items = [dict(a) for a in self.items]
        return new

    def add_periodic(self, k: int, winding: int, theta, v, monodromy) -> int:
        theta, v = np.asarray(theta, dtype=float), np.asarray(v, dtype=float)
        for idx, a in enumerate(self.items):
            if a["kind"] == "periodic" and a["period"] == k and a["winding"] == winding and theta.size == \
                    a["theta"].size:
                d = _dist(theta[:, None], v[:, None], a["theta"][None, :], a["v"][None, :]).min(axis=1)
                if d.max() < self.merge_tol:
                    return idx
        q = int(np.argmin(theta))      # the cycle from its point of smallest angle
        self.items.append({"kind": "periodic", "period": int(k), "winding": int(winding),
                           "theta": np.roll(theta, -q), "v": np.roll(v, -q),
                           "monodromy": np.asarray(monodromy, dtype=float).reshape(2, 2),
                           "cells": np.unique(cell_ids(theta, v, self.cell))})
        return len(self.items) - 1

    def add_chaotic(self, cells, point: tuple[float, float] = (math.nan, math.nan),
                    fields: dict | None = None) -> int:
        """A non-periodic attractor by its cells (kind 'chaotic' until ``classify_aperiodic`` says
        more), a point of it on the section and the scene fields of the grid point that found it."""
        cells = np.unique(np.asarray(cells, dtype=np.int64))
        for idx, a in enumerate(self.items):
            if a["kind"] != "periodic":
                shared = np.intersect1d(a["cells"], cells, assume_unique=True).size
                if shared > 0 and 10 * shared >= min(a["cells"].size, cells.size):
                    a["cells"] = np.union1d(a["cells"], cells)
                    return idx
        self.items.append({"kind": "chaotic", "period": 0, "winding": 0, "cells": cells,
                           "point": (float(point[0]), float(point[1])), "fields": dict(fields or {})})
        return len(self.items) - 1

    def table(self, kinds: tuple = ("periodic", "chaotic")) -> tuple:
        """(kcell sorted, klab, need, cth, cv, catt, crad): the kernel's table of the attractors of these
        kinds, with the periodic attractors' cycle points and confirmation radii (:meth:`confirm_radius`);
        ValueError when the cell width cannot tell two attractors apart (every cell of one is claimed by
        another)."""
        cth, cv, catt, crad = self._cycle_table(kinds)
        if not any(a["kind"] in kinds for a in self.items):
            return (np.array([-2**62], np.int64), np.array([-1], np.int32), np.ones(max(1, len(self.items)),
                                                                                     np.int32), cth, cv, catt,
                    crad)
        ids, labs = [], []
        for idx, a in enumerate(self.items):
            if a["kind"] not in kinds:
                continue
            c = _dilate(a["cells"], self.cell)
            ids.append(c)
            labs.append(np.full(c.size, idx, dtype=np.int32))
        ids, labs = np.concatenate(ids), np.concatenate(labs)
        uniq, inv = np.unique(ids, return_inverse=True)
        lo = np.full(uniq.size, len(self.items), dtype=np.int32)
        hi = np.full(uniq.size, -1, dtype=np.int32)
        np.minimum.at(lo, inv, labs)
        np.maximum.at(hi, inv, labs)
        # a cell of two attractors labels neither: the orbit goes on until it is in cells of one only
        keep = lo == hi
        kcell, klab = uniq[keep], lo[keep]
        for idx, a in enumerate(self.items):
            if a["kind"] in kinds and not np.isin(a["cells"], kcell).any():
                other = sorted({int(x) for x in labs[np.isin(ids, a["cells"])] if x != idx})
                raise ValueError(f"parameter 'cell': cells {self.cell:g} wide cannot tell attractor {idx} "
                                 f"({a['kind']}) from attractor(s) {other}: every cell of it is another's too; "
                                 "use a smaller cell")
        need = np.array([self.need.get(a["kind"], self.need["chaotic"]) for a in self.items], dtype=np.int32)
        return np.ascontiguousarray(kcell, np.int64), np.ascontiguousarray(klab, np.int32), need, cth, cv, catt, crad

    def confirm_radius(self, idx: int) -> float:
        """The confirmation radius of periodic attractor idx: 0 (none: its cells alone label an orbit) when
        every other attractor lies at least _CLOSE_CELLS cells away from it; else a quarter of that distance
        (to the nearest point of another periodic attractor, or cell of a non-periodic one, max-norm, angle
        modulo 2 pi): an orbit in its cells is labelled only once it comes that close to one of its cycle
        points, well inside the half-way line to the other attractor, where cells of this width (whose
        neighbours label too) reach past it."""
        a = self.items[idx]
        if a["kind"] != "periodic":
            return 0.0
        sep = math.inf
        ni = math.ceil(TWO_PI / self.cell)
        for j, b in enumerate(self.items):
            if j == idx:
                continue
            if b["kind"] == "periodic":
                bth, bv, pad = b["theta"], b["v"], 0.0
            else:
                jj, ii = np.divmod(b["cells"], ni)
                bth, bv, pad = (ii + 0.5) * self.cell - math.pi, (jj + 0.5) * self.cell, 0.5 * self.cell
            d = _dist(a["theta"][:, None], a["v"][:, None], np.asarray(bth)[None, :], np.asarray(bv)[None, :])
            sep = min(sep, float(d.min()) - pad)
        if sep >= _CLOSE_CELLS * self.cell:
            return 0.0
        return max(sep, 0.0) / 4

    def _cycle_table(self, kinds: tuple):
        """(cth, cv, catt, crad): the cycle points of the periodic attractors among ``kinds`` that have a
        confirmation radius, their attractor, and each attractor's radius (0: none)."""
        crad = np.zeros(max(1, len(self.items)))
        th, v, att = [], [], []
        for idx, a in enumerate(self.items):
            if a["kind"] == "periodic" and a["kind"] in kinds:
                crad[idx] = self.confirm_radius(idx)
                if crad[idx] > 0:
                    th.append(a["theta"])
                    v.append(a["v"])
                    att.append(np.full(a["theta"].size, idx))
        if not th:
            return np.zeros(1), np.zeros(1), np.full(1, -1, np.int32), crad
        return (np.ascontiguousarray(np.concatenate(th), float), np.ascontiguousarray(np.concatenate(v), float),
                np.ascontiguousarray(np.concatenate(att), np.int32), crad)

    def attractors(self, counts: np.ndarray, npts: int) -> tuple[list, np.ndarray]:
        """The attractors with points in their basins, numbered by the rule on the attractors alone
        (periodic by period, then the angle and velocity of their first point; chaotic ones after them
        by basin size, then by their smallest cell), and the map from indices here to those labels
        (-1 for attractors with no point)."""
        live = [i for i in range(len(self.items)) if counts[i] > 0]

        def key(i):
            a = self.items[i]
            if a["kind"] == "periodic":
                return (0, a["period"], round(float(a["theta"][0]), 6), round(float(a["v"][0]), 6), 0, 0)
            return (1, 0, 0.0, 0.0, -int(counts[i]), int(a["cells"][0]))
        live.sort(key=key)
        remap = np.full(len(self.items) + 1, -1, dtype=np.int64)
        out = []
        ni = math.ceil(TWO_PI / self.cell)
        for lab, i in enumerate(live):
            a = self.items[i]
            remap[i] = lab
            if a["kind"] == "periodic":
                mu = np.linalg.eigvals(a["monodromy"]).astype(complex)
                mu = mu[np.argsort(-np.abs(mu), kind="stable")]
                out.append(Attractor(lab, "periodic", a["period"], a["theta"].copy(), a["v"].copy(),
                                     counts[i] / max(npts, 1), mu, a["winding"]))
            else:
                j, ii = np.divmod(a["cells"], ni)
                info = a.get("classified", {})
                out.append(Attractor(lab, a["kind"], 0, (ii + 0.5) * self.cell - math.pi, (j + 0.5) * self.cell,
                                     counts[i] / max(npts, 1), lyapunov=tuple(info.get("lyapunov", ())),
                                     rotation_number=info.get("rotation_number", math.nan),
                                     dimension=info.get("dimension", math.nan)))
        return out, remap

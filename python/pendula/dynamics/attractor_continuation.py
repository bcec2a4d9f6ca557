"""Attractors followed over a parameter: an attractor map at each value, its
attractors matched to the previous value's, and the basin fractions of each
(the attractors' birth, death and the change of their basins).
"""

from __future__ import annotations

import json
import math
import os
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from .. import _checks
from .._optional import require
from .._sweep_engine import AXIS_META, check_driven, check_over, check_work
from ..scene import GRIDDABLE, Scene, SceneError
from ..systems import contract
from .attractor_maps import attractor_map, recurrence_options

if TYPE_CHECKING:   # xarray and distributed are optional: named in annotations only
    import distributed
    import xarray

__all__ = ["attractor_continuation"]


def _attractor_distance(a, b) -> float:
    """The distance of two attractors on the section (max-norm, angle modulo 2 pi): the largest distance
    from a point of either to the nearest point of the other (Hausdorff); periodic attractors by their
    cycle points, chaotic ones by their cells' centres.  Attractors of another kind or period are
    infinitely far apart."""
    from .attractors import _dist
    if a["kind"] != b["kind"] or a["period"] != b["period"]:
        return math.inf
    ta, va, tb, vb = (np.asarray(a["theta"]), np.asarray(a["v"]), np.asarray(b["theta"]), np.asarray(b["v"]))
    d = _dist(ta[:, None], va[:, None], tb[None, :], vb[None, :])
    return float(max(d.min(axis=1).max(), d.min(axis=0).max()))


def attractor_continuation(scene: Scene, over: dict[str, ArrayLike], param: str, values: ArrayLike, *,
                           match_tol: float = 0.5, out: str | os.PathLike[str] | None = None, threads: int = 0,
                           client: distributed.Client | None = None, progress: bool = False,
                           **options: float | int) -> xarray.Dataset:
    """The attractors of a driven scene and their basin fractions as one scene field moves.

    At each value of ``param`` the attractor map over the grid ``over`` is
    computed (:func:`attractor_map`, method 'recurrence', with ``options``);
    each attractor is then matched to one of the previous value's attractors:
    the pairs of the same kind and period are taken in order of their distance
    on the section (the Hausdorff distance in the max-norm, angle modulo 2 pi,
    between a periodic attractor's cycle points or a chaotic attractor's cells),
    nearest first, each attractor at most once, while the distance is below
    ``match_tol``; an attractor left unmatched is a new one (Datseris, Rossi &
    Wagemakers 2023, "global continuation", with matching by distance).  An
    attractor that vanishes and comes back later is a new one.

    Parameters
    ----------
    scene : Scene
        A periodically driven scene.
    over : dict
        The grid of initial states (e.g. ``{'theta0': ..., 'v0': ...}``).
    param : str
        The scene field that moves (one of ``eps``, ``damping``, ``torque``,
        ``drive_amplitude``, ``drive_frequency``, ``drive_phase``), not an axis of ``over``.
    values : array_like
        Its values, strictly increasing or strictly decreasing (at least 1).
    match_tol : float, optional
        The largest distance at which two attractors of neighbouring values are one (default 0.5).
    out : str or path, optional
        A folder for a resumable run: each value's map is a store ``out/value_NNNN/sweep.zarr`` and its
        summary ``out/value_NNNN/summary.json``; started again with the same ``out``, finished values are
        read back and unfinished ones resumed.  A folder of another continuation is refused.
    threads, client, progress : optional
        As for :func:`pendula.sweep`.
    **options
        The options of :func:`attractor_map` (``cell``, ``consecutive``, ``max_periods``, ``rtol`` ...).

    Returns
    -------
    xarray.Dataset
        ``fraction`` on (``param``, ``attractor``): the fraction of the grid in each attractor's basin,
        NaN where the attractor does not exist; ``undecided`` on (``param``): the fraction of points
        decided by no rule; coordinates ``kind`` and ``period`` on ``attractor``; ``theta`` and ``v``
        (``param``, ``attractor``): the attractor's first cycle point (NaN for a chaotic one).

    Raises
    ------
    TypeError
        A wrong kind of argument (named).
    ValueError
        An unknown or gridded ``param``, values that are not finite or not monotonic, an ``out`` that
        holds another continuation, or a bad option of :func:`attractor_map`.

    See Also
    --------
    attractor_map : one value's attractors and basins.

    Examples
    --------
    >>> import numpy as np, pendula
    >>> sc = pendula.Scene(damping=0.5, drive_frequency=2/3)
    >>> ds = pendula.attractor_continuation(sc, {"theta0": np.linspace(-3, 3, 6), "v0": np.linspace(-3, 3, 6)},
    ...                                     "drive_amplitude", [1.34, 1.35])
    >>> ds.fraction.sizes["attractor"], [int(p) for p in ds.period.values]
    (2, [1, 1])
    >>> bool(np.allclose(ds.fraction.sum("attractor") + ds.undecided, 1.0))
    True
    """
    xr = require("xarray", "sweep", "pendula.attractor_continuation")
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a pendula.Scene, got {type(scene).__name__}")
    fields = tuple(f for f in GRIDDABLE if f not in ("theta0", "v0"))
    if not isinstance(param, str) or param not in fields:
        raise ValueError(f"parameter 'param' must be one of {', '.join(fields)}; got {param!r}")
    if isinstance(over, dict) and param in over:
        raise ValueError(f"parameter 'param': {param!r} is an axis of 'over' too")
    vals = _checks.grid_values(values, "parameter 'values'")
    if vals.size > 1 and not (np.all(np.diff(vals) > 0) or np.all(np.diff(vals) < 0)):
        raise ValueError("parameter 'values' must be strictly increasing or strictly decreasing (the attractors "
                         "are followed from one value to the next)")
    match_tol = _checks.real(match_tol, "match_tol", 0.0, lo_open=True)
    for bad in ("method", "transient", "samples", "tol", "out", "chunk_points"):
        if bad in options:
            raise TypeError(f"attractor_continuation: {bad!r} is not an option here (method 'recurrence' only)")
    for v in (vals.min(), vals.max()):
        try:
            scene.replace(**{param: float(v)})
        except SceneError as exc:
            raise ValueError(f"parameter 'values': {exc}") from None
    over_c = check_over(scene, over)
    contract.require(scene, "attractor_continuation", over=tuple(over_c) + (param,))
    check_driven(scene.replace(**{param: float(vals[0])}), over_c, "attractor_continuation")
    opts = recurrence_options(options)     # checked once, before any work
    for val in vals:
        sv = scene.replace(**{param: float(val)})
        check_driven(sv, over_c, "attractor_continuation")
        check_work(sv, over_c, opts["max_periods"])
    root = None
    if out is not None:
        from .._store import _write_json_atomic
        root = _checks.path(out, "out")    # the one checker: '' is refused, never the current folder
        if root.exists() and not root.is_dir():
            raise NotADirectoryError(20, "is not a folder", str(root))
        ident = {"scene": scene.to_namelist(), "over": {k: v.tolist() for k, v in over_c.items()}, "param": param,
                 "values": vals.tolist(), "match_tol": match_tol, "options": opts}
        root.mkdir(exist_ok=True)
        idf = root / "continuation.json"
        if idf.exists():
            try:
                old = json.loads(idf.read_text())
            except (OSError, ValueError):
                old = None
            if old != json.loads(json.dumps(ident)):
                raise ValueError(f"parameter 'out': {root} holds another continuation (or a damaged one); "
                                 "use another folder")
        else:
            _write_json_atomic(idf, ident)
    per_value = []
    for i, val in enumerate(vals):
        summary = None
        if root is not None:
            sf = root / f"value_{i:04d}" / "summary.json"
            if sf.exists():
                try:
                    summary = json.loads(sf.read_text())
                except (OSError, ValueError):
                    summary = None
        if summary is None:
            am = attractor_map(scene.replace(**{param: float(val)}), over_c, threads=threads, client=client,
                               progress=progress, out=None if root is None else root / f"value_{i:04d}", **options)
            npts = am.dataset.attractor.size
            summary = {"value": float(val), "undecided": am.undecided / npts,
                       "attractors": [{"kind": a.kind, "period": a.period, "fraction": a.fraction,
                                       "theta": np.asarray(a.theta).tolist(), "v": np.asarray(a.v).tolist()}
                                      for a in am.attractors]}
            if root is not None:
                _write_json_atomic(root / f"value_{i:04d}" / "summary.json", summary)
        per_value.append(summary)
    # matching, value to value
    ids = []          # per value: the continued attractor id of each attractor
    kinds, periods = [], []
    for i, s in enumerate(per_value):
        cur = s["attractors"]
        assign = [-1] * len(cur)
        if i > 0:
            prev = per_value[i - 1]["attractors"]
            pairs = sorted((_attractor_distance(a, b), ja, jb) for ja, a in enumerate(cur) for jb, b in enumerate(prev))
            used = set()
            for d, ja, jb in pairs:
                if d >= match_tol:
                    break
                if assign[ja] < 0 and jb not in used:
                    assign[ja] = ids[i - 1][jb]
                    used.add(jb)
        for ja, a in enumerate(cur):
            if assign[ja] < 0:
                assign[ja] = len(kinds)
                kinds.append(a["kind"])
                periods.append(a["period"])
        ids.append(assign)
    n_att = len(kinds)
    frac = np.full((vals.size, n_att), np.nan)
    th = np.full((vals.size, n_att), np.nan)
    vv = np.full((vals.size, n_att), np.nan)
    for i, s in enumerate(per_value):
        for ja, a in enumerate(s["attractors"]):
            frac[i, ids[i][ja]] = a["fraction"]
            if a["kind"] == "periodic":
                th[i, ids[i][ja]], vv[i, ids[i][ja]] = a["theta"][0], a["v"][0]
    meta = AXIS_META[param]
    dims = (param, "attractor")
    return xr.Dataset(
        {"fraction": (dims, frac, {"long_name": "fraction of the grid in the attractor's basin (NaN: the "
                                                "attractor does not exist)", "units": "1"}),
         "undecided": ((param,), np.array([s["undecided"] for s in per_value]),
                       {"long_name": "fraction of the grid decided by no rule within max_periods", "units": "1"}),
         "theta": (dims, th, {"long_name": "first point of the periodic attractor on the section", "units": "rad"}),
         "v": (dims, vv, {"long_name": "first point of the periodic attractor on the section",
                          "units": "rad s-1"})},
        coords={param: (param, vals, {"long_name": meta[0], "units": meta[1]}),
                "attractor": ("attractor", np.arange(n_att), {"long_name": "attractor, continued over the values"}),
                "kind": ("attractor", np.array(kinds, dtype=str), {"long_name": "periodic or chaotic"}),
                "period": ("attractor", np.array(periods, dtype=np.int32),
                           {"long_name": "period in drive periods (0 chaotic)", "units": "1"})},
        attrs={"Conventions": "CF-1.10", "title": f"pendula attractor continuation: basin fractions over {param}",
               "scene": scene.to_namelist(), "param": param, "match_tol": match_tol,
               "matching": "attractors of one kind and period matched to the previous value's by Hausdorff "
                           "distance on the section (max-norm, angle modulo 2 pi), nearest pairs first, below "
                           "match_tol", **opts})

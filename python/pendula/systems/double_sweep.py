"""The double pendulum's flip-time map as a sweep: chunks of rows of the
(theta1, theta2) grid computed by the kernel on OpenMP threads, in memory,
into a resumable Zarr store, or on a Dask cluster, through the sweep engine
(:mod:`pendula._sweep_engine`, :mod:`pendula._store`, :mod:`pendula._cluster`).

Every pixel is computed on its own (the kernel's flip search from rest at
that pixel, at the tolerance and at a tenth of it), so a pixel's numbers do
not depend on the chunk it falls in, the thread that ran it or the run that
wrote it: a resumed or distributed map equals the one-piece map bit for bit.
"""

from __future__ import annotations

import hashlib
import json

import numpy as np

#: status of a pixel: 0 computed; otherwise the kernel's integrator status (pendula_integrators st_*)
FLIP_STATUS = {0: "computed", 1: "bad step", 2: "bad tolerances", 5: "step size underflow", 6: "non-finite state",
               7: "too many steps", 8: "cancelled"}


class FlipPlan:
    """Everything that defines a flip-time map's result (the pendulum, the axes, the search), and its chunks:
    ``rows`` whole rows of theta1 each, one Zarr chunk per chunk.  ``pendulum``: the DoublePendulum (not
    imported here: double_motion imports this module)."""

    def __init__(self, pendulum, theta1: np.ndarray, theta2: np.ndarray, t_max: float, rtol: float,
                 atol: float, agree: float, chunk_points: int):
        self.pendulum = pendulum
        self.over = {"theta1": theta1, "theta2": theta2}
        self.t_max, self.rtol, self.atol, self.agree = t_max, rtol, atol, agree
        self.shape = (theta1.size, theta2.size)
        self.rows = max(1, min(chunk_points // theta2.size, theta1.size))
        self.nchunks = -(-self.shape[0] // self.rows)

    def key(self) -> dict:
        """The map's identity: the pendulum, the axes (length, ends, SHA-256 of the values), the search."""
        def axis(v):
            v = np.ascontiguousarray(v, dtype="<f8")
            return {"n": int(v.size), "first": float(v[0]), "last": float(v[-1]),
                    "sha256": hashlib.sha256(v.tobytes()).hexdigest()}
        return {"system": "double_pendulum", "measure": "flip_time",
                "pendulum": [float(x) for x in self.pendulum._p], "over": {k: axis(v) for k, v in self.over.items()},
                "t_max": self.t_max, "rtol": self.rtol, "atol": self.atol, "agree": self.agree, "rows": self.rows}


def flip_chunk(plan: FlipPlan, i: int, threads: int):
    """Chunk i of the map: (i, values (rows, n2, 4): flip time, its check, forbidden, unresolved; status)."""
    lo = i * plan.rows
    hi = min(lo + plan.rows, plan.shape[0])
    g1, g2 = np.meshgrid(plan.over["theta1"][lo:hi], plan.over["theta2"], indexing="ij")
    tf, tc, forbidden, moved, st = plan.pendulum._flip_pixels(g1, g2, plan.t_max, plan.rtol, plan.atol, plan.agree,
                                                              threads, raise_on_status=False)
    return i, np.stack([tf, tc, forbidden, moved], axis=-1), st


def flip_vars(plan: FlipPlan, out: np.ndarray, st: np.ndarray) -> dict:
    """One chunk's output as the map's variables."""
    return {"time": out[..., 0], "check": out[..., 1], "forbidden": out[..., 2].astype(np.int8),
            "unresolved": out[..., 3].astype(np.int8), "status": st.astype(np.int32)}


def _meta(theta1: np.ndarray, theta2: np.ndarray):
    """The map's coordinates and variables (dims, dtype, CF attributes, the store's fill value)."""
    from .._store import Variable

    dims = ("theta1", "theta2")
    coords = {"theta1": (theta1, {"long_name": "initial angle of the first arm from the downward vertical, at rest",
                                  "units": "rad"}),
              "theta2": (theta2, {"long_name": "initial angle of the second arm from the downward vertical, at rest",
                                  "units": "rad"})}
    variables = {
        "time": Variable(dims, np.dtype(np.float64), {
            "long_name": "first time either arm passes over the top (abs(theta) = pi); inf: no flip by t_max",
            "units": "1"}, np.nan),
        "check": Variable(dims, np.dtype(np.float64), {
            "long_name": "the flip time again at the tolerances tightened tenfold", "units": "1"}, np.nan),
        "forbidden": Variable(dims, np.dtype(np.int8), {
            "long_name": "1: the energy forbids either arm to flip (skipped, time inf exactly)", "units": "1"}, -1),
        "unresolved": Variable(dims, np.dtype(np.int8), {
            "long_name": "1: the answer moves when the tolerances are tightened tenfold", "units": "1"}, -1),
        "status": Variable(dims, np.dtype(np.int32), {
            "long_name": "status of the pixel: 0 computed, else the integrator's failure",
            "flag_values": np.array(sorted(FLIP_STATUS), dtype=np.int32),
            "flag_meanings": " ".join(FLIP_STATUS[k].replace(" ", "_") for k in sorted(FLIP_STATUS)),
            "comment": "-1 (the store's fill value) only in a store whose map has not finished: not computed yet"},
            -1)}
    return coords, variables


def _attrs(t_max: float, rtol: float, agree: float) -> dict:
    return {"Conventions": "CF-1.10", "title": "pendula flip-time map of the double pendulum", "t_max": t_max,
            "rtol": rtol, "agree": agree, "status_codes": json.dumps(FLIP_STATUS)}


def flip_layout(plan: FlipPlan):
    """The map's dataset apart from its values: axes, variables with CF attributes, identity."""
    from .._store import Layout

    coords, variables = _meta(plan.over["theta1"], plan.over["theta2"])
    p = plan.pendulum
    attrs = {**_attrs(plan.t_max, plan.rtol, plan.agree), "atol": plan.atol,
             "m1": p.m1, "m2": p.m2, "l1": p.l1, "l2": p.l2, "g": p.g, "rods": int(p.rods),
             "damping": [float(x) for x in p.damping]}
    return Layout(axes=dict(plan.over), coords=coords, variables=variables, rows=plan.rows,
                  identity=json.dumps(plan.key(), sort_keys=True), attrs=attrs)


def flip_dataset(fm):
    """A FlipMap as the Dataset flip_sweep gives (its variables and their attributes; status 0)."""
    from .._optional import require
    xr = require("xarray", "xarray", "FlipMap.to_xarray")

    coords, variables = _meta(fm.theta1, fm.theta2)
    vals = {"time": fm.time, "check": fm.check, "forbidden": fm.forbidden.astype(np.int8),
            "unresolved": fm.unresolved.astype(np.int8), "status": np.zeros(fm.time.shape, dtype=np.int32)}
    data = {n: (v.dims, np.asarray(vals[n], dtype=v.dtype), dict(v.attrs)) for n, v in variables.items()}
    return xr.Dataset(data, coords={n: (n, c, dict(a)) for n, (c, a) in coords.items()},
                      attrs=_attrs(fm.t_max, fm.rtol, fm.agree))


def flip_sweep(plan: FlipPlan, out, client, threads: int, progress: bool):
    """The map of a checked plan as an xarray Dataset (lazy when stored under ``out``)."""
    from .._sweep_engine import run

    layout = flip_layout(plan)
    ds = run(plan, layout, flip_chunk, flip_vars, out, client, threads, progress, "flip map")
    ds.attrs.update(layout.attrs)
    return ds

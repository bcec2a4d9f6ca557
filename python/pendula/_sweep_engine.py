"""The sweep engine: a scene, a grid over one to three of its fields, and a
measure, computed in chunks of grid points by the kernel on OpenMP threads,
into a resumable Zarr store or over a Dask cluster.

Generic over measures and over what a chunk computes: :func:`run` takes a plan
(everything that defines the result), a layout (the dataset's variables), a
function that computes one chunk and one that turns its output into
variables.  :func:`pendula.sweep` (the measures of the kernel), the attractor
maps (:mod:`pendula.dynamics.attractor_maps`) and the I-V curve build on it.
The rules every sweep applies before any work live here too: the grid's
values (each a valid scene), the forcing of a map's measures at every grid
point, and the work of one point (the kernel's time scales).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from . import _checks, _interrupt
from ._optional import require
from ._progress import Progress
from .scene import GRIDDABLE, Scene, SceneError
from .systems import contract

if TYPE_CHECKING:   # xarray is optional: named in annotations only
    import xarray

#: kernel codes of the measures (kernel/sweep/pendula_sweep.f90)


@dataclass(frozen=True)
class Measure:
    """A measure of the kernel's sweep, declared once: what one grid point answers.

    Which scene fields it honours and which it needs (a periodic forcing for
    the stroboscopic ones) is the capability table's row ``sweep:NAME``.
    """

    name: str
    #: the kernel's measure code (kernel/sweep/pendula_sweep.f90, ms_*)
    code: int
    #: its output variables, in the kernel's order
    variables: tuple
    #: what it is, in words (figure titles)
    words: str
    #: one value of each variable per stroboscopic sample (the grid gets a 'sample' axis)
    per_sample: bool = False
    #: a discrete answer: points on a boundary are computed again at 1000 times tighter tolerances
    recheck: bool = False


MEASURE_TABLE = {m.name: m for m in (
    Measure("final_well", 1, ("well", "t_decided"), "the well an undriven damped orbit settles in", recheck=True),
    Measure("mean_velocity", 2, ("mean_velocity", "mean_velocity_err", "step"),
            "the mean velocity <v> (a junction's voltage)"),
    Measure("locked", 3, ("locked", "t_decided"), "at rest (1) or running (0)", recheck=True),
    Measure("poincare", 4, ("theta", "v"), "the state once per drive period (Poincare section)", per_sample=True),
    Measure("lyapunov", 5, ("lyapunov", "lyapunov_err", "lyapunov2"), "the largest Lyapunov exponent"))}
#: kernel codes of the measures
MEASURE_CODES = {name: m.code for name, m in MEASURE_TABLE.items()}
#: point status codes
STATUS = {0: "decided", 1: "not settled / undecided by the limit", 2: "measure does not apply",
          3: "bad measure", 4: "uncertain: the answer changes with the tolerance",
          5: "stopped (cancelled)",
          6: "locked: phase-locked to the drive, mean velocity = step * drive_frequency exactly",
          # 100 + s: the integrator's status s (pendula_integrators st_*)
          **{100 + s: f"the integrator failed: {w}" for s, w in (
              (1, "bad step"), (2, "bad tolerances"), (3, "bad method"), (5, "step size underflow"),
              (6, "non-finite state"), (7, "too many steps"), (8, "cancelled"), (9, "no dense output"),
              (10, "stopped by an event"))}}
PARAM_ORDER = ("eps", "damping", "torque", "drive_amplitude", "drive_frequency", "drive_phase", "theta0", "v0",
                "pivot_amplitude", "pivot_frequency", "friction", "drag")



def grid_of(scene: Scene) -> dict:
    """The grid a scene names (``grid``, ``gridK`` or ``gridK_range``) as {field: values}."""
    over = {}
    for k, name in enumerate(scene.grid, start=1):
        vals = getattr(scene, f"grid{k}")
        if vals:
            over[name] = np.asarray(vals, dtype=float)
        else:
            a, b, n = getattr(scene, f"grid{k}_range")
            over[name] = np.linspace(a, b, int(n))
    return over


def check_over(scene: Scene, over) -> dict:
    if not isinstance(over, dict) or not 1 <= len(over) <= 3:
        raise ValueError("parameter 'over' must be a dict of 1 to 3 {field: values}")
    out = {}
    for name, vals in over.items():
        if not isinstance(name, str) or name not in GRIDDABLE:
            raise ValueError(f"parameter 'over': cannot sweep {name!r}; one of {', '.join(GRIDDABLE)}")
        a = _checks.grid_values(vals, f"parameter 'over[{name!r}]'")
        if name == "theta0" and not np.all(np.abs(a) <= _checks.MAX_ANGLE):
            raise ValueError("parameter 'over['theta0']': |theta0| must be at most 2^52 in a sweep")
        # each value must make a valid scene (damping >= 0, eps > 0 ...)
        for v in (a.min(), a.max()):
            try:
                scene.replace(**{name: float(v)})
            except SceneError as exc:
                raise ValueError(f"parameter 'over[{name!r}]': {exc}") from None
        out[name] = a
    npts = math.prod(len(a) for a in out.values())
    if npts > _checks.MAX_GRID_POINTS:
        raise ValueError(f"parameter 'over': {npts} grid points; a sweep takes at most "
                         f"{_checks.MAX_GRID_POINTS:.0e} (split it, or use a coarser grid)")
    return out


def block(code, p, rtol, atol, t_tr, t_max, nout, threads, force=None):
    """One kernel sweep block that Ctrl-C stops (KeyboardInterrupt within a
    few integration windows; the process stays usable); ``force``: a checked user's force."""
    from . import _kernel
    cancel = _interrupt.cancel_flag()
    # the user's force (address 0: none) is called by the kernel from every thread
    faddr, fparams = _checks.force_args(force)
    out, st = _interrupt.call(_kernel.sweep_block, code, p, rtol, atol, t_tr, t_max, nout, int(threads), faddr,
                              fparams, cancel, cancel=cancel)
    if force is not None:
        force.reraise()
    if cancel[0]:
        raise KeyboardInterrupt
    return out, st


class Plan:
    """Everything that defines a sweep's result (and nothing about how it runs)."""

    def __init__(self, scene, over, measure, rtol, atol, t_max, transient, samples, chunk_points):
        self.scene = scene
        self.over = over
        self.measure = measure
        self.rtol, self.atol = rtol, atol
        self.t_max, self.transient, self.samples = t_max, transient, samples
        self.force = None   # a user's force: in-process sweeps only, never stored
        self.shape = tuple(len(v) for v in over.values())
        inner = int(np.prod(self.shape[1:], dtype=np.int64))
        # never more rows than the axis has: the chunk is also the store's Zarr chunk shape
        self.rows = max(1, min(chunk_points // max(inner, 1), self.shape[0]))
        self.nchunks = -(-self.shape[0] // self.rows)
        # the kernel's outputs per point (a stroboscopic measure: per sample); the kernel rounds the
        # transient up to whole periods of each point's own forcing where the measure samples it
        m = MEASURE_TABLE.get(measure)
        self.nout = 0 if m is None else len(m.variables) * (samples if m.per_sample else 1)
        self.t_tr = transient

    def key(self) -> dict:
        """What names the sweep (a store's identity): of bounded size whatever the grid's, each axis
        by its length, ends and the SHA-256 of its values (the values themselves are the store's
        coordinate arrays)."""
        import hashlib

        def axis(v):
            v = np.ascontiguousarray(v, dtype="<f8")
            return {"n": int(v.size), "first": float(v[0]), "last": float(v[-1]),
                    "sha256": hashlib.sha256(v.tobytes()).hexdigest()}
        return {"scene": self.scene.to_namelist(), "measure": self.measure,
                "over": {k: axis(v) for k, v in self.over.items()},
                "rtol": self.rtol, "atol": self.atol, "t_max": self.t_max, "transient": self.transient,
                "samples": self.samples, "rows": self.rows}

    def params(self, i: int) -> np.ndarray:
        """The kernel's (12, npts) parameter block of chunk i."""
        return self.params_rows(i * self.rows, min((i + 1) * self.rows, self.shape[0]))

    def params_rows(self, lo: int, hi: int) -> np.ndarray:
        """The kernel's (12, npts) parameter block of rows lo .. hi - 1 of the first axis."""
        inner = math.prod(self.shape[1:])
        return self.params_at(np.arange(lo * inner, hi * inner)), (hi - lo,) + self.shape[1:]

    def params_at(self, flat: np.ndarray) -> np.ndarray:
        """The kernel's (12, npts) parameter block of the grid points with these flat (C-order) indices."""
        flat = np.asarray(flat, dtype=np.int64)
        p = np.empty((len(PARAM_ORDER), flat.size), order="F")
        for j, f in enumerate(PARAM_ORDER):
            p[j] = getattr(self.scene, f)
        for n, ix in zip(self.over, np.unravel_index(flat, self.shape)):
            p[PARAM_ORDER.index(n)] = self.over[n][ix]
        return p


def answers(out, st):
    """The answer of each point for the boundary test: out[..., 0] when decided,
    else a value no answer takes (decided and undecided neighbours differ too)."""
    return np.where(st == 0, out[..., 0], -1e300)


def compute_chunk(plan: Plan, i: int, threads: int):
    p, shape = plan.params(i)
    if plan.scene.noise > 0:
        # thermal noise: point k of the grid (flat, first axis slowest) on the stream (seed, k)
        from . import _kernel
        first = i * plan.rows * (p.shape[1] // shape[0])
        cancel = _interrupt.cancel_flag()
        out, st = _interrupt.call(_kernel.sweep_block_noisy, p, plan.scene.noise, plan.scene.seed, first,
                                  plan.scene.dt, plan.t_tr, plan.t_max, int(threads), cancel, cancel=cancel)
        if cancel[0]:
            raise KeyboardInterrupt
        return i, out.T.reshape(shape + (plan.nout,)), st.reshape(shape)
    code = MEASURE_CODES[plan.measure]
    out, st = block(code, p, plan.rtol, plan.atol, plan.t_tr, plan.t_max, plan.nout, threads, plan.force)
    out = out.T.reshape(shape + (plan.nout,))
    st = st.reshape(shape)
    if MEASURE_TABLE[plan.measure].recheck:
        # Points on a basin boundary (a grid neighbour answers differently, along
        # any axis) are computed again at 1000 times tighter tolerances; where
        # the answer changes, it is not known: NaN and status 4.  The rows just
        # outside the chunk are computed too (first pass only), so that
        # neighbours across chunk edges count: the answer of every point
        # depends on the grid alone, never on the chunking (resume, Dask and
        # pendula-run agree bit for bit).
        lo = i * plan.rows
        hi = lo + shape[0]
        parts = [answers(out, st)]
        if lo > 0:
            pb, sb = plan.params_rows(lo - 1, lo)
            ob, tb = block(code, pb, plan.rtol, plan.atol, plan.t_tr, plan.t_max, plan.nout, threads)
            parts.insert(0, answers(ob.T.reshape(sb + (plan.nout,)), tb.reshape(sb)))
        if hi < plan.shape[0]:
            pa, sa = plan.params_rows(hi, hi + 1)
            oa, ta = block(code, pa, plan.rtol, plan.atol, plan.t_tr, plan.t_max, plan.nout, threads)
            parts.append(answers(oa.T.reshape(sa + (plan.nout,)), ta.reshape(sa)))
        edge = edge_mask(np.concatenate(parts, axis=0))
        first = 1 if lo > 0 else 0
        edge = edge[first:first + shape[0]]
        idx = np.flatnonzero(edge.ravel())
        if idx.size:
            p2 = np.asfortranarray(p[:, idx])
            o2, s2 = block(code, p2, plan.rtol * 1e-3, plan.atol * 1e-3, plan.t_tr, plan.t_max, plan.nout,
                            threads)
            flat_o = out.reshape(-1, plan.nout)
            flat_s = st.reshape(-1)
            a1 = np.where(flat_s[idx] == 0, flat_o[idx, 0], -1e300)
            a2 = np.where(s2 == 0, o2[0], -1e300)
            bad = idx[a1 != a2]
            flat_o[bad, 0] = np.nan
            flat_s[bad] = 4
    return i, out, st


#: long_name and CF units of every variable a measure gives (time in the scene's unit, the second)
VAR_META = {
    "well": ("well n of the rest angle asin(tau/eps) + 2 pi n where the orbit ends", "1"),
    "t_decided": ("time at which the answer was decided", "s"),
    "locked": ("1 when the orbit spirals into an equilibrium, 0 when it runs", "1"),
    "mean_velocity": ("mean angular velocity over t_max after the transient", "rad s-1"),
    "mean_velocity_err": ("error bar of the mean angular velocity: the larger of |<v> - <v> over the second "
                          "half of the window| and the windowing bound; 0 where locked", "rad s-1"),
    "step": ("Shapiro step p / q of a phase-locked driven orbit (<v> = p Omega / q exactly); NaN elsewhere", "1"),
    "theta": ("stroboscopic angle once per drive period, in [-pi, pi)", "rad"),
    "v": ("stroboscopic angular velocity once per drive period", "rad s-1"),
    "lyapunov": ("largest Lyapunov exponent", "s-1"),
    "lyapunov_err": ("standard error of the largest Lyapunov exponent over 8 blocks", "s-1"),
    "lyapunov2": ("second Lyapunov exponent", "s-1"),
}
#: long_name and CF units of the axes a sweep can take (and of the Poincare sample number)
AXIS_META = {
    "v0": ("initial angular velocity", "rad s-1"), "theta0": ("initial angle", "rad"),
    "eps": ("g / l, the square of the small-oscillation angular frequency", "s-2"),
    "damping": ("linear damping beta", "s-1"), "torque": ("constant torque tau", "rad s-2"),
    "drive_amplitude": ("drive amplitude A", "rad s-2"), "drive_frequency": ("drive angular frequency Omega", "rad s-1"),
    "drive_phase": ("drive phase", "rad"), "sample": ("stroboscopic sample number", "1"),
    "pivot_amplitude": ("vibrating pivot's amplitude a (units of the length)", "1"),
    "pivot_frequency": ("vibrating pivot's angular frequency Omega", "rad s-1"),
    "friction": ("dry (Coulomb) friction mu", "rad s-2"), "drag": ("quadratic drag gamma", "1"),
}
def status_attrs() -> dict:
    """CF flag attributes of 'status', from STATUS (flag_meanings: one word per code)."""
    import re
    codes = sorted(STATUS)
    return {"long_name": "status of the point's answer",
            "flag_values": np.array(codes, dtype=np.int32),
            "flag_meanings": " ".join(re.sub(r"[^0-9A-Za-z]+", "_", STATUS[c]).strip("_") for c in codes),
            "comment": "-1 (the store's fill value) only in a store whose sweep has not finished: not computed yet"}


def layout_of(plan: Plan):
    """What a sweep's dataset holds, apart from the values: the store's and the in-memory run's common form."""
    from ._store import Layout, Variable

    dims = tuple(plan.over)

    def meta(name):
        long_name, units = AXIS_META.get(name, VAR_META.get(name, (name, "1")))
        return {"long_name": long_name, "units": units}
    coords = {n: (plan.over[n], meta(n)) for n in dims}
    vdims = dims
    measure = MEASURE_TABLE[plan.measure]
    if measure.per_sample:
        coords["sample"] = (np.arange(plan.samples), meta("sample"))
        vdims = dims + ("sample",)
    variables = {"status": Variable(dims, np.dtype(np.int32), status_attrs(), -1)}
    for n in measure.variables:
        variables[n] = Variable(vdims, np.dtype(np.float64), meta(n), np.nan)
    attrs = {"Conventions": "CF-1.10", "title": f"pendula sweep: {plan.measure}", "scene": plan.scene.to_namelist(),
             "measure": plan.measure, "rtol": plan.rtol, "atol": plan.atol, "t_max": plan.t_max,
             "transient": plan.transient, "samples": plan.samples, "status_codes": json.dumps(STATUS)}
    return Layout(axes={n: plan.over[n] for n in dims}, coords=coords, variables=variables, rows=plan.rows,
                  identity=json.dumps(plan.key(), sort_keys=True), attrs=attrs)


def chunk_vars(plan: Plan, out: np.ndarray, st: np.ndarray) -> dict:
    """The kernel's output of one chunk as {variable: values}."""
    names = MEASURE_TABLE[plan.measure].variables
    if MEASURE_TABLE[plan.measure].per_sample:
        vals = {n: out[..., k::len(names)] for k, n in enumerate(names)}
    else:
        vals = {n: out[..., k] for k, n in enumerate(names)}
    vals["status"] = st.astype(np.int32)
    return vals


def chunk_dataset(layout, i: int, vals: dict):
    xr = require("xarray", "xarray", "pendula.sweep")
    lo, hi = layout.rows_of(i)
    coords = {n: xr.Variable((n,), v[lo:hi] if n == layout.first else v, dict(a))
              for n, (v, a) in layout.coords.items()}
    data = {n: (var.dims, vals[n], dict(var.attrs)) for n, var in layout.variables.items()}
    return xr.Dataset(data, coords=coords)


def run(plan, layout, compute, to_vars, out, client, threads: int, progress: bool, desc: str):
    """Compute every chunk of a plan (``compute(plan, i, threads) -> (i, out, status)``; ``to_vars`` turns
    that into {variable: values}) in memory, into the resumable store under ``out``, or on a Dask client;
    the dataset (lazy when stored)."""
    # in memory xarray alone does (pendula[xarray]); a store or a cluster needs the sweep extra
    xr = require("xarray", "xarray" if out is None and client is None else "sweep", "pendula.sweep")
    chunks: dict[int, object] = {}
    store = None
    if out is not None:
        from ._store import SweepStore
        store = SweepStore(out, layout)   # takes the store's lock; finds the chunks done and sound
        store.open()
    try:
        todo = [i for i in range(plan.nchunks) if store is None or i not in store.done]

        def done(i, o, st):
            vals = to_vars(plan, o, st)
            if store is not None:
                store.write_chunk(i, vals)
            else:
                chunks[i] = chunk_dataset(layout, i, vals)
            bar.update(1)

        # pendula's one progress rule (_progress.Progress): nothing drawn for work under two seconds
        with Progress(plan.nchunks, desc, enabled=progress, initial=plan.nchunks - len(todo),
                      unit="chunk") as bar:
            if client is not None:
                from ._cluster import run_chunks
                run_chunks(client, compute, plan, todo, threads, done)
            else:
                for i in todo:
                    done(*compute(plan, i, threads))
        if store is not None:
            # lazily (dask): the grid is never held in memory at once
            ds = store.dataset()
        else:
            parts = [chunks[i] for i in range(plan.nchunks)]
            ds = xr.concat(parts, dim=layout.first) if len(parts) > 1 else parts[0]
    finally:
        if store is not None:
            store.close()
    return ds


def run_measure(scene: Scene, over: dict, measure: str, rtol: float, atol: float, t_max: float, transient: float,
                samples: int, chunk_points: int, out, client, threads: int, progress: bool,
                force=None) -> "xarray.Dataset":
    """One of the kernel's measures over a checked grid, with checked arguments: the dataset."""
    plan = Plan(scene, over, measure, rtol, atol, t_max, transient, samples, int(chunk_points))
    plan.force = force
    layout = layout_of(plan)
    ds = run(plan, layout, compute_chunk, chunk_vars, out, client, threads, progress, f"sweep {measure}")
    ds.attrs.update(layout.attrs)
    if MEASURE_TABLE[plan.measure].recheck:
        # read from the store in this process (threads): a cluster's workers need not see 'out'
        ds.attrs["fraction_decided"] = float((ds.status == 0).mean().compute(scheduler="threads"))
    return ds


def grid_scenes(scene: Scene, over: dict) -> list:
    """The grid's first point, and from it each axis at each of its ends (the extremes of every time scale
    and forcing); the scene's own value of a swept field plays no part."""
    first = scene.replace(**{name: float(np.asarray(vals).reshape(-1)[0]) for name, vals in over.items()})
    out = [first]
    for name, vals in over.items():
        for v in (float(np.min(vals)), float(np.max(vals))):
            out.append(first.replace(**{name: v}))
    return out


def check_work(scene: Scene, over: dict, max_periods: int) -> None:
    """max_periods forcing periods of the slowest forcing on the grid must stay within a sweep point's time
    limit, and their expected steps at the fastest time scale (the kernel's rule) within the point's work
    limit: refused before any work, naming the field."""
    ends = grid_scenes(scene, over)
    om = min(contract.forcing_frequency(s, "max_periods") for s in ends)
    t = max_periods * 2 * math.pi / om
    limit = _checks._sweep_limits()[1]
    if not t <= limit:
        raise ValueError(f"max_periods: {max_periods} periods of the forcing at frequency {om:g} are {t:.3g} "
                         f"time units, beyond a sweep point's limit {limit:g} (lower max_periods)")
    worst = max(ends, key=lambda s: contract.time_scales(s).fastest)
    steps = contract.expected_steps(worst, t, 1e-10)
    if not steps <= contract.MAX_POINT_STEPS:
        ts = contract.time_scales(worst)
        fast = max(ts.rates, key=ts.rates.get)
        raise ValueError(f"max_periods: {max_periods} forcing periods ({t:.3g} time units) at the fastest time "
                         f"scale of the grid ({fast}, rate {ts.fastest:.3g}) are about {steps:.2g} integration "
                         f"steps a point, beyond the limit {contract.MAX_POINT_STEPS:.0e} (lower max_periods, or a slower "
                         f"{fast})")


def check_driven(scene: Scene, over: dict, what: str) -> None:
    """Every grid point's scene is periodically forced (the kernel's one definition: a drive, a vibrating
    pivot, or both at one frequency); refused naming the fields otherwise."""
    ends = grid_scenes(scene, over)
    for s in ends:
        contract.forcing_frequency(s, what)
    for name in ("drive_amplitude", "drive_frequency", "pivot_amplitude", "pivot_frequency"):
        if name in over and np.any(np.asarray(over[name]) == 0):
            contract.forcing_frequency(ends[0].replace(**{name: 0.0}), f"{what} at {name} = 0")


def edge_mask(ans: np.ndarray) -> np.ndarray:
    """The points of a grid of answers with a grid neighbour (along any axis) that answers differently.

    Examples
    --------
    >>> from pendula.dynamics.attractors import edge_mask
    >>> edge_mask(np.array([0, 0, 1, 1])).tolist()
    [False, True, True, False]
    """
    edge = np.zeros(ans.shape, dtype=bool)
    for ax in range(ans.ndim):
        d = np.diff(ans, axis=ax) != 0
        lo = [slice(None)] * ans.ndim
        hi = [slice(None)] * ans.ndim
        lo[ax] = slice(0, -1)
        hi[ax] = slice(1, None)
        edge[tuple(lo)] |= d
        edge[tuple(hi)] |= d
    return edge

"""Sweeps: one scene, a grid over one to three of its fields, and a measure.

Every grid point answers one question (the *measure*); the compiled kernel
runs a block of points per call on OpenMP threads, with no Python per point,
and each point stops as soon as its answer is decided.

Measures
--------
``final_well``
    The well n (angle asin(tau/eps) + 2 pi n) where an undriven damped orbit
    ends.  Decided when the energy v^2/2 - eps cos(theta) - tau theta (which
    can only fall) is below the lower barrier around the current well.  Points
    not trapped by ``t_max`` are NaN with status 1 ("not settled").
``mean_velocity``
    <v> over ``t_max`` after a transient ``transient`` (the junction's voltage),
    ``mean_velocity_err`` its error bar (the larger of |<v> - <v> over the
    second half| and a bound on the error of a finite window), and ``step``.
    An undriven damped orbit that gets trapped has <v> = 0 exactly, decided at
    once.  A driven orbit is averaged over whole drive periods (transient and
    window rounded up to whole periods, the window to an even number); when its
    stroboscopic map repeats after q periods with theta advanced by 2 pi p, it
    is phase-locked: <v> = p Omega / q exactly, ``step`` = p / q (the Shapiro
    step) and status 6 'locked'; ``step`` is NaN elsewhere.  A scene with
    thermal ``noise`` runs the Langevin integrator (BAOAB, step ``dt`` or its
    default; a driven point over whole drive periods): grid point k (flat
    index, first axis slowest) draws its noise from the stream (``seed``, k),
    so chunks, threads and resumes give the same numbers bit for bit;
    ``mean_velocity_err`` is then the standard error from up to 16 batch
    means, and ``mean_velocity`` is the only measure.
``locked``
    1 when the orbit spirals into an equilibrium, 0 when it runs (an open
    orbit over a further window, after ``t_max``), status 1 when undecided.
``poincare``
    ``samples`` stroboscopic (theta in [-pi, pi), v) once per drive period
    after ``ceil(transient / T)`` periods.
``lyapunov``
    The largest Lyapunov exponent ``lyapunov`` of the orbit (variational
    equations integrated with it by DOP853 on the 6-D state, Gram-Schmidt
    renormalisation of two tangent vectors every fixed interval: Benettin),
    averaged over ``t_max`` after ``transient`` (both rounded up to whole drive
    periods, or small-oscillation periods 2 pi / sqrt(eps) without a drive);
    ``lyapunov_err`` = the standard error of the mean over 8 equal blocks of
    the window; ``lyapunov2`` = the second exponent (lyapunov + lyapunov2 =
    -damping exactly in theory: a check).  See kernel/sweep/pendula_lyapunov.f90.

Scale: the grid is cut into chunks along its first axis.  With ``out``, the
result is a Zarr (v3) store ``out/sweep.zarr`` with CF attributes, filled by
region as each chunk finishes and committed chunk by chunk (checksummed,
fsynced), so a run killed and started again with the same ``out`` computes
only the missing or damaged chunks and gives the same dataset bit for bit;
one sweep at a time writes a store (a lock file).  A Dask distributed
``client`` spreads the chunks over its workers, each task's OpenMP threads
set so that no machine runs more threads than it has cores.  See
``docs/source/sweeps_at_scale.rst``.
"""

from __future__ import annotations

import json
import math
import os
import pathlib
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike
from ._optional import require

from ._store import StoreBusyError, SweepStoreWarning  # noqa: F401 - raised and warned by sweep(out=...)
from . import _checks, _interrupt
from ._files import atomic_path, save_figure
from ._progress import Progress
from .scene import GRIDDABLE, MEASURES, Scene, SceneError
from .systems import contract
from .dynamics.attractors import AttractorMap, edge_mask as _edge_mask

if TYPE_CHECKING:   # xarray and distributed are optional: named in annotations only
    import distributed
    import xarray

__all__ = ["sweep", "iv_curve", "grid_of", "MEASURE_CODES", "attractor_map", "attractor_continuation"]

#: kernel codes of the measures (kernel/sweep/pendula_sweep.f90)
MEASURE_CODES = {"final_well": 1, "mean_velocity": 2, "locked": 3, "poincare": 4, "lyapunov": 5}
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
#: noise streams per I-V branch (at most 1e6 torques, and a lead-in ramp of as many)
_IV_STREAMS = 2 * 10 ** 6
_PARAM_ORDER = ("eps", "damping", "torque", "drive_amplitude", "drive_frequency", "drive_phase", "theta0", "v0",
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


def _check_over(scene: Scene, over) -> dict:
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


def _block(code, p, rtol, atol, t_tr, t_max, nout, threads, force=None):
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


class _Plan:
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
        if measure == "poincare":
            # the kernel rounds the transient up to whole periods of each point's drive
            self.nout = 2 * samples
            self.t_tr = transient
        elif measure == "mean_velocity":
            # <v>, its error bar and the Shapiro step of a phase-locked point
            self.nout = 3
            self.t_tr = transient
        elif measure == "lyapunov":
            # the kernel rounds transient and window up to whole periods, point by point
            self.nout = 3
            self.t_tr = transient
        else:
            self.nout = 2
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
        p = np.empty((len(_PARAM_ORDER), flat.size), order="F")
        for j, f in enumerate(_PARAM_ORDER):
            p[j] = getattr(self.scene, f)
        for n, ix in zip(self.over, np.unravel_index(flat, self.shape)):
            p[_PARAM_ORDER.index(n)] = self.over[n][ix]
        return p


def _answers(out, st):
    """The answer of each point for the boundary test: out[..., 0] when decided,
    else a value no answer takes (decided and undecided neighbours differ too)."""
    return np.where(st == 0, out[..., 0], -1e300)


def _compute_chunk(plan: _Plan, i: int, threads: int):
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
    out, st = _block(code, p, plan.rtol, plan.atol, plan.t_tr, plan.t_max, plan.nout, threads, plan.force)
    out = out.T.reshape(shape + (plan.nout,))
    st = st.reshape(shape)
    if plan.measure in ("final_well", "locked"):
        # Points on a basin boundary (a grid neighbour answers differently, along
        # any axis) are computed again at 1000 times tighter tolerances; where
        # the answer changes, it is not known: NaN and status 4.  The rows just
        # outside the chunk are computed too (first pass only), so that
        # neighbours across chunk edges count: the answer of every point
        # depends on the grid alone, never on the chunking (resume, Dask and
        # pendula-run agree bit for bit).
        lo = i * plan.rows
        hi = lo + shape[0]
        parts = [_answers(out, st)]
        if lo > 0:
            pb, sb = plan.params_rows(lo - 1, lo)
            ob, tb = _block(code, pb, plan.rtol, plan.atol, plan.t_tr, plan.t_max, plan.nout, threads)
            parts.insert(0, _answers(ob.T.reshape(sb + (plan.nout,)), tb.reshape(sb)))
        if hi < plan.shape[0]:
            pa, sa = plan.params_rows(hi, hi + 1)
            oa, ta = _block(code, pa, plan.rtol, plan.atol, plan.t_tr, plan.t_max, plan.nout, threads)
            parts.append(_answers(oa.T.reshape(sa + (plan.nout,)), ta.reshape(sa)))
        edge = _edge_mask(np.concatenate(parts, axis=0))
        first = 1 if lo > 0 else 0
        edge = edge[first:first + shape[0]]
        idx = np.flatnonzero(edge.ravel())
        if idx.size:
            p2 = np.asfortranarray(p[:, idx])
            o2, s2 = _block(code, p2, plan.rtol * 1e-3, plan.atol * 1e-3, plan.t_tr, plan.t_max, plan.nout,
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
_VAR_META = {
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
_AXIS_META = {
    "v0": ("initial angular velocity", "rad s-1"), "theta0": ("initial angle", "rad"),
    "eps": ("g / l, the square of the small-oscillation angular frequency", "s-2"),
    "damping": ("linear damping beta", "s-1"), "torque": ("constant torque tau", "rad s-2"),
    "drive_amplitude": ("drive amplitude A", "rad s-2"), "drive_frequency": ("drive angular frequency Omega", "rad s-1"),
    "drive_phase": ("drive phase", "rad"), "sample": ("stroboscopic sample number", "1"),
    "pivot_amplitude": ("vibrating pivot's amplitude a (units of the length)", "1"),
    "pivot_frequency": ("vibrating pivot's angular frequency Omega", "rad s-1"),
    "friction": ("dry (Coulomb) friction mu", "rad s-2"), "drag": ("quadratic drag gamma", "1"),
}
#: the variables of each measure, in the kernel's output order
_MEASURE_VARS = {"final_well": ("well", "t_decided"), "locked": ("locked", "t_decided"),
                 "mean_velocity": ("mean_velocity", "mean_velocity_err", "step"), "poincare": ("theta", "v"),
                 "lyapunov": ("lyapunov", "lyapunov_err", "lyapunov2")}


def _status_attrs() -> dict:
    """CF flag attributes of 'status', from STATUS (flag_meanings: one word per code)."""
    import re
    codes = sorted(STATUS)
    return {"long_name": "status of the point's answer",
            "flag_values": np.array(codes, dtype=np.int32),
            "flag_meanings": " ".join(re.sub(r"[^0-9A-Za-z]+", "_", STATUS[c]).strip("_") for c in codes),
            "comment": "-1 (the store's fill value) only in a store whose sweep has not finished: not computed yet"}


def _layout(plan: _Plan):
    """What a sweep's dataset holds, apart from the values: the store's and the in-memory run's common form."""
    from ._store import Layout, Variable

    dims = tuple(plan.over)

    def meta(name):
        long_name, units = _AXIS_META.get(name, _VAR_META.get(name, (name, "1")))
        return {"long_name": long_name, "units": units}
    coords = {n: (plan.over[n], meta(n)) for n in dims}
    vdims = dims
    if plan.measure == "poincare":
        coords["sample"] = (np.arange(plan.samples), meta("sample"))
        vdims = dims + ("sample",)
    variables = {"status": Variable(dims, np.dtype(np.int32), _status_attrs(), -1)}
    for n in _MEASURE_VARS[plan.measure]:
        variables[n] = Variable(vdims, np.dtype(np.float64), meta(n), np.nan)
    attrs = {"Conventions": "CF-1.10", "title": f"pendula sweep: {plan.measure}", "scene": plan.scene.to_namelist(),
             "measure": plan.measure, "rtol": plan.rtol, "atol": plan.atol, "t_max": plan.t_max,
             "transient": plan.transient, "samples": plan.samples, "status_codes": json.dumps(STATUS)}
    return Layout(axes={n: plan.over[n] for n in dims}, coords=coords, variables=variables, rows=plan.rows,
                  identity=json.dumps(plan.key(), sort_keys=True), attrs=attrs)


def _chunk_vars(plan: _Plan, out: np.ndarray, st: np.ndarray) -> dict:
    """The kernel's output of one chunk as {variable: values}."""
    if plan.measure == "poincare":
        vals = {"theta": out[..., 0::2], "v": out[..., 1::2]}
    else:
        vals = {n: out[..., k] for k, n in enumerate(_MEASURE_VARS[plan.measure])}
    vals["status"] = st.astype(np.int32)
    return vals


def _chunk_dataset(layout, i: int, vals: dict):
    xr = require("xarray", "xarray", "pendula.sweep")
    lo, hi = layout.rows_of(i)
    coords = {n: xr.Variable((n,), v[lo:hi] if n == layout.first else v, dict(a))
              for n, (v, a) in layout.coords.items()}
    data = {n: (var.dims, vals[n], dict(var.attrs)) for n, var in layout.variables.items()}
    return xr.Dataset(data, coords=coords)


def _run(plan, layout, compute, to_vars, out, client, threads: int, progress: bool, desc: str):
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
                chunks[i] = _chunk_dataset(layout, i, vals)
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


def sweep(scene: Scene | str | os.PathLike[str], over: dict[str, ArrayLike] | None = None,
          measure: Literal["final_well", "mean_velocity", "locked", "poincare", "lyapunov", "attractor"]
          | None = None, *, rtol: float | None = None, atol: float | None = None, t_max: float | None = None,
          transient: float | None = None, samples: int | None = None, out: str | os.PathLike[str] | None = None,
          chunk_points: int = 20000, client: distributed.Client | None = None, threads: int = 0,
          progress: bool = False, force: object = None, force_params: ArrayLike | None = None) -> xarray.Dataset:
    """Evaluate a measure over a grid of one scene's fields.

    Parameters
    ----------
    scene : Scene or str or path
        The base scene (a Scene, or a namelist file).
    over : dict, optional
        {field: values} for 1 to 3 axes (fields: v0, theta0, eps, damping,
        torque, drive_amplitude, drive_frequency, drive_phase).  Default: the
        scene's own grid (``grid``, ``grid1`` ... fields).
    measure : str, optional
        'final_well', 'mean_velocity', 'locked', 'poincare', 'lyapunov', or
        'attractor' (the attractor each point's orbit ends on, read from
        ``samples`` stroboscopic samples after ``transient``: method
        'samples' of :func:`attractor_map`, whose measures and attractors are
        in the Dataset's attributes; :func:`attractor_map` itself defaults to
        the faster recurrence method with early stopping).  Default: the
        scene's ``measure`` (a scene file names one of the kernel's measures).
    rtol, atol : float, optional
        DOP853 tolerances (default: the scene's).
    t_max : float, optional
        final_well/locked: the limit; mean_velocity, lyapunov: the averaging time.
        Default: the scene's ``sweep_t_max``.
    transient : float, optional
        Time skipped before averaging or sampling (default ``sweep_transient``).
    samples : int, optional
        Poincare samples per point (default ``sweep_samples``).
    out : str or path, optional
        Folder of the result's Zarr store ``out/sweep.zarr`` (filled chunk by
        chunk; a sweep started again with the same ``out`` resumes, checking
        every chunk already there and computing damaged ones again).  Without
        it everything stays in memory.  One sweep at a time writes a store.
    chunk_points : int
        Points per chunk (whole rows of the first axis).
    client : dask.distributed.Client, optional
        Spread chunks over its workers; a task's OpenMP threads are
        ``max(1, cores // slots)`` with ``slots`` the tasks the machine's
        workers run at once (their nthreads summed), so no machine runs more
        threads than it has cores.
    threads : int
        OpenMP threads per chunk (0: OMP_NUM_THREADS or all cores; with a
        ``client``: the rule above, which a positive ``threads`` can lower).
    progress : bool
        Show a tqdm bar of chunks done and the time left.
    force, force_params : optional
        A user's force, as in :func:`pendula.simulate`, added at every point
        (the kernel calls it from every thread); not with ``out`` or
        ``client``, and final_well and locked do not apply with it (status
        2).  Friction, drag and a vibrating pivot are in the sweeps too (the
        pivot's period is the stroboscopic map's when there is no drive; no
        Lyapunov exponents with friction, which sticks).

    Returns
    -------
    xarray.Dataset
        Lazy (dask-backed, read from the Zarr store) when ``out`` is given.
        Coordinates = the axes (with CF ``units`` and ``long_name``); variables per measure plus ``status``
        (0 decided, 1 not settled by the limit, 2 measure does not apply,
        4 uncertain: a basin-boundary point -- a grid neighbour along any axis,
        across chunk edges too, answers differently -- whose answer changed when
        computed again at 1000 times tighter tolerances; final_well and locked);
        the scene and options as attributes.

    Raises
    ------
    ValueError
        A bad argument (named): an unknown measure or grid field, grid values
        that are empty, not finite or out of the field's range, bad tolerances
        or times, 'poincare' without a drive, or an `out` that holds a
        different sweep.
    NotImplementedError
        For a model the sweeps do not run (flexible cord, cycloid,
        non-uniform gravity).
    pendula._store.StoreBusyError
        (an OSError) another sweep is writing the same ``out``; the message
        names the store and that sweep's pid.
    SceneError
        If `scene` is a file that does not hold a valid scene.

    See Also
    --------
    iv_curve : the adiabatic torque ramp (hysteresis), which a grid cannot give.
    simulate : one point of the grid, in full.

    Examples
    --------
    >>> import pendula
    >>> s = pendula.Scene(damping=0.04)
    >>> ds = pendula.sweep(s, over={"v0": [1.0, 2.3, 3.0]}, measure="final_well")
    >>> ds.well.values.tolist()
    [0.0, 2.0, 5.0]

    The largest Lyapunov exponent of the driven damped pendulum (chaotic at
    A = 1.5, a stable cycle at A = 0.9):

    >>> d = pendula.Scene(damping=0.5, drive_frequency=2 / 3)
    >>> ly = pendula.sweep(d, over={"drive_amplitude": [0.9, 1.5]}, measure="lyapunov",
    ...                    transient=1000.0, t_max=3000.0)
    >>> [bool(x > 0) for x in ly.lyapunov.values]
    [False, True]
    >>> bool(abs(ly.lyapunov[0] + ly.lyapunov2[0] + 0.5) < 1e-8)     # lambda_1 + lambda_2 = -beta
    True
    """
    # in memory xarray alone does (pendula[xarray]); a store or a cluster needs the sweep extra
    xr = require("xarray", "xarray" if out is None and client is None else "sweep", "pendula.sweep")

    # a user's force: its code is no part of a store's key and its address means nothing in
    # another process, so it runs in this process without a store
    uf = None
    if force is not None or force_params is not None:
        if out is not None or client is not None:
            raise ValueError("parameters 'force' and 'out'/'client': a sweep with a user's force runs in this "
                             "process and is not stored (its code is not part of the store's key)")
        uf = _checks.force(force, force_params)
    if not isinstance(scene, Scene):
        scene = Scene.from_file(scene)
    if out is not None:
        out = _checks.path(out, "out")
    if client is not None:
        from ._cluster import check_client
        check_client(client)
    progress = _checks.flag(progress, "progress")
    measure = measure or scene.measure
    if scene.noise > 0 and uf is not None:
        raise ValueError("fields 'noise' and 'force': a user's force with thermal noise is not implemented "
                         "(the Langevin integrator takes the scene's own force law only)")
    if not isinstance(measure, str) or measure not in MEASURES + ("attractor",):
        raise ValueError(f"parameter 'measure' must be one of {', '.join(MEASURES + ('attractor',))}; "
                         f"got {measure!r}")
    if scene.noise > 0 and (over or {}).keys() & {"damping"} and not np.all(np.asarray(over["damping"]) > 0):
        raise ValueError("field 'noise': every grid point needs damping > 0 (the thermal force comes with it)")
    _checks.angle(scene.theta0, "field 'theta0'")
    over = grid_of(scene) if over is None else over
    over = _check_over(scene, over)
    # the capability table: the fields this measure honours, the rest (noise in a deterministic measure,
    # another model) refused by name, a measure of the stroboscopic map refused without a forcing
    contract.require(scene, f"sweep:{measure}", over=over, force=uf is not None)
    rtol, atol = _checks.tolerances(scene.rtol if rtol is None else rtol, scene.atol if atol is None else atol)
    t_max = _checks.duration(scene.sweep_t_max if t_max is None else t_max, "t_max")
    transient = _checks.duration(scene.sweep_transient if transient is None else transient, "transient",
                                 positive=False)
    samples = _checks.count(scene.sweep_samples if samples is None else samples, "samples", 1, 100000)
    chunk_points = _checks.count(chunk_points, "chunk_points", 1)
    threads = _checks.threads(threads)
    if measure == "attractor":
        # the attractor map read from the kernel's poincare samples (method 'samples' of pendula.attractor_map)
        return attractor_map(scene, over, method="samples", transient=transient, samples=samples, rtol=rtol,
                             atol=atol, threads=threads, out=out, client=client, progress=progress,
                             chunk_points=chunk_points).dataset
    if measure == "mean_velocity":
        _checks.window(transient, t_max, "t_max")
    if measure == "poincare" and math.prod(len(v) for v in over.values()) * samples > _checks.MAX_GRID_POINTS:
        raise ValueError(f"parameter 'samples': {samples} samples at each grid point is more than "
                         f"{_checks.MAX_GRID_POINTS:.0e} values")
    if measure in ("poincare",):
        _check_driven(scene, over, f"measure '{measure}'")
    plan = _Plan(scene, over, measure, rtol, atol, t_max, transient, samples, int(chunk_points))
    plan.force = uf

    layout = _layout(plan)
    ds = _run(plan, layout, _compute_chunk, _chunk_vars, out, client, threads, progress, f"sweep {measure}")
    ds.attrs.update(layout.attrs)
    if plan.measure == "final_well" or plan.measure == "locked":
        # read from the store in this process (threads): a cluster's workers need not see 'out'
        ds.attrs["fraction_decided"] = float((ds.status == 0).mean().compute(scheduler="threads"))
    return ds


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


class _AttractorPlan(_Plan):
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
    from . import _kernel
    kcell, klab, need = table
    bth, bv, blab = plan.basin
    cancel = _interrupt.cancel_flag()
    out, cells, ncell, st = _interrupt.call(_kernel.attractor_block, np.asfortranarray(p), rtol, atol, plan.cfg,
                                            kcell, klab, need, bth, bv, blab, plan.nout, maxc, int(threads),
                                            cancel, cancel=cancel)
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
    edge = _edge_mask(np.concatenate(parts, axis=0))[first:first + shape[0]].ravel()
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
    from ._store import Layout, Variable
    dims = tuple(plan.over)

    def meta(name):
        long_name, units = _AXIS_META[name]
        return {"long_name": long_name, "units": units}
    coords = {n: (plan.over[n], meta(n)) for n in dims}
    variables = {
        "status": Variable(dims, np.dtype(np.int32), _status_attrs(), -1),
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
                labels[g] = found.add_chaotic(cells[:ncell[j], j])
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


def _recurrence_options(kw: dict) -> dict:
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


def _grid_scenes(scene: Scene, over: dict) -> list:
    """The scene at each end of each grid axis (the extremes of every time scale and forcing)."""
    out = [scene]
    for name, vals in over.items():
        for v in (float(np.min(vals)), float(np.max(vals))):
            try:
                out.append(scene.replace(**{name: v}))
            except SceneError:
                pass        # a value the scene refuses alone (refused with the grid's own check)
    return out


def _check_work(scene: Scene, over: dict, max_periods: int) -> None:
    """max_periods forcing periods of the slowest forcing on the grid must stay within a sweep point's time
    limit, and their expected steps at the fastest time scale (the kernel's rule) within the point's work
    limit: refused before any work, naming the field."""
    ends = _grid_scenes(scene, over)
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


def _check_driven(scene: Scene, over: dict, what: str) -> None:
    """Every grid point's scene is periodically forced (the kernel's one definition: a drive, a vibrating
    pivot, or both at one frequency); refused naming the fields otherwise."""
    for s in _grid_scenes(scene, over):
        contract.forcing_frequency(s, what)
    for name in ("drive_amplitude", "drive_frequency", "pivot_amplitude", "pivot_frequency"):
        if name in over and np.any(np.asarray(over[name]) == 0):
            contract.forcing_frequency(scene.replace(**{name: 0.0}), f"{what} at {name} = 0")


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
      shows no cycle closing in: a thin chaotic set), is a new chaotic
      attractor, whose cells are collected over ``collect`` more samples;
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
    over = _check_over(scene, over)
    contract.require(scene, "attractor_map", over=over)
    _check_driven(scene, over, "attractor_map")
    threads = _checks.threads(threads)
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
    opts = _recurrence_options(dict(cell=cell, recurrence_cell=recurrence_cell, near=near, consecutive=consecutive,
                                    consecutive_chaotic=consecutive_chaotic, recurrences=recurrences,
                                    collect=collect, max_periods=max_periods, max_period=max_period,
                                    merge_tol=merge_tol, pilot=pilot, rtol=rtol, atol=atol,
                                    recheck_rtol=recheck_rtol, recheck_atol=recheck_atol, inherit=inherit,
                                    margin=margin))
    _check_work(scene, over, opts["max_periods"])
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

    from .dynamics.attractors import AttractorSet
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
        ds = _run(plan, _attractor_layout(plan), _attractor_chunk, _attractor_vars, out if s == 1 else None,
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
    atts, remap = found.attractors(counts, npts)
    labels = remap[labels].reshape(fine.shape)     # remap[-1] = -1: undecided stays -1
    status = status.reshape(fine.shape)
    undecided = int((labels < 0).sum())
    if undecided == npts:
        warnings.warn(f"attractor_map: no point was decided within max_periods = {opts['max_periods']} drive "
                      "periods (status 1: raise max_periods)", RuntimeWarning, stacklevel=3)
    dims = tuple(fine.over)
    coords = {d: (d, fine.over[d], dict(zip(("long_name", "units"), _AXIS_META[d]))) for d in dims}
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
         "status": (dims, status, _status_attrs())}, coords=coords)
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
    from .dynamics.attractors import basin_entropy, boundary_fraction, uncertainty_exponent
    dims = tuple(d for d in ds.status.dims)
    per = np.array([a.period for a in atts] + [-1])[labels]
    ds["attractor"] = (dims, labels.astype(np.int32), {
        "long_name": "attractor of the stroboscopic map the orbit ends on (-1 undecided)",
        "flag_values": np.arange(-1, len(atts), dtype=np.int32),
        "flag_meanings": " ".join(["undecided"] + [f"{a.kind}_period_{a.period}_{a.label}" if a.period
                                                   else f"chaotic_{a.label}" for a in atts])})
    ds["period"] = (dims, per.astype(np.int32), {"long_name": "period of the attractor in drive periods "
                                                              "(0 chaotic, -1 undecided)", "units": "1"})
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
                                                "multipliers_abs": np.abs(x.multipliers).tolist()}
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
    pc = sweep(scene, over=over, measure="poincare", transient=transient, samples=samples, rtol=rtol,
               atol=atol, threads=threads, out=out, client=client, progress=progress, chunk_points=chunk_points)
    from .dynamics.attractors import label_attractors
    labels, atts = label_attractors(pc.theta.values, pc.v.values, tol=tol, merge_tol=merge_tol,
                                    max_period=max_period, cell=cell)
    st = pc.status.values
    labels = np.where(st == 0, labels, -1)
    dims = tuple(d for d in pc.theta.dims if d != "sample")
    ds = pc[["status"]].load() if hasattr(pc, "load") else pc[["status"]]
    ds = ds.drop_vars([c for c in ds.coords if c not in dims])
    extra = {k: pc.attrs[k] for k in pc.attrs if k not in ("measure", "title")}
    extra.update({"method": "samples", "tol": tol, "merge_tol": merge_tol, "cell": cell,
                  "undecided": int((labels < 0).sum())})
    return _finish_map(ds, labels, atts, scene, extra)


def _attractor_distance(a, b) -> float:
    """The distance of two attractors on the section (max-norm, angle modulo 2 pi): the largest distance
    from a point of either to the nearest point of the other (Hausdorff); periodic attractors by their
    cycle points, chaotic ones by their cells' centres.  Attractors of another kind or period are
    infinitely far apart."""
    from .dynamics.attractors import _dist
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
    over_c = _check_over(scene, over)
    contract.require(scene, "attractor_continuation", over=tuple(over_c) + (param,))
    _check_driven(scene.replace(**{param: float(vals[0])}), over_c, "attractor_continuation")
    opts = _recurrence_options(options)     # checked once, before any work
    for val in vals:
        sv = scene.replace(**{param: float(val)})
        _check_driven(sv, over_c, "attractor_continuation")
        _check_work(sv, over_c, opts["max_periods"])
    root = None
    if out is not None:
        from ._store import _write_json_atomic
        root = pathlib.Path(out)
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
    meta = _AXIS_META[param]
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


def iv_curve(scene: Scene | str | os.PathLike[str], torques: ArrayLike,
             direction: Literal["up", "down", "both"] = "both", *, transient: float = 200.0,
             t_max: float | None = None, rtol: float | None = None, atol: float | None = None,
             start: Literal["ramp", "scene"] | tuple[float, float] = "ramp", t_avg: float | None = None
             ) -> xarray.Dataset:
    """The I-V curve of the constant-torque pendulum (RCSJ junction), adiabatically.

    Each torque starts from the end state of the previous one, so the up and
    down branches show the hysteresis: the junction switches to running at
    tau = eps on the way up and is retrapped near the Stewart-McCumber torque
    4 beta / pi (small beta) on the way down.

    Where the first torque starts matters: a run that begins at a high torque
    from rest is a step, not a ramp, and lands on whichever branch the step
    reaches.  ``start`` says what the branch begins from.

    Parameters
    ----------
    scene : Scene or str or path
        Gives eps, damping (> 0) and the start state; its torque is ignored.
        A path is read as a scene file (as :func:`sweep` does).
    torques : array_like
        Torque values, ascending; 'down' runs them in reverse.
    direction : {'up', 'down', 'both'}
        The branches: torque ramped up, down, or up then down (the down branch
        starting where the up branch ended).
    transient, t_max : float
        Time skipped, then time averaged, at each torque (default 200, 400):
        the averaging time has the name it has in :func:`sweep`.
    rtol, atol : float, optional
        DOP853 tolerances (default: the scene's).
    start : {'ramp', 'scene'} or (float, float), optional
        ``'ramp'`` (default): where an adiabatic ramp from rest at zero torque
        would be.  The up branch starts at rest at tau = 0 and, when its first
        torque is not 0, ramps to it first through steps of the torques' own
        spacing (at most 1000 steps; those values are not reported); a
        ``'down'`` branch alone first runs that up ramp through all the torques
        (not reported), so it starts on the running branch when the largest
        torque exceeds eps.  ``'scene'``: the scene's theta0, v0 (the first
        torque is a step).  A pair ``(theta, v)``: that state.
    t_avg : float, optional
        The former name of ``t_max`` (deprecated: a DeprecationWarning).

    Returns
    -------
    xarray.Dataset
        Dimensions ``direction`` (the branches asked, 'up' and/or 'down') and
        ``torque`` (the torques as given; the down branch runs them in
        reverse, and its values are stored against their torque):
        ``mean_velocity`` <v>, ``mean_velocity_err`` (its error bar: the
        larger of abs(<v> - <v> over the second half of the window) and a bound
        on the error of a finite window), ``step`` (the Shapiro step p / q of a
        phase-locked driven point, NaN elsewhere) and ``status`` (0 decided,
        6 locked: <v> = step * drive_frequency exactly; CF flags), with CF
        units and the options as attributes.  In a driven scene every torque
        is averaged over whole drive periods (see :func:`sweep`'s
        ``mean_velocity``).  A scene with thermal ``noise`` runs the Langevin
        integrator: each torque of each branch draws its noise from its own
        stream of the scene's ``seed``, ``mean_velocity_err`` is the standard
        error from batch means, and no step locks (``step`` is NaN).

    Raises
    ------
    TypeError
        If `scene` is not a :class:`Scene`.
    ValueError
        For an unknown `direction`, empty or non-finite torques, or a negative
        `transient` or non-positive `t_avg`.

    See Also
    --------
    sweep : grids of scenes, each from its own initial state.

    Examples
    --------
    >>> import pendula
    >>> r = pendula.iv_curve(pendula.Scene(damping=0.2), [0.5, 1.1], "up", transient=50, t_max=100)
    >>> up = r.mean_velocity.sel(direction="up")
    >>> float(up.sel(torque=0.5))                     # locked below tau = eps: no voltage
    0.0
    >>> bool(abs(up.sel(torque=1.1) - 1.1 / 0.2) < 0.01)   # running: close to the ohmic line tau / beta
    True

    With an ac drive the I-V curve has Shapiro steps, where the phase locks to
    the drive and <v> is a whole multiple of its frequency, exactly:

    >>> ac = pendula.Scene(damping=1.0, drive_amplitude=1.0, drive_frequency=1.0)
    >>> r = pendula.iv_curve(ac, [0.3, 1.1], "up", transient=100, t_max=200)
    >>> r.mean_velocity.values.tolist(), r.step.values.tolist()
    ([[0.0, 1.0]], [[0.0, 1.0]])
    """
    import warnings

    from . import _kernel
    xr = require("xarray", "sweep", "pendula.iv_curve")
    if isinstance(scene, (str, bytes, os.PathLike)):
        scene = Scene.from_file(scene)
    if not isinstance(scene, Scene):
        raise TypeError("parameter 'scene' must be a pendula.Scene or the path of a scene file")
    t_name = "t_max"
    if t_avg is not None:
        if t_max is not None:
            raise TypeError("give the averaging time as t_max only (t_avg is its former name)")
        warnings.warn("iv_curve: t_avg is now called t_max (as in sweep); t_avg will go", DeprecationWarning,
                      stacklevel=2)
        t_max, t_name = t_avg, "t_avg"
    t_max = 400.0 if t_max is None else t_max
    if not isinstance(direction, str) or direction not in ("up", "down", "both"):
        raise ValueError(f"parameter 'direction' must be 'up', 'down' or 'both'; got {direction!r}")
    contract.require(scene, "iv_curve")
    _checks.angle(scene.theta0, "field 'theta0'")
    if not scene.damping > 0:
        raise ValueError("field 'damping' must be > 0 for an I-V curve (without damping <v> grows without bound)")
    tau = _checks.grid_values(torques, "parameter 'torques'")
    if tau.size > 10 ** 6:
        raise ValueError(f"parameter 'torques': at most 1e6 values, got {tau.size}")
    transient = _checks.duration(transient, "transient", positive=False)
    t_avg = _checks.duration(t_max, t_name)
    _checks.window(transient, t_avg, t_name)
    rtol, atol = _checks.tolerances(scene.rtol if rtol is None else rtol, scene.atol if atol is None else atol)
    p = np.array([getattr(scene, f) for f in _PARAM_ORDER], dtype=float)

    def branch(p, taus, first):
        # first: the noise stream of the branch's first torque (a scene with noise; the lead-in ramp,
        # the up and the down branch each have their own streams, so no two torques share noise)
        cancel = _interrupt.cancel_flag()
        r = _interrupt.call(_kernel.sweep_iv_branch, p, taus, rtol, atol, transient, t_avg, scene.noise,
                            scene.seed, first, scene.dt, cancel, cancel=cancel)
        if cancel[0]:
            raise KeyboardInterrupt
        return r

    if isinstance(start, str):
        if start not in ("ramp", "scene"):
            raise ValueError(f"parameter 'start' must be 'ramp', 'scene' or a state (theta, v); got {start!r}")
    else:
        try:
            th_s, v_s = (float(x) for x in start)
        except (TypeError, ValueError):
            raise ValueError(f"parameter 'start' must be 'ramp', 'scene' or a state (theta, v); got {start!r}") \
                from None
        if not (math.isfinite(th_s) and math.isfinite(v_s)):
            raise ValueError(f"parameter 'start' must be a finite state (theta, v); got {start!r}")
        p[6], p[7] = th_s, v_s
    if start == "ramp":
        p[6], p[7] = 0.0, 0.0
        first = tau[0] if direction != "down" else tau[-1]
        spacing = float(np.min(np.abs(np.diff(tau)))) if tau.size > 1 else 0.0
        spacing = spacing if spacing > 0 else abs(first) / 100.0
        lead = tau if direction == "down" else np.array([])
        if direction != "down" and first != 0.0:
            steps = min(1000, max(1, math.ceil(abs(first) / spacing)))
            lead = np.linspace(0.0, first, steps + 1)[:-1]
        if lead.size:
            *_, th_end, v_end = branch(p, np.ascontiguousarray(lead, dtype=float), 0)
            p[6], p[7] = th_end, v_end
    rows = {}
    if direction in ("up", "both"):
        vm, err, step, st, th_end, v_end = branch(p, tau, _IV_STREAMS)
        rows["up"] = (vm, err, step, st)
    if direction in ("down", "both"):
        td = tau[::-1].copy()
        if direction == "both":
            # the down branch starts where the up branch ended
            p = p.copy()
            p[6], p[7] = th_end, v_end
        vm, err, step, st, _, _ = branch(p, td, 2 * _IV_STREAMS)
        rows["down"] = (vm[::-1], err[::-1], step[::-1], st[::-1])     # stored against their torques
    dims = ("direction", "torque")
    dirs = list(rows)
    return xr.Dataset(
        {"mean_velocity": (dims, np.stack([rows[d][0] for d in dirs]),
                           {"long_name": "mean angular velocity <v> after the transient (the junction's voltage)",
                            "units": "rad s-1"}),
         "mean_velocity_err": (dims, np.stack([rows[d][1] for d in dirs]),
                               {"long_name": _VAR_META["mean_velocity_err"][0], "units": "rad s-1"}),
         "step": (dims, np.stack([rows[d][2] for d in dirs]),
                  {"long_name": _VAR_META["step"][0], "units": "1"}),
         "status": (dims, np.stack([rows[d][3] for d in dirs]).astype(np.int32), _status_attrs())},
        coords={"direction": ("direction", dirs, {"long_name": "branch of the adiabatic torque ramp"}),
                "torque": ("torque", tau, {"long_name": "constant torque tau", "units": "rad s-2"})},
        attrs={"scene": scene.to_namelist(), "measure": "iv_curve", "transient": transient, "t_max": t_avg,
               "rtol": rtol, "atol": atol, "start": start if isinstance(start, str) else repr(tuple(start)),
               "order_run": "up: the torques as given; down: in reverse, from where the up branch ended "
                            "(both) or from the up ramp's end (down alone, start='ramp')",
               "status_codes": json.dumps(STATUS)})


def plot_sweep(ds, path) -> pathlib.Path:
    """A figure of a sweep: a map (2 axes; discrete colours for wells), a curve
    (1 axis), or a bifurcation diagram (poincare over 1 axis)."""
    matplotlib = require("matplotlib", "plot", "pendula.sweeps.plot_sweep (figures)")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path = pathlib.Path(path)
    measure = ds.attrs["measure"]
    dims = [d for d in ds.dims if d != "sample"]
    var = {"final_well": "well", "locked": "locked", "mean_velocity": "mean_velocity", "poincare": "theta",
           "lyapunov": "lyapunov", "attractor": "attractor"}[measure]
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    if measure == "poincare":
        x = np.repeat(ds[dims[0]].values, ds.sizes["sample"])
        th = ds.theta.values.reshape(-1) if len(dims) == 1 else ds.theta.isel({d: 0 for d in dims[1:]}).values.ravel()
        ax.plot(x, th, ".k", markersize=1.5, alpha=0.6)
        ax.set_xlabel(dims[0]); ax.set_ylabel("stroboscopic theta (mod 2 pi)")
    elif len(dims) == 1:
        ax.plot(ds[dims[0]].values, ds[var].values, ".-")
        ax.set_xlabel(dims[0]); ax.set_ylabel(var)
    else:
        z = ds[var]
        if len(dims) > 2:
            z = z.isel({d: 0 for d in dims[2:]})
        z = z.transpose(dims[0], dims[1]).values
        x, y = ds[dims[0]].values, ds[dims[1]].values
        if measure in ("final_well", "locked", "attractor"):
            lo, hi = np.nanmin(z), np.nanmax(z)
            lo, hi = (0, 1) if not np.isfinite(lo) else (int(lo), int(hi))
            cmap = plt.get_cmap("tab20", hi - lo + 1)
            im = ax.imshow(z.T, origin="lower", aspect="auto", cmap=cmap, vmin=lo - 0.5, vmax=hi + 0.5,
                           extent=[x[0], x[-1], y[0], y[-1]], interpolation="nearest")
            fig.colorbar(im, ax=ax, ticks=range(lo, hi + 1), label=var)
        else:
            im = ax.imshow(z.T, origin="lower", aspect="auto", extent=[x[0], x[-1], y[0], y[-1]])
            fig.colorbar(im, ax=ax, label=var)
        ax.set_xlabel(dims[0]); ax.set_ylabel(dims[1])
    ax.set_title(f"pendula sweep: {measure}")
    fig.tight_layout()
    try:
        save_figure(fig, path, dpi=120)     # whole under its name, or absent
    finally:
        plt.close(fig)
    return path


def cli_main(args) -> int:
    """``pendula sweep SCENE.nml -o OUT``: the dataset (the Zarr store OUT/sweep.zarr; with ``--netcdf``
    also OUT/sweep.nc) and its figure (OUT/sweep.png).

    One line on standard error for every failure, and the exit status of
    pendula-run: 2 bad scene or arguments (``--threads``, ``--workers``,
    ``--chunk-points`` out of range), 3 the scene's model is not one a sweep
    runs, 4 the computation failed, 5 the output cannot be written (OUT is a
    file, a device, read-only, a full disk, or another sweep is writing it);
    nothing is left under a final name after a failure (the resumable store
    stays).  A cluster started for ``--workers`` is closed on every path."""
    import contextlib
    import sys

    def say(msg: str, code: int) -> int:
        print(f"pendula sweep: {msg}", file=sys.stderr)
        return code

    out = pathlib.Path(args.output)
    try:
        if getattr(args, "netcdf", False):     # before the sweep runs: a missing package is one line, exit 6
            require("scipy.io", "sweep", "pendula sweep --netcdf (NetCDF3 through SciPy)")
        workers = _checks.count(args.workers, "--workers", 0, 256)
        threads = _checks.threads(args.threads, "--threads")
        chunk_points = _checks.count(args.chunk_points, "--chunk-points", 1)
        scene = Scene.from_file(args.scene)
        if not scene.grid:
            raise SceneError(f"{args.scene}: field 'grid' is empty: a sweep scene names 1 to 3 axes")
        if out.exists() and not out.is_dir():
            raise NotADirectoryError(20, "is not a folder", str(out))
        with contextlib.ExitStack() as stack:
            client = None
            if workers:
                from ._cluster import local_client
                client = stack.enter_context(local_client(workers))   # closed, cluster and all, on leaving
            ds = sweep(scene, out=out, chunk_points=chunk_points, client=client, threads=threads,
                       progress=not args.quiet)
        files = [out / "sweep.zarr"]
        if getattr(args, "netcdf", False):
            with atomic_path(out / "sweep.nc") as tmp:
                ds.to_netcdf(tmp, engine="scipy")
            files.append(out / "sweep.nc")
        files.append(plot_sweep(ds, out / "sweep.png"))
    except (SceneError, ValueError, TypeError) as exc:
        return say(str(exc), 2)
    except NotImplementedError as exc:
        return say(f"{args.scene}: {exc}", 3)
    except StoreBusyError as exc:     # another sweep writes the same output folder
        return say(exc.strerror, 5)
    except OSError as exc:
        where = f"{exc.filename}: " if exc.filename else f"{out}: "
        return say(f"cannot write the output: {where}{exc.strerror or exc}", 5)
    except (ArithmeticError, RuntimeError, MemoryError) as exc:
        return say(f"{args.scene}: {exc}", 4)
    except Exception as exc:    # noqa: BLE001 - the Dask cluster failed (a worker died: KilledWorker ...)
        if not type(exc).__module__.startswith(("distributed", "dask")):
            raise
        first = (str(exc).strip().splitlines() or [type(exc).__name__])[0]
        return say(f"{args.scene}: the Dask cluster failed ({type(exc).__name__}: {first})", 4)
    st = ds.status.values
    print(f"pendula sweep: {st.size} points, {np.mean(st == 0) * 100:.1f} % decided -> "
          f"{', '.join(map(str, files))}")
    return 0

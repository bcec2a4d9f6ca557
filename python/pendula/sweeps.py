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
    step) and status 6 'locked'; ``step`` is NaN elsewhere.  A window that
    ends unlocked but may be on a step (its mean within its error bar of one,
    or the map closing in on a periodic orbit, or an error bar above Omega / 8)
    runs on for windows twice as long (up to 63 or 7 first windows) until the
    map locks or the error bar falls below the distance to the nearest step;
    500 periods without a phase slip off a step's line also lock; the mean is
    the last window's (docs/source/guide/josephson.md, How it works).  A scene with
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

import math
import os
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike

from . import _checks
from ._optional import require
from ._sweep_engine import MEASURE_CODES, STATUS, check_driven, check_over, grid_of, run_measure
from ._sweep_follow import check_follow, follow_sweep
from ._store import StoreBusyError, SweepStoreWarning  # noqa: F401 - raised and warned by sweep(out=...)
from .scene import MEASURES, Scene
from .systems import contract
from .dynamics.attractor_maps import attractor_map

if TYPE_CHECKING:   # xarray and distributed are optional: named in annotations only
    import distributed
    import xarray

__all__ = ["sweep", "grid_of", "MEASURE_CODES", "STATUS"]


def sweep(scene: Scene | str | os.PathLike[str], over: dict[str, ArrayLike] | None = None,
          measure: Literal["final_well", "mean_velocity", "locked", "poincare", "lyapunov", "attractor"]
          | None = None, *, rtol: float | None = None, atol: float | None = None, t_max: float | None = None,
          transient: float | None = None, samples: int | None = None, out: str | os.PathLike[str] | None = None,
          chunk_points: int = 20000, client: distributed.Client | None = None, threads: int = 0,
          progress: bool = False, force: object = None, force_params: ArrayLike | None = None,
          follow: bool = False) -> xarray.Dataset:
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
    follow : bool
        An adiabatic sweep over one field (default False): each value starts
        from the end state of the value before (the last stroboscopic sample
        of a ``poincare`` point, else the state after its transient and
        window, in whole forcing periods), up the values from the scene's
        ``(theta0, v0)`` at the lowest, then down from the end of the way up
        at the highest.  An orbit diagram then follows one attractor until it
        disappears instead of jumping between coexisting ones, and where two
        coexist the two ways differ (hysteresis).  The result gains the
        dimension ``direction`` ('up', 'down').  One point after another in
        this process: not with ``out``, ``client``, a user's force, thermal
        noise or the ``attractor`` measure.

    Returns
    -------
    xarray.Dataset
        Lazy (dask-backed, read from the Zarr store) when ``out`` is given; with ``follow``, the
        dimension ``direction`` ('up', 'down') first.
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

    Followed up and down, the damped pendulum under a torque stays at rest up to the torque 1 and
    runs down to the retrapping torque (about 4 damping / pi): the I-V hysteresis of a junction:

    >>> j = pendula.Scene(damping=0.2)
    >>> iv = pendula.sweep(j, {"torque": [0.1, 0.5, 1.2]}, "mean_velocity", transient=100.0, t_max=300.0,
    ...                    follow=True)
    >>> (iv.mean_velocity.round(2).values > 0).tolist()
    [[False, False, True], [False, True, True]]
    """
    # in memory xarray alone does (pendula[xarray]); a store or a cluster needs the sweep extra
    require("xarray", "xarray" if out is None and client is None else "sweep", "pendula.sweep")

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
    over = check_over(scene, over)
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
    if _checks.flag(follow, "follow"):
        if measure == "mean_velocity":
            _checks.window(transient, t_max, "t_max")
        name, values = check_follow(scene, over, measure, out, client, uf)
        if measure == "poincare":
            check_driven(scene, over, "measure 'poincare'")
        return follow_sweep(scene, name, values, measure, rtol, atol, t_max, transient, samples, threads)
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
        check_driven(scene, over, f"measure '{measure}'")
    return run_measure(scene, over, measure, rtol, atol, t_max, transient, samples, chunk_points, out, client,
                       threads, progress, uf)

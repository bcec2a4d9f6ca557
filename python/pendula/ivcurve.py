"""The I-V curve of the Josephson junction (the damped, torqued pendulum): the
mean velocity <v> (the voltage) along a ramp of the torque (the bias
current), up and down, each torque starting from where the previous ended, so
that the hysteresis of the underdamped junction shows; with thermal noise on
one stream per branch.  :class:`pendula.Junction` gives it in laboratory units.
"""

from __future__ import annotations

import json
import math
import os
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike

from . import _checks, _interrupt
from ._optional import require
from ._sweep_engine import PARAM_ORDER, STATUS, VAR_META, status_attrs
from .scene import Scene
from .systems import contract

if TYPE_CHECKING:   # xarray is optional: named in annotations only
    import xarray

__all__ = ["iv_curve"]

#: noise streams per I-V branch (at most 1e6 torques, and a lead-in ramp of as many)
_IV_STREAMS = 2 * 10 ** 6


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
    if tau.size > 1 and not np.all(np.diff(tau) > 0):
        # 'up' ramps them in the order given: descending torques ramped down would be labelled 'up'
        raise ValueError("parameter 'torques' must be strictly ascending ('up' ramps them in this order, 'down' "
                         "in reverse); sort them first")
    transient = _checks.duration(transient, "transient", positive=False)
    t_avg = _checks.duration(t_max, t_name)
    _checks.window(transient, t_avg, t_name)
    rtol, atol = _checks.tolerances(scene.rtol if rtol is None else rtol, scene.atol if atol is None else atol)
    p = np.array([getattr(scene, f) for f in PARAM_ORDER], dtype=float)

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
                               {"long_name": VAR_META["mean_velocity_err"][0], "units": "rad s-1"}),
         "step": (dims, np.stack([rows[d][2] for d in dirs]),
                  {"long_name": VAR_META["step"][0], "units": "1"}),
         "status": (dims, np.stack([rows[d][3] for d in dirs]).astype(np.int32), status_attrs())},
        coords={"direction": ("direction", dirs, {"long_name": "branch of the adiabatic torque ramp"}),
                "torque": ("torque", tau, {"long_name": "constant torque tau", "units": "rad s-2"})},
        attrs={"scene": scene.to_namelist(), "measure": "iv_curve", "transient": transient, "t_max": t_avg,
               "rtol": rtol, "atol": atol, "start": start if isinstance(start, str) else repr(tuple(start)),
               "order_run": "up: the torques as given; down: in reverse, from where the up branch ended "
                            "(both) or from the up ramp's end (down alone, start='ramp')",
               "status_codes": json.dumps(STATUS)})

"""The physical systems (models) of pendula, one module per system.

A scene's fields select one model; the model says which of the scene's
effects it accepts and which keep an exact (closed-form) path.  The decision
scene -> model -> exact path or integrator is taken once, in the kernel's
dispatcher (kernel/dispatch/pendula_simulate.f90); :func:`run` hands it the
scene and returns what it computed, and :func:`models` lists the registry.

Adding a model: one kernel module (kernel/models), one registry entry and one
case in the kernel's dispatcher, and one line in ``_COLUMNS`` below when the
model returns more than theta, v and its invariant.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .. import _interrupt, _kernel
from .. import _checks
from .._checks import as_float
from . import contract
from ..scene import Scene, SceneError
from ..trajectory import Trajectory

__all__ = ["ModelInfo", "models", "run", "METHOD_NAMES"]

#: the kernel's method codes (kernel/dispatch/pendula_simulate.f90)
METHOD_NAMES = {0: "exact", 1: "rk4", 2: "verlet", 3: "yoshida4", 4: "yoshida6", 5: "yoshida8",
                6: "gauss4", 7: "gauss6", 8: "dopri5", 9: "dop853", 10: "gsl-rk8pd", 11: "dprkn6", 12: "vern9",
                13: "langevin", 14: "vern8"}

#: expected steps above which a run is made interruptible (fixed steps; an adaptive
#: step costs about ten fixed ones)
_LONG_STEPS = 1e5

# kernel status -> exception type (the kernel's message is the text)
_NOT_IMPLEMENTED = 14
_UNSORTED = 12
_INTEGRATOR_FAILED = 13   # (the kernel's sim_integrator_failed)


@dataclass(frozen=True)
class ModelInfo:
    """One model of the registry: what :func:`models` lists.

    Attributes
    ----------
    name : str
        The model's name ('rigid', 'cord', 'cycloid', 'gravity').
    selector : str
        The scene fields that select it.
    effects : tuple of str
        The effects it accepts (damping, torque, drive).
    exact_with : tuple of str
        The effects under which its exact path still answers (empty: exact
        only without effects).
    path : str
        'exact' (closed form), 'hybrid' (exact pieces joined at events) or
        'integrated'.
    implemented : bool
        False for a model the scene format names but pendula cannot run yet.
    summary : str
        One line about the model.
    state : str
        The size of its state and what the state holds.
    parameters : tuple of str
        Its parameters: the scene's fields for the models a :class:`Scene`
        selects, the arguments of its class for the others (``pendula.Network``, ...).
    scene : bool
        True for a model a :class:`Scene` selects; False for one built by its
        own class or function.
    time_scales : str
        The time scales its fields create (for the models a Scene selects,
        :func:`pendula.time_scales` computes them for a scene).

    See Also
    --------
    models : the registry.
    simulate : runs a scene on its model.

    Examples
    --------
    >>> import pendula
    >>> cyc = [m for m in pendula.models() if m.name == "cycloid"][0]
    >>> cyc.selector, cyc.path, cyc.exact_with
    ("guide='cycloid'", 'exact', ('damping', 'torque', 'drive'))
    """

    name: str
    selector: str
    effects: tuple
    exact_with: tuple
    path: str
    implemented: bool
    summary: str
    state: str = ""
    parameters: tuple = ()
    scene: bool = True
    time_scales: str = ""


def models() -> list[ModelInfo]:
    """The models pendula knows, from the kernel's registry.

    The scene's ``cord``, ``guide`` and ``gravity`` fields select one of the
    first four models; the dispatcher then answers by the model's exact path
    when the scene's effects allow it and otherwise by an integrator.  The
    others are built by their own class or function (``pendula.Network``,
    ``pendula.DoublePendulum``, ``pendula.FoucaultPendulum``,
    ``pendula.spherical_orbit``), whose tools ask the same capability table.
    ``pendula models`` prints the same table.

    Returns
    -------
    list of ModelInfo
        One entry per model, the rigid pendulum first.

    See Also
    --------
    ModelInfo : the fields of an entry.
    Scene : the fields that select a model.

    Examples
    --------
    >>> import pendula
    >>> [m.name for m in pendula.models()]
    ['rigid', 'cord', 'cycloid', 'gravity', 'network', 'double', 'foucault', 'spherical']
    """
    table = _kernel.models_v()
    text = table.decode() if isinstance(table, bytes) else str(table)
    out = []
    for line in text.strip().splitlines():
        name, sel, eff, exact, path, impl, summary, state, params, door, scales = (f.strip() for f in line.split("|"))
        words = lambda s: tuple(w for w in s.split() if w != "(none)")  # noqa: E731
        out.append(ModelInfo(name, sel, words(eff), words(exact), path, impl == "yes", summary, state,
                             tuple(params.split()), door == "scene", scales))
    return out


def _force_failure(t, theta, v) -> str:
    """Where a run with a user's force stopped on a non-finite value: the last output before it."""
    ok = np.isfinite(theta) & np.isfinite(v)
    k = int(np.argmin(ok)) if not ok.all() else len(t)
    if k == 0:
        return "force: the force (or the state) was not finite at the start: t = 0"
    return (f"force: the force (or the state) became non-finite after t = {t[k - 1]!r} (theta = {theta[k - 1]!r}, "
            f"v = {v[k - 1]!r}, the last finite output) and before t = {t[min(k, len(t) - 1)]!r}")


def run(scene: Scene, t, force: _checks.Force | None = None, recheck: bool = False,
        land: bool = False) -> Trajectory:
    """Run a scene through the kernel's dispatcher at the times t (any order);
    ``force``: a user's force (checked by ``_checks.force``) added to its force law.

    recheck: the kernel checks the scene's fields before running them (a scene
    whose integrator knobs were changed without building a new Scene: see
    pendula.motion.simulate); a refusal is a SceneError.  land: Verner's 9(8) pair
    ends its steps on the output times instead of interpolating.

    Raises
    ------
    NotImplementedError
        The scene selects a model pendula cannot run yet.
    ValueError
        The scene and the method disagree (a fixed-step method without dt,
        'exact' with effects, ...), or the integrator failed.
    """
    t = as_float(t, "t")
    _checks.angle(scene.theta0, "field 'theta0'")     # |theta0| <= 2^52, as in every function
    flat = np.ascontiguousarray(t, dtype=np.float64).reshape(-1)
    x, words, wlen, nout, ngrid = scene._kernel_fields
    # the times as given: the exact paths take any order, and an integrator
    # refuses unsorted times (status 12) before any work, so they are sorted
    # only then (the scene's own times and most others come in order)
    order, sorted_t = None, flat
    while True:
        cancel = _interrupt.cancel_flag()
        long = bool(scene.effects) and _long_run(scene, sorted_t)
        faddr, fparams = _checks.force_args(force)
        theta_s, v_s, e_s, stats, method, status, msg = _interrupt.call(
            _kernel.simulate_v, x, words, wlen, nout, ngrid, sorted_t, faddr, fparams, cancel, int(recheck),
            int(land), cancel=cancel, long=long or force is not None)
        if force is not None:
            force.reraise()
        if status != _UNSORTED or order is not None:
            break
        order = np.argsort(flat, kind="stable")
        sorted_t = np.ascontiguousarray(flat[order])
    if status:
        msg = (msg.decode(errors="replace") if isinstance(msg, bytes) else str(msg)).strip()
        if status == _NOT_IMPLEMENTED:
            raise NotImplementedError(msg)
        if status == 100:
            raise SceneError(f"the kernel refused the scene: {msg}")
        if force is not None and status == _INTEGRATOR_FAILED:
            raise ValueError(_force_failure(sorted_t, theta_s, v_s))
        raise ValueError(msg)
    if order is None:
        theta, v, e = theta_s, v_s, e_s
    else:
        theta = np.empty_like(flat)
        v = np.empty_like(flat)
        e = np.empty_like(flat)
        theta[order] = theta_s
        v[order] = v_s
        e[order] = e_s
    if t.shape != theta.shape:
        theta, v, e = (a.reshape(t.shape) for a in (theta, v, e))
    name = METHOD_NAMES[int(method)]
    st = {} if method == 0 else {"steps": int(stats[0]), "accepted": int(stats[1]), "rejected": int(stats[2]),
                                 "rhs_evaluations": int(stats[3]), "stopped_by_event": False}
    if not np.isfinite(theta_s.sum() + v_s.sum()):   # (a finite sum: every value finite)
        nan_out = ~(np.isfinite(theta) & np.isfinite(v)) & ~np.isnan(t)
        if np.any(nan_out & ~np.isfinite(t)):
            warnings.warn(f"simulate: {int(np.sum(nan_out & ~np.isfinite(t)))} non-finite time(s) gave NaN",
                          RuntimeWarning, stacklevel=3)
        if np.any(nan_out & np.isfinite(t)):
            warnings.warn(f"simulate: {int(np.sum(nan_out & np.isfinite(t)))} value(s) at finite times are NaN: "
                          "the state has no value there (at a cusp of the cycloidal guide the cord is horizontal "
                          "and v is undefined; beyond 2**48 half periods the exact path cannot reduce its phase)",
                          RuntimeWarning, stacklevel=3)
    return Trajectory(t, theta, v, e, name, scene, st)


def _long_run(scene: Scene, t: np.ndarray) -> bool:
    """Could this integration take more than a few milliseconds?  Then it runs
    where Ctrl-C can stop it (a worker thread, a fraction of a millisecond);
    short runs skip that.  Decided by the expected work: the span in periods of
    the scene's fastest time scale (the kernel's one time-scale rule, which sees
    every field: the pivot's force, a steep field, the damping ...), times the
    steps a period takes at the scene's tolerance, or the fixed steps."""
    if t.size == 0:
        return False
    span = max(abs(float(t[0])), abs(float(t[-1]))) if t.size < 2 or t[-1] >= t[0] else float(np.max(np.abs(t)))
    ts = contract.time_scales(scene)
    if scene.noise > 0:
        return span / (scene.dt if scene.dt > 0 else ts.langevin_dt) > _LONG_STEPS
    if scene.dt > 0 and scene.method not in ("auto", "dop853", "dopri5", "gsl-rk8pd", "vern9", "vern8", "dprkn6"):
        return span / scene.dt > _LONG_STEPS
    return contract.expected_steps(scene, span) > _LONG_STEPS / 10

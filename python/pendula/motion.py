"""The motion of a scene: simulate() and period().

The conservative rigid pendulum is answered exactly (pendula.systems.rigid);
scenes that name effects (damping, torque, drive, ...) go to the integrators.
The rigid model's functions are re-exported here for compatibility.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from . import _checks
from ._checks import as_float
from .systems.rigid import Orbit, energy, exact_motion, orbit
from .scene import _NUMBER_LISTS, _NUMBERS, _WORDS, METHODS, Scene, SceneError
from .systems import run
from .systems.contract import require
from .systems.cord import simulate_cord
from .systems.cycloid import cycloid_period
from .systems.gravity import gravity_orbit
from .trajectory import Trajectory

__all__ = ["Orbit", "Trajectory", "orbit", "exact_motion", "energy", "simulate", "period"]


def simulate(scene: Scene, t: ArrayLike | None = None, method: str | None = None, rtol: float | None = None,
             atol: float | None = None, dt: float | None = None, force: object = None,
             force_params: ArrayLike | None = None, land_on_outputs: bool = False) -> Trajectory:
    """Run one scene at the times ``t`` (default: the scene's own output times).

    The scene selects its model (see :func:`pendula.models`); the kernel's
    dispatcher answers by the model's exact path whenever the scene allows it
    (method 'auto', the default, or 'exact') and otherwise integrates with the
    scene's method ('auto': the pair the work-precision study found fastest for
    the scene's class and rtol, see the guide page "Effects and integrators").  The initial state is at t = 0; the times need not start
    at 0 or be increasing.  A scene with a sweep is run at its own (un-swept)
    values; use ``scene.members()`` for the family.

    Parameters
    ----------
    scene : Scene
        What to compute: the system, its initial state and its effects.
    t : array_like, optional
        Output times (default ``scene.times()``).
    method : str, optional
        The integrator ('auto', 'exact', 'rk4', 'verlet', 'yoshida4',
        'yoshida6', 'yoshida8', 'gauss4', 'gauss6', 'dopri5', 'dop853',
        'gsl-rk8pd', 'dprkn6', 'vern9', 'vern8'); overrides the scene's field.
    rtol, atol : float, optional
        Tolerances of the adaptive methods (scipy ``solve_ivp``'s names).
    dt : float, optional
        Step of the fixed-step methods.
    force : C function pointer or callable, optional
        A force of one's own added to theta'': ``double f(double t, double
        theta, double v, const double *params)`` as a ctypes function
        (argtypes and restype set), a numba ``cfunc`` (the object or its
        ``.address``) or an integer address; the kernel calls it on every
        right-hand-side evaluation, from every thread (it must keep no state).
        A plain Python callable ``f(t, theta, v, params)`` is accepted too:
        the slow path (the kernel calls back into Python).  The scene is then
        integrated (never the exact path); see the guide page "Effects".
    force_params : sequence of float, optional
        The params the force reads, passed as given (the force must read no
        more than ``len(force_params)`` values; a force with an attribute
        ``nparams`` gets exactly that many, or ValueError).
    land_on_outputs : bool, optional
        The adaptive pairs with an interpolant ('dopri5', 'dop853', 'vern9', 'vern8'):
        end the steps exactly on the output times, so that every output is a
        step's own value, instead of interpolating inside the steps (the
        default: the steps are then never shortened).  With outputs closer
        than the steps the tolerance allows, landing costs more steps and
        gives more accuracy; the work-precision study shows where each wins.

    Returns
    -------
    Trajectory
        The times, angle, angular velocity and energy, the method that
        answered, and the work done (``stats``).

    Raises
    ------
    TypeError
        If `scene` is not a :class:`Scene`, a time or knob has the wrong type
        (`land_on_outputs` not a bool), or `force` is None, not callable or a
        ctypes function of another signature.
    SceneError
        If a knob is invalid (an unknown method, a negative tolerance; a
        subclass of ValueError naming the field).
    ValueError
        If the computation cannot be done as asked (e.g. a fixed-step method
        for the flexible cord, more steps than the limit, `land_on_outputs`
        with a method that does not interpolate), or the force returned NaN
        (the message gives the time and state).
    NotImplementedError
        For a combination of model and effects not implemented.

    See Also
    --------
    Scene : the question.
    find_events : event times on the same integrators.
    exact_motion : the exact motion from numbers instead of a scene.

    Examples
    --------
    >>> import pendula
    >>> tr = pendula.simulate(pendula.Scene(v0=1.0, damping=0.1), [0.0, 1.0], rtol=1e-12, atol=1e-14)
    >>> tr.method                        # 'auto': the work-precision study's pick for damped, rtol 1e-12
    'vern8'
    >>> pendula.simulate(pendula.Scene(v0=1.9), [0.0, 1.0]).method     # conservative: exact
    'exact'
    >>> landed = pendula.simulate(pendula.Scene(v0=1.0, damping=0.1), [0.0, 0.5, 1.0], method="vern9",
    ...                           land_on_outputs=True)
    >>> landed.stats["steps"] >= 2                                      # a step ends on each output
    True
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"simulate expects a pendula.Scene, got {type(scene).__name__}")
    if not isinstance(land_on_outputs, (bool, np.bool_)):
        raise TypeError(f"land_on_outputs must be True or False, not {type(land_on_outputs).__name__}")
    uf = None if force is None and force_params is None else _checks.force(force, force_params)
    if land_on_outputs:
        return _landed(scene, t, method, rtol, atol, dt, uf)
    if uf is None and (method is not None or rtol is not None or atol is not None or dt is not None):
        knobs = {k: v for k, v in (("method", method), ("rtol", rtol), ("atol", atol), ("dt", dt)) if v is not None}
        variant = _with_knobs(scene, knobs)
        if variant is not None:
            # the kernel checks the changed fields as it runs them (no new Scene built and checked first),
            # once: the variant is kept on the scene, marked as checked
            tt = variant.times() if t is None else as_float(t, "t")
            checked = variant.__dict__.get("_knobs_checked", False)
            try:
                tr = run(variant, tt, recheck=not checked)
            except SceneError:
                pass        # the knobs do not fit the scene: replace() below raises with the field named
            else:
                variant.__dict__["_knobs_checked"] = True
                return tr
        scene = scene.replace(**knobs)
    elif method is not None or rtol is not None or atol is not None or dt is not None:
        scene = scene.replace(**{k: v for k, v in (("method", method), ("rtol", rtol), ("atol", atol), ("dt", dt))
                                 if v is not None})
    t = scene.times() if t is None else as_float(t, "t")
    if uf is not None:
        return run(scene, t, uf)
    if scene.cord == "flexible":
        # the flexible cord's own driver: the kernel's exact circle-flight-jerk path, or (with
        # damping, torque or drive) the integrator with the tension event between exact flights
        return simulate_cord(scene, t)
    return run(scene, t)


def _landed(scene, t, method, rtol, atol, dt, force=None):
    """simulate(..., land_on_outputs=True): an adaptive pair with its steps ending on the outputs."""
    knobs = {k: v for k, v in (("method", method), ("rtol", rtol), ("atol", atol), ("dt", dt)) if v is not None}
    scene = scene.replace(**knobs) if knobs else scene
    if scene.method not in _LANDING or scene.cord != "rigid":
        raise ValueError(f"land_on_outputs: the adaptive pairs that interpolate ({', '.join(_LANDING)}) land their "
                         f"steps on the outputs on request, on the rigid cord (dprkn6 always lands, the fixed-step "
                         f"methods branch off a step); the method is {scene.method!r}, the cord {scene.cord!r}")
    t = scene.times() if t is None else as_float(t, "t")
    return run(scene, t, force, land=True)


def period(scene: Scene) -> float:
    """The period of the scene's conservative orbit (exact).

    Parameters
    ----------
    scene : Scene
        A conservative scene: the rigid pendulum (any regime), Huygens'
        cycloid (also with a torque) or a non-uniform gravity field.

    Returns
    -------
    float
        The period of a libration, the time of one turn of a rotation, inf on
        the separatrix (4K(m)/sqrt(eps) for the rigid pendulum; 4 pi sqrt(R/g)
        on the cycloid; an exact quadrature in non-uniform gravity).

    Raises
    ------
    TypeError
        If `scene` is not a :class:`Scene`.
    ValueError
        If the scene has effects (damping, a drive, ...), which leave no period
        in this sense; use :func:`numerical_period` for event-based periods.

    See Also
    --------
    orbit : the period with the other facts of the orbit.
    numerical_period : the period measured by events on an integrator.
    period_series : the series of T/T0 in the amplitude.

    Examples
    --------
    >>> import pendula
    >>> pendula.period(pendula.Scene(theta0=1.0))
    6.699975664370453
    >>> pendula.period(pendula.Scene(guide="cycloid", theta0=1.0))   # 2 pi at any amplitude
    6.283185307179586
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"period expects a pendula.Scene, got {type(scene).__name__}")
    require(scene, "period")      # the capability table: a conservative orbit's fact (the cycloid: any torque)
    # the cycloid (any amplitude) and non-uniform gravity (exact quadrature) have their own periods
    if scene.guide == "cycloid":
        return cycloid_period(scene)
    if scene.gravity != "uniform":
        return gravity_orbit(scene).period
    return orbit(scene.theta0, scene.v0, scene.eps).period


#: where the integrator's knobs sit among the kernel's fields of a scene
_KNOB_NUMBER = {name: _NUMBERS.index(name) for name in ("rtol", "atol", "dt")}
_METHOD_WORD = _WORDS.index("method")


def _with_knobs(scene: Scene, knobs: dict) -> Scene | None:
    """The scene with other integrator knobs (method, rtol, atol, dt), its kernel fields patched in place of
    building and checking a new Scene (``simulate`` then has the kernel check them as it runs); kept on the
    scene (a few, by the knobs) so that asking again costs a look-up; None where
    that does not apply: a sweep or grid, the flexible cord (its own driver), a knob that is not a float or
    a method name as written in ``METHODS`` (``Scene.replace`` converts and checks those)."""
    key = tuple(knobs.items())
    kept = scene.__dict__.get("_knob_variants")
    if kept is not None and key in kept:
        return kept[key]
    if scene.sweep or scene.grid or scene.cord != "rigid" or any(getattr(scene, n) for n in _NUMBER_LISTS):
        return None
    for k, v in knobs.items():
        if not (type(v) is str and v in METHODS if k == "method" else type(v) is float):
            return None
    x, words, wlen, nout, ngrid = scene._kernel_fields
    x = x.copy()
    for k, i in _KNOB_NUMBER.items():
        if k in knobs:
            x[i] = knobs[k]
    if "method" in knobs:
        start = int(wlen[:_METHOD_WORD].sum())
        word = knobs["method"].encode()
        words = words[:start] + word + words[start + int(wlen[_METHOD_WORD]):]
        wlen = wlen.copy()
        wlen[_METHOD_WORD] = len(word)
    variant = object.__new__(Scene)
    variant.__dict__.update({k: v for k, v in scene.__dict__.items() if k not in _NOT_COPIED})
    variant.__dict__.update(knobs)
    variant.__dict__["_kernel_fields"] = (x, words, wlen, nout, ngrid)
    if kept is None or len(kept) >= _MAX_VARIANTS:
        kept = scene.__dict__["_knob_variants"] = {}
    kept[key] = variant
    return variant


#: the methods that land their steps on the outputs on request (simulate's land_on_outputs)
_LANDING = ("dopri5", "dop853", "vern9", "vern8")
#: a scene keeps at most this many variants with other knobs (the last ones asked for)
_MAX_VARIANTS = 8
#: what a variant does not inherit from its scene: the scene's own variants and check mark
_NOT_COPIED = ("_knob_variants", "_knobs_checked")

"""Integrators, events and the numerical period.

Method names (a contract): 'rk4', 'verlet', 'yoshida4', 'yoshida6', 'yoshida8',
'gauss4', 'gauss6' (fixed step: they take ``dt``), 'dopri5', 'dop853',
'gsl-rk8pd', 'dprkn6' (adaptive: they take ``rtol`` and ``atol``; 'dprkn6', Dormand &
Prince's Runge-Kutta-Nystrom pair RKN6(4), takes undamped scenes only and has no dense
output, so no events), 'vern9' (Verner's 9(8) pair, any scene, Verner's order-8
interpolant; no events), 'vern8' (Verner's 8(7) pair, likewise), 'exact' and 'auto'.
The right-hand side holds only the effects the scene names.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from . import _checks, _interrupt, _kernel
from ._checks import as_float
from .scene import Scene
from .systems import run
from .systems.contract import require
from .systems.cord import simulate_cord
from .systems.cycloid import cycloid_motion, cycloid_period
from .systems.gravity import gravity_orbit
from .systems.rigid import orbit

if TYPE_CHECKING:   # xarray is optional: named in annotations only
    import xarray

__all__ = ["integrate_scene", "find_events", "numerical_period", "Events", "FIXED_STEP", "ADAPTIVE"]

CODES = {"rk4": 1, "verlet": 2, "yoshida4": 3, "yoshida6": 4, "yoshida8": 5, "gauss4": 6, "gauss6": 7,
         "dopri5": 8, "dop853": 9, "gsl-rk8pd": 10, "dprkn6": 11, "vern9": 12, "vern8": 14}
FIXED_STEP = ("rk4", "verlet", "yoshida4", "yoshida6", "yoshida8", "gauss4", "gauss6")
ADAPTIVE = ("dopri5", "dop853", "gsl-rk8pd", "dprkn6", "vern9", "vern8")
_STATUS = {1: "the step dt must be positive", 2: "rtol must be > 0 and atol >= 0", 3: "unknown method",
           5: "step size underflow (the problem may be singular or the tolerance unreachable)",
           6: "the state became non-finite", 9: "events are located on the dense output of dopri5 and dop853 only",
           7: "the run needs more steps than the work limit (1e8 adaptive, 2e9 fixed-step): shorten the span, "
              "or give a larger dt or rtol",
           8: "interrupted",
           11: "gsl-rk8pd integrates forward only: give times >= 0",
           12: "the Runge-Kutta-Nystrom pair integrates theta'' = f(t, theta) only: no damping",
           100: "the scene's fields do not form a scene (the kernel refused them)"}
_EVENT_KINDS = {"turning": 1, "theta": 2, "theta_mod_2pi": 3}
#: the flexible cord's events: the cord slackens (the bob leaves the circle) or is taut again
CORD_EVENT_KINDS = ("departure", "return")
#: the sense of a crossing, by name (the numbers are accepted too)
_DIRECTIONS = {"rising": 1, "falling": -1, "both": 0}
#: the most events one call records (memory: 24 bytes each)
MAX_EVENTS = 10_000_000
#: samples of the cycloid's exact path per shortest period when its events are bracketed
CYCLOID_SAMPLES_PER_PERIOD = 64
#: the most samples of the exact path one event search takes (in blocks of CYCLOID_BLOCK)
CYCLOID_MAX_SAMPLES = 10**9
CYCLOID_BLOCK = 1 << 16


def _run(scene, method, t_sorted, ev_kind=0, ev_level=0.0, ev_dir=0, terminal=False, max_events=1):
    if method not in CODES:
        raise ValueError(f"unknown method {method!r}; known: {', '.join(CODES)}, exact, auto")
    if method in FIXED_STEP and not scene.dt > 0:
        raise ValueError(f"method {method!r} is fixed-step: give the scene a step dt > 0")
    if method in ADAPTIVE and not (scene.rtol > 0 and scene.atol >= 0):
        raise ValueError("adaptive methods need rtol > 0 and atol >= 0")
    if scene.cord != "rigid":
        raise ValueError("field 'cord': events and the numerical period are located on the rigid cord; the "
                         "flexible cord's departures and returns are in simulate(...).flips")
    if scene.guide == "cycloid":
        raise ValueError("the cycloidal pendulum is solved in closed form, never integrated")
    if scene.gravity != "uniform" and method == "gsl-rk8pd":
        raise ValueError("gsl-rk8pd does not take a non-uniform gravity field; use dop853")
    if scene.friction != 0.0:
        # the stick needs the dispatcher's stretches between v = 0 events (simulate)
        raise NotImplementedError("field 'friction': events on a scene with dry friction are not implemented; "
                                  "simulate(scene) gives the path, friction_turning_points(scene) its stops")
    cancel = _interrupt.cancel_flag()
    x, words, wlen, nout, ngrid = scene._kernel_fields     # the scene as the kernel checked it
    # always interruptible: a short span can still take many steps (stiff damping, tight tolerances)
    out = _interrupt.call(_kernel.integrate_v, x, words, wlen, nout, ngrid, CODES[method], t_sorted, ev_kind,
                          ev_level, ev_dir, int(terminal), max_events, cancel, cancel=cancel)
    theta, v, stats, status, nev, tev, thev, vev = out
    if status not in (0, 10):
        if status > 100:
            raise RuntimeError(f"GSL odeiv2 failed with status {status - 100}")
        raise ValueError(f"{method}: {_STATUS.get(status, f'kernel status {status}')}")
    stats = {"steps": int(stats[0]), "accepted": int(stats[1]), "rejected": int(stats[2]),
             "rhs_evaluations": int(stats[3]), "stopped_by_event": status == 10}
    return theta, v, stats, tev[:nev], thev[:nev], vev[:nev]


def integrate_scene(scene: Scene, t, method: str = "auto"):
    """A Trajectory of the scene at the times t by the named method (the
    kernel's dispatcher, as :func:`pendula.simulate` with ``method``)."""
    if method not in CODES and method not in ("auto", "exact"):
        raise ValueError(f"unknown method {method!r}; known: {', '.join(CODES)}, exact, auto")
    if method in FIXED_STEP and not scene.dt > 0:
        raise ValueError(f"method {method!r} is fixed-step: give the scene a step dt > 0")
    return run(scene.replace(method=method), t)


@dataclass
class Events:
    """Located events: what :func:`find_events` returns.

    Attributes
    ----------
    t : ndarray
        Event times, increasing.
    theta, v : ndarray
        The state at each event.
    stats : dict
        Work done: ``steps``, ``accepted``, ``rejected``, ``rhs_evaluations``,
        ``stopped_by_event``; ``path_evaluations`` where the events are roots of
        an exact path (the cycloidal guide).

    See Also
    --------
    find_events : makes it.
    Trajectory : a motion at given times.

    Examples
    --------
    >>> import pendula
    >>> ev = pendula.find_events(pendula.Scene(theta0=1.0), "turning", direction=-1, t_end=20)
    >>> ev.t.round(6).tolist()             # maxima of theta: one per period 6.699976
    [6.699976, 13.399951]
    """

    t: np.ndarray
    theta: np.ndarray
    v: np.ndarray
    stats: dict

    def __repr__(self) -> str:
        n = np.size(self.t)
        span = f" from t={self.t[0]:.6g} to {self.t[-1]:.6g}" if n else ""
        return f"Events({n} events{span}, {self.stats.get('steps', 0)} steps)"

    def to_xarray(self) -> xarray.Dataset:
        """The events as an :class:`xarray.Dataset` along the dimension ``event``.

        Returns
        -------
        xarray.Dataset
            ``t``, ``theta``, ``v`` on ``event``; the work counters as attributes.

        Examples
        --------
        >>> import pendula
        >>> ev = pendula.find_events(pendula.Scene(theta0=1.0), "turning", t_end=10.0)
        >>> ev.to_xarray().sizes["event"] == ev.t.size
        True
        """
        from ._optional import require
        xr = require("xarray", "xarray", "Events.to_xarray")
        return xr.Dataset({"t": ("event", self.t, {"long_name": "time of the event", "units": "s"}),
                           "theta": ("event", self.theta, {"long_name": "angle at the event", "units": "rad"}),
                           "v": ("event", self.v, {"long_name": "angular velocity at the event",
                                                   "units": "rad s-1"})},
                          coords={"event": np.arange(self.t.size)},
                          attrs={k: (int(v) if isinstance(v, (bool, np.bool_)) else v) for k, v in self.stats.items()})


def find_events(scene: Scene, kind: str = "turning", level: float = 0.0, direction: int | str = 0,
                t_end: float | None = None, terminal: bool = False, method: str = "dop853",
                max_events: int = 100_000) -> Events:
    """Locate events on the dense output of an adaptive integrator.

    Each accepted step is sampled at four interior points, so two crossings
    inside one step are both found; a crossing is refined by the Illinois
    method to a few ulps of t.  An event function that is exactly zero at the
    start (an event that starts at zero) is not reported there.

    The flexible cord's events are its flips, from the kernel's flip log (the
    departure point and the re-entry are found in closed form there); its
    other crossings are not located (NotImplementedError).

    The cycloidal guide is never integrated: its events are roots of its
    closed-form path, bracketed on CYCLOID_SAMPLES_PER_PERIOD samples per
    shortest period (natural or drive) and bisected to adjacent doubles
    (``method`` is ignored there; ``stats['path_evaluations']`` counts the work).

    Parameters
    ----------
    scene : Scene
        The motion to search (any effects; the exact path is not used, except
        for the cycloidal guide, which has no other).
    kind : {'turning', 'theta', 'theta_mod_2pi', 'departure', 'return'}
        'turning': v = 0; 'theta': theta = level; 'theta_mod_2pi': theta = level + 2 pi k;
        the flexible cord's flips: 'departure' (the tension vanishes and the bob
        leaves the circle) and 'return' (the cord is taut again; the state just
        after the jerk).
    level : float, optional
        The angle for 'theta' and 'theta_mod_2pi'.
    direction : {'both', 'rising', 'falling'} or {0, +1, -1}
        Every crossing, or only those where the event function rises (+1) or
        falls (-1).
    t_end : float, optional
        End of the search, > 0 (default the scene's `t_end`).
    terminal : bool
        Stop at the first event.
    method : {'dop853', 'dopri5'}
        The integrator (events need dense output).
    max_events : int
        At most this many events (1 to 1e7).

    Returns
    -------
    Events
        The event times and states, and the work done.

    Raises
    ------
    TypeError
        For a `scene` that is not a Scene, a non-integer `max_events`, a
        non-bool `terminal` or a non-number `level`.
    ValueError
        For an unknown `kind`, a `direction` other than those above, a method
        without dense output, `max_events` out of range, a `level` that is not
        finite or beyond 2^52 in magnitude (where level + 2 pi k has no
        fraction left), or `t_end` not positive and finite.
    NotImplementedError
        For other crossings of the flexible cord, and for a scene with dry
        ``friction`` (its stops: :func:`friction_turning_points`).

    See Also
    --------
    numerical_period : the period from events.
    simulate : the motion at given times.

    Examples
    --------
    >>> import pendula
    >>> ev = pendula.find_events(pendula.Scene(theta0=1.0), "turning", direction=-1, t_end=20)
    >>> ev.t.size, round(float(ev.t[0]), 9)       # one maximum per period 6.699975664
    (2, 6.699975664)
    """
    _checks.instance(scene, "scene", Scene, "a pendula.Scene")
    require(scene, "find_events")    # the capability table: noise refused, friction not yet
    if kind not in _EVENT_KINDS and kind not in CORD_EVENT_KINDS:
        raise ValueError(f"kind must be one of {', '.join(tuple(_EVENT_KINDS) + CORD_EVENT_KINDS)}, got {kind!r}")
    direction = _DIRECTIONS.get(direction, direction) if isinstance(direction, str) else direction
    if isinstance(direction, bool) or direction not in (-1, 0, 1):
        raise ValueError(f"direction must be 'rising' (+1), 'falling' (-1) or 'both' (0), got {direction!r}")
    if scene.guide != "cycloid" and scene.cord != "flexible" and method not in ("dopri5", "dop853"):
        raise ValueError("events need a method with dense output: 'dopri5' or 'dop853'")
    if isinstance(max_events, bool) or not isinstance(max_events, (int, np.integer)):
        raise TypeError(f"max_events must be a whole number, got {max_events!r}")
    if not 1 <= max_events <= MAX_EVENTS:
        raise ValueError(f"max_events must be between 1 and {MAX_EVENTS}, got {max_events}")
    if not isinstance(terminal, (bool, np.bool_)):
        raise TypeError(f"terminal must be True or False, got {terminal!r}")
    # finite, and |level| <= 2^52 as every angle: beyond, level + 2 pi k has no fraction left
    level = _checks.angle(level, "level")
    t_end = scene.t_end if t_end is None else as_float(t_end, "t_end")
    t_end = float(np.reshape(t_end, -1)[0]) if np.size(t_end) == 1 else math.nan
    if not t_end > 0 or not math.isfinite(t_end):
        raise ValueError(f"t_end must be positive and finite (events are located forward in time), got {t_end!r}")
    if scene.cord == "flexible" or kind in CORD_EVENT_KINDS:
        return _cord_events(scene, kind, int(direction), t_end, bool(terminal), int(max_events))
    if scene.guide == "cycloid":
        return _cycloid_events(scene, kind, float(level), int(direction), t_end, bool(terminal), int(max_events))
    _, _, stats, tev, thev, vev = _run(scene, method, np.array([t_end]), _EVENT_KINDS[kind], float(level),
                                       int(direction), terminal, int(max_events))
    return Events(tev.copy(), thev.copy(), vev.copy(), stats)


def numerical_period(scene: Scene, periods: int = 20, method: str = "dop853") -> float:
    """The period measured by event location (Prusa & Tuma, task 2).

    Libration: the mean spacing of successive maxima (v falling through 0);
    rotation: the mean time per turn (theta passing theta0 + 2 pi k).  The
    integration runs over ``periods`` estimated periods (at most 1e6).  Every
    conservative model: the rigid pendulum (its exact period from the elliptic
    integral), the non-uniform gravity fields (their quadrature period,
    :func:`pendula.gravity_orbit`) and the cycloidal guide (events on its exact
    path; a torque only shifts its centre).  The measured period is compared
    with the model's exact one.

    Next to the separatrix an integrator's energy error can carry the orbit
    across it (v0 = 2 - 1e-12 measured 49.2 at rtol 1e-10 against the exact
    60.8): the tolerance is tightened to 1% of the orbit's distance from the
    separatrix (down to rtol = 1e-14), and where even that cannot resolve the
    orbit, or the measured period disagrees with the exact one by more than
    1e-6, a RuntimeWarning says so.

    Parameters
    ----------
    scene : Scene
        A conservative rigid scene.
    periods : int, optional
        How many periods to measure over (2 to 1e6).
    method : {'dop853', 'dopri5'}
        The integrator.

    Returns
    -------
    float
        The measured period; inf on the separatrix.

    Raises
    ------
    TypeError
        If `scene` is not a Scene or `periods` is not a number.
    ValueError
        If `periods` is out of range or the scene has effects.
    RuntimeError
        If fewer than two events were found.

    See Also
    --------
    period : the exact period.
    find_events : the events it measures.

    Examples
    --------
    >>> import pendula
    >>> s = pendula.Scene(theta0=1.0, rtol=1e-12, atol=1e-14)
    >>> abs(pendula.numerical_period(s) / pendula.period(s) - 1) < 1e-12
    True
    """
    _checks.instance(scene, "scene", Scene, "a pendula.Scene")
    if isinstance(periods, bool) or not isinstance(periods, (int, float, np.integer, np.floating)):
        raise TypeError(f"periods must be a number, got {periods!r}")
    if not 2 <= periods <= 1e6:
        raise ValueError(f"periods must be between 2 and 1e6, got {periods!r}")
    require(scene, "numerical_period")    # a conservative orbit's period (the cycloid: any torque)
    if scene.guide == "cycloid":
        # Huygens: the period does not depend on the amplitude; a torque only shifts the centre
        if scene.damping != 0.0 or scene.drive_amplitude != 0.0:
            raise ValueError("numerical_period measures the period of a conservative orbit: this cycloid "
                             "scene has damping or a drive")
        exact, regime = cycloid_period(scene), "libration"
    elif scene.cord == "flexible":
        # a cord that never slackens moves as the rigid pendulum does, to the bit (tested): its period is
        # that motion's; one that slackens has no period (its flips are find_events(..., 'departure'))
        rigid = scene.replace(cord="rigid")
        if rigid.effects:
            raise ValueError("numerical_period measures the period of a conservative orbit: the scene has "
                             + ", ".join(e for e in rigid.effects if e in ("damping", "torque", "drive")))
        o = orbit(scene.theta0, scene.v0, scene.eps)
        if not math.isfinite(o.period):
            return math.inf
        fl = _cord_events(scene, "departure", 0, float(periods) * o.period * 1.02, True, 1)
        if fl.t.size:
            raise ValueError(f"the flexible cord slackens (first at t = {fl.t[0]!r}, theta = {fl.theta[0]!r}): its "
                             "motion is not periodic; its flips are find_events(scene, 'departure')")
        return numerical_period(rigid, periods, method)
    elif set(scene.effects) - {"gravity"}:
        raise ValueError("numerical_period measures the period of a conservative orbit: the scene has "
                         + ", ".join(e for e in scene.effects if e != "gravity"))
    else:
        o = gravity_orbit(scene) if scene.gravity != "uniform" else orbit(scene.theta0, scene.v0, scene.eps)
        if not math.isfinite(o.period):
            return math.inf
        exact, regime = o.period, o.regime
        dist = o.mc  # 1 - k^2 (libration) or 1 - 1/k^2 (rotation): the distance from the separatrix
        rtol = min(scene.rtol, max(1e-14, 0.01 * dist))
        if rtol > 0.01 * dist:
            warnings.warn(f"numerical_period: the orbit lies within {dist:.1e} (in k^2) of the separatrix; an "
                          f"integrator at rtol = {rtol:.0e} cannot resolve it (the exact period is {exact!r})",
                          RuntimeWarning, stacklevel=2)
        scene = scene.replace(rtol=rtol, atol=min(scene.atol, rtol * 1e-2))
    span = periods * exact * 1.02
    if regime == "libration":
        ev = find_events(scene, "turning", direction=-1, t_end=span, method=method)
    else:
        ev = find_events(scene, "theta_mod_2pi", level=scene.theta0, direction=0, t_end=span, method=method)
    if ev.t.size < 2:
        raise RuntimeError("fewer than two events: cannot measure a period")
    measured = float((ev.t[-1] - ev.t[0]) / (ev.t.size - 1))
    if abs(measured - exact) > 1e-6 * exact:
        warnings.warn(f"numerical_period: measured {measured!r} differs from the exact period {exact!r} by "
                      f"{abs(measured / exact - 1):.1e} (relative): the integration did not resolve the orbit",
                      RuntimeWarning, stacklevel=2)
    return measured


def _cycloid_event_function(scene, kind, level, t):
    """The event function on the cycloid's exact path at the times t, and the state there."""
    theta, v, s, sd = cycloid_motion(scene, t)
    if kind == "turning":
        return sd, theta, v          # s' = 4 R cos(theta) theta' has the sign of theta' between the cusps
    return s - 4 * scene.cycloid_radius * math.sin(level), theta, v   # theta = level <=> s = 4 R sin(level)


def _cycloid_events(scene, kind, level, direction, t_end, terminal, max_events) -> Events:
    """Events of the cycloidal guide as roots of its exact path (no integration)."""
    if kind == "theta_mod_2pi":
        level = math.remainder(level, 2 * math.pi)
    if kind != "turning" and not abs(level) <= math.pi / 2:
        # the bob stays between the cusps, |theta| <= pi/2: that level is never crossed
        empty = np.empty(0)
        return Events(empty, empty.copy(), empty.copy(), {"steps": 0, "accepted": 0, "rejected": 0,
                                                          "rhs_evaluations": 0, "stopped_by_event": False,
                                                          "path_evaluations": 0})
    w = math.sqrt(scene.eps / (4 * scene.cycloid_radius))
    shortest = 2 * math.pi / max(w, abs(scene.drive_frequency) if scene.drive_amplitude else 0.0)
    h = shortest / CYCLOID_SAMPLES_PER_PERIOD
    n_total = math.ceil(t_end / h)
    if n_total > CYCLOID_MAX_SAMPLES:
        raise ValueError(f"t_end: {t_end!r} spans {t_end / shortest:.3g} periods; the cycloid's event search "
                         f"samples at most {CYCLOID_MAX_SAMPLES // CYCLOID_SAMPLES_PER_PERIOD:.3g} periods")
    found_t, found_th, found_v = [], [], []
    evaluations = 0
    count = 0
    cancel = _interrupt.cancel_flag()
    for start in range(0, n_total, CYCLOID_BLOCK):
        if cancel[0]:
            raise KeyboardInterrupt
        idx = np.arange(start, min(start + CYCLOID_BLOCK, n_total) + 1, dtype=np.float64)
        tt = np.minimum(idx * h, t_end)
        g, _, _ = _cycloid_event_function(scene, kind, level, tt)
        evaluations += tt.size
        ga, gb = g[:-1], g[1:]
        # a root in (a, b]: a sign change, or g(b) = 0 after a non-zero g(a); never at t = 0
        hit = ((ga < 0) & (gb >= 0)) | ((ga > 0) & (gb <= 0))
        rising = ga < 0
        if direction:
            hit &= rising if direction > 0 else ~rising
        a, b = tt[:-1][hit], tt[1:][hit]
        if a.size:
            fa = ga[hit]
            # bisection to adjacent doubles: every bracket at once, one path evaluation per step
            for _ in range(200):
                mid = 0.5 * (a + b)
                open_ = (mid > a) & (mid < b)
                if not open_.any():
                    break
                fm, _, _ = _cycloid_event_function(scene, kind, level, mid)
                evaluations += mid.size
                left = open_ & ((fm == 0) | (np.sign(fm) != np.sign(fa)))
                right = open_ & ~left
                b = np.where(left, mid, b)
                a = np.where(right, mid, a)
                fa = np.where(right, fm, fa)
            _, th, vv = _cycloid_event_function(scene, kind, level, b)
            take = b[: max_events - count]
            found_t.append(take)
            found_th.append(th[: take.size])
            found_v.append(vv[: take.size])
            count += take.size
            if count >= max_events or terminal:
                break
    tev = np.concatenate(found_t) if found_t else np.empty(0)
    if terminal:
        tev = tev[:1]
    thev = np.concatenate(found_th)[: tev.size] if found_th else np.empty(0)
    vev = np.concatenate(found_v)[: tev.size] if found_v else np.empty(0)
    return Events(tev, thev, vev, {"steps": 0, "accepted": 0, "rejected": 0, "rhs_evaluations": 0,
                                   "stopped_by_event": bool(terminal and tev.size), "path_evaluations": evaluations})


def _cord_events(scene, kind, direction, t_end, terminal, max_events) -> Events:
    """The flexible cord's flips up to t_end, from the kernel's flip log."""
    if scene.cord != "flexible":
        raise ValueError(f"kind {kind!r}: departures and returns are the flexible cord's events; this scene's "
                         "cord is rigid (cord = 'flexible')")
    if kind not in CORD_EVENT_KINDS:
        raise NotImplementedError(f"find_events on the flexible cord locates its flips ({', '.join(CORD_EVENT_KINDS)});"
                                  f" {kind!r} crossings of its motion are not located (simulate samples them)")
    if direction != 0:
        raise ValueError("direction: a departure or a return has no sense of crossing; give 'both'")
    tr = simulate_cord(scene, np.array([0.0, t_end]))
    fl = tr.flips
    key = "leave" if kind == "departure" else "return"
    t, th, v = fl[f"t_{key}"], fl[f"theta_{key}"], fl[f"v_{key}"]
    keep = np.isfinite(t) & (t > 0) & (t <= t_end)
    n = 1 if terminal else max_events
    t, th, v = t[keep][:n], th[keep][:n], v[keep][:n]
    return Events(t.copy(), th.copy(), v.copy(), {"steps": 0, "accepted": 0, "rejected": 0, "rhs_evaluations": 0,
                                                 "stopped_by_event": bool(terminal and t.size),
                                                 "flips": int(tr.stats.get("flips", 0)),
                                                 "stop_reason": tr.stats.get("stop_reason", "")})

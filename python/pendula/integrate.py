"""Integrators, events and the numerical period.

Method names (a contract): 'rk4', 'verlet', 'yoshida4', 'yoshida6', 'yoshida8',
'gauss4', 'gauss6' (fixed step: they take ``dt``), 'dopri5', 'dop853',
'gsl-rk8pd', 'dprkn6' (adaptive: they take ``rtol`` and ``atol``; 'dprkn6', Dormand &
Prince's Runge-Kutta-Nystrom pair RKN6(4), takes undamped scenes only and has no dense
output, so no events), 'vern9' (Verner's 9(8) pair, any scene, no dense output: no
events), 'exact' and 'auto'.
The right-hand side holds only the effects the scene names.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from . import _interrupt, _kernel
from ._checks import as_float
from .scene import Scene
from .systems import run
from .systems.gravity import field_of
from .systems.rigid import orbit

__all__ = ["integrate_scene", "find_events", "numerical_period", "Events", "FIXED_STEP", "ADAPTIVE"]

CODES = {"rk4": 1, "verlet": 2, "yoshida4": 3, "yoshida6": 4, "yoshida8": 5, "gauss4": 6, "gauss6": 7,
         "dopri5": 8, "dop853": 9, "gsl-rk8pd": 10, "dprkn6": 11, "vern9": 12}
FIXED_STEP = ("rk4", "verlet", "yoshida4", "yoshida6", "yoshida8", "gauss4", "gauss6")
ADAPTIVE = ("dopri5", "dop853", "gsl-rk8pd", "dprkn6", "vern9")
_STATUS = {1: "the step dt must be positive", 2: "rtol must be > 0 and atol >= 0", 3: "unknown method",
           5: "step size underflow (the problem may be singular or the tolerance unreachable)",
           6: "the state became non-finite", 9: "events need a method with dense output (dopri5, dop853)",
           7: "the run needs more steps than the work limit (1e8 adaptive, 2e9 fixed-step): shorten the span, "
              "or give a larger dt or rtol",
           8: "interrupted",
           11: "gsl-rk8pd integrates forward only: give times >= 0",
           12: "the Runge-Kutta-Nystrom pair integrates theta'' = f(t, theta) only: no damping",
           20: "bad gravity field parameters (gravity_distance > 1, gravity_gradient < 0.5)"}
_EVENT_KINDS = {"turning": 1, "theta": 2, "theta_mod_2pi": 3}
#: the most events one call records (memory: 24 bytes each)
MAX_EVENTS = 10_000_000


def choose_method(scene: Scene) -> str:
    """What 'auto' picks: the exact solution whenever the scene allows it,
    otherwise DOP853.  The work-precision study (README) finds DOP853 and GSL's
    rk8pd within a few per cent of each other at equal final error, and both
    far cheaper than every other method below 1e-6; DOP853 also has dense
    output, runs backwards in time and locates events, which rk8pd here does not."""
    if scene.is_conservative_rigid:
        return "exact"
    return "dop853"


def _params(scene: Scene) -> np.ndarray:
    return np.array([scene.eps, scene.damping, scene.torque, scene.drive_amplitude,
                     scene.drive_frequency, scene.drive_phase], dtype=np.float64)


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
    cancel = _interrupt.cancel_flag()
    span = float(np.max(np.abs(t_sorted))) if t_sorted.size else 0.0
    gkind, gpar = field_of(scene)
    out = _interrupt.call(_kernel.integrate_v, CODES[method], _params(scene), gkind, gpar, scene.theta0, scene.v0,
                          t_sorted, scene.rtol, scene.atol, scene.dt, ev_kind, ev_level, ev_dir, int(terminal),
                          max_events, cancel, cancel=cancel, long=span * max(1.0, scene.eps ** 0.5) > 1e3)
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
    """Located events: times t, states theta and v, and the work done."""

    t: np.ndarray
    theta: np.ndarray
    v: np.ndarray
    stats: dict


def find_events(scene: Scene, kind: str = "turning", level: float = 0.0, direction: int = 0,
                t_end: float | None = None, terminal: bool = False, method: str = "dop853",
                max_events: int = 100_000) -> Events:
    """Locate events on the dense output of an adaptive integrator.

    Parameters
    ----------
    kind : {'turning', 'theta', 'theta_mod_2pi'}
        'turning': v = 0; 'theta': theta = level; 'theta_mod_2pi': theta = level + 2 pi k.
    direction : {-1, 0, +1}
        Only falling, both, or only rising crossings of the event function.
    terminal : bool
        Stop at the first event.

    Each accepted step is sampled at four interior points, so two crossings
    inside one step are both found; a crossing is refined by the Illinois
    method to a few ulps of t.  An event function that is exactly zero at the
    start (an event that starts at zero) is not reported there.
    """
    if kind not in _EVENT_KINDS:
        raise ValueError(f"kind must be one of {', '.join(_EVENT_KINDS)}, got {kind!r}")
    if direction not in (-1, 0, 1):
        raise ValueError("direction must be -1, 0 or +1")
    if method not in ("dopri5", "dop853"):
        raise ValueError("events need a method with dense output: 'dopri5' or 'dop853'")
    if isinstance(max_events, bool) or not isinstance(max_events, (int, np.integer)):
        raise TypeError(f"max_events must be a whole number, got {max_events!r}")
    if not 1 <= max_events <= MAX_EVENTS:
        raise ValueError(f"max_events must be between 1 and {MAX_EVENTS}, got {max_events}")
    if not isinstance(terminal, (bool, np.bool_)):
        raise TypeError(f"terminal must be True or False, got {terminal!r}")
    if not isinstance(level, (int, float, np.integer, np.floating)) or isinstance(level, bool):
        raise TypeError(f"level must be a real number, got {level!r}")
    t_end = scene.t_end if t_end is None else as_float(t_end, "t_end")
    t_end = float(np.reshape(t_end, -1)[0]) if np.size(t_end) == 1 else math.nan
    if not t_end > 0 or not math.isfinite(t_end):
        raise ValueError(f"t_end must be positive and finite (events are located forward in time), got {t_end!r}")
    _, _, stats, tev, thev, vev = _run(scene, method, np.array([t_end]), _EVENT_KINDS[kind], float(level),
                                       int(direction), terminal, int(max_events))
    return Events(tev.copy(), thev.copy(), vev.copy(), stats)


def numerical_period(scene: Scene, periods: int = 20, method: str = "dop853") -> float:
    """The period measured by event location (source 003, task 2).

    Libration: the mean spacing of successive maxima (v falling through 0);
    rotation: the mean time per turn (theta passing theta0 + 2 pi k).  The
    integration runs over ``periods`` estimated periods (at most 1e6).

    Next to the separatrix an integrator's energy error can carry the orbit
    across it (v0 = 2 - 1e-12 measured 49.2 at rtol 1e-10 against the exact
    60.8): the tolerance is tightened to 1% of the orbit's distance from the
    separatrix (down to rtol = 1e-14), and where even that cannot resolve the
    orbit, or the measured period disagrees with the exact one by more than
    1e-6, a RuntimeWarning says so.
    """
    if isinstance(periods, bool) or not isinstance(periods, (int, float, np.integer, np.floating)):
        raise TypeError(f"periods must be a number, got {periods!r}")
    if not 2 <= periods <= 1e6:
        raise ValueError(f"periods must be between 2 and 1e6, got {periods!r}")
    if not scene.is_conservative_rigid:
        raise ValueError("numerical_period measures the period of a conservative orbit")
    o = orbit(scene.theta0, scene.v0, scene.eps)
    if not math.isfinite(o.period):
        return math.inf
    dist = o.mc  # 1 - k^2 (libration) or 1 - 1/k^2 (rotation)
    rtol = min(scene.rtol, max(1e-14, 0.01 * dist))
    if rtol > 0.01 * dist:
        warnings.warn(f"numerical_period: the orbit lies within {dist:.1e} (in k^2) of the separatrix; an "
                      f"integrator at rtol = {rtol:.0e} cannot resolve it (the exact period is {o.period!r})",
                      RuntimeWarning, stacklevel=2)
    scene = scene.replace(rtol=rtol, atol=min(scene.atol, rtol * 1e-2))
    span = periods * o.period * 1.02
    if o.regime == "libration":
        ev = find_events(scene, "turning", direction=-1, t_end=span, method=method)
    else:
        ev = find_events(scene, "theta_mod_2pi", level=scene.theta0, direction=0, t_end=span, method=method)
    if ev.t.size < 2:
        raise RuntimeError("fewer than two events: cannot measure a period")
    measured = float((ev.t[-1] - ev.t[0]) / (ev.t.size - 1))
    if abs(measured - o.period) > 1e-6 * o.period:
        warnings.warn(f"numerical_period: measured {measured!r} differs from the exact period {o.period!r} by "
                      f"{abs(measured / o.period - 1):.1e} (relative): the integration did not resolve the orbit",
                      RuntimeWarning, stacklevel=2)
    return measured

"""The pendulum on a flexible cord (Garfinkel 1957).

A bob on a massless inextensible cord of length l that can go slack.  Units:
lengths in l (the pivot at the origin, x to the right, y up, the bob at
(sin theta, -cos theta) on the circle), gravity eps = g/l.

Phases
------
circle
    While the tension m l (v^2 + eps cos theta) is positive.  Without effects
    the motion is the exact elliptic solution (:func:`pendula.exact_motion`)
    and the departure point and time are closed forms of the energy
    xi = (v^2 - 2 eps cos theta) / (3 eps): cos theta1 = -xi, and the time to
    reach it is an incomplete elliptic integral F (no root search).  This
    conservative case is closed form (kernel/models/pendula_cord.f90,
    ``cord_run``), about 1 us per flip.  With damping, torque or drive the
    circle is integrated by the scene's adaptive method (dopri5/dop853) and the
    departure is located as an event of the tension (event kind 4 of the
    kernel integrators: kernel/dispatch/pendula_cord_hybrid.f90).  One kernel
    loop (``cord_loop``) runs both, the circle phase behind one interface;
    both run through the
    dispatcher (``cord_scene_run``), as in ``pendula-run``.  Fixed-step methods have
    no dense output: a scene naming one is refused (SceneError, a ValueError) naming the method.
flight
    A parabola in closed form.  |p(tau)|^2 - 1 is a quartic in the flight time
    tau whose low coefficients vanish at a tangential departure (r' = 0 and
    zero tension make tau^3 a factor), so the re-entry time is the root of the
    remaining linear factor: tau = -4 (u . g) / |g|^2 (Garfinkel, eq. 13.1),
    never the departure point itself.  After a springy re-entry (restitution
    e > 0) the flight starts with an inward radial velocity: then tau is the
    smallest positive root of a cubic, taken from its companion matrix and
    polished by bisection on a sign-change bracket.
    Damping, torque and drive are effects applied at the pivot (the damping
    beta v is pivot friction): a slack cord transmits none of them, so the
    flight is free fall under gravity alone.
jerk
    At re-entry the cord removes the radial velocity (times 1 + e): the angular
    momentum about the pivot is conserved, energy is lost.

Stopping: a run ends after ``max_flips`` flips or at a flight shorter than
``min_flight`` (in units of 1/sqrt(eps)); output times after the stop are NaN
(RuntimeWarning) and ``stats['stop_reason']`` says why.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _kernel
from .. import _checks
from .._checks import as_float
from .rigid import energy

__all__ = ["flip_map", "cord_state", "flip_sequence", "simulate_cord", "xi_of"]



# ------------------------------------------------------------ closed forms

#: the longest sequence x_k computed (each term is one bisection; x_k lies within 1e-6 of 1 long before)
MAX_SEQUENCE_TERMS = 100_000


def flip_map(xi: ArrayLike) -> NDArray[np.float64] | np.float64:
    """Garfinkel's flip map f (his eqs. 14-15), vectorised.

    The energy xi' after one flip (departure from the circle, free flight,
    inelastic jerk at re-entry) as a function of the energy xi before it.

    Parameters
    ----------
    xi : array_like
        Garfinkel's energy xi = (theta'^2 - 2 eps cos theta) / (3 eps).

    Returns
    -------
    ndarray or float
        f(x) = x - (64/3) [x (1 - x^2)]^3 for 0 <= x <= 1, and f(x) = x outside
        (no flight there).

    Raises
    ------
    TypeError
        For a string, complex or object argument.

    See Also
    --------
    flip_sequence : the sequence x_k of the map's preimages.
    cord_state : the state index k of an energy.
    simulate : the simulated flips (``Scene(cord='flexible')``), which the map is checked against.

    Examples
    --------
    >>> import pendula
    >>> float(pendula.flip_map(0.5))
    -0.625
    >>> float(pendula.flip_map(1.5))
    1.5
    """
    x = as_float(xi, "xi")
    out = _kernel.cord_flip_map_v(np.ascontiguousarray(x, dtype=np.float64).reshape(-1)).reshape(x.shape)
    return out if out.ndim else out[()]


def _finv_upper(y):
    """The inverse of f on its increasing branch above its minimum (x in [0.5458, 1]),
    by bisection on the bracket (f is monotone there): robust, about 1 ulp."""
    lo, hi = _XMIN, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        w = mid * (1.0 - mid) * (1.0 + mid)
        if mid - (64.0 / 3.0) * w * w * w < y:  # f(mid), the same expression as flip_map
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _argmin_f():
    # f'(x) = 1 - 64 w^2 (1 - 3 x^2) with w = x(1 - x^2); f' < 0 on (0.2, 0.55) region's right
    # end; bisection on f' in [1/3^0.5 - 0.1, 1/3^0.5) where the minimum lies
    def fp(x):
        w = x * (1 - x * x)
        return 1.0 - 64.0 * w * w * (1.0 - 3.0 * x * x)
    lo, hi = 0.5, 0.577  # fp(0.5) < 0 < fp(0.577)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        if fp(mid) < 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


_XMIN = _argmin_f()


def flip_sequence(n: int) -> np.ndarray:
    """The first n terms of Garfinkel's sequence x_k (his eqs. 16-17).

    x_0 = -2/3, x_1, x_2, x_3 the zeros of f (0, 0.2360, 0.7511), then
    x_{k+4} = f^{-1}(x_{k+2}) on the branch of f above its minimum, found by
    bisection (f is monotone there), so every term is good to about 1 ulp.

    Parameters
    ----------
    n : int
        How many terms (>= 0).

    Returns
    -------
    ndarray
        x_0 ... x_{n-1}, increasing towards 1.

    Raises
    ------
    ValueError
        If `n` is not a non-negative whole number.

    See Also
    --------
    cord_state : where an energy falls in the sequence.
    flip_map : the map.

    Examples
    --------
    >>> import pendula
    >>> [round(float(x), 3) for x in pendula.flip_sequence(5)]
    [-0.667, 0.0, 0.236, 0.751, 0.791]
    """
    # the terms approach 1 (x_200 is 1e-3 below it) and each costs a bisection:
    # at most MAX_SEQUENCE_TERMS terms (absurd sizes refused up front)
    n = _checks.count(n, "n", 0, MAX_SEQUENCE_TERMS)
    # the zeros of f in (0, 1): w^3 = 3 x / 64 with w = x (1 - x^2), i.e. (1 - x^2)^3 x^2 = 3/64;
    # g(x) = x^2 (1 - x^2)^3 rises on (0, 1/2) and falls on (1/2, 1): one root on each side.
    def g(x):
        return x * x * (1 - x * x) ** 3 - 3.0 / 64.0

    def bis(lo, hi):
        glo = g(lo)
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if mid <= lo or mid >= hi:
                break
            if (g(mid) < 0) == (glo < 0):
                lo, glo = mid, g(mid)
            else:
                hi = mid
        return 0.5 * (lo + hi)

    xs = [-2.0 / 3.0, 0.0, bis(0.0, 0.5), bis(0.5, 1.0)]
    while len(xs) < n:
        xs.append(_finv_upper(xs[len(xs) - 2]))
    return np.array(xs[:n])


def cord_state(xi: ArrayLike, nmax: int = 200) -> NDArray[np.float64] | np.float64:
    """Garfinkel's state index k of an energy xi (his eq. 18), vectorised.

    Parameters
    ----------
    xi : array_like
        Garfinkel's energy.
    nmax : int, optional
        Terms of the sequence x_k to compute, 1 to ``MAX_SEQUENCE_TERMS``
        (x_200 lies 1e-3 below 1).

    Returns
    -------
    ndarray or float
        k such that x_k <= xi < x_{k+1} for -2/3 <= xi < 1; ``math.inf`` for
        xi >= 1 (circulation).  xi beyond the last term gives k = nmax - 1
        with a RuntimeWarning; xi < -2/3 is not an energy: NaN with a
        RuntimeWarning.

    Raises
    ------
    TypeError
        For a string, complex or object `xi`.
    ValueError
        If `nmax` is not a whole number from 1 to ``MAX_SEQUENCE_TERMS``.

    See Also
    --------
    flip_sequence : the sequence x_k.
    flip_map : the map that moves an energy down the sequence.

    Examples
    --------
    >>> import pendula
    >>> float(pendula.cord_state(0.777))      # state 3: one flip to state 1, then flips without end
    3.0
    """
    if isinstance(nmax, bool) or not isinstance(nmax, (int, np.integer)) or not 1 <= nmax <= MAX_SEQUENCE_TERMS:
        raise ValueError(f"cord_state: nmax must be a whole number from 1 to {MAX_SEQUENCE_TERMS} (the terms "
                         f"of the sequence x_k computed), got {nmax!r}")
    x = as_float(xi, "xi")
    seq = flip_sequence(nmax)
    k = np.searchsorted(seq, x, side="right").astype(float) - 1.0
    k = np.where(x >= 1.0, math.inf, k)
    bad = (x < seq[0] - 1e-15) | np.isnan(x)
    if np.any(bad):
        warnings.warn("cord_state: xi below -2/3 is not an energy: NaN", RuntimeWarning, stacklevel=2)
        k = np.where(bad, np.nan, k)
    top = (x >= seq[-1]) & (x < 1.0)
    if np.any(top):
        warnings.warn(f"cord_state: xi above x_{nmax - 1}: raise nmax", RuntimeWarning, stacklevel=2)
    k = np.where((x >= seq[0] - 1e-15) & (x < seq[0]), 0.0, k)
    return k if k.ndim else k[()]


def xi_of(theta, v, eps):
    """Garfinkel's normalised energy xi = (v^2 - 2 eps cos theta) / (3 eps)."""
    return (np.asarray(v) ** 2 - 2.0 * eps * np.cos(theta)) / (3.0 * eps)


# ------------------------------------------------------------ the engine

_LOG = ("t_leave", "theta_leave", "t_return", "theta_return", "xi_before", "xi_after", "v_leave", "v_return")
_STOPS = {0: "t_end", 1: "max_flips", 2: "min_flight"}


def simulate_cord(scene, t):
    """A Trajectory of a flexible-cord scene at the times t (>= 0, any order).

    Both cases run whole in the kernel, through the dispatcher that
    ``pendula-run`` uses (``cord_scene_run`` in
    kernel/dispatch/pendula_simulate.f90): without effects the closed form
    (kernel/models/pendula_cord.f90), with damping, torque or drive the hybrid
    loop (kernel/dispatch/pendula_cord_hybrid.f90: the circle integrated by
    dopri5 or dop853 up to the tension event, the flight and the jerk in
    closed form).

    The Trajectory gains x, y, r (the bob's position in units of l; r < 1 in
    flight) and ``flips``: a dict of arrays t_leave, theta_leave, t_return,
    theta_return, xi_before, xi_after, v_leave, v_return, one entry per flip in
    time order (xi_before at departure, xi_after after the jerk, v_return the
    angular velocity after the jerk).  ``stats`` holds
    'flips', 'stop_reason' ('t_end', 'max_flips' or 'min_flight') and, when
    integrated, the integrator's work ('steps', 'rhs_evaluations').
    """
    from .. import _interrupt
    from ..scene import SceneError
    from ..trajectory import Trajectory
    from . import METHOD_NAMES, _long_run

    t = as_float(t, "t")
    flat = np.ascontiguousarray(t, dtype=np.float64).reshape(-1)
    if not np.all(np.isfinite(flat)):
        raise ValueError("t must be finite")
    if flat.size and flat.min() < 0:
        raise ValueError("t: a flexible cord runs forward only (the jerk is irreversible): give times >= 0")
    # (which methods can run a flexible cord is a rule of the scene, checked when it was made)
    integrated = any(e for e in scene.effects if e != "cord") or scene.method not in ("auto", "exact")

    order = np.argsort(flat, kind="stable")
    ts = np.ascontiguousarray(flat[order])
    inv = np.empty(ts.size, dtype=np.intp)
    inv[order] = np.arange(ts.size)

    def back(a):
        return a[inv].reshape(t.shape)

    fields = scene._kernel_fields
    maxf = max(1, min(scene.max_flips, 65536))
    while True:
        cancel = _interrupt.cancel_flag()
        th, v, x, y, r, fl, nf, stop, stats, code, status, msg = _interrupt.call(
            _kernel.cord_scene_v, *fields, maxf, ts, cancel, cancel=cancel,
            long=_long_run(scene, ts))   # the closed-form loop is cancellable too
        if status or nf <= maxf:
            break
        maxf = int(nf)  # the flip log had no room for every flip: once more with room
    msg = (msg.decode(errors="replace") if isinstance(msg, bytes) else str(msg)).strip()
    if status == 100:
        raise SceneError(f"the kernel refused the scene: {msg}")
    if status:
        raise ValueError(msg)
    nan_after = int(np.count_nonzero(np.isnan(th)))
    if nan_after:
        warnings.warn(f"flexible cord: the run stopped ({_STOPS[int(stop)]}) at flip {nf}; "
                      f"{nan_after} later output time(s) are NaN", RuntimeWarning, stacklevel=3)
    theta, vv = back(th), back(v)
    flips = {k: fl[i, :nf].copy() for i, k in enumerate(_LOG)}
    st = {"flips": int(nf), "stop_reason": _STOPS[int(stop)]}
    if code != 0:
        st.update(steps=int(stats[0]), rhs_evaluations=int(stats[3]))
    return Trajectory(t, theta, vv, energy(theta, vv, scene.eps), METHOD_NAMES[int(code)], scene, st,
                      x=back(x), y=back(y), r=back(r), flips=flips)

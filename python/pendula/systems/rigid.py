"""The rigid pendulum: the exact solution of theta'' + eps sin(theta) = 0.

The conservative rigid pendulum is answered exactly by Jacobi elliptic
functions in every regime (see kernel/models/pendula_exact.f90 for the
formulas).  This is the first model of pendula; the dispatcher
(:func:`pendula.simulate`) sends a scene here whenever it names no effect.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _kernel
from .._checks import as_float

__all__ = ["Orbit", "orbit", "exact_motion", "energy"]

_CHUNK = 1 << 20
_REGIMES = {0: "libration", 1: "separatrix", 2: "rotation"}
_STATUS = {1: "eps must be positive and at most 1e300", 2: "theta0 must be finite", 3: "v0 must be finite",
           4: "theta0 beyond 2**52 (4.5e15) cannot be reduced modulo 2 pi in double precision",
           5: "v0 too large for this eps: |v0| / (2 sqrt(eps)) must stay below 1e154"}


@dataclass(frozen=True)
class Orbit:
    """Facts about one conservative orbit, from the exact solution.

    Attributes
    ----------
    regime : str
        'libration' (k < 1), 'separatrix' (k = 1) or 'rotation' (k > 1).
        (At rest upside down is not a state a double can give: np.pi lies
        1.2e-16 below pi, so it is a libration that slowly falls off the top.)
    k : float
        Modulus sqrt(E / (2 eps)).
    m, mc : float
        Parameter of the Jacobi functions used (k^2 in libration, 1/k^2 in
        rotation) and its complement, computed without cancellation.
    period : float
        4K(m)/sqrt(eps) in libration, the time of one full turn in rotation,
        inf on the separatrix.
    omega : float
        2 pi / period (0 on the separatrix).
    theta_max : float
        Amplitude 2 arcsin(k) of a libration; pi on the separatrix; inf for a
        rotation.

    See Also
    --------
    orbit : makes it.
    gravity_orbit : the orbit in a non-uniform field (``GravityOrbit``, the
        shared facts under the same names).

    Examples
    --------
    >>> import pendula
    >>> o = pendula.orbit(0.0, 3.0)
    >>> o.regime, round(o.period, 12), o.theta_max
    ('rotation', 2.412889993982, inf)
    """

    regime: str
    k: float
    m: float
    mc: float
    period: float
    omega: float
    theta_max: float


def _check_status(status: int) -> None:
    if status:
        raise ValueError(_STATUS.get(status, f"pendula kernel status {status}"))


def _scalar(x, name: str) -> float:
    a = as_float(x, name)
    if a.ndim != 0 and a.size != 1:
        raise ValueError(f"{name} must be a single number, got shape {a.shape}")
    return float(a.reshape(()))


def orbit(theta0: float, v0: float, eps: float = 1.0) -> Orbit:
    """Regime, modulus, period, frequency and amplitude of the orbit through (theta0, v0).

    Parameters
    ----------
    theta0 : float
        Angle at t = 0 (rad, from the bottom; any value).
    v0 : float
        Angular velocity at t = 0 (any sign).
    eps : float, optional
        g / l > 0 (default 1).

    Returns
    -------
    Orbit
        The orbit's facts, from the exact solution (periods within a few eps).

    Raises
    ------
    TypeError
        For a string, complex or array argument.
    ValueError
        For eps <= 0 or beyond 1e300, abs(theta0) beyond 2**52, or abs(v0)
        beyond 1e154 sqrt(eps).

    See Also
    --------
    exact_motion : the motion itself.
    period : the period of a scene.
    gravity_orbit : the same facts in a non-uniform gravity field.

    Examples
    --------
    >>> import pendula
    >>> o = pendula.orbit(0.0, 1.0)          # libration, k = 1/2
    >>> o.regime, o.k, round(o.period, 12)
    ('libration', 0.5, 6.74300141925)
    >>> pendula.orbit(0.0, 2 - 1e-12).period   # 1e-12 below the separatrix
    60.807041883089525
    """
    info, status = _kernel.exact_info_v(_scalar(theta0, "theta0"), _scalar(v0, "v0"), _scalar(eps, "eps"))
    _check_status(status)
    regime, k, m, mc, per, tmax = _REGIMES[int(info[0])], *info[1:6]
    omega = 0.0 if math.isinf(per) else float(2 * math.pi / per)
    return Orbit(regime, float(k), float(m), float(mc), float(per), omega, float(tmax))


def exact_motion(theta0: float, v0: float, eps: float, t: ArrayLike
                 ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """theta(t) and v(t) of the conservative pendulum from the exact solution.

    Parameters
    ----------
    theta0, v0 : float
        State at t = 0 (any angle, any sign of v0).
    eps : float
        g / l > 0.
    t : array_like
        Times, in any order, before or after 0.

    Returns
    -------
    theta, v : ndarray
        Arrays of the shape of `t`.  The angle is continuous: it grows without
        bound in a rotation.  NaN (with a RuntimeWarning) at infinite times
        or beyond 2**48 half periods.

    Raises
    ------
    TypeError
        For a string, complex or object argument.
    ValueError
        For eps <= 0 or an out-of-range initial state (as :func:`orbit`).

    See Also
    --------
    orbit : the facts of the orbit (regime, period, amplitude).
    simulate : the same motion from a scene, with effects.
    ellipj : the Jacobi functions it is made of.

    Examples
    --------
    >>> import pendula
    >>> theta, v = pendula.exact_motion(0.0, 2.0, 1.0, [0.0, 10.0, 40.0])   # on the separatrix
    >>> [round(float(x), 6) for x in theta]                                 # -> pi, never over
    [0.0, 3.141411, 3.141593]
    """
    t = as_float(t, "t")
    tf = np.ascontiguousarray(t, dtype=np.float64).reshape(-1)
    args = (_scalar(theta0, "theta0"), _scalar(v0, "v0"), _scalar(eps, "eps"))
    if tf.size <= _CHUNK:
        theta, v, status = _kernel.exact_motion_v(*args, tf)
        _check_status(status)
    else:  # chunks with the GIL released, so that Ctrl-C is seen between them
        theta, v = np.empty_like(tf), np.empty_like(tf)
        for i in range(0, tf.size, _CHUNK):
            theta[i:i + _CHUNK], v[i:i + _CHUNK], status = _kernel.exact_motion_v(*args, tf[i:i + _CHUNK])
            _check_status(status)
    bad = ~np.isfinite(theta) & ~np.isnan(tf)
    if np.any(bad):
        warnings.warn(f"exact_motion: {int(bad.sum())} time(s) infinite or beyond 2**48 half periods gave NaN",
                      RuntimeWarning, stacklevel=2)
    return theta.reshape(t.shape), v.reshape(t.shape)


def energy(theta: ArrayLike, v: ArrayLike, eps: ArrayLike = 1.0) -> NDArray[np.float64] | np.float64:
    """The energy E = v^2/2 + eps (1 - cos theta) of the rigid pendulum.

    Parameters
    ----------
    theta : array_like
        Angle (rad).
    v : array_like
        Angular velocity.
    eps : float or array_like, optional
        g / l (default 1).

    Returns
    -------
    ndarray
        E, broadcast over the arguments, per unit m l^2; 2 eps on the
        separatrix.

    Raises
    ------
    TypeError
        For a string, complex or object argument.

    See Also
    --------
    exact_motion : a path along which E is constant.
    Trajectory : carries the energy along any computed path.

    Notes
    -----
    Written as v^2/2 + 2 eps sin^2(theta/2), so no digits cancel near the
    bottom.

    Examples
    --------
    >>> import pendula
    >>> float(pendula.energy(0.0, 2.0)), float(pendula.energy(3.141592653589793, 0.0))
    (2.0, 2.0)
    """
    theta = as_float(theta, "theta")
    v = as_float(v, "v")
    eps = as_float(eps, "eps")
    s = np.sin(0.5 * theta)
    # (eps s) s: where sin^2 alone would underflow (theta ~ 1e-160) eps s^2 may not; below 2^-450
    # eps theta^2 / 2 to 2^-900, the half of a subnormal theta never formed
    pot = np.where(np.abs(theta) < 2.0 ** -450, (0.5 * eps * theta) * theta, 2.0 * (eps * s) * s)
    return 0.5 * v * v + pot

"""The motion of the pendulum: the exact solution, and simulate() for scenes.

The conservative pendulum theta'' + eps sin(theta) = 0 is answered exactly by
Jacobi elliptic functions (see pendula_exact.f90 for the formulas); scenes
that name effects (damping, torque, drive, ...) go to the integrators.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from . import _kernel
from ._checks import as_float
from .scene import Scene

__all__ = ["Orbit", "Trajectory", "orbit", "exact_motion", "energy", "simulate", "period"]

_REGIMES = {0: "libration", 1: "separatrix", 2: "rotation"}
_STATUS = {1: "eps must be positive and finite", 2: "theta0 must be finite", 3: "v0 must be finite"}


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

    Examples
    --------
    >>> import pendula
    >>> o = pendula.orbit(0.0, 1.0)          # libration, k = 1/2
    >>> round(o.period, 12)
    6.74300141925
    """
    info, status = _kernel.exact_info_v(_scalar(theta0, "theta0"), _scalar(v0, "v0"), _scalar(eps, "eps"))
    _check_status(status)
    regime, k, m, mc, per, tmax = _REGIMES[int(info[0])], *info[1:6]
    omega = 0.0 if math.isinf(per) else float(2 * math.pi / per)
    return Orbit(regime, float(k), float(m), float(mc), float(per), omega, float(tmax))


def exact_motion(theta0: float, v0: float, eps: float, t) -> tuple[np.ndarray, np.ndarray]:
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
        The angle is continuous: it grows without bound in a rotation.
    """
    t = as_float(t, "t")
    tf = np.ascontiguousarray(t, dtype=np.float64).reshape(-1)
    theta, v, status = _kernel.exact_motion_v(_scalar(theta0, "theta0"), _scalar(v0, "v0"),
                                              _scalar(eps, "eps"), tf)
    _check_status(status)
    bad = ~np.isfinite(theta) & ~np.isnan(tf)
    if np.any(bad):
        warnings.warn(f"exact_motion: {int(bad.sum())} time(s) infinite or beyond 2**48 half periods gave NaN",
                      RuntimeWarning, stacklevel=2)
    return theta.reshape(t.shape), v.reshape(t.shape)


def energy(theta, v, eps: float = 1.0) -> np.ndarray:
    """E = v^2/2 + eps (1 - cos theta), written as v^2/2 + 2 eps sin^2(theta/2) (no cancellation)."""
    theta = as_float(theta, "theta")
    v = as_float(v, "v")
    return 0.5 * v * v + 2.0 * eps * np.sin(0.5 * theta) ** 2


@dataclass
class Trajectory:
    """A computed motion.

    Attributes
    ----------
    t, theta, v, energy : ndarray
        Times, angle (continuous), angular velocity, and the energy
        v^2/2 + eps (1 - cos theta) evaluated along the path (for damped or
        driven scenes it is not conserved, and shows it).
    method : str
        'exact' or the integrator's name.
    scene : Scene
    stats : dict
        Work done: steps, right-hand-side evaluations, rejected steps (empty
        for the exact solution).
    """

    t: np.ndarray
    theta: np.ndarray
    v: np.ndarray
    energy: np.ndarray
    method: str
    scene: Scene
    stats: dict = field(default_factory=dict)

    def as_array(self) -> np.ndarray:
        """Columns t, theta, v, energy."""
        return np.column_stack([self.t, self.theta, self.v, self.energy])


def simulate(scene: Scene, t=None, method: str | None = None) -> Trajectory:
    """Run one scene at the times ``t`` (default: the scene's own output times).

    The initial state is at t = 0; the times need not start at 0 or be
    increasing.  With method 'auto' (the default) a conservative rigid scene is
    answered by the exact solution, never by an integrator.  A scene with a
    sweep is run at its own (un-swept) values; use ``scene.members()`` for the
    family.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"simulate expects a pendula.Scene, got {type(scene).__name__}")
    t = scene.times() if t is None else as_float(t, "t")
    method = method or scene.method
    scene.require_implemented()
    if method in ("auto", "exact") and scene.is_conservative_rigid:
        theta, v = exact_motion(scene.theta0, scene.v0, scene.eps, t)
        return Trajectory(t, theta, v, energy(theta, v, scene.eps), "exact", scene)
    if method == "exact":
        raise ValueError(f"method 'exact' answers only the conservative rigid pendulum; "
                         f"the scene names {', '.join(scene.effects)}")
    from .integrate import integrate_scene

    return integrate_scene(scene, t, method)


def period(scene: Scene) -> float:
    """The period of the scene's conservative orbit (exact): see :class:`Orbit`.

    A scene with effects has no period in this sense: ValueError.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"period expects a pendula.Scene, got {type(scene).__name__}")
    if not scene.is_conservative_rigid:
        raise ValueError(f"period(scene) is the exact period of a conservative orbit; the scene names "
                         f"{', '.join(scene.effects)} (see pendula.numerical_period for event-based periods)")
    return orbit(scene.theta0, scene.v0, scene.eps).period

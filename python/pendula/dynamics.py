"""Equilibria, their linear stability, and periodic orbits of the driven pendulum.

The mathematics runs in the kernel (``kernel/models/pendula_equilibria.f90``
for the rest points; GSL's rk8pd and its hybrid Newton solver in
``kernel/glue/pendula_gsl.c`` for the periodic orbits); this module turns a
:class:`~pendula.Scene` into the kernel's arguments and the answers into
records.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import _kernel
from .scene import Scene
from .systems.gravity import field_of

__all__ = ["Equilibrium", "equilibria", "PeriodicOrbit", "periodic_orbit", "EQUILIBRIUM_KINDS"]

#: The kinds of rest point, indexed by the kernel's codes (1 ... 7).
EQUILIBRIUM_KINDS = ("stable node", "stable spiral", "centre", "saddle", "unstable node", "unstable spiral",
                     "saddle-node")

_MODEL_RIGID, _MODEL_CORD, _MODEL_CYCLOID = 1, 2, 3
#: The most equilibria one call returns (a window wider than this many turns is refused).
MAX_EQUILIBRIA = 4096


@dataclass(frozen=True)
class Equilibrium:
    """A rest point of a scene's model and its linear stability.

    Attributes
    ----------
    theta : float
        The angle of the rest point (rad).
    eigenvalues : numpy.ndarray
        The two eigenvalues of the linearisation (complex), largest real part first.
    kind : str
        One of ``pendula.dynamics.EQUILIBRIUM_KINDS``: ``'stable node'``, ``'stable spiral'``, ``'centre'``,
        ``'saddle'``, ``'unstable node'``, ``'unstable spiral'``, ``'saddle-node'``.

    See Also
    --------
    equilibria : makes them.

    Examples
    --------
    >>> import pendula
    >>> bottom, top = pendula.equilibria(pendula.Scene(damping=0.2))
    >>> bottom.kind, bottom.stable, top.kind
    ('stable spiral', True, 'saddle')
    """

    theta: float
    eigenvalues: np.ndarray
    kind: str

    @property
    def stable(self) -> bool:
        """True when every eigenvalue has a negative real part (asymptotically stable)."""
        return bool(np.all(self.eigenvalues.real < 0))


def _model_code(scene: Scene) -> int:
    if scene.guide == "cycloid":
        return _MODEL_CYCLOID
    if scene.cord == "flexible":
        return _MODEL_CORD
    return _MODEL_RIGID


def equilibria(scene: Scene, window: tuple[float, float] = (-math.pi, math.pi)) -> list[Equilibrium]:
    """Every equilibrium of the scene's model in a window of angles, with its stability.

    The rigid pendulum with torque tau in the uniform field rests at
    ``theta = asin(tau/eps) + 2 pi n`` (a centre, or a stable spiral or node
    with damping) and ``pi - asin(tau/eps) + 2 pi n`` (a saddle), and nowhere
    when ``|tau| > eps``; at ``|tau| = eps`` the two merge in a saddle-node.
    The eigenvalues solve ``lambda**2 + beta lambda + c = 0`` with ``c`` the
    restoring slope ``-a'(theta*)`` (Suzuki & Suzuki, section 7.1).  The
    non-uniform gravity fields rest at the bottom and the top (with a torque,
    at the roots of the field's force plus the torque); the cycloidal guide has
    one rest point, ``s = tau / w2`` along its path, when it lies between the
    cusps (its angle is not periodic: the window does not apply); a flexible
    cord rests only where it is taut (``cos theta* > 0``).

    Parameters
    ----------
    scene : Scene
        The scene; its model (``guide``, ``cord``, ``gravity``), ``eps``,
        ``damping`` and ``torque`` are used.  A periodically driven scene
        (``drive_amplitude != 0``) has no rest points: see :func:`periodic_orbit`.
    window : (float, float), optional
        The angles ``lo < theta <= hi`` to list (default one turn, ``(-pi, pi]``).

    Returns
    -------
    list of Equilibrium
        Sorted by angle; empty when the model has none.

    Raises
    ------
    ValueError
        If the scene is driven, or the window is not finite and increasing, or
        holds more than ``MAX_EQUILIBRIA`` rest points.

    See Also
    --------
    periodic_orbit : the periodic orbits of a driven scene.

    Examples
    --------
    >>> import pendula
    >>> for e in pendula.equilibria(pendula.Scene(damping=0.1, torque=0.5)):
    ...     print(f"{e.theta:.6f} {e.kind}")
    0.523599 stable spiral
    2.617994 saddle
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a pendula.Scene, got {type(scene).__name__}")
    if scene.drive_amplitude != 0.0:
        raise ValueError("drive_amplitude: a periodically driven scene has no equilibria "
                         "(it is not autonomous); its periodic orbits come from pendula.periodic_orbit")
    try:
        lo, hi = (float(w) for w in window)
    except (TypeError, ValueError):
        raise TypeError(f"window must be two numbers (lo, hi), got {window!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise ValueError(f"window must be finite with lo < hi, got {window!r}")
    if (hi - lo) / (2 * math.pi) * 2 + 2 > MAX_EQUILIBRIA:
        raise ValueError(f"window: at most {MAX_EQUILIBRIA} equilibria per call; "
                         f"a window of {(hi - lo) / (2 * math.pi):.3g} turns holds more")
    kind, par = field_of(scene)
    theta, eig, ekind, count, status = _kernel.equilibria_v(
        MAX_EQUILIBRIA, _model_code(scene), kind, par, scene.eps, scene.cycloid_radius, scene.damping,
        scene.torque, lo, hi)
    if status == 1:
        raise ValueError("the scene's parameters have no equilibria to compute (eps, the field's parameter "
                         "and the torque must be finite)")
    if status == 2:
        raise ValueError(f"window: more than {MAX_EQUILIBRIA} equilibria")
    out = []
    for i in range(count):
        lam = np.array([complex(eig[0, i], eig[1, i]), complex(eig[2, i], eig[3, i])])
        out.append(Equilibrium(float(theta[i]), lam, EQUILIBRIUM_KINDS[ekind[i] - 1]))
    return out


@dataclass(frozen=True)
class PeriodicOrbit:
    """A periodic orbit of a driven scene's stroboscopic map.

    Attributes
    ----------
    theta, v : float
        The orbit's state on the section ``t = 0 (mod period)`` (the drive's phase ``drive_phase``),
        theta in ``[-pi, pi]``.  A period-k call may find an orbit of a smaller period that divides k.
    period : float
        Its period, ``k`` drive periods ``2 pi k / drive_frequency``.
    multipliers : numpy.ndarray
        The Floquet multipliers (the eigenvalues of the monodromy matrix), largest modulus first.
    exponents : numpy.ndarray
        ``log|mu| / period``, the Lyapunov exponents of the orbit; they add up to ``-damping``.
    monodromy : numpy.ndarray
        The 2 x 2 monodromy matrix ``d(theta, v)(period) / d(theta, v)(0)``.
    winding : int
        Turns the orbit advances per period (0 for an oscillation).
    residual : float
        ``max |P(x) - x - (2 pi winding, 0)|`` at the returned state.

    See Also
    --------
    periodic_orbit : makes it.

    Examples
    --------
    >>> import pendula
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=0.9, drive_frequency=2/3)
    >>> po = pendula.periodic_orbit(sc, guess=(0.5, 0.5))
    >>> round(float(po.exponents.sum()), 9)          # Liouville: -damping
    -0.5
    """

    theta: float
    v: float
    period: float
    multipliers: np.ndarray
    exponents: np.ndarray
    monodromy: np.ndarray
    winding: int
    residual: float

    @property
    def stable(self) -> bool:
        """True when every multiplier lies inside the unit circle."""
        return bool(np.all(np.abs(self.multipliers) < 1))


_PO_STATUS = {1: "Newton's iteration did not converge (try another guess, or a looser tol)",
              2: "the flow over one period failed (the state left the finite numbers, or rk8pd failed)",
              3: "Newton's iteration stalled without reaching the tolerance (try another guess)"}


def periodic_orbit(scene: Scene, guess: tuple[float, float] | None = None, k: int = 1, winding: int = 0,
                   tol: float = 1e-11, rtol: float = 1e-12, atol: float = 1e-12, maxit: int = 100) -> PeriodicOrbit:
    """A period-k orbit of a driven scene's stroboscopic map, by Newton on the monodromy.

    The map ``P`` takes the state at ``t = 0`` to the state ``k`` drive periods
    later; a periodic orbit is a root of ``P(x) - x - (2 pi winding, 0)``.  The
    flow and its monodromy matrix (the variational equations) come from GSL's
    rk8pd, the root from GSL's hybrid Newton method with that exact Jacobian.
    The Floquet multipliers are the eigenvalues of the monodromy; their
    product is ``exp(-damping * period)`` (Liouville), and ``log|mu| / period``
    are the orbit's Lyapunov exponents, the ones a ``lyapunov`` sweep measures
    on an attracting orbit.

    Parameters
    ----------
    scene : Scene
        A driven rigid pendulum in the uniform field (``drive_amplitude`` and
        ``drive_frequency`` non-zero); ``eps``, ``damping``, ``torque`` and
        ``drive_phase`` are used.
    guess : (float, float), optional
        The starting state ``(theta, v)``; default ``(scene.theta0, scene.v0)``.
    k : int, optional
        The period in drive periods (default 1).
    winding : int, optional
        Turns per period of a running orbit (default 0, an oscillation).
    tol : float, optional
        Newton's stopping tolerance on the residual and the step (default 1e-11).
    rtol, atol : float, optional
        The integrator's tolerances (default 1e-12).
    maxit : int, optional
        The most Newton iterations (default 100).

    Returns
    -------
    PeriodicOrbit
        The state on the section, the period, the multipliers and exponents.

    Raises
    ------
    ValueError
        If the scene is not driven, an argument is out of range, or Newton's
        iteration fails (the message says how).
    NotImplementedError
        For the flexible cord, the cycloidal guide and the non-uniform fields.

    See Also
    --------
    equilibria : the rest points of an autonomous scene.

    Examples
    --------
    >>> import pendula
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=0.9, drive_frequency=2/3)
    >>> po = pendula.periodic_orbit(sc, guess=(0.5, 0.5))
    >>> print(f"{po.theta:.6f} {po.v:.6f} {po.stable}")
    -0.560228 1.933586 True
    >>> print(f"{po.exponents[0]:.6f}")
    -0.250000
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a pendula.Scene, got {type(scene).__name__}")
    if scene.guide != "none" or scene.cord != "rigid" or scene.gravity != "uniform":
        model = "cycloid" if scene.guide != "none" else ("flexible cord" if scene.cord != "rigid" else
                                                           f"gravity = {scene.gravity!r}")
        raise NotImplementedError(f"periodic_orbit: the {model} model is not supported yet "
                                  "(only the rigid pendulum in the uniform field)")
    if scene.drive_amplitude == 0.0 or scene.drive_frequency == 0.0:
        raise ValueError("drive_amplitude, drive_frequency: periodic_orbit needs a periodically driven scene; "
                         "an undriven scene's rest points come from pendula.equilibria")
    for name, val in (("k", k), ("winding", winding), ("maxit", maxit)):
        if isinstance(val, bool) or not isinstance(val, (int, np.integer)):
            raise TypeError(f"{name} must be a whole number, got {val!r}")
    if not 1 <= k <= 10**4:
        raise ValueError(f"k must be between 1 and 10000 drive periods, got {k}")
    if not 1 <= maxit <= 10**4:
        raise ValueError(f"maxit must be between 1 and 10000, got {maxit}")
    if abs(winding) > 10**9:
        raise ValueError(f"winding must be at most 1e9 turns in magnitude, got {winding}")
    for name, val in (("tol", tol), ("rtol", rtol), ("atol", atol)):
        if not (isinstance(val, (int, float, np.floating)) and math.isfinite(val) and val > 0):
            raise ValueError(f"{name} must be a positive finite number, got {val!r}")
    if guess is None:
        guess = (scene.theta0, scene.v0)
    try:
        x0 = np.array([float(guess[0]), float(guess[1])], dtype=np.float64)
        if len(guess) != 2:
            raise ValueError
    except (TypeError, ValueError, IndexError):
        raise ValueError(f"guess must be a state (theta, v), got {guess!r}") from None
    if not np.all(np.isfinite(x0)):
        raise ValueError(f"guess must be finite, got {guess!r}")
    period = k * 2 * math.pi / abs(scene.drive_frequency)
    params = np.array([scene.eps, scene.damping, scene.torque, scene.drive_amplitude, scene.drive_frequency,
                       scene.drive_phase], dtype=np.float64)
    x, mono, info, status = _kernel.periodic_orbit_v(params, period, float(winding), rtol, atol, tol, maxit, x0)
    if status:
        raise ValueError(f"periodic_orbit: {_PO_STATUS[status]}; residual {info[2]:.3g} after {int(info[0])} "
                         "iterations")
    # the state on the section, theta taken to (-pi, pi] (the force is 2 pi periodic)
    theta = float(x[0]) - 2 * math.pi * round(float(x[0]) / (2 * math.pi))
    m = mono.reshape(2, 2).copy()
    mu = np.linalg.eigvals(m).astype(complex)
    mu = mu[np.argsort(-np.abs(mu), kind="stable")]
    return PeriodicOrbit(theta, float(x[1]), period, mu, np.log(np.abs(mu)) / period, m, int(winding),
                         float(info[2]))

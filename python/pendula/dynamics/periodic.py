"""Periodic orbits of a driven scene: Newton on the stroboscopic map and its monodromy.

The flow and its monodromy matrix (the variational equations) run in the
kernel (GSL's rk8pd and its hybrid Newton solver, ``kernel/glue/pendula_gsl.c``);
this module turns a :class:`~pendula.Scene` into the kernel's arguments and the
answer into a record.  It is the one Newton-on-the-stroboscopic-map core of
the dynamics: continuation and the attractor finder build on it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .. import _checks, _kernel
from ..scene import Scene

__all__ = ["PeriodicOrbit", "periodic_orbit"]


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
    kind : str
        'oscillation' or 'rotation' (from the winding).
    stable : bool
        True when every multiplier lies inside the unit circle.
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
    >>> po                       # a complex pair: |mu| = exp(-damping * period / 2)
    PeriodicOrbit(theta=-0.560228, v=1.93359, period=9.42478, kind='oscillation', stable=True, |multipliers|=[0.09478, 0.09478])
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

    @property
    def kind(self) -> str:
        """'oscillation' (winding 0) or 'rotation' (the orbit advances ``winding`` turns per period)."""
        return "oscillation" if self.winding == 0 else "rotation"

    def __repr__(self) -> str:
        mods = ", ".join(f"{abs(m):.4g}" for m in self.multipliers)
        wind = f", winding={self.winding}" if self.winding else ""
        return (f"PeriodicOrbit(theta={self.theta:.6g}, v={self.v:.6g}, period={self.period:.6g}, "
                f"kind={self.kind!r}{wind}, stable={self.stable}, |multipliers|=[{mods}])")


_PO_STATUS = {1: "Newton's iteration did not converge (try another guess, or a looser tol)",
              2: "the flow over one period failed (the state left the finite numbers, or rk8pd failed)",
              3: "Newton's iteration stalled without reaching the tolerance (try another guess)"}


def periodic_orbit(scene: Scene, guess: tuple[float, float] | None = None, k: int = 1, winding: int = 0,
                   tol: float = 1e-11, rtol: float = 1e-12, atol: float = 1e-12, maxit: int = 100,
                   force: object = None, force_params: ArrayLike | None = None) -> PeriodicOrbit:
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
    force, force_params : optional
        A user's force added to the force law, as in :func:`pendula.simulate`
        (its derivatives for the monodromy by central differences).

    A vibrating pivot (``pivot_amplitude``, ``pivot_frequency``) drives the
    scene too: its period is the pivot's when there is no drive, and a drive
    with a pivot must share its frequency.  Drag is accepted (its force is
    once differentiable at v = 0); friction is not (the flow sticks).

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
    # the forcing's period: the drive's or the vibrating pivot's
    freqs = {f for a, f in ((scene.drive_amplitude, scene.drive_frequency),
                            (scene.pivot_amplitude, scene.pivot_frequency)) if a != 0.0 and f != 0.0}
    if scene.friction != 0.0:
        raise ValueError("field 'friction': periodic_orbit needs a smooth flow (its monodromy); dry friction "
                         "sticks: simulate the scene instead")
    if len(freqs) > 1:
        raise ValueError("fields 'drive_frequency' and 'pivot_frequency': periodic_orbit needs one forcing "
                         "period; give the drive and the pivot the same frequency")
    if not freqs:
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
    period = k * 2 * math.pi / abs(freqs.pop())
    fx, words, wlen, nout, ngrid = scene._kernel_fields     # the scene as the kernel checked it
    if force is None and force_params is None:
        x, mono, info, status = _kernel.periodic_orbit_v(fx, words, wlen, nout, ngrid, period, float(winding),
                                                         rtol, atol, tol, maxit, x0)
    else:
        uf = _checks.force(force, force_params)
        x, mono, info, status = _kernel.periodic_orbit_force_v(fx, words, wlen, nout, ngrid, period,
                                                               float(winding), rtol, atol, tol, maxit, x0,
                                                               uf.address, uf.params)
        uf.reraise()
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

"""Equilibria of the autonomous models and their linear stability.

The mathematics runs in the kernel (``kernel/models/pendula_equilibria.f90``);
this module turns a :class:`~pendula.Scene` into the kernel's arguments and the
answers into records.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _checks, _kernel
from ..scene import Scene
from ..systems.contract import require
from ..systems.gravity import field_of

__all__ = ["Equilibrium", "equilibria", "EQUILIBRIUM_KINDS", "MAX_EQUILIBRIA"]

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

    def __repr__(self) -> str:
        ev = ", ".join(f"{complex(e):.4g}" for e in self.eigenvalues)
        return f"Equilibrium(theta={self.theta:.6g}, kind={self.kind!r}, stable={self.stable}, eigenvalues=[{ev}])"


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
        The angles ``lo < theta <= hi`` to list (default one turn, ``(-pi, pi]``);
        ``|lo|, |hi| <= 2**52``.

    Returns
    -------
    list of Equilibrium
        Sorted by angle; empty when the model has none.

    Raises
    ------
    TypeError
        If the window is not two real numbers (strings, bytes and bools are refused).
    ValueError
        If the scene is driven, or the window is not finite and increasing,
        beyond ``|theta| = 2**52``, or holds more than ``MAX_EQUILIBRIA`` rest points.

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
    # the capability table: rest points of an autonomous smooth flow (a drive or a vibrating pivot makes
    # the rest states periodic orbits: periodic_orbit; dry friction makes a band of angles rest states)
    require(scene, "equilibria")
    if isinstance(window, (str, bytes)) or not hasattr(window, "__len__") or len(window) != 2:
        raise TypeError(f"window must be two numbers (lo, hi), got {window!r:.60}")
    # |theta| <= 2^52: beyond it an angle has no fractional digits left (the one checker's rule)
    lo, hi = _checks.angle(window[0], "window[0]"), _checks.angle(window[1], "window[1]")
    if not lo < hi:
        raise ValueError(f"window must have lo < hi, got {window!r}")
    if (hi - lo) / (2 * math.pi) * 2 + 2 > MAX_EQUILIBRIA:
        raise ValueError(f"window: at most {MAX_EQUILIBRIA} equilibria per call; "
                         f"a window of {(hi - lo) / (2 * math.pi):.3g} turns holds more")
    kind, par = field_of(scene)
    theta, eig, ekind, count, status = _kernel.equilibria_v(
        MAX_EQUILIBRIA, _model_code(scene), kind, par, scene.eps, scene.cycloid_radius, scene.damping,
        scene.torque, lo, hi)
    if status == 1:
        raise ValueError("the scene's parameters have no equilibria to compute (eps, the field's parameter "
                         "and the torque must be finite, the window within 2^50 turns)")
    if status == 2:
        raise ValueError(f"window: more than {MAX_EQUILIBRIA} equilibria")
    out = []
    for i in range(count):
        lam = np.array([complex(eig[0, i], eig[1, i]), complex(eig[2, i], eig[3, i])])
        out.append(Equilibrium(float(theta[i]), lam, EQUILIBRIUM_KINDS[ekind[i] - 1]))
    return out


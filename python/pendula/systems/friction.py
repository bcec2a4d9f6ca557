"""Dry (Coulomb) friction on the rigid pendulum: the exact turning points.

Between two turning points the work of gravity, the torque and friction
balances: eps (cos theta_b - cos theta_a) + (tau - mu s)(theta_b - theta_a) = 0
(s the sign of the velocity on the stretch; without torque
eps (cos theta_b - cos theta_a) = mu |theta_b - theta_a|), so each turning angle
is a root (GSL's Brent method, in the distance travelled) and the time between
two is the quadrature of dtheta / |v| (GSL's QAWS, on the integrand with its
turning point's inverse square root taken out by a substitution, and a slow
start's near singularity by geometric grading); the bob sticks at the first
turning point where
|eps sin theta - tau| <= mu.  The kernel's pendula_friction module computes
them; the integrated path (simulate) must pass through them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _kernel
from ..scene import Scene
from .contract import require

__all__ = ["FrictionTurningPoints", "friction_turning_points"]

#: the most turning points returned (each half swing loses about 2 mu / eps of amplitude)
MAX_TURNING_POINTS = 1_000_000
_STATUS = {1: "the scene's numbers are out of range",
           2: "the bob never stops: the torque (at least friction) keeps it turning (no turning point in a "
              "whole turn, so none ever)",
           4: "GSL's root finder or quadrature failed",
           5: "the next turning point lies beyond 2e4 rad of travel (the bob does stop, but so long a "
              "stretch, thousands of turns, is not computed): a smaller speed or more friction"}


@dataclass(frozen=True)
class FrictionTurningPoints:
    """The turning points of a pendulum with dry friction (exact energy balance).

    Attributes
    ----------
    times, angles : numpy.ndarray
        The times and angles where v = 0, in order (t = 0 first when v0 = 0).
    stuck : bool
        Whether the bob sticks at the last one (for good: no drive).
    stick_angle, stick_time : float
        Where and when it sticks (NaN when it does not within the points returned).

    See Also
    --------
    friction_turning_points : makes it.

    Examples
    --------
    >>> import pendula
    >>> tp = pendula.friction_turning_points(pendula.Scene(theta0=0.5, friction=0.1))
    >>> tp.angles.round(6).tolist(), tp.stuck       # 2 mu / eps lost per half swing, nearly
    ([0.5, -0.294282, 0.092687], True)
    """

    times: np.ndarray
    angles: np.ndarray
    stuck: bool
    stick_angle: float
    stick_time: float

    def __repr__(self) -> str:
        end = (f"stuck at theta={self.stick_angle:.6g} from t={self.stick_time:.6g}" if self.stuck
               else "not stuck")
        return f"FrictionTurningPoints({np.size(self.times)} turning points, {end})"


def friction_turning_points(scene: Scene, max_points: int = MAX_TURNING_POINTS) -> FrictionTurningPoints:
    """The exact turning points and the stick of a pendulum with dry friction.

    Parameters
    ----------
    scene : Scene
        The rigid pendulum in uniform gravity with ``friction`` > 0 (a
        ``torque`` is allowed); no damping, drag, drive or pivot.
    max_points : int, optional
        The most turning points to return (default 1e6).

    Returns
    -------
    FrictionTurningPoints
        The times and angles where the velocity vanishes and where the bob sticks.

    Raises
    ------
    TypeError
        If `scene` is not a :class:`Scene`.
    ValueError
        If the scene has no friction, names another effect or model, the
        bob never stops (a torque at least as large as friction), or a
        turning point lies beyond 2e4 rad of travel.

    See Also
    --------
    simulate : the integrated path, stopped and restarted at these points.

    Examples
    --------
    >>> import pendula
    >>> tp = pendula.friction_turning_points(pendula.Scene(theta0=1.0, friction=0.05))
    >>> print(len(tp.angles), tp.stuck, f"{tp.stick_angle:.6f} {tp.stick_time:.4f}")
    10 True -0.045799 28.9059
    """
    from .. import _checks
    if not isinstance(scene, Scene):
        raise TypeError(f"friction_turning_points expects a pendula.Scene, got {type(scene).__name__}")
    # the capability table: dry friction (needed) and a torque on the rigid pendulum, the rest refused by name
    require(scene, "friction_turning_points")
    n = _checks.count(max_points, "max_points", 1, 10**8)
    times, angles, count, stuck, status = _kernel.friction_turning_v(scene.eps, scene.torque, scene.friction,
                                                                     scene.theta0, scene.v0, n)
    if status not in (0, 3):
        raise ValueError(f"friction_turning_points: {_STATUS.get(int(status), f'status {int(status)}')}")
    count = int(count)
    times, angles = times[:count].copy(), angles[:count].copy()
    st = bool(stuck) and status == 0
    return FrictionTurningPoints(times, angles, st, float(angles[-1]) if st else float("nan"),
                                 float(times[-1]) if st else float("nan"))

"""What a computation returns: the Trajectory record shared by every model and path."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .scene import Scene

__all__ = ["Trajectory"]


@dataclass
class Trajectory:
    """A computed motion: what :func:`simulate` returns.

    Attributes
    ----------
    t, theta, v, energy : ndarray
        Times, angle (continuous), angular velocity, and the energy
        v^2/2 + eps (1 - cos theta) evaluated along the path (for damped or
        driven scenes it is not conserved, and shows it).
    method : str
        'exact' or the integrator's name.
    scene : Scene
        The scene that was run.
    stats : dict
        Work done: steps, right-hand-side evaluations, rejected steps (empty
        for the exact solution); for the flexible cord also the number of
        flips and the reason the run stopped.
    x, y, r : ndarray or None
        Flexible cord only: the bob's position (pivot at the origin, y up) and
        distance from the pivot, in units of the cord length (r < 1 in flight).
    flips : dict or None
        Flexible cord only: arrays t_leave, theta_leave, t_return,
        theta_return, xi_before, xi_after, v_leave, v_return, one entry per
        flip in time order.

    See Also
    --------
    simulate : makes it.
    Events : what :func:`find_events` returns.

    Examples
    --------
    >>> import pendula
    >>> tr = pendula.simulate(pendula.Scene(v0=1.0, t_end=2.0, n_samples=3))
    >>> tr.method, tr.t.tolist(), tr.theta.round(6).tolist()
    ('exact', [0.0, 1.0, 2.0], [0.0, 0.847799, 1.004615])
    >>> tr.as_array().shape          # columns t, theta, v, energy
    (3, 4)
    """

    t: np.ndarray
    theta: np.ndarray
    v: np.ndarray
    energy: np.ndarray
    method: str
    scene: Scene
    stats: dict = field(default_factory=dict)
    # flexible cord (systems/cord.py): the bob's position in units of l, and the flip log
    x: np.ndarray | None = None
    y: np.ndarray | None = None
    r: np.ndarray | None = None
    flips: dict | None = None

    def as_array(self) -> np.ndarray:
        """Columns t, theta, v, energy.

        Returns
        -------
        ndarray
            Shape (len(t), 4).
        """
        return np.column_stack([self.t, self.theta, self.v, self.energy])

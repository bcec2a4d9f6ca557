"""What a computation returns: the Trajectory record shared by every model and path."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .scene import Scene

__all__ = ["Trajectory"]


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
    x, y, r : ndarray or None
        Flexible cord only: the bob's position (pivot at the origin, y up) and
        distance from the pivot, in units of the cord length (r < 1 in flight).
    flips : dict or None
        Flexible cord only: arrays t_leave, theta_leave, t_return,
        theta_return, xi_before, xi_after, one entry per flip in time order.
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
        """Columns t, theta, v, energy."""
        return np.column_stack([self.t, self.theta, self.v, self.energy])

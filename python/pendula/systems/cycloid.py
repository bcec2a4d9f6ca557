"""Huygens' cycloidal pendulum (Prusa & Tuma, section 4).

The cord wraps on two cycloidal cheeks, so the bob moves on a cycloid: the
arc length s = 4 R sin(theta) from the lowest point obeys
s'' + beta s' + (g / 4R) s = 4R (tau + A cos(Omega t + phase)), a (damped,
driven) harmonic oscillator, answered in closed form by the kernel
(kernel/models/pendula_cycloid.f90) at any amplitude up to the cusps.
Scenes select it with ``guide = 'cycloid'`` and ``guide_radius`` = R / l.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _kernel
from .._checks import as_float

__all__ = ["CycloidGeometry", "cycloid_geometry", "cycloid_period"]


@dataclass(frozen=True)
class CycloidGeometry:
    """The clock's geometry, lengths in units of the cord's length l.

    Attributes
    ----------
    radius : float
        The generating radius R.
    path_x, path_y : ndarray
        The bob's cycloid between the cusps (pivot at the origin).
    cheek_x, cheek_y : ndarray
        The right cheek from the pivot to its end; the left cheek is
        (-cheek_x, cheek_y).
    """

    radius: float
    path_x: np.ndarray
    path_y: np.ndarray
    cheek_x: np.ndarray
    cheek_y: np.ndarray

    def cord(self, theta: float) -> tuple[np.ndarray, np.ndarray]:
        """The cord at free-cord angle theta: the part wrapped on the cheek
        (from the pivot to the contact point) and the straight free part to the
        bob, as x and y arrays."""
        th = float(theta)
        if not abs(th) < math.pi / 2:
            raise ValueError(f"theta must lie between the cusps, |theta| < pi/2, got {th!r}")
        r = self.radius
        phi = np.linspace(0.0, 2 * abs(th), 64)
        _, _, cx, cy = _kernel.cycloid_geometry_v(r, np.zeros(1), phi)
        cx = math.copysign(1.0, th) * cx
        bx, by, _, _ = _kernel.cycloid_geometry_v(r, np.array([th]), np.zeros(1))
        return np.concatenate([cx, bx]), np.concatenate([cy, by])


def cycloid_geometry(radius: float = 0.25, n: int = 401) -> CycloidGeometry:
    """The cheeks and the bob's path of the cycloidal clock (the involute construction).

    Examples
    --------
    >>> import pendula
    >>> g = pendula.cycloid_geometry(0.25)
    >>> float(g.path_y.min())          # the lowest point: the cord's length below the pivot
    -1.0
    """
    r = float(as_float(radius, "radius"))
    if not (r > 0 and math.isfinite(r)):
        raise ValueError(f"radius must be positive and finite, got {radius!r}")
    if not (isinstance(n, (int, np.integer)) and n >= 3):
        raise ValueError(f"n must be a whole number >= 3, got {n!r}")
    theta = np.linspace(-math.pi / 2, math.pi / 2, n)
    phi = np.linspace(0.0, math.pi, n)
    x, y, cx, cy = _kernel.cycloid_geometry_v(r, theta, phi)
    return CycloidGeometry(r, x, y, cx, cy)


def cycloid_period(eps: float = 1.0, radius: float = 0.25) -> float:
    """T = 4 pi sqrt(R / g) = 2 pi sqrt(4 R / eps) (lengths in units of l): the
    same for every amplitude up to the cusps."""
    e = float(as_float(eps, "eps"))
    r = float(as_float(radius, "radius"))
    if not (e > 0 and r > 0 and math.isfinite(e) and math.isfinite(r)):
        raise ValueError("eps and radius must be positive and finite")
    return 2 * math.pi * math.sqrt(4 * r / e)

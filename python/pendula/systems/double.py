"""The double pendulum's exact parts: its small-amplitude normal modes and the
region from which no arm can flip over.

Two arms hang from a fixed pivot, the second from the end of the first;
theta1 and theta2 are the arms' angles from the downward vertical.  Each arm
is a massless rod with a point mass at its end (``rods=False``) or a uniform
rod (``rods=True``, the compound double pendulum).  The full motion is chaotic
and has no closed form; these two facts have one:

* near the bottom the motion is the sum of two normal modes, from the
  generalised eigenproblem K v = omega^2 M v of the 2x2 mass and stiffness
  matrices;
* the potential energy is V = -g (A cos theta1 + B cos theta2), A = (c m1 + m2)
  l1, B = c m2 l2 (c = 1 for point masses, 1/2 for rods: the centres of
  mass).  To flip the first arm over the top it must pass theta1 = pi, where V
  is at least g (A - B); the second arm needs g (B - A).  From rest at
  (theta1, theta2) the energy is V(theta1, theta2), so neither arm can ever
  flip where A cos theta1 + B cos theta2 > abs(A - B) (for equal point masses and
  lengths: 2 cos theta1 + cos theta2 > 1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._checks import as_float, flag, real

__all__ = ["DoublePendulumModes", "double_pendulum_modes", "flip_forbidden"]


def _arms(m1, m2, l1, l2, g, rods):
    """The checked parameters, and the mass and stiffness matrices (M, K)."""
    m1 = real(m1, "m1", 0.0, lo_open=True)
    m2 = real(m2, "m2", 0.0, lo_open=True)
    l1 = real(l1, "l1", 0.0, lo_open=True)
    l2 = real(l2, "l2", 0.0, lo_open=True)
    g = real(g, "g", 0.0, lo_open=True)
    rods = flag(rods, "rods")
    if rods:
        # uniform rods about the pivot and about the joint: T = (1/2) q' M q', V = (1/2) q K q
        mm = np.array([[(m1 / 3 + m2) * l1 * l1, m2 * l1 * l2 / 2], [m2 * l1 * l2 / 2, m2 * l2 * l2 / 3]])
        kk = np.array([[g * l1 * (m1 / 2 + m2), 0.0], [0.0, g * m2 * l2 / 2]])
    else:
        mm = np.array([[(m1 + m2) * l1 * l1, m2 * l1 * l2], [m2 * l1 * l2, m2 * l2 * l2]])
        kk = np.array([[g * l1 * (m1 + m2), 0.0], [0.0, g * m2 * l2]])
    return (m1, m2, l1, l2, g, rods), mm, kk


@dataclass(frozen=True)
class DoublePendulumModes:
    """The two small-amplitude normal modes of a double pendulum.

    Attributes
    ----------
    omega : ndarray
        The angular frequencies, slow mode first, shape (2,).
    period : ndarray
        2 pi / omega.
    shapes : ndarray
        The mode shapes as columns, shape (2, 2): column k is (1, r_k), the
        ratio theta2 / theta1 of mode k (positive in the slow mode, where the
        arms swing together, negative in the fast one).
    mass, stiffness : ndarray
        The matrices M and K of T = q' M q' / 2, V = q K q / 2, q = (theta1,
        theta2).

    See Also
    --------
    double_pendulum_modes : makes it.

    Examples
    --------
    >>> import pendula
    >>> nm = pendula.double_pendulum_modes()
    >>> [round(float(w), 12) for w in nm.omega ** 2]      # (2 -+ sqrt 2) g/l
    [0.585786437627, 3.414213562373]
    """

    omega: NDArray[np.float64]
    period: NDArray[np.float64]
    shapes: NDArray[np.float64]
    mass: NDArray[np.float64]
    stiffness: NDArray[np.float64]


def double_pendulum_modes(m1: float = 1.0, m2: float = 1.0, l1: float = 1.0, l2: float = 1.0, g: float = 1.0,
                          rods: bool = False) -> DoublePendulumModes:
    """The normal modes of a double pendulum near the bottom, exactly.

    Parameters
    ----------
    m1, m2 : float, optional
        The arms' masses (default 1), > 0.
    l1, l2 : float, optional
        The arms' lengths (default 1), > 0.
    g : float, optional
        Gravity (default 1), > 0.
    rods : bool, optional
        Uniform rods (the compound double pendulum) instead of point masses
        on massless rods (default False).

    Returns
    -------
    DoublePendulumModes
        Frequencies, periods and mode shapes.

    Raises
    ------
    ValueError
        Naming the parameter that is not positive and finite.
    TypeError
        For a string or array parameter, or a rods that is not a bool.

    See Also
    --------
    flip_forbidden : the region from which no arm can flip.
    spherical_orbit : the spherical pendulum, exactly.

    Notes
    -----
    det(K - omega^2 M) = 0 is the quadratic a w^2 + b w + c = 0 in
    w = omega^2, a = det M (m1 m2 l1^2 l2^2 for point masses, m2 l1^2 l2^2
    (m1/9 + m2/12) for rods: no cancellation), b = -(K11 M22 + K22 M11), c = det K, solved
    without cancellation (the root of larger size first, the other as c over
    it).  For equal point masses and lengths, omega^2 = (2 -+ sqrt 2) g / l,
    shapes theta2 / theta1 = +-sqrt 2.

    Examples
    --------
    >>> import pendula
    >>> nm = pendula.double_pendulum_modes(m1=1.0, m2=1.0, l1=1.0, l2=1.0)
    >>> [round(float(r), 12) for r in nm.shapes[1]]      # theta2/theta1
    [1.414213562373, -1.414213562373]
    >>> nm = pendula.double_pendulum_modes(rods=True)     # two uniform rods
    >>> [round(float(w), 12) for w in nm.omega ** 2]     # 3 -+ 6/sqrt(7)
    [0.732213161945, 5.267786838055]
    """
    (m1, m2, l1, l2, g, rods), mm, kk = _arms(m1, m2, l1, l2, g, rods)
    # det M in closed form, a sum of positive terms (as M11 M22 - M12^2 it cancels for m1 << m2)
    a = m2 * (l1 * l2) ** 2 * (m1 / 9 + m2 / 12 if rods else m1)
    b = -(kk[0, 0] * mm[1, 1] + kk[1, 1] * mm[0, 0])
    c = kk[0, 0] * kk[1, 1]
    disc = b * b - 4.0 * a * c
    q = -0.5 * (b - math.sqrt(max(disc, 0.0)))     # b < 0: the larger root times a, no cancellation
    w2 = np.array([c / q, q / a])
    omega = np.sqrt(w2)
    # (K - w M) v = 0, first row: v = (1, (K11 - w M11) / (w M12))
    ratio = (kk[0, 0] - w2 * mm[0, 0]) / (w2 * mm[0, 1])
    shapes = np.vstack([np.ones(2), ratio])
    return DoublePendulumModes(omega=omega, period=2.0 * np.pi / omega, shapes=shapes, mass=mm, stiffness=kk)


def flip_forbidden(theta1: ArrayLike, theta2: ArrayLike, m1: float = 1.0, m2: float = 1.0, l1: float = 1.0,
                   l2: float = 1.0, rods: bool = False) -> NDArray[np.bool_]:
    """Where a double pendulum released from rest can never flip either arm.

    Parameters
    ----------
    theta1, theta2 : array_like
        The arms' angles at rest (from the downward vertical), broadcast
        together.
    m1, m2, l1, l2 : float, optional
        Masses and lengths (default 1), > 0.
    rods : bool, optional
        Uniform rods instead of point masses (default False).

    Returns
    -------
    ndarray of bool
        True where the energy from rest lies below the least energy with
        which either arm can pass over the top: A cos theta1 + B cos theta2 >
        abs(A - B).  The mask of a flip-time map: there the flip time is
        infinite without any integration.  (Decided in double precision:
        points within a few eps of the boundary may fall either way.)

    Raises
    ------
    ValueError
        Naming a parameter that is not positive and finite.
    TypeError
        For a string, complex or object angle.

    See Also
    --------
    double_pendulum_modes : the normal modes near the bottom.

    Examples
    --------
    >>> import numpy as np, pendula
    >>> pendula.flip_forbidden([0.5, 2.0], [0.5, 0.0]).tolist()
    [True, False]
    >>> th = np.linspace(-np.pi, np.pi, 5)         # a 5 x 5 map's mask
    >>> pendula.flip_forbidden(th[:, None], th[None, :]).astype(int)
    array([[0, 0, 0, 0, 0],
           [0, 0, 1, 0, 0],
           [0, 1, 1, 1, 0],
           [0, 0, 1, 0, 0],
           [0, 0, 0, 0, 0]])
    """
    theta1 = as_float(theta1, "theta1")
    theta2 = as_float(theta2, "theta2")
    (m1, m2, l1, l2, _, rods), _, _ = _arms(m1, m2, l1, l2, 1.0, rods)
    c = 0.5 if rods else 1.0
    big_a = (c * m1 + m2) * l1
    big_b = c * m2 * l2
    return big_a * np.cos(theta1) + big_b * np.cos(theta2) > abs(big_a - big_b)

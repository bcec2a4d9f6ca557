"""The Floquet solution me_nu(z, q) of Mathieu's equation of non-integer order.

For a real order nu that is not an integer, Mathieu's equation
y'' + (λ_ν(q) - 2 q cos 2z) y = 0 has the solution
me_nu(z, q) = sum_m c_2m exp(i (nu + 2m) z) (DLMF 28.12, 28.14.1), whose real
and imaginary parts for real z are ce_nu(z, q) = sum_m c_2m cos((nu + 2m) z)
and se_nu(z, q) = sum_m c_2m sin((nu + 2m) z) (DLMF 28.14.2-3).  The
coefficients are the eigenvector of the bi-infinite Hill matrix (the kernel's,
as for the transmon's wavefunctions), normalised so that sum_m c_2m^2 = 1
(DLMF 28.14.4), the sign so that c_0 > 0 (at q = 0, me_nu = exp(i nu z)).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _kernel
from ._checks import as_float, real
from .quantum import MATHIEU_MAX_Q

__all__ = ["mathieu_me"]


def _coefficients(nu: float, q: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The orders nu + 2m and the coefficients c_2m of me_nu, every one that carries
    more than 1e-17 of the norm."""
    nr = nu % 2.0
    k0 = round((nu - nr) / 2.0)
    # the level of the matrix of offset nr that continues nu^2 from q = 0: the
    # number of orders nr + 2k nearer zero than nu (the levels never cross)
    half = k0 + 2
    k = np.arange(-half, half + 1)
    m = int(np.count_nonzero(np.abs(nr + 2 * k) < nu))
    nm = int(2 * math.sqrt(abs(q)) + nu / 2 + 24)
    while True:
        kmin = -nm
        _, vec, lost, status = _kernel.mathieu_level_vector_v(
            2 * nm + 1, np.array([nr]), np.array([q]), np.array([m], dtype=np.int32), kmin)
        if status[0] != 0:
            raise ValueError(f"mathieu_me: the coefficients of order {nu:g} could not be computed at q = {q:g}")
        if lost[0] <= 1e-17:
            break
        nm *= 2
    c = vec[:, 0]
    orders = nr + 2.0 * np.arange(kmin, kmin + c.size)
    i0 = int(np.argmin(np.abs(orders - nu)))      # the row of order nu, c_0
    if c[i0] < 0:
        c = -c
    return orders, c


def mathieu_me(nu: float, q: float, z: ArrayLike
               ) -> tuple[NDArray[np.complex128] | np.complex128, NDArray[np.complex128] | np.complex128]:
    """The Floquet solution me_nu(z, q) of non-integer order and its derivative.

    me_nu(z, q) = sum_m c_2m exp(i (nu + 2m) z) solves Mathieu's equation
    y'' + (λ_ν(q) - 2 q cos 2z) y = 0 with λ_ν(q) = ``mathieu_a(nu, q)``, and
    me_nu(z + pi) = exp(i nu pi) me_nu(z).  For real z its real part is
    ce_nu(z, q) and its imaginary part se_nu(z, q) (DLMF 28.12, 28.14).
    Normalised as DLMF 28.14.4, sum_m c_2m^2 = 1 (so that the mean of
    me_nu(z) me_nu(-z) over a period pi is 1), with c_0 > 0: at q = 0,
    me_nu(z, 0) = exp(i nu z).

    Parameters
    ----------
    nu : float
        Order, not an integer, 0 < nu <= 1e4 (for a negative order,
        the solution of order -nu at z is this one at -z).
    q : float
        Parameter, any sign, abs(q) <= 1e10.
    z : array_like
        Real points (radians).

    Returns
    -------
    me, dme : ndarray or complex
        me_nu(z, q) and d me_nu / dz.  Absolutely accurate to a few eps
        times the largest order summed (the coefficients have unit norm).

    Raises
    ------
    ValueError
        An integer order (the periodic functions are ``mathieu_ce`` and
        ``mathieu_se``), or nu or q out of range.

    See Also
    --------
    mathieu_ce : the periodic even functions of integer order.
    mathieu_a : the characteristic value λ_ν(q).

    Examples
    --------
    >>> import numpy as np, pendula
    >>> me, dme = pendula.mathieu_me(0.5, 0.0, np.pi / 3)   # exp(i z / 2) at q = 0
    >>> bool(abs(me - np.exp(0.5j * np.pi / 3)) < 1e-15)
    True
    >>> me, _ = pendula.mathieu_me(1.5, 2.0, [0.3, 0.3 + np.pi])
    >>> bool(abs(me[1] - np.exp(1.5j * np.pi) * me[0]) < 1e-14)   # Floquet
    True
    """
    nu = real(nu, "nu", lo=0.0, hi=1.0e4, lo_open=True)
    if nu == int(nu):
        raise ValueError(f"nu must not be an integer (got {nu:g}): use mathieu_ce and mathieu_se")
    q = real(q, "q", lo=-MATHIEU_MAX_Q, hi=MATHIEU_MAX_Q)
    zz = as_float(z, "z")
    orders, c = _coefficients(nu, q)
    zf = zz.reshape(-1)
    phase = np.exp(1j * np.outer(zf, orders))
    me = phase @ c
    dme = phase @ (1j * orders * c)
    if zz.ndim == 0:
        return me[0], dme[0]
    return me.reshape(zz.shape), dme.reshape(zz.shape)

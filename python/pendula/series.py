"""Series: the period series in the amplitude, and Poincare-Lindstedt.

Everything here is exact rational arithmetic on truncated power series
(``fractions.Fraction``), so coefficients come out as exact fractions to any
order; only the final evaluation is in floating point.

* :func:`period_series` -- T/T0 = 1 + theta0^2/16 + 11 theta0^4/3072 + ...
  from T/T0 = (2/pi) K(m), m = sin^2(theta0/2) (source 003, section 3).
* :func:`poincare_lindstedt` -- the Poincare-Lindstedt solution to any odd
  order in the amplitude a.  The Poincare-Lindstedt expansion is unique, so
  it is obtained here as the expansion in a of the exact Fourier series of the
  libration, theta = 8 sum q^(n+1/2) / ((2n+1)(1 + q^(2n+1))) cos((2n+1) w t),
  and of w = pi sqrt(eps) / (2K): at order 3 it is the textbook
  a cos(wt) + (a^3/192)(cos wt - cos 3wt), w = sqrt(eps)(1 - a^2/16).
"""

from __future__ import annotations

import math
from fractions import Fraction as Fr
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._checks import as_float

__all__ = ["period_series", "period_from_series", "poincare_lindstedt", "poincare_lindstedt_coefficients"]


# -------------------------------------------------- truncated power series
# A series is a list of Fractions c[0..N] meaning sum c[i] x^i, truncated at x^N.

def _mul(a, b, n):
    out = [Fr(0)] * (n + 1)
    for i, x in enumerate(a[: n + 1]):
        if x:
            for j, y in enumerate(b[: n + 1 - i]):
                out[i + j] += x * y
    return out


def _add(a, b, n):
    return [(a[i] if i < len(a) else 0) + (b[i] if i < len(b) else 0) for i in range(n + 1)]


def _scale(a, c):
    return [x * c for x in a]


def _pow_int(a, k, n):
    out = [Fr(1)] + [Fr(0)] * n
    for _ in range(k):
        out = _mul(out, a, n)
    return out


def _binom_series(a, alpha, n):
    """(1 + a)^alpha for a series a with a[0] = 0 (binomial series)."""
    out = [Fr(1)] + [Fr(0)] * n
    term = [Fr(1)] + [Fr(0)] * n
    coef = Fr(1)
    for j in range(1, n + 1):
        coef = coef * (alpha - (j - 1)) / j
        term = _mul(term, a, n)
        if not any(term):
            break
        out = _add(out, _scale(term, coef), n)
    return out


def _inv(a, n):
    """1/a for a series with a[0] != 0."""
    a0 = a[0]
    rest = [Fr(0)] + [x / a0 for x in a[1: n + 1]]
    return _scale(_binom_series(rest, Fr(-1), n), 1 / a0)


def _sin_half(n):
    """sin(x/2) as a series in x."""
    out = [Fr(0)] * (n + 1)
    for j in range(0, n + 1):
        p = 2 * j + 1
        if p > n:
            break
        out[p] = Fr((-1) ** j, math.factorial(p) * 2**p)
    return out


def _k_over_2pi_series(m, n):
    """(2/pi) K(m) = sum ((2j)! / (4^j j!^2))^2 m^j, composed with the series m."""
    out = [Fr(1)] + [Fr(0)] * n
    mj = [Fr(1)] + [Fr(0)] * n
    for j in range(1, n + 1):
        mj = _mul(mj, m, n)
        if not any(mj):
            break
        c = Fr(math.comb(2 * j, j), 4**j) ** 2
        out = _add(out, _scale(mj, c), n)
    return out


@lru_cache(maxsize=None)
def period_series(n: int) -> tuple[Fr, ...]:
    """Coefficients of theta0^(2j), j = 0..n, of T/T0 as exact fractions.

    T is the period of the pendulum released from rest at theta0, T0 = 2 pi /
    sqrt(eps) the small-oscillation period:
    T/T0 = 1 + theta0^2/16 + 11 theta0^4/3072 + 173 theta0^6/737280 + ...

    Parameters
    ----------
    n : int
        The highest power kept is theta0^(2n) (n >= 0).

    Returns
    -------
    tuple of fractions.Fraction
        n + 1 coefficients, exact.

    Raises
    ------
    ValueError
        If `n` is not a non-negative whole number.

    See Also
    --------
    period_from_series : the truncated series evaluated.
    period : the exact period.

    Examples
    --------
    >>> from pendula import period_series
    >>> [str(c) for c in period_series(3)]
    ['1', '1/16', '11/3072', '173/737280']
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise ValueError(f"n must be a non-negative whole number, got {n!r}")
    n = int(n)
    N = 2 * n
    k = _sin_half(N)
    m = _mul(k, k, N)
    t = _k_over_2pi_series(m, N)
    return tuple(t[2 * j] for j in range(n + 1))


def period_from_series(theta0: ArrayLike, n: int, eps: float = 1.0) -> NDArray[np.float64] | np.float64:
    """T from the series truncated after theta0^(2n) (for comparing with the exact period).

    Parameters
    ----------
    theta0 : array_like
        Amplitude (rad) of a pendulum released from rest.
    n : int
        The highest power kept is theta0^(2n).
    eps : float, optional
        g / l (default 1).

    Returns
    -------
    ndarray or float
        (2 pi / sqrt(eps)) sum_j c_j theta0^(2j), broadcast over `theta0`.

    Raises
    ------
    TypeError
        For a string, complex or object `theta0`.
    ValueError
        If `n` is not a non-negative whole number.

    See Also
    --------
    period_series : the coefficients.
    period : the exact period.

    Examples
    --------
    >>> import pendula
    >>> float(pendula.period_from_series(0.5, 3))            # exact: 6.382789697677741
    6.382789263003258
    """
    theta0 = as_float(theta0, "theta0")
    c = period_series(n)
    x = theta0 * theta0
    s = np.zeros_like(x)
    for cj in reversed(c):
        s = s * x + float(cj)
    return 2 * np.pi / np.sqrt(eps) * s


# -------------------------------------------------- Poincare-Lindstedt

_Q_OF_EPS = (1, 2, 15, 150, 1707, 20910, 268616, 3567400)   # q = sum c_i e^(4i+1)


@lru_cache(maxsize=None)
def poincare_lindstedt_coefficients(order: int) -> tuple[tuple[tuple[Fr, ...], ...], tuple[Fr, ...]]:
    """Exact Poincare-Lindstedt coefficients up to a^order (order odd).

    Returns ``(harmonics, freq)``: ``harmonics[n]`` is the series (in a) of the
    amplitude of cos((2n+1) w t) and ``freq`` the series of w / sqrt(eps).
    """
    if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or order < 1 or order % 2 == 0:
        raise ValueError(f"order must be an odd whole number >= 1, got {order!r}")
    N = int(order)
    n_ser = N + 1
    k = _sin_half(n_ser)
    m = _mul(k, k, n_ser)
    # s = (1 - m)^(1/4) = sqrt(k');  e = (1 - s) / (2 (1 + s))
    s = _binom_series(_scale(m, -1), Fr(1, 4), n_ser)
    one_minus_s = _add([Fr(1)], _scale(s, -1), n_ser)
    one_plus_s = _add([Fr(1)], s, n_ser)
    e = _scale(_mul(one_minus_s, _inv(one_plus_s, n_ser), n_ser), Fr(1, 2))
    # e = m g(m) with g(0) = 1/16: write e = (k^2/16) h, h(0) = 1, so sqrt(e) = (k/4) sqrt(h)
    # h = 16 e / m: divide the series by x^2 through m = x^2 / 4 (1 + ...)
    m_over_x2 = m[2:] + [Fr(0), Fr(0)]
    e_over_x2 = e[2:] + [Fr(0), Fr(0)]
    h = _scale(_mul(e_over_x2, _inv(m_over_x2, n_ser), n_ser), 16)
    # q = e (1 + 2 e^4 + 15 e^8 + ...);  q^(1/2) = (k/4) sqrt(h) sqrt(1 + 2 e^4 + ...)
    e4 = _pow_int(e, 4, n_ser)
    r = [Fr(0)] * (n_ser + 1)
    p = [Fr(1)] + [Fr(0)] * n_ser
    for c in _Q_OF_EPS[1:]:
        p = _mul(p, e4, n_ser)
        if not any(p):
            break
        r = _add(r, _scale(p, c), n_ser)
    q = _mul(e, _add([Fr(1)], r, n_ser), n_ser)
    sqrt_q = _mul(_scale(k, Fr(1, 4)), _mul(_binom_series(_add(h, [Fr(-1)], n_ser), Fr(1, 2), n_ser),
                                             _binom_series(r, Fr(1, 2), n_ser), n_ser), n_ser)
    harmonics = []
    n = 0
    while 2 * n + 1 <= N:
        qn = _pow_int(q, n, n_ser)
        num = _scale(_mul(qn, sqrt_q, n_ser), Fr(8, 2 * n + 1))
        den = _add([Fr(1)], _mul(_pow_int(q, 2 * n, n_ser), q, n_ser), n_ser)
        # released from rest at theta = a: sin((2n+1)(wt + pi/2)) = (-1)^n cos((2n+1) wt)
        c = _scale(_mul(num, _inv(den, n_ser), n_ser), (-1) ** n)
        harmonics.append(tuple(c[: N + 1]))
        n += 1
    freq = _inv(_k_over_2pi_series(m, n_ser), n_ser)
    return tuple(harmonics), tuple(freq[: N + 1])


def _eval(series, a):
    out = np.zeros_like(a)
    for c in reversed(series):
        out = out * a + float(c)
    return out


def poincare_lindstedt(a: float, t: ArrayLike, eps: float = 1.0, order: int = 3) -> NDArray[np.float64] | np.float64:
    """The Poincare-Lindstedt approximation of theta(t), released from rest at theta(0) = a.

    Parameters
    ----------
    a : float
        Amplitude (rad), abs(a) < pi.
    t : array_like
        Times.
    eps : float
        g / l.
    order : int
        Highest power of a kept (odd): 1 is the harmonic oscillator, 3 the
        textbook a cos wt + (a^3/192)(cos wt - cos 3wt) with w = sqrt(eps)(1 - a^2/16).

    Returns
    -------
    theta : ndarray
        The approximation at the times `t`.

    Raises
    ------
    ValueError
        If abs(a) >= pi, eps <= 0, or `order` is not an odd whole number >= 1.
    TypeError
        For a string, complex or object argument.

    See Also
    --------
    exact_motion : the exact motion it approximates.
    period_series : the series of the period.

    Notes
    -----
    The coefficients are exact fractions to any order, from the Fourier series
    of the exact solution in the nome.  Prusa & Tuma (3.36) and (3.41) print
    the third-order term with the opposite sign (a slip).

    Examples
    --------
    >>> import pendula
    >>> pendula.poincare_lindstedt(0.1, [0.0, 1.0], order=3).round(8).tolist()
    [0.1, 0.05409078]
    >>> pendula.exact_motion(0.1, 0.0, 1.0, [1.0])[0].round(8).tolist()
    [0.05409079]
    """
    a = float(as_float(a, "a"))
    if not abs(a) < math.pi:
        raise ValueError(f"the amplitude a must satisfy |a| < pi (a libration), got {a!r}")
    if not eps > 0:
        raise ValueError(f"eps must be positive, got {eps!r}")
    t = as_float(t, "t")
    harmonics, freq = poincare_lindstedt_coefficients(order)
    w = math.sqrt(eps) * float(_eval(freq, np.asarray(a)))
    theta = np.zeros_like(t)
    for n, c in enumerate(harmonics):
        theta = theta + float(_eval(c, np.asarray(a))) * np.cos((2 * n + 1) * w * t)
    return theta

"""Elliptic integrals, the nome and the Jacobi elliptic functions.

The parameter convention is m = k^2 (as in scipy.special and the DLMF).  Every
function also takes the complementary parameter ``mc = 1 - m``; when it is
given it is used instead of ``m``, so that parameters as close to 1 as
m = 1 - 1e-300 (the pendulum next to its separatrix) are exact.  Nothing here
forms 1 - m by subtraction when ``mc`` is known.

All functions broadcast like numpy ufuncs, compute in float64 in the Fortran
kernel (no per-element Python), and return NaN with a RuntimeWarning outside
their domain.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _kernel
from ._checks import as_float, flat, parameter, shaped, warn_domain

__all__ = ["ellipk", "ellipe", "ellipf", "ellipeinc", "ellipj", "nome"]


_NO_MC = np.zeros(1)


#: elements per kernel call: long arrays go in chunks, so that Ctrl-C is seen
#: between them (each chunk runs with the GIL released, ~50 ms at most)
CHUNK = 1 << 20


def _unary(kfunc, name, m, mc):
    if mc is None and m is not None:
        # the kernel forms mc = 1 - m itself: one pass less over the data
        a = as_float(m, "m")
        shape = a.shape
        if a.size == 0:
            return np.empty(shape)
        mf = np.ascontiguousarray(a.reshape(-1), dtype=np.float64)
        out = kfunc(mf, _NO_MC if mf.size != 1 else np.array([1.0 - mf[0]]))
        warn_domain(name, out, mf)
        return shaped(out, shape)
    m, mc = parameter(m, mc)
    shape, (mf, mcf) = flat(m, mc)
    if mf.size == 0:
        return np.empty(shape)
    out = kfunc(mf, mcf)
    warn_domain(name, out, mf, mcf)
    return shaped(out, shape)


def _incomplete(kfunc, name, phi, m, mc):
    phi = as_float(phi, "phi")
    m, mc = parameter(m, mc)
    shape, (pf, mf, mcf) = flat(phi, m, mc)
    if pf.size == 0:
        return np.empty(shape)
    out = kfunc(pf, mf, mcf)
    warn_domain(name, out, pf, mf, mcf)
    return shaped(out, shape)


def ellipk(m: ArrayLike | None, mc: ArrayLike | None = None) -> NDArray[np.float64] | np.float64:
    """Complete elliptic integral of the first kind K(m).

    Parameters
    ----------
    m : array_like
        Parameter m = k^2, m <= 1.  May be None when `mc` is given.
    mc : array_like, optional
        Complementary parameter 1 - m; used instead of `m` when given.

    Returns
    -------
    K : ndarray or float
        K(m) = int_0^{pi/2} dt / sqrt(1 - m sin^2 t); +inf at m = 1, NaN
        (with a RuntimeWarning) for m > 1.

    Raises
    ------
    TypeError
        For a string, complex or object argument, or when neither `m` nor `mc`
        is given.
    ValueError
        When `m` and `mc` are both given and ``mc != 1 - m``.

    See Also
    --------
    ellipe : the complete integral of the second kind.
    ellipf : the incomplete integral F(phi|m); F(pi/2|m) = K(m).
    scipy.special.ellipk, scipy.special.ellipkm1 : the peers, from m or 1 - m.

    Notes
    -----
    The arithmetic-geometric mean K = pi / (2 AGM(1, sqrt(mc))) carried in
    double-double, so the result is within about 1 ulp for every mc > 0,
    mc = 1e-300 included.

    Examples
    --------
    >>> import pendula
    >>> float(pendula.ellipk(0.0))
    1.5707963267948966
    >>> float(pendula.ellipk(None, mc=1e-300))  # ln 4 + 150 ln 10
    346.77405831022674
    """
    return _unary(_kernel.ellipk_v, "ellipk", m, mc)


def ellipe(m: ArrayLike | None, mc: ArrayLike | None = None) -> NDArray[np.float64] | np.float64:
    """Complete elliptic integral of the second kind E(m), m <= 1.

    Parameters
    ----------
    m : array_like
        Parameter m = k^2, m <= 1.  May be None when `mc` is given.
    mc : array_like, optional
        Complementary parameter 1 - m; used instead of `m` when given.

    Returns
    -------
    E : ndarray or float
        E(m) = int_0^{pi/2} sqrt(1 - m sin^2 t) dt; 1 at m = 1, NaN (with a
        RuntimeWarning) for m > 1.

    Raises
    ------
    TypeError
        For a string, complex or object argument, or when neither `m` nor `mc`
        is given.
    ValueError
        When `m` and `mc` are both given and ``mc != 1 - m``.

    See Also
    --------
    ellipk : the complete integral of the first kind.
    ellipeinc : the incomplete integral E(phi|m).
    scipy.special.ellipe : the peer.

    Notes
    -----
    Computed as (mc/3) (R_D(0, mc, 1) + R_D(0, 1, mc)) (DLMF 19.25.1), a sum
    of positive terms, so it stays accurate as m -> 1.

    Examples
    --------
    >>> import pendula
    >>> float(pendula.ellipe(0.5))
    1.3506438810476755
    >>> float(pendula.ellipe(None, mc=1e-300))
    1.0
    """
    return _unary(_kernel.ellipe_v, "ellipe", m, mc)


def ellipf(phi: ArrayLike, m: ArrayLike | None, mc: ArrayLike | None = None) -> NDArray[np.float64] | np.float64:
    """Incomplete elliptic integral of the first kind F(phi|m).

    Parameters
    ----------
    phi : array_like
        Amplitude in radians, any real value (F(phi + j pi) = F(phi) + 2 j K).
    m : array_like
        Parameter m = k^2, any real value.  For m > 1 the integral is real
        only while m sin^2 phi <= 1 with abs(phi) < pi/2; elsewhere NaN.  May be
        None when `mc` is given.
    mc : array_like, optional
        Complementary parameter 1 - m; used instead of `m` when given.

    Returns
    -------
    F : ndarray or float
        F(phi|m) = int_0^phi dt / sqrt(1 - m sin^2 t), broadcast over the
        arguments; NaN with a RuntimeWarning outside the real domain.

    Raises
    ------
    TypeError
        For a string, complex or object argument, or when neither `m` nor `mc`
        is given.
    ValueError
        When `m` and `mc` are both given and ``mc != 1 - m``.

    See Also
    --------
    ellipk : the complete integral, F(pi/2|m).
    ellipj : the inverse: am(F(phi|m)|m) = phi.
    ellipeinc : the incomplete integral of the second kind.
    scipy.special.ellipkinc : the peer.

    Notes
    -----
    phi is reduced by pi from the exact double: next to an odd multiple of
    pi/2 its distance from it is formed in double-double, so F keeps its
    accuracy there even when mc is tiny and F is ill-conditioned in phi.
    Whether m sin^2 phi > 1 (m > 1) is decided from the double-double sine.

    Examples
    --------
    >>> import pendula
    >>> round(float(pendula.ellipf(1.0, 0.5)), 15)
    1.083216772845169
    >>> float(pendula.ellipf(3.141592653589793 / 2, 0.5)), float(pendula.ellipk(0.5))   # F(pi/2) = K, 1 ulp
    (1.854074677301372, 1.8540746773013719)
    """
    return _incomplete(_kernel.ellipf_v, "ellipf", phi, m, mc)


def ellipeinc(phi: ArrayLike, m: ArrayLike | None, mc: ArrayLike | None = None) -> NDArray[np.float64] | np.float64:
    """Incomplete elliptic integral of the second kind E(phi|m).

    Parameters
    ----------
    phi : array_like
        Amplitude in radians, any real value.
    m : array_like
        Parameter m = k^2, any real value (the same real domain for m > 1 as
        :func:`ellipf`).  May be None when `mc` is given.
    mc : array_like, optional
        Complementary parameter 1 - m; used instead of `m` when given.

    Returns
    -------
    E : ndarray or float
        E(phi|m) = int_0^phi sqrt(1 - m sin^2 t) dt; NaN with a RuntimeWarning
        outside the real domain (m > 1 and m sin^2 phi > 1, decided exactly).

    Raises
    ------
    TypeError
        For a string, complex or object argument, or when neither `m` nor `mc`
        is given.
    ValueError
        When `m` and `mc` are both given and ``mc != 1 - m``.

    See Also
    --------
    ellipe : the complete integral, E(pi/2|m).
    ellipf : the incomplete integral of the first kind.
    scipy.special.ellipeinc : the peer.

    Notes
    -----
    For 0 <= m < 1 it uses E = mc F + (m mc/3) s^3 R_D(c^2, 1, D^2) + m s c / D
    (s = sin phi, c = cos phi, D^2 = 1 - m s^2), whose terms are all positive,
    so no digits cancel near m = 1.

    Examples
    --------
    >>> import pendula
    >>> round(float(pendula.ellipeinc(1.0, 0.5)), 15)
    0.92732988362444
    """
    return _incomplete(_kernel.ellipeinc_v, "ellipeinc", phi, m, mc)


def nome(m: ArrayLike | None, mc: ArrayLike | None = None) -> NDArray[np.float64] | np.float64:
    """The nome q(m) = exp(-pi K(1-m) / K(m)) for 0 <= m <= 1.

    Parameters
    ----------
    m : array_like
        Parameter m = k^2, 0 <= m <= 1.  May be None when `mc` is given.
    mc : array_like, optional
        Complementary parameter 1 - m; used instead of `m` when given.

    Returns
    -------
    q : ndarray or float
        The nome, 0 at m = 0 and 1 at m = 1; NaN with a RuntimeWarning
        outside [0, 1].

    Raises
    ------
    TypeError
        For a string, complex or object argument, or when neither `m` nor `mc`
        is given.
    ValueError
        When `m` and `mc` are both given and ``mc != 1 - m``.

    See Also
    --------
    ellipk : K(m), of which the nome is a ratio.
    fourier_series : the pendulum's Fourier amplitudes, powers of the nome.

    Notes
    -----
    Computed from Jacobi's series q = e + 2 e^5 + 15 e^9 + ... with
    e = (1 - mc^(1/4)) / (2 (1 + mc^(1/4))) written without cancellation for
    m <= 1/2, and from ln q ln q' = pi^2 with the complementary series for
    m > 1/2, so q keeps its relative accuracy at both ends (q ~ m/16 as m -> 0,
    q -> 1 as mc -> 0).

    Examples
    --------
    >>> import pendula
    >>> float(pendula.nome(0.5))             # e^-pi
    0.043213918263772244
    >>> float(pendula.nome(None, mc=1e-300))
    0.9858701784145535
    """
    return _unary(_kernel.nome_v, "nome", m, mc)


def ellipj(u: ArrayLike, m: ArrayLike | None, mc: ArrayLike | None = None
           ) -> tuple[NDArray[np.float64] | np.float64, NDArray[np.float64] | np.float64,
                      NDArray[np.float64] | np.float64, NDArray[np.float64] | np.float64]:
    """Jacobi elliptic functions sn, cn, dn and the amplitude am of (u|m).

    Parameters
    ----------
    u : array_like
        Argument, any real value.  Arguments up to 2**48 half periods are
        reduced with K in double-double, so the error does not grow with u.
    m : array_like
        Parameter m = k^2, any real value: m > 1 through the reciprocal-modulus
        transformation, m < 0 through the imaginary-modulus transformation
        (for m <= -1023 its core from Jacobi's theta series, so that dn, up
        to sqrt(1 - m), keeps its relative accuracy).
        May be None when `mc` is given.
    mc : array_like, optional
        Complementary parameter 1 - m, used instead of `m` when given.

    Returns
    -------
    sn, cn, dn, am : ndarray or float
        For 0 <= m <= 1, `am` is the continuous (unwrapped) amplitude, monotone
        in u: the angle of the rotating pendulum.  For m > 1 it is
        asin(sn), which stays in [-pi/2, pi/2] (computed as atan2(sn, cn),
        cn > 0, so that it keeps its accuracy next to sn = +-1/sqrt(m)).  NaN
        with a RuntimeWarning for abs(u) beyond 2**48 half periods.

    Raises
    ------
    TypeError
        For a string, complex or object argument, or when neither `m` nor `mc`
        is given.
    ValueError
        When `m` and `mc` are both given and ``mc != 1 - m``.

    See Also
    --------
    ellipk : the quarter period K(m).
    ellipf : the inverse of am.
    exact_motion : the pendulum's motion, theta/2 = am (rotation) or asin(k sn).
    scipy.special.ellipj : the peer (0 <= m <= 1 only).

    Notes
    -----
    When `m` is a scalar, everything that depends only on m (K in
    double-double, the series coefficients) is computed once for the whole
    array of u: that is the pendulum's case, many times at one energy.

    Examples
    --------
    >>> import pendula
    >>> sn, cn, dn, am = pendula.ellipj(0.5, 0.3)
    >>> round(float(sn), 15)
    0.474215622711821
    >>> K = float(pendula.ellipk(0.3))
    >>> [round(float(x), 12) for x in pendula.ellipj(K, 0.3)[:3]]   # sn, cn, dn at u = K
    [1.0, 0.0, 0.836660026534]
    """
    u = as_float(u, "u")
    m, mc = parameter(m, mc)
    if m.size == 1 and mc.size == 1:
        shape = np.broadcast_shapes(u.shape, m.shape)
        uf = np.ascontiguousarray(np.broadcast_to(u, shape), dtype=np.float64).reshape(-1)
        mf = m.reshape(1).astype(np.float64)
        mcf = mc.reshape(1).astype(np.float64)
    else:
        shape, (uf, mf, mcf) = flat(u, m, mc)
    if uf.size == 0:
        return tuple(np.empty(shape) for _ in range(4))
    # the kernel writes into these (no zero-filled copies); chunks keep Ctrl-C responsive
    sn, cn, dn, am = (np.empty(uf.size) for _ in range(4))
    status = 0
    for i in range(0, uf.size, CHUNK):
        j = min(i + CHUNK, uf.size)
        part = (mf, mcf) if mf.size == 1 else (mf[i:j], mcf[i:j])
        status = status or _kernel.ellipj_v(uf[i:j], *part, sn[i:j], cn[i:j], dn[i:j], am[i:j])
    if status != 0:  # pragma: no cover - the sizes above always agree
        raise RuntimeError("pendula kernel: ellipj_v got inconsistent sizes")
    warn_domain("ellipj", sn, uf, np.broadcast_to(mf, uf.shape), np.broadcast_to(mcf, uf.shape),
                what="outside the domain (or |u| beyond 2**48 half periods)")
    return tuple(shaped(a, shape) for a in (sn, cn, dn, am))

"""The quantum pendulum: Mathieu characteristic values and the transmon.

Mathieu's equation y'' + (a - 2 q cos 2z) y = 0 has solutions of period
pi or 2 pi only for the characteristic values a_n(q) (even solutions) and
b_n(q) (odd ones), and Floquet solutions exp(i nu z) P(z) of any real order
nu for λ_ν(q) (DLMF 28.2, 28.12).  The same numbers are the spectrum of
the quantum pendulum H = 4 E_C (n - n_g)^2 - E_J cos phi (the transmon,
Koch et al. 2007) and the stability boundaries of the pendulum on a
vibrating pivot (the Ince-Strutt chart).

Every value is computed in the Fortran kernel as an eigenvalue of a
symmetric tridiagonal Hill matrix, picked by its index with Sturm-sequence
bisection (so no value jumps to a neighbouring order), with an a-posteriori
bound on the truncation error.  Functions broadcast like numpy ufuncs and
return NaN with a RuntimeWarning outside their domain.
"""

from __future__ import annotations

import math
import warnings
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _kernel
from ._checks import as_float, count, flat, real, shaped
from ._optional import require

if TYPE_CHECKING:   # xarray is optional: named in annotations only
    import xarray

__all__ = ["mathieu_a", "mathieu_b", "mathieu_exponent", "mathieu_ce", "mathieu_se", "Transmon", "MATHIEU_MAX_Q"]

#: the largest |q| served (the Hill matrix grows as sqrt(|q|): 2e5 rows here)
MATHIEU_MAX_Q = 1.0e10
#: the largest order served
MATHIEU_MAX_ORDER = 1.0e8
#: the largest |q| of the double-double levels (the charge dispersion)
_DD_MAX_Q = 1.0e6

_STATUS_TEXT = {1: "outside the domain", 2: "with the truncation bound not met"}


def _warn_status(func: str, status: np.ndarray, stacklevel: int = 3) -> None:
    for code, text in _STATUS_TEXT.items():
        n = int(np.count_nonzero(status == code))
        if n:
            warnings.warn(f"{func}: {n} value(s) {text} gave NaN", RuntimeWarning, stacklevel=stacklevel + 1)


def _char(kind: int, name: str, nu, q, bound: bool):
    nu = as_float(nu, "nu")
    q = as_float(q, "q")
    shape, (nf, qf) = flat(nu, q)
    if nf.size == 0:
        empty = np.empty(shape)
        return (empty, np.empty(shape)) if bound else empty
    val, bnd, status = _kernel.mathieu_char_v(kind, nf, qf)
    # NaN in gives NaN out without a warning (numpy's way)
    _warn_status(name, np.where(np.isnan(nf) | np.isnan(qf), 0, status))
    if bound:
        return shaped(val, shape), shaped(bnd, shape)
    return shaped(val, shape)


def mathieu_a(nu: ArrayLike, q: ArrayLike, *, bound: bool = False
              ) -> NDArray[np.float64] | np.float64 | tuple[NDArray[np.float64] | np.float64, NDArray[np.float64] | np.float64]:
    """Characteristic value a_nu(q) of Mathieu's equation, any real order.

    For integer nu = n, the value for which y'' + (a - 2 q cos 2z) y = 0 has
    the even solution ce_n of period pi or 2 pi (DLMF 28.2(v)); for
    non-integer nu, the value λ_ν(q) of the Floquet solution of
    exponent nu (DLMF 28.12), the same as :func:`mathieu_b`.

    Parameters
    ----------
    nu : array_like
        Order, 0 <= nu <= 1e8 (integer or not).  Negative orders are refused
        (NaN with a RuntimeWarning): for non-integer nu, the value of -nu is
        the value of nu, so pass abs(nu).
    q : array_like
        Parameter, any sign, abs(q) <= 1e10.  Broadcast against `nu`.
    bound : bool, optional
        Also return the a-posteriori bound on the truncation error of each
        value (the residual of the truncated eigenvector in the infinite
        Hill matrix); the rounding error, a few eps times max(abs(a), abs(q)),
        comes on top.

    Returns
    -------
    a : ndarray or float
        a_nu(q); NaN with a RuntimeWarning outside the domain.
    bound : ndarray or float
        Only with ``bound=True``.

    See Also
    --------
    mathieu_b : the odd solutions' values.
    mathieu_exponent : the inverse, nu(a, q).
    Transmon : the quantum pendulum's levels.

    Examples
    --------
    >>> import pendula
    >>> round(float(pendula.mathieu_a(5, 21)), 9)
    37.462613226
    >>> a = pendula.mathieu_a([0, 0.5, 1], 1.0)
    >>> [round(float(x), 10) for x in a]
    [-0.4551386041, -0.3072853506, 1.8591080725]
    """
    return _char(1, "mathieu_a", nu, q, bound)


def mathieu_b(nu: ArrayLike, q: ArrayLike, *, bound: bool = False
              ) -> NDArray[np.float64] | np.float64 | tuple[NDArray[np.float64] | np.float64, NDArray[np.float64] | np.float64]:
    """Characteristic value b_nu(q) of Mathieu's equation, any real order.

    For integer nu = n >= 1, the value for which Mathieu's equation has the
    odd solution se_n of period pi or 2 pi (DLMF 28.2(v)); b_0 does not exist
    (NaN with a RuntimeWarning).  For non-integer nu, λ_ν(q), the same
    as :func:`mathieu_a`.

    Parameters
    ----------
    nu : array_like
        Order, 0 < nu <= 1e8.  Negative orders are refused (NaN with a
        RuntimeWarning).
    q : array_like
        Parameter, any sign, abs(q) <= 1e10.
    bound : bool, optional
        Also return the truncation bound (see :func:`mathieu_a`).

    Returns
    -------
    b : ndarray or float
        b_nu(q); NaN with a RuntimeWarning outside the domain.
    bound : ndarray or float
        Only with ``bound=True``.

    See Also
    --------
    mathieu_a : the even solutions' values.

    Examples
    --------
    >>> import pendula
    >>> round(float(pendula.mathieu_b(1, 1.0)), 10)
    -0.110248817
    >>> # a_0 < b_1 < a_1 < b_2 < a_2 for q > 0
    >>> import numpy as np
    >>> edges = [pendula.mathieu_a(0, 5.0), pendula.mathieu_b(1, 5.0),
    ...          pendula.mathieu_a(1, 5.0), pendula.mathieu_b(2, 5.0)]
    >>> bool(np.all(np.diff(edges) > 0))
    True
    """
    return _char(2, "mathieu_b", nu, q, bound)


def mathieu_exponent(a: ArrayLike, q: ArrayLike) -> NDArray[np.float64] | np.float64:
    """Characteristic exponent nu(a, q) of Mathieu's equation.

    The inverse of λ_ν(q): the order nu >= 0 whose Floquet solutions
    exp(+-i nu z) P(z) solve y'' + (a - 2 q cos 2z) y = 0 (DLMF 28.2(iii)).
    It is real exactly where every solution is bounded: in the bands
    a_n(abs(q)) <= a <= b_n+1(abs(q)), where n <= nu <= n + 1.  Between the bands
    (the instability tongues of the Ince-Strutt chart, and a < a_0) it is
    complex, and NaN is returned there without a warning: NaN is the answer
    "unstable", not an error.  Where a band is narrower than the rounding
    of ``a`` (large abs(q), low bands, whose width falls like exp(-4 sqrt(q))),
    a double cannot say where in the band it lies; such an ``a`` counts as
    an edge of the band, and NaN comes back.

    Parameters
    ----------
    a : array_like
        Characteristic value, abs(a) <= 1e16.
    q : array_like
        Parameter, any sign (nu depends on abs(q) only), abs(q) <= 1e10.

    Returns
    -------
    nu : ndarray or float
        The real exponent, or NaN where the solutions are unbounded; NaN
        with a RuntimeWarning outside the domain.

    See Also
    --------
    mathieu_a, mathieu_b : the band edges a_n(q), b_n(q).

    Examples
    --------
    >>> import pendula
    >>> a = pendula.mathieu_a(0.3, 2.0)
    >>> round(float(pendula.mathieu_exponent(a, 2.0)), 12)
    0.3
    >>> import numpy as np
    >>> bool(np.isnan(pendula.mathieu_exponent(0.0, 1.0)))   # a tongue
    True
    """
    a = as_float(a, "a")
    q = as_float(q, "q")
    shape, (af, qf) = flat(a, q)
    if af.size == 0:
        return np.empty(shape)
    nu, status = _kernel.mathieu_nu_v(af, qf)
    _warn_status("mathieu_exponent", np.where(np.isnan(af) | np.isnan(qf), 0, status))
    return shaped(nu, shape)


def _function(kind: int, name: str, n, q, z):
    n = count(n, "n", 1 if kind == 2 else 0, 10 ** 8)
    q = real(q, "q")
    z = as_float(z, "z")
    zf = np.ascontiguousarray(z, dtype=np.float64).reshape(-1)
    if zf.size == 0:
        return np.empty(z.shape), np.empty(z.shape)
    val, dval, status = _kernel.mathieu_function_v(kind, n, q, zf)
    _warn_status(name, np.full(1, status))
    return shaped(val, z.shape), shaped(dval, z.shape)


def mathieu_ce(n: int, q: float, z: ArrayLike) -> tuple[NDArray[np.float64] | np.float64, NDArray[np.float64] | np.float64]:
    """The even periodic Mathieu function ce_n(z, q) and its derivative.

    Normalised as in DLMF 28.2(vi) and 28.4(iii): the integral of ce_n^2
    over a period 2 pi is pi, and ce_n(0, q) > 0 (the sign of q = 0, carried
    by continuity).  z in radians.

    Parameters
    ----------
    n : int
        Order, n >= 0.
    q : float
        Parameter, any sign, abs(q) <= 1e10.
    z : array_like
        The points.

    Returns
    -------
    ce, dce : ndarray or float
        ce_n(z, q) and d ce_n / dz.  Absolutely accurate to a few eps (the
        Fourier coefficients have unit norm); where the function is
        exponentially small (near z = 0 or pi/2 for large abs(q)) that is not
        a relative accuracy.

    See Also
    --------
    mathieu_se : the odd functions.
    mathieu_a : the characteristic value.

    Examples
    --------
    >>> import math, pendula
    >>> ce, dce = pendula.mathieu_ce(0, 0.0, 1.0)   # 1/sqrt(2) at q = 0
    >>> round(float(ce), 12), float(dce)
    (0.707106781187, 0.0)
    """
    return _function(1, "mathieu_ce", n, q, z)


def mathieu_se(n: int, q: float, z: ArrayLike) -> tuple[NDArray[np.float64] | np.float64, NDArray[np.float64] | np.float64]:
    """The odd periodic Mathieu function se_n(z, q) and its derivative.

    Normalised as in DLMF 28.2(vi) and 28.4(iii): the integral of se_n^2
    over a period 2 pi is pi, and se_n'(0, q) > 0.  z in radians.

    Parameters
    ----------
    n : int
        Order, n >= 1.
    q : float
        Parameter, any sign, abs(q) <= 1e10.
    z : array_like
        The points.

    Returns
    -------
    se, dse : ndarray or float
        se_n(z, q) and d se_n / dz (absolutely accurate, see
        :func:`mathieu_ce`).

    See Also
    --------
    mathieu_ce : the even functions.
    mathieu_b : the characteristic value.

    Examples
    --------
    >>> import math, pendula
    >>> se, dse = pendula.mathieu_se(2, 0.0, math.pi / 4)   # sin 2z at q = 0
    >>> round(float(se), 15), round(float(dse), 15)
    (1.0, 0.0)
    """
    return _function(2, "mathieu_se", n, q, z)


def _spectrum(nu: np.ndarray, q: np.ndarray, n_levels: int, name: str) -> np.ndarray:
    """The lowest n_levels Hill levels (units of E_C) at each broadcast (nu, q),
    one kernel window per pair: shape ``broadcast shape + (n_levels,)``."""
    b = np.broadcast_arrays(nu, q)
    shape = b[0].shape
    nf = np.ascontiguousarray(b[0], dtype=np.float64).reshape(-1)
    qf = np.ascontiguousarray(b[1], dtype=np.float64).reshape(-1)
    if nf.size == 0:
        return np.empty(shape + (n_levels,))
    val, _, status = _kernel.mathieu_levels_v(n_levels, nf, qf)
    bad = (np.isnan(nf) | np.isnan(qf))[None, :]
    _warn_status(name, np.where(bad, 0, status), stacklevel=4)
    return val.T.reshape(shape + (n_levels,))


class Transmon:
    """The quantum pendulum H = 4 E_C (n - n_g)^2 - E_J cos phi.

    The Cooper-pair box and the transmon (Koch et al. 2007): its levels are
    E_m(n_g) = E_C lambda(q), the m-th eigenvalue of the Hill matrix of
    offset 2 n_g with q = -E_J / (2 E_C), that is E_C a_r(q) with the order
    r = 2 (n_g + k(m, n_g)) of Koch et al., section II.  Energies come in
    the units of E_J and E_C.

    Parameters
    ----------
    E_J : float
        Josephson energy, E_J >= 0 (E_J = 0 is the free rotor).
    E_C : float
        Charging energy, E_C > 0.
    n_g : float, optional
        Offset charge (in Cooper pairs, periodic with period 1).

    See Also
    --------
    mathieu_a : the characteristic values behind the levels
        (``pendula.plot.levels`` draws them against n_g).

    Examples
    --------
    >>> import pendula
    >>> t = pendula.Transmon(E_J=50.0, E_C=1.0)
    >>> t
    Transmon(E_J=50, E_C=1, n_g=0)
    >>> e = t.levels(3)                   # a_0, b_2, a_2 at q = -25
    >>> e.shape
    (3,)
    >>> bool(abs(e[0] - pendula.mathieu_a(0, -25.0)) < 1e-13)
    True
    """

    def __init__(self, E_J: float, E_C: float, n_g: float = 0.0) -> None:
        self.E_J = real(E_J, "E_J", lo=0.0)
        self.E_C = real(E_C, "E_C", lo=0.0, lo_open=True)
        if not self.E_J / self.E_C / 2.0 <= MATHIEU_MAX_Q:
            raise ValueError(f"E_J / E_C must be at most {2 * MATHIEU_MAX_Q:g}, got {self.E_J / self.E_C:g}")
        self.n_g = real(n_g, "n_g")

    def __repr__(self) -> str:
        return f"Transmon(E_J={self.E_J:g}, E_C={self.E_C:g}, n_g={self.n_g:g})"

    @classmethod
    def flux_tunable(cls, E_J_max: float, E_C: float, flux: float, asymmetry: float = 0.0,
                     n_g: float = 0.0) -> Transmon:
        """The split transmon (a SQUID of two junctions) at an external flux.

        E_J = E_J_max abs(cos(pi flux)) sqrt(1 + d^2 tan^2(pi flux)), with flux
        in flux quanta and d = (E_J1 - E_J2)/(E_J1 + E_J2) the junctions'
        asymmetry (Koch et al. 2007, eq. 2.16).

        Parameters
        ----------
        E_J_max : float
            E_J1 + E_J2, >= 0.
        E_C : float
            Charging energy, > 0.
        flux : float
            External flux in units of the flux quantum.
        asymmetry : float, optional
            d, 0 <= d <= 1 (default 0: equal junctions).
        n_g : float, optional
            Offset charge.

        Returns
        -------
        Transmon

        See Also
        --------
        Transmon : the fixed-E_J transmon it returns.

        Examples
        --------
        >>> import pendula
        >>> t = pendula.Transmon.flux_tunable(40.0, 1.0, 0.25, asymmetry=0.2)
        >>> round(t.E_J, 10)         # 40 cos(pi/4) sqrt(1 + 0.04)
        28.8444102037
        """
        e_max = real(E_J_max, "E_J_max", lo=0.0)
        f = real(flux, "flux")
        d = real(asymmetry, "asymmetry", lo=0.0, hi=1.0)
        # |cos x| sqrt(1 + d^2 tan^2 x) = sqrt(cos^2 x + d^2 sin^2 x): no division at cos x = 0
        c, s = math.cos(math.pi * f), math.sin(math.pi * f)
        return cls(e_max * math.sqrt(c * c + d * d * s * s), E_C, n_g)

    @property
    def q(self) -> float:
        """Mathieu's parameter q = -E_J / (2 E_C)."""
        return -self.E_J / (2.0 * self.E_C)

    def _ng(self, n_g) -> np.ndarray:
        return np.asarray(self.n_g if n_g is None else as_float(n_g, "n_g"), dtype=np.float64)

    def levels(self, n_levels: int = 5, n_g: ArrayLike | None = None) -> NDArray[np.float64]:
        """The lowest levels E_0 < E_1 < ... at the offset charge(s) n_g.

        Parameters
        ----------
        n_levels : int, optional
            How many levels (the first positional argument), at least 1.
        n_g : array_like, optional
            Offset charge(s); the transmon's own when omitted.

        Returns
        -------
        E : ndarray
            Shape ``np.shape(n_g) + (n_levels,)``: E_m(n_g) for m = 0 ..
            n_levels - 1, in the units of E_J and E_C.

        Examples
        --------
        >>> import pendula
        >>> rotor = pendula.Transmon(E_J=0.0, E_C=1.0, n_g=0.25)
        >>> rotor.levels(3).tolist()      # 4 E_C (n - n_g)^2 sorted
        [0.25, 2.25, 6.25]
        """
        c = count(n_levels, "n_levels", 1, 10 ** 6)
        ng = self._ng(n_g)
        lam = _spectrum(2.0 * ng, np.float64(self.q), c, "Transmon.levels")
        return self.E_C * lam

    def transition(self, m: int = 1, n_g: ArrayLike | None = None) -> NDArray[np.float64] | np.float64:
        """The transition energy E_m - E_0 at n_g.

        Parameters
        ----------
        m : int, optional
            Upper level, at least 1.
        n_g : array_like, optional
            Offset charge(s); the transmon's own when omitted.

        Returns
        -------
        E_m0 : ndarray or float

        Examples
        --------
        >>> import pendula
        >>> round(float(pendula.Transmon(50.0, 1.0).transition()), 6)
        18.941919
        """
        m = count(m, "m", 1, 10 ** 6)
        e = self.levels(m + 1, n_g)
        out = e[..., m] - e[..., 0]
        return out[()] if np.ndim(out) == 0 else out

    def anharmonicity(self, n_g: ArrayLike | None = None) -> NDArray[np.float64] | np.float64:
        """The anharmonicity alpha = E_12 - E_01 = E_2 - 2 E_1 + E_0.

        Tends to -E_C as E_J / E_C grows (Koch et al., section IV).

        Parameters
        ----------
        n_g : array_like, optional
            Offset charge(s); the transmon's own when omitted.

        Returns
        -------
        alpha : ndarray or float

        Examples
        --------
        >>> import pendula
        >>> t = pendula.Transmon(E_J=1000.0, E_C=1.0)
        >>> round(float(t.anharmonicity()), 3)
        -1.027
        """
        e = self.levels(3, n_g)
        out = (e[..., 2] - e[..., 1]) - (e[..., 1] - e[..., 0])
        return out[()] if np.ndim(out) == 0 else out

    def charge_dispersion(self, m: ArrayLike = 0) -> NDArray[np.float64] | np.float64:
        """The charge dispersion eps_m = E_m(n_g = 1/2) - E_m(n_g = 0).

        The width of the m-th band with the sign of Koch et al., eq. (2.5):
        positive for even m.  Both levels are computed to double-double
        precision (about 1e-31 of abs(q)) in the kernel, so the difference
        keeps full double precision even where it is 1e-15 of the levels,
        and 1e-10 relative while it is above about 1e-22 of them (for m = 0
        up to E_J/E_C of about 250); below that, NaN with a RuntimeWarning
        (:meth:`charge_dispersion_asymptotic` is then within a few per cent).

        Parameters
        ----------
        m : array_like of int, optional
            Level index (or indices), m >= 0.

        Returns
        -------
        eps : ndarray or float
            In the units of E_J and E_C; NaN (RuntimeWarning) where it is
            not resolved to 1e-10.

        Raises
        ------
        ValueError
            E_J / E_C above 2e6 (the double-double window's limit).

        Examples
        --------
        >>> import pendula
        >>> t = pendula.Transmon(E_J=50.0, E_C=1.0)
        >>> f"{float(t.charge_dispersion(0)):.8e}"   # b_1(25) - a_0(25)
        '5.61882628e-07'
        """
        mm = np.asarray(m)
        if mm.dtype.kind not in "iu" or np.any(mm < 0):
            raise TypeError("m must be a whole number >= 0 (or an array of them)")
        if -self.q > _DD_MAX_Q:
            raise ValueError(f"charge_dispersion: E_J / E_C must be at most {2 * _DD_MAX_Q:g}")
        mf = np.ascontiguousarray(mm, dtype=np.int32).reshape(-1)
        qf = np.full(mf.size, self.q)
        h0, l0, b0, s0 = _kernel.mathieu_level_dd_v(np.zeros(mf.size), qf, mf)
        h1, l1, b1, s1 = _kernel.mathieu_level_dd_v(np.ones(mf.size), qf, mf)
        _warn_status("Transmon.charge_dispersion", np.maximum(s0, s1))
        eps = (h1 - h0) + (l1 - l0)
        # a band narrower than the levels' double-double error is not
        # resolved (m = 0 beyond E_J/E_C of about 250): NaN, not a wrong digit
        blurred = (b0 + b1) > 1e-10 * np.abs(eps)
        if np.any(blurred & (s0 == 0) & (s1 == 0)):
            warnings.warn(f"Transmon.charge_dispersion: {int(np.count_nonzero(blurred))} value(s) below the "
                          "resolution of the double-double levels (about 1e-22 of the level) gave NaN; "
                          "see charge_dispersion_asymptotic", RuntimeWarning, stacklevel=2)
        eps = np.where(blurred, np.nan, eps) * self.E_C
        return shaped(eps, mm.shape)

    def charge_dispersion_asymptotic(self, m: int = 0) -> float:
        """Koch et al.'s asymptotic charge dispersion, eq. (2.5).

        eps_m ~ (-1)^m E_C 2^(4m+5) / m! sqrt(2/pi) (E_J/(2 E_C))^(m/2+3/4)
        exp(-sqrt(8 E_J/E_C)), valid for E_J >> E_C.

        Parameters
        ----------
        m : int, optional
            Level index, m >= 0.

        Returns
        -------
        eps : float

        Examples
        --------
        >>> import pendula
        >>> t = pendula.Transmon(E_J=50.0, E_C=1.0)
        >>> r = t.charge_dispersion_asymptotic(0) / t.charge_dispersion(0)
        >>> round(float(r), 3)
        1.047
        """
        m = count(m, "m", 0, 170)
        r = self.E_J / self.E_C
        return ((-1) ** m * self.E_C * 2.0 ** (4 * m + 5) / math.factorial(m) * math.sqrt(2.0 / math.pi)
                * (r / 2.0) ** (m / 2.0 + 0.75) * math.exp(-math.sqrt(8.0 * r)))

    def spectrum_vs_ng(self, n_g: ArrayLike, n_levels: int = 5) -> xarray.DataArray:
        """The levels against the offset charge, as an xarray DataArray.

        Parameters
        ----------
        n_g : array_like
            1-D offset charges.
        n_levels : int, optional
            How many levels.

        Returns
        -------
        E : xarray.DataArray
            Dimensions ``("n_g", "level")``.

        Examples
        --------
        >>> import pendula
        >>> da = pendula.Transmon(1.0, 1.0).spectrum_vs_ng([0, 0.25, 0.5], 2)
        >>> da.dims, da.shape
        (('n_g', 'level'), (3, 2))
        """
        xr = require("xarray", "xarray", "Transmon.spectrum_vs_ng")
        ng = as_float(n_g, "n_g")
        if ng.ndim != 1:
            raise ValueError("n_g must be one-dimensional")
        e = self.levels(n_levels, ng)
        return xr.DataArray(e, dims=("n_g", "level"),
                            coords={"n_g": ng, "level": np.arange(e.shape[-1])},
                            name="E", attrs={"E_J": self.E_J, "E_C": self.E_C})

    def spectrum_vs_ratio(self, ratio: ArrayLike, n_levels: int = 5,
                          n_g: float | None = None) -> xarray.DataArray:
        """The levels in units of E_C against E_J / E_C, as an xarray DataArray.

        Parameters
        ----------
        ratio : array_like
            1-D values of E_J / E_C (>= 0).
        n_levels : int, optional
            How many levels.
        n_g : float, optional
            Offset charge; the transmon's own when omitted.

        Returns
        -------
        E : xarray.DataArray
            E_m / E_C with dimensions ``("EJ_over_EC", "level")``.

        Examples
        --------
        >>> import pendula
        >>> da = pendula.Transmon(1.0, 1.0).spectrum_vs_ratio([0, 1, 10], 3)
        >>> da.sel(EJ_over_EC=0).values.tolist()
        [0.0, 4.0, 4.0]
        """
        xr = require("xarray", "xarray", "Transmon.spectrum_vs_ratio")
        r = as_float(ratio, "ratio")
        if r.ndim != 1:
            raise ValueError("ratio must be one-dimensional")
        if np.any(~(r >= 0)):
            raise ValueError("ratio (E_J / E_C) must be >= 0 and not NaN")
        c = count(n_levels, "n_levels", 1, 10 ** 6)
        ng = self.n_g if n_g is None else real(n_g, "n_g")
        lam = _spectrum(np.float64(2.0 * ng), -r / 2.0, c, "Transmon.spectrum_vs_ratio")
        return xr.DataArray(lam, dims=("EJ_over_EC", "level"),
                            coords={"EJ_over_EC": r, "level": np.arange(c)},
                            name="E_over_EC", attrs={"n_g": ng})

    def wavefunctions(self, n_levels: int = 5, n_g: float | None = None,
                      n_max: int | None = None) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """The eigenfunctions in the charge basis: psi_m(n), n = -n_max .. n_max.

        Real, unit norm, each with its largest component positive.

        Parameters
        ----------
        n_levels : int, optional
            How many levels (m = 0 .. n_levels - 1).
        n_g : float, optional
            Offset charge; the transmon's own when omitted.
        n_max : int, optional
            The largest charge abs(n) kept; by default grown until what lies
            beyond carries less than 1e-15 of each function's norm.

        Returns
        -------
        n : ndarray of int
            The charges -n_max .. n_max.
        psi : ndarray
            Shape ``(n_levels, 2 n_max + 1)``: psi[m, i], the amplitude of charge n_i in level m.

        Raises
        ------
        ValueError
            A given n_max leaves more than 1e-15 of a function's norm out.

        Examples
        --------
        >>> import numpy as np, pendula
        >>> n, psi = pendula.Transmon(20.0, 1.0).wavefunctions(2)
        >>> bool(np.allclose(psi @ psi.T, np.eye(2), atol=1e-14))
        True
        """
        c = count(n_levels, "n_levels", 1, 10 ** 5)
        ng = self.n_g if n_g is None else real(n_g, "n_g")
        grow = n_max is None
        nm = count(n_max, "n_max", 1, 10 ** 7) if n_max is not None else \
            int(2 * math.sqrt(self.E_J / self.E_C) + c + 16)
        p = math.floor(ng)   # the kernel's row k holds the charge n = p - k
        while True:
            val, vec, lost, status = _kernel.mathieu_level_vector_v(
                2 * nm + 1, np.full(c, 2.0 * ng), np.full(c, self.q), np.arange(c, dtype=np.int32), p - nm)
            if np.any(status != 0):
                raise ValueError("wavefunctions: the levels could not be computed for these parameters")
            if np.all(lost <= 1e-15):
                break
            if not grow:
                raise ValueError(f"n_max = {nm} leaves {float(lost.max()):.1e} of a wavefunction's norm out")
            nm *= 2
        # rows k = p - nm .. p + nm are the charges n = p - k: nm .. -nm
        return np.arange(-nm, nm + 1), vec.T[:, ::-1].copy()

    def wavefunctions_phase(self, phi: ArrayLike, n_levels: int = 5,
                            n_g: float | None = None) -> NDArray[np.complex128]:
        """The eigenfunctions in the phase basis: psi_m(phi) = sum_n psi_m(n) exp(i n phi) / sqrt(2 pi).

        Normalised on one period, abs(psi_m)^2 integrates to 1 over [-pi, pi].

        Parameters
        ----------
        phi : array_like
            The phases (radians).
        n_levels : int, optional
            How many levels.
        n_g : float, optional
            Offset charge; the transmon's own when omitted.

        Returns
        -------
        psi : ndarray of complex
            Shape ``(n_levels,) + np.shape(phi)``.

        See Also
        --------
        wavefunctions : the same in the charge basis.

        Examples
        --------
        >>> import numpy as np, pendula
        >>> phi = np.linspace(-np.pi, np.pi, 257)[:-1]
        >>> psi = pendula.Transmon(20.0, 1.0).wavefunctions_phase(phi, 1)
        >>> round(float(np.sum(abs(psi[0]) ** 2) * 2 * np.pi / 256), 12)
        1.0
        """
        p = as_float(phi, "phi")
        n, psi = self.wavefunctions(n_levels, n_g)
        return (psi @ np.exp(1j * np.outer(n, p.reshape(-1)))).reshape((psi.shape[0],) + p.shape) \
            / math.sqrt(2.0 * math.pi)

    def matrix_elements(self, operator: str, n_levels: int = 5, n_g: float | None = None) -> NDArray[np.float64]:
        """Matrix elements A_ij = (i, A j) between the lowest levels.

        Parameters
        ----------
        operator : {"n", "cos_phi"}
            The charge n (Cooper pairs) or cos phi.
        n_levels : int, optional
            How many levels.
        n_g : float, optional
            Offset charge; the transmon's own when omitted.

        Returns
        -------
        A : ndarray
            Shape ``(n_levels, n_levels)``, real symmetric.

        Examples
        --------
        >>> import pendula
        >>> t = pendula.Transmon(50.0, 1.0)
        >>> a = t.matrix_elements("n", 3)
        >>> bool(abs(a[0, 2]) < 1e-3 * abs(a[0, 1]))   # nearly a ladder
        True
        """
        if operator not in ("n", "cos_phi"):
            raise ValueError(f"operator must be 'n' or 'cos_phi', got {operator!r}")
        n, psi = self.wavefunctions(n_levels, n_g)
        if operator == "n":
            return (psi * n) @ psi.T
        shifted = psi[:, 1:] @ psi[:, :-1].T
        return 0.5 * (shifted + shifted.T)


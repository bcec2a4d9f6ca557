"""Argument checking shared by the public functions (private module).

Every public function converts its arguments with :func:`as_float`, which
accepts anything numeric (Python numbers, lists, numpy arrays of bool, int or
float) and rejects strings, bytes, complex numbers and object arrays with a
TypeError that names the argument.  Out-of-domain mathematics is not an error:
it gives NaN and one RuntimeWarning, as numpy does.
"""

from __future__ import annotations

import warnings

import numpy as np

_EPS = np.finfo(np.float64).eps


def as_float(x, name: str) -> np.ndarray:
    """``x`` as a float64 array; TypeError naming ``name`` for non-numbers."""
    if isinstance(x, (str, bytes)):
        raise TypeError(f"{name} must be a real number or an array of them, not {type(x).__name__}")
    try:
        arr = np.asarray(x)
    except Exception as exc:  # ragged lists and the like
        raise TypeError(f"{name} must be a real number or an array of them: {exc}") from None
    if arr.dtype.kind == "c":
        raise TypeError(f"{name} must be real; complex values are not supported")
    if arr.dtype.kind not in "biuf":
        raise TypeError(f"{name} must be a real number or an array of them, not dtype {arr.dtype}")
    return arr.astype(np.float64, copy=False)


def parameter(m, mc, m_name: str = "m", mc_name: str = "mc") -> tuple[np.ndarray, np.ndarray]:
    """The parameter as (m, mc) with mc = 1 - m, whichever of the two was given.

    When ``mc`` is given it defines the parameter (so that m = 1 - 1e-300 is
    representable); ``m`` may then be None, and if it is given it must agree
    with 1 - mc to rounding (4 eps), or ValueError.
    """
    if m is None and mc is None:
        raise TypeError(f"give the parameter {m_name} (or its complement {mc_name})")
    if mc is None:
        m = as_float(m, m_name)
        return m, 1.0 - m
    mc = as_float(mc, mc_name)
    if m is None:
        return 1.0 - mc, mc
    m = as_float(m, m_name)
    mb, mcb = np.broadcast_arrays(m, mc)
    finite = np.isfinite(mb) & np.isfinite(mcb)
    bad = finite & (np.abs(mb - (1.0 - mcb)) > 4 * _EPS * np.maximum(1.0, np.abs(mb)))
    if np.any(bad):
        raise ValueError(f"{m_name} and {mc_name} disagree: {mc_name} must be 1 - {m_name} "
                         f"(give only {mc_name} near {m_name} = 1)")
    return 1.0 - mcb, mcb


def flat(*arrays: np.ndarray) -> tuple[tuple[int, ...], list[np.ndarray]]:
    """Broadcast the arrays together; return the shape and C-contiguous 1-D copies."""
    try:
        b = np.broadcast_arrays(*arrays)
    except ValueError as exc:
        raise ValueError(f"arguments do not broadcast together: {exc}") from None
    shape = b[0].shape
    return shape, [np.ascontiguousarray(a, dtype=np.float64).reshape(-1) for a in b]


def shaped(out: np.ndarray, shape: tuple[int, ...]):
    """A kernel result reshaped; a 0-d result becomes a numpy scalar."""
    out = out.reshape(shape)
    return out[()] if out.ndim == 0 else out


def warn_domain(func: str, result: np.ndarray, *inputs: np.ndarray, what: str = "outside the domain") -> None:
    """One RuntimeWarning if NaN came out where no NaN went in.

    The common case (no NaN at all) costs one summation over the result."""
    if not np.isnan(np.add.reduce(result, axis=None)):
        return
    born = np.isnan(result)
    for x in inputs:
        born &= ~np.isnan(x)
    n = int(np.count_nonzero(born))
    if n:
        warnings.warn(f"{func}: {n} value(s) {what} gave NaN", RuntimeWarning, stacklevel=3)

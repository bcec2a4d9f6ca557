"""Argument checking shared by the public functions (private module).

One checker per kind of argument, used by every public function that takes
an argument of that kind, so that the same value gets the same verdict and
the same message everywhere (docs/source/bad_input.rst lists the limits):

=====================  =========================================================
checker                arguments
=====================  =========================================================
:func:`as_float`       arrays of reals (elliptic functions, times, states ...)
:func:`count`          whole numbers: ``samples``, ``n``, ``chunk_points``, sizes
:func:`threads`        ``threads`` (0 or 1 .. the kernel's limit)
:func:`real`           one real: a time (``t_max``, ``t_avg``, ``transient``)
:func:`tolerances`     ``rtol``, ``atol``
:func:`grid_values`    the values of a sweep axis (``over=``), ``torques``
:func:`angle`          ``theta0``, an event's ``level`` (|x| <= 2^52)
:func:`flag`           ``progress``, ``terminal``, ``measure``: True or False
:func:`choice`         one word of a fixed list (``window``, ``kind``)
:func:`counts`         a list of whole numbers (``sizes`` of the FFTW wisdom)
:func:`path`           a file or folder name (``out``, ``path``): str or os.PathLike
:func:`instance`       an object of one class (``scene``, ``client``)
=====================  =========================================================

:func:`as_float` accepts anything numeric (Python numbers, lists, numpy
arrays of bool, int or float) and rejects strings, bytes, complex numbers,
object arrays and masked arrays with masked values with a TypeError or
ValueError that names the argument.  The scalar checkers accept Python and
numpy numbers only: a bool, a string, bytes, a float where a whole number is
wanted (``samples=1.5``) are refused, never converted.  Out-of-domain
mathematics is not an error: it gives NaN and one RuntimeWarning, as numpy does.
"""

from __future__ import annotations

import math
import os
import warnings

import numpy as np

_EPS = np.finfo(np.float64).eps


def as_float(x, name: str) -> np.ndarray:
    """``x`` as a float64 array; TypeError naming ``name`` for non-numbers."""
    if isinstance(x, (str, bytes)):
        raise TypeError(f"{name} must be a real number or an array of them, not {type(x).__name__}")
    _no_mask(x, name)
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


#: the largest |theta0| anywhere (2^52: beyond it an angle has no fractional
#: digits left and a well index no meaning)
MAX_ANGLE = 2.0 ** 52
#: the most points of one sweep grid (absurd work is refused up front)
MAX_GRID_POINTS = 10 ** 8


def _no_mask(x, name: str) -> None:
    """A masked array with masked values is refused (numpy would drop the mask)."""
    if isinstance(x, np.ma.MaskedArray) and np.ma.count_masked(x):
        raise ValueError(f"{name}: masked values are not supported (fill them first, e.g. x.filled(np.nan))")


def _kind(x) -> str:
    return type(x).__name__


def count(x, name: str, lo: int = 0, hi: int | None = None) -> int:
    """A whole number lo <= x <= hi as int.

    Python and numpy integers only: a bool, a float (even 3.0), a string or
    bytes is a TypeError naming ``name``; out of range a ValueError stating the
    range."""
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, np.integer)):
        raise TypeError(f"{name} must be a whole number (int), not {_kind(x)} {x!r:.40}")
    x = int(x)
    if x < lo or (hi is not None and x > hi):
        rng = f"between {lo} and {hi}" if hi is not None else f"at least {lo}"
        raise ValueError(f"{name} must be {rng}, got {x}")
    return x


def _sweep_limits() -> tuple[int, float, float]:
    from . import _kernel
    lim = _kernel.sweep_limits_v()
    return int(lim[0]), float(lim[1]), float(lim[2])


def threads(x, name: str = "threads") -> int:
    """OpenMP threads of a kernel call: 0 (OpenMP's default: OMP_NUM_THREADS or
    all cores) or 1 .. the kernel's limit (256, pendula_sweep%sweep_max_threads)."""
    return count(x, name, 0, _sweep_limits()[0])


def real(x, name: str, lo: float | None = None, hi: float | None = None, lo_open: bool = False) -> float:
    """One finite real lo <= x <= hi (lo < x when ``lo_open``) as float.

    Python and numpy reals (ints included) only: a bool, a string, bytes, a
    complex number, an array is a TypeError naming ``name``."""
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a real number, not {_kind(x)} {x!r:.40}")
    try:
        v = float(x)
    except OverflowError:
        raise ValueError(f"{name} must be finite, got a {len(str(x))}-digit integer") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {v!r}")
    if lo is not None and (v < lo or (lo_open and v == lo)):
        raise ValueError(f"{name} must be {'>' if lo_open else '>='} {lo:g}, got {v!r}")
    if hi is not None and v > hi:
        raise ValueError(f"{name} must be at most {hi:g}, got {v!r}")
    return v


def duration(x, name: str, positive: bool = True) -> float:
    """A time of a sweep or I-V curve (``t_max``, ``t_avg``, ``transient``):
    finite, > 0 (or >= 0 when not ``positive``), at most the kernel's limit 1e8."""
    return real(x, name, 0.0, _sweep_limits()[1], lo_open=positive)


def tolerances(rtol, atol) -> tuple[float, float]:
    """The integrator's tolerances: 0 < rtol < 1, 0 <= atol < 1, both finite."""
    r = real(rtol, "rtol", 0.0, lo_open=True)
    a = real(atol, "atol", 0.0)
    if r >= 1.0:
        raise ValueError(f"rtol must be below 1, got {r!r}")
    if a >= 1.0:
        raise ValueError(f"atol must be below 1, got {a!r}")
    return r, a


def angle(x, name: str = "theta0") -> float:
    """An initial angle: a finite real with |x| <= 2^52."""
    return real(x, name, -MAX_ANGLE, MAX_ANGLE)


def grid_values(vals, name: str) -> np.ndarray:
    """The values of one grid axis: a non-empty 1-D list or array of finite
    reals (ints and floats; no bools, strings, bytes or masked values)."""
    if isinstance(vals, (str, bytes, bytearray)):
        raise TypeError(f"{name} must be a list of numbers, not {_kind(vals)}")
    _no_mask(vals, name)
    seq = vals if isinstance(vals, np.ndarray) else None
    if seq is None:
        items = list(vals) if isinstance(vals, (list, tuple, range)) else [vals]
        for v in items:
            if isinstance(v, (bool, np.bool_)) or not isinstance(v, (int, float, np.integer, np.floating)):
                raise TypeError(f"{name} must hold numbers only, not {_kind(v)} {v!r:.40}")
        try:
            a = np.array(items, dtype=float)
        except OverflowError:
            raise ValueError(f"{name} must hold finite numbers (an integer too large for a float)") from None
    else:
        if seq.dtype.kind not in "iuf":
            raise TypeError(f"{name} must hold real numbers, not dtype {seq.dtype}")
        a = np.asarray(seq, dtype=float)
    a = np.atleast_1d(a)
    if a.ndim != 1 or a.size == 0 or not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be a non-empty 1-D list of finite numbers")
    return a


def window(transient: float, t_avg: float, name: str = "t_avg") -> None:
    """An averaging window after a transient must be resolved by it:
    transient < transient + t_avg / 2 < transient + t_avg (else <v> would be 0
    or NaN as if decided)."""
    if not (transient < transient + 0.5 * t_avg < transient + t_avg):
        raise ValueError(f"{name} = {t_avg!r} is below the resolution of transient = {transient!r}: "
                         "the window cannot be told from the transient")


def flag(x, name: str) -> bool:
    """True or False (Python or numpy bool); anything else is a TypeError naming ``name``
    (``progress='no'`` is not taken as True)."""
    if not isinstance(x, (bool, np.bool_)):
        raise TypeError(f"{name} must be True or False, not {_kind(x)} {x!r:.40}")
    return bool(x)


def choice(x, name: str, options, allow_none: bool = False):
    """One word of ``options`` (or None when ``allow_none``): a non-word is a TypeError,
    an unknown word a ValueError, both naming ``name`` and the options."""
    if x is None and allow_none:
        return None
    known = ", ".join(repr(o) for o in options) + (" or None" if allow_none else "")
    if not isinstance(x, str):
        raise TypeError(f"{name} must be one of {known}, not {_kind(x)} {x!r:.40}")
    if x not in options:
        raise ValueError(f"{name} must be one of {known}, got {x!r:.40}")
    return x


def counts(xs, name: str, lo: int = 0, hi: int | None = None) -> list[int]:
    """A list (tuple, range, 1-D array) of whole numbers, each as :func:`count` checks it."""
    if isinstance(xs, np.ndarray):
        if xs.ndim != 1:
            raise TypeError(f"{name} must be a list of whole numbers, not a {xs.ndim}-D array")
        xs = list(xs)
    if not isinstance(xs, (list, tuple, range)):
        raise TypeError(f"{name} must be a list of whole numbers, not {_kind(xs)} {xs!r:.40}")
    return [count(x, name, lo, hi) for x in xs]


def path(x, name: str) -> "os.PathLike":
    """A file or folder name: a non-empty str or os.PathLike (not bytes, not a number) as a Path.

    An empty name is a ValueError (pathlib would read it as the current folder)."""
    import pathlib

    if isinstance(x, (bytes, bytearray)) or not isinstance(x, (str, os.PathLike)):
        raise TypeError(f"{name} must be a path (str or os.PathLike), not {_kind(x)} {x!r:.40}")
    text = os.fspath(x)
    if not isinstance(text, str):
        raise TypeError(f"{name} must be a path (str or os.PathLike), not a bytes path {x!r:.40}")
    if not text or "\0" in text:
        raise ValueError(f"{name} must be a non-empty path without NUL characters, got {text!r:.40}")
    return pathlib.Path(text)


def instance(x, name: str, cls, what: str | None = None):
    """``x`` if it is an instance of ``cls``, else a TypeError naming ``name`` (and ``what`` it should be)."""
    if not isinstance(x, cls):
        what = what or f"a {cls.__module__.split('.')[0]}.{cls.__name__}"
        raise TypeError(f"{name} must be {what}, not {_kind(x)} {x!r:.40}")
    return x


# ---------------------------------------------------------------- a user's force (simulate(force=...))

class Force:
    """A user's force as the kernel takes it: the C address of
    ``double f(double t, double theta, double v, const double *params)``, the
    params as a float64 array, the objects that must outlive the call, and the
    first exception a Python callable raised (the slow path)."""

    def __init__(self, address: int, params: np.ndarray, keep: tuple, errors: list):
        self.address, self.params, self.keep, self.errors = address, params, keep, errors

    def reraise(self) -> None:
        """Raise the first exception the Python callable raised, if any."""
        if self.errors:
            raise self.errors[0]


def force_args(f: Force | None) -> tuple[int, np.ndarray]:
    """The (address, params) a kernel call takes for a checked force, or for none (address 0)."""
    return (0, np.zeros(0)) if f is None else (f.address, f.params)


def force(f, params, name: str = "force") -> Force:
    """Check a user's force and its params (see :func:`pendula.simulate`): a ctypes function
    with argtypes (double, double, double, POINTER(double) or c_void_p) and restype double, a
    numba cfunc (the object or its ``.address``), an integer address, or a plain Python callable
    ``f(t, theta, v, params)`` (the slow path: the kernel calls back into Python)."""
    import ctypes
    if f is None:
        raise TypeError(f"{name} must be a C function pointer (ctypes, numba cfunc, address) or a callable, "
                        "got None")
    if params is None:
        arr = np.zeros(0)
    else:
        if isinstance(params, (str, bytes)):
            raise TypeError(f"{name}_params must be a sequence of real numbers, got {type(params).__name__}")
        arr = as_float(params, f"{name}_params")
        if arr.ndim > 1:
            raise ValueError(f"{name}_params must be a flat sequence of numbers, got shape {arr.shape}")
        arr = np.ascontiguousarray(arr.reshape(-1), dtype=np.float64)
        if not np.all(np.isfinite(arr)):
            raise ValueError(f"{name}_params must be finite numbers, got {params!r}")
    nparams = getattr(f, "nparams", None)     # how many params the force says it reads
    if nparams is not None and (isinstance(nparams, bool) or not isinstance(nparams, (int, np.integer))
                                or int(nparams) != arr.size):
        raise ValueError(f"{name}_params: the force reads {nparams!r} numbers (its nparams), got {arr.size}")
    errors: list = []
    proto = ctypes.CFUNCTYPE(ctypes.c_double, ctypes.c_double, ctypes.c_double, ctypes.c_double,
                             ctypes.POINTER(ctypes.c_double))
    if isinstance(f, ctypes._CFuncPtr):
        if f.restype is not ctypes.c_double or f.argtypes is None or len(f.argtypes) != 4 or \
                any(a is not ctypes.c_double for a in f.argtypes[:3]) or \
                f.argtypes[3] not in (ctypes.POINTER(ctypes.c_double), ctypes.c_void_p):
            raise TypeError(f"{name}: a ctypes function must have restype c_double and argtypes (c_double, "
                            "c_double, c_double, POINTER(c_double)): double f(double t, double theta, "
                            "double v, const double *params)")
        address = ctypes.cast(f, ctypes.c_void_p).value
        if not address:
            raise ValueError(f"{name}: a NULL ctypes function pointer (no function to call)")
        return Force(address, arr, (f,), errors)
    address = getattr(f, "address", None)
    if isinstance(address, (int, np.integer)) and not isinstance(address, bool) and hasattr(f, "ctypes"):
        return force(f.ctypes, params, name)       # a numba cfunc: its ctypes wrapper carries the signature
    if isinstance(f, (int, np.integer)) and not isinstance(f, bool):
        # the kernel takes the address as a C intptr_t: 0 < address < 2^63 (user space on every
        # 64-bit system lies far below it)
        if not 0 < int(f) < 2**63:
            raise ValueError(f"{name}: an address must be a positive integer below 2**63, got {f}")
        return Force(int(f), arr, (), errors)
    if not callable(f):
        raise TypeError(f"{name} must be a C function pointer (ctypes, numba cfunc, address) or a callable, "
                        f"got {type(f).__name__}")
    view = arr.copy()
    view.flags.writeable = False

    def slow(t, theta, v, _p):
        try:
            out = f(t, theta, v, view)
            # a real number only: a string, a bool, None or an array (even of one element, as
            # ``-p * v`` with p the params) is refused, never converted
            if isinstance(out, (bool, np.bool_)) or not isinstance(out, (int, float, np.integer, np.floating)):
                raise TypeError(f"{name} must return a real number (float), returned {_kind(out)} {out!r:.40}")
            return float(out)
        except BaseException as exc:  # noqa: BLE001 - re-raised by the caller after the run
            if not errors:
                errors.append(exc)
            return math.nan
    cb = proto(slow)
    return Force(ctypes.cast(cb, ctypes.c_void_p).value, arr, (cb, slow, view), errors)

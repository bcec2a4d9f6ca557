"""Harmonic spectra of theta(t) with FFTW, and the exact Fourier series.

The libration theta(t) = 8 sum_n q^(n+1/2) / ((2n+1)(1 + q^(2n+1))) sin((2n+1) w t)
has only odd harmonics of w = pi sqrt(eps) / (2K); as v0 -> 2 the nome q -> 1
and more of them stand out (Suzuki & Suzuki, sections 2.4 and 6).  A rotation
theta = w t + 4 sum_n q^n / (n (1 + q^(2n))) sin(n w t) has all of them.
"""

from __future__ import annotations

import atexit
import collections
import contextlib
import functools
import math
import os
import threading
import warnings
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Literal, NamedTuple, Protocol

import numpy as np
from numpy.typing import ArrayLike

from . import _checks, _interrupt, _kernel
from ._checks import as_float
from ._files import atomic_path

if TYPE_CHECKING:   # xarray is optional: named in annotations only
    import xarray

#: the longest record a spectrum or a wisdom plan takes (2^27 samples: 1 GiB
#: per signal); longer is refused up front
MAX_SAMPLES = 1 << 27

__all__ = ["Spectrum", "spectrum", "spectra", "fourier_series", "FourierSeries", "odd_harmonics_above",
           "precompute_wisdom", "wisdom_path"]

_WINDOWS = {None: 0, "none": 0, "hann": 1}

# FFTW plans by (length, measured): made once, kept for the process (at most
# _MAX_PLANS lengths).  FFTW's planner (making and destroying plans) is not
# thread-safe, so both happen under _PLAN_LOCK; executing a plan on new arrays
# is thread-safe and runs without the lock (and without the GIL).  A plan is
# counted while a call uses it: evicting a plan in use only retires it, and
# the last user frees it (without this, one thread could free a plan between
# another's look-up and its execution: a segfault).
class _Plan:
    __slots__ = ("handle", "users", "retired")

    def __init__(self, handle: int):
        self.handle = handle
        self.users = 0
        self.retired = False


_PLANS: "collections.OrderedDict[tuple[int, bool], _Plan]" = collections.OrderedDict()
_PLAN_LOCK = threading.Lock()
_MAX_PLANS = 16


# FFTW wisdom (measured plans) is kept per machine in a cache file, loaded once
# per process before the first plan; `pendula wisdom` precomputes it.
_WISDOM_LOADED = False


def wisdom_path() -> Path:
    """The FFTW wisdom cache file.

    Returns
    -------
    pathlib.Path
        $PENDULA_WISDOM, else $XDG_CACHE_HOME/pendula/fftw-wisdom, else
        ~/.cache/pendula/fftw-wisdom (the file need not exist).

    See Also
    --------
    precompute_wisdom : writes it.

    Examples
    --------
    >>> import pendula
    >>> pendula.wisdom_path().name
    'fftw-wisdom'
    """
    env = os.environ.get("PENDULA_WISDOM")
    if env:
        return Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "pendula" / "fftw-wisdom"


def _load_wisdom_locked() -> None:
    global _WISDOM_LOADED
    if _WISDOM_LOADED:
        return
    _WISDOM_LOADED = True
    path = wisdom_path()
    try:
        if not path.is_file():
            return
        ok = _kernel.spectrum_wisdom_v(str(path), 0)
    except (OSError, ValueError, UnicodeError) as exc:     # unreadable path: plan without it
        warnings.warn(f"pendula: FFTW wisdom {path} ignored ({exc})", RuntimeWarning, stacklevel=4)
        return
    if not ok:
        warnings.warn(f"pendula: FFTW wisdom {path} is corrupt or from another FFTW; ignored "
                      "(rerun `pendula wisdom` to remake it)", RuntimeWarning, stacklevel=4)


def precompute_wisdom(sizes: Iterable[int] | None = None, path: str | os.PathLike[str] | None = None,
                      progress: bool = False) -> Path:
    """Measure FFTW plans for the given record lengths and save the wisdom.

    Later processes load it before their first spectrum and then use the
    measured plans without paying for the planning (``measure=False`` uses a
    measured plan when the wisdom has one for that length, else an estimated
    one).  This is what ``pendula wisdom`` runs.

    Parameters
    ----------
    sizes : iterable of int, optional
        Record lengths (default: powers of two 2^6 .. 2^20, and 3 * 2^k).
    path : str or pathlib.Path, optional
        Where to save (default: `wisdom_path()`).
    progress : bool, optional
        Print each length as it is planned.

    Returns
    -------
    pathlib.Path
        The file written (under a temporary name, then renamed).

    Raises
    ------
    TypeError, ValueError
        A size that is not a whole number between 4 and 2^27 (``sizes`` must
        be a list), a ``path`` that is not a str or os.PathLike, a
        ``progress`` that is not True or False.
    MemoryError
        If FFTW cannot plan a length.
    OSError
        ``path`` names something other than a regular file (a device such as
        /dev/full is never replaced), or its folder does not exist (only the
        default cache folder is created), or the write failed; the file is
        then left as it was and no temporary file remains.

    Notes
    -----
    Measured planning stops after 10 s per length with the best plan found
    (FFTW's time limit), so every length costs at most that.

    See Also
    --------
    wisdom_path : the default file.
    spectra : uses the wisdom.

    Examples
    --------
    >>> import pathlib, tempfile, pendula
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = pendula.precompute_wisdom([64, 128], path=pathlib.Path(d) / "wisdom")
    ...     print(p.name, p.stat().st_size > 0)
    wisdom True
    """
    if sizes is None:
        sizes = [1 << k for k in range(6, 21)] + [3 << k for k in range(5, 18)]
    sizes = sorted(set(_checks.counts(sizes, "sizes", 4, MAX_SAMPLES)))
    progress = _checks.flag(progress, "progress")
    if path is not None:
        path = _checks.path(path, "path")
    else:
        path = wisdom_path()
        path.parent.mkdir(parents=True, exist_ok=True)    # the cache folder only
    with atomic_path(path) as tmp:
        with _PLAN_LOCK:
            _load_wisdom_locked()
            for n in sizes:
                if progress:
                    print(f"  planning {n} samples", flush=True)
                cancel = _interrupt.cancel_flag()
                handle = int(_interrupt.call(_kernel.spectrum_plan_v, n, 1, cancel=cancel))
                if handle == 0:
                    raise MemoryError(f"FFTW could not plan a transform of {n} samples")
                _kernel.spectrum_plan_free_v(handle)
            if not _kernel.spectrum_wisdom_v(str(tmp), 1):
                raise OSError(f"could not write FFTW wisdom to {path}")
    return Path(path)


def wisdom_main(args) -> int:
    """``pendula wisdom [SIZES ...] [--path FILE]``."""
    import time

    import sys

    t0 = time.perf_counter()
    try:
        path = precompute_wisdom(args.sizes or None, args.path, progress=True)
    except (ValueError, TypeError, MemoryError) as exc:
        print(f"pendula wisdom: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:
        where = f"{exc.filename}: " if exc.filename else ""
        print(f"pendula wisdom: cannot write the wisdom: {where}{exc.strerror or exc}", file=sys.stderr)
        return 5
    print(f"FFTW wisdom saved to {path} ({time.perf_counter() - t0:.1f} s of planning)")
    return 0


@contextlib.contextmanager
def _plan(n: int, measure: bool):
    """The plan handle for n samples, kept alive for the duration of the block."""
    key = (n, bool(measure))
    with _PLAN_LOCK:
        _load_wisdom_locked()
        entry = _PLANS.get(key)
        if entry is None:
            while len(_PLANS) >= _MAX_PLANS:
                _, old = _PLANS.popitem(last=False)
                old.retired = True
                if old.users == 0:
                    _kernel.spectrum_plan_free_v(old.handle)
            cancel = _interrupt.cancel_flag()
            handle = int(_interrupt.call(_kernel.spectrum_plan_v, n, int(bool(measure)), cancel=cancel,
                                         long=bool(measure)))
            if handle == 0:
                raise MemoryError(f"FFTW could not plan a transform of {n} samples")
            entry = _PLANS[key] = _Plan(handle)
        else:
            _PLANS.move_to_end(key)
        entry.users += 1
    try:
        yield entry.handle
    finally:
        with _PLAN_LOCK:
            entry.users -= 1
            if entry.retired and entry.users == 0:
                _kernel.spectrum_plan_free_v(entry.handle)


@atexit.register
def _free_plans() -> None:  # pragma: no cover - runs at interpreter exit
    with _PLAN_LOCK:
        for entry in _PLANS.values():
            entry.retired = True
            if entry.users == 0:
                _kernel.spectrum_plan_free_v(entry.handle)
        _PLANS.clear()


@dataclass
class Spectrum:
    """A one-sided power spectrum: what :func:`spectrum` and :func:`spectra` return.

    Attributes
    ----------
    omega : ndarray
        Angular frequencies 2 pi k / (n dt), k = 0 .. n/2.
    power : ndarray
        The squared amplitude of each line, normalised so that a sin(w t) over
        whole periods has amplitude a.
    amplitude : ndarray
        The square root of `power`.
    window : str or None
        The window applied, or None.
    fundamental : float
        The angular frequency of the strongest non-constant line, refined
        between bins (NaN with a RuntimeWarning for a signal without one).

    See Also
    --------
    spectrum, spectra : make it.
    odd_harmonics_above : the odd harmonics that stand out.

    Examples
    --------
    >>> import numpy as np, pendula
    >>> t = np.linspace(0, 8 * np.pi, 256, endpoint=False)
    >>> s = pendula.spectrum(t, np.sin(t))
    >>> s.fundamental, float(s.amplitude.max())
    (1.0, 1.0)
    """

    omega: np.ndarray
    power: np.ndarray
    window: str | None

    def to_xarray(self) -> xarray.Dataset:
        """The spectrum as an :class:`xarray.Dataset` along ``omega``, with CF attributes.

        Returns
        -------
        xarray.Dataset
            ``power`` and ``amplitude`` on the dimension ``omega``; the window as an attribute.

        Examples
        --------
        >>> import numpy as np, pendula
        >>> t = np.arange(64) * 0.1
        >>> ds = pendula.spectrum(t, np.sin(2 * np.pi * t / 6.4)).to_xarray()
        >>> ds.power.attrs["long_name"]
        'one-sided power |A_k|^2'
        """
        from ._optional import require
        xr = require("xarray", "xarray", "Spectrum.to_xarray")
        return xr.Dataset(
            {"power": ("omega", self.power, {"long_name": "one-sided power |A_k|^2", "units": "rad2"}),
             "amplitude": ("omega", self.amplitude, {"long_name": "amplitude |A_k|", "units": "rad"})},
            coords={"omega": ("omega", self.omega, {"long_name": "angular frequency", "units": "rad s-1"})},
            attrs={"window": self.window or "none"})

    @property
    def amplitude(self) -> np.ndarray:
        """The amplitude of each line: the square root of `power`."""
        return np.sqrt(self.power)

    def __repr__(self) -> str:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            w = self.fundamental if self.power.size >= 2 else math.nan
        top = float(self.omega[-1]) if self.omega.size else math.nan
        return (f"Spectrum({self.omega.size} lines up to omega={top:.4g}, fundamental={w:.6g}, "
                f"window={self.window!r})")

    @functools.cached_property
    def fundamental(self) -> float:
        """Angular frequency of the strongest non-constant line, refined by
        quadratic interpolation of log power around the peak bin (exact when
        the record spans a whole number of periods).

        NaN with a RuntimeWarning when the signal has no fundamental: a
        non-finite spectrum (NaN or inf in the signal), or no line above the
        rounding floor (a constant or zero signal).
        """
        p = self.power
        if p.size < 2 or not np.all(np.isfinite(p)):
            warnings.warn("spectrum: no fundamental (the signal is not finite)",
                          RuntimeWarning, stacklevel=2)
            return math.nan
        k = int(np.argmax(p[1:])) + 1
        # ms bounds the mean square (Parseval, within a factor 2); the FFT's
        # rounding floor for a constant is an amplitude of a few eps of the
        # signal's size (growing like log n), so a strongest line below 1e3 eps
        # of the RMS is rounding, not a line.
        ms = np.sum(p)
        if not p[k] > (1e3 * np.finfo(float).eps) ** 2 * ms:
            warnings.warn("spectrum: no fundamental (a constant signal: no line above rounding)",
                          RuntimeWarning, stacklevel=2)
            return math.nan
        if 1 < k < p.size - 1 and p[k - 1] > 0 and p[k + 1] > 0 and p[k] > 0:
            a, b, c = np.log(p[k - 1]), np.log(p[k]), np.log(p[k + 1])
            den = a - 2 * b + c
            delta = 0.5 * (a - c) / den if den != 0 else 0.0
            # whole periods: the neighbours are at the numerical floor, no refinement
            if max(p[k - 1], p[k + 1]) < 1e-20 * p[k]:
                delta = 0.0
        else:
            delta = 0.0
        dw = self.omega[1] - self.omega[0]
        return float(self.omega[k] + delta * dw)

    def harmonics(self, n: int) -> np.ndarray:
        """Amplitudes of the first n odd harmonics w, 3w, 5w, ... of the fundamental.

        The lines of a libration, read at the nearest bins.

        Parameters
        ----------
        n : int
            How many (n >= 1).

        Returns
        -------
        ndarray
            n amplitudes; NaN beyond the Nyquist frequency, and all NaN (with a
            RuntimeWarning) when the signal has no fundamental.

        Raises
        ------
        TypeError
            If `n` is not a whole number (a bool or a float is refused).
        ValueError
            If `n` is below 1.
        """
        n = _checks.count(n, "n", 1)
        dw = self.omega[1] - self.omega[0]
        out = np.full(n, np.nan)
        if not math.isfinite(self.fundamental):
            warnings.warn("spectrum: no fundamental, so no harmonics (NaN)", RuntimeWarning, stacklevel=2)
            return out
        bins = np.rint((2 * np.arange(n) + 1) * self.fundamental / dw).astype(np.int64)
        inside = bins < self.power.size
        out[inside] = np.sqrt(self.power[bins[inside]])
        return out


def _uniform_step(t: np.ndarray) -> float:
    if t.ndim != 1 or t.size < 4:
        raise ValueError("t must be a 1-D array of at least 4 samples")
    if not np.all(np.isfinite(t)):
        raise ValueError("t must be finite")
    d = np.diff(t)
    dt = (t[-1] - t[0]) / (t.size - 1)
    # max |d - dt| from the extremes of d (two reductions, no temporaries)
    dev = max(float(d.max()) - dt, dt - float(d.min()))
    if not dt > 0 or not dev <= 1e-9 * abs(dt) * max(1.0, t.size / 1e3):
        raise ValueError("t must be increasing with a uniform spacing (resample first)")
    return float(dt)


def spectra(t: ArrayLike, signals: ArrayLike, window: Literal["hann", "none"] | None = None,
            measure: bool = False) -> list[Spectrum]:
    """Power spectra of many signals on one time grid: one FFTW plan, reused.

    Parameters
    ----------
    t : array_like, shape (n,)
        Uniformly spaced times.
    signals : array_like, shape (m, n) or (n,)
        NaN in a signal gives NaN in its spectrum (as numpy.fft does).
        m = 0 (no signals) gives an empty list.
    window : {None, 'hann'}
        A window applied before the transform.
    measure : bool
        Plan with FFTW_MEASURE (~25 s of planning for 2^20 samples here, then
        transforms about twice as fast).  Without it, a measured plan is still
        used when the machine's wisdom file has one for this length (made once
        by ``pendula wisdom``, see `precompute_wisdom`), else FFTW_ESTIMATE.
        Plans are kept for the process, per length, so only the first call of
        a length pays.  Safe to call from several threads at once.

    Returns
    -------
    list of Spectrum
        One per signal (an empty list for m = 0).

    Raises
    ------
    ValueError
        Fewer than 4 samples, non-uniform or non-finite t, mismatched shapes,
        an unknown window.
    TypeError
        For a string, complex or object argument.

    See Also
    --------
    spectrum : one signal.
    numpy.fft.rfft : the peer.

    Examples
    --------
    >>> import numpy as np, pendula
    >>> t = np.linspace(0, 8 * np.pi, 256, endpoint=False)
    >>> specs = pendula.spectra(t, np.vstack([np.sin(t), 2 * np.sin(3 * t)]))
    >>> [round(s.fundamental, 12) for s in specs]
    [1.0, 3.0]
    """
    t = as_float(t, "t")
    dt = _uniform_step(t)
    x = as_float(signals, "signals")
    if x.ndim == 1:
        x = x[None, :]
    if x.ndim != 2 or x.shape[1] != t.size:
        raise ValueError(f"signals must have shape (m, {t.size}) to match t, got {x.shape}")
    window = _checks.choice(window, "window", ("hann", "none"), allow_none=True)
    n = t.size
    if n > MAX_SAMPLES:
        raise ValueError(f"t: at most 2^27 samples, got {n}")
    measure = _checks.flag(measure, "measure")
    if x.shape[0] == 0:                         # no signals in, no spectra out
        return []
    cols = np.asfortranarray(x.T)
    with _plan(n, measure) as handle:
        cancel = _interrupt.cancel_flag()
        omega, power, status = _interrupt.call(_kernel.spectra_v, handle, cols, dt, _WINDOWS[window], n // 2 + 1,
                                               cancel, cancel=cancel, long=cols.size > 1 << 22)
    if status:
        raise RuntimeError(f"pendula kernel: spectrum status {status}")
    finite_in = np.all(np.isfinite(x), axis=1)
    if np.any(~np.all(np.isfinite(power), axis=0) & finite_in):
        warnings.warn("spectra: |A|^2 overflowed for a finite signal (values near 1e154 or beyond): inf",
                      RuntimeWarning, stacklevel=2)
    win = None if window in (None, "none") else window
    return [Spectrum(omega, power[:, j], win) for j in range(x.shape[0])]


class _Sampled(Protocol):
    """Anything with uniformly spaced times ``t`` and a signal ``theta``: a :class:`~pendula.Trajectory`."""

    t: np.ndarray
    theta: np.ndarray


def spectrum(t: ArrayLike | _Sampled, theta: ArrayLike | None = None,
             window: Literal["hann", "none"] | None = None) -> Spectrum:
    """Power spectrum of theta(t) against angular frequency (FFTW).

    Parameters
    ----------
    t : array_like, shape (n,), or Trajectory
        Uniformly spaced times (n >= 4); or a :class:`~pendula.Trajectory`
        (anything with ``t`` and ``theta``), whose theta(t) is then the signal.
    theta : array_like, shape (n,), optional
        The signal (not given when `t` is a Trajectory).
    window : {None, 'hann'}
        A window applied before the transform.

    Returns
    -------
    Spectrum
        The one-sided power spectrum.

    Raises
    ------
    ValueError
        Fewer than 4 samples, non-uniform or non-finite t, mismatched shapes,
        an unknown window.
    TypeError
        For a string, complex or object argument; `theta` missing with times,
        or given with a Trajectory.

    See Also
    --------
    spectra : many signals with one plan.
    Trajectory.spectrum : the same, as a method.
    fourier_series : the exact amplitudes of the pendulum's lines.

    Examples
    --------
    >>> import numpy as np, pendula
    >>> T = pendula.orbit(0.0, 1.9).period
    >>> t = np.arange(4096) * (8 * T / 4096)          # eight whole periods
    >>> theta, v = pendula.exact_motion(0.0, 1.9, 1.0, t)
    >>> s = pendula.spectrum(t, theta)
    >>> round(s.fundamental * T / (2 * np.pi), 12)
    1.0

    A trajectory is taken whole:

    >>> tr = pendula.simulate(pendula.Scene(v0=1.9), t)
    >>> round(pendula.spectrum(tr).fundamental * T / (2 * np.pi), 12)
    1.0
    """
    if hasattr(t, "t") and hasattr(t, "theta") and not isinstance(t, np.ndarray):
        if theta is not None:
            raise TypeError("spectrum: give a Trajectory alone, or the times and the signal "
                            "(spectrum(tr) or spectrum(t, theta))")
        t, theta = t.t, t.theta
    elif theta is None:
        raise TypeError("spectrum: parameter 'theta' is missing (spectrum(t, theta), or spectrum(tr) "
                        "for a Trajectory)")
    return spectra(t, theta, window)[0]


class FourierSeries(NamedTuple):
    """The exact Fourier series of an orbit: what :func:`fourier_series` returns.

    A named tuple, so ``omega, amplitudes = fourier_series(...)`` unpacks as before.

    Attributes
    ----------
    omega : float
        The angular frequency 2 pi / T of the orbit.
    amplitudes : numpy.ndarray
        The amplitudes of the odd harmonics (2j+1) omega of a libration, or of
        every harmonic j omega of a rotation.

    See Also
    --------
    fourier_series : makes it.
    Spectrum.harmonics : the measured amplitudes, to compare.

    Examples
    --------
    >>> import pendula
    >>> fs = pendula.fourier_series(0.0, 1.0, 1.0, 3)
    >>> omega, amplitudes = fs
    >>> fs.omega == omega, len(fs.amplitudes)
    (True, 3)
    """

    omega: float
    amplitudes: np.ndarray

    def __repr__(self) -> str:
        a = np.abs(np.asarray(self.amplitudes))
        top = f", largest {a.max():.6g}" if a.size else ""
        return f"FourierSeries(omega={self.omega:.10g}, {a.size} amplitudes{top})"


def fourier_series(theta0: float, v0: float, eps: float = 1.0, n: int = 10) -> FourierSeries:
    """The exact Fourier series of the orbit: a named pair (omega, amplitudes).

    Libration: amplitudes b_j = 8 q^(j+1/2) / ((2j+1)(1 + q^(2j+1))) of the odd
    harmonics (2j+1) omega, j = 0..n-1, omega = pi sqrt(eps) / (2K(k^2)).
    Rotation: amplitudes c_j = 4 q^j / (j (1 + q^(2j))) of all harmonics j omega,
    j = 1..n, omega = pi k sqrt(eps) / K(1/k^2), theta = omega t + sum c_j sin(j omega t).
    q is the nome of the parameter (k^2 or 1/k^2).  (Phases: for an orbit through
    theta = 0 at t = 0.)

    Parameters
    ----------
    theta0, v0 : float
        A state on the orbit.
    eps : float, optional
        g / l (default 1).
    n : int, optional
        Number of amplitudes (>= 1).

    Returns
    -------
    FourierSeries
        A named tuple: ``omega``, the angular frequency 2 pi / T, and
        ``amplitudes``, n amplitudes as above.

    Raises
    ------
    TypeError
        If `n` is not a whole number (a bool or a float is refused).
    ValueError
        If `n` is below 1, or the orbit is the separatrix
        (infinite period).

    See Also
    --------
    spectrum : the measured spectrum.
    nome : the q of the series.

    Examples
    --------
    >>> import pendula
    >>> fs = pendula.fourier_series(0.0, 1.9, 1.0, 4)
    >>> round(fs.omega, 12), fs.amplitudes.round(6).tolist()
    (0.606482438404, [2.637235, 0.141741, 0.012079, 0.001222])
    >>> omega, b = fs                                  # unpacks as a pair
    """
    from .elliptic import nome
    from .systems.rigid import orbit

    n = _checks.count(n, "n", 1)
    o = orbit(theta0, v0, eps)
    if o.regime not in ("libration", "rotation"):
        raise ValueError(f"the {o.regime} orbit has no Fourier series (infinite period)")
    q = float(nome(o.m, o.mc))
    j = np.arange(n, dtype=float)
    if o.regime == "libration":
        amps = 8 * q ** (j + 0.5) / ((2 * j + 1) * (1 + q ** (2 * j + 1)))
    else:
        j = j + 1
        amps = 4 * q**j / (j * (1 + q ** (2 * j)))
    return FourierSeries(o.omega, amps)


def odd_harmonics_above(spec: Spectrum, threshold: float = 1e-6, n_max: int = 50) -> list[int]:
    """The odd harmonics (1, 3, 5, ...) whose power exceeds threshold times the fundamental's.

    Parameters
    ----------
    spec : Spectrum
        A spectrum with a fundamental.
    threshold : float, optional
        The fraction of the fundamental's power (default 1e-6).
    n_max : int, optional
        How many odd harmonics to look at.

    Returns
    -------
    list of int
        The harmonic numbers, in increasing order.

    Raises
    ------
    TypeError, ValueError
        A `spec` that is not a Spectrum, a `threshold` that is not a real
        >= 0, an `n_max` that is not a whole number >= 1.

    See Also
    --------
    Spectrum.harmonics : their amplitudes.

    Examples
    --------
    >>> import numpy as np, pendula
    >>> T = pendula.orbit(0.0, 1.9).period
    >>> t = np.arange(4096) * (8 * T / 4096)
    >>> pendula.odd_harmonics_above(pendula.spectrum(t, pendula.exact_motion(0.0, 1.9, 1.0, t)[0]))
    [1, 3, 5]
    """
    _checks.instance(spec, "spec", Spectrum, "a pendula.Spectrum")
    threshold = _checks.real(threshold, "threshold", 0.0)
    n_max = _checks.count(n_max, "n_max", 1)
    a = spec.harmonics(n_max)
    p = a**2
    return [2 * j + 1 for j in range(n_max) if np.isfinite(p[j]) and p[j] > threshold * p[0]]

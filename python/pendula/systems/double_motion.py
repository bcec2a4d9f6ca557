"""The double pendulum integrated: its path with the energy error, the
flip-time map over the initial angles, and the Lyapunov spectrum.

The kernel integrates Hamilton's equations in the canonical coordinates
(theta1, theta2, p1, p2) (``kernel/models/pendula_double.f90``) on the
n-dimensional core (``kernel/integrators/pendula_ode.f90``): Gauss-Legendre
collocation of order 6 or 4 (symplectic: with no damping the energy error
stays bounded and does not drift) or DOP853 with error control (the damped
case, or any case when asked).  The exact parts (the normal modes, the
region that cannot flip) are in :mod:`pendula.systems.double`.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from .. import _checks, _interrupt, _kernel
from .._optional import require
from .contract import require_fields
from .double import DoublePendulumModes, _arms, double_pendulum_modes, flip_forbidden

if TYPE_CHECKING:   # xarray and distributed are optional: named in annotations only
    import distributed
    import xarray

__all__ = ["DoublePendulum", "FlipMap", "LyapunovSpectrum", "DOUBLE_METHODS"]

#: the integrators of :meth:`DoublePendulum.simulate`
DOUBLE_METHODS = ("auto", "gauss6", "gauss4", "dop853")
_METHOD_CODE = {"dop853": 1, "gauss4": 2, "gauss6": 3}
_STATUS = {1: "the step dt must be positive and finite", 2: "rtol must be > 0 and atol >= 0",
           3: "unknown method", 5: "step size underflow (the tolerance may be unreachable)",
           6: "the state became non-finite",
           7: "the run needs more steps than the work limit (1e8 adaptive, 2e9 fixed-step): "
              "shorten the span, or give a larger dt or rtol",
           8: "interrupted", 20: "t must be ascending and >= 0"}


def _fail(what: str, status: int) -> ValueError:
    return ValueError(f"{what}: {_STATUS.get(int(status), f'kernel status {status}')}")


def _flip_args(theta1, theta2, t_max, rtol, atol, agree):
    """The flip map's checked axes (1-D, in [-pi, pi]) and search parameters."""
    a1 = _checks.as_float(theta1, "theta1").ravel()
    a2 = _checks.as_float(theta2, "theta2").ravel()
    for arr, name in ((a1, "theta1"), (a2, "theta2")):
        if arr.size == 0:
            raise ValueError(f"{name} must hold at least one angle")
        if not np.all(np.abs(arr) <= math.pi):
            raise ValueError(f"{name} must lie in [-pi, pi] (the map starts each arm below or at the top)")
    t_max = _checks.real(t_max, "t_max", 0.0, lo_open=True)
    rtol, atol = _checks.tolerances(rtol, atol)
    agree = _checks.real(agree, "agree", 0.0, lo_open=True)
    return a1, a2, t_max, rtol, atol, agree


@dataclass(frozen=True)
class FlipMap:
    """The flip-time map of a double pendulum released from rest.

    Attributes
    ----------
    theta1, theta2 : numpy.ndarray
        The axes of the map: the initial angles (rad); pixel (i, j) starts
        from rest at (theta1[i], theta2[j]).
    time : numpy.ndarray
        The first time either arm passes over the top (abs(theta) = pi),
        shape (theta1.size, theta2.size); inf where no arm flipped by t_max.
    check : numpy.ndarray
        The same at the tolerance tightened tenfold.
    forbidden : numpy.ndarray of bool
        The pixels the energy forbids to flip (:func:`flip_forbidden`):
        inf without integration.
    unresolved : numpy.ndarray of bool
        The pixels whose answer moves when the tolerance is tightened
        tenfold: one run flips before t_max and the other not, or the two
        flip times differ by more than agree times the later one.
    t_max, rtol, agree : float
        The search's end, the tolerance of ``time`` (``check`` at rtol / 10)
        and the agreement asked of the two.

    See Also
    --------
    DoublePendulum.flip_map : makes it.

    Examples
    --------
    >>> import numpy as np, pendula
    >>> th = np.linspace(-3.0, 3.0, 5)
    >>> fm = pendula.DoublePendulum().flip_map(th, th, t_max=20.0)
    >>> int(fm.forbidden.sum()), bool(np.isinf(fm.time[2, 2]))
    (7, True)
    """

    theta1: np.ndarray
    theta2: np.ndarray
    time: np.ndarray
    check: np.ndarray
    forbidden: np.ndarray
    unresolved: np.ndarray
    t_max: float
    rtol: float
    agree: float

    def to_xarray(self) -> xarray.Dataset:
        """The map as an xarray Dataset over (theta1, theta2), with CF attributes.

        Returns
        -------
        xarray.Dataset
            ``time``, ``check``, ``forbidden`` and ``unresolved`` (0 or 1) and
            ``status`` (0), as :meth:`DoublePendulum.flip_sweep` gives them;
            attributes ``t_max``, ``rtol`` and ``agree``.

        Examples
        --------
        >>> import numpy as np, pendula
        >>> th = np.linspace(-3.0, 3.0, 5)
        >>> ds = pendula.DoublePendulum().flip_map(th, th, t_max=20.0).to_xarray()
        >>> ds.time.dims, int(ds.forbidden.sum())
        (('theta1', 'theta2'), 7)
        """
        from .double_sweep import flip_dataset
        return flip_dataset(self)

    def __repr__(self) -> str:
        n = self.time.size
        flipped = int(np.sum(np.isfinite(self.time)))
        return (f"FlipMap({self.theta1.size} x {self.theta2.size} pixels, t_max={self.t_max:g}, rtol={self.rtol:g}: "
                f"{int(self.forbidden.sum())} forbidden, {flipped} flipped, {n - flipped - int(self.forbidden.sum())} "
                f"not flipped by t_max, {int(self.unresolved.sum())} unresolved)")


@dataclass(frozen=True)
class LyapunovSpectrum:
    """The four Lyapunov exponents of a double pendulum's orbit.

    Attributes
    ----------
    exponents : numpy.ndarray
        The exponents, largest first (per unit time).
    total : float
        Their sum: minus the mean phase-space contraction rate, zero for
        the undamped (Hamiltonian) pendulum.
    pairing : numpy.ndarray
        (lambda1 + lambda4, lambda2 + lambda3): both zero for a Hamiltonian
        system (the exponents come in pairs +-lambda; Arnold, "Mathematical
        Methods of Classical Mechanics", section 41), to rounding with a
        symplectic method; with damping they need not vanish.
    time : float
        The span averaged over.
    method : str
        The integrator of the path and its variational equations.
    energy0 : float
        The orbit's energy at the start.

    See Also
    --------
    DoublePendulum.lyapunov : makes it.

    Examples
    --------
    >>> import pendula
    >>> ls = pendula.DoublePendulum().lyapunov(2.0, 2.0, t=200.0)
    >>> bool(ls.exponents[0] > 0.2), bool(abs(ls.total) < 1e-10)
    (True, True)
    """

    exponents: np.ndarray
    total: float
    pairing: np.ndarray
    time: float
    method: str
    energy0: float

    def __repr__(self) -> str:
        ex = ", ".join(f"{float(x):.6g}" for x in self.exponents)
        return (f"LyapunovSpectrum([{ex}] over t={self.time:g} by {self.method}: sum {self.total:.3g}, "
                f"pairs {float(self.pairing[0]):.3g}, {float(self.pairing[1]):.3g})")


class DoublePendulum:
    """A double pendulum: two arms, the second hanging from the end of the first.

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
    damping : float or array_like, optional
        k >= 0, the viscous torque -k_i dtheta_i/dt on each angle (one
        number for both or two; default 0).

    Raises
    ------
    ValueError
        Naming the field: a mass, length or g not positive and finite, a
        negative damping.

    See Also
    --------
    double_pendulum_modes : the exact normal modes.
    flip_forbidden : the region from which no arm can flip.

    Notes
    -----
    The state is integrated as (theta1, theta2, p1, p2), p the canonical
    momenta, so that Gauss-Legendre is symplectic (Hairer, Lubich and
    Wanner, "Geometric Numerical Integration", section VI.4); the angular
    velocities are M(theta1 - theta2)^-1 p.  Angles are measured from the
    downward vertical and are not wrapped.

    Examples
    --------
    >>> import numpy as np, pendula
    >>> dp = pendula.DoublePendulum()
    >>> run = dp.simulate(np.linspace(0, 10, 6), theta1=1.0, theta2=0.5)
    >>> run.attrs["method"], bool(run.attrs["energy_error_max"] < 1e-12)
    ('gauss6', True)
    """

    def __init__(self, m1: float = 1.0, m2: float = 1.0, l1: float = 1.0, l2: float = 1.0, g: float = 1.0,
                 rods: bool = False, damping: ArrayLike = 0.0) -> None:
        (m1, m2, l1, l2, g, rods), mm, _ = _arms(m1, m2, l1, l2, g, rods)
        k = _checks.as_float(damping, "damping")
        if k.ndim == 0:
            k = np.full(2, float(k))
        if k.shape != (2,):
            raise ValueError(f"damping must be one number or two (one per angle), got shape {k.shape}")
        if not np.all(np.isfinite(k)) or np.any(k < 0):
            raise ValueError(f"damping must be finite and >= 0, got {k.tolist()}")
        self.m1, self.m2, self.l1, self.l2, self.g, self.rods = m1, m2, l1, l2, g, rods
        self.damping = k
        self._a, self._b, self._c = float(mm[0, 0]), float(mm[0, 1]), float(mm[1, 1])
        self._p = np.array([m1, m2, l1, l2, g, 1.0 if rods else 0.0, k[0], k[1]])

    def __repr__(self) -> str:
        kind = "rods" if self.rods else "point masses"
        return (f"DoublePendulum(m1={self.m1:g}, m2={self.m2:g}, l1={self.l1:g}, l2={self.l2:g}, g={self.g:g}, "
                f"{kind}, damping={self.damping.tolist()})")

    def _fields_on(self) -> list:
        """The fields that are on (non-zero): the capability table decides what each tool does with them."""
        return ["damping"] if np.any(self.damping) else []

    @property
    def conservative(self) -> bool:
        """True when there is no damping (the energy is conserved)."""
        return bool(np.all(self.damping == 0))

    def modes(self) -> DoublePendulumModes:
        """The exact small-amplitude normal modes (:func:`double_pendulum_modes`).

        Returns
        -------
        DoublePendulumModes

        Examples
        --------
        >>> import pendula
        >>> [round(float(w), 9) for w in pendula.DoublePendulum().modes().omega]
        [0.765366865, 1.847759065]
        """
        return double_pendulum_modes(self.m1, self.m2, self.l1, self.l2, self.g, self.rods)

    # ------------------------------------------------------------------ states
    def _momenta(self, th1, th2, w1, w2):
        cd = np.cos(th1 - th2)
        return self._a * w1 + self._b * cd * w2, self._b * cd * w1 + self._c * w2

    def _state(self, y: np.ndarray):
        """Energy, velocities (2, n), rhs (4, n) and the Jacobian at the first of the states y (4, n)."""
        return _kernel.double_state_v(self._p, np.asfortranarray(y))

    def energy(self, theta1: ArrayLike, theta2: ArrayLike, omega1: ArrayLike = 0.0,
               omega2: ArrayLike = 0.0) -> np.ndarray:
        """The energy T + V, zero at rest at the bottom.

        Parameters
        ----------
        theta1, theta2 : array_like
            The angles from the downward vertical (rad), broadcast together.
        omega1, omega2 : array_like, optional
            Their rates (default 0).

        Returns
        -------
        numpy.ndarray
            The energy of each state (in units of mass x length^2 x g / length).

        Examples
        --------
        >>> import math, pendula
        >>> float(pendula.DoublePendulum().energy(math.pi, 0.0))   # arm 1 up, arm 2 down: 2 m g l
        4.0
        """
        arrs = np.broadcast_arrays(*(_checks.as_float(x, n) for x, n in
                                     ((theta1, "theta1"), (theta2, "theta2"), (omega1, "omega1"),
                                      (omega2, "omega2"))))
        th1, th2, w1, w2 = (a.ravel() for a in arrs)
        p1, p2 = self._momenta(th1, th2, w1, w2)
        if th1.size == 0:
            return np.zeros(arrs[0].shape)
        en = self._state(np.stack([th1, th2, p1, p2]))[0]
        return en.reshape(arrs[0].shape)

    # ------------------------------------------------------------------ the path
    def _default_dt(self, y0: np.ndarray | None = None) -> float:
        """A Gauss-Legendre step from the kernel's time scales at the canonical state y0 (at rest at the
        bottom when None): 1/100 of the period of the fastest of the fast normal mode, the damping and the
        whirl the state's energy allows."""
        _, _, dt = _kernel.double_time_scales_v(self._p, np.zeros(4) if y0 is None else y0)
        return float(dt)

    def simulate(self, t: ArrayLike, theta1: float = 0.0, theta2: float = 0.0, omega1: float = 0.0,
                 omega2: float = 0.0, *, method: str = "auto", dt: float | None = None, rtol: float = 1e-12,
                 atol: float = 1e-12) -> xarray.Dataset:
        """The path at the times t, with its energy error, as an xarray Dataset.

        Parameters
        ----------
        t : array_like
            Output times, ascending, >= 0 (the run starts at t = 0).
        theta1, theta2 : float, optional
            The initial angles (rad, from the downward vertical).
        omega1, omega2 : float, optional
            The initial rates (rad per unit time).
        method : {'auto', 'gauss6', 'gauss4', 'dop853'}, optional
            Gauss-Legendre of order 6 or 4 (fixed step dt, symplectic: the
            energy error of the undamped pendulum stays bounded), or DOP853
            with error control (rtol, atol).  'auto' (default): gauss6 when
            there is no damping and the times lie on a grid of equal steps
            from 0 (the step then divides the grid's spacing), otherwise
            dop853.
        dt : float, optional
            The Gauss-Legendre step (default: 1/100 of the period of the
            fastest time scale, the fast normal mode or, at high energy, the
            whirl the starting energy H allows, sqrt(2 H / lambda_min) with
            lambda_min the smallest eigenvalue of the mass matrix; shortened
            to divide the output spacing).  The times must be multiples of it.
        rtol, atol : float, optional
            DOP853's tolerances on (theta1, theta2, p1, p2) (default 1e-12).

        Returns
        -------
        xarray.Dataset
            ``theta1``, ``theta2``, ``omega1``, ``omega2``, ``p1``, ``p2``,
            ``energy`` and ``energy_error`` (E(t) - E(0)) over ``time``;
            attributes ``method``, ``l1``, ``l2`` (for
            ``pendula.plot.animate``), ``dt`` (Gauss), ``steps``,
            ``rhs_evaluations``, ``energy0`` and ``energy_error_max`` (the
            largest abs(E(t) - E(0)) over the larger of abs(E(0)) and the
            energy with both arms up: a relative error).

        Raises
        ------
        ValueError
            Naming the field (times not ascending or off the step grid), or
            the kernel's failure (the work limit, a non-finite state).

        Examples
        --------
        >>> import numpy as np, pendula
        >>> dp = pendula.DoublePendulum(damping=0.1)
        >>> run = dp.simulate(np.linspace(0, 20, 5), theta1=2.0)
        >>> run.attrs["method"], bool(run.energy[-1] < run.energy[0])
        ('dop853', True)
        """
        xr = require("xarray", "xarray", "DoublePendulum.simulate")
        require_fields("double", "simulate", self._fields_on())
        tt = _checks.as_float(t, "t").ravel()
        if tt.size == 0:
            raise ValueError("t must hold at least one time")
        if not np.all(np.isfinite(tt)):
            raise ValueError("t must be finite")
        if tt.size and not (np.all(np.diff(tt) >= 0) and tt[0] >= 0):
            raise ValueError("t must be ascending and >= 0")
        method = _checks.choice(method, "method", DOUBLE_METHODS)
        y0 = np.array([_checks.real(theta1, "theta1"), _checks.real(theta2, "theta2"),
                       _checks.real(omega1, "omega1"), _checks.real(omega2, "omega2")])
        y0[2], y0[3] = self._momenta(y0[0], y0[1], y0[2], y0[3])
        h = 0.0
        counts = np.zeros(tt.size, dtype=np.int64)
        if method == "auto":
            method = "dop853"
            if self.conservative and tt.size and tt[-1] > 0:
                # times on one grid of equal steps from 0: Gauss-Legendre with a step dividing it
                gaps = np.diff(np.concatenate([[0.0], tt]))
                base = float(tt[-1] / np.rint(tt[-1] / np.min(gaps[gaps > 0])))
                k = tt / base
                if np.all(np.abs(k - np.rint(k)) <= 1e-9 * np.maximum(1.0, k)):
                    method = "gauss6"
                    if dt is None:
                        dt = base / math.ceil(base / self._default_dt(y0))
        if method != "dop853":
            if dt is None:
                dt = self._default_dt(y0)
            h = _checks.real(dt, "dt", 0.0, lo_open=True)
            steps = tt / h
            if steps.size and not steps[-1] <= 2e9:
                raise _fail("t, dt", 7)
            n = np.rint(steps)
            if np.any(np.abs(steps - n) > 1e-9 * np.maximum(1.0, steps)):
                raise ValueError(f"t must lie on the step grid of dt={h!r} (multiples of dt)")
            counts = np.diff(np.concatenate([[0.0], n])).astype(np.int64)
        else:
            rtol, atol = _checks.tolerances(rtol, atol)
        cancel = _interrupt.cancel_flag()
        span = float(tt[-1]) if tt.size else 0.0
        long = span / max(h, self._default_dt(y0)) > 1e5
        yout, stats, status = _interrupt.call(
            _kernel.double_simulate_v, self._p, _METHOD_CODE[method], y0, tt, counts, float(rtol), float(atol),
            h, cancel, cancel=cancel, long=long)
        if status != 0:
            raise _fail(method, status)
        en, w, _, _ = self._state(yout) if tt.size else (np.zeros(0), np.zeros((2, 0)), None, None)
        e0 = float(self._state(y0[:, None])[0][0])
        err = en - e0
        scale = max(abs(e0), float(self.energy(math.pi, math.pi)))
        dims = ("time",)
        attrs = {"method": method, "l1": self.l1, "l2": self.l2, "steps": int(stats[0]),
                 "rhs_evaluations": int(stats[3]), "energy0": e0,
                 "energy_error_max": float(np.max(np.abs(err)) / scale) if err.size else 0.0}
        if method != "dop853":
            attrs["dt"] = h
        return xr.Dataset({"theta1": (dims, yout[0]), "theta2": (dims, yout[1]), "omega1": (dims, w[0]),
                           "omega2": (dims, w[1]), "p1": (dims, yout[2]), "p2": (dims, yout[3]),
                           "energy": (dims, en), "energy_error": (dims, err)},
                          coords={"time": tt}, attrs=attrs)

    # ------------------------------------------------------------------ the flip-time map
    def flip_map(self, theta1: ArrayLike, theta2: ArrayLike, *, t_max: float = 100.0, rtol: float = 1e-10,
                 atol: float = 1e-10, agree: float = 1e-3, threads: int = 0) -> FlipMap:
        """Heyl's flip-time map: how long until an arm flips, from rest at each (theta1, theta2).

        Parameters
        ----------
        theta1, theta2 : array_like
            The map's axes: initial angles in [-pi, pi] (1-D).
        t_max : float, optional
            The search's end (default 100): a pixel with no flip by then is inf.
        rtol, atol : float, optional
            DOP853's tolerances (default 1e-10); every pixel is run again at a
            tenth of both.
        agree : float, optional
            The relative agreement of the two runs' flip times below which a
            pixel counts as resolved (default 1e-3).
        threads : int, optional
            OpenMP threads for the pixels (0: OpenMP's default); each pixel's
            result is the same on any thread count.

        Returns
        -------
        FlipMap
            Flip times, the forbidden pixels (skipped: the energy forbids a
            flip, exactly) and the unresolved ones.

        Raises
        ------
        ValueError
            Naming the field: an angle outside [-pi, pi], t_max not positive,
            bad tolerances.

        See Also
        --------
        flip_forbidden : the pixels skipped.

        Notes
        -----
        A flip is the first time abs(theta1) or abs(theta2) reaches pi (Heyl,
        "The double pendulum fractal", 2008).  The path is output on a grid
        of 1/10 of the fast normal mode's period; the crossing is found on the
        cubic Hermite interpolant of the grid interval where it happens, then
        polished by Newton's method on the integrated path.

        Examples
        --------
        >>> import numpy as np, pendula
        >>> th = np.linspace(-3.0, 3.0, 7)
        >>> fm = pendula.DoublePendulum().flip_map(th, th, t_max=10.0)
        >>> fm.time.shape, int(fm.unresolved.sum()) <= 2
        ((7, 7), True)
        """
        require_fields("double", "flip_map", self._fields_on())
        a1, a2, t_max, rtol, atol, agree = _flip_args(theta1, theta2, t_max, rtol, atol, agree)
        g1, g2 = np.meshgrid(a1, a2, indexing="ij")
        tf, tc, forbidden, unresolved, _ = self._flip_pixels(g1, g2, t_max, rtol, atol, agree,
                                                             _checks.threads(threads))
        return FlipMap(a1, a2, tf, tc, forbidden, unresolved, t_max, rtol, agree)

    def flip_sweep(self, theta1: ArrayLike, theta2: ArrayLike, *, t_max: float = 100.0, rtol: float = 1e-10,
                   atol: float = 1e-10, agree: float = 1e-3, out: str | os.PathLike[str] | None = None,
                   client: distributed.Client | None = None, threads: int = 0, chunk_points: int = 4096,
                   progress: bool = True) -> xarray.Dataset:
        """The flip-time map as a sweep: in chunks, into a resumable Zarr store or on a Dask cluster.

        The same map as :meth:`flip_map`, for grids too large for one call:
        computed in chunks of whole rows of theta1, each written to the store
        under ``out`` as it finishes (a run stopped at any moment resumes where
        it stopped), or sent to the workers of a Dask cluster.

        Parameters
        ----------
        theta1, theta2 : array_like
            The map's axes: initial angles in [-pi, pi] (1-D).
        t_max, rtol, atol, agree : float, optional
            As in :meth:`flip_map` (defaults 100, 1e-10, 1e-10, 1e-3).
        out : str or path, optional
            A folder for the resumable store (``out/sweep.zarr``, readable by
            ``xarray.open_zarr``); None (default): in memory.
        client : dask.distributed.Client, optional
            Run the chunks on the cluster's workers (each with OpenMP
            threads by the rule of :func:`pendula.sweep`).
        threads : int, optional
            OpenMP threads per chunk (0: all the cores).
        chunk_points : int, optional
            Pixels per chunk (default 4096; whole rows, at least one).
        progress : bool, optional
            A progress bar over the chunks (tqdm; drawn after two seconds).

        Returns
        -------
        xarray.Dataset
            Over (``theta1``, ``theta2``): ``time`` (inf: no flip by t_max),
            ``check`` (at the tolerances tightened tenfold), ``forbidden`` and
            ``unresolved`` (0 or 1, as the FlipMap's masks) and ``status``
            (0: computed; otherwise the integrator's failure, the pixel's
            times NaN); attributes the pendulum and the search.  Lazy (Dask
            arrays) when stored.  Every pixel's numbers are the same whatever
            the chunking, the threads, the cluster or the resumption.

        Raises
        ------
        ValueError
            Naming the field (as :meth:`flip_map`), or a store under ``out``
            that holds another map.
        TypeError
            For a client that is not a dask.distributed.Client.

        See Also
        --------
        DoublePendulum.flip_map : the same map in one call, as a FlipMap.
        pendula.sweep : the sweeps of the single pendulum's measures.

        Examples
        --------
        >>> import numpy as np, pendula
        >>> th = np.linspace(-3.0, 3.0, 5)
        >>> ds = pendula.DoublePendulum().flip_sweep(th, th, t_max=20.0, chunk_points=10, progress=False)
        >>> ds.time.dims, int(ds.forbidden.sum()), bool(np.isinf(ds.time[2, 2]))
        (('theta1', 'theta2'), 7, True)
        """
        from .double_sweep import FlipPlan, flip_sweep

        require_fields("double", "flip_map", self._fields_on())
        a1, a2, t_max, rtol, atol, agree = _flip_args(theta1, theta2, t_max, rtol, atol, agree)
        threads = _checks.threads(threads)
        chunk_points = _checks.count(chunk_points, "chunk_points", 1)
        progress = _checks.flag(progress, "progress")
        if out is not None:
            out = _checks.path(out, "out")
        if client is not None:
            from .._cluster import check_client
            check_client(client)
        plan = FlipPlan(self, a1, a2, t_max, rtol, atol, agree, chunk_points)
        return flip_sweep(plan, out, client, threads, progress)

    def _flip_pixels(self, g1: np.ndarray, g2: np.ndarray, t_max: float, rtol: float, atol: float, agree: float,
                     threads: int, raise_on_status: bool = True):
        """The flip search from rest at the pixels (g1, g2) (checked): flip time, its check at a tenth of
        the tolerances, forbidden, unresolved (each of g1's shape) and the kernel's status of each pixel
        (raised as a ValueError when raise_on_status, else returned with the pixel's times NaN)."""
        forbidden = flip_forbidden(g1, g2, self.m1, self.m2, self.l1, self.l2, self.rods)
        # damping only lowers the energy: the forbidden pixels stay forbidden
        hg = float(self.modes().period[1]) / 10.0
        cancel = _interrupt.cancel_flag()
        tf, tc, status = _interrupt.call(
            _kernel.double_flip_map_v, self._p, np.ravel(g1), np.ravel(g2), forbidden.ravel().astype(np.int32),
            t_max, hg, rtol, atol, int(threads), cancel, cancel=cancel, long=g1.size > 16)
        if cancel[0]:
            raise KeyboardInterrupt
        bad = status[status != 0]
        if bad.size and raise_on_status:
            raise _fail("flip_map", int(bad[0]))
        tf, tc, status = tf.reshape(g1.shape), tc.reshape(g1.shape), status.reshape(g1.shape)
        both = np.isfinite(tf) & np.isfinite(tc)
        with np.errstate(invalid="ignore"):
            moved = np.where(both, np.abs(tf - tc) > agree * np.maximum(tf, tc), np.isfinite(tf) != np.isfinite(tc))
        return tf, tc, forbidden, moved & ~forbidden & (status == 0), status

    # ------------------------------------------------------------------ Lyapunov exponents
    def lyapunov(self, theta1: float, theta2: float, omega1: float = 0.0, omega2: float = 0.0, *,
                 t: float = 1000.0, dt: float | None = None, every: int = 10, method: str = "auto",
                 rtol: float = 1e-11, atol: float = 1e-11) -> LyapunovSpectrum:
        """The Lyapunov spectrum of the orbit from a state: all four exponents.

        Parameters
        ----------
        theta1, theta2, omega1, omega2 : float
            The initial state (rad, rad per unit time).
        t : float, optional
            The span averaged over (default 1000).
        dt : float, optional
            The Gauss-Legendre step (default 1/100 of the period of the
            fastest time scale at the start, as in :meth:`simulate`), or the
            span between re-orthonormalisations over every for DOP853.
        every : int, optional
            Steps between re-orthonormalisations (default 10).
        method : {'auto', 'gauss6', 'gauss4', 'dop853'}, optional
            'auto': gauss6 without damping (symplectic: the exponents pair to
            rounding), dop853 with it.
        rtol, atol : float, optional
            DOP853's tolerances.

        Returns
        -------
        LyapunovSpectrum

        Raises
        ------
        ValueError
            Naming the field.

        Notes
        -----
        The variational equations of Hamilton's equations (their Jacobian in
        closed form in the kernel) beside the path, re-orthonormalised by
        Gram-Schmidt (Benettin, Galgani, Giorgilli and Strelcyn, Meccanica 15
        (1980) 9); the exponents are the mean logarithmic growth of the
        Gram-Schmidt norms.  The frame starts as (e1, e2, e4, e3) in
        (theta1, theta2, p1, p2): its last vector is J times its first (J
        the symplectic unit) and its first three span the symplectic
        complement of the first.  A symplectic step keeps both, and so does
        Gram-Schmidt, so the last norm is the inverse of the first at every
        step: with Gauss-Legendre the pairs lambda1 + lambda4 and lambda2 +
        lambda3 vanish to rounding at any span, not only as t grows, and the
        sum too (the linearised step has determinant one).  The exponents
        themselves converge as 1/t (the neutral pair, along the flow and
        across the energy shell, tends to zero so).

        Examples
        --------
        >>> import pendula
        >>> ls = pendula.DoublePendulum().lyapunov(0.1, 0.1, t=200.0)   # near the bottom: regular
        >>> bool(abs(ls.exponents[0]) < 0.05)
        True
        """
        require_fields("double", "lyapunov", self._fields_on())
        y0 = np.array([_checks.real(theta1, "theta1"), _checks.real(theta2, "theta2"),
                       _checks.real(omega1, "omega1"), _checks.real(omega2, "omega2")])
        y0[2], y0[3] = self._momenta(y0[0], y0[1], y0[2], y0[3])
        t = _checks.real(t, "t", 0.0, lo_open=True)
        every = _checks.count(every, "every", 1)
        method = _checks.choice(method, "method", DOUBLE_METHODS)
        if method == "auto":
            method = "gauss6" if self.conservative else "dop853"
        h = self._default_dt(y0) if dt is None else _checks.real(dt, "dt", 0.0, lo_open=True)
        rtol, atol = _checks.tolerances(rtol, atol)
        nren = max(1, int(round(t / (h * every))))
        cancel = _interrupt.cancel_flag()
        lam, _, status = _interrupt.call(_kernel.double_lyapunov_v, self._p, _METHOD_CODE[method], y0, h, every,
                                         nren, rtol, atol, cancel, cancel=cancel, long=nren * every > 1e5)
        if status != 0:
            raise _fail(f"lyapunov ({method})", status)
        e0 = float(self._state(y0[:, None])[0][0])
        return LyapunovSpectrum(lam, float(np.sum(lam)), np.array([lam[0] + lam[3], lam[1] + lam[2]]),
                                h * every * nren, method, e0)

    # ------------------------------------------------------------------ Poincare sections
    def poincare(self, energy: float, theta2: ArrayLike, p2: ArrayLike, *, t_max: float = 2000.0,
                 dt: float | None = None, points: int = 1000, method: str = "gauss6", rtol: float = 1e-12,
                 atol: float = 1e-12, threads: int = 0) -> xarray.Dataset:
        """Poincare sections at fixed energy: where orbits cross theta1 = 0 with theta1 increasing.

        Parameters
        ----------
        energy : float
            The energy of every orbit (zero at rest at the bottom).
        theta2, p2 : array_like
            The orbits' starts on the section (theta1 = 0), broadcast together:
            the second angle and its canonical momentum; p1 follows from the
            energy (the root with theta1 increasing).
        t_max : float, optional
            How long each orbit runs (default 2000).
        dt : float, optional
            The output spacing, and Gauss-Legendre's step (default 1/100 of
            the period of the fastest time scale at the energy, as in
            :meth:`simulate`).
        points : int, optional
            The most crossings kept per orbit (default 1000).
        method : {'gauss6', 'dop853'}, optional
            Gauss-Legendre of order 6 (default: symplectic, the points stay
            on their energy shell), or DOP853 at (rtol, atol).
        rtol, atol : float, optional
            DOP853's tolerances.
        threads : int, optional
            OpenMP threads for the orbits (0: OpenMP's default).

        Returns
        -------
        xarray.Dataset
            ``theta2`` (folded into [-pi, pi)) and ``p2`` over (``orbit``,
            ``crossing``), NaN past each orbit's last crossing; ``count``
            over ``orbit``; ``energy_error`` the largest relative energy error
            of an orbit's points; attributes ``energy`` and ``method``.  A start
            that has no real p1 at this energy (outside the energy shell) is an
            orbit of NaN, with a RuntimeWarning.

        Raises
        ------
        ValueError
            Naming the field.

        Notes
        -----
        The crossing is the root of the cubic Hermite interpolant of theta1
        on the output interval where it passes a multiple of 2 pi; the other
        components are interpolated there the same way (error O(dt^4)).

        Examples
        --------
        >>> import numpy as np, pendula
        >>> dp = pendula.DoublePendulum()
        >>> sec = dp.poincare(1.0, [0.0, 0.5], [0.0, 0.0], t_max=200.0)
        >>> sec.theta2.dims, bool(sec["count"].min() > 10)
        (('orbit', 'crossing'), True)
        """
        import warnings

        xr = require("xarray", "xarray", "DoublePendulum.poincare")
        require_fields("double", "poincare", self._fields_on())
        e = _checks.real(energy, "energy")
        a2, b2 = np.broadcast_arrays(_checks.as_float(theta2, "theta2"), _checks.as_float(p2, "p2"))
        th2, q2 = a2.ravel().astype(float), b2.ravel().astype(float)
        if not (np.all(np.isfinite(th2)) and np.all(np.isfinite(q2))):
            raise ValueError("theta2 and p2 must be finite")
        t_max = _checks.real(t_max, "t_max", 0.0, lo_open=True)
        if dt is None:   # a state of this energy: at the bottom, the first arm turning alone
            w = math.sqrt(2 * max(e, 0.0) / self._a)
            h = self._default_dt(np.array([0.0, 0.0, self._a * w, self._b * w]))
        else:
            h = _checks.real(dt, "dt", 0.0, lo_open=True)
        points = _checks.count(points, "points", 1)
        method = _checks.choice(method, "method", ("gauss6", "dop853"))
        rtol, atol = _checks.tolerances(rtol, atol)
        # p1 on the energy shell at theta1 = 0: c p1^2 - 2 b C p2 p1 + a p2^2 - 2 det (E - V) = 0
        cd = np.cos(th2)
        det = self._a * self._c - (self._b * cd) ** 2
        v = self.energy(np.zeros_like(th2), th2)
        disc = (self._b * cd * q2) ** 2 - self._c * (self._a * q2 ** 2 - 2 * det * (e - v))
        ok = disc >= 0
        if not np.all(ok):
            warnings.warn(f"poincare: {int(np.sum(~ok))} start(s) lie outside the energy shell of energy={e!r} "
                          "(no real p1): their orbits are NaN", RuntimeWarning, stacklevel=2)
        p1 = (self._b * cd * q2 + np.sqrt(np.where(ok, disc, 0.0))) / self._c
        y0s = np.asfortranarray(np.stack([np.zeros_like(th2), th2, p1, q2])[:, ok])
        n = th2.size
        out_t2 = np.full((n, points), np.nan)
        out_p2 = np.full((n, points), np.nan)
        count = np.zeros(n, dtype=np.int64)
        err = np.full(n, np.nan)
        if y0s.shape[1]:
            cancel = _interrupt.cancel_flag()
            pts, npts, status = _interrupt.call(
                _kernel.double_section_v, self._p, _METHOD_CODE[method], y0s, t_max, h, rtol, atol, points,
                _checks.threads(threads), cancel, cancel=cancel, long=True)
            bad = status[status != 0]
            if bad.size:
                raise _fail("poincare", int(bad[0]))
            idx = np.flatnonzero(ok)
            scale = max(abs(e), float(self.energy(math.pi, math.pi)))
            for j, i in enumerate(idx):
                m = int(npts[j])
                count[i] = m
                out_t2[i, :m] = np.mod(pts[1, :m, j] + np.pi, 2 * np.pi) - np.pi
                out_p2[i, :m] = pts[3, :m, j]
                if m:
                    en = self._state(np.asfortranarray(pts[:, :m, j]))[0]
                    err[i] = float(np.max(np.abs(en - e))) / scale
        return xr.Dataset({"theta2": (("orbit", "crossing"), out_t2), "p2": (("orbit", "crossing"), out_p2),
                           "count": (("orbit",), count), "energy_error": (("orbit",), err)},
                          coords={"orbit": np.arange(n)}, attrs={"energy": e, "method": method, "dt": h})

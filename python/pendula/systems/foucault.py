"""The Foucault pendulum: the spherical pendulum in the frame of the turning Earth.

The kernel integrates the bob's position and velocity in local axes at the
pivot (x east, y north, z up) with the Coriolis and centrifugal forces of the
Earth's rotation and an optional viscous drag (``kernel/models/pendula_foucault.f90``),
by DOP853 on the n-dimensional core.  The swing's plane turns at the
Coriolis rate -Omega_E sin(latitude) plus the pendulum's own apsidal (Airy)
precession, which the exact spherical solution gives
(:func:`~pendula.spherical_orbit`); :meth:`FoucaultPendulum.precession`
measures the turning and splits it into the two.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from .. import _checks, _interrupt, _kernel
from .._optional import require
from .contract import require_fields
from .spherical import spherical_orbit

if TYPE_CHECKING:   # xarray is optional: named in annotations only
    import xarray

__all__ = ["FoucaultPendulum", "FoucaultPrecession"]

#: the Earth's sidereal rotation rate (rad/s; IERS Conventions 2010, section 1.2)
EARTH_RATE = 7.292115e-5

_PSTATUS = {1: "latitude must lie in [-90, 90] degrees, got {latitude!r}",
            2: "g and length must be positive and finite, got g={g!r}, length={length!r}",
            3: "earth_rate and damping must be finite and >= 0, got earth_rate={earth_rate!r}, damping={damping!r}",
            4: "anisotropy must be two finite numbers > -1 (east, north), got {anisotropy!r}"}
_STATUS = {2: "rtol must be > 0 and atol >= 0", 5: "step size underflow", 6: "the state became non-finite",
           7: "the run needs more steps than the work limit (1e8): shorten the span or loosen rtol",
           8: "interrupted", 20: "t must be ascending and >= 0"}


@dataclass(frozen=True)
class FoucaultPrecession:
    """The measured turning of a Foucault pendulum's swing and its two causes.

    Attributes
    ----------
    measured : float
        The rate at which the line of the swing's far points (apsides) turns,
        rad/s, counter-clockwise seen from above positive: the slope of a
        least-squares line through the apsides' azimuths.
    coriolis : float
        -Omega_E sin(latitude): the Earth turning under the pendulum.
    airy : float
        The pendulum's own apsidal (Airy) precession, exact: the precession
        rate of the spherical orbit with the same start in the frame that does
        not turn about the vertical (:func:`~pendula.spherical_orbit`).
    residual : float
        measured - coriolis - airy: the effects of the horizontal component of
        the Earth's rotation, the centrifugal force and the drag, and the
        measurement's error.
    apsides : int
        The number of apsides fitted.
    span : float
        The time they span (s).

    See Also
    --------
    FoucaultPendulum.precession : makes it.

    Examples
    --------
    >>> import pendula
    >>> fp = pendula.FoucaultPendulum(latitude=48.85, length=67.0)
    >>> pr = fp.precession(0.05, swings=40)
    >>> round(pr.coriolis * 86400 * 180 / 3.141592653589793, 1)   # degrees per day
    -271.8
    """

    measured: float
    coriolis: float
    airy: float
    residual: float
    apsides: int
    span: float

    def __repr__(self) -> str:
        day = 86400.0 * 180.0 / math.pi
        return (f"FoucaultPrecession(measured {self.measured * day:.6g} deg/day = Coriolis "
                f"{self.coriolis * day:.6g} + Airy {self.airy * day:.6g} + residual {self.residual * day:.3g}; "
                f"{self.apsides} apsides over {self.span:.6g} s)")


class FoucaultPendulum:
    """A spherical pendulum in the frame of the turning Earth.

    Parameters
    ----------
    latitude : float
        Degrees, in [-90, 90] (north positive).
    length : float, optional
        The rod's length (m; default 67, Foucault's pendulum in the Pantheon).
    g : float, optional
        The apparent gravity at the pivot (m/s^2; default 9.81).
    earth_rate : float, optional
        Omega_E (rad/s; default 7.292115e-5, the sidereal rate).
    damping : float, optional
        gamma >= 0, a viscous drag rate (1/s; default 0): the force -gamma v
        per unit mass.
    anisotropy : tuple of float, optional
        (ae, an), an anisotropic support: a horizontal restoring force
        -(g / length) (ae x, an y) per unit mass besides gravity's, so that a
        small swing east has omega^2 = (g / length) (1 + ae) and one north
        (g / length) (1 + an) (default (0, 0)).  Its precession is not in the
        Coriolis or Airy part: it shows in the residual.

    Raises
    ------
    ValueError
        Naming the field: a latitude outside [-90, 90], g or length not
        positive, a negative earth_rate or damping, an anisotropy at most -1.

    See Also
    --------
    spherical_orbit : the spherical pendulum exactly (the Airy part).

    Examples
    --------
    >>> import numpy as np, pendula
    >>> fp = pendula.FoucaultPendulum(latitude=45.0, length=10.0)
    >>> run = fp.simulate(np.linspace(0, 60, 4), 0.1)
    >>> bool(np.max(np.abs(run.constraint_error)) < 1e-9)
    True
    """

    def __init__(self, latitude: float, length: float = 67.0, g: float = 9.81, earth_rate: float = EARTH_RATE,
                 damping: float = 0.0, anisotropy: ArrayLike = (0.0, 0.0)) -> None:
        self.latitude = _checks.real(latitude, "latitude")
        self.length = _checks.real(length, "length")
        self.g = _checks.real(g, "g")
        self.earth_rate = _checks.real(earth_rate, "earth_rate")
        self.damping = _checks.real(damping, "damping")
        an = _checks.as_float(anisotropy, "anisotropy")
        if an.shape != (2,):
            raise ValueError(f"anisotropy must be two numbers (east, north), got shape {an.shape}")
        self.anisotropy = (float(an[0]), float(an[1]))
        self._p = np.array([self.g, self.length, self.earth_rate, self.latitude, self.damping, *self.anisotropy])
        self._run(np.zeros(6), np.zeros(1), 1e-10, 1e-10)   # the kernel checks the fields

    def __repr__(self) -> str:
        return (f"FoucaultPendulum(latitude={self.latitude:g}, length={self.length:g}, g={self.g:g}, "
                f"earth_rate={self.earth_rate:g}, damping={self.damping:g}, anisotropy={self.anisotropy})")

    def _run(self, y0, tt, rtol, atol):
        cancel = _interrupt.cancel_flag()
        yout, stats, pstatus, status = _interrupt.call(_kernel.foucault_simulate_v, self._p, y0, tt, rtol, atol,
                                                       cancel, cancel=cancel, long=tt.size > 1)
        if pstatus:
            raise ValueError(_PSTATUS[int(pstatus)].format(latitude=self.latitude, g=self.g, length=self.length,
                                                           earth_rate=self.earth_rate, damping=self.damping,
                                                           anisotropy=self.anisotropy))
        if status:
            raise ValueError(f"FoucaultPendulum: {_STATUS.get(int(status), f'kernel status {status}')}")
        return yout, stats

    @property
    def period(self) -> float:
        """2 pi sqrt(length / g): the small-swing period (s)."""
        return 2.0 * math.pi * math.sqrt(self.length / self.g)

    def _start(self, theta0, azimuth, theta_dot0, phi_dot0):
        th = _checks.real(theta0, "theta0")
        if not 0.0 <= th < 0.5 * math.pi:
            raise ValueError(f"theta0 must lie in [0, pi/2) (the bob below the pivot), got {th!r}")
        ph = _checks.real(azimuth, "azimuth")
        thd = _checks.real(theta_dot0, "theta_dot0")
        phd = _checks.real(phi_dot0, "phi_dot0")
        if th == 0.0 and phd != 0.0:
            raise ValueError("phi_dot0 must be 0 at the bottom theta0 = 0: the azimuth is undefined there")
        el = self.length
        st, ct, sp, cp = math.sin(th), math.cos(th), math.sin(ph), math.cos(ph)
        r = el * np.array([st * cp, st * sp, -ct])
        v = el * np.array([thd * ct * cp - st * sp * phd, thd * ct * sp + st * cp * phd, thd * st])
        return np.concatenate([r, v]), th, thd, phd

    def simulate(self, t: ArrayLike, theta0: float, *, azimuth: float = 0.0, theta_dot0: float = 0.0,
                 phi_dot0: float = 0.0, rtol: float = 1e-12, atol: float | None = None) -> xarray.Dataset:
        """The bob's path at the times t, in the Earth's frame, as an xarray Dataset.

        Parameters
        ----------
        t : array_like
            Output times (s), ascending, >= 0.
        theta0 : float
            The polar angle from the downward vertical at t = 0 (rad), in [0, pi/2).
        azimuth : float, optional
            The azimuth at t = 0 (rad, counter-clockwise from east seen from above).
        theta_dot0, phi_dot0 : float, optional
            The rates of the two angles at t = 0 in the Earth's frame (rad/s;
            default 0: released from rest).
        rtol, atol : float, optional
            DOP853's tolerances (default 1e-12, and atol = rtol x length).

        Returns
        -------
        xarray.Dataset
            ``x``, ``y``, ``z`` (east, north, up; m) and ``vx``, ``vy``, ``vz``
            over ``time``, ``theta`` and ``phi`` (the azimuth, unwrapped where
            the bob is away from the bottom) and ``constraint_error`` (abs(r) /
            length - 1, which the exact motion keeps at zero); attributes
            ``steps`` and ``rhs_evaluations``.

        Raises
        ------
        ValueError
            Naming the field.

        Examples
        --------
        >>> import numpy as np, pendula
        >>> fp = pendula.FoucaultPendulum(latitude=90.0, length=1.0)
        >>> run = fp.simulate([0.0, fp.period], 0.1)
        >>> round(float(run.theta[-1]), 4)
        0.1
        """
        xr = require("xarray", "xarray", "FoucaultPendulum.simulate")
        require_fields("foucault", "simulate", ["damping"] if self.damping else [])
        tt = _checks.as_float(t, "t").ravel()
        if tt.size == 0:
            raise ValueError("t must hold at least one time")
        y0, *_ = self._start(theta0, azimuth, theta_dot0, phi_dot0)
        rtol, atol = _checks.tolerances(rtol, rtol * self.length if atol is None else atol)
        yout, stats = self._run(y0, tt, rtol, atol)
        x, y, z = yout[0], yout[1], yout[2]
        rho = np.hypot(x, y)
        dims = ("time",)
        return xr.Dataset({"x": (dims, x), "y": (dims, y), "z": (dims, z), "vx": (dims, yout[3]),
                           "vy": (dims, yout[4]), "vz": (dims, yout[5]), "theta": (dims, np.arctan2(rho, -z)),
                           "phi": (dims, np.unwrap(np.arctan2(y, x))),
                           "constraint_error": (dims, np.sqrt(x * x + y * y + z * z) / self.length - 1.0)},
                          coords={"time": tt}, attrs={"steps": int(stats[0]), "rhs_evaluations": int(stats[3])})

    def precession(self, theta0: float, *, azimuth: float = 0.0, theta_dot0: float = 0.0, phi_dot0: float = 0.0,
                   swings: int = 200, rtol: float = 1e-12) -> FoucaultPrecession:
        """The turning rate of the swing, measured, and split into Coriolis and Airy parts.

        Parameters
        ----------
        theta0 : float
            The amplitude: the polar angle at t = 0 (rad), in (0, pi/2).
        azimuth, theta_dot0, phi_dot0 : float, optional
            As in :meth:`simulate`; phi_dot0 != 0 opens the swing into an
            ellipse (and adds Airy precession).
        swings : int, optional
            How many periods to run (default 200).
        rtol : float, optional
            DOP853's relative tolerance (default 1e-12).

        Returns
        -------
        FoucaultPrecession

        Raises
        ------
        ValueError
            Naming the field (theta0 = 0 has no swing to measure).

        Notes
        -----
        The apsides are the maxima of the bob's horizontal distance, found on
        an output grid of 1/64 period and refined by a parabola through three
        points; their azimuths, folded modulo pi (the swing has two far
        ends), are fitted by a line.  In the frame that does not turn about
        the vertical the pendulum starts with the azimuthal rate phi_dot0 +
        Omega_E sin(latitude), and there, apart from the horizontal component
        of the Earth's rotation and the centrifugal force, it is the spherical
        pendulum: its apsidal precession from :func:`~pendula.spherical_orbit`
        is the Airy part.

        Examples
        --------
        >>> import pendula
        >>> fp = pendula.FoucaultPendulum(latitude=-30.0, length=20.0)
        >>> pr = fp.precession(0.05, swings=40)
        >>> bool(pr.coriolis > 0), bool(abs(pr.residual) < 1e-3 * abs(pr.coriolis))
        (True, True)
        """
        require_fields("foucault", "precession", ["damping"] if self.damping else [])
        y0, th, thd, phd = self._start(theta0, azimuth, theta_dot0, phi_dot0)
        if th == 0.0:
            raise ValueError("theta0 must be > 0: a pendulum at rest at the bottom has no swing to measure")
        swings = _checks.count(swings, "swings", 2)
        per = self.period
        tt = np.arange(64 * swings + 1) * (per / 64)
        rtol, atol = _checks.tolerances(rtol, rtol * self.length)
        yout, _ = self._run(y0, tt, rtol, atol)
        x, y = yout[0], yout[1]
        r2 = x * x + y * y
        k = np.flatnonzero((r2[1:-1] > r2[:-2]) & (r2[1:-1] >= r2[2:])) + 1
        # the parabola through (k-1, k, k+1): the maximum's offset s in steps, and x, y there
        den = r2[k - 1] - 2 * r2[k] + r2[k + 1]
        s = np.where(den != 0, 0.5 * (r2[k - 1] - r2[k + 1]) / np.where(den != 0, den, 1.0), 0.0)

        def at(u):
            return u[k] + 0.5 * s * (u[k + 1] - u[k - 1]) + 0.5 * s * s * (u[k + 1] - 2 * u[k] + u[k - 1])
        ta = tt[k] + s * (per / 64)
        psi = np.unwrap(2.0 * np.arctan2(at(y), at(x))) / 2.0
        if ta.size < 3:
            raise ValueError("swings: too few apsides to fit; run more swings")
        measured = float(np.polyfit(ta, psi, 1)[0])
        oz = self.earth_rate * math.sin(math.radians(self.latitude))
        coriolis = -oz
        orbit = spherical_orbit(th, thd, phd + oz, self.g / self.length)
        airy = float(orbit.precession_rate)
        return FoucaultPrecession(measured, coriolis, airy, measured - coriolis - airy, int(ta.size),
                                  float(ta[-1] - ta[0]))

"""The spherical pendulum, exactly: a point mass on a rod free to swing in
every direction (kernel/models/pendula_spherical.f90).

The polar angle theta (from the downward vertical) swings between two
turning angles as a Jacobi elliptic function; the azimuth phi is an elliptic
integral of the third kind (Carlson's R_J).  Both are evaluated in closed form
at any time, at constant cost per sample, with the phase reduced by whole
polar periods, so that t = 1e12 is as accurate as t = 1.  Units as the planar
pendulum's: eps = g / l, lengths in units of l, the angular momentum
L_z = sin^2(theta) phi' per unit m l^2.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _kernel
from .._checks import as_float, real
from .contract import require_fields

__all__ = ["SphericalOrbit", "SphericalPath", "spherical_orbit"]

_STATUS = {1: "eps must be positive and at most 1e300, got {eps!r}",
           2: "theta0 is the polar angle from the downward vertical: it must lie in [0, pi], got {theta0!r}",
           3: "theta_dot0 must be finite, got {theta_dot0!r}",
           4: "phi_dot0 must be finite, got {phi_dot0!r}",
           5: "phi_dot0 must be 0 at the pole theta0 = 0: the azimuth, and so its rate, is undefined there "
              "(got phi_dot0 = {phi_dot0!r})",
           6: "theta_dot0 and phi_dot0 must stay below 1e100 sqrt(eps) in magnitude",
           7: "phi_dot0 gives |L_z| = sin^2(theta0) |phi_dot0| below 1e-100 sqrt(eps), too small for the "
              "azimuth to be resolved: give phi_dot0 = 0 for the planar motion",
           8: "phi0 must be finite, got {phi0!r}"}


def _check(status: int, **fields) -> None:
    if status:
        raise ValueError(_STATUS.get(status, "pendula kernel status {status}").format(status=status, **fields))


@dataclass(frozen=True, repr=False)
class SphericalPath:
    """The spherical pendulum's state at the times asked for.

    Attributes
    ----------
    t : ndarray
        The times.
    theta, phi : ndarray
        Polar angle from the downward vertical (in [0, pi]) and azimuth
        (continuous, growing without bound).  For L_z = 0 the motion stays in
        the plane phi = phi0 and theta is the planar pendulum's signed angle.
    theta_dot, phi_dot : ndarray
        Their rates.
    eps : float
        g / l.

    See Also
    --------
    SphericalOrbit.path : makes it.

    Examples
    --------
    >>> import pendula
    >>> p = pendula.spherical_orbit(0.5, 0.0, 1.2).path([0.0, 1.0])
    >>> p
    SphericalPath(2 samples, t in [0, 1], theta in [0.5, 0.5438])
    >>> round(float(p.theta[0]), 15), float(p.theta_dot[0])
    (0.5, 0.0)
    """

    t: NDArray[np.float64]
    theta: NDArray[np.float64]
    phi: NDArray[np.float64]
    theta_dot: NDArray[np.float64]
    phi_dot: NDArray[np.float64]
    eps: float

    @property
    def energy(self) -> NDArray[np.float64]:
        """(theta'^2 + sin^2(theta) phi'^2) / 2 + eps (1 - cos theta) per unit
        m l^2 along the path (constant: a check of the path)."""
        s = np.sin(self.theta)
        h = np.sin(0.5 * self.theta)
        return 0.5 * (self.theta_dot ** 2 + (s * self.phi_dot) ** 2) + 2.0 * self.eps * h * h

    @property
    def lz(self) -> NDArray[np.float64]:
        """The vertical angular momentum sin^2(theta) phi' per unit m l^2
        along the path (constant)."""
        return np.sin(self.theta) ** 2 * self.phi_dot

    def position(self, length: float = 1.0) -> NDArray[np.float64]:
        """The bob's position (x, y, z), z up from the pivot, shape (3,) + t.shape.

        Parameters
        ----------
        length : float, optional
            The rod's length (default 1), > 0.

        Returns
        -------
        ndarray
            length (sin theta cos phi, sin theta sin phi, -cos theta).

        Raises
        ------
        ValueError
            For a length that is not positive and finite.

        Examples
        --------
        >>> import pendula
        >>> p = pendula.spherical_orbit(0.5, 0.0, 1.2).path([0.0])
        >>> [round(float(c), 6) for c in p.position(2.0)[:, 0]]
        [0.958851, 0.0, -1.755165]
        """
        ln = real(length, "length", 0.0, lo_open=True)
        s = np.sin(self.theta)
        return ln * np.stack([s * np.cos(self.phi), s * np.sin(self.phi), -np.cos(self.theta)])

    def __repr__(self) -> str:
        n = self.t.size
        if n == 0:
            return "SphericalPath(0 samples)"
        return (f"SphericalPath({n} sample{'s' if n != 1 else ''}, t in [{np.nanmin(self.t):.4g}, "
                f"{np.nanmax(self.t):.4g}], theta in [{np.nanmin(self.theta):.4g}, {np.nanmax(self.theta):.4g}])")


@dataclass(frozen=True)
class SphericalOrbit:
    """One orbit of the spherical pendulum and its facts, from the exact solution.

    Attributes
    ----------
    theta0, theta_dot0, phi_dot0, eps : float
        The state at t = 0 and g / l.
    period : float
        The polar period: the time from one lowest point to the next.
    azimuth_advance : float
        The azimuth swept in one polar period (signed as L_z).
    apsidal_angle : float
        The azimuth swept from a lowest point to the next highest point, half
        the advance (pi/2 for the small ellipse).
    precession_rate : float
        The apsidal (Airy) precession rate: (azimuth_advance - pi sign(L_z)) /
        period; for a small ellipse of semi-axes a, b (in units of l) it tends
        to Airy's 3 sqrt(eps) a b / 8.
    theta_min, theta_max : float
        The turning polar angles (equal on the conical orbit).
    energy : float
        (theta'^2 + sin^2(theta) phi'^2) / 2 + eps (1 - cos theta) per unit
        m l^2.
    lz : float
        sin^2(theta) phi'.
    m, mc : float
        The parameter of the Jacobi functions and its complement.
    planar : bool
        L_z = 0: the planar pendulum; the facts are then the limit L_z -> 0
        (the azimuth jumps by pi at each passage through the bottom).

    See Also
    --------
    spherical_orbit : makes it.

    Examples
    --------
    >>> import math, pendula
    >>> o = pendula.spherical_orbit(math.pi / 3, 0.0, math.sqrt(2.0))  # conical
    >>> o.theta_min == o.theta_max
    True
    >>> # its apsidal angle: pi phi' / Omega, Omega^2 = (1 + 3 cos^2) / cos
    >>> round(o.apsidal_angle, 12), round(math.pi * math.sqrt(2 / 3.5), 12)
    (2.374820823447, 2.374820823447)
    """

    theta0: float
    theta_dot0: float
    phi_dot0: float
    eps: float
    period: float
    azimuth_advance: float
    apsidal_angle: float
    precession_rate: float
    theta_min: float
    theta_max: float
    energy: float
    lz: float
    m: float
    mc: float
    planar: bool

    def path(self, t: ArrayLike, phi0: float = 0.0) -> SphericalPath:
        """theta, phi and their rates at the times t, from the exact solution.

        Parameters
        ----------
        t : array_like
            Times, in any order, before or after 0.
        phi0 : float, optional
            The azimuth at t = 0 (default 0).

        Returns
        -------
        SphericalPath
            Arrays of the shape of `t`; NaN (with a RuntimeWarning) at
            infinite times or beyond 2**48 polar half periods.

        Raises
        ------
        TypeError
            For a string, complex or object argument.
        ValueError
            For a non-finite phi0.

        Examples
        --------
        >>> import pendula
        >>> o = pendula.spherical_orbit(0.5, 0.0, 1.2)
        >>> p = o.path([0.0, o.period])        # one polar period later
        >>> round(float(p.theta[1]), 12), round(float(p.phi[1]), 12)
        (0.5, 3.495459637173)
        >>> bool(p.phi[1] == o.azimuth_advance)
        True
        """
        t = as_float(t, "t")
        ph0 = real(phi0, "phi0")
        tf = np.ascontiguousarray(t, dtype=np.float64).reshape(-1)
        th, ph, thd, phd, status = _kernel.spherical_path_v(self.theta0, self.theta_dot0, self.phi_dot0, ph0,
                                                           self.eps, tf)
        _check(status, theta0=self.theta0, theta_dot0=self.theta_dot0, phi_dot0=self.phi_dot0, eps=self.eps,
               phi0=ph0)
        bad = ~np.isfinite(th) & ~np.isnan(tf)
        if np.any(bad):
            warnings.warn(f"spherical path: {int(bad.sum())} time(s) infinite or beyond 2**48 half periods "
                          "gave NaN", RuntimeWarning, stacklevel=2)
        sh = t.shape
        return SphericalPath(t.reshape(sh).copy(), th.reshape(sh), ph.reshape(sh), thd.reshape(sh),
                             phd.reshape(sh), self.eps)


def _scalar(x, name: str) -> float:
    a = as_float(x, name)
    if a.ndim != 0 and a.size != 1:
        raise ValueError(f"{name} must be a single number, got shape {a.shape}")
    return float(a.reshape(()))


def spherical_orbit(theta0: float, theta_dot0: float, phi_dot0: float, eps: float = 1.0) -> SphericalOrbit:
    """The spherical pendulum's orbit through a state, with its facts.

    Parameters
    ----------
    theta0 : float
        Polar angle at t = 0, from the downward vertical, in [0, pi].
    theta_dot0 : float
        Its rate at t = 0.
    phi_dot0 : float
        The azimuthal rate at t = 0 (0 at the pole theta0 = 0).
    eps : float, optional
        g / l > 0 (default 1).

    Returns
    -------
    SphericalOrbit
        The polar period, the azimuth advance and apsidal angle, the apsidal
        precession rate, the turning angles, the energy and L_z; its
        ``path(t)`` gives the motion.

    Raises
    ------
    TypeError
        For a string, complex or array argument.
    ValueError
        Naming the field: eps not in (0, 1e300]; theta0 outside [0, pi];
        a non-finite rate; an azimuthal rate at the pole (undefined there);
        rates beyond 1e100 sqrt(eps); 0 < abs(L_z) < 1e-100 sqrt(eps).

    See Also
    --------
    orbit : the planar pendulum's orbit (the case phi_dot0 = 0).

    Notes
    -----
    With x = 1 - cos(theta) and time scaled by sqrt(eps), x'^2 = 2 (e - x)
    x (2 - x) - L^2 has the turning heights xa <= xb and a third root
    xc >= 2; x = xa + (xb - xa) sn^2(u | m), m = (xb - xa) / (xc - xa), and
    the azimuth is two elliptic integrals of the third kind (Landau and
    Lifshitz, Mechanics, section 14, problem 1).

    Examples
    --------
    The orbit between 30 and 60 degrees (g = l = 1):

    >>> import math, pendula
    >>> xa, xb = 1 - math.cos(math.pi / 6), 1 - math.cos(math.pi / 3)
    >>> sa, sb = xa * (2 - xa), xb * (2 - xb)
    >>> e = (xa * sa - xb * sb) / (sa - sb)
    >>> lz = math.sqrt(2 * (e - xa) * sa)
    >>> o = pendula.spherical_orbit(math.pi / 6, 0.0, lz / sa)
    >>> round(o.period, 12), round(math.degrees(o.apsidal_angle), 10)
    (3.382971354162, 111.6835524236)
    """
    require_fields("spherical", "spherical_orbit", [])
    args = {"theta0": _scalar(theta0, "theta0"), "theta_dot0": _scalar(theta_dot0, "theta_dot0"),
            "phi_dot0": _scalar(phi_dot0, "phi_dot0"), "eps": _scalar(eps, "eps")}
    f, status = _kernel.spherical_facts_v(args["theta0"], args["theta_dot0"], args["phi_dot0"], args["eps"])
    _check(status, phi0=0.0, **args)
    return SphericalOrbit(args["theta0"], args["theta_dot0"], args["phi_dot0"], args["eps"],
                          period=float(f[0]), azimuth_advance=float(f[1]), apsidal_angle=float(f[2]),
                          precession_rate=float(f[3]), theta_min=float(f[4]), theta_max=float(f[5]),
                          energy=float(f[6]), lz=float(f[7]), m=float(f[8]), mc=float(f[9]),
                          planar=bool(f[10]))


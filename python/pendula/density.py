"""The density of the angle (Prusa & Tuma, task 5): how much of its time a
conservative orbit spends near each angle.

Over one period of a libration the bob passes every angle twice, so the
time-averaged probability density is p(theta) = 2 / (T |theta'(theta)|) on
[-theta_max, theta_max]; over one turn of a rotation it is 1 / (T |theta'|)
on [-pi, pi).  The cumulative distribution is the time to reach theta over
the period, an incomplete elliptic integral F: with sin(theta/2) =
sqrt(m) sin(phi) (libration) or phi = theta/2 (rotation),

    t(theta) = int_0^F(phi | m) h(u) du,

where h is constant (1/sqrt(eps) in libration, sqrt(2/E) in rotation) for
the rigid pendulum in uniform gravity, so that the CDF is exactly
1/2 + 2 F(phi|m) / (4 K(m)) (libration) or 1/2 + F(theta/2 | m) / (2 K(m))
(rotation): finite and accurate up to the turning points, where the density
blows up.  In a non-uniform field h(u) is smooth, even and 2K-periodic (see
pendula.systems.gravity), and int_0^U h du is summed from its cosine series.
For the cycloidal pendulum s = 4 R sin(theta) is harmonic in time, so s has
the arcsine law at every amplitude: p(s) = 1 / (pi sqrt(A^2 - (s - s_c)^2)).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._checks import as_float
from . import _kernel
from .scene import Scene
from .systems.contract import require

__all__ = ["angle_density", "angle_cdf", "arcsine_density"]


def arcsine_density(theta: ArrayLike, theta_init: float) -> NDArray[np.float64]:
    """The small-amplitude limit of the density of the angle: the arcsine law.

    Parameters
    ----------
    theta : array_like
        Angles.
    theta_init : float
        The amplitude.

    Returns
    -------
    ndarray
        1 / (pi sqrt(theta_init^2 - theta^2)) inside (-theta_init, theta_init),
        0 outside.  (Prusa & Tuma, task 5, print it without the factor
        1/theta_init that makes it integrate to 1: a slip.)

    Raises
    ------
    TypeError
        For a string, complex or object `theta`.

    See Also
    --------
    angle_density : the exact density at any amplitude.

    Examples
    --------
    >>> import pendula
    >>> float(pendula.arcsine_density(0.0, 0.1))       # 1 / (0.1 pi)
    3.183098861837907
    """
    theta = as_float(theta, "theta")
    a = float(theta_init)
    out = np.zeros_like(theta)
    inside = np.abs(theta) < abs(a)
    out[inside] = 1.0 / (math.pi * np.sqrt((abs(a) - np.abs(theta[inside])) * (abs(a) + np.abs(theta[inside]))))
    return out


def _check(scene, tool="angle_density"):
    from .scene import Scene

    if not isinstance(scene, Scene):
        raise TypeError(f"expected a pendula.Scene, got {type(scene).__name__}")
    require(scene, tool)    # the capability table: the fields the density honours, the rest refused by name


class _Model:
    """What the density needs from one orbit: (density, cdf) callables."""

    def __init__(self, scene, tool="angle_density"):
        _check(scene, tool)
        self.scene = scene
        if scene.guide == "cycloid":
            self._setup_cycloid()
        else:
            self._setup_energy()

    # -- the cycloid: the arcsine law in s
    def _setup_cycloid(self):
        sc = self.scene
        r = sc.cycloid_radius
        w2 = sc.eps / (4 * r)
        s0 = 4 * r * math.sin(sc.theta0)
        sd0 = 4 * r * math.cos(sc.theta0) * sc.v0
        self.r = r
        self.centre = sc.torque / w2
        self.amp = math.hypot(s0 - self.centre, sd0 / math.sqrt(w2))
        if not self.amp > 0:
            raise ValueError("the orbit is a point at rest: its density is a delta, not a function")
        if abs(self.centre) + self.amp > 4 * r:
            raise ValueError("the motion runs beyond a cusp (|s| > 4R, the ends of the cheeks)")
        self.kind = "cycloid"

    # -- rigid pendulum, uniform or non-uniform gravity: through F and the cosine series of h
    def _setup_energy(self):
        from .systems.gravity import gravity_orbit, h_samples

        sc = self.scene
        o = gravity_orbit(sc)
        if o.regime == "separatrix":
            raise ValueError("on the separatrix the period is infinite: the density is a delta at the top")
        if not o.theta_max > 0:
            raise ValueError("the orbit is a point at rest: its density is a delta, not a function")
        self.orbit = o
        self.kind = o.regime
        self.mc = o.mc
        # the amplitude: exactly |theta0| when starting at rest (the kernel's 2 asin(sqrt(m)) rounds)
        # (|theta0| <= pi: no reduction needed, exact; otherwise the kernel's reduced amplitude)
        self.at_rest = sc.v0 == 0.0 and o.regime == "libration" and abs(sc.theta0) <= math.pi
        self.thm = abs(sc.theta0) if self.at_rest else o.theta_max
        # an amplitude below 2^-400: every field is harmonic there to 2^-800, the density is the
        # arcsine law exactly (theta and theta_max scaled by 2^600: their squares would underflow)
        self.tiny = o.regime == "libration" and self.thm < 2.0 ** -400
        if self.tiny:
            return                         # (no series: the arcsine law needs none)
        K = o.K
        # cosine coefficients of h on its period 2K: doubling until the last ones are below rounding
        n = 16
        while True:
            u = np.linspace(0.0, K, n + 1)
            h = h_samples(sc, o, u)
            c = np.fft.rfft(np.concatenate([h, h[-2:0:-1]])).real
            a = c / n
            a[0] *= 0.5
            a[n] *= 0.5
            if np.max(np.abs(a[3 * n // 4:])) <= 2 * np.finfo(float).eps * abs(a[0]):
                break
            if n >= 1 << 20:
                raise ValueError("the cosine series of the time integrand did not converge in 2^20 terms "
                                 "(inverse-square field with the mass too close under the circle: "
                                 "gravity_distance - 1 too small)")
            n *= 2
        keep = np.nonzero(np.abs(a) > np.finfo(float).eps * 1e-3 * abs(a[0]))[0]
        self.a = a[:keep[-1] + 1]          # the coefficients below rounding add nothing
        self.K = K
        self.T = (4.0 if o.regime == "libration" else 2.0) * a[0] * K

    def _chunks(self, U, f):
        """f over U in chunks that keep the outer products below ~4M elements"""
        U = np.asarray(U, dtype=float)
        flat = U.reshape(-1)
        step = max(1, (1 << 22) // self.a.size)
        out = np.concatenate([f(flat[i:i + step]) for i in range(0, flat.size, step)]) if flat.size else flat
        return out.reshape(U.shape)

    def _time(self, U):
        """int_0^U h du from the cosine series (U in [-K, K])."""
        j = np.arange(1, self.a.size)
        w = self.a[1:] * self.K / (j * math.pi)

        def f(u):
            return self.a[0] * u + (w * np.sin(np.multiply.outer(u, j) * (math.pi / self.K))).sum(axis=-1)

        return self._chunks(U, f)

    def _h(self, U):
        j = np.arange(self.a.size)
        return self._chunks(U, lambda u: (self.a * np.cos(np.multiply.outer(u, j) * (math.pi / self.K))).sum(axis=-1))

    def _phi(self, theta):
        """sin(phi), cos(phi) with sin(theta/2) = sqrt(m) sin(phi), and sqrt(m) cos(phi), from the
        angle difference (m cos^2 phi = sin((theta_m - theta)/2) sin((theta_m + theta)/2)), so that
        they keep their accuracy at the turning points where arcsin(sin(theta/2)/k) would not."""
        a = np.abs(theta)
        sa = np.sin(0.5 * a)
        if self.at_rest:
            # theta_max = |theta0| exactly: from the angle difference
            kc2 = np.sin(0.5 * (self.thm - a)) * np.sin(0.5 * (self.thm + a))
        else:
            # theta_max is rounded: m - sin^2(theta/2), or cos^2(theta/2) - mc next to the top, from
            # the orbit's m and mc (each to a few ulps), which keeps more digits next to the turning point
            m, mc = self.orbit.m, self.mc
            kc2 = m - sa * sa if m < 0.5 else np.cos(0.5 * a) ** 2 - mc
            kc2 = np.where(a >= self.thm, 0.0, kc2)
        kc = np.sqrt(np.maximum(0.0, kc2))
        r = np.hypot(sa, kc)
        r = np.where(r > 0, r, 1.0)
        return sa / r, kc / r, kc

    def _f(self, s, c):
        """F(phi | m) from sin(phi) and cos(phi), never from phi (dF/dphi ~ 1/sqrt(mc) next to
        pi/2 would amplify the rounding of an angle)."""
        shape = np.shape(s)
        if np.size(s) == 0:
            return np.zeros(shape)
        s = np.ascontiguousarray(s, dtype=np.float64).reshape(-1)
        c = np.ascontiguousarray(c, dtype=np.float64).reshape(-1)
        return _kernel.gravity_f_sc_v(s, c, self.orbit.m, self.mc).reshape(shape)

    def _turn(self, theta):
        """(whole turns, sin(w/2), cos(w/2)) with theta = 2 pi turns + w, w in [-pi, pi]: reduced
        exactly, as numpy's sin reduces its argument (the kernel's reduction of theta0, pi in
        three parts; in plain double w lost |theta| eps: 1.2e3 eps of the density at theta = -908).
        Beyond 2^52 (and at +-inf) theta cannot be reduced modulo 2 pi: NaN there, with a
        RuntimeWarning naming theta."""
        far = ~(np.abs(theta) <= 2.0 ** 52) & ~np.isnan(theta)
        if np.any(far):
            warnings.warn("angle density of a rotation: theta beyond 2**52 (4.5e15) or infinite cannot be "
                          "reduced modulo 2 pi: NaN there (the CDF, continued by whole turns, is +-inf at "
                          "+-inf)", RuntimeWarning, stacklevel=4)
        flat = np.ascontiguousarray(theta, dtype=np.float64).reshape(-1)
        turns, s, c = _kernel.half_angle_v(flat)
        shape = np.shape(theta)
        return turns.reshape(shape), s.reshape(shape), c.reshape(shape)

    def density(self, theta):
        out = np.zeros_like(theta)
        if self.kind == "cycloid":
            r = self.r
            x = 4 * r * np.sin(theta) - self.centre
            inside = (np.abs(x) < self.amp) & (np.abs(theta) <= math.pi / 2)
            xi = x[inside]
            out[inside] = 4 * r * np.cos(theta[inside]) / (math.pi * np.sqrt((self.amp - xi) * (self.amp + xi)))
            out[np.isnan(theta)] = np.nan
            return out
        if self.kind == "libration" and self.tiny:
            inside = np.abs(theta) < self.thm
            a, x = self.thm * 2.0 ** 600, np.abs(theta[inside]) * 2.0 ** 600
            out[inside] = 2.0 ** 600 / (math.pi * np.sqrt((a - x) * (a + x)))
            out[np.isnan(theta)] = np.nan
            return out
        if self.kind == "libration":
            inside = np.abs(theta) < self.thm
            if np.any(inside):
                sn, cs, kc = self._phi(theta[inside])
                U = self._f(sn, cs)
                out[inside] = self._h(U) / (self.T * kc)
            out[np.isnan(theta)] = np.nan
            return out
        # rotation: one turn on [-pi, pi)
        _, s, c = self._turn(theta)
        U = self._f(s, c)
        # 1 - m sin^2(w/2) = mc + m cos^2(w/2): no cancellation next to the separatrix
        return self._h(U) / (2 * self.T * np.sqrt(self.mc + self.orbit.m * c ** 2))

    def cdf(self, theta):
        if self.kind == "cycloid":
            x = 4 * self.r * np.sin(np.clip(theta, -math.pi / 2, math.pi / 2)) - self.centre
            out = 0.5 + np.arcsin(np.clip(x / self.amp, -1.0, 1.0)) / math.pi
            out = np.where(theta > math.pi / 2, 1.0, np.where(theta < -math.pi / 2, 0.0, out))
            return np.where(np.isnan(theta), np.nan, out)
        if self.kind == "libration" and self.tiny:
            out = 0.5 + np.arcsin(np.clip(theta / self.thm, -1.0, 1.0)) / math.pi
            return np.where(np.isnan(theta), np.nan, out)
        if self.kind == "libration":
            sn, cs, _ = self._phi(np.clip(theta, -self.thm, self.thm))
            U = self._f(sn, cs)
            out = 0.5 + np.sign(theta) * 2.0 * self._time(U) / self.T
            out = np.where(theta >= self.thm, 1.0, np.where(theta <= -self.thm, 0.0, out))
            return np.where(np.isnan(theta), np.nan, np.clip(out, 0.0, 1.0))
        # rotation: the CDF over [-pi, pi), continued by whole turns
        turns, s, c = self._turn(theta)
        U = self._f(s, c)
        out = turns + 0.5 + self._time(U) / self.T
        return np.where(np.isinf(theta), theta, out)     # continued by whole turns: +-inf at +-inf


def angle_density(scene: Scene, theta: ArrayLike) -> NDArray[np.float64] | np.float64:
    """The time-averaged probability density of the angle over one period.

    Parameters
    ----------
    scene : Scene
        A conservative scene: the rigid pendulum in uniform or non-uniform
        gravity, or the cycloidal pendulum (torque allowed there).
    theta : array_like
        Angles.  Libration: the density lives on (-theta_max, theta_max) and
        is 0 outside; rotation: over one turn, theta reduced modulo 2 pi into
        [-pi, pi] exactly (as numpy's sin reduces its argument), so the
        density is 2 pi periodic (unlike :func:`angle_cdf`, which counts the
        turns); cycloid: theta is the angle of the free cord.

    Returns
    -------
    ndarray
        p(theta); it integrates to 1 over the orbit and is infinite (not
        returned: the endpoints are excluded) at the turning points.

    Raises
    ------
    TypeError
        If `scene` is not a :class:`Scene`, or for a string, complex or object `theta`.
    ValueError
        If the scene names damping or a drive (no period to average over).
    NotImplementedError
        For the flexible cord, and for the rigid pendulum with a torque.

    See Also
    --------
    angle_cdf : its integral, exact through F(phi|m).
    arcsine_density : the small-amplitude limit.

    Examples
    --------
    >>> import pendula
    >>> sc = pendula.Scene(theta0=1e-3)
    >>> p = float(pendula.angle_density(sc, 0.0))
    >>> round(p * 3.141592653589793 * 1e-3, 6)      # the arcsine law 1/(pi theta0) at 0
    1.0
    """
    theta = as_float(theta, "theta")
    return _Model(scene).density(theta)


def angle_cdf(scene: Scene, theta: ArrayLike) -> NDArray[np.float64] | np.float64:
    """The cumulative distribution of the angle over one period (see :func:`angle_density`).

    Exact through the incomplete elliptic integral F, so it is finite and
    accurate up to the turning points.

    Parameters
    ----------
    scene : Scene
        A conservative scene, as for :func:`angle_density`.
    theta : array_like
        Angles.  Rotation: any angle (up to 2^52 in magnitude), reduced
        exactly; the whole turns are counted, not wrapped.

    Returns
    -------
    ndarray
        The fraction of the period spent below theta.  Libration: 0 below
        -theta_max, 1 above theta_max.  Rotation: the fraction of a turn from
        -pi, continued by whole turns: ``angle_cdf(theta + 2 pi) =
        angle_cdf(theta) + 1``, whereas :func:`angle_density` wraps
        (``angle_density(theta + 2 pi) = angle_density(theta)``).  The CDF of
        the angle taken modulo 2 pi is ``angle_cdf(theta) % 1`` on [-pi, pi);
        beyond abs(theta) = 2^52 it is NaN with a RuntimeWarning (the turns are
        no longer exact), and +-inf at +-inf.

    Raises
    ------
    TypeError
        If `scene` is not a :class:`Scene`, or for a string, complex or object `theta`.
    ValueError
        If the scene names damping or a drive (no period to average over).
    NotImplementedError
        For the flexible cord, and for the rigid pendulum with a torque.

    See Also
    --------
    angle_density : its derivative.
    ellipf : the integral it is made of.

    Examples
    --------
    >>> import pendula
    >>> sc = pendula.Scene(theta0=2.0)
    >>> [round(float(x), 15) for x in pendula.angle_cdf(sc, [-2.0, 0.0, 2.0])]
    [0.0, 0.5, 1.0]

    A rotation counts its turns (the density, by contrast, repeats every 2 pi):

    >>> rot = pendula.Scene(v0=3.0)
    >>> [round(float(x), 12) for x in pendula.angle_cdf(rot, [0.0, 2 * 3.141592653589793])]
    [0.5, 1.5]
    """
    theta = as_float(theta, "theta")
    return _Model(scene, "angle_cdf").cdf(theta)

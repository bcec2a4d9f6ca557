"""The pendulum of the classroom: metres, seconds and degrees.

A bob on a rigid rod of length l (metres) in a uniform field g (m/s²),
released from rest at an angle given in degrees, optionally damped by a
torque proportional to its angular velocity:

    θ'' + β θ' + (g / l) sin θ = 0,

θ in radians, t in seconds, β in 1/s.  This is pendula's scene with
eps = g / l (in 1/s²): the scene's time unit is then the second itself, so
no time is rescaled anywhere.  :class:`Pendulum` converts degrees to and from
radians and hands the rest to the library: the period comes from the exact
solution (:func:`pendula.period`, 4 K(m) / √(g / l) with m = sin²(θ₀ / 2)),
the motion from :func:`pendula.simulate` (exact Jacobi functions without
damping, an integrator with it), and :attr:`Pendulum.scene` is the scene for
everything else (spectra, events, sweeps, figures).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from . import _checks
from .motion import period as _period
from .motion import simulate
from .scene import Scene
from .trajectory import Trajectory

__all__ = ["Pendulum", "Swing", "STANDARD_GRAVITY"]

#: the standard acceleration of gravity g_n, m/s² (exact, by definition: CGPM 1901)
STANDARD_GRAVITY = 9.80665


@dataclass(frozen=True)
class Swing:
    """The motion of a :class:`Pendulum` in degrees and seconds.

    Attributes
    ----------
    t : numpy.ndarray
        Times, s.
    angle : numpy.ndarray
        The angle from the downward vertical, degrees (continuous: a pendulum
        that goes over the top counts on past 180).
    angular_velocity : numpy.ndarray
        dθ/dt, degrees per second.
    trajectory : Trajectory
        The same motion in the library's units (radians, rad/s, seconds):
        what :func:`pendula.simulate` returned, for the figures of
        ``pendula.plot`` and :meth:`Trajectory.spectrum`.

    See Also
    --------
    Pendulum.motion : makes it.

    Examples
    --------
    >>> import pendula
    >>> sw = pendula.Pendulum(1.0, amplitude_deg=10).motion([0.0, 1.0])
    >>> sw.angle.round(4).tolist()
    [10.0, -9.9987]
    >>> sw
    Swing(2 samples, t from 0 to 1 s, angle from -9.99872 to 10 deg, method 'exact')
    """

    t: np.ndarray
    angle: np.ndarray
    angular_velocity: np.ndarray
    trajectory: Trajectory

    def __repr__(self) -> str:
        n = np.size(self.t)
        if not n:
            return "Swing(0 samples)"
        return (f"Swing({n} samples, t from {self.t[0]:.6g} to {self.t[-1]:.6g} s, angle from "
                f"{np.nanmin(self.angle):.6g} to {np.nanmax(self.angle):.6g} deg, "
                f"method {self.trajectory.method!r})")


class Pendulum:
    """A simple pendulum in laboratory units: metres, seconds, degrees.

    θ'' + β θ' + (g / l) sin θ = 0 with the bob released from rest at
    ``amplitude_deg``.  The equivalent scene has eps = g / l in 1/s², so its
    times are seconds (nothing is rescaled) and β is the scene's ``damping``.

    Parameters
    ----------
    length : float
        The length l from the pivot to the bob's centre, m (> 0).
    g : float
        The acceleration of gravity, m/s² (> 0; default the standard 9.80665).
    amplitude_deg : float
        The release angle from the downward vertical, degrees, the bob at rest
        (0 <= amplitude_deg <= 180).  180 becomes the double nearest π,
        1.2e-16 below it: as near the unstable rest upside down as a double
        can start, a swing with a long but finite period (49.5 s for 1 m).
    damping : float
        β, 1/s (>= 0): the damping torque per moment of inertia is −β θ'.
        The amplitude of small swings decays as exp(−β t / 2).

    Raises
    ------
    TypeError
        A parameter that is not a real number, naming it.
    ValueError
        A parameter out of range, naming it.

    See Also
    --------
    Scene : the pendulum in the library's units (``eps``, radians).
    Junction : the Josephson junction in amperes and volts.

    Examples
    --------
    >>> import pendula
    >>> p = pendula.Pendulum(length=1.0, amplitude_deg=30)
    >>> p
    Pendulum(length=1 m, g=9.80665 m/s², amplitude 30°, period 2.0413 s)
    >>> round(p.period, 6), round(p.small_angle_period, 6)     # seconds
    (2.041338, 2.006409)
    >>> p.scene
    Scene(eps=9.80665, theta0=0.5235987755982988)
    >>> round(float(p.motion([p.period / 2]).angle[0]), 9)       # the far side
    -30.0
    """

    def __init__(self, length: float, g: float = STANDARD_GRAVITY, amplitude_deg: float = 0.0,
                 damping: float = 0.0) -> None:
        self.length = _checks.real(length, "parameter 'length'", 0.0, lo_open=True)
        self.g = _checks.real(g, "parameter 'g'", 0.0, lo_open=True)
        self.amplitude_deg = _checks.real(amplitude_deg, "parameter 'amplitude_deg'", 0.0, 180.0)
        self.damping = _checks.real(damping, "parameter 'damping'", 0.0)
        # the scene checks eps = g / l against its own range (a SceneError naming 'eps')
        self.scene = Scene(eps=self.g / self.length, theta0=math.radians(self.amplitude_deg),
                           damping=self.damping)

    def __repr__(self) -> str:
        damped = f", damping {self.damping:g}/s" if self.damping else ""
        try:
            per = f", period {self.period:.5g} s" if not self.damping else ""
        except ValueError:   # no period to show: say nothing rather than a wrong one
            per = ""
        return (f"Pendulum(length={self.length:g} m, g={self.g:g} m/s², amplitude {self.amplitude_deg:g}°"
                f"{damped}{per})")

    @property
    def period(self) -> float:
        """The exact period of the undamped swing, s: 4 K(m) √(l / g), m = sin²(θ₀ / 2).

        Computed by :func:`pendula.period` on :attr:`scene`.

        Raises
        ------
        ValueError
            With damping: a damped swing has no period in this sense (see
            :func:`pendula.numerical_period` for one measured by events).
        """
        return _period(self.scene)

    @property
    def small_angle_period(self) -> float:
        """2π √(l / g), s: the period of vanishingly small swings (Galileo's)."""
        return 2.0 * math.pi * math.sqrt(self.length / self.g)

    @property
    def frequency(self) -> float:
        """1 / period, Hz."""
        return 1.0 / self.period

    def motion(self, t: ArrayLike | None = None) -> Swing:
        """The angle (degrees) and angular velocity (degrees/s) at the times ``t`` (s).

        Parameters
        ----------
        t : array_like, optional
            Times in seconds (any order, may be negative).  Default: three
            small-angle periods in 301 samples.

        Returns
        -------
        Swing
            ``t``, ``angle``, ``angular_velocity`` and the library's
            :class:`Trajectory` (radians) of the same motion.

        Raises
        ------
        ValueError
            Times that are not finite numbers.

        Examples
        --------
        >>> import pendula
        >>> p = pendula.Pendulum(0.5, amplitude_deg=20, damping=0.1)
        >>> sw = p.motion()
        >>> len(sw.t), sw.trajectory.method != "exact"       # damping: integrated
        (301, True)
        """
        if t is None:
            t = np.linspace(0.0, 3.0 * self.small_angle_period, 301)
        t = _checks.as_float(t, "t")
        if not np.all(np.isfinite(t)):
            raise ValueError("t must be finite times in seconds")
        tr = simulate(self.scene, t)
        return Swing(t=tr.t, angle=np.degrees(tr.theta), angular_velocity=np.degrees(tr.v), trajectory=tr)

"""The time-averaged density of the angle (Prusa & Tuma, task 5).

Over one period of a conservative orbit the pendulum spends the time
dt = dtheta / |theta'(theta)| near each angle, so the angle's density is
p(theta) = 2 / (T |theta'(theta)|) for a libration (on [-theta_max,
theta_max] around its well) and 1 / (T |theta'|) over one turn of a rotation
(theta taken modulo 2 pi in [-pi, pi)).  Its cumulative distribution is the
fraction of the period spent below theta: the time to reach theta is an
incomplete elliptic integral, so the CDF is exact through F and stays finite
and accurate up to the turning points where the density blows up:

* libration:  CDF = (F(phi | k^2) + K) / (2K),  sin(phi) = sin(theta/2) / k;
* rotation:   CDF = (F(theta/2 | 1/k^2) + K') / (2K'),  theta in [-pi, pi];
* cycloidal guide: the arcsine law in s = 4R sin(theta) at every amplitude,
  CDF = 1/2 + asin(s / A) / pi.

In the small-amplitude limit the libration's density tends to the arcsine law
1 / (pi sqrt(theta_max^2 - theta^2)) of the harmonic oscillator.
"""

from __future__ import annotations

import math

import numpy as np

from ._checks import as_float
from .elliptic import ellipf, ellipk
from .scene import Scene
from .systems.rigid import orbit

__all__ = ["angle_density", "angle_cdf", "arcsine_density"]


def _libration_parts(scene: Scene, theta):
    """The orbit, theta in the scene's well, and k^2 - sin^2(theta/2) without
    cancellation next to the turning points: sin((a - x)/2) sin((a + x)/2) + w^2
    (a = theta0 in its well, w = v0 / (2 sqrt eps)); through 1 - (sin(x/2)/k)^2
    the rounding of k alone cost 1e-10 of the CDF there."""
    o = orbit(scene.theta0, scene.v0, scene.eps)
    th = as_float(theta, "theta")
    well = 2 * math.pi * round(scene.theta0 / (2 * math.pi))
    x = th - well
    a = scene.theta0 - well
    w = scene.v0 / (2 * math.sqrt(scene.eps))
    d2 = np.sin(0.5 * (a - x)) * np.sin(0.5 * (a + x)) + w * w
    return o, x, d2


def _check(scene: Scene) -> str:
    if not isinstance(scene, Scene):
        raise TypeError(f"expects a pendula.Scene, got {type(scene).__name__}")
    scene.require_implemented()
    if scene.guide == "cycloid":
        if scene.damping or scene.torque or scene.drive_amplitude:
            raise ValueError("the angle's density is that of a conservative orbit: the scene names "
                             + ", ".join(e for e in scene.effects if e != "guide"))
        return "cycloid"
    if not scene.is_conservative_rigid:
        raise ValueError("the angle's density is that of a conservative orbit: the scene names "
                         + ", ".join(scene.effects))
    o = orbit(scene.theta0, scene.v0, scene.eps)
    if o.regime == "separatrix":
        raise ValueError("the separatrix has no time-averaged density (its period is infinite: "
                         "all the time is spent next to the top)")
    if o.k == 0.0:
        raise ValueError("at rest at the bottom the angle has no spread: its density is a point mass at 0")
    return o.regime


def _cycloid_amplitude(scene: Scene):
    c4 = 4 * scene.guide_radius
    s0 = c4 * math.sin(scene.theta0)
    sd0 = c4 * math.cos(scene.theta0) * scene.v0
    w2 = scene.eps / c4
    a = math.sqrt(s0 * s0 + sd0 * sd0 / w2)
    if a > c4:
        raise ValueError("the motion reaches the cusps of the cycloidal guide (|s| = 4R)")
    if a == 0.0:
        raise ValueError("at rest at the bottom the angle has no spread: its density is a point mass at 0")
    return c4, a


def angle_density(scene: Scene, theta):
    """The time-averaged density p(theta) of the scene's conservative orbit.

    Parameters
    ----------
    scene : Scene
        A conservative rigid pendulum (libration or rotation) or a
        conservative cycloidal guide.
    theta : array_like
        Angles; for a libration measured in the scene's own well (theta0's),
        for a rotation taken modulo 2 pi.

    Returns
    -------
    ndarray
        p(theta); 0 outside the range the orbit visits, +inf at a turning point.

    Examples
    --------
    >>> import pendula
    >>> s = pendula.Scene(theta0=1.0)
    >>> p = pendula.angle_density(s, [0.0, 0.5])
    >>> bool(p[1] > p[0])              # more time near the turning points
    True
    """
    kind = _check(scene)
    th = as_float(theta, "theta")
    with np.errstate(divide="ignore", invalid="ignore"):
        if kind == "cycloid":
            c4, a = _cycloid_amplitude(scene)
            s = c4 * np.sin(th)
            inside = (np.abs(th) < math.pi / 2) & (np.abs(s) <= a)
            d = np.sqrt((a - s) * (a + s))
            p = np.where(inside, c4 * np.cos(th) / (math.pi * d), 0.0)
            return p[()] if p.ndim == 0 else p
        o = orbit(scene.theta0, scene.v0, scene.eps)
        if kind == "libration":
            _, x, d2 = _libration_parts(scene, th)
            K = float(ellipk(o.m, mc=o.mc))
            p = np.where((np.abs(x) <= o.theta_max) & (d2 >= 0), 1.0 / (4 * K * np.sqrt(d2)), 0.0)
        else:
            Kr = float(ellipk(o.m, mc=o.mc))
            x = np.remainder(th + math.pi, 2 * math.pi) - math.pi
            p = 1.0 / (4 * Kr * np.sqrt(1.0 - o.m * np.sin(0.5 * x) ** 2))
    return p[()] if np.ndim(p) == 0 else p


def angle_cdf(scene: Scene, theta):
    """The fraction of one period the orbit spends at angles below theta (exact, through F).

    Same conventions as :func:`angle_density`; 0 below the orbit's range, 1
    above it, and finite and accurate up to the turning points.

    Examples
    --------
    >>> import pendula
    >>> s = pendula.Scene(theta0=1.0)
    >>> float(pendula.angle_cdf(s, 0.0))     # symmetric: half the time on each side
    0.5
    """
    kind = _check(scene)
    th = as_float(theta, "theta")
    if kind == "cycloid":
        c4, a = _cycloid_amplitude(scene)
        r = np.clip(c4 * np.sin(np.clip(th, -math.pi / 2, math.pi / 2)) / a, -1.0, 1.0)
        out = 0.5 + np.arcsin(r) / math.pi
        return out[()] if out.ndim == 0 else out
    o = orbit(scene.theta0, scene.v0, scene.eps)
    if kind == "libration":
        _, x, d2 = _libration_parts(scene, th)
        K = float(ellipk(o.m, mc=o.mc))
        # phi from its sine and its cosine, the cosine without cancellation
        inside = np.abs(x) < o.theta_max
        sh = np.where(inside, np.sin(0.5 * x), np.sign(x) * o.k)
        c = np.where(inside, np.sqrt(np.maximum(d2, 0.0)), 0.0) / o.k
        phi = np.arctan2(sh / o.k, c)
        out = (np.asarray(ellipf(phi, o.m, mc=o.mc)) + K) / (2 * K)
    else:
        Kr = float(ellipk(o.m, mc=o.mc))
        x = np.clip(th, -math.pi, math.pi)
        out = (np.asarray(ellipf(0.5 * x, o.m, mc=o.mc)) + Kr) / (2 * Kr)
    out = np.clip(out, 0.0, 1.0)
    return out[()] if out.ndim == 0 else out


def arcsine_density(theta, amplitude: float):
    """The harmonic oscillator's density 1 / (pi sqrt(a^2 - theta^2)) on (-a, a)."""
    th = as_float(theta, "theta")
    a = float(as_float(amplitude, "amplitude"))
    with np.errstate(divide="ignore", invalid="ignore"):
        p = np.where(np.abs(th) < a, 1.0 / (math.pi * np.sqrt(np.maximum(a * a - th * th, 0.0))), 0.0)
    return p[()] if p.ndim == 0 else p

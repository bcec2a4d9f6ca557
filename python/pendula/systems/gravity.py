"""Non-uniform gravity (Prusa & Tuma, task 4): the rigid pendulum in a
conservative field that is not uniform.

Fields (scene ``gravity``), each parameterised so that g is the strength at the
lowest point of the circle and each reducing to the uniform field in a limit:

- 'inverse-square': a point mass at D = ``gravity_distance`` * l below the
  pivot (D > l): V = eps (d-1)^2 (1/(d-1) - 1/rho), rho the bob's distance to
  the mass in units of l; uniform as d -> infinity.
- 'linear': g(h) = g (1 - kappa h / l), h the height above the lowest point,
  kappa = ``gravity_gradient`` < 1/2: V = eps (u - kappa u^2 / 2), u = 1 - cos
  theta; uniform at kappa = 0.

The motion is conservative and one-dimensional: integrated (energy is the
check of every integration) and, for the period, the exact quadrature of the
energy integral after the substitution sin(theta/2) = sqrt(w_m) sn(u | w_m),
which removes the inverse-square-root endpoints (kernel/models/pendula_gravity.f90).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _kernel
from .._checks import as_float
from ..scene import Scene
from .contract import require

__all__ = ["KINDS", "field_of", "potential", "acceleration", "gravity_orbit", "GravityOrbit",
           "small_oscillation_omega"]

KINDS = {"uniform": 0, "inverse-square": 1, "linear": 2}
_REGIMES = {0: "libration", 1: "separatrix", 2: "rotation"}
_STATUS = {1: "bad field parameters (eps > 0; gravity_distance > 1; gravity_gradient < 0.5)",
           2: "theta0 and v0 must be finite",
           3: "the period quadrature did not converge in 2^20 panels ({field})",
           4: "theta0 beyond 2**52 (4.5e15) cannot be reduced modulo 2 pi in double precision",
           5: "v0 must stay below 1e150 in a non-uniform field (its square must be a double)",
           6: "this orbit is beyond double precision in this field ({field}): a quantity of it under- or "
              "overflows"}


def _field_words(scene) -> str:
    if scene.gravity == "inverse-square":
        return (f"inverse-square field, gravity_distance = {scene.gravity_distance!r}: the mass closer than "
                f"about 2e-5 l below the circle, or eps = {scene.eps!r} extreme")
    if scene.gravity == "linear":
        return f"linear field, gravity_gradient = {scene.gravity_gradient!r}, eps = {scene.eps!r}"
    return f"uniform field, eps = {scene.eps!r}"


def field_of(scene) -> tuple[int, float]:
    """(kernel kind, parameter) of the scene's gravity field."""
    kind = KINDS[scene.gravity]
    par = {0: 0.0, 1: scene.gravity_distance, 2: scene.gravity_gradient}[kind]
    return kind, float(par)


def _field(scene, theta):
    kind, par = field_of(scene)
    theta = as_float(theta, "theta")
    flat = np.ascontiguousarray(theta, dtype=np.float64).reshape(-1)
    pot, acc, status = _kernel.gravity_field_v(kind, par, scene.eps, flat)
    if status:
        raise ValueError(_STATUS[1])
    return pot.reshape(theta.shape), acc.reshape(theta.shape)


def potential(scene, theta):
    """V(theta) per m l^2 of the scene's field (V(0) = 0)."""
    return _field(scene, theta)[0]


def acceleration(scene, theta):
    """theta'' = -V'(theta) of the scene's field (no other effects)."""
    return _field(scene, theta)[1]


def small_oscillation_omega(scene) -> float:
    """sqrt(V''(0)).  Linear field: V''(0) = eps.  Inverse-square: V''(0) =
    eps d / (d - 1), larger than eps although g is the same at the bottom: the
    field lines converge on the point mass, so a displaced bob is also pulled
    sideways towards the axis."""
    kind, par = field_of(scene)
    if kind == 1:
        return math.sqrt(scene.eps * par / (par - 1.0))
    return math.sqrt(scene.eps)


@dataclass(frozen=True)
class GravityOrbit:
    """The orbit through the scene's initial state in its gravity field.

    Attributes
    ----------
    regime : str
        'libration', 'separatrix' or 'rotation'.
    energy : float
        E = v0^2/2 + V(theta0).
    m, K : float
        Parameter of the substitution (w_m = sin^2(theta_max/2) in libration,
        V(pi)/E in rotation) and K(m).
    mc : float
        1 - m, formed without cancellation (it sets K near the separatrix).
    theta_max : float
        Amplitude (pi on the separatrix, inf for a rotation).
    period : float
        Period of the libration, time of one turn of a rotation, inf on the separatrix.
    omega : float
        2 pi / period (0 on the separatrix), as :class:`pendula.Orbit` has it.

    The facts both orbits give have the same names in both: ``regime``, ``m``,
    ``mc``, ``period``, ``omega``, ``theta_max``.
    """

    regime: str
    energy: float
    m: float
    K: float
    theta_max: float
    period: float
    mc: float

    @property
    def omega(self) -> float:
        """2 pi / period, 0 on the separatrix (the name :class:`pendula.Orbit` gives it)."""
        return 2 * math.pi / self.period if math.isfinite(self.period) else 0.0


def gravity_orbit(scene: Scene) -> GravityOrbit:
    """Energy, regime, amplitude and period of the scene's orbit (exact quadrature).

    One classifier for every field: the regime is the sign of the distance from
    the separatrix f(1) - E = Q(w0, 1) cos^2(theta0/2) - v0^2/2, formed in
    double-double, and mc follows from it; the uniform field is answered by the
    exact pendulum itself (the same bits as :func:`pendula.orbit`).

    Both fields depend on theta through w = sin^2(theta/2) only, so the
    substitution sin(theta/2) = sqrt(w_m) sn(u | w_m) turns the energy
    integral into T = 4 int_0^K h(u) du with h smooth and periodic, which the
    trapezoid rule integrates to a few eps.

    Parameters
    ----------
    scene : Scene
        A conservative scene in uniform or non-uniform gravity (``gravity``
        and its ``gravity_distance`` or ``gravity_gradient``).

    Returns
    -------
    GravityOrbit
        regime, energy, m, K, theta_max, period, mc (the fields of
        :class:`Orbit` it shares have the same meaning).

    Raises
    ------
    TypeError
        scene is not a :class:`pendula.Scene`.
    ValueError
        theta0 beyond 2^52, v0 beyond 1e150, eps beyond 1e300, or the
        inverse-square mass closer than about 2e-5 l below the circle (the
        quadrature of the period does not converge); the message names it.

    See Also
    --------
    period : the period of any conservative scene.
    orbit : the same facts in uniform gravity.

    Examples
    --------
    >>> import pendula
    >>> o = pendula.gravity_orbit(pendula.Scene(gravity='linear', gravity_gradient=0.2, theta0=1.0))
    >>> o.regime, round(o.theta_max, 15)
    ('libration', 1.0)
    >>> s = pendula.Scene(gravity="inverse-square", gravity_distance=2.0, theta0=2.5)
    >>> pendula.gravity_orbit(s).period == pendula.period(s)
    True
    """
    from ..scene import Scene

    if not isinstance(scene, Scene):
        raise TypeError(f"gravity_orbit: scene must be a pendula.Scene, got {type(scene).__name__}")
    require(scene, "gravity_orbit")     # the conservative orbit: every effect refused by name
    kind, par = field_of(scene)
    info, status = _kernel.gravity_orbit_v(kind, par, scene.eps, scene.theta0, scene.v0)
    if status:
        raise ValueError("gravity_orbit: " + _STATUS.get(status, f"kernel status {status}").format(
            field=_field_words(scene)))
    return GravityOrbit(_REGIMES[int(info[0])], *(float(x) for x in info[1:7]))


def h_samples(scene, orb: GravityOrbit, u):
    """The integrand h(u) of t = int_0^U h du at the nodes u (libration or rotation)."""
    kind, par = field_of(scene)
    u = np.ascontiguousarray(u, dtype=np.float64)
    return _kernel.gravity_h_v(kind, par, scene.eps, 0 if orb.regime == "libration" else 2, orb.m, orb.mc,
                               orb.energy, u)


def model_orbit_facts(scene):
    """The orbit facts (a :class:`pendula.Orbit`) of a conservative cycloid scene (the
    guide, perhaps a torque) or of a scene whose only effect is non-uniform gravity;
    None for any other scene.  k is sqrt(m) in libration and 1/sqrt(m) in rotation
    (the rigid pendulum's k in uniform gravity); on the cycloid k, m, mc are NaN."""
    from .rigid import Orbit

    nan = math.nan
    if scene.guide == "cycloid" and set(scene.effects) <= {"guide", "torque"}:
        from .cycloid import cycloid_amplitude, cycloid_period

        r = scene.cycloid_radius
        c, a = cycloid_amplitude(scene)
        T = cycloid_period(scene)
        return Orbit("libration", nan, nan, nan, T, 2 * math.pi / T, math.asin((c + a) / (4 * r)))
    if scene.effects == ("gravity",):
        o = gravity_orbit(scene)
        k = math.sqrt(o.m) if o.regime == "libration" else (1 / math.sqrt(o.m) if o.regime == "rotation" else 1.0)
        omega = 0.0 if math.isinf(o.period) else 2 * math.pi / o.period
        return Orbit(o.regime, k, o.m, o.mc, o.period, omega, o.theta_max)
    return None

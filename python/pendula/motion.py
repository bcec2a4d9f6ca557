"""The motion of a scene: simulate() and period().

The conservative rigid pendulum is answered exactly (pendula.models.rigid);
scenes that name effects (damping, torque, drive, ...) go to the integrators.
The rigid model's functions are re-exported here for compatibility.
"""

from __future__ import annotations

from ._checks import as_float
from .models.rigid import Orbit, energy, exact_motion, orbit
from .scene import Scene
from .trajectory import Trajectory

__all__ = ["Orbit", "Trajectory", "orbit", "exact_motion", "energy", "simulate", "period"]


def simulate(scene: Scene, t=None, method: str | None = None) -> Trajectory:
    """Run one scene at the times ``t`` (default: the scene's own output times).

    The initial state is at t = 0; the times need not start at 0 or be
    increasing.  With method 'auto' (the default) a conservative rigid scene is
    answered by the exact solution, never by an integrator.  A scene with a
    sweep is run at its own (un-swept) values; use ``scene.members()`` for the
    family.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"simulate expects a pendula.Scene, got {type(scene).__name__}")
    t = scene.times() if t is None else as_float(t, "t")
    method = method or scene.method
    scene.require_implemented()
    # ---- flexible cord (Garfinkel): its own model, exact where the physics allows -----------
    if scene.cord == "flexible":
        from .models.cord import simulate_cord

        return simulate_cord(scene.replace(method=method), t)
    # ---- end flexible cord ----------------------------------------------------------------
    if method in ("auto", "exact") and scene.is_conservative_rigid:
        theta, v = exact_motion(scene.theta0, scene.v0, scene.eps, t)
        return Trajectory(t, theta, v, energy(theta, v, scene.eps), "exact", scene)
    if method == "exact":
        raise ValueError(f"method 'exact' answers only the conservative rigid pendulum; "
                         f"the scene names {', '.join(scene.effects)}")
    from .integrate import integrate_scene

    return integrate_scene(scene, t, method)


def period(scene: Scene) -> float:
    """The period of the scene's conservative orbit (exact): see :class:`Orbit`.

    A scene with effects has no period in this sense: ValueError.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"period expects a pendula.Scene, got {type(scene).__name__}")
    if not scene.is_conservative_rigid:
        raise ValueError(f"period(scene) is the exact period of a conservative orbit; the scene names "
                         f"{', '.join(scene.effects)} (see pendula.numerical_period for event-based periods)")
    return orbit(scene.theta0, scene.v0, scene.eps).period

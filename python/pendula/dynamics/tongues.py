"""Arnold tongues of the driven pendulum: the Shapiro steps of a Josephson junction as fold curves.

Step n of a junction under a dc bias (the torque) and an rf drive (the drive's amplitude and
frequency) is the range of bias where the phase is locked to the drive, advancing n turns per
drive period: a periodic orbit of the stroboscopic map with winding n.  It exists between two
saddle-nodes (folds) of that orbit, where the stable locked orbit meets the unstable one; in the
plane of the bias and the rf amplitude the folds form two curves, the step's edges, which bound an
Arnold tongue (Arnold, *Geometrical Methods in the Theory of Ordinary Differential Equations*,
section 11; for the junction, Likharev, *Dynamics of Josephson Junctions and Circuits*, section
10.2).  Each edge is found by :func:`.continuation.continue_orbit` in the torque and followed in the
rf amplitude by :func:`.bifurcation_curves.continue_bifurcation`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .. import _checks
from ..scene import Scene
from .bifurcation_curves import BifurcationCurve, continue_bifurcation
from .branches import ContinuationError
from .continuation import continue_orbit
from .periodic import NewtonError, OrbitProblem, newton

__all__ = ["ShapiroTongue", "shapiro_tongue"]


@dataclass(frozen=True)
class ShapiroTongue:
    """The edges of one Shapiro step (an Arnold tongue) in the plane of the bias torque and the rf amplitude.

    Attributes
    ----------
    scene : Scene
        The scene the tongue started from (its damping and drive frequency hold along the tongue).
    n : int
        The step: the locked orbit advances n turns per ``q`` drive periods (mean velocity
        n drive_frequency / q).
    q : int
        The drive periods of the locked orbit (1 for an integer step).
    lower, upper : BifurcationCurve
        The lower and upper edges: fold curves of the locked orbit in (``torque``, ``drive_amplitude``),
        ``first`` the torque and ``second`` the rf amplitude at each point.
    critical_current : float or None
        The junction's I_c (A) when made by :meth:`pendula.Junction.shapiro_tongue`: ``lab_edges`` gives
        amperes.

    See Also
    --------
    shapiro_tongue : makes it.

    Examples
    --------
    >>> import pendula
    >>> sc = pendula.Scene(damping=1.0, drive_amplitude=1.0, drive_frequency=2.0)
    >>> tongue = pendula.shapiro_tongue(sc, 1, 1.1)
    >>> lo, hi = tongue.edges()
    >>> bool(lo[-1] < 2.0 < hi[-1])               # the step n = 1 holds the torque damping * n * frequency
    True
    """

    scene: Scene
    n: int
    lower: BifurcationCurve
    upper: BifurcationCurve
    q: int = 1
    critical_current: float | None = field(default=None, repr=False)

    def lab_edges(self) -> dict[str, np.ndarray]:
        """The edges in amperes: the bias (torque times I_c) and the rf current (amplitude times I_c).

        Returns
        -------
        dict
            ``lower_bias``, ``lower_rf``, ``upper_bias``, ``upper_rf`` (A), point by point along each edge.

        Raises
        ------
        ValueError
            A tongue in reduced units only (not made by :meth:`pendula.Junction.shapiro_tongue`).

        Examples
        --------
        >>> import pendula
        >>> t = pendula.Junction(1e-6, 10.0, 1e-11).shapiro_tongue(1, 1e-6, 20e9, 1.1e-6)
        >>> sorted(t.lab_edges())
        ['lower_bias', 'lower_rf', 'upper_bias', 'upper_rf']
        """
        ic = self.critical_current
        if ic is None:
            raise ValueError("critical_current: this tongue is in reduced units (make it with "
                             "Junction.shapiro_tongue for amperes)")
        return {"lower_bias": self.lower.first * ic, "lower_rf": self.lower.second * ic,
                "upper_bias": self.upper.first * ic, "upper_rf": self.upper.second * ic}

    def edges(self) -> tuple[np.ndarray, np.ndarray]:
        """The torques of the lower and upper edges at their points (each curve's ``first``).

        Returns
        -------
        tuple of numpy.ndarray
            ``(lower.first, upper.first)``; their rf amplitudes are ``lower.second`` and ``upper.second``.

        Examples
        --------
        >>> import pendula
        >>> sc = pendula.Scene(damping=1.0, drive_amplitude=1.0, drive_frequency=2.0)
        >>> lo, hi = pendula.shapiro_tongue(sc, 1, 1.1).edges()
        >>> bool(hi[-1] - lo[-1] > 0)
        True
        """
        return self.lower.first, self.upper.first

    def __repr__(self) -> str:
        def side(c):
            if not len(c):
                return "[]"
            return f"[{c.first[0]:.6g} at a={c.second[0]:.6g} .. {c.first[-1]:.6g} at a={c.second[-1]:.6g}]"
        step = f"{self.n}" if self.q == 1 else f"{self.n}/{self.q}"
        return (f"ShapiroTongue(n={step}, damping={self.scene.damping:.6g}, "
                f"drive_frequency={self.scene.drive_frequency:.6g}, lower={side(self.lower)}, "
                f"upper={side(self.upper)}, ends=({self.lower.end!r}, {self.upper.end!r}))")


def _locked_orbit(scene: Scene, n: int, guess, q: int = 1) -> tuple[float, np.ndarray]:
    """A locked orbit of winding n and its torque: for a section phase theta0 the torque is an unknown
    and theta = theta0 the extra equation (every phase is a fixed point of the map at some torque on the
    step's closed branch), by the one Newton core; eight phases are tried, or the guess."""
    omega = scene.drive_frequency
    starts = [tuple(guess)] if guess is not None else [(th, n * omega / q) for th in
                                                       np.linspace(-math.pi, math.pi, 8, endpoint=False)]
    prob = OrbitProblem(scene, "map", q, n, "torque")
    last = None
    for th, v in starts:
        plane = (np.array([1.0, 0.0, 0.0]), np.array([th, 0.0, 0.0]))
        try:
            u, tau, _, _ = newton(prob, (th, v), scene.torque, 1e-11, 60, plane=plane)
            return float(tau), u
        except NewtonError as exc:
            last = exc
    raise ValueError(f"scene: no orbit locked to step {n}/{q} (winding {n} per {q} drive periods) found near torque = "
                     f"{scene.torque!r} from {'the guess' if guess is not None else 'eight phases'} ({last}); "
                     "give a guess (theta, v) on the locked orbit")


def shapiro_tongue(scene: Scene, n: int, stop: float, *, q: int = 1, guess: tuple[float, float] | None = None,
                   step: float | None = None) -> ShapiroTongue:
    """The edges of Shapiro step n in the (bias torque, rf amplitude) plane, as curves.

    The junction's phase obeys the driven pendulum (``Junction.scene``:
    torque the dc bias over the critical current, ``drive_amplitude`` the rf
    current over it, ``drive_frequency`` the rf frequency over the plasma
    frequency, damping ``1 / sqrt(beta_c)``).  On step n the phase is locked,
    ``n`` turns per drive period (the dc voltage ``n h f / 2e``); the step's
    edges are the saddle-nodes of the locked orbit.  From the locked orbit at
    the scene's torque (``damping * n * drive_frequency``, the step's centre in
    the high-frequency limit, when the scene's torque is 0) both folds are
    found along the torque (:func:`continue_orbit`) and followed in the rf
    amplitude to ``stop`` (:func:`continue_bifurcation`), each to 1e-11 in the
    torque at every point.  The edges bound where the locked orbit exists;
    next to each edge it attracts (its other multiplier is exp(-damping T) <
    1), but where it loses stability inside the step (a period doubling, as
    at small damping) the step seen on an I-V curve has a hole there.

    Parameters
    ----------
    scene : Scene
        A driven pendulum (``drive_amplitude`` and ``drive_frequency`` > 0) with damping.
    n : int
        The step, n >= 1 (with ``q``: the fractional step n/q).
    stop : float
        The rf amplitude (``drive_amplitude``) to follow the edges to (> 0).
    q : int, optional
        The drive periods of the locked orbit (default 1): ``q > 1`` asks for the fractional
        (subharmonic) step n/q, n turns in q drive periods, dc voltage (n/q) h f / 2e.
    guess : (float, float), optional
        A state ``(theta, v)`` near the locked orbit; default eight phases at ``v = n drive_frequency``.
    step : float, optional
        The first arclength step of the edges (as :func:`continue_bifurcation`).

    Returns
    -------
    ShapiroTongue
        The lower and upper edges as fold curves, with their end reasons.

    Raises
    ------
    TypeError
        An argument that is not of its kind.
    ValueError
        ``n`` below 1, a scene without drive or damping, ``stop`` not above 0 or
        equal to the scene's rf amplitude, or no locked orbit at the scene's
        torque (naming the argument).
    ContinuationError
        The locked orbit's branch in the torque has no fold (its ``branch`` holds it).

    See Also
    --------
    continue_bifurcation : the fold curves.
    pendula.Junction.shapiro_steps : the overdamped junction's steps at one rf amplitude.

    Examples
    --------
    >>> import pendula
    >>> sc = pendula.Scene(damping=1.0, drive_amplitude=1.0, drive_frequency=2.0)
    >>> t = pendula.shapiro_tongue(sc, 1, 1.2)
    >>> t.lower.end, t.upper.end
    ('stop', 'stop')
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a pendula.Scene, got {type(scene).__name__}")
    n = _checks.count(n, "n", 1, 10**6)
    q = _checks.count(q, "q", 1, 10**3)
    stop = _checks.real(stop, "stop")
    if not scene.drive_amplitude > 0 or not scene.drive_frequency > 0:
        raise ValueError("scene: a Shapiro step needs an rf drive (drive_amplitude and drive_frequency > 0)")
    if not scene.damping > 0:
        raise ValueError("scene: damping must be > 0 (a junction's 1 / sqrt(beta_c)); without it no orbit locks")
    if not stop > 0:
        raise ValueError(f"stop: the rf amplitude must be > 0, got {stop!r} (at 0 the scene is no longer driven)")
    if stop == scene.drive_amplitude:
        raise ValueError(f"stop: equals the scene's drive_amplitude = {stop!r}; give the amplitude to follow to")
    sc = scene if scene.torque != 0 else scene.replace(torque=scene.damping * n * scene.drive_frequency / q)
    tau, u = _locked_orbit(sc, n, guess, q)
    sc = sc.replace(torque=tau)
    span = 2.0 + abs(scene.drive_amplitude)       # the step lies within |torque - tau| < 1 + rf amplitude
    curves = []
    for side, target in (("lower", tau - span), ("upper", tau + span)):
        br = continue_orbit(sc, (float(u[0]), float(u[1])), "torque", target, k=q, winding=n)
        folds = [b for b in br.bifurcations if b.kind == "fold"]
        if not folds:
            raise ContinuationError(f"torque: the locked orbit of step {n} has no {side} fold between "
                                    f"{tau!r} and {target!r} ({br.end})", br)
        curves.append(continue_bifurcation(folds[0], "drive_amplitude", stop, step=step))
    return ShapiroTongue(scene, n, curves[0], curves[1], q)

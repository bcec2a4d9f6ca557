"""Equilibria followed as one scene field moves: the rest points at each value,
and the folds where two of them meet.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _checks
from ..scene import Scene
from ..systems.contract import require
from .branches import Bifurcation, _bifurcation_list
from .continuation import _param_value, _stop_value
from .equilibria import equilibria

__all__ = ["EquilibriumBranch", "continue_equilibria"]


@dataclass(frozen=True)
class EquilibriumBranch:
    """The equilibria of an autonomous scene against one field (:func:`continue_equilibria`).

    Attributes
    ----------
    param : str
        The scene field.
    values : numpy.ndarray
        The parameter values.
    equilibria : tuple of list of Equilibrium
        The rest points (one turn, ``(-pi, pi]``) at each value.
    bifurcations : tuple of Bifurcation
        The saddle-nodes, each where the number of rest points changes, at the last double
        on the side that has them.

    See Also
    --------
    continue_equilibria : makes it.

    Examples
    --------
    >>> import pendula
    >>> eb = pendula.continue_equilibria(pendula.Scene(damping=0.2), "torque", 1.5)
    >>> [(b.kind, b.value) for b in eb.bifurcations]
    [('saddle-node', 1.0)]
    """

    param: str
    values: np.ndarray
    equilibria: tuple
    bifurcations: tuple

    def __repr__(self) -> str:
        n = len(self.values)
        span = f" from {self.values[0]:.6g} to {self.values[-1]:.6g}" if n else ""
        counts = sorted({len(e) for e in self.equilibria})
        return (f"EquilibriumBranch({self.param}{span}, {n} values, {'-'.join(map(str, counts)) or 0} rest points "
                f"a value, bifurcations [{_bifurcation_list(self.bifurcations)}])")


def continue_equilibria(scene: Scene, param: str, stop: float, points: int = 101) -> EquilibriumBranch:
    """The equilibria and their eigenvalues against one scene field, with the saddle-nodes located exactly.

    The rest points come in closed form from the kernel (:func:`equilibria`) at
    ``points`` values from the scene's to ``stop``; where their number changes a
    saddle-node is located by bisection on the floating-point numbers to the
    last double on the side where the pair exists (for the torqued rigid
    pendulum ``|torque| = eps`` exactly).  The trace of the linearisation is
    ``-damping`` at every rest point, so no Hopf bifurcation exists: a
    damped pendulum's rest points change stability only through a saddle-node
    (and at ``damping = 0``, a centre, with no limit cycle born).

    Parameters
    ----------
    scene : Scene
        An autonomous scene (no drive).
    param : str
        The numeric scene field to move (``'torque'``, ``'eps'``, ``'damping'``, ...).
    stop : float
        The value to move it to.
    points : int, optional
        Values sampled (default 101), at least 2.

    Returns
    -------
    EquilibriumBranch

    Raises
    ------
    TypeError
        If ``param`` is not a string or ``points`` not a whole number.
    ValueError
        If the scene is driven, ``param`` is not a numeric scene field, or ``stop`` equals the start.

    See Also
    --------
    equilibria : the rest points at one value.
    continue_orbit : periodic orbits against a parameter.

    Examples
    --------
    >>> import pendula
    >>> eb = pendula.continue_equilibria(pendula.Scene(damping=0.1, torque=0.5), "eps", 0.2, points=5)
    >>> [len(e) for e in eb.equilibria], eb.bifurcations[0].value
    ([2, 2, 2, 0, 0], 0.5)
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a pendula.Scene, got {type(scene).__name__}")
    require(scene, "continue_equilibria", over=(param,))    # an autonomous smooth flow's rest points
    p0 = _param_value(scene, param)
    stop = _stop_value(scene, param, p0, stop)
    points = _checks.count(points, "points", 2, 10**6)
    values = np.linspace(p0, stop, points)
    values[-1] = stop

    def at(p):
        return equilibria(scene.replace(**{param: float(p)}))

    eqs = [at(p) for p in values]
    bifs = []
    for i in range(points - 1):
        if len(eqs[i]) != len(eqs[i + 1]):
            a, b = float(values[i]), float(values[i + 1])
            na = len(eqs[i])
            # bisection on the doubles: a keeps the count of values[i]
            for _ in range(2100):
                mid = 0.5 * (a + b)
                if mid in (a, b):
                    break
                if len(at(mid)) == na:
                    a = mid
                else:
                    b = mid
            more = a if na > len(eqs[i + 1]) else b
            # the merged pair itself where the kernel meets it (|tau| = eps exactly: one saddle-node)
            for x in (a, b):
                if any(e.kind == "saddle-node" for e in at(x)):
                    more = x
            if bifs and bifs[-1].value == more:      # the merged point was itself a sample: met twice
                continue
            merged = at(more)
            sn = [e for e in merged if e.kind == "saddle-node"] or merged
            e = min(sn, key=lambda e: abs(e.eigenvalues).min()) if sn else None
            bifs.append(Bifurcation("saddle-node", more, 0.0, e.theta if e else math.nan, 0.0,
                                    e.eigenvalues if e else np.array([math.nan, math.nan], dtype=complex),
                                    cycle=np.array([[e.theta if e else math.nan, 0.0]])))
    return EquilibriumBranch(param, values, tuple(eqs), tuple(bifs))

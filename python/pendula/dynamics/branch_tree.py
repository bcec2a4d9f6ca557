"""Whole bifurcation diagrams: a branch of periodic orbits and every branch born on it, to a depth.

From the starting orbit the branch is continued through everything (as
:func:`continue_orbit` with ``follow='branch'``); at each pitchfork the two
children (the two asymmetric orbits a symmetric one splits into) and at each
period doubling the child of twice the period are continued in turn, over the
same parameter range, each through everything again, and so on to the depth
asked for.  The parent goes on past its bifurcation on the same branch
(unstable, after a supercritical point), so the tree holds every branch met.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterator

import numpy as np

from .. import _checks
from ..scene import Scene
from .branches import Bifurcation, Branch, ContinuationError, _bifurcation_list
from ..systems.contract import time_scales
from .continuation import _Tracer, start

__all__ = ["BranchTree", "bifurcation_tree"]

#: The most branches of one tree (the work limit; 2 x 2^depth for a cascade with a pitchfork first).
MAX_BRANCHES = 256
#: The deepest tree asked for.
MAX_DEPTH = 12


@dataclass(frozen=True)
class BranchTree:
    """A branch of periodic orbits and the branches born on it (one call of :func:`bifurcation_tree`).

    Attributes
    ----------
    branch : Branch
        This branch, continued through everything over the parameter range (its ``stable`` tells where
        it attracts, its ``cycle`` holds the whole k-cycle at each point).
    origin : Bifurcation or None
        The bifurcation of the parent where this branch was born (None for the root).
    generation : int
        0 for the root, one more for each bifurcation between it and this branch.
    children : tuple of BranchTree
        The branches born at this branch's pitchforks (two each) and period doublings (one each), in the
        order met.
    missing : tuple of str
        Why a child was not continued (no child branch found next to its branch point, the depth
        reached, the work limit).

    See Also
    --------
    bifurcation_tree : makes it.
    pendula.plot.branches : draws it.

    Examples
    --------
    >>> import pendula
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2/3)
    >>> tree = pendula.bifurcation_tree(sc, (0.1, 1.9), "drive_amplitude", 1.07, depth=1)
    >>> len(tree), [b.kind for b in tree.branch.bifurcations]
    (3, ['pitchfork'])
    >>> [round(c.origin.value, 8) for c in tree.children]
    [1.00431948, 1.00431948]
    """

    branch: Branch
    origin: Bifurcation | None
    generation: int
    children: tuple
    missing: tuple = ()

    def walk(self) -> Iterator["BranchTree"]:
        """Every node of the tree, parents before their children (depth first, in the order met).

        Returns
        -------
        iterator of BranchTree

        Examples
        --------
        >>> import pendula
        >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2/3)
        >>> tree = pendula.bifurcation_tree(sc, (0.1, 1.9), "drive_amplitude", 1.07, depth=1)
        >>> [node.generation for node in tree.walk()]
        [0, 1, 1]
        """
        yield self
        for child in self.children:
            yield from child.walk()

    def branches(self) -> list[Branch]:
        """Every branch of the tree, parents before their children.

        Returns
        -------
        list of Branch

        Examples
        --------
        >>> import pendula
        >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2/3)
        >>> tree = pendula.bifurcation_tree(sc, (0.1, 1.9), "drive_amplitude", 1.07, depth=1)
        >>> [int(b.period[0]) for b in tree.branches()]
        [1, 1, 1]
        """
        return [node.branch for node in self.walk()]

    def __len__(self) -> int:
        return sum(1 for _ in self.walk())

    def __repr__(self) -> str:
        nodes = list(self.walk())
        br = self.branch
        nbif = sum(len(n.branch.bifurcations) for n in nodes)
        span = f" from {br.values[0]:.6g} to {br.values[-1]:.6g}" if len(br) else ""
        if _driven(br):
            periods = sorted({int(p) for n in nodes for p in np.unique(n.branch.period)})
            what = f"periods {periods} (drive periods)"
        else:
            what = "a running orbit"
        gens = max(n.generation for n in nodes) + 1
        return (f"BranchTree({br.param}{span}, {_count(len(nodes), 'branch')} in {_count(gens, 'generation')}, "
                f"{what}, {_count(nbif, 'bifurcation')}, {sum(len(n.missing) for n in nodes)} not followed)")

    def outline(self) -> str:
        """The tree as indented text, a line a branch: its period, points, stability and bifurcations.

        Returns
        -------
        str

        Examples
        --------
        >>> import pendula
        >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2/3)
        >>> tree = pendula.bifurcation_tree(sc, (0.1, 1.9), "drive_amplitude", 1.07, depth=1)
        >>> print(tree.outline())
        period 1 from 1 to 1.07: 43 points (4 stable), pitchfork at 1.00432; end 'stop'
          period 1 from 1.00432 to 1.07: 128 points (125 stable), period-doubling at 1.06637; end 'stop'
          period 1 from 1.00432 to 1.07: 211 points (205 stable), period-doubling at 1.06637; end 'stop'
        """
        lines = []
        for node in self.walk():
            b = node.branch
            if not len(b):
                continue
            bifs = _bifurcation_list(b.bifurcations, 3)
            what = f"period {int(b.period[0])}" if _driven(b) else "running orbit"
            lines.append(f"{'  ' * node.generation}{what} from {b.values[0]:.6g} to "
                         f"{b.values[-1]:.6g}: {len(b)} points ({int(np.sum(b.stable))} stable)"
                         f"{', ' + bifs if bifs else ''}; end {b.end!r}")
        return "\n".join(lines)


def _driven(branch: Branch) -> bool:
    """A branch of a periodically forced scene (its periods are whole drive periods)."""
    return time_scales(branch.scene).forcing_status != 1


def _count(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else ('es' if word.endswith('ch') else 's')}"


def _trace(tracer: _Tracer, prob, U, ev, t) -> Branch:
    """One branch traced to its end; one that cannot go on keeps what it traced (its end says why)."""
    try:
        tracer.run_segment(prob, U, ev, t)
    except ContinuationError as exc:
        tracer.end = f"error: {exc}"
    return tracer.branch()


def bifurcation_tree(scene: Scene, guess: tuple[float, float], param: str, stop: float, *, depth: int = 2,
                     k: int = 1, winding: int = 0, step: float | None = None) -> BranchTree:
    """A whole bifurcation diagram: a periodic orbit's branch and every branch born on it, to a depth.

    The starting orbit (found as :func:`continue_orbit` finds it) is continued
    through everything up to ``stop``; at each pitchfork both children and at
    each period doubling the child of twice the period are continued in turn
    over the range between the start and ``stop`` (each in the direction it
    leaves its branch point: away from ``stop`` after a subcritical one), and
    the branches born on them, to ``depth`` generations.  Every branch carries
    its stability and its whole k-cycle at each point (``Branch.cycle``), and
    each branch point its located parameter (to about 1e-12, as in
    :func:`continue_orbit`).  A branch that cannot be continued keeps what it
    traced (its ``end`` says why); a child not found is named in its parent's
    ``missing``.  Ctrl-C stops the call.

    Parameters
    ----------
    scene : Scene
        A driven rigid pendulum in the uniform field (or an autonomous one: its running orbit has no
        pitchfork or period doubling, so its tree is the one branch).
    guess : (float, float)
        A state ``(theta, v)`` near the orbit at the start.
    param : str
        The numeric scene field to move.
    stop : float
        The other end of the parameter range.
    depth : int, optional
        Generations of children to continue (default 2; 0 is the one branch, as
        ``continue_orbit``); at most 12, and at most 256 branches in all.
    k, winding : int, optional
        The starting orbit's period in drive periods and turns per period (default 1 and 0).
    step : float, optional
        The first arclength step (as :func:`continue_orbit`).

    Returns
    -------
    BranchTree
        The root branch, its children, theirs, and so on.

    Raises
    ------
    TypeError, ValueError
        As :func:`continue_orbit` for the scene, guess, parameter, stop and step; ``depth`` not a whole
        number in 0..12.
    ContinuationError
        The starting branch cannot leave its first point (a child that cannot go on keeps what it traced).
    NotImplementedError
        For the flexible cord, the cycloidal guide and the non-uniform fields.

    See Also
    --------
    continue_orbit : one branch, or the attracting route.
    BranchTree : the result.
    pendula.plot.branches : the diagram drawn.

    Examples
    --------
    The damped driven pendulum's symmetric orbit, its two asymmetric children and their period doublings:

    >>> import pendula
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2/3)
    >>> tree = pendula.bifurcation_tree(sc, (0.1, 1.9), "drive_amplitude", 1.075, depth=2)
    >>> [(node.generation, int(node.branch.period[0])) for node in tree.walk()]
    [(0, 1), (1, 1), (2, 2), (1, 1), (2, 2)]
    >>> tree.children[0].branch.cycle.shape[1:], tree.children[0].children[0].branch.cycle.shape[1:]
    ((1, 2), (2, 2))
    """
    depth = _checks.count(depth, "depth", 0, MAX_DEPTH)
    tracer, prob, U, ev, t = start(scene, guess, param, stop, k, winding, "branch", step)
    lo, hi = sorted((tracer.p0, tracer.stop))
    budget = [MAX_BRANCHES - 1]

    def grow(tracer, prob, U, ev, t, origin, generation) -> BranchTree:
        branch = _trace(tracer, prob, U, ev, t)
        children, missing = [], []
        for index, kind, prob_s, Us, evs, ts in tracer.spawns:
            bif = tracer.bifs[index]
            if generation >= depth:
                missing.append(f"{kind} at {param} = {bif.value!r}: the depth {depth} is reached")
                continue
            for sign in ((1, -1) if kind == "pitchfork" else (1,)):
                if budget[0] <= 0:
                    missing.append(f"{kind} at {param} = {bif.value!r}: the work limit of {MAX_BRANCHES} branches")
                    continue
                first = tracer.child_start(kind, prob_s, Us, evs, ts, sign)
                if isinstance(first, str):
                    missing.append(first)
                    continue
                budget[0] -= 1
                child, U1, ev1, t1 = first
                up = U1[2] > Us[2]
                sub = _Tracer(scene, param, lo if up else hi, hi if up else lo, "branch", step)
                sub.record(child, U1, ev1)
                children.append(grow(sub, child, U1, ev1, t1, bif, generation + 1))
        return BranchTree(branch, origin, generation, tuple(children), tuple(missing))

    return grow(tracer, prob, U, ev, t, None, 0)

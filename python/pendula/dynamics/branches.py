"""The records of a continuation: a branch of periodic orbits, its
bifurcations, and the error that keeps what a continuation traced.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..scene import Scene

if TYPE_CHECKING:   # xarray is optional: named in annotations only
    import xarray

__all__ = ["BIFURCATION_KINDS", "Bifurcation", "Branch", "ContinuationError"]

#: The kinds of bifurcation a branch reports.
BIFURCATION_KINDS = ("fold", "pitchfork", "period-doubling", "neimark-sacker", "homoclinic", "snic",
                     "saddle-node")


class ContinuationError(ValueError):
    """The continuation could not go on; ``branch`` holds the part traced before it stopped.

    A ValueError, raised by :func:`continue_orbit` when a step shrinks to nothing (say at a fold the
    steps cannot pass); the message names the field and where the branch stopped.

    Attributes
    ----------
    branch : Branch or None
        The points traced before the error.

    See Also
    --------
    continue_orbit : raises it.

    Examples
    --------
    >>> import pendula
    >>> err = pendula.ContinuationError("torque: the step shrank to nothing at torque = 0.3")
    >>> isinstance(err, ValueError), err.branch
    (True, None)
    """

    def __init__(self, message: str, branch: "Branch | None" = None) -> None:
        super().__init__(message)
        self.branch = branch


@dataclass(frozen=True)
class Bifurcation:
    """A bifurcation on a branch, located by solving its defining condition.

    Attributes
    ----------
    kind : str
        ``'fold'`` (a multiplier through +1 where the branch turns), ``'pitchfork'`` (through +1 where
        the symmetric orbit's symmetry breaks: a branch point), ``'period-doubling'`` (through -1),
        ``'neimark-sacker'`` (a complex pair through the unit circle), ``'homoclinic'`` (the period
        diverges: the orbit meets a saddle), ``'snic'`` (the period diverges: a saddle and a node are born on
        the orbit, a saddle-node on an invariant circle), ``'saddle-node'`` (two equilibria merge).
    value : float
        The parameter at the bifurcation.
    period : float
        Drive periods k of a driven orbit, the time period of an autonomous one (``inf`` at a
        homoclinic or a snic), 0 for an equilibrium.
    theta, v : float
        The orbit's state on its section (the saddle, for a homoclinic; the rest point, for a saddle-node).
    multipliers : numpy.ndarray
        The Floquet multipliers there (eigenvalues, for an equilibrium).
    scene : Scene or None
        The scene at the bifurcation (its field ``param`` set to ``value``), as
        :func:`continue_bifurcation` starts from it.
    param : str or None
        The field the branch was continued in.
    winding : int
        Turns per period of the orbit (0 for an oscillation).
    det_residual : float
        The certificate of the multipliers: ``abs(det M - exp(-damping T))`` (Liouville's formula,
        T the time period), NaN where it does not apply (drag, an equilibrium, a homoclinic).
    trivial_residual : float
        For an autonomous orbit, the trivial multiplier's distance from 1; NaN for a driven one.
    cycle : numpy.ndarray
        The orbit's k section points ``(theta, v)`` one drive period apart, shape (k, 2) (one point for
        an autonomous orbit or an equilibrium).

    See Also
    --------
    continue_orbit, continue_equilibria : find them.
    continue_bifurcation : follows one in a second field.

    Examples
    --------
    >>> import pendula
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2/3)
    >>> br = pendula.continue_orbit(sc, (0.1, 1.9), "drive_amplitude", 1.07)
    >>> [(b.kind, round(b.value, 6)) for b in br.bifurcations]
    [('pitchfork', 1.004319)]
    """

    kind: str
    value: float
    period: float
    theta: float
    v: float
    multipliers: np.ndarray
    scene: Scene | None = field(default=None, repr=False, compare=False)
    param: str | None = field(default=None, repr=False, compare=False)
    winding: int = field(default=0, repr=False, compare=False)
    det_residual: float = math.nan
    trivial_residual: float = math.nan
    cycle: np.ndarray | None = None

    def __repr__(self) -> str:
        mods = ", ".join(f"{abs(complex(m)):.4g}" for m in np.ravel(self.multipliers))
        return (f"Bifurcation({self.kind!r} at {self.value:.10g}, period={self.period:.6g}, "
                f"theta={self.theta:.6g}, v={self.v:.6g}, |multipliers|=[{mods}])")


@dataclass(frozen=True)
class Branch:
    """A continued branch of periodic orbits (one call of :func:`continue_orbit`).

    Attributes
    ----------
    scene : Scene
        The scene the continuation started from.
    param : str
        The scene field continued in.
    values : numpy.ndarray
        The parameter at each point.
    theta, v : numpy.ndarray
        The state on the section at each point (theta in ``[-pi, pi]``; for an autonomous orbit theta
        is the section's angle).
    period : numpy.ndarray
        Drive periods k of a driven orbit, the time period of an autonomous one.
    multipliers : numpy.ndarray
        The two Floquet multipliers at each point (complex, shape (points, 2), largest modulus first).
    stable : numpy.ndarray
        True where the orbit attracts (for an autonomous orbit: the non-trivial multiplier ``det M``).
    segment : numpy.ndarray
        The segment of each point: 0, and one more after each switch to a child branch (``follow='stable'``).
    bifurcations : tuple of Bifurcation
        In the order met.
    end : str
        Why the branch ends (``'stop'`` when it reached ``stop``).
    cycle : numpy.ndarray
        The whole k-cycle at each point: the k section points ``(theta, v)`` one drive period apart,
        shape (points, K, 2) with K the longest period on the branch (NaN past a shorter point's k;
        K = 1 for an autonomous orbit, its point on the section).
    det_residual : numpy.ndarray
        The certificate of each point's multipliers: ``abs(det M - exp(-damping T))`` (Liouville's
        formula: the flow of the pendulum shrinks areas at the rate ``damping``), NaN with drag.
    trivial_residual : numpy.ndarray
        For an autonomous orbit, the distance of the multiplier nearest 1 (the flow's direction) from 1;
        NaN for a driven orbit.
    certified : numpy.ndarray
        True where the point's stability verdict is decided beyond the monodromy's error (as
        ``PeriodicOrbit.certified``: the Jury conditions, or ``1 - abs(det M)`` for an autonomous orbit,
        beyond ``100 rtol (1 + norm(M))^2``, and the Liouville residual within it); False next to a
        bifurcation.

    See Also
    --------
    continue_orbit : makes it.
    Bifurcation : its records of the bifurcations.

    Examples
    --------
    >>> import pendula
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2/3)
    >>> br = pendula.continue_orbit(sc, (0.1, 1.9), "drive_amplitude", 1.004)
    >>> br.end, bool(br.stable.all()), round(float(br.values[-1]), 12)
    ('stop', True, 1.004)
    """

    scene: Scene
    param: str
    values: np.ndarray
    theta: np.ndarray
    v: np.ndarray
    period: np.ndarray
    multipliers: np.ndarray
    stable: np.ndarray
    segment: np.ndarray
    bifurcations: tuple
    end: str
    cycle: np.ndarray
    det_residual: np.ndarray
    trivial_residual: np.ndarray
    certified: np.ndarray

    def __repr__(self) -> str:
        n = len(self.values)
        span = f" from {self.values[0]:.6g} to {self.values[-1]:.6g}" if n else ""
        return (f"Branch({self.param}{span}, {n} points, {int(np.sum(self.stable))} stable, "
                f"bifurcations [{_bifurcation_list(self.bifurcations)}], end={self.end!r})")

    def __len__(self) -> int:
        return len(self.values)

    def to_xarray(self) -> xarray.Dataset:
        """The branch as an xarray Dataset with dims (``point``, ``multiplier``).

        Returns
        -------
        xarray.Dataset
            Variables: the parameter (named for the field), ``theta``, ``v``, ``period``,
            ``multipliers`` (complex), ``stable``, ``segment``, the certificates ``det_residual``,
            ``trivial_residual`` and ``certified``, and the k-cycles ``cycle_theta`` and ``cycle_v``
            (dims ``point``, ``cycle``); the bifurcations in the attribute ``bifurcations`` as text.

        Examples
        --------
        >>> import pendula
        >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2/3)
        >>> ds = pendula.continue_orbit(sc, (0.1, 1.9), "drive_amplitude", 1.01).to_xarray()
        >>> dict(ds.sizes)["multiplier"]
        2
        """
        import xarray as xr
        n = len(self.values)
        return xr.Dataset(
            {self.param: ("point", self.values), "theta": ("point", self.theta), "v": ("point", self.v),
             "period": ("point", self.period), "multipliers": (("point", "multiplier"), self.multipliers),
             "stable": ("point", self.stable), "segment": ("point", self.segment),
             "det_residual": ("point", self.det_residual), "trivial_residual": ("point", self.trivial_residual),
             "certified": ("point", self.certified),
             "cycle_theta": (("point", "cycle"), self.cycle[:, :, 0]),
             "cycle_v": (("point", "cycle"), self.cycle[:, :, 1])},
            coords={"point": np.arange(n), "multiplier": np.arange(2), "cycle": np.arange(self.cycle.shape[1])},
            attrs={"param": self.param, "end": self.end,
                   "bifurcations": "; ".join(f"{b.kind} at {self.param}={b.value!r}" for b in self.bifurcations)})


# ---------------------------------------------------------------- arguments


def _bifurcation_list(bifs, most: int = 6) -> str:
    """'kind at value; ...' of the first `most` bifurcations (and how many more)."""
    text = "; ".join(f"{b.kind} at {b.value:.6g}" for b in bifs[:most])
    return text + (f"; and {len(bifs) - most} more" if len(bifs) > most else "")

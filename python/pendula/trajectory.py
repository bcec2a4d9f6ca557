"""What a computation returns: the Trajectory record shared by every model and path."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Literal

import numpy as np

from ._optional import require
from .scene import Scene
from .spectrum import Spectrum, spectrum

if TYPE_CHECKING:   # xarray is optional: named in annotations only
    import xarray

__all__ = ["Trajectory", "FlipLog"]


@dataclass
class Trajectory:
    """A computed motion: what :func:`simulate` returns.

    Attributes
    ----------
    t, theta, v, energy : ndarray
        Times, angle (continuous), angular velocity, and the energy
        v^2/2 + eps (1 - cos theta) evaluated along the path (for damped or
        driven scenes it is not conserved, and shows it).
    method : str
        'exact' or the integrator's name.
    scene : Scene
        The scene that was run.
    stats : dict
        Work done: ``steps`` (attempted), ``accepted``, ``rejected``,
        ``rejection_rate`` (rejected / steps: how often the step-size
        controller had to retry), ``rhs_evaluations`` (empty for the exact
        solution); for the flexible cord also the number of flips and the
        reason the run stopped.
    x, y, r : ndarray or None
        Flexible cord only: the bob's position (pivot at the origin, y up) and
        distance from the pivot, in units of the cord length (r < 1 in flight).
    flips : FlipLog or None
        Flexible cord only: a dict of arrays t_leave, theta_leave, v_leave,
        t_return, theta_return, v_return, xi_before, xi_after, one entry per
        flip in time order; ``flips.to_xarray()`` gives a Dataset.

    See Also
    --------
    simulate : makes it.
    Events : what :func:`find_events` returns.

    Examples
    --------
    >>> import pendula
    >>> tr = pendula.simulate(pendula.Scene(v0=1.0, t_end=2.0, n_samples=3))
    >>> tr.method, tr.t.tolist(), tr.theta.round(6).tolist()
    ('exact', [0.0, 1.0, 2.0], [0.0, 0.847799, 1.004615])
    >>> tr.as_array().shape          # columns t, theta, v, energy
    (3, 4)
    >>> tr
    Trajectory(method='exact', 3 samples, t from 0 to 2, scene=Scene(v0=1.0, t_end=2.0, n_samples=3))
    """

    t: np.ndarray
    theta: np.ndarray
    v: np.ndarray
    energy: np.ndarray
    method: str
    scene: Scene
    stats: dict = field(default_factory=dict)
    # flexible cord (systems/cord.py): the bob's position in units of l, and the flip log
    x: np.ndarray | None = None
    y: np.ndarray | None = None
    r: np.ndarray | None = None
    flips: dict | None = None

    def __post_init__(self):
        # the share of attempted steps the step-size controller rejected (adaptive methods)
        steps = self.stats.get("steps") if isinstance(self.stats, dict) else None
        if steps is not None and "rejected" in self.stats and "rejection_rate" not in self.stats:
            self.stats["rejection_rate"] = self.stats["rejected"] / steps if steps > 0 else 0.0
        if self.flips is not None and not isinstance(self.flips, FlipLog):
            self.flips = FlipLog(self.flips)

    def __repr__(self) -> str:
        n = np.size(self.t)
        span = f", t from {self.t[0]:.6g} to {self.t[-1]:.6g}" if n else ""
        flips = f", {len(self.flips.get('t_leave', ()))} flips" if self.flips is not None else ""
        return f"Trajectory(method={self.method!r}, {n} samples{span}{flips}, scene={self.scene!r})"

    def spectrum(self, window: Literal["hann", "none"] | None = None) -> Spectrum:
        """The power spectrum of theta(t): ``pendula.spectrum(self)``.

        Parameters
        ----------
        window : {None, 'hann'}
            A window applied before the transform.

        Returns
        -------
        Spectrum

        Raises
        ------
        ValueError
            Fewer than 4 samples, or times that are not uniformly spaced.

        See Also
        --------
        pendula.spectrum : the function.

        Examples
        --------
        >>> import numpy as np, pendula
        >>> T = pendula.orbit(0.0, 1.0).period
        >>> tr = pendula.simulate(pendula.Scene(v0=1.0), np.arange(1024) * (8 * T / 1024))  # 8 periods
        >>> sp = tr.spectrum()
        >>> sp
        Spectrum(513 lines up to omega=...)
        >>> round(sp.fundamental * T / (2 * np.pi), 12)
        1.0
        """
        return spectrum(self, window=window)

    def as_array(self) -> np.ndarray:
        """Columns t, theta, v, energy.

        Returns
        -------
        ndarray
            Shape (len(t), 4).
        """
        return np.column_stack([self.t, self.theta, self.v, self.energy])

    def to_xarray(self) -> xarray.Dataset:
        """The trajectory as an :class:`xarray.Dataset` along ``t``, with CF attributes.

        Returns
        -------
        xarray.Dataset
            ``theta``, ``v``, ``energy`` (and the cord's ``x``, ``y``, ``r``) on the
            dimension ``t``; the method, the scene (namelist text) and the work
            counters as attributes.  The flip log of a cord is ``self.flips.to_xarray()``.

        Examples
        --------
        >>> import pendula
        >>> ds = pendula.simulate(pendula.Scene(v0=1.0, t_end=1.0, n_samples=3)).to_xarray()
        >>> ds.theta.attrs["units"], ds.sizes["t"]
        ('rad', 3)
        """
        xr = require("xarray", "sweep", "Trajectory.to_xarray")
        data = {name: ("t", getattr(self, name), dict(zip(("long_name", "units"), meta)))
                for name, meta in _TRAJECTORY_META.items() if getattr(self, name) is not None}
        attrs = {"method": self.method, "scene": self.scene.to_namelist()}
        attrs.update({f"stats_{k}": (int(v) if isinstance(v, (bool, np.bool_)) else v)
                      for k, v in self.stats.items() if isinstance(v, (int, float, str, bool, np.number))})
        return xr.Dataset(data, coords={"t": ("t", self.t, {"long_name": "time", "units": "s"})}, attrs=attrs)


#: long_name and CF units of a trajectory's variables (time in the scene's unit, the second)
_TRAJECTORY_META = {
    "theta": ("angle from the downward vertical (continuous, not wrapped)", "rad"),
    "v": ("angular velocity", "rad s-1"),
    "energy": ("energy per m l^2: v^2/2 + V(theta)", "s-2"),
    "x": ("bob position, horizontal, in cord lengths (flexible cord)", "1"),
    "y": ("bob position, vertical (up), in cord lengths (flexible cord)", "1"),
    "r": ("bob distance from the pivot in cord lengths (flexible cord)", "1"),
}

#: long_name and units of the flip log's columns
_FLIP_META = {
    "t_leave": ("time the cord slackens", "s"), "theta_leave": ("angle where the bob leaves the circle", "rad"),
    "t_return": ("time the cord is taut again", "s"),
    "theta_return": ("angle where the bob re-enters the circle", "rad"),
    "xi_before": ("Garfinkel's state xi before the flip", "1"), "xi_after": ("Garfinkel's state xi after it", "1"),
    "v_leave": ("angular velocity where the bob leaves the circle", "rad s-1"),
    "v_return": ("angular velocity just after the re-entry jerk", "rad s-1"),
}


class FlipLog(dict):
    """The flexible cord's flip log: a dict of equal-length arrays, one entry per flip in time order.

    Its keys: ``t_leave``, ``theta_leave``, ``v_leave`` (where and when the cord
    slackens), ``t_return``, ``theta_return``, ``v_return`` (where it is taut
    again, v just after the jerk), ``xi_before``, ``xi_after`` (Garfinkel's
    state); :meth:`to_xarray` gives them as a Dataset along ``flip``.
    """

    def __repr__(self) -> str:
        n = len(self.get("t_leave", ()))
        return f"FlipLog({n} flips: {', '.join(self)})"

    def to_xarray(self) -> xarray.Dataset:
        """The flip log as an :class:`xarray.Dataset` along the dimension ``flip``.

        Returns
        -------
        xarray.Dataset

        Examples
        --------
        >>> import pendula
        >>> tr = pendula.simulate(pendula.Scene(cord="flexible", v0=2.2, t_end=20.0, n_samples=5))
        >>> "t_leave" in tr.flips.to_xarray()
        True
        """
        xr = require("xarray", "sweep", "FlipLog.to_xarray")
        data = {}
        for k, v in self.items():
            a = np.asarray(v)
            if a.ndim == 1:
                meta = _FLIP_META.get(k, (k.replace("_", " "), "1"))
                data[k] = ("flip", a, {"long_name": meta[0], "units": meta[1]})
        n = max((a[1].size for a in data.values()), default=0)
        return xr.Dataset(data, coords={"flip": np.arange(n)})

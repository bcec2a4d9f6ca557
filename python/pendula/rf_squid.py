"""The rf SQUID: one Josephson junction in a superconducting loop, and its static flux states.

With φ = 2πΦ/Φ₀ the phase across the junction (Φ the flux in the loop) and
φₑ = 2πΦₑ/Φ₀ the applied flux, the loop's energy over E_J = Φ₀I₀/2π is

    U(φ) = (φ − φₑ)² / (2β_L) − cos φ,    β_L = 2πLI₀/Φ₀,

and its rest points solve φ + β_L sin φ = φₑ (Clarke and Braginski, *The
SQUID Handbook* I, section 2.3; Barone and Paternò, section 12.2).  For
β_L < 1 there is one flux state at every φₑ; for β_L > 1 several coexist,
the stable ones on the rising pieces of φ + β_L sin φ (between the folds
cos φ = −1/β_L), and a slowly swept flux follows one until its fold, then
jumps: hysteresis of width 2(φ_c + √(β_L² − 1)) − 2π in φₑ, φ_c = arccos(−1/β_L).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike

from . import _checks
from ._optional import require
from .junction import FLUX_QUANTUM

if TYPE_CHECKING:   # xarray is optional: named in annotations only
    import xarray

__all__ = ["RFSquid"]

_TWO_PI = 2.0 * math.pi


def _pieces(beta_l: float, lo: float, hi: float) -> list[tuple[float, float, bool]]:
    """[lo, hi] cut at the folds cos φ = −1/β_L into pieces on which φ + β_L sin φ is monotone:
    (a, b, rising)."""
    if beta_l <= 1:
        return [(lo, hi, True)]
    pc = math.acos(-1.0 / beta_l)
    cuts = []
    for k in range(math.floor((lo - pc) / _TWO_PI) - 1, math.ceil((hi + pc) / _TWO_PI) + 2):
        cuts += [_TWO_PI * k - pc, _TWO_PI * k + pc]
    cuts = sorted(c for c in cuts if lo < c < hi)
    edges = [lo, *cuts, hi]
    out = []
    for a, b in zip(edges[:-1], edges[1:]):
        m = 0.5 * (a + b)
        out.append((a, b, 1 + beta_l * math.cos(m) > 0))
    return out


def _root(beta_l: float, phie: float, a: float, b: float) -> float | None:
    """The root of g = φ + β_L sin φ − φₑ on a piece [a, b] where g is monotone, by Newton safeguarded by
    bisection (to the last bit), or None when g keeps one sign there."""
    def g(x):
        return x + beta_l * math.sin(x) - phie
    ga, gb = g(a), g(b)
    if ga == 0:
        return a
    if gb == 0:
        return b
    if (ga > 0) == (gb > 0):
        return None
    x = 0.5 * (a + b)
    for _ in range(200):
        gx = g(x)
        if gx == 0:
            return x
        if (gx > 0) == (ga > 0):
            a, ga = x, gx
        else:
            b = x
        d = 1 + beta_l * math.cos(x)
        xn = x - gx / d if d != 0 else 0.5 * (a + b)
        if not a < xn < b:
            xn = 0.5 * (a + b)
        if xn == x or b - a <= 4 * math.ulp(max(abs(a), abs(b))):
            return xn
        x = xn
    return x


def flux_states(beta_l: float, external_flux: float) -> tuple[np.ndarray, np.ndarray]:
    """Every flux state φ (rad, ascending) at the applied φₑ = 2π external_flux, and whether each is stable."""
    phie = _TWO_PI * external_flux
    roots, stable = [], []
    for a, b, rising in _pieces(beta_l, phie - beta_l - 1e-3, phie + beta_l + 1e-3):
        r = _root(beta_l, phie, a, b)
        if r is not None and not (roots and r == roots[-1]):
            roots.append(r)
            stable.append(bool(rising and 1 + beta_l * math.cos(r) > 0))
    return np.array(roots), np.array(stable, dtype=bool)


class RFSquid:
    """An rf SQUID in laboratory units: one junction in a loop of inductance L.

    Parameters
    ----------
    critical_current : float
        I₀ of the junction (A), > 0.
    inductance : float
        The loop's inductance L (H), > 0 (a negative inductance is refused).
    resistance : float, optional
        The junction's shunt resistance (Ω), > 0, kept in ``resistance``
        (the static flux states do not depend on it; default None).
    capacitance : float, optional
        The junction's capacitance (F), >= 0, kept in ``capacitance``
        (the static flux states do not depend on it; default None).

    Raises
    ------
    ValueError
        Naming the field, for a value out of range.

    See Also
    --------
    DCSquid : two junctions in a loop.

    Examples
    --------
    >>> import pendula
    >>> sq = pendula.RFSquid(critical_current=1e-6, inductance=500e-12)
    >>> round(sq.beta_l, 4), sq.hysteretic
    (1.5193, True)
    """

    def __init__(self, critical_current: float, inductance: float, resistance: float | None = None,
                 capacitance: float | None = None) -> None:
        self.critical_current = _checks.real(critical_current, "critical_current", 0.0, lo_open=True)
        self.inductance = _checks.real(inductance, "inductance", 0.0, lo_open=True)
        self.resistance = None if resistance is None else \
            _checks.real(resistance, "resistance", 0.0, lo_open=True)
        self.capacitance = None if capacitance is None else _checks.real(capacitance, "capacitance", 0.0)

    def __repr__(self) -> str:
        return f"RFSquid(I0={self.critical_current!r} A, beta_l={self.beta_l:.6g})"

    @property
    def beta_l(self) -> float:
        """The screening parameter β_L = 2πLI₀/Φ₀ (the rf SQUID's convention)."""
        return _TWO_PI * self.inductance * self.critical_current / FLUX_QUANTUM

    @property
    def hysteretic(self) -> bool:
        """True when flux states coexist (β_L > 1): a swept flux jumps between them with hysteresis."""
        return self.beta_l > 1

    @property
    def switching_flux(self) -> float:
        """The applied flux Φₑ/Φ₀ at which the state that holds no flux at Φₑ = 0 ends on an upward sweep.

        (φ_c + √(β_L² − 1))/2π with φ_c = arccos(−1/β_L); NaN, with no
        warning, for a SQUID that is not hysteretic (it never jumps).
        """
        b = self.beta_l
        if b <= 1:
            return math.nan
        pc = math.acos(-1.0 / b)
        return (pc + math.sqrt(b * b - 1)) / _TWO_PI

    def flux_states(self, external_flux: float) -> xarray.Dataset:
        """Every static flux state of the loop at the applied flux Φₑ/Φ₀.

        The roots of φ + β_L sin φ = 2πΦₑ/Φ₀, one on each piece between the
        folds cos φ = −1/β_L where the left side crosses the right, by
        Newton's method kept inside the piece by bisection, to the last bit.

        Parameters
        ----------
        external_flux : float
            Φₑ/Φ₀.

        Returns
        -------
        xarray.Dataset
            Over ``state`` (ascending in the flux): ``flux`` (Φ/Φ₀),
            ``stable`` (a minimum of the loop's energy), ``screening_current``
            (A, −I₀ sin φ) and ``energy`` (J).

        Raises
        ------
        ValueError
            A flux that is not finite.

        Examples
        --------
        >>> import pendula
        >>> sq = pendula.RFSquid(1e-6, 1000e-12)               # beta_L = 3.04
        >>> r = sq.flux_states(0.5)
        >>> r.flux.size, r.stable.values.tolist()
        (3, [True, False, True])
        """
        xr = require("xarray", "xarray", "RFSquid.flux_states")
        fe = _checks.real(external_flux, "external_flux")
        b, i0 = self.beta_l, self.critical_current
        phi, stable = flux_states(b, fe)
        ej = FLUX_QUANTUM * i0 / _TWO_PI         # the Josephson energy
        energy = ej * ((phi - _TWO_PI * fe) ** 2 / (2 * b) - np.cos(phi))
        return xr.Dataset(
            {"flux": ("state", phi / _TWO_PI, {"long_name": "flux in the loop / flux quantum", "units": "Phi0"}),
             "stable": ("state", stable, {"long_name": "a minimum of the loop's energy"}),
             "screening_current": ("state", -i0 * np.sin(phi), {"long_name": "screening current", "units": "A"}),
             "energy": ("state", energy, {"long_name": "energy of the loop", "units": "J"})},
            attrs={"external_flux": fe, "beta_l": b})

    def flux_curve(self, external_fluxes: ArrayLike,
                   direction: Literal["up", "down", "both"] = "both") -> xarray.Dataset:
        """The flux in the loop as the applied flux is swept slowly: the static branches and their jumps.

        The state is continued from one applied flux to the next by Newton's
        method started from the last flux state and kept on its piece of
        φ + β_L sin φ (between two folds); when the piece no longer holds a
        root (the sweep passed the fold) the loop jumps to the nearest
        stable state in the direction of the sweep.  The sweep starts in the
        stable state nearest to the applied flux.

        Parameters
        ----------
        external_fluxes : array_like
            Φₑ/Φ₀, ascending: the up branch runs them in this order and the
            down branch in reverse.
        direction : {'up', 'down', 'both'}, optional
            The branches of the sweep (default 'both').

        Returns
        -------
        xarray.Dataset
            Over (``direction``, ``external_flux``): ``flux`` (Φ/Φ₀),
            ``screening_current`` (A) and ``jump`` (True where the state
            jumped on arriving at that flux).

        Raises
        ------
        ValueError
            Fluxes not finite or not ascending, naming the argument.

        Examples
        --------
        >>> import numpy as np, pendula
        >>> sq = pendula.RFSquid(1e-6, 1000e-12)
        >>> r = sq.flux_curve(np.linspace(0, 1, 11))
        >>> r.jump.sel(direction="up").values.nonzero()[0].tolist()
        [8]
        """
        xr = require("xarray", "xarray", "RFSquid.flux_curve")
        fe = _checks.grid_values(external_fluxes, "external_fluxes")
        if np.any(np.diff(fe) < 0):
            raise ValueError("external_fluxes must be ascending: the up sweep runs them as given and the down "
                             "sweep in reverse; give np.sort(external_fluxes)")
        direction = _checks.choice(direction, "direction", ("up", "down", "both"))
        dirs = ["up", "down"] if direction == "both" else [direction]
        b = self.beta_l
        phi_out = np.full((len(dirs), fe.size), np.nan)
        jump = np.zeros((len(dirs), fe.size), dtype=bool)
        for d, name in enumerate(dirs):
            order = list(range(fe.size)) if name == "up" else list(range(fe.size - 1, -1, -1))
            phi = None
            for j in order:
                phie = _TWO_PI * fe[j]
                if phi is None:
                    roots, stable = flux_states(b, fe[j])
                    s = roots[stable]
                    phi = float(s[np.argmin(np.abs(s - phie))])
                else:
                    nxt = self._continue(phi, phie)
                    if nxt is None:
                        roots, stable = flux_states(b, fe[j])
                        s = roots[stable]
                        s = s[s > phi] if name == "up" else s[s < phi]
                        nxt = float(s[0] if name == "up" else s[-1])
                        jump[d, j] = True
                    phi = nxt
                phi_out[d, j] = phi
        i0 = self.critical_current
        dims = ("direction", "external_flux")
        return xr.Dataset(
            {"flux": (dims, phi_out / _TWO_PI, {"long_name": "flux in the loop / flux quantum", "units": "Phi0"}),
             "screening_current": (dims, -i0 * np.sin(phi_out), {"long_name": "screening current", "units": "A"}),
             "jump": (dims, jump, {"long_name": "the state jumped arriving here"})},
            coords={"direction": dirs,
                    "external_flux": ("external_flux", fe, {"long_name": "applied flux / flux quantum",
                                                            "units": "Phi0"})},
            attrs={"beta_l": b, "switching_flux": self.switching_flux})

    def _continue(self, phi: float, phie: float) -> float | None:
        """The flux state on phi's rising piece at the applied phie, by Newton from phi kept in the piece;
        None when the piece holds no root there (the fold was passed)."""
        b = self.beta_l
        if b <= 1:
            a, c = phie - b - 1.0, phie + b + 1.0
        else:
            pc = math.acos(-1.0 / b)
            k = math.floor((phi + pc) / _TWO_PI)
            a, c = _TWO_PI * k - pc, _TWO_PI * k + pc
        return _root(b, phie, a, c)

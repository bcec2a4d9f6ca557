"""The long Josephson junction as a ring of pendula: a fluxon's terminal speed against the bias.

The driven, damped sine-Gordon equation φ_tt − φ_xx + sin φ = γ − αφ_t
(lengths in the Josephson length λ_J, time in 1/ω_p) on a lattice of spacing
a is a ring of pendula joined by springs K = 1/a²; m·2π twist on the closing
spring traps m fluxons (an annular junction).  Each site's phase rises by 2π
as a fluxon passes it, so the fluxons' speed in sites per unit time is the
rise of Σφ_n over 2πm per unit time, and their speed in units of the Swihart
velocity λ_J ω_p is a times that.  Beside it, McLaughlin and Scott's power
balance for the continuum (Phys. Rev. A 18, 1652 (1978), section IV): the
bias feeds a kink 2πγu, the damping takes 8αu/√(1 − u²), so
u = 1/√(1 + (4α/πγ)²).
"""

from __future__ import annotations

import math
import os
from concurrent.futures import ThreadPoolExecutor
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from . import _checks
from ._optional import require
from .systems.network import Network

if TYPE_CHECKING:   # xarray is optional: named in annotations only
    import xarray

__all__ = ["fluxon_velocity"]

#: the most sites of the ring (its offset matrix is N x N: 32 MB at this size)
_MAX_SITES = 2048


def _power_balance(alpha: float, gamma: np.ndarray) -> np.ndarray:
    g = np.abs(gamma)
    with np.errstate(divide="ignore"):
        return np.where(g > 0, 1 / np.sqrt(1 + (4 * alpha / (math.pi * np.where(g > 0, g, 1.0))) ** 2), 0.0)


def fluxon_velocity(biases: ArrayLike, damping: float, *, length: float = 40.0, spacing: float = 0.125,
                    fluxons: int = 1, transient: float | None = None, window: float = 200.0,
                    rtol: float = 1e-9, threads: int = 0) -> xarray.Dataset:
    """The terminal speed of fluxons in an annular long Josephson junction, against the bias.

    The junction is a ring of round(length/spacing) pendula with springs
    1/spacing² (the sine-Gordon equation φ_tt − φ_xx + sin φ = γ − αφ_t on a
    lattice, lengths in λ_J, time in 1/ω_p), ``fluxons`` of them trapped by
    a twist of 2π each on the closing spring.  At each bias the fluxons
    start at rest, evenly spaced, each the continuum's kink
    4 arctan(exp(x − x₀)); after ``transient`` their speed is measured over
    ``window`` from the rise of Σφ_n (2π per site a fluxon passes).
    McLaughlin and Scott's power balance for the continuum (Phys. Rev. A 18,
    1652 (1978), section IV), u = 1/√(1 + (4α/πγ)²), is returned beside it;
    the lattice's speed tends to it as the spacing falls (its error falls
    at least as spacing²).

    Parameters
    ----------
    biases : array_like
        γ, the bias current density over the critical one (the speed does not
        depend on its sign).
    damping : float
        α > 0 (without damping there is no terminal speed).
    length : float, optional
        The ring's circumference in λ_J (default 40).
    spacing : float, optional
        The lattice spacing a in λ_J, > 0 (default 1/8).
    fluxons : int, optional
        The number of trapped fluxons, >= 1 (default 1).
    transient : float, optional
        The time (1/ω_p) let pass first (default 10/α: the speed relaxes at
        the rate α, e⁻¹⁰ of the start left).
    window : float, optional
        The time over which the speed is measured (default 200).
    rtol : float, optional
        The integrator's relative tolerance (default 1e-9).
    threads : int, optional
        Threads over the biases (0: every core).

    Returns
    -------
    xarray.Dataset
        Over ``bias``: ``speed`` (the lattice's, in units of the Swihart
        velocity) and ``power_balance`` (McLaughlin and Scott's); the ring's
        sites, spacing, length, damping and fluxons in the attributes.

    Raises
    ------
    ValueError
        A damping, spacing, length or window that is not positive, fewer
        than 8 sites a fluxon or more than 2048 in all, or a bias that is not
        finite, naming it.

    See Also
    --------
    Network : the ring of pendula it runs.

    Examples
    --------
    >>> r = fluxon_velocity([0.1], 0.05, length=20.0, spacing=0.25)
    >>> round(float(r.speed[0]), 2), round(float(r.power_balance[0]), 4)
    (0.83, 0.8436)
    """
    xr = require("xarray", "xarray", "pendula.fluxon_velocity")
    gam = _checks.grid_values(biases, "biases")
    alpha = _checks.real(damping, "damping", 0.0, lo_open=True)
    length = _checks.real(length, "length", 0.0, lo_open=True)
    a = _checks.real(spacing, "spacing", 0.0, lo_open=True)
    m = _checks.count(fluxons, "fluxons", 1)
    tr = 10.0 / alpha if transient is None else _checks.real(transient, "transient", 0.0)
    win = _checks.real(window, "window", 0.0, lo_open=True)
    rtol = _checks.real(rtol, "rtol", 0.0, lo_open=True)
    nthreads = _checks.threads(threads) or (os.cpu_count() or 1)
    n = int(round(length / a))
    if n < 8 * m:
        raise ValueError(f"length / spacing gives {n} sites: at least 8 a fluxon are needed (fluxons={m})")
    if n > _MAX_SITES:
        raise ValueError(f"length / spacing gives {n} sites, more than {_MAX_SITES} (the closing spring's twist "
                         "is given to the ring as an N x N offset matrix): a shorter ring or a coarser spacing")
    k = 1.0 / (a * a)
    off = np.zeros((n, n))
    off[n - 1, 0], off[0, n - 1] = -2 * math.pi * m, 2 * math.pi * m
    x = a * np.arange(n)
    centres = length * (np.arange(m) + 0.5) / m
    start = sum(4 * np.arctan(np.exp(x - c)) for c in centres)

    def speed(g: float) -> float:
        ring = Network(n, topology="ring", strength=k, offset=off, damping=alpha, bias=g)
        run = ring.simulate([tr, tr + win], phi0=start, rtol=rtol, atol=rtol * 1e-2)
        s = run.phi.values.sum(axis=1)
        return abs(float(s[1] - s[0])) / win / (2 * math.pi * m) * a

    with ThreadPoolExecutor(max_workers=min(nthreads, gam.size)) as pool:
        u = np.array(list(pool.map(speed, [float(g) for g in gam])))
    return xr.Dataset(
        {"speed": ("bias", u, {"long_name": "fluxon speed on the lattice / Swihart velocity", "units": "1"}),
         "power_balance": ("bias", _power_balance(alpha, gam),
                           {"long_name": "McLaughlin-Scott power balance speed / Swihart velocity",
                            "units": "1"})},
        coords={"bias": ("bias", gam, {"long_name": "bias current density / critical", "units": "1"})},
        attrs={"damping": alpha, "length": length, "spacing": a, "sites": n, "fluxons": m,
               "transient": tr, "window": win, "rtol": rtol})

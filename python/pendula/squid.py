"""The dc SQUID: two Josephson junctions in a superconducting loop.

In the junctions' own units (phases φ₁, φ₂; energies in E_J = Φ₀I₀/2π;
time in 1/ω_p) the symmetric dc SQUID is a network of two pendula coupled
by the loop's inductance L:

    U = Σ (1 − cos φ_k) − (i/2)(φ₁ + φ₂) + (φ₁ − φ₂ − 2πΦ/Φ₀)² / (2π β_L),

β_L = 2LI₀/Φ₀ the screening parameter, i the bias over I₀ shared by the two
arms, Φ the applied flux: a :class:`~pendula.Network` of two elements with
the spring K = 1/(π β_L) and the offset −2πΦ/Φ₀ (Tesche and Clarke 1977,
section 2).  Its static critical current Ic(Φ) is the largest bias with a
stable rest point: the fold of the branch of stable rest points continued in
the bias, located by Newton on the extended system of Moore and Spence
(F = 0, J v = 0, c·v = 1), over every flux state (the fluxoid branches that
coexist at large β_L).
"""

from __future__ import annotations

import math

import numpy as np

from . import _checks
from .junction import FLUX_QUANTUM, Junction
from .systems.network import Network

__all__ = ["DCSquid", "squid_critical_current"]


def _network(beta_l: float, flux: float, bias: float = 0.0, damping: float = 0.0) -> Network:
    off = np.array([[0.0, -2 * math.pi * flux], [2 * math.pi * flux, 0.0]])
    return Network(2, coupling=[[0.0, 1 / (math.pi * beta_l)], [1 / (math.pi * beta_l), 0.0]], offset=off,
                   bias=bias / 2, damping=damping)


def _fold(net: Network, phi: np.ndarray, i0: float) -> tuple[float, np.ndarray]:
    """Newton on the Moore-Spence system from (phi, i0) near the fold: (i, phi) at the fold."""
    n = net.n
    b = np.full(n, 0.5)
    jac = net.jacobian(phi)
    w, u = np.linalg.eigh(-jac)
    v = u[:, 0] / np.linalg.norm(u[:, 0])
    c = v.copy()
    z = np.concatenate([phi, v, [i0]])
    dold = math.inf
    for _ in range(60):
        q, v, i = z[:n], z[n:2 * n], z[-1]
        f = net.force(q) + i * b
        jac = net.jacobian(q)
        g = jac @ v
        res = np.concatenate([f, g, [c @ v - 1]])
        big = np.zeros((2 * n + 1, 2 * n + 1))
        big[:n, :n] = jac
        big[:n, -1] = b
        big[n:2 * n, :n] = np.diag(net.eps * np.sin(q) * v)
        big[n:2 * n, n:2 * n] = jac
        big[-1, n:2 * n] = c
        d = np.linalg.solve(big, -res)
        z = z + d
        dmax = float(np.max(np.abs(d)))
        # converged: a step at rounding level, or steps that stop shrinking once below 1e-8 (rounding of a
        # stiff loop, K = 1/(pi beta_L) large, bounds them)
        if dmax <= 1e-15 * (1 + np.max(np.abs(z))) or (dmax < 1e-8 and dmax >= dold):
            break
        dold = dmax
    else:
        raise ArithmeticError("the fold's Newton did not converge")
    return float(z[-1]), z[:n]


def _rest_points(beta_l: float, flux: float) -> list[np.ndarray]:
    """The stable rest points at zero bias, one per flux state.  At zero bias sin φ₁ + sin φ₂ = 0, so
    φ₁,₂ = s ± x/2 with s = 0 or π, and σ sin(x/2) = −K(x − 2πΦ/Φ₀) (σ = cos s): every root lies within
    1/K = πβ_L of 2πΦ/Φ₀; each sign change on a fine grid there is polished by Newton on the network and
    kept if stable."""
    net = _network(beta_l, flux)
    k, x0 = 1 / (math.pi * beta_l), 2 * math.pi * flux
    xs = np.linspace(x0 - math.pi * beta_l - 0.1, x0 + math.pi * beta_l + 0.1, 4001)
    found = []
    for s, sigma in ((0.0, 1.0), (math.pi, -1.0)):
        g = sigma * np.sin(xs / 2) + k * (xs - x0)
        for j in np.flatnonzero(np.sign(g[:-1]) != np.sign(g[1:])):
            x = xs[j] - g[j] * (xs[j + 1] - xs[j]) / (g[j + 1] - g[j])
            try:
                eq = net.equilibrium([s + x / 2, s - x / 2])
            except ValueError:
                continue
            if eq.stable and not any(abs((eq.phi[0] - eq.phi[1]) - (p[0] - p[1])) < 1e-8 for p in found):
                found.append(eq.phi)
    return found


def squid_critical_current(beta_l: float, flux: float) -> float:
    """The static critical current of a symmetric dc SQUID over one junction's I₀.

    The largest bias with a stable rest point, over all flux states: the fold
    of each stable branch continued in the bias from zero, located by Newton
    on the Moore-Spence system.  As β_L → 0 it tends to 2|cos(πΦ/Φ₀)|.

    Parameters
    ----------
    beta_l : float
        The screening parameter β_L = 2LI₀/Φ₀ > 0.
    flux : float
        The applied flux over the flux quantum, Φ/Φ₀.

    Returns
    -------
    float
        Ic / I₀ (between 0 and 2).

    Raises
    ------
    ValueError
        For β_L <= 0 or a flux that is not finite.

    See Also
    --------
    DCSquid.critical_current : the same in amperes.

    Examples
    --------
    >>> round(squid_critical_current(1e-6, 0.25), 5)
    1.41421
    >>> round(squid_critical_current(1.0, 0.0), 12)
    2.0
    """
    beta_l = _checks.real(beta_l, "beta_l", 0.0, lo_open=True)
    flux = _checks.real(flux, "flux")
    best = -math.inf
    for phi in _rest_points(beta_l, flux):
        i, step = 0.0, 0.05
        # near a fold at small bias (Ic ~ beta_L at half a flux quantum) the steps shrink further
        while step > 1e-3 or (i == 0.0 and step > 1e-12):
            try:
                eq = _network(beta_l, flux, i + step).equilibrium(phi)
                ok = eq.stable
            except ValueError:
                ok = False
            if ok:
                i, phi = i + step, eq.phi
            else:
                step /= 2
        if i == 0.0:
            # a flux state at the edge of its stability (its Hessian next to singular): no bias of 1e-12 keeps
            # it at rest, so its critical current is below every other state's and it is passed over
            continue
        ic, _ = _fold(_network(beta_l, flux), phi, i)
        if not i <= ic <= i + 4 * step:
            raise ArithmeticError(f"the fold of the stable branch was lost (bias {i!r}, fold at {ic!r})")
        best = max(best, ic)
    if best == -math.inf:
        raise ArithmeticError(f"no flux state of beta_l = {beta_l!r}, flux = {flux!r} stays at rest under a bias")
    return best


class DCSquid:
    """A symmetric dc SQUID in laboratory units: two equal junctions in a loop of inductance L.

    Parameters
    ----------
    critical_current : float
        I₀ of each junction (A), > 0.
    resistance : float
        The shunt resistance of each junction (Ω), > 0.
    capacitance : float
        The capacitance of each junction (F), > 0.
    inductance : float
        The loop's inductance L (H), > 0 (a negative inductance is refused).

    Raises
    ------
    ValueError
        Naming the field, for a value that is not positive and finite.

    See Also
    --------
    Junction : the single junction whose constants it builds on
        (``pendula.squid.squid_critical_current`` gives Ic(Φ)/I₀ in reduced units).

    Examples
    --------
    >>> sq = DCSquid(10e-6, 2.0, 1e-13, 103.4e-12)
    >>> round(sq.beta_l, 3)
    1.0
    >>> round(sq.critical_current(0.0) / 10e-6, 9)
    2.0
    """

    def __init__(self, critical_current: float, resistance: float, capacitance: float, inductance: float) -> None:
        self.junction = Junction(critical_current, resistance, capacitance)
        self.inductance = _checks.real(inductance, "inductance", 0.0, lo_open=True)

    def __repr__(self) -> str:
        return f"DCSquid(I0={self.junction.critical_current!r} A, beta_l={self.beta_l:.6g})"

    @property
    def beta_l(self) -> float:
        """The screening parameter β_L = 2LI₀/Φ₀."""
        return 2 * self.inductance * self.junction.critical_current / FLUX_QUANTUM

    def critical_current(self, flux: float) -> float:
        """The static critical current Ic (A) at the applied flux Φ/Φ₀.

        Parameters
        ----------
        flux : float
            Φ/Φ₀.

        Returns
        -------
        float
            Ic in amperes.

        Examples
        --------
        >>> sq = DCSquid(1e-6, 10.0, 1e-13, 1e-12)
        >>> round(sq.critical_current(0.5) / 1e-6, 4)
        0.0015
        """
        return squid_critical_current(self.beta_l, flux) * self.junction.critical_current

    def network(self, bias: float, flux: float) -> Network:
        """The SQUID as a :class:`~pendula.Network` in the junctions' reduced units.

        Parameters
        ----------
        bias : float
            The total bias current (A).
        flux : float
            Φ/Φ₀.

        Returns
        -------
        Network
            Two elements, damping 1/√β_c, spring 1/(π β_L), offset −2πΦ/Φ₀.

        Examples
        --------
        >>> sq = DCSquid(10e-6, 2.0, 1e-13, 103.4e-12)
        >>> net = sq.network(5e-6, 0.25)
        >>> net.n, float(net.bias[0])
        (2, 0.25)
        """
        b = _checks.real(bias, "bias") / self.junction.critical_current
        return _network(self.beta_l, _checks.real(flux, "flux"), b, self.junction.damping)

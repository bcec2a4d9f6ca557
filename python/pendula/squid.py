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
coexist at large β_L).  An asymmetric SQUID (junctions of critical currents
I₀(1 ∓ α_I), arms of inductance (1 ∓ η)L/2) is the same network with sine
strengths 1 ∓ α_I and the bias split (1 ± η)/2 between the arms
(squid_voltage.py derives the split from the fluxoid condition).
"""

from __future__ import annotations

import math
import os

import numpy as np
from numpy.typing import ArrayLike

from typing import TYPE_CHECKING, Literal

from . import _checks
from ._optional import require
from .junction import FLUX_QUANTUM, Junction
from .squid_voltage import arms, mean_velocity, noisy_mean_velocity, squid_network, wrap
from .systems.network import Network

if TYPE_CHECKING:   # xarray is optional: named in annotations only
    import xarray

__all__ = ["DCSquid", "squid_critical_current"]

_TWO_PI = 2.0 * math.pi


def _asymmetry(x, name: str) -> float:
    """An asymmetry parameter: a real strictly between -1 and 1 (at ±1 one arm has no junction or no
    inductance)."""
    v = _checks.real(x, name)
    if not -1.0 < v < 1.0:
        raise ValueError(f"{name} must lie strictly between -1 and 1 (a fraction of the mean), got {v!r}")
    return v


def _network(beta_l: float, flux: float, bias: float = 0.0, damping: float = 0.0,
             asym: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> Network:
    eps, cond, share = arms(*asym)
    off = np.array([[0.0, -2 * math.pi * flux], [2 * math.pi * flux, 0.0]])
    return Network(2, coupling=[[0.0, 1 / (math.pi * beta_l)], [1 / (math.pi * beta_l), 0.0]], offset=off,
                   eps=eps, mass=cond, bias=bias * share, damping=damping * cond)


def _fold(net: Network, phi: np.ndarray, i0: float, b: np.ndarray) -> tuple[float, np.ndarray]:
    """Newton on the Moore-Spence system from (phi, i0) near the fold: (i, phi) at the fold (b: each
    element's share of the bias)."""
    n = net.n
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


def _stable_seeds(beta_l: float, flux: float, asym: tuple[float, float, float] = (0.0, 0.0, 0.0)
                  ) -> list[tuple[float, np.ndarray]]:
    """Stable rest points (bias, phases) from which every stable branch can be continued up to its fold.

    A flux state of an asymmetric SQUID need not be stable at zero bias: a stable branch can be born at a
    fold at a positive bias.  So the rest points are sought on a ladder of biases i from 0 to 2 (step
    0.01).  At bias i junction 1's balance fixes the loop's phase x = φ₁ − φ₂ by φ₁ alone,
    x = 2πΦ/Φ₀ + πβ_L(b₁i − ε₁ sin φ₁), and what is left is junction 2's, equivalently the total
    supercurrent ε₁ sin φ₁ + ε₂ sin(φ₁ − x) = i: one periodic function of φ₁, whose sign changes on a fine
    grid are every rest point of every flux state.  A root whose Hessian (diag(ε_k cos φ_k) plus the loop's
    spring) is positive definite, and that has no neighbour on the rung below (a branch born between the
    rungs), is polished by Newton on the network."""
    (e1, e2), _, (b1, _) = arms(*asym)
    k, x0 = 1 / (math.pi * beta_l), 2 * math.pi * flux
    th = np.linspace(0.0, _TWO_PI, 4001)[None, :]
    rungs = np.linspace(0.0, 2.0, 201)[:, None]
    x = x0 + math.pi * beta_l * (b1 * rungs - e1 * np.sin(th))
    g = e1 * np.sin(th) + e2 * np.sin(th - x) - rungs
    seeds: list[tuple[float, np.ndarray]] = []
    below: list[float] = []
    for m in range(rungs.shape[0]):
        i, gm, xm = float(rungs[m, 0]), g[m], x[m]
        here: list[float] = []
        for j in np.flatnonzero(np.sign(gm[:-1]) != np.sign(gm[1:])):
            u = gm[j] / (gm[j] - gm[j + 1])
            q, xq = th[0, j] + u * (th[0, j + 1] - th[0, j]), xm[j] + u * (xm[j + 1] - xm[j])
            h11, h22 = e1 * math.cos(q) + k, e2 * math.cos(q - xq) + k
            if not (h11 > 0 and h11 * h22 > k * k):
                continue
            here.append(q)
            if any(abs(math.remainder(q - y, _TWO_PI)) < 0.1 for y in below):
                continue
            try:
                eq = _network(beta_l, flux, i, asym=asym).equilibrium([q, q - xq])
            except ValueError:
                continue
            if eq.stable:
                seeds.append((i, eq.phi))
        below = here
    return seeds


def squid_critical_current(beta_l: float, flux: float, *, current_asymmetry: float = 0.0,
                           inductance_asymmetry: float = 0.0) -> float:
    """The static critical current of a dc SQUID over its junctions' mean I₀.

    The largest positive bias with a stable rest point, over all flux
    states: the fold of each stable branch (sought on a ladder of biases
    from 0 to 2I₀, as a flux state of an asymmetric SQUID can be born under
    a bias) continued in the bias, located by Newton on the Moore-Spence
    system.  The junctions' critical
    currents are I₀(1 ∓ α_I), the arms' inductances (1 ∓ η)L/2 (Tesche and
    Clarke 1977, section 2): the arm of the smaller inductance carries the
    larger share (1 ± η)/2 of the bias.  As β_L → 0 it tends to
    √((1 − α_I)² + (1 + α_I)² + 2(1 − α_I²) cos(2πΦ/Φ₀)), for equal
    junctions 2 abs(cos(πΦ/Φ₀)); at β_L > 0 either asymmetry shifts and
    skews the lobes, and the negative bias's critical current is this one
    at −Φ.

    Parameters
    ----------
    beta_l : float
        The screening parameter β_L = 2LI₀/Φ₀ > 0.
    flux : float
        The applied flux over the flux quantum, Φ/Φ₀.
    current_asymmetry : float, optional
        α_I, strictly between -1 and 1 (default 0: equal junctions).
    inductance_asymmetry : float, optional
        η, strictly between -1 and 1 (default 0: the loop split evenly).

    Returns
    -------
    float
        Ic / I₀ (between 0 and 2).

    Raises
    ------
    ValueError
        For β_L <= 0, a flux that is not finite, or an asymmetry outside
        (-1, 1), naming it.

    See Also
    --------
    DCSquid.critical_current : the same in amperes.

    Examples
    --------
    >>> round(squid_critical_current(1e-6, 0.25), 5)
    1.41421
    >>> round(squid_critical_current(1.0, 0.0), 12)
    2.0
    >>> round(squid_critical_current(1e-6, 0.5, current_asymmetry=0.2), 5)   # 2 α_I at half a quantum
    0.4
    """
    beta_l = _checks.real(beta_l, "beta_l", 0.0, lo_open=True)
    flux = _checks.real(flux, "flux")
    asym = (_asymmetry(current_asymmetry, "current_asymmetry"), 0.0,
            _asymmetry(inductance_asymmetry, "inductance_asymmetry"))
    share = arms(*asym)[2]
    best = -math.inf
    for i0, phi in _stable_seeds(beta_l, flux, asym):
        i, step = i0, 0.05
        # near a fold at small bias (Ic ~ beta_L at half a flux quantum) the steps shrink further
        while step > 1e-3 or (i == i0 and step > 1e-12):
            try:
                eq = _network(beta_l, flux, i + step, asym=asym).equilibrium(phi)
                ok = eq.stable
            except ValueError:
                ok = False
            if ok:
                i, phi = i + step, eq.phi
            else:
                step /= 2
        if i == i0:
            # a flux state at the edge of its stability (its Hessian next to singular): no bias of 1e-12 more
            # keeps it at rest, so its fold is where it was found, below the other states' (if any)
            if i0 > 0:
                best = max(best, i0)
            continue
        ic, _ = _fold(_network(beta_l, flux, asym=asym), phi, i, share)
        if not i <= ic <= i + 4 * step:
            raise ArithmeticError(f"the fold of the stable branch was lost (bias {i!r}, fold at {ic!r})")
        best = max(best, ic)
    if best == -math.inf:
        raise ArithmeticError(f"no flux state of beta_l = {beta_l!r}, flux = {flux!r} stays at rest under a bias")
    return best


class DCSquid:
    """A dc SQUID in laboratory units: two junctions in a loop of inductance L.

    Equal junctions and an evenly split loop by default; the asymmetries
    are fractions of the mean (Tesche and Clarke 1977, section 2): critical
    currents I₀(1 ∓ α_I), shunt resistances R/(1 ∓ α_R) and capacitances
    C(1 ∓ α_R) (junctions of unequal area: each one's RC stays RC), arm
    inductances (1 ∓ η)L/2, junction 1 taking the upper signs.

    Parameters
    ----------
    critical_current : float
        The junctions' mean critical current I₀ (A), > 0.
    resistance : float
        The mean shunt resistance R (Ω), > 0: junction k's is R/(1 ∓ α_R).
    capacitance : float
        The mean capacitance C (F), > 0: junction k's is C(1 ∓ α_R).
    inductance : float
        The loop's inductance L (H), > 0 (a negative inductance is refused).
    temperature : float, optional
        T (K), >= 0: the Johnson noise of each shunt in the dynamic curves
        (default 0).
    current_asymmetry : float, optional
        α_I, strictly between -1 and 1 (default 0).
    resistance_asymmetry : float, optional
        α_R, strictly between -1 and 1 (default 0).
    inductance_asymmetry : float, optional
        η, strictly between -1 and 1 (default 0).

    Raises
    ------
    ValueError
        Naming the field, for a value that is not positive and finite, or an
        asymmetry outside (-1, 1).

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
    >>> skew = DCSquid(10e-6, 2.0, 1e-13, 103.4e-12, current_asymmetry=0.2, inductance_asymmetry=0.3)
    >>> skew.critical_current(-0.1) > skew.critical_current(0.1)     # the lobe shifted off zero flux
    True
    """

    def __init__(self, critical_current: float, resistance: float, capacitance: float, inductance: float,
                 temperature: float = 0.0, *, current_asymmetry: float = 0.0, resistance_asymmetry: float = 0.0,
                 inductance_asymmetry: float = 0.0) -> None:
        self.junction = Junction(critical_current, resistance, capacitance, temperature)
        if not self.junction.capacitance > 0:
            raise ValueError("parameter 'capacitance' must be > 0 (the SQUID's junctions are pendula with "
                             "inertia; a small capacitance gives the overdamped limit)")
        self.inductance = _checks.real(inductance, "inductance", 0.0, lo_open=True)
        self.current_asymmetry = _asymmetry(current_asymmetry, "current_asymmetry")
        self.resistance_asymmetry = _asymmetry(resistance_asymmetry, "resistance_asymmetry")
        self.inductance_asymmetry = _asymmetry(inductance_asymmetry, "inductance_asymmetry")

    def __repr__(self) -> str:
        a = self._asym
        more = "" if a == (0.0, 0.0, 0.0) else f", alpha_i={a[0]:.6g}, alpha_r={a[1]:.6g}, eta={a[2]:.6g}"
        return f"DCSquid(I0={self.junction.critical_current!r} A, beta_l={self.beta_l:.6g}{more})"

    @property
    def _asym(self) -> tuple[float, float, float]:
        return (self.current_asymmetry, self.resistance_asymmetry, self.inductance_asymmetry)

    @property
    def beta_l(self) -> float:
        """The screening parameter β_L = 2LI₀/Φ₀ (I₀ the junctions' mean)."""
        return 2 * self.inductance * self.junction.critical_current / FLUX_QUANTUM

    @property
    def beta_c(self) -> float:
        """The Stewart-McCumber parameter β_c = 2πI₀R²C/Φ₀ of the mean junction."""
        return self.junction.stewart_mccumber

    @property
    def characteristic_frequency(self) -> float:
        """ω_c = 2πI₀R/Φ₀ (rad/s), the time unit of the dynamic curves."""
        return self.junction.characteristic_frequency

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
        return squid_critical_current(self.beta_l, flux, current_asymmetry=self.current_asymmetry,
                                      inductance_asymmetry=self.inductance_asymmetry) * self.junction.critical_current

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
            Two elements, damping (1 ∓ α_R)/√β_c, mass (1 ∓ α_R), sine
            strength (1 ∓ α_I), bias (1 ± η)/2 of the total, spring
            1/(π β_L), offset −2πΦ/Φ₀.

        Examples
        --------
        >>> sq = DCSquid(10e-6, 2.0, 1e-13, 103.4e-12)
        >>> net = sq.network(5e-6, 0.25)
        >>> net.n, float(net.bias[0])
        (2, 0.25)
        """
        b = _checks.real(bias, "bias") / self.junction.critical_current
        return _network(self.beta_l, _checks.real(flux, "flux"), b, self.junction.damping, self._asym)

    # ------------------------------------------------------------------ the dynamic curves
    def _times(self, transient, t_max) -> tuple[float, float]:
        wc = self.characteristic_frequency
        tr = 200.0 * max(1.0, self.beta_c) if transient is None else \
            _checks.real(transient, "transient", 0.0) * wc
        tm = 1000.0 if t_max is None else _checks.real(t_max, "t_max", 0.0, lo_open=True) * wc
        return tr, tm

    def _noise(self, dt, paths, seed, threads, bias: float = 0.0,
               rf: tuple[float, float] = (0.0, 0.0)) -> tuple[float, float, int, int, int]:
        temp = self.junction.noise
        if temp == 0:
            return 0.0, 0.0, 1, 0, 0
        # the default step: the network rule's (the kernel's) for the SQUID at the largest reduced bias
        # and the rf drive: the velocity's relaxation 1/β_c, the loop's fastest mode, the running speed,
        # the drive
        h = squid_network(self.beta_l, self.beta_c, 0.0, bias, *rf, asym=self._asym).time_scales() \
            .default_dt["baoab"] if dt is None else \
            _checks.real(dt, "dt", 0.0, lo_open=True) * self.characteristic_frequency
        return (temp, h, _checks.count(paths, "paths", 2), _checks.count(seed, "seed", 0, 2**63 - 1),
                _checks.threads(threads))

    def _velocity(self, bias: float, flux: float, phi, v, tr, tm, rtol, noise, rf=(0.0, 0.0)):
        """⟨s'⟩ (in ω_c), its error, each path's drift (noise) and the final state, at the reduced bias."""
        net = squid_network(self.beta_l, self.beta_c, flux, bias, *rf, asym=self._asym)
        temp, h, paths, seed, threads = noise
        if temp == 0:
            vel, err, phi, v = mean_velocity(net, phi, v, tr, tm, rtol)
            return vel, err, None, wrap(phi), v
        drift, phi, v = noisy_mean_velocity(net, phi, v, tr, tm, temp, h, paths, seed, threads)
        return float(drift.mean()), float(drift.std(ddof=1) / math.sqrt(paths)), drift, wrap(phi), v

    def _attrs(self, noise, rtol, tr, tm) -> dict:
        wc = self.characteristic_frequency
        a = {"critical_current": self.junction.critical_current, "resistance": self.junction.resistance,
             "capacitance": self.junction.capacitance, "inductance": self.inductance,
             "temperature": self.junction.temperature, "beta_l": self.beta_l, "beta_c": self.beta_c,
             "current_asymmetry": self.current_asymmetry, "resistance_asymmetry": self.resistance_asymmetry,
             "inductance_asymmetry": self.inductance_asymmetry,
             "characteristic_frequency": wc, "transient": tr / wc, "t_max": tm / wc,
             "constants": "CODATA 2018 (exact): h = 6.62607015e-34 J s, e = 1.602176634e-19 C, "
                          "k_B = 1.380649e-23 J/K"}
        if noise[0] > 0:
            a.update({"method": "baoab", "dt": noise[1] / wc, "paths": noise[2], "seed": noise[3],
                      "voltage_err": "standard error of the paths' mean"})
        else:
            a.update({"method": "dop853", "rtol": rtol,
                      "voltage_err": "half the difference of the means over the first and second halves of "
                                     "the whole turns, not below rtol"})
        return a

    def iv_curve(self, currents: ArrayLike, flux: float = 0.0,
                 direction: Literal["up", "down", "both"] = "up", *, transient: float | None = None,
                 t_max: float | None = None, rf_current: float = 0.0, rf_frequency: float = 0.0,
                 rtol: float = 1e-10, dt: float | None = None, paths: int = 4, seed: int = 0,
                 threads: int = 0) -> xarray.Dataset:
        """The SQUID's dynamic I-V curve at the flux Φ/Φ₀: the dc voltage at each bias current.

        The bias is ramped through ``currents`` (each current starts from the
        state the previous one ended in), so a hysteretic SQUID (β_c > 1)
        shows its two branches with ``direction='both'``.  The junctions
        obey the RCSJ equations (Tesche and Clarke 1977, section 2), run in
        the time unit 1/ω_c; the voltage is I₀R⟨s'⟩, s the mean of the two
        phases.  Without noise ⟨s'⟩ is measured over whole turns of the
        running state (exact for a periodic one); at a temperature > 0 it is
        the mean drift of ``paths`` noisy paths (BAOAB, one noise stream
        per junction keyed by (seed, path, junction): the same numbers on
        any thread count).  An rf current I_rf cos(2πft) beside the bias
        gives Shapiro steps, locked at V = (n/m) fΦ₀ (the SQUID also locks
        at fractions of fΦ₀).

        Parameters
        ----------
        currents : array_like
            Bias currents (A), ascending.
        flux : float, optional
            The applied flux Φ/Φ₀ (default 0).
        direction : {'up', 'down', 'both'}, optional
            The branches of the ramp (default 'up').
        transient, t_max : float, optional
            Seconds skipped and averaged at each current (default 200
            max(1, β_c) and 1000 times 1/ω_c).
        rf_current, rf_frequency : float, optional
            The amplitude (A) and frequency (Hz, >= 0) of an rf current
            shared by the two junctions like the bias (both or neither).
        rtol : float, optional
            The integrator's relative tolerance without noise (default 1e-10).
        dt : float, optional
            The step (s) of the noisy paths (default: the network rule's
            BAOAB step for the SQUID at the largest current and the rf drive,
            :meth:`Network.time_scales <pendula.Network.time_scales>`: 2π/100
            over the fastest of 1/β_c, the loop's fastest mode, the running
            speed and the drive, in the time unit 1/ω_c).
        paths : int, optional
            Noisy paths at each current (>= 2; default 4).
        seed : int, optional
            The seed of the noise (>= 0).
        threads : int, optional
            OpenMP threads for the noisy paths (0: OpenMP's default).

        Returns
        -------
        xarray.Dataset
            Over (``direction``, ``current``): ``voltage`` and ``voltage_err``
            (V), ``mean_velocity`` (⟨s'⟩/ω_c); coordinates ``current`` (A)
            and ``bias`` (I/I₀); CF ``units`` attributes; the SQUID's
            constants and how the error was estimated in the attributes.

        Raises
        ------
        ValueError
            Currents not ascending, a bad time, flux, rtol or dt, naming it.

        See Also
        --------
        v_phi_curve, transfer_function, critical_current

        Examples
        --------
        >>> sq = DCSquid(10e-6, 10.0, 1.6e-13, 51.7e-12)      # beta_L = 0.5, beta_c = 0.49
        >>> r = sq.iv_curve([10e-6, 40e-6], flux=0.25)
        >>> r.voltage.dims, r.voltage.attrs["units"]
        (('direction', 'current'), 'V')
        >>> v = r.voltage[0].values * 1e6                           # µV
        >>> bool(abs(v[0]) < 1e-6), round(float(v[1]), 3)   # at rest, then running
        (True, 179.365)
        """
        xr = require("xarray", "xarray", "DCSquid.iv_curve")
        cur = _checks.grid_values(currents, "currents")
        if np.any(np.diff(cur) < 0):
            raise ValueError("currents must be in ascending order: direction='up' ramps them as given and "
                             "'down' in reverse; give np.sort(currents)")
        direction = _checks.choice(direction, "direction", ("up", "down", "both"))
        flux = _checks.real(flux, "flux")
        rtol = _checks.real(rtol, "rtol", 0.0, lo_open=True)
        tr, tm = self._times(transient, t_max)
        i0 = self.junction.critical_current
        a = _checks.real(rf_current, "rf_current")
        f = _checks.real(rf_frequency, "rf_frequency", 0.0)
        if (a != 0) != (f > 0):
            raise ValueError(f"rf_current ({a!r} A) and rf_frequency ({f!r} Hz): an rf drive needs both, "
                             "or give neither")
        rf = (a / i0, _TWO_PI * f / self.characteristic_frequency)
        noise = self._noise(dt, paths, seed, threads, float(np.max(np.abs(cur))) / i0 if cur.size else 0.0, rf)
        dirs = ["up", "down"] if direction == "both" else [direction]
        vel = np.full((len(dirs), cur.size), np.nan)
        err = np.full_like(vel, np.nan)
        phi, v = np.array([math.pi * flux, -math.pi * flux]), np.zeros(2)
        for d, name in enumerate(dirs):
            order = range(cur.size) if name == "up" else range(cur.size - 1, -1, -1)
            for j in order:
                vel[d, j], err[d, j], _, phi, v = self._velocity(cur[j] / i0, flux, phi, v, tr, tm, rtol, noise,
                                                                 rf)
        volt = i0 * self.junction.resistance
        ds = xr.Dataset(
            {"voltage": (("direction", "current"), vel * volt, {"long_name": "dc voltage", "units": "V"}),
             "voltage_err": (("direction", "current"), err * volt,
                             {"long_name": "error of the dc voltage", "units": "V"}),
             "mean_velocity": (("direction", "current"), vel,
                               {"long_name": "mean phase velocity / omega_c", "units": "1"})},
            coords={"direction": dirs, "current": ("current", cur, {"long_name": "bias current", "units": "A"}),
                    "bias": ("current", cur / i0, {"long_name": "bias current / I0", "units": "1"})},
            attrs=self._attrs(noise, rtol, tr, tm) | {"flux": flux, "rf_current": a, "rf_frequency": f})
        return ds

    def v_phi_curve(self, current: float, fluxes: ArrayLike,
                    direction: Literal["up", "down", "both"] = "up", *, transient: float | None = None,
                    t_max: float | None = None, rtol: float = 1e-10, dt: float | None = None, paths: int = 4,
                    seed: int = 0, threads: int = 0) -> xarray.Dataset:
        """The SQUID's V-Φ curve: the dc voltage at a fixed bias current over the applied flux.

        The flux is swept through ``fluxes`` in the order given (each flux
        starts from the state the previous one ended in), as in the
        laboratory; the voltage is measured as in :meth:`iv_curve`.  A
        hysteretic SQUID (β_c > 1, or β_L large enough for several flux
        states) shows two branches: ``direction='down'`` sweeps the fluxes
        in reverse order, ``'both'`` forwards and then back from where the
        forward sweep ended.

        Parameters
        ----------
        current : float
            The bias current (A).
        fluxes : array_like
            Φ/Φ₀, swept in this order.
        direction : {'up', 'down', 'both'}, optional
            The order given, the reverse, or both one after the other
            (default 'up').
        transient, t_max, rtol, dt, paths, seed, threads
            As in :meth:`iv_curve`.

        Returns
        -------
        xarray.Dataset
            Over ``flux`` (units ``Phi0``): ``voltage``, ``voltage_err`` (V)
            and ``mean_velocity``; ``direction`` a coordinate, and with
            ``'both'`` a dimension (``'up'`` then ``'down'``).

        Raises
        ------
        ValueError
            A bad current, flux, time, rtol or dt, naming it.

        See Also
        --------
        iv_curve, transfer_function

        Examples
        --------
        >>> sq = DCSquid(10e-6, 10.0, 1.6e-13, 51.7e-12)
        >>> r = sq.v_phi_curve(20e-6, [0.0, 0.5])
        >>> bool(r.voltage[0] < r.voltage[1]), r.flux.attrs["units"]
        (True, 'Phi0')
        >>> h = sq.v_phi_curve(20e-6, [0.0, 0.5], direction="both")
        >>> h.voltage.dims, h.direction.values.tolist()
        (('direction', 'flux'), ['up', 'down'])
        """
        xr = require("xarray", "xarray", "DCSquid.v_phi_curve")
        cur = _checks.real(current, "current")
        fl = _checks.as_float(fluxes, "fluxes").ravel()
        if not np.all(np.isfinite(fl)):
            raise ValueError("fluxes must be finite")
        direction = _checks.choice(direction, "direction", ("up", "down", "both"))
        rtol = _checks.real(rtol, "rtol", 0.0, lo_open=True)
        tr, tm = self._times(transient, t_max)
        noise = self._noise(dt, paths, seed, threads, cur / self.junction.critical_current)
        i0 = self.junction.critical_current
        dirs = ["up", "down"] if direction == "both" else [direction]
        vel, err = np.full((len(dirs), fl.size), np.nan), np.full((len(dirs), fl.size), np.nan)
        start = fl[0] if direction != "down" else fl[-1]
        phi = np.array([math.pi * start, -math.pi * start]) if fl.size else np.zeros(2)
        v = np.zeros(2)
        for d, name in enumerate(dirs):
            for j in (range(fl.size) if name == "up" else range(fl.size - 1, -1, -1)):
                vel[d, j], err[d, j], _, phi, v = self._velocity(cur / i0, float(fl[j]), phi, v, tr, tm, rtol,
                                                                 noise)
        volt = i0 * self.junction.resistance
        ds = xr.Dataset(
            {"voltage": (("direction", "flux"), vel * volt, {"long_name": "dc voltage", "units": "V"}),
             "voltage_err": (("direction", "flux"), err * volt,
                             {"long_name": "error of the dc voltage", "units": "V"}),
             "mean_velocity": (("direction", "flux"), vel,
                               {"long_name": "mean phase velocity / omega_c", "units": "1"})},
            coords={"direction": dirs,
                    "flux": ("flux", fl, {"long_name": "applied flux / flux quantum", "units": "Phi0"})},
            attrs=self._attrs(noise, rtol, tr, tm) | {"current": cur})
        return ds if direction == "both" else ds.isel(direction=0)

    def sweep(self, fluxes: ArrayLike, currents: ArrayLike, *, transient: float | None = None,
              t_max: float | None = None, rtol: float = 1e-10, dt: float | None = None, paths: int = 4,
              seed: int = 0, threads: int = 0, progress: bool = False,
              out: str | os.PathLike[str] | None = None) -> xarray.Dataset:
        """The dc voltage over a grid of applied flux and bias current, on threads.

        Every grid point starts from rest: a map of the voltage, not a ramp
        (the ramps, with their hysteresis, are :meth:`iv_curve` and
        :meth:`v_phi_curve`).  The voltage at each point is measured as in
        :meth:`iv_curve`.  The points of one flux run on ``threads``
        threads; with noise, grid point p (row-major) draws the noise
        streams p·paths to p·paths + paths − 1 of ``seed``: the same numbers
        on any thread count, and after a resume.

        Parameters
        ----------
        fluxes : array_like
            Φ/Φ₀, the first axis.
        currents : array_like
            Bias currents (A), the second axis.
        transient, t_max, rtol, dt, paths, seed
            As in :meth:`iv_curve`.
        threads : int, optional
            Threads over the points of a flux (0: every core).
        progress : bool, optional
            A progress bar over the fluxes (default False).
        out : str or os.PathLike, optional
            A folder for the resumable Zarr store of :func:`pendula.sweep`
            (one flux a chunk): a sweep stopped half way resumes where it
            stopped.

        Returns
        -------
        xarray.Dataset
            Over (``flux``, ``current``): ``voltage``, ``voltage_err`` (V)
            and ``mean_velocity`` (⟨s'⟩/ω_c); coordinates ``flux`` (Phi0),
            ``current`` (A) and ``bias`` (I/I₀); the SQUID's constants in the
            attributes.

        Raises
        ------
        ValueError
            Empty or non-finite axes, a bad time, rtol or dt, or an ``out``
            that holds something else, naming it.

        See Also
        --------
        iv_curve, v_phi_curve

        Examples
        --------
        >>> sq = DCSquid(10e-6, 10.0, 1.6e-13, 51.7e-12)
        >>> m = sq.sweep([0.0, 0.5], [10e-6, 25e-6])
        >>> m.voltage.dims, m.voltage.attrs["units"]
        (('flux', 'current'), 'V')
        >>> v = m.voltage.values * 1e6                                   # µV
        >>> bool(abs(v[0, 0]) < 1e-6), bool(v[1, 0] > 1)    # at rest at Φ = 0, running at Φ₀/2
        (True, True)
        """
        from .squid_sweep import squid_sweep
        rtol = _checks.real(rtol, "rtol", 0.0, lo_open=True)
        tr, tm = self._times(transient, t_max)
        noise = self._noise(dt, paths, seed, threads)
        return squid_sweep(self, fluxes, currents, tr, tm, rtol, noise, progress, out)

    def transfer_function(self, current: float, fluxes: ArrayLike, *, step: float | None = None,
                          transient: float | None = None, t_max: float | None = None, rtol: float = 1e-10,
                          dt: float | None = None, paths: int = 4, seed: int = 0,
                          threads: int = 0) -> xarray.Dataset:
        """The transfer function dV/dΦ at a fixed bias current: the SQUID's gain as a flux sensor.

        At each flux the voltage is measured at Φ ± h and Φ ± 2h (h =
        ``step``), swept in that order from the rest state.  Without noise
        dV/dΦ is the central difference extrapolated (Richardson) to h → 0,
        (4 D(h) − D(2h))/3, its error estimate abs(D(h) − D(2h))/3 plus the
        voltages' errors over 2h.  With noise the paths at Φ − h and Φ + h
        draw the same noise (the same seed: common random numbers), and the
        error is the standard error of the paths' differences.

        Parameters
        ----------
        current : float
            The bias current (A).
        fluxes : array_like
            Φ/Φ₀.
        step : float, optional
            h in units of Φ₀ (default 1e-3, or 0.02 with noise).
        transient, t_max, rtol, dt, paths, seed, threads
            As in :meth:`iv_curve`.

        Returns
        -------
        xarray.Dataset
            Over ``flux``: ``transfer`` and ``transfer_err`` (V/Φ₀, units
            ``V/Phi0``) and ``voltage`` (V) at the flux itself, the mean of
            the two inner points.

        Raises
        ------
        ValueError
            A bad current, flux, step, time, rtol or dt, naming it.

        See Also
        --------
        v_phi_curve

        Examples
        --------
        >>> sq = DCSquid(10e-6, 10.0, 1.6e-13, 51.7e-12)
        >>> r = sq.transfer_function(20e-6, [0.25])
        >>> bool(r.transfer[0] > 0), r.transfer.attrs["units"]
        (True, 'V/Phi0')
        """
        xr = require("xarray", "xarray", "DCSquid.transfer_function")
        cur = _checks.real(current, "current")
        fl = _checks.as_float(fluxes, "fluxes").ravel()
        if not np.all(np.isfinite(fl)):
            raise ValueError("fluxes must be finite")
        rtol = _checks.real(rtol, "rtol", 0.0, lo_open=True)
        tr, tm = self._times(transient, t_max)
        noise = self._noise(dt, paths, seed, threads, cur / self.junction.critical_current)
        noisy = noise[0] > 0
        h = (0.02 if noisy else 1e-3) if step is None else _checks.real(step, "step", 0.0, lo_open=True)
        i0 = self.junction.critical_current
        volt = i0 * self.junction.resistance
        tf, tf_err, vmid = np.full(fl.size, np.nan), np.full(fl.size, np.nan), np.full(fl.size, np.nan)
        for j, f in enumerate(fl):
            f = float(f)
            phi, v = np.array([math.pi * f, -math.pi * f]), np.zeros(2)
            res = {}
            for m in ((-1, 1) if noisy else (-2, -1, 1, 2)):
                res[m] = self._velocity(cur / i0, f + m * h, phi, v, tr, tm, rtol, noise)
                phi, v = res[m][3], res[m][4]
            d1 = (res[1][0] - res[-1][0]) / (2 * h)
            vmid[j] = 0.5 * (res[1][0] + res[-1][0])
            if noisy:
                diff = (res[1][2] - res[-1][2]) / (2 * h)
                tf[j], tf_err[j] = d1, float(diff.std(ddof=1) / math.sqrt(diff.size))
            else:
                d2 = (res[2][0] - res[-2][0]) / (4 * h)
                tf[j] = (4 * d1 - d2) / 3
                tf_err[j] = abs(d1 - d2) / 3 + (res[1][1] + res[-1][1]) / (2 * h)
        return xr.Dataset(
            {"transfer": ("flux", tf * volt, {"long_name": "transfer function dV/dPhi", "units": "V/Phi0"}),
             "transfer_err": ("flux", tf_err * volt, {"long_name": "error of dV/dPhi", "units": "V/Phi0"}),
             "voltage": ("flux", vmid * volt, {"long_name": "dc voltage", "units": "V"})},
            coords={"flux": ("flux", fl, {"long_name": "applied flux / flux quantum", "units": "Phi0"})},
            attrs=self._attrs(noise, rtol, tr, tm) | {"current": cur, "step": h})

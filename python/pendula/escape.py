"""Escape of a current-biased junction out of its well, and switching at any ramp rate.

The zero-voltage state of a current-biased junction is a particle in a well
of the tilted washboard U(phi) = -E_J (cos phi + i phi), i = I / I_c.  It
leaves the well (the junction switches to the voltage state) by thermal
activation over the barrier or, at low temperature, by macroscopic quantum
tunnelling through it.  This module gives the rate Gamma(I, T) of both, the
crossover temperature between them, and the switching-current distribution
of a linear ramp at any rate by the Fulton-Dunkleberger integral (Fulton and
Dunkleberger, Phys. Rev. B 9 (1974) 4760):

    P(I) = Gamma(I) / (dI/dt) exp(-int_0^I Gamma(I') dI' / (dI/dt)).

Inputs are laboratory units through :class:`pendula.Junction` (its critical
current, resistance, capacitance and temperature; the constants are the
exact CODATA 2018 ones of :mod:`pendula.junction`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from . import _checks
from .junction import BOLTZMANN, PLANCK, Junction

__all__ = ["thermal_rate", "quantum_rate", "escape_rate", "crossover_temperature",
           "switching_distribution", "SwitchingDistribution"]

_HBAR = PLANCK / (2.0 * math.pi)

# Gauss-Legendre nodes of the barrier orbit's action and of the panels of the
# Fulton-Dunkleberger integral, with the matrix that integrates the degree-15
# interpolant from -1 to each node (Legendre series: legint)
_XA, _WA = np.polynomial.legendre.leggauss(48)
_XP, _WP = np.polynomial.legendre.leggauss(16)
_XD, _WD = np.polynomial.legendre.leggauss(8)


def _node_integrals(x: np.ndarray) -> np.ndarray:
    v = np.polynomial.legendre.legvander(x, x.size - 1)
    coef = np.linalg.inv(v)                       # column k: the Legendre series of the k-th Lagrange basis
    out = np.empty((x.size, x.size))
    for k in range(x.size):
        out[:, k] = np.polynomial.legendre.legval(x, np.polynomial.legendre.legint(coef[:, k], lbnd=-1))
    return out


_MP = _node_integrals(_XP)
# the Mel'nikov integral: x = sinh(u), trapezoid in u (the integrand is analytic: exponential convergence;
# 201 points on [0, u_max] give A(Delta) to 4e-14 against mpmath for Delta in [1e-10, 150])
_MEL_N = 201


def _junction(junction) -> Junction:
    if not isinstance(junction, Junction):
        raise TypeError(f"parameter 'junction' must be a pendula.Junction, not {type(junction).__name__}")
    if not junction.capacitance > 0:
        raise ValueError("parameter 'junction': field 'capacitance' is 0 (the overdamped RSJ junction): escape "
                         "out of a well needs the capacitance, the particle's mass (give C > 0)")
    return junction


def _temperature(junction: Junction, temperature) -> float:
    if temperature is None:
        return junction.temperature
    return _checks.real(temperature, "parameter 'temperature'", 0.0)


def _bias(junction: Junction, bias) -> np.ndarray:
    b = _checks.as_float(bias, "parameter 'bias'")
    if np.any(np.isnan(b)):
        raise ValueError("parameter 'bias' must hold numbers, not NaN")
    return np.abs(b) / junction.critical_current


def _barrier(i):
    """Barrier height dU / E_J, well frequency omega_a / omega_p (the barrier's
    curvature frequency is the same for the washboard) at bias i in [0, 1)."""
    s = np.sqrt((1.0 - i) * (1.0 + i))
    return 2.0 * (s - i * np.arccos(i)), np.sqrt(s)


def _barrier_action(i):
    """The action S_b / (E_J / omega_p) of the orbit at the barrier's energy,
    the loop from the barrier top round the well and back: 2 int sqrt(2 (U_b -
    U)) dphi, by 48-point Gauss-Legendre after phi = phi_t + L u^2 (u in [0,
    1]) removes the square root at the turning point phi_t."""
    i = np.asarray(i, dtype=float)
    top = np.pi - np.arcsin(i)
    ub = -np.cos(top) - i * top
    lo, hi = top - 2.0 * np.pi, np.arcsin(i)         # U(lo) >= U_b > U(hi): the turning point between
    for _ in range(64):
        mid = 0.5 * (lo + hi)
        above = -np.cos(mid) - i * mid >= ub
        lo, hi = np.where(above, mid, lo), np.where(above, hi, mid)
    turn = 0.5 * (lo + hi)
    span = top - turn
    u = 0.5 * (_XA + 1.0)
    phi = turn[..., None] + span[..., None] * u * u
    gap = np.maximum(ub[..., None] - (-np.cos(phi) - i[..., None] * phi), 0.0)
    return 2.0 * np.sum(0.5 * _WA * np.sqrt(2.0 * gap) * 2.0 * span[..., None] * u, axis=-1)


def _melnikov(delta):
    """Mel'nikov's depopulation factor A(Delta) = exp((1/pi) int_0^inf ln(1 -
    exp(-Delta (x^2 + 1/4))) / (x^2 + 1/4) dx) (Mel'nikov and Meshkov 1986;
    Hanggi, Talkner and Borkovec 1990, section VI.C): A -> Delta as Delta -> 0
    (energy diffusion: the integral tends to pi ln Delta), A -> 1 as Delta ->
    infinity."""
    d = np.asarray(delta, dtype=float)
    flat = d.reshape(-1)
    out = np.ones_like(flat)
    pos = (flat > 0) & (flat < 150.0)        # from Delta = 150 on, ln A > -1e-17: A = 1 in double precision
    dp = flat[pos]
    if dp.size:
        umax = np.arcsinh(np.sqrt(60.0 / np.minimum(dp, 60.0)))            # exp(-Delta x^2) < e^-60 beyond
        t = np.linspace(0.0, 1.0, _MEL_N)
        u = umax[:, None] * t
        x = np.sinh(u)
        q = x * x + 0.25
        f = np.log(-np.expm1(-dp[:, None] * q)) / q * np.cosh(u)
        h = umax * (t[1] - t[0])
        integral = h * (np.sum(f, axis=1) - 0.5 * (f[:, 0] + f[:, -1]))
        # the integrand is even in u: the trapezoid from 0 keeps its exponential convergence; beyond x_max
        # it is ln(1 - e^{-Delta q}) / q ~ -e^{-Delta q} / q: below e^-60
        out[pos] = np.exp(integral / np.pi)
    out[flat == 0] = 0.0
    return out.reshape(d.shape)


def _log_thermal(i, beta, temp):
    """ln(Gamma_thermal / omega_p) in reduced units (beta the damping 1 / (omega_p R C),
    temp = k_B T / E_J)."""
    du, wa = _barrier(i)
    alpha = beta / (2.0 * wa)
    kramers = np.sqrt(1.0 + alpha * alpha) - alpha
    with np.errstate(divide="ignore"):
        if temp > 0:
            # Mel'nikov's factor (A <= 1) only where the rate is above e^-800 omega_p (below, it is 0 in double
            # precision whatever A is: A = 1 there)
            a = np.ones_like(i)
            live = du / temp < 800.0
            a[live] = _melnikov(beta * _barrier_action(i[live]) / temp)
            return np.log(wa / (2.0 * math.pi) * kramers * a) - du / temp
        return np.full_like(i, -np.inf)


def _log_quantum(i, beta, hw):
    """ln(Gamma_quantum / omega_p) in reduced units (hw = hbar omega_p / E_J)."""
    du, wa = _barrier(i)
    b = 7.2 * du / (hw * wa)
    q = wa / beta
    with np.errstate(divide="ignore"):
        return np.log(wa / (2.0 * math.pi) * np.sqrt(120.0 * math.pi * b)) - b * (1.0 + 0.87 / q)


def _log_rate(i, beta, temp, hw):
    """ln(Gamma / omega_p): the larger of thermal activation and tunnelling; +inf at i >= 1."""
    i = np.asarray(i, dtype=float)
    out = np.full(i.shape, np.inf)
    ok = i < 1.0
    if np.any(ok):
        ii = i[ok]
        out[ok] = np.maximum(_log_thermal(ii, beta, temp), _log_quantum(ii, beta, hw))
    return out


def _reduced(junction: Junction, temperature: float) -> tuple[float, float, float]:
    ej = junction.josephson_energy
    return junction.damping, BOLTZMANN * temperature / ej, _HBAR * junction.plasma_frequency / ej


def _rate(log_fn, junction, bias):
    i = _bias(junction, bias)
    out = np.full(i.shape, np.inf)
    ok = i < 1.0
    if np.any(ok):
        out[ok] = junction.plasma_frequency * np.exp(log_fn(i[ok]))
    return out


def thermal_rate(junction: Junction, bias: ArrayLike, temperature: float | None = None) -> np.ndarray:
    """The thermal escape rate over the barrier at every damping, 1 / s.

    Mel'nikov and Meshkov's turnover formula (J. Chem. Phys. 85 (1986)
    1018; Hanggi, Talkner and Borkovec, Rev. Mod. Phys. 62 (1990) 251,
    section VI.C, eq. 6.26), which joins the energy-diffusion (weak damping)
    and the spatial-diffusion (moderate to strong damping) regimes:

        Gamma = A(Delta) (sqrt(1 + alpha²) - alpha) (omega_a / 2π) exp(-ΔU / k_B T),

    with ΔU = 2 E_J (sqrt(1 - i²) - i arccos i) the barrier, omega_a =
    omega_p (1 - i²)^(1/4) the frequency of the well (and of the barrier's
    top), alpha = 1 / (2 omega_a R C) (Kramers' factor for the barrier),
    Delta = S_b / (omega_p R C k_B T) the energy lost by damping along the
    orbit at the barrier's energy (S_b its action ∮ p dphi, computed
    exactly for the washboard, not in the cubic approximation), and
    Mel'nikov's factor A(Delta) = exp((1/π) ∫₀^∞ ln(1 - exp(-Delta (x² + ¼))) /
    (x² + ¼) dx) (A -> Delta at weak damping, -> 1 at strong).  Buttiker, Harris and Landauer's interpolation (Phys.
    Rev. B 28 (1983) 1268; :meth:`pendula.Junction.escape_rate` with
    ``regime='underdamped'``) is the earlier form of the same crossover.
    Valid while ΔU >> k_B T; no quantum corrections (see
    :func:`crossover_temperature`).

    Parameters
    ----------
    junction : Junction
        The junction (C > 0).
    bias : array_like
        Bias currents, A (the sign is the direction of the tilt).
    temperature : float, optional
        Kelvin, >= 0 (default: the junction's).

    Returns
    -------
    numpy.ndarray
        Gamma, 1 / s (0 at T = 0, inf at abs(I) >= I_c).

    Raises
    ------
    TypeError
        A junction that is not a :class:`pendula.Junction`, or a bias that is
        not numbers.
    ValueError
        A negative temperature, a NaN bias, or a junction without
        capacitance, naming the parameter.

    See Also
    --------
    quantum_rate, escape_rate, crossover_temperature

    Examples
    --------
    >>> import pendula
    >>> from pendula.escape import thermal_rate
    >>> j = pendula.Junction(10e-6, 30.0, 1e-12, temperature=4.2)
    >>> g = thermal_rate(j, [8e-6, 9e-6])
    >>> bool(g[1] > 1e2 * g[0])
    True
    """
    j = _junction(junction)
    beta, temp, _ = _reduced(j, _temperature(j, temperature))
    return _rate(lambda i: _log_thermal(i, beta, temp), j, bias)


def quantum_rate(junction: Junction, bias: ArrayLike) -> np.ndarray:
    """The rate of macroscopic quantum tunnelling out of the well at T = 0, 1 / s.

    The Caldeira-Leggett rate for the cubic well with its first-order
    damping correction (Caldeira and Leggett, Ann. Phys. 149 (1983) 374,
    section 6; in the form used for junctions by Martinis, Devoret and
    Clarke, Phys. Rev. B 35 (1987) 4682, section II):

        Gamma_q = a_q (omega_a / 2π) exp(-7.2 (ΔU / ħ omega_a) (1 + 0.87 / Q)),
        a_q = sqrt(120 π · 7.2 ΔU / ħ omega_a),

    Q = omega_a R C the quality factor, ΔU and omega_a as in
    :func:`thermal_rate`.  The prefactor is the undamped one (its damping
    correction is of order 1 / Q, beside the exponent's 0.87 / Q).  Valid
    for ΔU >> ħ omega_a and Q >~ 1.

    Parameters
    ----------
    junction : Junction
        The junction (C > 0).
    bias : array_like
        Bias currents, A.

    Returns
    -------
    numpy.ndarray
        Gamma_q, 1 / s (inf at abs(I) >= I_c).

    Raises
    ------
    TypeError, ValueError
        As :func:`thermal_rate`.

    See Also
    --------
    thermal_rate, escape_rate, crossover_temperature

    Examples
    --------
    >>> import pendula
    >>> from pendula.escape import quantum_rate
    >>> j = pendula.Junction(10e-6, 30.0, 1e-12)
    >>> g = quantum_rate(j, 9.9e-6)               # per second
    >>> bool(1e2 < g[()] < 1e8)
    True
    """
    j = _junction(junction)
    beta, _, hw = _reduced(j, 0.0)
    return _rate(lambda i: _log_quantum(i, beta, hw), j, bias)


def escape_rate(junction: Junction, bias: ArrayLike, temperature: float | None = None) -> np.ndarray:
    """The escape rate Gamma(I, T): thermal activation or tunnelling, 1 / s.

    The larger of :func:`thermal_rate` and :func:`quantum_rate`.  Far above
    the crossover temperature (:func:`crossover_temperature`) that is the
    thermal rate, far below it the quantum one; the two meet a little below
    T_cr (at about 0.87 T_cr for weak damping, where the exponents
    ΔU / k_B T and 7.2 ΔU / ħ omega_a are equal).  Near the crossover both
    formulas miss the quantum enhancement of thermal activation (Grabert,
    Olschowski and Weiss, Phys. Rev. B 36 (1987) 1931), which is largest at
    T_cr, a factor of a few: the joined rate is a lower bound there.

    Parameters
    ----------
    junction : Junction
        The junction (C > 0).
    bias : array_like
        Bias currents, A.
    temperature : float, optional
        Kelvin, >= 0 (default: the junction's).

    Returns
    -------
    numpy.ndarray
        Gamma, 1 / s (inf at abs(I) >= I_c).

    Raises
    ------
    TypeError, ValueError
        As :func:`thermal_rate`.

    See Also
    --------
    switching_distribution : the switching currents of a ramp from this rate.

    Examples
    --------
    >>> import pendula
    >>> from pendula.escape import escape_rate, quantum_rate
    >>> j = pendula.Junction(10e-6, 30.0, 1e-12, temperature=0.02)
    >>> bool(escape_rate(j, 9.9e-6) == quantum_rate(j, 9.9e-6))   # 20 mK: tunnelling
    True
    """
    j = _junction(junction)
    beta, temp, hw = _reduced(j, _temperature(j, temperature))
    return _rate(lambda i: _log_rate(i, beta, temp, hw), j, bias)


def crossover_temperature(junction: Junction, bias: ArrayLike) -> np.ndarray:
    """The crossover temperature between thermal activation and tunnelling, K.

    T_cr = ħ omega_R / (2π k_B), omega_R = omega_a (sqrt(1 + alpha²) -
    alpha), alpha = 1 / (2 omega_a R C): the temperature below which the
    escape is dominated by tunnelling through the barrier rather than
    activation over it (Affleck, Phys. Rev. Lett. 46 (1981) 388; with
    damping, Grabert and Weiss, Phys. Rev. Lett. 53 (1984) 1787).  It falls
    with the bias as omega_a = omega_p (1 - i²)^(1/4).

    Parameters
    ----------
    junction : Junction
        The junction (C > 0).
    bias : array_like
        Bias currents, A (abs(I) < I_c; 0 at abs(I) >= I_c).

    Returns
    -------
    numpy.ndarray
        Kelvin.

    Raises
    ------
    TypeError, ValueError
        As :func:`thermal_rate`.

    See Also
    --------
    escape_rate : the rate on either side.

    Examples
    --------
    >>> import pendula
    >>> from pendula.escape import crossover_temperature
    >>> j = pendula.Junction(10e-6, 30.0, 1e-12)
    >>> round(float(crossover_temperature(j, 0.0)), 4)          # K, at zero bias
    0.1926
    """
    j = _junction(junction)
    i = np.minimum(_bias(j, bias), 1.0)
    _, wa = _barrier(i)
    alpha = j.damping / (2.0 * np.where(wa > 0, wa, 1.0))
    wr = wa * (np.sqrt(1.0 + alpha * alpha) - alpha)
    return _HBAR * j.plasma_frequency * wr / (2.0 * math.pi * BOLTZMANN)


@dataclass(frozen=True)
class SwitchingDistribution:
    """The switching-current distribution of a linear ramp (Fulton and Dunkleberger).

    Attributes
    ----------
    mean, width : float
        The mean switching current and the standard deviation, A.
    at_critical : float
        The probability of reaching I_c without escaping (then the junction
        switches at I_c: counted in the mean and width as a point mass).
    currents, density : numpy.ndarray
        P(I) (1 / A) at the currents asked (A).
    ramp_rate, temperature : float
        dI/dt (A / s) and T (K).

    See Also
    --------
    switching_distribution : what makes it.

    Examples
    --------
    >>> import pendula
    >>> from pendula.escape import switching_distribution
    >>> j = pendula.Junction(10e-6, 30.0, 1e-12, temperature=4.2)
    >>> d = switching_distribution(j, 1.0)
    >>> bool(0.8e-6 < j.critical_current - d.mean < 2e-6)
    True
    """

    mean: float
    width: float
    at_critical: float
    currents: np.ndarray
    density: np.ndarray
    ramp_rate: float
    temperature: float

    def __repr__(self) -> str:
        return (f"SwitchingDistribution(mean {self.mean:.6g} A, width {self.width:.4g} A at {self.ramp_rate:.3g} A/s "
                f"and {self.temperature:.4g} K; {self.currents.size} currents, {self.at_critical:.3g} at I_c)")


def _panels(log_g, a, b, max_dlog=0.5, min_panels=64):
    """Panel edges on [a, b] with ln g changing by at most max_dlog across each."""
    x = np.linspace(a, b, 1025)
    lg = log_g(x)
    lg = np.where(np.isfinite(lg), lg, np.nanmax(np.where(np.isfinite(lg), lg, -np.inf)))
    var = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(lg)))])
    n = max(min_panels, int(math.ceil(var[-1] / max_dlog)))
    # equal shares of variation and of length: fine where ln g moves fast, never coarse elsewhere
    share = 0.5 * (var / max(var[-1], 1e-300) + (x - a) / (b - a))
    return np.interp(np.linspace(0.0, 1.0, n + 1), share, x)


def _cumulative(log_g, edges):
    """The nodes, weights and Phi = int_0^x g at the Gauss-Legendre nodes of each panel."""
    h = np.diff(edges)
    nodes = edges[:-1, None] + 0.5 * h[:, None] * (_XP + 1.0)
    g = np.exp(log_g(nodes.ravel())).reshape(nodes.shape)
    within = 0.5 * h[:, None] * (g @ _MP.T)                     # from each panel's left edge to its nodes
    totals = 0.5 * h * (g @ _WP)
    start = np.concatenate([[0.0], np.cumsum(totals)[:-1]])
    return nodes, 0.5 * h[:, None] * _WP, g, start[:, None] + within, start, totals


def _fd(log_g, i_top):
    """Mean, variance, mass at i_top and the panels of the distribution of the first escape of a
    process with hazard g(i) = exp(log_g(i)) per unit i, from i = 0 up to i_top (then certain)."""
    # locate where Phi = int g grows from 1e-16 to 80: a coarse pass on a grid dense towards i_top
    x = np.unique(np.concatenate([np.linspace(0.0, i_top, 1001),
                                  i_top * (1.0 - np.logspace(-14, 0, 200))]))
    x = x[x < i_top]
    lg = log_g(x)
    g = np.exp(lg)
    phi = np.concatenate([[0.0], np.cumsum(0.5 * (g[1:] + g[:-1]) * np.diff(x))])
    k_lo = max(int(np.searchsorted(phi, 1e-16)) - 2, 0)
    k_hi = int(np.searchsorted(phi, 80.0)) + 2
    a = x[k_lo]
    b = i_top if k_hi >= x.size else x[k_hi]
    edges = [np.linspace(0.0, a, 9)] if a > 0 else []
    edges.append(_panels(log_g, a, b))
    if b == i_top and i_top == 1.0:
        # refine geometrically towards the critical current, where (1 - i^2)^(1/4) has its branch point,
        # up to 1 - 1e-10 (the nodes stay below 1 in floating point; the escapes in the last 1e-10 I_c are
        # counted in the mass at I_c)
        last = edges[-1]
        tail = 1.0 - (1.0 - last[-2]) * np.logspace(0, -10, 41)
        edges[-1] = np.concatenate([last[:-1], tail[1:]])
    e = np.unique(np.concatenate(edges))
    nodes, w, g, phi, start, totals = _cumulative(log_g, e)
    p = g * np.exp(-phi)
    end_phi = start[-1] + totals[-1]
    mass_top = math.exp(-end_phi) if b >= i_top else 0.0
    norm = float(np.sum(w * p)) + mass_top
    mean = (float(np.sum(w * p * nodes)) + mass_top * i_top) / norm
    var = (float(np.sum(w * p * (nodes - mean) ** 2)) + mass_top * (i_top - mean) ** 2) / norm
    return mean, var, mass_top, e, start


def _density_at(log_g, i, e, start):
    """P(i) = g(i) exp(-Phi(i)) at arbitrary i, Phi from the panel's left edge by 8-point Gauss-Legendre
    (ln g changes by at most 0.5 across a panel: the rule's error is below 1e-17 of the piece)."""
    out = np.zeros(i.shape)
    inside = (i >= 0.0) & (i < e[-1])
    ii = i[inside]
    k = np.clip(np.searchsorted(e, ii, side="right") - 1, 0, e.size - 2)
    left = e[k]
    half = 0.5 * (ii - left)
    pts = left[:, None] + half[:, None] * (_XD + 1.0)
    phi = start[k] + half * (np.exp(log_g(pts.ravel())).reshape(pts.shape) @ _WD)
    out[inside] = np.exp(log_g(ii) - phi)
    return out


def switching_distribution(junction: Junction, ramp_rate: float, currents: ArrayLike | None = None, *,
                           temperature: float | None = None) -> SwitchingDistribution:
    """The switching-current distribution of a linear current ramp at any rate.

    The Fulton-Dunkleberger integral (Phys. Rev. B 9 (1974) 4760) of the
    escape rate Gamma of :func:`escape_rate` (thermal activation or
    tunnelling, whichever is larger):

        P(I) = Gamma(I) / (dI/dt) exp(-∫₀^I Gamma(I') dI' / (dI/dt)),

    the ramp starting at I = 0.  The integral runs on panels of 16-point
    Gauss-Legendre placed where ln Gamma changes by at most 0.5 (from where
    the escape probability is 1e-16 up to where the survival is e^-80), each
    node's cumulative integral by the exact integral of the panel's
    interpolating polynomial; the mean and the width are the quadratures of
    I P(I) and (I - mean)² P(I) on the same nodes.  A ramp so fast that the
    junction may reach I_c unswitched puts the rest of the probability at
    I_c (``at_critical``).  Milliseconds at any rate, 1 mA/s as 1e6 A/s.

    Parameters
    ----------
    junction : Junction
        The junction (C > 0).
    ramp_rate : float
        dI/dt, A / s (> 0).
    currents : array_like, optional
        Where to evaluate the density P(I), A (default: 401 points over
        the mean ± 6 widths).
    temperature : float, optional
        Kelvin, >= 0 (default: the junction's).

    Returns
    -------
    SwitchingDistribution
        The mean, the width (A), the mass at I_c, the density (1 / A).

    Raises
    ------
    TypeError
        A junction that is not a :class:`pendula.Junction`.
    ValueError
        A ramp rate that is not > 0 and finite, a negative temperature, or a
        junction without capacitance, naming the parameter.

    See Also
    --------
    pendula.Junction.switching_currents : direct Langevin ramps (fast
        ramps only).

    Examples
    --------
    >>> import pendula
    >>> from pendula.escape import switching_distribution
    >>> j = pendula.Junction(10e-6, 30.0, 1e-12, temperature=4.2)
    >>> fast, slow = switching_distribution(j, 1.0), switching_distribution(j, 1e-3)
    >>> bool(slow.mean < fast.mean), bool(slow.width < fast.width)
    (True, True)
    """
    j = _junction(junction)
    rate = _checks.real(ramp_rate, "parameter 'ramp_rate'", 0.0, lo_open=True)
    temp = _temperature(j, temperature)
    beta, t_red, hw = _reduced(j, temp)
    # hazard per unit of i = I / I_c: Gamma / (di/dt), in logs (the rates span hundreds of decades)
    shift = math.log(j.plasma_frequency * j.critical_current / rate)

    def log_g(i):
        return _log_rate(i, beta, t_red, hw) + shift

    mean, var, top, e, start = _fd(log_g, 1.0)
    ic = j.critical_current
    if currents is None:
        sd = math.sqrt(max(var, 0.0))
        cur = np.linspace(max(mean - 6 * sd, 0.0), min(mean + 6 * sd, 1.0), 401) * ic
    else:
        cur = _checks.as_float(currents, "parameter 'currents'")
        if np.any(~np.isfinite(cur)):
            raise ValueError("parameter 'currents' must hold finite numbers")
    dens = _density_at(log_g, np.asarray(cur, dtype=float).ravel() / ic, e, start).reshape(np.shape(cur)) / ic
    return SwitchingDistribution(mean * ic, math.sqrt(max(var, 0.0)) * ic, top, np.asarray(cur, dtype=float),
                                 dens, rate, temp)

"""The dc SQUID's mean voltage: the running state's whole turns, or the noisy paths' drift (private module).

In the time unit 1/ω_c (ω_c = 2πI₀R/Φ₀, the characteristic frequency) each
junction of a symmetric dc SQUID obeys β_c φ_k'' + φ_k' + sin φ_k = i/2 ∓ j,
j the circulating current over I₀ (Tesche and Clarke 1977, section 2): a
:class:`~pendula.Network` of two elements with mass β_c, damping 1, the spring
1/(πβ_L) and the offset −2πΦ/Φ₀.  An asymmetric SQUID has junctions of
critical currents I₀(1 ∓ α_I), conductances and capacitances (1 ∓ α_R) times
the mean's (the area's asymmetry), and arms of inductance (1 ∓ η)L/2.  The
fluxoid condition φ₁ − φ₂ = 2πΦ/Φ₀ + (2π/Φ₀)(L₂I₂ − L₁I₁) with I₁ + I₂ = I
gives the arm currents I(1 ± η)/2 ∓ J, J = (φ₁ − φ₂ − 2πΦ/Φ₀)I₀/(πβ_L): the
inductance's asymmetry splits the bias unevenly and leaves the spring as it
is.  The dc voltage is (Φ₀/2π) ω_c ⟨s'⟩, s the
mean of the two phases.

Without noise the mean velocity is measured over whole turns: the first times
s reaches 2πk_a and 2πk_b (k_b − k_a whole turns) are found by cubic Hermite
interpolation of s and s' sampled densely (64 samples a turn or more), and
⟨s'⟩ = 2π(k_b − k_a)/(t_b − t_a), exact for a periodic running state.  Its
error estimate is half the difference of the means over the first and the
second half of the turns (a transient left over, or a motion that is not
periodic, shows there), and never below the integrator's rtol.  Fewer than
two turns in the window (at rest, or creeping towards rest) give the drift
over the window, its error no smaller than the drift itself.  With noise
each path's mean is its drift over the window; the paths' standard error is
the error.
"""

from __future__ import annotations

import math

import numpy as np

from .systems.network import Network

_TWO_PI = 2.0 * math.pi


def arms(current_asymmetry: float = 0.0, resistance_asymmetry: float = 0.0,
         inductance_asymmetry: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The two junctions' factors on the mean: critical currents (1 ∓ α_I), conductances and capacitances
    (1 ∓ α_R), and the share of the bias each arm carries, (1 ± η)/2 (the arm of the smaller inductance
    (1 ∓ η)L/2 carries more)."""
    a_i, a_r, eta = current_asymmetry, resistance_asymmetry, inductance_asymmetry
    return (np.array([1.0 - a_i, 1.0 + a_i]), np.array([1.0 - a_r, 1.0 + a_r]),
            np.array([(1.0 + eta) / 2, (1.0 - eta) / 2]))


def squid_network(beta_l: float, beta_c: float, flux: float, bias: float, rf: float = 0.0,
                  omega: float = 0.0, asym: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> Network:
    """The dc SQUID in the time unit 1/ω_c: mass β_c(1 ∓ α_R), damping (1 ∓ α_R), sine (1 ∓ α_I), the bias
    and an rf current rf cos(ω t) split (1 ± η)/2 between the arms (asym = (α_I, α_R, η))."""
    eps, cond, share = arms(*asym)
    k = 1.0 / (math.pi * beta_l)
    off = np.array([[0.0, -_TWO_PI * flux], [_TWO_PI * flux, 0.0]])
    return Network(2, coupling=[[0.0, k], [k, 0.0]], offset=off, eps=eps, bias=bias * share, damping=cond,
                   mass=beta_c * cond, drive_amplitude=rf * share, drive_frequency=omega)


def _first_hits(t: np.ndarray, s: np.ndarray, sv: np.ndarray, levels: np.ndarray) -> np.ndarray:
    """The first time s reaches each level (ascending levels), by cubic Hermite interpolation of (s, s')
    between the samples that bracket it, its root polished by Newton on the cubic."""
    run_max = np.maximum.accumulate(s)
    out = np.empty(levels.size)
    for n, lev in enumerate(levels):
        j = int(np.searchsorted(run_max, lev, side="left"))   # first sample with s >= lev
        if j == 0:
            out[n] = t[0]
            continue
        t0, h = t[j - 1], t[j] - t[j - 1]
        p0, p1, m0, m1 = s[j - 1], s[j], sv[j - 1] * h, sv[j] * h
        # Hermite basis in u in [0, 1]
        a3 = 2 * p0 - 2 * p1 + m0 + m1
        a2 = -3 * p0 + 3 * p1 - 2 * m0 - m1
        u = (lev - p0) / (p1 - p0) if p1 != p0 else 0.5
        for _ in range(30):
            f = ((a3 * u + a2) * u + m0) * u + p0 - lev
            df = (3 * a3 * u + 2 * a2) * u + m0
            if df <= 0:
                break
            du = f / df
            u = min(1.0, max(0.0, u - du))
            if abs(du) < 1e-15:
                break
        out[n] = t0 + u * h
    return out


def mean_velocity(net: Network, phi0: np.ndarray, v0: np.ndarray, transient: float, window: float,
                  rtol: float) -> tuple[float, float, np.ndarray, np.ndarray]:
    """The running state's mean velocity ⟨s'⟩ over whole turns, its error estimate, and the final state."""
    vmax = max(1.0, float(np.max(np.abs(net.bias))) / float(np.min(net.damping)),
               float(np.max(np.abs(net.drive_frequency))))
    h = min(0.05, _TWO_PI / (64.0 * vmax))
    m = int(math.ceil(window / h))
    t = transient + h * np.arange(m + 1)
    run = net.simulate(t, phi0, v0, rtol=rtol, atol=rtol * 1e-2)
    phi, v = run.phi.values, run.v.values
    s, sv = phi.mean(axis=1), v.mean(axis=1)
    k_a = math.floor(s[0] / _TWO_PI) + 1
    k_b = math.floor(float(np.max(s)) / _TWO_PI)
    turns = k_b - k_a
    if turns < 2:
        # at rest, creeping towards a rest point, or slower than two turns over the window: the drift over
        # the window, its error the larger of the excursions of s about that drift and the drift itself
        # (a creep that slows, as next to the fold at Ic, tends to no voltage at all)
        drift = (s[-1] - s[0]) / (t[-1] - t[0])
        dev = s - s[0] - drift * (t - t[0])
        err = max((float(np.max(dev) - np.min(dev)) + rtol) / (t[-1] - t[0]), abs(drift))
        return float(drift), err, phi[-1], v[-1]
    levels = _TWO_PI * np.arange(k_a, k_b + 1)
    hits = _first_hits(t, s, sv, levels)
    vel = _TWO_PI * turns / (hits[-1] - hits[0])
    half = turns // 2
    v1 = _TWO_PI * half / (hits[half] - hits[0])
    v2 = _TWO_PI * (turns - half) / (hits[-1] - hits[half])
    err = max(0.5 * abs(v1 - v2), rtol * abs(vel))
    return float(vel), float(err), phi[-1], v[-1]


def noisy_mean_velocity(net: Network, phi0: np.ndarray, v0: np.ndarray, transient: float, window: float,
                        temperature: float, dt: float, paths: int, seed: int,
                        threads: int, first_path: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each path's drift ⟨s'⟩ over the window, and the first path's final state (the paths draw the noise
    streams first_path, first_path + 1, ...)."""
    n_tr = int(math.ceil(transient / dt))
    n_w = max(1, int(math.ceil(window / dt)))
    t = dt * np.array([n_tr, n_tr + n_w], dtype=float)
    run = net.simulate(t, phi0, v0, dt=dt, temperature=temperature, paths=paths, seed=seed,
                       first_path=first_path, threads=threads)
    s = run.phi.values.mean(axis=2)            # (path, time)
    drift = (s[:, 1] - s[:, 0]) / (t[1] - t[0])
    return drift, run.phi.values[0, -1], run.v.values[0, -1]


def wrap(phi: np.ndarray) -> np.ndarray:
    """Both phases shifted by the same multiple of 2π, their mean into [−π, π): the loop's state unchanged."""
    s = float(np.mean(phi))
    return phi - _TWO_PI * math.floor((s + math.pi) / _TWO_PI)

"""The overdamped Josephson junction: the RSJ model (C = 0), a first-order equation.

Without capacitance the junction's phase obeys, in units of the
characteristic frequency omega_c = 2π I_c R / Phi_0,

    phi' = i + a cos(Omega t) - sin(phi),

i = I / I_c, a = I_rf / I_c, Omega = 2π f / omega_c, and the dc voltage is
V = I_c R <phi'> (Stewart 1968, McCumber 1968; Likharev, Dynamics of
Josephson Junctions and Circuits, 1986, chapter 4).  Without rf the I-V
curve is exact, V = R sqrt(I² - I_c²) above I_c; with rf the phase locks on
Shapiro steps V = n f Phi_0, only integer ones (the stroboscopic map is an
increasing circle map whose rotation number has plateaus at the integers
only: Renne and Polder, Rev. Phys. Appl. 9 (1974) 25).

The route: the kernel (kernel/models/pendula_rsj_map.c) integrates the
first-order equation with GSL's rk8pd over one drive period, from every
initial phase it needs: F(x) = phi(T; phi(0) = x).  The step n holds exactly
when min (F(x) - x) <= 2π n <= max (F(x) - x) (the extrema by Brent); off
the steps the rotation number is (F^K(0)) / (2π K), within 1 / K of the
truth for a circle map.  Not the pendulum with a huge damping: that is
stiff.  This module is the engine of :class:`pendula.Junction` at C = 0
(its ``iv_curve``, ``dc_voltage`` and ``shapiro_steps``).
"""

from __future__ import annotations

import math

import numpy as np

from . import _checks, _interrupt

__all__ = ["dc_velocity", "mean_velocity", "step_edges"]

#: the kernel's integration tolerance (relative and absolute) of the phase over one drive period
RTOL = 1e-12


def dc_velocity(bias: np.ndarray, critical_current: float) -> np.ndarray:
    """<phi'> of the undriven RSJ junction at the bias currents (A): sign(I)
    sqrt(I² - I_c²) / I_c above I_c, 0 below (the phase at rest in its well).
    Computed as sqrt((|I| - I_c)(|I| + I_c)) in amperes: |I| - I_c is exact
    next to I_c (Sterbenz), so there is no cancellation there."""
    b = np.asarray(bias, dtype=float)
    a = np.abs(b)
    above = a > critical_current
    v = np.sqrt(np.where(above, (a - critical_current) * (a + critical_current), 0.0)) / critical_current
    return np.copysign(v, b) * above


def mean_velocity(i: np.ndarray, a: float, omega: float, periods: int = 2000, threads: int = 0):
    """<phi'> of the driven RSJ junction at reduced biases i (kernel): the mean
    velocity, its error bound (0 on a step: exact), the step n (NaN off the
    steps) and the status (0 decided, 6 locked, 1 the integration failed)."""
    from . import _kernel
    i = np.ascontiguousarray(np.asarray(i, dtype=float).ravel())
    cancel = _interrupt.cancel_flag()
    vm, err, step, st = _interrupt.call(_kernel.rsj_mean_velocity_v, i, float(a), float(omega), RTOL, RTOL,
                                        int(periods), _checks.threads(threads), cancel, cancel=cancel)
    if cancel[0]:
        raise KeyboardInterrupt
    if np.any(st == 1):
        raise ArithmeticError(f"the RSJ integration failed at {int(np.sum(st == 1))} biases (GSL rk8pd)")
    return vm, err, step, st.astype(np.int32)


def _gap_range(i, a, omega, threads):
    from . import _kernel
    gmin, gmax, st = _kernel.rsj_gap_ranges_v(np.ascontiguousarray(i, dtype=float), float(a), float(omega),
                                              RTOL, RTOL, _checks.threads(threads))
    if np.any(st != 0):
        raise ArithmeticError("the RSJ integration failed while bracketing a step edge (GSL rk8pd)")
    return gmin, gmax


def step_edges(orders, a: float, omega: float, threads: int = 0, xtol: float = 1e-11):
    """The reduced bias edges (lower, upper) of the Shapiro steps n in ``orders``
    of the RSJ junction under the drive a cos(Omega t): the lower edge is
    where the largest gap max (F(x) - x) reaches 2π n, the upper where the
    smallest does (both increase with the bias), by bisection to ``xtol``
    from the bracket n Omega ± (a + 1.1) (|phi' - i| <= a + 1 always).  NaN
    edges for a step of zero width (a zero of the Bessel law)."""
    n = np.asarray(orders, dtype=float)
    target = 2.0 * math.pi * n
    edges = []
    for which in (1, 0):        # the lower edge from gmax, the upper from gmin
        lo = n * omega - (a + 1.1)
        hi = n * omega + (a + 1.1)
        while True:
            mid = 0.5 * (lo + hi)
            g = _gap_range(mid, a, omega, threads)[which]
            up = g >= target
            hi, lo = np.where(up, mid, hi), np.where(up, lo, mid)
            if np.all(hi - lo <= xtol * np.maximum(1.0, np.abs(hi))):
                break
        edges.append(0.5 * (lo + hi))
    lower, upper = edges
    # an empty step: gmax reaches 2 pi n after gmin passes it
    return np.where(upper >= lower, lower, np.nan), np.where(upper >= lower, upper, np.nan)

"""Switching currents of a junction under a current ramp: the kernel's Langevin ramps
(kernel/integrators/pendula_langevin.f90) and their record, for :meth:`pendula.Junction.switching_currents`."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import _checks, _interrupt

#: the largest number of Langevin steps one call of switching_currents may take (all ramps)
_MAX_SWITCHING_STEPS = 2.0e10


@dataclass(frozen=True)
class SwitchingCurrents:
    """Switching currents of a junction under a current ramp.

    Attributes
    ----------
    samples : numpy.ndarray
        The switching current of each ramp, in amperes (NaN for a ramp that
        had not switched at 1.2 times the critical current: none in practice).
    counts, edges : numpy.ndarray
        Their histogram (numpy.histogram of the finite samples; edges in A).
    ramp_rate : float
        dI/dt of the ramps, A / s.
    temperature : float
        The junction's temperature, K.

    See Also
    --------
    Junction.switching_currents : what makes them.
    Junction.switching_density : their theory (Fulton and Dunkleberger).

    Examples
    --------
    >>> import pendula
    >>> j = pendula.Junction(1e-7, 100.0, 1e-12, temperature=0.05)
    >>> s = j.switching_currents(ramp_rate=1e-3 * 1e-7 * j.plasma_frequency, n=10, seed=1)
    >>> int(s.counts.sum()), s.samples.shape
    (10, (10,))
    """

    samples: np.ndarray
    counts: np.ndarray
    edges: np.ndarray
    ramp_rate: float
    temperature: float

    def __repr__(self) -> str:
        n = np.size(self.samples)
        ok = int(np.sum(np.isfinite(self.samples)))
        stats = f", mean {self.mean:.6g} A, width {self.width:.3g} A" if ok >= 2 else ""
        return (f"SwitchingCurrents({n} ramps ({ok} switched){stats}, {np.size(self.counts)} bins, "
                f"ramp {self.ramp_rate:.3g} A/s, T = {self.temperature:g} K)")

    @property
    def mean(self) -> float:
        """The mean switching current of the finite samples, A."""
        return float(np.nanmean(self.samples))

    @property
    def width(self) -> float:
        """The standard deviation (ddof = 1) of the finite samples, A."""
        return float(np.nanstd(self.samples, ddof=1))


def switching_samples(junction, ramp_rate, n, seed, dt, bins, threads) -> SwitchingCurrents:
    """The switching currents of :meth:`pendula.Junction.switching_currents` (its arguments checked here)."""
    from . import _kernel
    rate = _checks.real(ramp_rate, "parameter 'ramp_rate'", 0.0, lo_open=True)
    n = _checks.count(n, "parameter 'n'", 1, 10 ** 6)
    seed = _checks.count(seed, "parameter 'seed'", 0, 2 ** 53)
    threads = _checks.threads(threads)
    if not junction.temperature > 0:
        raise ValueError("parameter 'temperature' must be > 0 for switching-current samples (without noise "
                         "a ramp switches at the critical current exactly)")
    h = 2.0 * math.pi / 100.0 if dt is None else _checks.real(dt, "parameter 'dt'", 0.0, lo_open=True)
    r = rate / (junction.critical_current * junction.plasma_frequency)
    i_max = 1.2
    if n * i_max / (r * h) > _MAX_SWITCHING_STEPS:
        raise ValueError(f"parameter 'ramp_rate': {n} ramps at {r:.3g} I_c per plasma period take "
                         f"{n * i_max / (r * h):.2g} steps, more than the limit {_MAX_SWITCHING_STEPS:.0e}: "
                         "a faster ramp, fewer ramps or a larger dt")
    cancel = _interrupt.cancel_flag()
    isw, status = _interrupt.call(_kernel.junction_switching_v, junction.damping, junction.noise, r, seed, h, i_max, n,
                                  threads, cancel, cancel=cancel)
    if cancel[0]:
        raise KeyboardInterrupt
    samples = np.asarray(isw) * junction.critical_current
    counts, edges = np.histogram(samples[np.isfinite(samples)], bins=bins)
    return SwitchingCurrents(samples, counts, edges, rate, junction.temperature)

"""A Josephson junction in laboratory units: the RCSJ model on the pendulum.

The resistively and capacitively shunted junction (Stewart, McCumber; Suzuki
and Suzuki section 8.3) is the damped, torqued pendulum: with the phase
difference theta, the time in units of the inverse plasma frequency and the
currents in units of the critical current,

    theta'' + beta theta' + sin(theta) = I / I_c + (I_rf / I_c) cos(Omega t) + sqrt(2 beta T) xi(t),

beta = 1 / sqrt(beta_c) (beta_c the Stewart-McCumber parameter), Omega the rf
frequency over the plasma frequency, T the temperature in units of the
Josephson energy.  The mean angular velocity is the dc voltage:
V = (hbar / 2e) omega_p <theta'>.  :class:`Junction` does the conversions with
the CODATA 2018 values of h, e and k_B (exact since the 2019 SI) and runs the
pendulum's kernel: I-V curves with Shapiro steps (:func:`pendula.iv_curve`)
and switching-current distributions (the Langevin integrator of
kernel/integrators/pendula_langevin.f90).
"""

from __future__ import annotations

import dataclasses
import math
import os
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike

from . import _checks
from .dynamics.tongues import ShapiroTongue, shapiro_tongue
from .junction_lab import rf_pair, with_voltage
from .junction_switching import SwitchingCurrents
from .scene import Scene

if TYPE_CHECKING:   # xarray and distributed are optional: named in annotations only
    import distributed
    import xarray

__all__ = ["Junction", "SwitchingCurrents", "PLANCK", "ELEMENTARY_CHARGE", "BOLTZMANN", "FLUX_QUANTUM"]

#: the Planck constant h, J s (exact: CODATA 2018, the 2019 SI)
PLANCK = 6.62607015e-34
#: the elementary charge e, C (exact)
ELEMENTARY_CHARGE = 1.602176634e-19
#: the Boltzmann constant k_B, J / K (exact)
BOLTZMANN = 1.380649e-23
#: the magnetic flux quantum h / 2e, Wb
FLUX_QUANTUM = PLANCK / (2.0 * ELEMENTARY_CHARGE)

class Junction:
    """A current-biased Josephson junction (RCSJ model) in SI units.

    Parameters
    ----------
    critical_current : float
        I_c, amperes (> 0).
    resistance : float
        The shunt resistance R, ohms (> 0).
    capacitance : float
        The capacitance C, farads (>= 0).  C = 0 is the overdamped junction
        (the RSJ model, a first-order equation, ``pendula.overdamped``):
        its exact dc I-V, its Shapiro steps and their edges
        (:meth:`iv_curve`, :meth:`dc_voltage`, :meth:`shapiro_steps`);
        what needs a plasma frequency (the pendulum's scene, escape,
        switching) refuses it, naming the field.
    temperature : float
        T, kelvin (>= 0): thermal noise of the resistor (Johnson-Nyquist),
        the pendulum's Langevin force.

    Raises
    ------
    TypeError
        A parameter that is not a real number.
    ValueError
        A parameter out of range, naming it.

    See Also
    --------
    iv_curve : the pendulum's I-V curve in reduced units.
    SwitchingCurrents : the samples of :meth:`switching_currents`.

    Examples
    --------
    >>> import pendula
    >>> j = pendula.Junction(critical_current=1e-6, resistance=10.0, capacitance=1e-12)
    >>> round(j.stewart_mccumber, 3)            # 2 pi I_c R^2 C / Phi_0
    0.304
    >>> round(j.plasma_frequency / 2 / 3.141592653589793 / 1e9, 3)   # GHz
    8.773
    """

    def __init__(self, critical_current: float, resistance: float, capacitance: float,
                 temperature: float = 0.0) -> None:
        self.critical_current = _checks.real(critical_current, "parameter 'critical_current'", 0.0, lo_open=True)
        self.resistance = _checks.real(resistance, "parameter 'resistance'", 0.0, lo_open=True)
        self.capacitance = _checks.real(capacitance, "parameter 'capacitance'", 0.0)
        self.temperature = _checks.real(temperature, "parameter 'temperature'", 0.0)

    def __repr__(self) -> str:
        return (f"Junction(critical_current={self.critical_current!r}, resistance={self.resistance!r}, "
                f"capacitance={self.capacitance!r}, temperature={self.temperature!r})")

    # ------------------------------------------------------------- derived quantities
    @property
    def josephson_energy(self) -> float:
        """E_J = Phi_0 I_c / 2 pi, joules (the pendulum's energy unit)."""
        return FLUX_QUANTUM * self.critical_current / (2.0 * math.pi)

    @property
    def plasma_frequency(self) -> float:
        """omega_p = sqrt(2 pi I_c / (Phi_0 C)), rad / s (the pendulum's time unit is 1 / omega_p)."""
        if not self.capacitance > 0:
            raise ValueError("field 'capacitance' is 0: the overdamped (RSJ) junction has no plasma frequency "
                             "and is not the pendulum; at C = 0 pendula gives iv_curve (the exact dc I-V and "
                             "Shapiro steps), dc_voltage and shapiro_steps (give C > 0 for the rest)")
        return math.sqrt(2.0 * math.pi * self.critical_current / (FLUX_QUANTUM * self.capacitance))

    @property
    def stewart_mccumber(self) -> float:
        """beta_c = 2 pi I_c R^2 C / Phi_0 (hysteretic above about 1)."""
        return 2.0 * math.pi * self.critical_current * self.resistance ** 2 * self.capacitance / FLUX_QUANTUM

    @property
    def damping(self) -> float:
        """The pendulum's damping beta = 1 / (omega_p R C) = 1 / sqrt(beta_c)."""
        return 1.0 / (self.plasma_frequency * self.resistance * self.capacitance)

    @property
    def noise(self) -> float:
        """The pendulum's temperature k_B T / E_J (the scene field ``noise``)."""
        return BOLTZMANN * self.temperature / self.josephson_energy

    def reduced_frequency(self, frequency: float) -> float:
        """An rf frequency f (Hz) as the pendulum's drive frequency 2 pi f / omega_p.

        Parameters
        ----------
        frequency : float
            Hz, >= 0.

        Returns
        -------
        float

        Examples
        --------
        >>> import pendula
        >>> j = pendula.Junction(1e-6, 10.0, 1e-12)
        >>> round(j.reduced_frequency(j.plasma_frequency / (2 * 3.141592653589793)), 12)
        1.0
        """
        f = _checks.real(frequency, "parameter 'frequency'", 0.0)
        return 2.0 * math.pi * f / self.plasma_frequency

    def voltage(self, mean_velocity: ArrayLike) -> np.ndarray:
        """The dc voltage V = (Phi_0 / 2 pi) omega_p <theta'> of a mean angular velocity (reduced).

        Parameters
        ----------
        mean_velocity : array_like
            <theta'> in units of omega_p.

        Returns
        -------
        numpy.ndarray
            Volts.

        Examples
        --------
        >>> import pendula
        >>> j = pendula.Junction(1e-6, 10.0, 1e-12)
        >>> v = float(j.voltage(j.reduced_frequency(10e9)))       # V = f Phi_0 = f h / 2e
        >>> round(v / (10e9 * pendula.junction.FLUX_QUANTUM), 12)
        1.0
        """
        v = _checks.as_float(mean_velocity, "mean_velocity")
        return v * (FLUX_QUANTUM / (2.0 * math.pi) * self.plasma_frequency)

    # ------------------------------------------------------------- runs
    def _rf(self, rf_current, rf_frequency) -> tuple[float, float]:
        a, f = rf_pair(rf_current, rf_frequency)
        return a / self.critical_current, self.reduced_frequency(f)

    def scene(self, bias: float, rf_current: float = 0.0, rf_frequency: float = 0.0, *, seed: int = 0) -> Scene:
        """The pendulum scene of the junction at a dc bias (and an rf drive).

        Parameters
        ----------
        bias : float
            The dc bias current, A.
        rf_current, rf_frequency : float
            The rf drive I_rf cos(2 pi f t): amplitude (A) and frequency (Hz),
            both or neither.
        seed : int
            The seed of the thermal noise (at a temperature > 0).

        Returns
        -------
        Scene
            eps = 1, damping = 1 / sqrt(beta_c), torque = I / I_c,
            drive_amplitude = I_rf / I_c, drive_frequency = 2 pi f / omega_p,
            noise = k_B T / E_J.

        Raises
        ------
        ValueError
            An rf frequency without a current (or a current without a
            frequency), naming the parameter.

        Examples
        --------
        >>> import pendula
        >>> j = pendula.Junction(1e-6, 10.0, 1e-12)
        >>> s = j.scene(0.5e-6)
        >>> s.torque, round(s.damping, 4)
        (0.5, 1.8141)
        """
        tau = _checks.real(bias, "parameter 'bias'") / self.critical_current
        amp, omega = self._rf(rf_current, rf_frequency)
        return Scene(eps=1.0, damping=self.damping, torque=tau, drive_amplitude=amp, drive_frequency=omega,
                     noise=self.noise, seed=_checks.count(seed, "parameter 'seed'", 0, 2 ** 53))

    def shapiro_tongue(self, n: int, rf_current: float, rf_frequency: float, stop: float) -> ShapiroTongue:
        """The edges of Shapiro step n from ``rf_current`` to ``stop`` (A), as :func:`pendula.shapiro_tongue`.

        The noise-free edges (thermal noise blurs them; the edges are the locked orbit's saddle-nodes),
        in reduced units on the curves and in amperes by ``ShapiroTongue.lab_edges()``.

        Parameters
        ----------
        n : int
            The step (voltage n h f / 2e), n >= 1.
        rf_current, rf_frequency : float
            The rf drive where the edges start: amplitude (A, > 0) and frequency (Hz, > 0).
        stop : float
            The rf amplitude (A, > 0) to follow the edges to.

        Returns
        -------
        ShapiroTongue
            With ``critical_current`` set, so that ``lab_edges()`` gives amperes.

        Raises
        ------
        ValueError
            A junction without capacitance (use :meth:`shapiro_steps`), or an argument out of range.

        Examples
        --------
        >>> import pendula
        >>> j = pendula.Junction(1e-6, 10.0, 1e-11)
        >>> t = j.shapiro_tongue(1, 1e-6, 20e9, 1.2e-6)
        >>> e = t.lab_edges()
        >>> bool(e["lower_bias"][-1] < e["upper_bias"][-1]), round(float(e["upper_rf"][-1]) * 1e6, 9)
        (True, 1.2)
        """
        if self.capacitance == 0:
            raise ValueError("field 'capacitance' is 0: the overdamped junction's steps come from shapiro_steps")
        amp, omega = self._rf(rf_current, rf_frequency)
        stop_r = _checks.real(stop, "parameter 'stop'") / self.critical_current
        sc = Scene(eps=1.0, damping=self.damping, drive_amplitude=amp, drive_frequency=omega)
        return dataclasses.replace(shapiro_tongue(sc, n, stop_r), critical_current=self.critical_current)

    def iv_curve(self, currents: ArrayLike, rf_current: float = 0.0, rf_frequency: float = 0.0,
                 direction: Literal["up", "down", "both"] = "up", *, transient: float | None = None,
                 t_max: float | None = None, seed: int = 0) -> xarray.Dataset:
        """The junction's I-V curve: the dc voltage at each bias current.

        The adiabatic ramp of :func:`pendula.iv_curve` in laboratory units.
        With an rf drive the curve has Shapiro steps at V = n h f / 2e: a
        phase-locked bias reports its step voltage exactly (status 'locked').

        At C = 0 (the overdamped RSJ junction) the curve is the first-order
        equation's (``pendula.overdamped``): exact without rf (V = R
        sqrt(I² - I_c²)); with rf, a bias on a step reports n f Phi_0
        exactly and off the steps the mean voltage over ``t_max`` (default
        2000 rf periods) within the bound ``voltage_err``; no hysteresis
        (both branches are the same curve) and no transient (``transient``
        is not used: the result does not depend on the initial phase).

        Parameters
        ----------
        currents : array_like
            Bias currents, A, ascending (non-decreasing): the up branch runs
            them in this order and the down branch in reverse.  Currents in
            another order are refused (a ValueError naming ``currents``)
            rather than reordered: ramped in the order given they would be
            another branch than the one named.
        rf_current, rf_frequency : float
            The rf drive (A, Hz), both or neither.
        direction : {'up', 'down', 'both'}
            The branches of the ramp (hysteresis when beta_c > 1).
        transient, t_max : float, optional
            Seconds skipped and averaged at each current (default 200 and
            400 inverse plasma frequencies; with an rf drive both are rounded
            up to whole rf periods).
        seed : int
            The seed of the thermal noise (at a temperature > 0).

        Returns
        -------
        xarray.Dataset
            Coordinates ``current`` (A) and ``direction``; ``voltage`` (V) and
            ``voltage_err`` (V), ``step`` (the Shapiro step n where locked),
            ``status``, and the reduced ``mean_velocity``, ``torque`` beside
            them; CF ``units`` attributes.

        Raises
        ------
        ValueError
            Bad currents (or currents not in ascending order), an rf
            frequency without a current, bad times.
        NotImplementedError
            At C = 0 with a temperature > 0 (thermal noise of the overdamped
            junction).

        Examples
        --------
        >>> import pendula
        >>> j = pendula.Junction(critical_current=1e-6, resistance=18.0, capacitance=1e-12)
        >>> f = j.plasma_frequency / (2 * 3.141592653589793)       # rf at the plasma frequency
        >>> r = j.iv_curve([0.3e-6, 1.1e-6], rf_current=1e-6, rf_frequency=f)
        >>> r.step.values.tolist(), (r.voltage / (f * pendula.junction.FLUX_QUANTUM)).values.tolist()
        ([[0.0, 1.0]], [[0.0, 1.0]])
        """
        from .ivcurve import iv_curve
        currents = _checks.grid_values(currents, "parameter 'currents'")
        if not isinstance(direction, str) or direction not in ("up", "down", "both"):
            raise ValueError(f"parameter 'direction' must be 'up', 'down' or 'both'; got {direction!r}")
        if np.any(np.diff(currents) < 0):
            raise ValueError("parameter 'currents' must be in ascending order: direction='up' ramps them as "
                             "given and 'down' in reverse, so currents in another order would be a branch "
                             f"mislabelled {direction!r}; give np.sort(currents)")
        if self.capacitance == 0:
            from .junction_lab import rsj_iv_curve
            return rsj_iv_curve(self, currents, rf_current, rf_frequency, direction, t_max)
        wp = self.plasma_frequency
        tr = 200.0 if transient is None else _checks.real(transient, "parameter 'transient'", 0.0) * wp
        tm = 400.0 if t_max is None else _checks.real(t_max, "parameter 't_max'", 0.0, lo_open=True) * wp
        sc = self.scene(0.0, rf_current, rf_frequency, seed=seed)
        r = iv_curve(sc, currents / self.critical_current, direction, transient=tr, t_max=tm, start="ramp")
        volt = FLUX_QUANTUM / (2.0 * math.pi) * wp
        r = r.rename({"torque": "current"})
        r = r.assign_coords(current=("current", currents, {"long_name": "bias current", "units": "A"}),
                            torque=("current", currents / self.critical_current,
                                    {"long_name": "bias current / critical current", "units": "1"}))
        with_voltage(r, volt)
        r["mean_velocity"].attrs["long_name"] = "mean phase velocity <theta'> / omega_p (reduced voltage)"
        r.attrs.update({"critical_current": self.critical_current, "resistance": self.resistance,
                        "capacitance": self.capacitance, "temperature": self.temperature,
                        "rf_current": float(rf_current), "rf_frequency": float(rf_frequency),
                        "plasma_frequency": wp, "stewart_mccumber": self.stewart_mccumber,
                        "constants": "CODATA 2018 (exact): h = 6.62607015e-34 J s, e = 1.602176634e-19 C, "
                                     "k_B = 1.380649e-23 J/K"})
        return r

    def steps(self, currents: ArrayLike, rf_current: float, rf_frequency: float,
              direction: Literal["up", "down"] = "up", *, transient: float | None = None,
              t_max: float | None = None) -> xarray.Dataset:
        """Each Shapiro step of an I-V branch: its voltage, edges and width, in volts and amperes.

        Runs :meth:`iv_curve` on the branch and reads its locked biases
        (``pendula.junction_lab``): a run of neighbouring biases locked on
        the same step p / q is a plateau at V = (p / q) f h / 2e; its
        ``lower`` and ``upper`` are its outermost locked biases, each edge
        known to the grid's resolution (the true edge lies within
        ``lower_gap`` below and ``upper_gap`` above them).  A step met twice
        (hysteresis, or chaos between) gives two plateaus.

        Parameters
        ----------
        currents : array_like
            Bias currents, A, ascending (as :meth:`iv_curve`).
        rf_current, rf_frequency : float
            The rf drive (A, Hz), both > 0.
        direction : {'up', 'down'}
            The branch.
        transient, t_max : float, optional
            As :meth:`iv_curve` (seconds).

        Returns
        -------
        xarray.Dataset
            Over ``plateau``: ``order``, ``voltage`` (V), ``lower``,
            ``upper``, ``width``, ``lower_gap``, ``upper_gap`` (A) and
            ``points``; CF units.

        Raises
        ------
        ValueError
            Bad currents, an rf current or frequency that is not > 0, or an
            unknown `direction`, naming the parameter.

        See Also
        --------
        shapiro_steps : the overdamped junction's edges, bisected to 1e-11 I_c.

        Examples
        --------
        >>> import numpy as np, pendula
        >>> j = pendula.Junction(1e-6, 18.0, 1e-12)
        >>> f = j.plasma_frequency / (2 * 3.141592653589793)
        >>> s = j.steps(np.linspace(0.0, 1.6e-6, 17), rf_current=1e-6, rf_frequency=f)
        >>> s.order.values.tolist()[:2]
        [0.0, 1.0]
        """
        from .junction_lab import plateaus
        _checks.real(rf_current, "parameter 'rf_current'", 0.0, lo_open=True)
        f = _checks.real(rf_frequency, "parameter 'rf_frequency'", 0.0, lo_open=True)
        if not isinstance(direction, str) or direction not in ("up", "down"):
            raise ValueError(f"parameter 'direction' must be 'up' or 'down'; got {direction!r}")
        r = self.iv_curve(currents, rf_current, rf_frequency, direction, transient=transient, t_max=t_max)
        b = r.sel(direction=direction)
        attrs = {k: r.attrs[k] for k in ("critical_current", "resistance", "capacitance", "temperature",
                                         "rf_current", "rf_frequency") if k in r.attrs}
        attrs["direction"] = direction
        return plateaus(r.current.values, b.step.values, b.status.values, f * FLUX_QUANTUM, attrs)

    def sweep(self, over: dict[str, ArrayLike], *, bias: float = 0.0, rf_current: float = 0.0,
              rf_frequency: float = 0.0, impedance: float | None = None, transient: float | None = None,
              t_max: float | None = None, threads: int = 0, seed: int = 0,
              out: str | os.PathLike[str] | None = None, client: distributed.Client | None = None
              ) -> xarray.Dataset:
        """The dc voltage over a grid of laboratory quantities, on threads (:func:`pendula.sweep`).

        Axes: ``bias`` (A), ``rf_current`` (A) or ``rf_power`` (dBm at
        ``impedance``, :func:`pendula.rf_current`), ``rf_frequency`` (Hz),
        ``temperature`` (K); one to three of the first four, and temperature
        beside them.  Each grid point starts from rest (theta = 0, v = 0): a
        step map, not a ramp (hysteresis: :meth:`iv_curve`).  Locked points
        report their step exactly, as in :meth:`iv_curve`.

        Parameters
        ----------
        over : dict
            {axis: values}.
        bias, rf_current, rf_frequency : float
            The values of the axes not swept (A, A, Hz).
        impedance : float, optional
            Ohm: the impedance a swept ``rf_power`` is delivered into.
        transient, t_max : float, optional
            Seconds skipped and averaged (default 200 and 400 inverse plasma
            frequencies).
        threads : int
            OpenMP threads (0: all cores).
        seed : int
            The noise's seed (at a temperature > 0).
        out, client : optional
            A Zarr store folder and a Dask client, as :func:`pendula.sweep`
            (not with a temperature axis).

        Returns
        -------
        xarray.Dataset
            ``voltage`` and ``voltage_err`` (V), ``step``, ``status`` and the
            reduced ``mean_velocity`` over the axes (coordinates in their
            units, the pendulum's reduced fields beside them); CF units.

        Raises
        ------
        ValueError
            An unknown axis, bad values, ``rf_power`` without ``impedance``,
            a negative temperature, or a drive without a frequency, naming the
            parameter.

        Examples
        --------
        >>> import numpy as np, pendula
        >>> j = pendula.Junction(1e-6, 18.0, 1e-12)
        >>> f = j.plasma_frequency / (2 * 3.141592653589793)
        >>> m = j.sweep({"bias": [0.3e-6, 1.1e-6], "rf_current": [1e-6]}, rf_frequency=f)
        >>> m.step.values.ravel().tolist(), m.voltage.attrs["units"]
        ([0.0, 1.0], 'V')
        """
        from .junction_lab import junction_sweep
        wp = self.plasma_frequency
        tr = 200.0 if transient is None else _checks.real(transient, "parameter 'transient'", 0.0) * wp
        tm = 400.0 if t_max is None else _checks.real(t_max, "parameter 't_max'", 0.0, lo_open=True) * wp
        return junction_sweep(self, over, bias, rf_current, rf_frequency, impedance, tr, tm, threads,
                              _checks.count(seed, "parameter 'seed'", 0, 2 ** 53), BOLTZMANN / self.josephson_energy,
                              out, client)

    def escape_rate(self, bias: ArrayLike, regime: Literal["moderate", "underdamped"] = "moderate") -> np.ndarray:
        """The thermal escape rate out of the tilted well, 1 / s.

        Gamma = a (omega_a / 2 pi) exp(-dU / k_B T), with omega_a =
        omega_p (1 - i^2)^(1/4) the attempt frequency (the barrier's curvature
        frequency is the same for the washboard), dU = 2 E_J (sqrt(1 - i^2) -
        i arccos(i)), i = I / I_c, and the prefactor a of the damping regime:

        * ``'moderate'``: Kramers' moderate-to-strong damping factor
          a = sqrt(1 + alpha^2) - alpha, alpha = 1 / (2 omega_a R C)
          (Kramers 1940; Hanggi, Talkner and Borkovec, Rev. Mod. Phys. 62
          (1990) section IV).  Valid outside the energy-diffusion regime
          (beta S_b / T >> 1, S_b = 36 dU / 5 omega_a the action of the barrier
          orbit).
        * ``'underdamped'``: the Buttiker-Harris-Landauer interpolation
          a = 4 / (sqrt(1 + Q k_B T / (1.8 dU)) + 1)^2, Q = omega_a R C
          (Buttiker, Harris and Landauer, Phys. Rev. B 28 (1983) 1268, as
          used for switching junctions by Martinis, Devoret and Clarke, Phys.
          Rev. B 35 (1987) 4682): for Q >> 1, across the turnover to energy
          diffusion; an interpolation, good to about 20 %.

        Both need dU >> k_B T.  The rate is that of the untilted well below
        zero bias and inf at i >= 1.

        Parameters
        ----------
        bias : array_like
            Bias currents, A.
        regime : {'moderate', 'underdamped'}
            The prefactor (above).

        Returns
        -------
        numpy.ndarray
            Escape rates, 1 / s.

        Raises
        ------
        ValueError
            At zero temperature (no thermal escape), or an unknown `regime`.

        Examples
        --------
        >>> import pendula
        >>> j = pendula.Junction(1e-7, 100.0, 1e-12, temperature=0.05)
        >>> bool(j.escape_rate(0.9e-7) > j.escape_rate(0.8e-7))
        True
        """
        if not self.temperature > 0:
            raise ValueError("parameter 'temperature' must be > 0 for a thermal escape rate")
        if regime not in ("moderate", "underdamped"):
            raise ValueError(f"parameter 'regime' must be 'moderate' or 'underdamped', got {regime!r}")
        i = np.clip(_checks.as_float(bias, "bias") / self.critical_current, 0.0, 1.0)
        from .junction_lab import escape_rate_reduced
        return self.plasma_frequency * escape_rate_reduced(i, self.damping, self.noise, regime)

    def switching_density(self, currents: ArrayLike, ramp_rate: float,
                          regime: Literal["moderate", "underdamped"] = "moderate") -> np.ndarray:
        """The switching-current density of a ramp (Fulton and Dunkleberger), per ampere.

        P(I) = (Gamma(I) / (dI/dt)) exp(-int_0^I Gamma(I') dI' / (dI/dt)),
        Gamma the escape rate of `regime` (:meth:`escape_rate`) (Fulton and Dunkleberger,
        Phys. Rev. B 9 (1974) 4760); the integral by the trapezoidal rule on
        20001 points from 0 to the largest current.

        Parameters
        ----------
        currents : array_like
            Currents, A (at most 1.2 I_c).
        ramp_rate : float
            dI/dt, A / s (> 0).
        regime : {'moderate', 'underdamped'}
            The escape rate's prefactor (:meth:`escape_rate`).

        Returns
        -------
        numpy.ndarray
            The density, 1 / A.

        Raises
        ------
        ValueError
            At zero temperature, or a ramp rate <= 0.

        Examples
        --------
        >>> import numpy as np, pendula
        >>> j = pendula.Junction(1e-7, 100.0, 1e-12, temperature=0.05)
        >>> I = np.linspace(0.5e-7, 1e-7, 2001)
        >>> p = j.switching_density(I, ramp_rate=1e-4 * 1e-7 * j.plasma_frequency)
        >>> round(float(np.sum(p) * (I[1] - I[0])), 3)        # a probability density
        1.0
        """
        rate = _checks.real(ramp_rate, "parameter 'ramp_rate'", 0.0, lo_open=True)
        cur = _checks.as_float(currents, "currents")
        top = float(np.max(cur)) if cur.size else 0.0
        grid = np.linspace(0.0, max(top, 1e-300), 20001)
        g = self.escape_rate(grid, regime)
        g_in = np.concatenate([[0.0], np.cumsum(0.5 * (g[1:] + g[:-1]) * np.diff(grid))]) / rate
        inside = np.interp(cur, grid, g_in)
        with np.errstate(over="ignore", invalid="ignore"):
            p = self.escape_rate(cur, regime) / rate * np.exp(-inside)
        # beyond the critical current every ramp has switched: no density left
        return np.where((cur >= 0) & np.isfinite(inside), p, 0.0)

    def switching_currents(self, ramp_rate: float, n: int, seed: int = 0, *, dt: float | None = None,
                           bins: int | str = "auto", threads: int = 0) -> SwitchingCurrents:
        """Switching currents of n current ramps from zero with thermal noise.

        Each ramp starts in thermal equilibrium at zero bias and raises the
        current as I = (dI/dt) t; it has switched when the phase has passed
        the second barrier (a running state, not a retrapped slip); its
        switching current is the bias when it last crossed the first
        barrier's top.  Ramp k draws its noise from the stream (seed, k):
        the samples are the same bit for bit on any thread count.

        Parameters
        ----------
        ramp_rate : float
            dI/dt, A / s (> 0).  The kernel steps the pendulum about 100 times
            per plasma period: a ramp of r = (dI/dt) / (I_c omega_p) costs
            about 1 / (r dt) steps, so laboratory rates (r ~ 1e-9) are out
            of reach; r >= 1e-5 runs in seconds (the distribution's theory
            scales with the rate: see :meth:`switching_density`).
        n : int
            Number of ramps (1 .. 10^6).
        seed : int
            The seed of the noise (0 .. 2^53).
        dt : float, optional
            The Langevin step in units of 1 / omega_p (default 2 pi / 100).
        bins : int or str
            The histogram's bins (numpy.histogram's ``bins``).
        threads : int
            OpenMP threads (0: all cores).

        Returns
        -------
        SwitchingCurrents
            Samples (A), histogram, rate and temperature.

        Raises
        ------
        ValueError
            At zero temperature (a noiseless ramp switches at I_c exactly:
            nothing to sample), a ramp rate <= 0, or a ramp that would take
            more than 2e10 steps in all.

        Examples
        --------
        >>> import pendula
        >>> j = pendula.Junction(1e-7, 100.0, 1e-12, temperature=0.05)
        >>> s = j.switching_currents(ramp_rate=1e-3 * 1e-7 * j.plasma_frequency, n=20, seed=1)
        >>> bool(0.5e-7 < s.mean < 1e-7)
        True
        """
        from .junction_switching import switching_samples
        return switching_samples(self, ramp_rate, n, seed, dt, bins, threads)


    # ------------------------------------------------------------- the overdamped (RSJ) junction, C = 0
    @property
    def characteristic_frequency(self) -> float:
        """omega_c = 2 pi I_c R / Phi_0, rad / s (the RSJ equation's time unit; V = I_c R at <phi'> = omega_c)."""
        return 2.0 * math.pi * self.critical_current * self.resistance / FLUX_QUANTUM

    def _overdamped(self, what: str) -> None:
        if self.capacitance != 0:
            raise ValueError(f"field 'capacitance' is {self.capacitance!r} F: {what} is the overdamped junction's "
                             "(the RSJ model, C = 0); with a capacitance use iv_curve")

    def dc_voltage(self, bias: ArrayLike) -> np.ndarray:
        """The exact dc I-V of the overdamped junction: V = R sqrt(I² - I_c²) above I_c.

        The RSJ junction (C = 0) without rf or noise: V = sign(I) R
        sqrt(I² - I_c²) for abs(I) > I_c, 0 below (Stewart 1968; Likharev 1986,
        section 4.1); computed as R sqrt((abs(I) - I_c)(abs(I) + I_c)), without
        cancellation next to I_c.

        Parameters
        ----------
        bias : array_like
            Bias currents, A.

        Returns
        -------
        numpy.ndarray
            Volts.

        Raises
        ------
        ValueError
            A junction with a capacitance (naming the field).
        TypeError
            A bias that is not numbers.

        Examples
        --------
        >>> import pendula
        >>> j = pendula.Junction(10e-6, 30.0, 0.0)
        >>> round(float(j.dc_voltage(20e-6) / (30.0 * 3 ** 0.5 * 10e-6)), 14)    # R sqrt(4 - 1) I_c
        1.0
        """
        from .overdamped import dc_velocity
        self._overdamped("the closed-form dc I-V")
        b = _checks.as_float(bias, "parameter 'bias'")
        return dc_velocity(b, self.critical_current) * (self.critical_current * self.resistance)

    def shapiro_steps(self, rf_current: float, rf_frequency: float, orders: ArrayLike = (0, 1, 2, 3), *,
                      threads: int = 0) -> dict[str, np.ndarray]:
        """The Shapiro steps of the overdamped junction: each step's voltage, edges and width.

        The step n of the RSJ junction (C = 0) under I_rf cos(2 pi f t) is
        the range of bias where the phase is locked n turns per rf period,
        V = n f Phi_0 exactly; its edges are where the stroboscopic map
        F(x) = phi(1 / f; phi(0) = x) gains or loses its fixed point
        n turns on: max (F(x) - x) = 2 pi n (lower edge), min (F(x) - x) =
        2 pi n (upper edge), bisected to 1e-11 I_c (``pendula.overdamped``;
        the map by GSL's rk8pd to 1e-12).  In the limit of a large rf
        frequency the widths approach the Bessel law 2 I_c abs(J_n(I_rf / (I_c
        Omega))).

        Parameters
        ----------
        rf_current, rf_frequency : float
            The rf drive: amplitude (A, > 0) and frequency (Hz, > 0).
        orders : array_like of int
            The steps n asked (n >= 0; the negative ones mirror them).
        threads : int
            OpenMP threads (0: all cores).

        Returns
        -------
        dict
            ``order``, ``voltage`` (V), ``lower`` and ``upper`` (the edges,
            A; NaN for a step of zero width) and ``width`` (A).

        Raises
        ------
        ValueError
            A junction with a capacitance, an rf current or frequency that
            is not > 0, or orders that are not whole numbers >= 0, naming the
            parameter.

        Examples
        --------
        >>> import pendula
        >>> j = pendula.Junction(10e-6, 30.0, 0.0)
        >>> s = j.shapiro_steps(10e-6, 100e9, orders=[1])
        >>> round(float(s["voltage"][0] * 1e6), 3)                 # uV: f Phi_0
        206.783
        >>> bool(0 < s["width"][0] < 2 * 10e-6)
        True
        """
        from .overdamped import step_edges
        self._overdamped("the step edges")
        a = _checks.real(rf_current, "parameter 'rf_current'", 0.0, lo_open=True)
        f = _checks.real(rf_frequency, "parameter 'rf_frequency'", 0.0, lo_open=True)
        n = _checks.grid_values(orders, "parameter 'orders'")
        if np.any(n < 0) or np.any(n != np.round(n)):
            raise ValueError(f"parameter 'orders' must be whole numbers >= 0, got {n.tolist()!r}")
        omega = 2.0 * math.pi * f / self.characteristic_frequency
        lo, hi = step_edges(n, a / self.critical_current, omega, threads)
        ic = self.critical_current
        return {"order": n.astype(int), "voltage": n * f * FLUX_QUANTUM, "lower": lo * ic, "upper": hi * ic,
                "width": np.where(np.isfinite(lo), (hi - lo) * ic, 0.0)}

"""The junction's laboratory tables: Shapiro plateaus read off an I-V branch, sweeps in laboratory
units, the overdamped junction's I-V dataset and the reduced escape rate (for pendula.junction).

The Shapiro steps of an I-V branch read off its grid: each run of locked biases on one step.

A bias that the I-V ramp reports locked (status 6) sits on the step p / q
exactly; a run of neighbouring locked biases on the same step is one
plateau.  Its edges are known to the grid's resolution: the true lower edge
lies between the first locked bias and the unlocked bias before it, the
upper edge between the last locked bias and the unlocked bias after it.
:meth:`pendula.Junction.steps` runs the branch and reads it here; :meth:`pendula.Junction.sweep`
runs :func:`pendula.sweep` with its axes converted.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from . import _checks
from ._optional import require

if TYPE_CHECKING:   # xarray is optional: named in annotations only
    import xarray

__all__ = ["plateaus", "rsj_iv_curve", "junction_sweep", "escape_rate_reduced"]

#: the I-V ramp's status of a phase-locked bias (the sweep engine's 'locked')
_LOCKED = 6


def plateaus(currents: np.ndarray, step: np.ndarray, status: np.ndarray, volt_per_step: float,
             attrs: dict) -> xarray.Dataset:
    """The plateaus of one branch: currents (A, ascending), step and status per current.

    volt_per_step: the voltage of the step 1 (f Phi_0).  Returns a Dataset
    over ``plateau`` (in order of current) with ``order`` (p / q), ``voltage``
    (V), ``lower``, ``upper`` (the outermost locked biases, A), ``width``
    (upper - lower, A), ``lower_gap``, ``upper_gap`` (A: the distance to the
    neighbouring bias off the plateau, within which the true edge lies; NaN
    at the end of the grid, where the plateau may go on) and ``points``.
    """
    xr = require("xarray", "sweep", "pendula.Junction.steps")
    locked = (np.asarray(status) == _LOCKED) & np.isfinite(step)
    runs = []
    k, n = 0, len(currents)
    while k < n:
        if not locked[k]:
            k += 1
            continue
        e = k
        while e + 1 < n and locked[e + 1] and step[e + 1] == step[k]:
            e += 1
        runs.append((k, e))
        k = e + 1
    cur = np.asarray(currents, dtype=float)
    order = np.array([step[a] for a, _ in runs], dtype=float)
    lower = np.array([cur[a] for a, _ in runs], dtype=float)
    upper = np.array([cur[b] for _, b in runs], dtype=float)
    lgap = np.array([cur[a] - cur[a - 1] if a > 0 else np.nan for a, _ in runs], dtype=float)
    ugap = np.array([cur[b + 1] - cur[b] if b + 1 < n else np.nan for _, b in runs], dtype=float)
    pts = np.array([b - a + 1 for a, b in runs], dtype=np.int64)
    dim = ("plateau",)
    return xr.Dataset(
        {"order": (dim, order, {"long_name": "Shapiro step p / q (n turns of the phase per rf period)",
                                "units": "1"}),
         "voltage": (dim, order * volt_per_step, {"long_name": "step voltage n f h / 2e", "units": "V"}),
         "lower": (dim, lower, {"long_name": "lowest locked bias of the plateau (its lower edge to the grid's "
                                              "resolution)", "units": "A"}),
         "upper": (dim, upper, {"long_name": "highest locked bias of the plateau (its upper edge to the grid's "
                                              "resolution)", "units": "A"}),
         "width": (dim, upper - lower, {"long_name": "upper - lower (the true width is up to lower_gap + "
                                                      "upper_gap more)", "units": "A"}),
         "lower_gap": (dim, lgap, {"long_name": "distance to the unlocked bias below: the lower edge lies "
                                                 "within it (NaN at the grid's end)", "units": "A"}),
         "upper_gap": (dim, ugap, {"long_name": "distance to the unlocked bias above: the upper edge lies "
                                                 "within it (NaN at the grid's end)", "units": "A"}),
         "points": (dim, pts, {"long_name": "locked biases of the plateau", "units": "1"})},
        coords={"plateau": ("plateau", np.arange(len(runs)), {"long_name": "plateau, in order of current"})},
        attrs=attrs)


def rf_pair(rf_current, rf_frequency) -> tuple[float, float]:
    """An rf drive as the junction takes it, checked: (current in A, frequency in Hz), both or neither."""
    a = _checks.real(rf_current, "parameter 'rf_current'")
    f = _checks.real(rf_frequency, "parameter 'rf_frequency'", 0.0)
    if f > 0 and a == 0:
        raise ValueError(f"parameter 'rf_current' is 0 but rf_frequency = {f!r} Hz: an rf drive needs a "
                         "current (give rf_current, or no rf_frequency)")
    if a != 0 and not f > 0:
        raise ValueError(f"parameter 'rf_frequency' must be > 0 Hz with rf_current = {a!r} A (a current "
                         "without a frequency is a dc bias: add it to the bias)")
    return a, f


def rsj_iv_curve(j, currents, rf_current, rf_frequency, direction, t_max):
    """Junction.iv_curve at C = 0 (pendula.overdamped): the same dataset (j: the Junction)."""
    from .overdamped import dc_velocity, mean_velocity
    xr = require("xarray", "sweep", "pendula.Junction.iv_curve")
    if j.temperature > 0:
        raise NotImplementedError("field 'temperature' must be 0 at capacitance 0: thermal noise in the "
                                  "overdamped junction (the Ambegaokar-Halperin phase-diffusion I-V) is not "
                                  "implemented")
    wc = j.characteristic_frequency
    a, f = rf_pair(rf_current, rf_frequency)
    i = currents / j.critical_current
    if a == 0:
        vm, err = dc_velocity(currents, j.critical_current), np.zeros_like(i)
        step, st = np.full_like(i, np.nan), np.zeros(i.shape, dtype=np.int32)
    else:
        tm = 2000.0 / f if t_max is None else _checks.real(t_max, "parameter 't_max'", 0.0, lo_open=True)
        vm, err, step, st = mean_velocity(i, a / j.critical_current, 2.0 * math.pi * f / wc,
                                          max(1, round(tm * f)))
    dirs = ["up", "down"] if direction == "both" else [direction]
    volt = j.critical_current * j.resistance
    dims = ("direction", "current")

    def rows(x):
        return np.stack([x] * len(dirs))
    r = xr.Dataset(
        {"voltage": (dims, rows(vm * volt), {"long_name": "dc voltage I_c R <phi'> / omega_c", "units": "V"}),
         "voltage_err": (dims, rows(err * volt), {"long_name": "error bound of the dc voltage", "units": "V"}),
         "step": (dims, rows(step), {"long_name": "Shapiro step n of a locked bias", "units": "1"}),
         "status": (dims, rows(st), {"long_name": "0 decided, 6 locked (exactly n f Phi_0)"}),
         "mean_velocity": (dims, rows(vm), {"long_name": "mean phase velocity <phi'> / omega_c (reduced "
                                                         "voltage of the RSJ junction)", "units": "1"}),
         "mean_velocity_err": (dims, rows(err), {"units": "1"})},
        coords={"direction": ("direction", dirs, {"long_name": "branch of the ramp (the same curve: no "
                                                                "hysteresis at C = 0)"}),
                "current": ("current", currents, {"long_name": "bias current", "units": "A"}),
                "torque": ("current", i, {"long_name": "bias current / critical current", "units": "1"})},
        attrs={"critical_current": j.critical_current, "resistance": j.resistance,
               "capacitance": 0.0, "temperature": j.temperature, "rf_current": a, "rf_frequency": f,
               "characteristic_frequency": wc, "model": "RSJ (overdamped): phi' = i + a cos(Omega t) - sin phi",
               "constants": "CODATA 2018 (exact): h = 6.62607015e-34 J s, e = 1.602176634e-19 C, "
                            "k_B = 1.380649e-23 J/K"})
    return r


#: the laboratory axes of Junction.sweep: (the scene's field, unit, long name)
LAB_AXES = {"bias": ("torque", "A", "dc bias current"),
            "rf_current": ("drive_amplitude", "A", "rf current amplitude"),
            "rf_power": ("drive_amplitude", "dBm", "rf power delivered into the stated impedance"),
            "rf_frequency": ("drive_frequency", "Hz", "rf frequency"),
            "temperature": ("noise", "K", "temperature")}


def junction_sweep(j, over, bias, rf_current, rf_frequency, impedance, transient, t_max, threads, seed,
                   k_over_ej, out=None, client=None):
    """Junction.sweep (j: the Junction; transient and t_max already in inverse plasma frequencies;
    k_over_ej: k_B / E_J, the reduced temperature of one kelvin)."""
    from .rf import rf_current as rf_amplitude
    from .scene import Scene
    from .sweeps import sweep
    xr = require("xarray", "xarray", "pendula.Junction.sweep")
    if not isinstance(over, dict) or not 1 <= len(over) <= 3:
        raise ValueError("parameter 'over' must be a dict of 1 to 3 {axis: values}, axes "
                         f"{', '.join(LAB_AXES)}")
    axes = {}
    for name, vals in over.items():
        if not isinstance(name, str) or name not in LAB_AXES:
            raise ValueError(f"parameter 'over': cannot sweep {name!r}; one of {', '.join(LAB_AXES)}")
        axes[name] = _checks.grid_values(vals, f"parameter 'over[{name!r}]'")
    if "rf_power" in axes and "rf_current" in axes:
        raise ValueError("parameter 'over': 'rf_power' and 'rf_current' are the same drive; sweep one of them")
    if "rf_power" in axes:
        if impedance is None:
            raise ValueError("parameter 'impedance' is needed with over['rf_power']: a power has a current only "
                             "at a stated impedance (I_rf = sqrt(2 P / Z))")
        amps = np.array([rf_amplitude(power_dbm=float(p), impedance=impedance) for p in axes["rf_power"]])
    if "temperature" in axes and np.any(axes["temperature"] < 0):
        raise ValueError("parameter 'over['temperature']': temperatures must be >= 0 K")
    ic, wp = j.critical_current, j.plasma_frequency
    tau = _checks.real(bias, "parameter 'bias'") / ic
    a = _checks.real(rf_current, "parameter 'rf_current'", 0.0) / ic
    f = _checks.real(rf_frequency, "parameter 'rf_frequency'", 0.0)
    driven = ("rf_current" in axes or "rf_power" in axes or a > 0)
    if driven and not (f > 0 or "rf_frequency" in axes):
        raise ValueError("parameter 'rf_frequency' must be > 0 Hz with an rf drive (or sweep 'rf_frequency')")
    if "rf_frequency" in axes and not np.all(axes["rf_frequency"] > 0):
        raise ValueError("parameter 'over['rf_frequency']': frequencies must be > 0 Hz")
    if "rf_frequency" in axes and not driven:
        raise ValueError("parameter 'rf_current' must be > 0 when sweeping 'rf_frequency' (no drive: nothing "
                         "depends on the frequency)")
    temps = axes.get("temperature", np.array([j.temperature]))
    if "temperature" in axes and (out is not None or client is not None):
        raise ValueError("parameters 'out' and 'client' do not take a temperature axis (one sweep per "
                         "temperature): sweep each temperature on its own Junction")
    fields = {}
    for name, vals in axes.items():
        if name == "bias":
            fields["torque"] = vals / ic
        elif name == "rf_current":
            fields["drive_amplitude"] = vals / ic
        elif name == "rf_power":
            fields["drive_amplitude"] = amps / ic
        elif name == "rf_frequency":
            fields["drive_frequency"] = 2.0 * math.pi * vals / wp
    if not fields:
        raise ValueError("parameter 'over': sweep at least one of bias, rf_current, rf_power, rf_frequency "
                         "beside temperature")
    base = Scene(eps=1.0, damping=j.damping, torque=tau, drive_amplitude=a,
                 drive_frequency=2.0 * math.pi * f / wp if f > 0 else 0.0, seed=seed)
    parts = []
    for temp in temps:
        sc = base.replace(noise=float(temp) * k_over_ej)
        parts.append(sweep(sc, over=dict(fields), measure="mean_velocity", transient=transient, t_max=t_max,
                           threads=threads, out=out, client=client))
    ds = parts[0] if "temperature" not in axes else xr.concat(parts, dim="temperature")
    volt = float(j.voltage(1.0))
    names = {LAB_AXES[n][0]: n for n in axes if n != "temperature"}
    ds = ds.rename({old: new for old, new in names.items()})
    for name, vals in axes.items():
        field, unit, long = LAB_AXES[name]
        ds = ds.assign_coords({name: (name, vals, {"long_name": long, "units": unit})})
        if name != "temperature":
            ds = ds.assign_coords({field: (name, fields[field], {"long_name": f"{field} of the pendulum "
                                                                               "(reduced)", "units": "1"})})
    with_voltage(ds, volt)
    ds.attrs.update({"critical_current": ic, "resistance": j.resistance, "capacitance": j.capacitance,
                     "temperature": j.temperature, "bias": float(bias), "rf_current": float(rf_current),
                     "rf_frequency": f, "impedance": float("nan") if impedance is None else float(impedance),
                     "plasma_frequency": wp, "measure": "mean_velocity",
                     "start": "every grid point from rest (theta = 0, v = 0): not a ramp (Junction.iv_curve)"})
    return ds



def with_voltage(ds, volt: float) -> None:
    """Add the dc voltage and its error bar, in V, to a dataset of the measure mean_velocity (reduced,
    units 1): V = (hbar / 2e) omega_p <theta'>, `volt` = (hbar / 2e) omega_p."""
    ds["voltage"] = ds.mean_velocity * volt
    ds["voltage"].attrs = {"long_name": "dc voltage (hbar / 2e) omega_p <theta'>", "units": "V"}
    ds["voltage_err"] = ds.mean_velocity_err * volt
    ds["voltage_err"].attrs = {"long_name": "error bar of the dc voltage", "units": "V"}
    ds["mean_velocity"].attrs["units"] = "1"
    ds["mean_velocity_err"].attrs["units"] = "1"

def escape_rate_reduced(i, beta, temp, regime):
    """The thermal escape rate of the tilted washboard (eps = 1, reduced
    units) at bias i in [0, 1]: Kramers' moderate-damping prefactor, or
    Buttiker-Harris-Landauer's underdamped one (Junction.escape_rate)."""
    i = np.asarray(i, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        s = np.sqrt(1.0 - i * i)
        wa = np.sqrt(s)
        du = 2.0 * (s - i * np.arccos(i))
        if regime == "moderate":
            alpha = beta / (2.0 * wa)
            pref = np.sqrt(1.0 + alpha * alpha) - alpha
        else:
            q = wa / beta
            pref = 4.0 / (np.sqrt(1.0 + q * temp / (1.8 * du)) + 1.0) ** 2
        g = wa / (2.0 * math.pi) * pref * np.exp(-du / temp)
    return np.where(i >= 1.0, np.inf, g)

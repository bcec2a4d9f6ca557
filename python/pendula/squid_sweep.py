"""The dc SQUID's voltage over a grid of applied flux and bias current (private module).

:meth:`pendula.DCSquid.sweep` runs here.  Every grid point starts from rest
(φ₁,₂ = ±πΦ/Φ₀, no velocity): a map of the voltage, not a ramp (the ramps
with their hysteresis are :meth:`~pendula.DCSquid.iv_curve` and
:meth:`~pendula.DCSquid.v_phi_curve`).  The points of one flux (a row) run
on a pool of threads (the kernel's integrators release the GIL); with noise,
point p of the grid (row-major) draws the noise streams p·paths ... p·paths
+ paths − 1 of the seed, so the result is the same on any number of threads
and after a resume.  With ``out`` the rows go to the resumable Zarr store
of :func:`pendula.sweep` (one row a chunk), and a sweep stopped half way
resumes where it stopped.
"""

from __future__ import annotations

import json
import math
import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from . import _checks
from ._optional import require
from ._progress import Progress
from .squid_voltage import mean_velocity, noisy_mean_velocity, squid_network

_VARIABLES = {
    "voltage": {"long_name": "dc voltage", "units": "V"},
    "voltage_err": {"long_name": "error of the dc voltage", "units": "V"},
    "mean_velocity": {"long_name": "mean phase velocity / omega_c", "units": "1"},
}


def _point(sq, flux: float, bias: float, tr: float, tm: float, rtol: float, noise, first_path: int
           ) -> tuple[float, float]:
    """⟨s'⟩ (in ω_c) and its error at one grid point, from rest."""
    net = squid_network(sq.beta_l, sq.beta_c, flux, bias, asym=sq._asym)
    phi, v = np.array([math.pi * flux, -math.pi * flux]), np.zeros(2)
    temp, h, paths, seed, _ = noise
    if temp == 0:
        vel, err, _, _ = mean_velocity(net, phi, v, tr, tm, rtol)
        return vel, err
    drift, _, _ = noisy_mean_velocity(net, phi, v, tr, tm, temp, h, paths, seed, 1, first_path)
    return float(drift.mean()), float(drift.std(ddof=1) / math.sqrt(paths))


def squid_sweep(sq, fluxes, currents, tr: float, tm: float, rtol: float, noise, progress: bool, out):
    """DCSquid.sweep (tr, tm in 1/ω_c; noise = (temperature, dt, paths, seed, threads) as DCSquid._noise)."""
    xr = require("xarray", "xarray" if out is None else "sweep", "pendula.DCSquid.sweep")
    fl = _checks.grid_values(fluxes, "fluxes")
    cur = _checks.grid_values(currents, "currents")
    progress = _checks.flag(progress, "progress")
    threads = noise[4] if noise[4] > 0 else (os.cpu_count() or 1)
    i0 = sq.junction.critical_current
    volt = i0 * sq.junction.resistance
    paths = noise[2] if noise[0] > 0 else 1
    coords = {"flux": (fl, {"long_name": "applied flux / flux quantum", "units": "Phi0"}),
              "current": (cur, {"long_name": "bias current", "units": "A"})}
    attrs = sq._attrs(noise, rtol, tr, tm) | {
        "start": "every grid point from rest (phi = +-pi flux, v = 0): not a ramp (DCSquid.iv_curve)"}
    if noise[0] > 0:
        attrs["noise_streams"] = "grid point p (row-major over flux, current) draws the streams p*paths ..."

    def row(r: int) -> dict:
        f = float(fl[r])
        firsts = [(r * cur.size + c) * paths for c in range(cur.size)]
        with ThreadPoolExecutor(max_workers=min(threads, cur.size)) as pool:
            res = list(pool.map(lambda c: _point(sq, f, float(cur[c]) / i0, tr, tm, rtol, noise, firsts[c]),
                                range(cur.size)))
        vel = np.array([a for a, _ in res])[None, :]
        err = np.array([b for _, b in res])[None, :]
        return {"voltage": vel * volt, "voltage_err": err * volt, "mean_velocity": vel}

    if out is None:
        rows = []
        with Progress(fl.size, "dc SQUID sweep", enabled=progress, unit="flux") as bar:
            for r in range(fl.size):
                rows.append(row(r))
                bar.update(1, note=f"flux {fl[r]:.4g}")
        data = {n: (("flux", "current"), np.concatenate([x[n] for x in rows]), dict(a))
                for n, a in _VARIABLES.items()}
        ds = xr.Dataset(data, coords={n: (n, v, dict(a)) for n, (v, a) in coords.items()}, attrs=attrs)
    else:
        from ._store import Layout, SweepStore, Variable
        variables = {n: Variable(("flux", "current"), np.dtype(np.float64), dict(a), np.nan)
                     for n, a in _VARIABLES.items()}
        identity = json.dumps({"sweep": "pendula.DCSquid.sweep", **{k: attrs[k] for k in sorted(attrs)},
                               "fluxes": fl.tolist(), "currents": cur.tolist()}, sort_keys=True, default=str)
        layout = Layout(axes={"flux": fl, "current": cur}, coords=coords, variables=variables, rows=1,
                        identity=identity, attrs={"Conventions": "CF-1.10", "title": "pendula DCSquid.sweep"})
        with SweepStore(_checks.path(out, "out"), layout) as store:
            todo = [r for r in range(fl.size) if r not in store.done]
            with Progress(fl.size, "dc SQUID sweep", enabled=progress, initial=fl.size - len(todo),
                          unit="flux") as bar:
                for r in todo:
                    store.write_chunk(r, row(r))
                    bar.update(1, note=f"flux {fl[r]:.4g}")
            ds = store.dataset().load()
        ds.attrs = attrs
    ds = ds.assign_coords(bias=("current", cur / i0, {"long_name": "bias current / I0", "units": "1"}))
    return ds

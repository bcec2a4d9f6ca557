"""The adiabatic sweep (``sweep(..., follow=True)``): each parameter value starts from the end state of the
one before, up the values and then down again, so that an orbit diagram follows one attractor until it
disappears and shows the hysteresis between coexisting attractors.

Each point is the kernel's measure at one grid point (:func:`._sweep_engine.run_measure`), started from the
carried state (``theta0``, ``v0``); the state carried on is the end of that point's run: the last
stroboscopic sample of a ``poincare`` point, otherwise the flow over the transient and the measuring window
(whole forcing periods for a forced scene, so that the next point starts at the forcing's phase 0 as every
sweep point does).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ._optional import require
from ._sweep_engine import run_measure
from .scene import Scene
from .systems import contract, run

if TYPE_CHECKING:
    import xarray

#: The measures an adiabatic sweep runs (the attractor map classifies a grid of starts: no state to carry).
FOLLOW_MEASURES = ("final_well", "mean_velocity", "locked", "poincare", "lyapunov")


def check_follow(scene: Scene, over: dict, measure: str, out, client, uf) -> tuple[str, np.ndarray]:
    """The one field and its values in increasing order, or a ValueError naming what an adiabatic sweep
    cannot do."""
    if measure not in FOLLOW_MEASURES:
        raise ValueError(f"parameter 'follow': measure {measure!r} has no state to carry from point to point; "
                         f"follow=True runs {', '.join(FOLLOW_MEASURES)}")
    if out is not None or client is not None:
        raise ValueError("parameter 'follow': an adiabatic sweep runs its points one after another in this "
                         "process; it takes neither 'out' nor 'client'")
    if uf is not None:
        raise ValueError("parameter 'follow': a user's force is not carried through an adiabatic sweep "
                         "(not implemented); sweep without follow")
    if scene.noise > 0:
        raise ValueError("parameter 'follow': with thermal noise the carried state is one sample of a random "
                         "motion; an adiabatic sweep needs noise = 0")
    if len(over) != 1:
        raise ValueError(f"parameter 'follow': an adiabatic sweep runs over one field, got {len(over)} "
                         f"({', '.join(over)})")
    (name, values), = over.items()
    if name in ("theta0", "v0"):
        raise ValueError(f"parameter 'follow': the state (theta0, v0) is what an adiabatic sweep carries; "
                         f"sweep another field than {name!r}")
    vals = np.sort(np.asarray(values, dtype=np.float64).reshape(-1))
    if np.any(np.diff(vals) == 0):
        raise ValueError(f"over[{name!r}]: a value repeats; an adiabatic sweep visits each value once each way")
    return name, vals


def _end_state(scene: Scene, ds, measure: str, rtol: float, atol: float, t_max: float, transient: float,
               samples: int) -> tuple[float, float]:
    """The state at the end of one point's run (theta reduced to [-pi, pi]: the force is 2 pi periodic)."""
    if measure == "poincare":
        th, v = float(ds.theta.values[0, -1]), float(ds.v.values[0, -1])
        if math.isfinite(th) and math.isfinite(v):
            return th, v
    ts = contract.time_scales(scene)
    forced = ts.forcing_status != 1
    period = 2 * math.pi / contract.forcing_frequency(scene, "follow") if forced else 0.0
    window = samples * period if measure == "poincare" else t_max
    span = transient + window
    if forced:
        span = math.ceil(span / period - 1e-9) * period
    tr = run(scene.replace(rtol=rtol, atol=atol), np.array([0.0, span]))
    th, v = float(tr.theta[-1]), float(tr.v[-1])
    return th - 2 * math.pi * round(th / (2 * math.pi)), v


def follow_sweep(scene: Scene, name: str, values: np.ndarray, measure: str, rtol: float, atol: float,
                 t_max: float, transient: float, samples: int, threads: int) -> "xarray.Dataset":
    """The measure at each value, up from the scene's state at the lowest and down from the end of the way
    up at the highest: a Dataset with the dimension ``direction`` ('up', 'down') before ``name``."""
    xr = require("xarray", "xarray", "pendula.sweep")
    state = (float(scene.theta0), float(scene.v0))
    runs = []
    for direction, seq in (("up", values), ("down", values[::-1])):
        parts = []
        for x in seq:
            sc = scene.replace(**{name: float(x), "theta0": state[0], "v0": state[1]})
            ds = run_measure(sc, {name: np.array([x])}, measure, rtol, atol, t_max, transient, samples, 1,
                             None, None, threads, False)
            parts.append(ds)
            state = _end_state(sc, ds, measure, rtol, atol, t_max, transient, samples)
        runs.append(xr.concat(parts, dim=name, combine_attrs="drop_conflicts").sortby(name))
    out = xr.concat(runs, dim="direction", combine_attrs="drop_conflicts")
    out = out.assign_coords(direction=("direction", ["up", "down"],
                                       {"long_name": "way through the values: each starts from the end state of "
                                                     "the value before"}))
    out.attrs.update(runs[0].attrs)
    out.attrs["scene"] = scene.to_namelist()
    out.attrs["follow"] = (f"adiabatic: up {name} from theta0 = {scene.theta0!r}, v0 = {scene.v0!r} at the lowest "
                           "value, each value from the end state of the one before; down from the end of the way "
                           "up at the highest")
    return out

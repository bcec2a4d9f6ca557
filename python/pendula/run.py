"""Run a scene and write what it asks for: CSV tables and PNG figures.

``run_scene(scene, outdir)`` computes only the outputs the scene names:
a scene asking for 'omega' gets the exact orbit table and no trajectory.
"""

from __future__ import annotations

import csv
import math
import pathlib
import re

import numpy as np

from ._progress import Progress
from .motion import orbit, simulate
from .scene import Scene

TRAJECTORY_OUTPUTS = {"trajectory", "theta_t", "v_t", "phase", "energy"}
ORBIT_OUTPUTS = {"period", "omega", "theta_max"}


def slug(text: str) -> str:
    s = re.sub(r"[^A-Za-z0-9]+", "_", text).strip("_").lower()
    return s or "scene"


def _header(scene: Scene) -> list[str]:
    lines = ["# pendula scene:"] + ["#   " + ln for ln in scene.to_namelist().splitlines()]
    eff = ", ".join(scene.effects) or "none (conservative rigid pendulum: exact solution)"
    return lines + [f"# effects = {eff}"]


def _write_csv(path: pathlib.Path, scene: Scene, columns: list[str], rows) -> pathlib.Path:
    """A table with the scene in its header.  A numeric array is written by
    numpy in one call (17 significant digits, enough to round-trip); lists of
    rows (which may hold words such as the regime) go through csv."""
    with path.open("w", newline="") as fh:
        for ln in _header(scene):
            fh.write(ln + "\n")
        if isinstance(rows, np.ndarray):
            fh.write(",".join(columns) + "\n")
            np.savetxt(fh, rows, delimiter=",", fmt="%.17g")
            return path
        w = csv.writer(fh)
        w.writerow(columns)
        for r in rows:
            w.writerow([repr(float(x)) if not isinstance(x, str) else x for x in r])
    return path


def run_scene(scene: Scene, outdir, stem: str | None = None, progress: bool = True) -> list[pathlib.Path]:
    """Compute the scene's outputs into ``outdir``; return the files written."""
    from . import plot

    outdir = pathlib.Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    stem = stem or slug(scene.name)
    wanted = set(scene.outputs)
    members = scene.members()
    values = list(scene.sweep_values) if scene.sweep else [math.nan]
    files: list[pathlib.Path] = []

    if wanted & TRAJECTORY_OUTPUTS:
        runs = []
        with Progress(len(members), f"{stem}: trajectories", enabled=progress) as bar:
            for value, member in zip(values, members):
                runs.append((value, simulate(member)))
                bar.update(note=f"{scene.sweep} = {value:g}" if scene.sweep else "")
        if "trajectory" in wanted:
            cols = ([scene.sweep] if scene.sweep else []) + ["t", "theta", "v", "energy"]
            rows = np.vstack([np.column_stack([np.full(tr.t.size, value), tr.as_array()])
                              if scene.sweep else tr.as_array() for value, tr in runs])
            files.append(_write_csv(outdir / f"{stem}.csv", scene, cols, rows))
        if "theta_t" in wanted:
            files.append(plot.time_series(scene, runs, outdir / f"{stem}_theta_t.png", "theta"))
        if "v_t" in wanted:
            files.append(plot.time_series(scene, runs, outdir / f"{stem}_v_t.png", "v"))
        if "phase" in wanted:
            files.append(plot.phase_portrait(scene, runs, outdir / f"{stem}_phase.png"))
        if "energy" in wanted:
            files.append(plot.energy_drift(scene, runs, outdir / f"{stem}_energy.png"))

    if wanted & ORBIT_OUTPUTS:
        from .models.gravity import issue13_orbit  # issue 13 hook: cycloid and gravity orbits

        if scene.effects and issue13_orbit(scene) is None:
            raise ValueError("outputs period/omega/theta_max are facts of the exact conservative orbit; "
                             f"the scene names {', '.join(scene.effects)}")
        table = {"period": [], "omega": [], "theta_max": [], "regime": [], "k": []}
        for member in members:
            o = issue13_orbit(member) or orbit(member.theta0, member.v0, member.eps)
            for key in table:
                table[key].append(getattr(o, key))
        cols = ([scene.sweep] if scene.sweep else []) + ["theta0", "v0", "eps", "regime", "k", "period",
                                                         "omega", "theta_max"]
        rows = [([value] if scene.sweep else []) + [m.theta0, m.v0, m.eps, table["regime"][i], table["k"][i],
                                                     table["period"][i], table["omega"][i], table["theta_max"][i]]
                for i, (value, m) in enumerate(zip(values, members))]
        files.append(_write_csv(outdir / f"{stem}_orbits.csv", scene, cols, rows))
        if scene.sweep:
            shown = {k: table[k] for k in ("omega", "theta_max", "period") if k in wanted}
            files.append(plot.orbit_curves(scene, values, shown, outdir / f"{stem}_orbits.png"))
            v = np.asarray(values) / math.sqrt(scene.eps)
            if scene.sweep == "v0" and "omega" in wanted and np.all(np.abs(v - 2) < 0.5) and np.any(v != 2):
                files.append(plot.critical_omega(scene, values, table["omega"], outdir / f"{stem}_critical.png"))

    if wanted & {"series", "lindstedt"} and scene.effects:  # issue 13 guard: both are the uniform rigid pendulum's
        raise ValueError("outputs series/lindstedt are the conservative rigid pendulum's in uniform gravity; "
                         f"the scene names {', '.join(scene.effects)}")
    if "series" in wanted:
        files += _series_outputs(scene, members, values, outdir, stem)
    if "lindstedt" in wanted:
        files += _lindstedt_outputs(scene, members, values, outdir, stem, progress)
    if "spectrum" in wanted:
        from .spectrum import spectrum_outputs

        files += spectrum_outputs(scene, members, values, outdir, stem, progress)
    return files


def _series_outputs(scene, members, values, outdir, stem):
    """The period series (orders 1, 2, 3, 5, 10) against the exact period, over theta0."""
    from . import plot
    from .series import period_from_series

    if scene.sweep != "theta0" or any(m.v0 != 0 for m in members):
        raise ValueError("output 'series' compares T(theta0) released from rest: sweep theta0 with v0 = 0")
    theta0 = np.asarray(values)
    exact = np.array([orbit(m.theta0, 0.0, m.eps).period for m in members])
    orders = (1, 2, 3, 5, 10)
    approx = {n: period_from_series(theta0, n, scene.eps) for n in orders}
    rows = [[theta0[i], exact[i]] + [approx[n][i] for n in orders] for i in range(len(theta0))]
    cols = ["theta0", "T_exact"] + [f"T_series_{2 * n}" for n in orders]
    return [_write_csv(outdir / f"{stem}_series.csv", scene, cols, rows),
            plot.period_series_figure(theta0, exact, approx, outdir / f"{stem}_series.png")]


def _lindstedt_outputs(scene, members, values, outdir, stem, progress):
    """Max error of Poincare-Lindstedt (orders 1, 3, 5, 7) against the exact solution, per amplitude."""
    from . import plot
    from .motion import exact_motion
    from .series import poincare_lindstedt

    if scene.sweep != "theta0" or any(m.v0 != 0 for m in members):
        raise ValueError("output 'lindstedt' needs a sweep of theta0 (the amplitude) with v0 = 0")
    t = scene.times()
    orders = (1, 3, 5, 7)
    errors = {o: [] for o in orders}
    with Progress(len(members), f"{stem}: Poincare-Lindstedt", enabled=progress) as bar:
        for m in members:
            theta, _ = exact_motion(m.theta0, 0.0, m.eps, t)
            for o in orders:
                errors[o].append(float(np.abs(poincare_lindstedt(m.theta0, t, m.eps, o) - theta).max()))
            bar.update()
    rows = [[values[i]] + [errors[o][i] for o in orders] for i in range(len(values))]
    cols = ["amplitude"] + [f"max_error_order_{o}" for o in orders]
    return [_write_csv(outdir / f"{stem}_lindstedt.csv", scene, cols, rows),
            plot.lindstedt_figure(np.asarray(values), errors, outdir / f"{stem}_lindstedt.png")]

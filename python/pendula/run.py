"""Run a scene and write what it asks for: CSV tables and PNG figures.

``run_scene(scene, outdir)`` computes only the outputs the scene names:
a scene asking for 'omega' gets the exact orbit table and no trajectory.
Which outputs a scene can have is a rule of the scene, checked by the
kernel when the Scene is made (kernel/io/pendula_scene.f90): a scene that
reaches run_scene can have every output it names.
"""

from __future__ import annotations

import errno
import math
import pathlib
import re
import warnings

import numpy as np

from . import _checks, run_figures
from ._files import staging, write_csv
from ._optional import MissingExtraError
from ._progress import Progress
from .motion import exact_motion, orbit, simulate
from .scene import Scene
from .series import period_from_series, poincare_lindstedt
from .spectrum import odd_harmonics_above, spectrum
from .systems.gravity import model_orbit_facts

TRAJECTORY_OUTPUTS = {"trajectory", "theta_t", "v_t", "phase", "energy"}
ORBIT_OUTPUTS = {"period", "omega", "theta_max"}



class FiguresNotDrawn(UserWarning):
    """The tables of a run are written but its figures are not: matplotlib (the plot extra) is missing."""


def _png(path, draw, *args, **kw):
    """Draw a figure with a figure function of pendula.run_figures, save it to path, and answer with the path;
    None (and a :class:`FiguresNotDrawn` warning) when matplotlib is not installed: the tables
    need only numpy, so they are written all the same."""
    try:
        draw(*args, path=path, **kw)
    except MissingExtraError as exc:
        warnings.warn(f"figures not drawn, tables written: {exc}", FiguresNotDrawn, stacklevel=3)
        return None
    return path

def slug(text: str) -> str:
    s = re.sub(r"[^A-Za-z0-9]+", "_", text).strip("_").lower()
    return s or "scene"


def run_scene(scene: Scene, outdir, stem: str | None = None, progress: bool = True) -> list[pathlib.Path]:
    """Compute the scene's outputs into ``outdir``; return the files written.

    All or nothing: the files are made in a staging folder inside ``outdir``
    and moved into place only when every output succeeded, so a failure
    leaves no partial file (and does not touch an earlier run's files).
    Without matplotlib the tables are written and the figures are not (a
    :class:`FiguresNotDrawn` warning names the extra to install).  ``outdir``
    is created with its missing parent folders (``mkdir -p``), as every output
    folder is; a file where the folder should be is a NotADirectoryError.
    """
    outdir = _checks.path(outdir, "outdir")     # the one checker: '' is refused, never the current folder
    if outdir.exists() and not outdir.is_dir():
        raise NotADirectoryError(errno.ENOTDIR, "is not a folder (the output folder of a run)", str(outdir))
    outdir.mkdir(parents=True, exist_ok=True)
    with staging(outdir) as stage:
        made = [f for f in _outputs(scene, stage, stem, progress) if f is not None]
    return [outdir / f.name for f in made]


def _outputs(scene: Scene, outdir: pathlib.Path, stem: str | None, progress: bool) -> list[pathlib.Path]:
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
            files.append(write_csv(outdir / f"{stem}.csv", scene, cols, rows))
        if "theta_t" in wanted:
            files.append(_png(outdir / f"{stem}_theta_t.png", run_figures.time_series, scene, runs, which="theta"))
        if "v_t" in wanted:
            files.append(_png(outdir / f"{stem}_v_t.png", run_figures.time_series, scene, runs, which="v"))
        if "phase" in wanted:
            files.append(_png(outdir / f"{stem}_phase.png", run_figures.phase_portrait, scene, runs))
        if "energy" in wanted:
            files.append(_png(outdir / f"{stem}_energy.png", run_figures.energy_drift, scene, runs))

    if wanted & ORBIT_OUTPUTS:
        table = {"period": [], "omega": [], "theta_max": [], "regime": [], "k": []}
        for member in members:
            o = model_orbit_facts(member) or orbit(member.theta0, member.v0, member.eps)
            for key in table:
                table[key].append(getattr(o, key))
        # the swept value has its own column unless it is one of the orbit's (no name twice)
        lead = bool(scene.sweep) and scene.sweep not in ("theta0", "v0", "eps")
        cols = ([scene.sweep] if lead else []) + ["theta0", "v0", "eps", "regime", "k", "period",
                                                  "omega", "theta_max"]
        rows = [([value] if lead else []) + [m.theta0, m.v0, m.eps, table["regime"][i], table["k"][i],
                                                     table["period"][i], table["omega"][i], table["theta_max"][i]]
                for i, (value, m) in enumerate(zip(values, members))]
        files.append(write_csv(outdir / f"{stem}_orbits.csv", scene, cols, rows))
        if scene.sweep:
            shown = {k: table[k] for k in ("omega", "theta_max", "period") if k in wanted}
            files.append(_png(outdir / f"{stem}_orbits.png", run_figures.orbit_curves, scene, values, shown))
            v = np.asarray(values) / math.sqrt(scene.eps)
            if scene.sweep == "v0" and "omega" in wanted and np.all(np.abs(v - 2) < 0.5) and np.any(v != 2):
                files.append(_png(outdir / f"{stem}_critical.png", run_figures.critical_omega, scene, values,
                                  table["omega"]))

    if "series" in wanted:
        files += _series_outputs(scene, members, values, outdir, stem)
    if "lindstedt" in wanted:
        files += _lindstedt_outputs(scene, members, values, outdir, stem, progress)
    if "spectrum" in wanted:
        files += _spectrum_outputs(scene, members, values, outdir, stem, progress)
    return files


def _series_outputs(scene, members, values, outdir, stem):
    """The period series (orders 1, 2, 3, 5, 10) against the exact period, over theta0 (the
    scene sweeps theta0 from rest: a rule of the scene)."""
    theta0 = np.asarray(values)
    exact = np.array([orbit(m.theta0, 0.0, m.eps).period for m in members])
    orders = (1, 2, 3, 5, 10)
    approx = {n: period_from_series(theta0, n, scene.eps) for n in orders}
    rows = [[theta0[i], exact[i]] + [approx[n][i] for n in orders] for i in range(len(theta0))]
    cols = ["theta0", "T_exact"] + [f"T_series_{2 * n}" for n in orders]
    return [write_csv(outdir / f"{stem}_series.csv", scene, cols, rows),
            _png(outdir / f"{stem}_series.png", run_figures.period_series_figure, theta0, exact, approx)]


def _lindstedt_outputs(scene, members, values, outdir, stem, progress):
    """Max error of Poincare-Lindstedt (orders 1, 3, 5, 7) against the exact solution, per amplitude
    (the scene sweeps theta0 from rest, |theta0| < pi: a rule of the scene)."""
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
    return [write_csv(outdir / f"{stem}_lindstedt.csv", scene, cols, rows),
            _png(outdir / f"{stem}_lindstedt.png", run_figures.lindstedt_figure, np.asarray(values), errors)]


def _spectrum_outputs(scene, members, values, outdir, stem, progress=True):
    """The 'spectrum' output of a scene: one FFTW plan for the whole sweep.

    Conservative scenes are sampled over ``scene.n_samples`` points spanning a
    whole number of periods (8, or what fits t_end), so the lines sit exactly
    on bins; other scenes use the scene's own time grid.
    """
    rows, specs, labels, notes = [], [], [], []
    n = scene.n_samples if scene.n_samples >= 64 else 4096
    for value, m in zip(values, members):
        if m.is_conservative_rigid:
            o = orbit(m.theta0, m.v0, m.eps)   # never the separatrix: a rule of the scene
            periods = 8
            tt = np.arange(n) * (periods * o.period / n)
            tr = simulate(m, tt)
            x = tr.theta - (o.omega * tt if o.regime == "rotation" else 0.0)
            s = spectrum(tt, x)
        else:
            tt = np.linspace(m.t_start, m.t_end, n)
            tr = simulate(m, tt)
            s = spectrum(tt, tr.theta - tr.theta.mean(), window="hann")
        specs.append(s)
        labels.append(f"{scene.sweep} = {value:.10g}" if scene.sweep else "")
        above = odd_harmonics_above(s)
        notes.append(above)
        rows.append([value, s.fundamental] + list(s.harmonics(8)))
    write_csv(outdir / f"{stem}_spectrum.csv", scene,
              [scene.sweep or "run", "fundamental_omega"] + [f"A_{2 * j + 1}" for j in range(8)], rows,
              notes=("harmonics above 1e-6 of the fundamental's power: "
                     + "; ".join(f"{lab or 'run'}: {h}" for lab, h in zip(labels, notes)),))
    files = [outdir / f"{stem}_spectrum.csv",
             _png(outdir / f"{stem}_spectrum.png", run_figures.spectra_figure, scene, specs, labels)]   # None: not drawn
    for lab, h in zip(labels, notes):
        print(f"    {stem}: {lab or 'run'}: odd harmonics above 1e-6 of the fundamental's power: "
              f"{', '.join(str(x) for x in h)}")
    return files

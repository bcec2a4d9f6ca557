"""The scene files of the systems built by their own class (groups &double, &foucault, &network),
read, checked and run by the kernel (kernel/dispatch/pendula_system_scenes.f90) as pendula-run runs
them: one verdict with one message for every file, and the same table to the bit.  ``pendula run
FILE`` writes the table as CSV and draws its figure (the double pendulum's angles, the Foucault bob
seen from above, the network's phases).
"""

from __future__ import annotations

import errno
import os
import pathlib
import warnings
from dataclasses import dataclass

import numpy as np

from . import _kernel
from ._files import atomic_path, save_figure, staging
from ._optional import MissingExtraError
from .scene import SceneError

#: the exit status of pendula-run for a kernel status of these files: 2 bad scene, 4 the run failed
RUN_FAILED = 4


class SystemRunError(RuntimeError):
    """The run of a system's scene file failed (the integrator's status named in the message)."""


def _text(b) -> str:
    return (b.decode("utf-8", errors="replace") if isinstance(b, bytes) else str(b)).strip()


def system_group(path) -> str:
    """The system whose scene file ``path`` is ('double', 'foucault' or 'network'), or '' when the file
    holds none of their groups (a file of the group &scene, or one that does not read); a bad scene
    of a system raises SceneError naming the field, the message pendula-run gives."""
    group, _, _, status, msg = _kernel.system_scene_size_v(os.fsencode(os.fspath(path)))
    if status == 1:
        return ""
    if status:
        raise SceneError(_text(msg))
    return _text(group)


@dataclass(frozen=True, repr=False)
class SystemTable:
    """The table of a system's scene file: its title, column names and rows (one per output time)."""

    group: str
    title: str
    columns: tuple
    rows: np.ndarray

    def __repr__(self) -> str:
        return f"SystemTable({self.title!r}, {self.rows.shape[0]} rows x {', '.join(self.columns)})"


def system_table(path) -> SystemTable:
    """Read, check and run the scene file ``path`` of a system through the kernel, as pendula-run does:
    SceneError for a bad scene (naming the field), SystemRunError when the run fails."""
    source = os.fsencode(os.fspath(path))
    group, nrows, ncols, status, msg = _kernel.system_scene_size_v(source)
    if status:
        raise SceneError(_text(msg))
    rows, heads, title, status, msg = _kernel.system_scene_table_v(source, nrows, ncols)
    if status == RUN_FAILED:
        raise SystemRunError(_text(msg))
    if status:
        raise SceneError(_text(msg))
    return SystemTable(_text(group), _text(title), tuple(_text(heads).split(",")), np.ascontiguousarray(rows))


def write_table(path, table: SystemTable, source) -> pathlib.Path:
    """The table as CSV: two comment lines (the file, the title), the column names, 17 significant digits."""
    path = pathlib.Path(path)
    with atomic_path(path) as tmp, tmp.open("w", newline="") as fh:
        fh.write(f"# pendula run {os.fspath(source)}\n# {table.title}\n{','.join(table.columns)}\n")
        np.savetxt(fh, table.rows, delimiter=",", fmt="%.17g")
    return path


def draw_table(table: SystemTable, path):
    """The figure of a system's run: the double pendulum's angles against t, the Foucault bob's path
    seen from above (x east, y north, in mm), or the network's phases against t."""
    from ._plot_common import _plt

    plt = _plt()
    t = table.rows[:, 0]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    if table.group == "double":
        ax.plot(t, table.rows[:, 1], lw=1.0, label="theta1")
        ax.plot(t, table.rows[:, 2], lw=1.0, label="theta2")
        ax.set_xlabel("t")
        ax.set_ylabel("angle (rad)")
    elif table.group == "foucault":
        ax.plot(1e3 * table.rows[:, 1], 1e3 * table.rows[:, 2], lw=0.6)
        ax.set_xlabel("x, east (mm)")
        ax.set_ylabel("y, north (mm)")
        ax.set_aspect("equal", adjustable="datalim")
    else:
        n = (len(table.columns) - 1) // 2
        for k in range(min(n, 12)):
            ax.plot(t, table.rows[:, 1 + k], lw=1.0, label=table.columns[1 + k])
        ax.set_xlabel("t")
        ax.set_ylabel("phase (rad)")
    ax.set_title(table.title, fontsize=10)
    ax.grid(True, alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=9, loc="best")
    fig.tight_layout()
    try:
        return save_figure(fig, path)
    finally:
        plt.close(fig)


def run_system_scene(path, outdir, stem: str | None = None) -> list[pathlib.Path]:
    """Run the scene file ``path`` of a system into ``outdir`` (created): STEM.csv and STEM.png, all or
    nothing; without matplotlib the table is written and a FiguresNotDrawn warning says why."""
    from .run import FiguresNotDrawn

    table = system_table(path)
    outdir = pathlib.Path(outdir)
    if outdir.exists() and not outdir.is_dir():
        raise NotADirectoryError(errno.ENOTDIR, "is not a folder (the output folder of a run)", str(outdir))
    outdir.mkdir(parents=True, exist_ok=True)
    stem = stem or pathlib.Path(os.fspath(path)).stem
    with staging(outdir) as stage:
        made = [write_table(stage / f"{stem}.csv", table, path)]
        try:
            made.append(draw_table(table, stage / f"{stem}.png"))
        except MissingExtraError as exc:
            warnings.warn(f"figures not drawn, tables written: {exc}", FiguresNotDrawn, stacklevel=2)
    return [outdir / f.name for f in made]

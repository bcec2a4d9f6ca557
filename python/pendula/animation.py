"""The pendulum swinging, as a GIF or MP4 file: :func:`pendula.plot.animate`.

matplotlib draws the frames (``FuncAnimation``) and one of its writers
encodes them: Pillow's for a ``.gif`` (Pillow comes with matplotlib: nothing
else is needed) and FFmpeg's for a ``.mp4`` (the ``ffmpeg`` program must be
on the PATH).
"""

from __future__ import annotations

import os
import pathlib
import shutil
import tempfile
from typing import TYPE_CHECKING

import numpy as np

from . import _checks
from ._files import atomic_path, check_target
from ._optional import require

if TYPE_CHECKING:
    import xarray

    from .trajectory import Trajectory

__all__ = ["animate"]

#: the writer of each file type: (matplotlib's writer name, what it needs)
_WRITERS = {".gif": ("pillow", "Pillow (installed with matplotlib)"),
            ".mp4": ("ffmpeg", "the ffmpeg program on the PATH (apt install ffmpeg, "
                               "dnf install ffmpeg, brew install ffmpeg)")}


def animate(tr: Trajectory | xarray.Dataset, path: str | os.PathLike, *, fps: float = 25.0,
            max_frames: int = 500, dpi: float = 80.0, trail: int = 0) -> pathlib.Path:
    """Write the pendulum's swing as an animation: a ``.gif`` or an ``.mp4``.

    One frame per sample of the trajectory (every k-th when there are more
    than ``max_frames``): the rod from the pivot to the bob, the time in the
    corner.  For the flexible cord the bob is drawn where it flies (the cord
    dashed while slack); for a double pendulum both arms, the trace following
    the lower end.

    Parameters
    ----------
    tr : Trajectory or xarray.Dataset
        What :func:`pendula.simulate` returns (or ``Pendulum.motion(t).trajectory``),
        or what :meth:`pendula.DoublePendulum.simulate` returns.
        Its times should be equally spaced: a frame is shown for 1 / fps s.
    path : str or os.PathLike
        The file to write; its suffix chooses the writer: ``.gif`` with
        Pillow's writer (no other program needed), ``.mp4`` with FFmpeg's
        (the ``ffmpeg`` program on the PATH).  Written whole or not at all.
    fps : float
        Frames per second of the file (> 0).
    max_frames : int
        The most frames written (>= 1).
    dpi : float
        Resolution of the 4 x 4 inch frames (> 0).
    trail : int
        How many earlier positions of the bob to draw as a fading trace (>= 0).

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    TypeError
        When ``tr`` is not a Trajectory.
    ValueError
        An unknown suffix, or a parameter out of range (naming it).
    RuntimeError
        An ``.mp4`` asked for without ``ffmpeg`` on the PATH.

    See Also
    --------
    pendula.Pendulum : the pendulum in metres, seconds and degrees.
    trajectory : theta(t) as a still figure.

    Examples
    --------
    >>> import pathlib, tempfile, pendula, pendula.plot
    >>> tr = pendula.Pendulum(1.0, amplitude_deg=40).motion().trajectory
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "swing.gif"
    >>> pendula.plot.animate(tr, out, max_frames=20).name
    'swing.gif'
    """
    from .trajectory import Trajectory

    double = _double_arms(tr)
    if double is None:
        _checks.instance(tr, "tr", Trajectory, "a Trajectory or a DoublePendulum.simulate Dataset")
    fps = _checks.real(fps, "fps", 0.0, lo_open=True)
    dpi = _checks.real(dpi, "dpi", 0.0, lo_open=True)
    max_frames = _checks.count(max_frames, "max_frames", 1)
    trail = _checks.count(trail, "trail", 0)
    path = check_target(pathlib.Path(path))
    suffix = path.suffix.lower()
    if suffix not in _WRITERS:
        raise ValueError(f"path: the suffix {path.suffix!r} has no writer; use .gif (Pillow) or .mp4 (FFmpeg)")
    writer_name, needs = _WRITERS[suffix]
    require("matplotlib", "plot", "pendula.plot.animate")
    import matplotlib.pyplot as plt
    from matplotlib import animation

    if not animation.writers.is_available(writer_name):
        raise RuntimeError(f"writing {suffix} needs {needs}; a .gif needs nothing beyond matplotlib")

    if double is None:
        x, y = _bob(tr)
        t = np.asarray(tr.t, dtype=float)
        xm = ym = None
    else:
        xm, ym, x, y = double
        t = np.asarray(tr["time"].values, dtype=float)
    step = max(1, -(-t.size // max_frames))
    frames = np.arange(0, t.size, step)

    fig, ax = plt.subplots(figsize=(4, 4), dpi=dpi)
    reach = 1.15 * max(1.0, float(np.nanmax(np.hypot(x, y))) if x.size else 1.0)
    ax.set_xlim(-reach, reach)
    ax.set_ylim(-reach, reach)
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.plot([0.0], [0.0], "ks", ms=4)
    rod, = ax.plot([], [], "k-", lw=1.5)
    trace, = ax.plot([], [], "-", color="C0", lw=0.8, alpha=0.5)
    bob, = ax.plot([], [], "o", color="C3", ms=12)
    clock = ax.text(0.02, 0.96, "", transform=ax.transAxes, fontsize=10, va="top")
    slack = double is None and tr.r is not None

    def frame(i):
        xi, yi = x[i], y[i]
        if xm is None:
            rod.set_data([0.0, xi], [0.0, yi])
        else:
            rod.set_data([0.0, xm[i], xi], [0.0, ym[i], yi])
        if slack:
            rod.set_linestyle("--" if tr.r[i] < 1.0 - 1e-9 else "-")
        if trail:
            j = max(0, i - trail * step)
            trace.set_data(x[j:i + 1:step], y[j:i + 1:step])
        bob.set_data([xi], [yi])
        clock.set_text(f"t = {t[i]:.2f}")
        return rod, trace, bob, clock

    anim = animation.FuncAnimation(fig, frame, frames=frames, blit=False)
    try:
        # the writers choose the container by the file's suffix: encode to a
        # name of the right suffix in a private folder, then rename into place
        with tempfile.TemporaryDirectory(prefix=".pendula-", dir=path.parent) as d, atomic_path(path) as tmp:
            staged = pathlib.Path(d) / f"frames{suffix}"
            anim.save(staged, writer=writer_name, fps=fps, dpi=dpi)
            shutil.move(staged, tmp)
    finally:
        plt.close(fig)
    return path


def _bob(tr) -> tuple[np.ndarray, np.ndarray]:
    """The bob's position in units of the length, the pivot at the origin, y up."""
    if tr.x is not None and tr.y is not None:
        return np.asarray(tr.x, dtype=float), np.asarray(tr.y, dtype=float)
    th = np.asarray(tr.theta, dtype=float)
    return np.sin(th), -np.cos(th)


def _double_arms(ds):
    """The joint's and the lower end's positions (x1, y1, x2, y2) of a DoublePendulum.simulate Dataset,
    or None for anything else."""
    if not (hasattr(ds, "data_vars") and {"theta1", "theta2"} <= set(ds.data_vars) and "l1" in ds.attrs):
        return None
    l1, l2 = float(ds.attrs["l1"]), float(ds.attrs["l2"])
    th1, th2 = np.asarray(ds.theta1.values, dtype=float), np.asarray(ds.theta2.values, dtype=float)
    x1, y1 = l1 * np.sin(th1), -l1 * np.cos(th1)
    return x1, y1, x1 + l2 * np.sin(th2), y1 - l2 * np.cos(th2)


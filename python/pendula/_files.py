"""Writing output files: the scene header, and writes that are all or nothing.

Every file pendula writes goes through :func:`atomic_path`: the content goes
to a temporary name in the same folder and is renamed into place only when it
is complete, so a failure (a bad scene member, a full disk, Ctrl-C) never
leaves a partial or stale file under the real name.
"""

from __future__ import annotations

import contextlib
import csv
import os
import pathlib
import tempfile

import numpy as np

__all__ = ["scene_header", "atomic_path", "staging", "write_csv", "gallery_dir"]


def scene_header(scene) -> list[str]:
    """Comment lines recording the scene (its namelist and the effects it names)."""
    lines = ["# pendula scene:"] + ["#   " + ln for ln in scene.to_namelist().splitlines()]
    eff = ", ".join(scene.effects) or "none (conservative rigid pendulum: exact solution)"
    return lines + [f"# effects = {eff}"]


@contextlib.contextmanager
def atomic_path(path):
    """Yield a temporary path beside ``path``; rename it to ``path`` on success.

    On any exception the temporary file is removed and ``path`` is left as it
    was.  Write errors (a full disk) surface as OSError, never as a silent
    truncation.
    """
    path = pathlib.Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent)
    os.close(fd)
    tmp = pathlib.Path(tmp)
    try:
        yield tmp
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            tmp.unlink()
        raise


@contextlib.contextmanager
def staging(outdir):
    """Yield a fresh folder inside ``outdir``; on success move every file in it
    to ``outdir`` (each by an atomic rename), on failure delete it."""
    import shutil

    outdir = pathlib.Path(outdir)
    stage = pathlib.Path(tempfile.mkdtemp(prefix=".pendula-", dir=outdir))
    try:
        yield stage
        for f in sorted(stage.iterdir()):
            os.replace(f, outdir / f.name)
    finally:
        shutil.rmtree(stage, ignore_errors=True)


def write_csv(path, scene, columns: list[str], rows, notes: tuple = ()) -> pathlib.Path:
    """A table with the scene in its header, written atomically.

    A numeric array is written by numpy in one call (17 significant digits,
    enough to round-trip); lists of rows (which may hold words such as the
    regime) go through csv.  ``notes`` are extra comment lines after the header.
    """
    path = pathlib.Path(path)
    with atomic_path(path) as tmp, tmp.open("w", newline="") as fh:
        for ln in scene_header(scene):
            fh.write(ln + "\n")
        for ln in notes:
            fh.write("# " + ln + "\n")
        if isinstance(rows, np.ndarray):
            fh.write(",".join(columns) + "\n")
            np.savetxt(fh, rows, delimiter=",", fmt="%.17g")
        else:
            w = csv.writer(fh)
            w.writerow(columns)
            for r in rows:
                w.writerow([repr(float(x)) if not isinstance(x, str) else x for x in r])
        fh.flush()
        os.fsync(fh.fileno())
    return path


def gallery_dir():
    """The default gallery of scenes shipped with the package (data/scenes in the repository)."""
    from importlib.resources import files

    return files("pendula") / "scenes"

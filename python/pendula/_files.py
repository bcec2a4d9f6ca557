"""Writing output files: the scene header, and writes that are all or nothing.

Every file pendula writes goes through :func:`atomic_path` (or :func:`staging`
for a folder of files, :func:`open_text` and :func:`save_figure` on top of
it), one rule for all, the same as pendula-run's (kernel/glue/pendula_os.c):

* only a regular file (or a name not yet taken) is written or replaced; a
  device, FIFO, socket or folder under the name is refused with an OSError
  and left as it was (``/dev/full`` is never replaced by a file);
* a symbolic link under the name is replaced by the new file (as rename(2)
  does); the file it pointed to is never opened nor changed;
* the folder of a file must exist (FileNotFoundError otherwise); an output
  *folder* (``pendula run -o``, ``sweep(out=)``) is created with its missing
  parents, as ``mkdir -p`` does;
* the content goes to a fresh temporary name beside the target
  (``.NAME.XXXX.part``), is fsynced, and is renamed onto the target only when
  complete; on any exception -- a full disk, Ctrl-C, SIGTERM in the
  ``pendula`` command (see :func:`exit_on_sigterm`) -- the temporary file is
  removed and the target is left as it was;
* CSV numbers are written with 17 significant digits (``'%.17g'``), as
  pendula-run writes them, and column names are unique.
"""

from __future__ import annotations

import contextlib
import csv
import errno
import os
import pathlib
import stat
import tempfile

import numpy as np

__all__ = ["scene_header", "atomic_path", "staging", "write_csv", "gallery_dir", "check_target", "open_text",
           "save_figure", "fmt_real", "exit_on_sigterm"]


def check_target(path) -> pathlib.Path:
    """``path`` as a Path after the writer's checks: OSError (naming the path)
    when it names something other than a regular file, FileNotFoundError when
    its folder does not exist.  A symbolic link to a regular file (or a
    dangling one) is what gets replaced, by the rename: the file it points to
    is never written (pendula-run's rule, kernel/glue/pendula_os.c)."""
    path = pathlib.Path(path)
    try:
        st = os.stat(path)
    except FileNotFoundError:
        st = None
    if st is not None:
        if stat.S_ISDIR(st.st_mode):
            raise IsADirectoryError(errno.EISDIR, "is a folder, not a file", str(path))
        if not stat.S_ISREG(st.st_mode):
            raise OSError(errno.EINVAL, "not a regular file (a device, FIFO or socket is never written or "
                          "replaced)", str(path))
    parent = path.parent
    if not parent.is_dir():
        raise FileNotFoundError(errno.ENOENT, "the folder does not exist (pendula does not create it)",
                                str(parent))
    return path


def fmt_real(x) -> str:
    """A real as CSV text: 17 significant digits, as pendula-run writes it."""
    return "%.17g" % x


def _fsync(path) -> None:
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def exit_on_sigterm() -> None:
    """Make SIGTERM (and SIGHUP) raise SystemExit(128 + signal) in the main
    thread, so that every ``with atomic_path(...)`` removes its temporary file
    before the process ends (the ``pendula`` command calls this once)."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        return

    def handler(sig, frame):
        raise SystemExit(128 + sig)

    for sig in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, handler)


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
    path = check_target(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent)
    os.close(fd)
    tmp = pathlib.Path(tmp)
    try:
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)
        yield tmp
        _fsync(tmp)
        check_target(path)        # still a regular file (or absent) at the moment of the rename
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
    if not outdir.is_dir():
        if outdir.exists():
            raise NotADirectoryError(errno.ENOTDIR, "is not a folder", str(outdir))
    stage = pathlib.Path(tempfile.mkdtemp(prefix=".pendula-", dir=outdir))
    try:
        yield stage
        files = sorted(stage.iterdir())
        for f in files:
            check_target(outdir / f.name)
            _fsync(f)
        for f in files:
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
    if len(set(columns)) != len(columns):
        dup = sorted({c for c in columns if columns.count(c) > 1})
        raise ValueError(f"{path.name}: column name(s) {', '.join(dup)} given twice")
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
                w.writerow([fmt_real(float(x)) if not isinstance(x, str) else x for x in r])
        fh.flush()
        os.fsync(fh.fileno())
    return path


@contextlib.contextmanager
def open_text(path, newline=None):
    """A text file opened for writing through :func:`atomic_path`."""
    with atomic_path(path) as tmp, open(tmp, "w", newline=newline) as fh:
        yield fh


def save_figure(fig, path, **kw) -> pathlib.Path:
    """``fig.savefig`` through :func:`atomic_path` (the format from the real
    name's suffix): a figure is whole under its name, or absent."""
    path = pathlib.Path(path)
    fmt = kw.pop("format", None) or (path.suffix[1:] or "png")
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=fmt, **kw)
    return path


def gallery_dir():
    """The default gallery of scenes shipped with the package (data/scenes in the repository)."""
    from importlib.resources import files

    return files("pendula") / "scenes"

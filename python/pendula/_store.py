"""The sweep store: a Zarr (v3) group on disk that a sweep fills chunk by chunk.

Private: :func:`pendula.sweep` with ``out=`` is the public face.  Layout of
the folder ``out``::

    out/sweep.lock          held while a sweep writes (pid and host of the holder)
    out/sweep.zarr/         the Zarr v3 group, readable by xarray.open_zarr
        zarr.json           group attributes (CF) and consolidated metadata
        <axis>/             one coordinate array per sweep axis (and 'sample')
        <variable>/         the measure's variables and 'status'
        commits/cNNNNNN/    one completion record per finished chunk (a Zarr
                            group whose attributes hold its rows, shape,
                            coordinate checksum, and the checksums of its
                            files' bytes and of its decoded values)

The grid is cut along its first axis into chunks of whole rows; one sweep
chunk is one Zarr chunk of every variable, so a chunk is written as one
region, with no read-modify-write.  A chunk counts as done only when its
completion record exists and checks out: the data files are written, fsynced,
then the record is written to a temporary file, fsynced and renamed into
place.  A run killed at any moment leaves at worst a chunk without a record,
which the next run computes again.

When a run resumes, every recorded chunk is checked against the plan: its
record must name its rows, shape and coordinates, and its files' bytes (first:
a damaged file never reaches the decoder) and decoded values must match the
recorded SHA-256 checksums.  A chunk that fails (a truncated, emptied or
halved file, a file copied from another position, a damaged or misplaced
record) is named in a :class:`SweepStoreWarning` and computed again.

Only one sweep writes a store at a time: the lock file ``out/sweep.lock`` is
taken with ``flock`` (atomic; released by the kernel when its holder dies, so
the lock of a dead process is taken over) and holds the holder's pid and host;
a second sweep on the same folder fails at once with :class:`StoreBusyError`
naming the store and the holder.  Temporary names carry the writer's pid.
The lock file is pendula's own: a symbolic link under its name is replaced
(the file it points to is never opened), a FIFO, device or folder under it is
refused and left as it was.

Only a pendula store is ever changed: ``out/sweep.zarr`` must be a folder
whose ``zarr.json`` (read as JSON, before Zarr opens anything) is a Zarr v3
group carrying this sweep's identity.  Anything else there (a user's folder,
a file, a store of a newer Zarr format, a store of another sweep, a
``zarr.json`` that cannot be read) is refused with a ValueError naming it and
left exactly as it was; only a store that proves to be this sweep's and is
damaged inside is built again.
"""

from __future__ import annotations

import errno
import hashlib
import json
import os
import pathlib
import shutil
import socket
import time
import warnings
from dataclasses import dataclass, field

import numpy as np

from ._optional import require

#: the store's folder and lock file names inside ``out``
STORE_NAME = "sweep.zarr"
LOCK_NAME = "sweep.lock"
COMMITS = "commits"


class StoreBusyError(OSError):
    """Another sweep holds the store's lock (errno EBUSY; the message names the store and the holder)."""


class SweepStoreWarning(UserWarning):
    """A chunk of a sweep store failed its check (or the store was rebuilt) and is computed again."""


@dataclass
class Variable:
    """One variable of the store: dimension names, dtype, CF attributes, Zarr fill value."""

    dims: tuple
    dtype: np.dtype
    attrs: dict
    fill_value: object


@dataclass
class Layout:
    """Everything the store holds, apart from the values.

    ``axes`` are the sweep axes in order (the first is cut into chunks of
    ``rows`` rows), ``coords`` every coordinate (axes and extra ones such as
    'sample') with its attributes, ``identity`` the text that names the sweep
    (a store holding another identity is refused), ``attrs`` the group's
    attributes.
    """

    axes: dict
    coords: dict            # name -> (values, attrs)
    variables: dict         # name -> Variable
    rows: int
    identity: str
    attrs: dict = field(default_factory=dict)

    @property
    def first(self) -> str:
        return next(iter(self.axes))

    @property
    def nchunks(self) -> int:
        return -(-len(self.axes[self.first]) // self.rows)

    def rows_of(self, i: int) -> tuple[int, int]:
        n0 = len(self.axes[self.first])
        return i * self.rows, min((i + 1) * self.rows, n0)

    def shape_of(self, name: str, i: int | None = None) -> tuple:
        """Full shape of a variable, or of its chunk i."""
        shape = []
        for d in self.variables[name].dims:
            if d == self.first and i is not None:
                lo, hi = self.rows_of(i)
                shape.append(hi - lo)
            else:
                shape.append(len(self.coords[d][0]))
        return tuple(shape)

    def chunk_shape(self, name: str) -> tuple:
        return tuple(self.rows if d == self.first else len(self.coords[d][0])
                     for d in self.variables[name].dims)

    def grid_shape(self, i: int) -> list:
        """Chunk i's shape on the sweep axes."""
        lo, hi = self.rows_of(i)
        return [hi - lo] + [len(v) for v in list(self.axes.values())[1:]]

    def coords_digest(self, i: int) -> str:
        """SHA-256 of chunk i's coordinates (its rows of the first axis, every other coordinate)."""
        lo, hi = self.rows_of(i)
        h = hashlib.sha256()
        for name, (vals, _) in self.coords.items():
            v = np.ascontiguousarray(vals[lo:hi] if name == self.first else vals)
            h.update(name.encode() + b"\0" + str(v.dtype).encode() + b"\0" + v.tobytes())
        return h.hexdigest()


def _digest(a: np.ndarray) -> str:
    a = np.ascontiguousarray(a)
    return hashlib.sha256(str(a.dtype).encode() + b"\0" + repr(a.shape).encode() + b"\0" + a.tobytes()).hexdigest()


def _file_digest(path: pathlib.Path) -> str | None:
    """SHA-256 of a file's bytes, None when there is no file."""
    try:
        return hashlib.sha256(path.read_bytes()).hexdigest()
    except FileNotFoundError:
        return None


def _fsync_path(path: pathlib.Path, directory: bool = False) -> None:
    try:
        fd = os.open(path, os.O_RDONLY | (os.O_DIRECTORY if directory else 0))
    except FileNotFoundError:
        return
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _write_json_atomic(path: pathlib.Path, obj) -> None:
    """Write JSON to a temporary file named for this writer, fsync it, rename it into place, fsync the folder."""
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        with open(tmp, "w") as fh:
            json.dump(obj, fh, sort_keys=True)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    _fsync_path(path.parent, directory=True)


def _jsonable(attrs: dict) -> dict:
    """Attributes as Zarr stores them (JSON: arrays become lists)."""
    return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in attrs.items()}


class StoreLock:
    """The store's lock: ``flock`` on ``out/sweep.lock``, which holds the holder's pid and host.

    ``flock`` is atomic and the kernel drops it when its holder dies, so a lock
    left by a dead process (a stale lock) is taken over by the next sweep; the
    pid written in the file names the holder in the error a second sweep gets.
    """

    def __init__(self, path: pathlib.Path, store: pathlib.Path):
        self.path = pathlib.Path(path)
        self.store = store
        self.fd = None
        self.previous = None      # the holder recorded in a lock taken over, if any

    def acquire(self) -> None:
        import fcntl

        import stat

        for _ in range(100):
            try:
                # never through a link (O_NOFOLLOW), never waiting on a FIFO (O_NONBLOCK)
                fd = os.open(self.path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC | os.O_NOFOLLOW | os.O_NONBLOCK,
                             0o644)
            except OSError as exc:
                if exc.errno == errno.ELOOP and os.path.islink(self.path):
                    os.unlink(self.path)    # a link under the lock's name is replaced; its target left alone
                    continue
                if exc.errno in (errno.EISDIR, errno.ENXIO):
                    raise OSError(exc.errno, "the store's lock file name is taken by something other than a "
                                  "regular file; it is left as it was", str(self.path)) from None
                raise
            if not stat.S_ISREG(os.fstat(fd).st_mode):
                os.close(fd)
                raise OSError(errno.EINVAL, "the store's lock file name is taken by a FIFO, device or socket "
                              "(never written or replaced); it is left as it was", str(self.path))
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError as exc:
                # the holder writes its pid and host just after taking the flock: give it a moment
                holder = ""
                for _wait in range(50):
                    holder = os.pread(fd, 200, 0).decode(errors="replace").strip()
                    if holder:
                        break
                    time.sleep(0.02)
                holder = holder or "unknown"
                os.close(fd)
                if exc.errno not in (errno.EWOULDBLOCK, errno.EAGAIN, errno.EACCES):
                    raise
                pid, _, host = holder.partition(" ")
                raise StoreBusyError(errno.EBUSY,
                                     f"sweep store {self.store} is in use by another sweep (pid {pid} on "
                                     f"{host or 'an unknown host'}, lock file {self.path}); wait for it to end "
                                     "or give another 'out'", str(self.store)) from None
            # the previous holder unlinks the file when it releases: make sure ours is the one on disk
            try:
                same = os.stat(self.path).st_ino == os.fstat(fd).st_ino
            except FileNotFoundError:
                same = False
            if not same:
                os.close(fd)
                continue
            # a holder written in the file whose flock is gone died without releasing: a stale lock
            self.previous = os.pread(fd, 200, 0).decode(errors="replace").strip() or None
            os.ftruncate(fd, 0)
            os.pwrite(fd, f"{os.getpid()} {socket.gethostname()}\n".encode(), 0)
            os.fsync(fd)
            self.fd = fd
            return
        raise StoreBusyError(errno.EBUSY, f"sweep store {self.store}: could not take its lock {self.path}",
                             str(self.store))

    def release(self) -> None:
        if self.fd is None:
            return
        try:
            self.path.unlink(missing_ok=True)    # unlinked while still held: no one can take a dead file
        finally:
            os.close(self.fd)
            self.fd = None


class SweepStore:
    """A sweep's Zarr store in the folder ``out`` (see the module's docstring).

    Use as a context manager: entering takes the lock, removes the temporaries
    of dead writers, creates the store or checks the one there, and sets
    ``done`` (the chunks already complete and sound); leaving releases the lock.
    """

    def __init__(self, out, layout: Layout):
        self.out = pathlib.Path(out)
        self.layout = layout
        self.path = self.out / STORE_NAME
        self.lock = StoreLock(self.out / LOCK_NAME, self.path)
        self.done: set[int] = set()
        self._group = None

    # -- opening ---------------------------------------------------------------------------
    def __enter__(self):
        self.open()
        return self

    def __exit__(self, *exc):
        self.close()

    def open(self) -> None:
        if self.out.exists() and not self.out.is_dir():
            raise NotADirectoryError(errno.ENOTDIR, f"parameter 'out': {self.out} is not a folder", str(self.out))
        self.out.mkdir(parents=True, exist_ok=True)
        self.lock.acquire()
        try:
            self._remove_temporaries()
            self._open_or_create()
            self.done = self._verify()
        except BaseException:
            self.lock.release()
            raise

    def close(self) -> None:
        self._group = None
        self.lock.release()

    def _warn(self, text: str, stacklevel: int = 5) -> None:
        # stacklevel: the frames from here up to the caller of pendula.sweep
        warnings.warn(f"sweep store {self.path}: {text}", SweepStoreWarning, stacklevel=stacklevel)

    def _remove_temporaries(self) -> None:
        """Temporaries of writers that died (we hold the lock: no live writer has any)."""
        for p in self.out.glob(f".{STORE_NAME}.*"):
            shutil.rmtree(p, ignore_errors=True) if p.is_dir() else p.unlink(missing_ok=True)
        if self.path.is_dir():
            for root, _dirs, files in os.walk(self.path):
                for f in files:
                    if f.endswith(".partial") or (f.startswith(".") and f.endswith(".tmp")):
                        pathlib.Path(root, f).unlink(missing_ok=True)

    def _open_or_create(self) -> None:
        zarr = require("zarr", "sweep", "a stored sweep (pendula.sweep(out=...))")

        if not os.path.lexists(self.path):
            self._create()
            return
        # whose is it?  Read before Zarr opens anything: only this sweep's store is ever changed
        identity = self._identity_on_disk()
        if identity != self.layout.identity:
            raise ValueError(f"parameter 'out': {self.out} holds a different sweep; use another folder")
        try:
            g = zarr.open_group(self.path, mode="r+", use_consolidated=False)
        except Exception as exc:   # noqa: BLE001 - this sweep's store, damaged
            self._rebuild(f"its metadata cannot be read ({type(exc).__name__}: {exc})")
            return
        bad = self._check_arrays(g)
        if bad:
            self._rebuild(bad)
            return
        self._group = g
        self._check_commits(g)
        self._check_consolidated(g)
        for name, (vals, _) in self.layout.coords.items():
            try:
                ok = np.array_equal(g[name][...], vals)
            except Exception:   # noqa: BLE001 - a damaged coordinate file
                ok = False
            if not ok:
                self._warn(f"coordinate '{name}' is damaged; written again from the plan")
                g[name][...] = vals

    def _identity_on_disk(self) -> str:
        """The identity recorded in ``sweep.zarr/zarr.json``; a ValueError naming the path (which is
        left as it was) when the thing there is not a pendula sweep store a Zarr v3 reader can open."""
        def refuse(why: str):
            return ValueError(f"parameter 'out': {self.path} is not a pendula sweep store ({why}); it is left "
                              "as it was: move it away or give another 'out'")
        if not self.path.is_dir():          # a link to a folder (a store on another disk) is followed
            raise refuse("not a folder")
        meta = self.path / "zarr.json"
        if not meta.is_file():
            raise refuse("no zarr.json")
        try:
            with open(meta, "rb") as fh:
                doc = json.loads(fh.read(1 << 24))      # pendula's group metadata is a few kB
        except (OSError, ValueError) as exc:
            raise refuse(f"its zarr.json cannot be read: {type(exc).__name__}") from None
        if not isinstance(doc, dict) or doc.get("zarr_format") != 3 or doc.get("node_type") != "group":
            fmt = doc.get("zarr_format") if isinstance(doc, dict) else None
            raise refuse(f"not a Zarr v3 group (zarr_format {fmt!r})")
        identity = (doc.get("attributes") or {}).get("pendula_sweep") if isinstance(doc.get("attributes"), dict) \
            else None
        if not isinstance(identity, str):
            raise refuse("no pendula sweep identity in its attributes")
        return identity

    def _check_consolidated(self, g) -> None:
        """The consolidated metadata (what readers such as xarray use) must say what the arrays' own say."""
        import zarr

        def text(a):
            return json.dumps(a.metadata.to_dict(), sort_keys=True, default=str)
        names = list(self.layout.coords) + list(self.layout.variables)
        try:
            gc = zarr.open_group(self.path, mode="r", use_consolidated=True)
            same = all(text(gc[n]) == text(g[n]) for n in names)
        except Exception:   # noqa: BLE001 - unreadable consolidated metadata
            same = False
        if not same:
            self._warn("its consolidated metadata is damaged; written again", stacklevel=6)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                zarr.consolidate_metadata(self.path)

    def _check_commits(self, g) -> None:
        """The folder of completion records: when it is missing, or something else lies under its name,
        it is built again, empty (the data files are kept, but no chunk can be shown complete without
        its record: each is computed again, and the warning says so)."""
        path = self.path / COMMITS
        if path.is_dir() and not path.is_symlink() and (path / "zarr.json").is_file():
            return
        what = "is missing" if not os.path.lexists(path) else "is not a folder of records"
        self._warn(f"its folder of completion records '{COMMITS}' {what}; it is built again, and the chunks "
                   "it recorded cannot be shown complete: every chunk is computed again", stacklevel=6)
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path)
        elif os.path.lexists(path):
            path.unlink()
        g.create_group(COMMITS, attributes={"about": "one completion record per finished chunk"})

    def _check_arrays(self, g) -> str | None:
        lay = self.layout
        for name, (vals, _) in lay.coords.items():
            try:
                a = g[name]
            except Exception as exc:   # noqa: BLE001
                return f"coordinate '{name}' cannot be opened ({type(exc).__name__})"
            if a.shape != np.shape(vals):
                return f"coordinate '{name}' has shape {a.shape}, the plan {np.shape(vals)}"
        for name, var in lay.variables.items():
            try:
                a = g[name]
            except Exception as exc:   # noqa: BLE001
                return f"variable '{name}' cannot be opened ({type(exc).__name__})"
            if a.shape != lay.shape_of(name) or a.dtype != var.dtype or a.chunks != lay.chunk_shape(name):
                return f"variable '{name}' has shape {a.shape}, dtype {a.dtype}, chunks {a.chunks}: not the plan's"
        return None

    def _rebuild(self, why: str) -> None:
        self._warn(f"{why}; the store is built again and every chunk computed again", stacklevel=6)
        aside = self.out / f".{STORE_NAME}.damaged.{os.getpid()}"
        os.replace(self.path, aside)
        shutil.rmtree(aside, ignore_errors=True)
        self._create()

    def _create(self) -> None:
        """Build the empty store under a temporary name, fsync it, rename it into place."""
        zarr = require("zarr", "sweep", "a stored sweep (pendula.sweep(out=...))")
        from zarr.codecs import BloscCodec

        lay = self.layout
        tmp = self.out / f".{STORE_NAME}.{os.getpid()}.tmp"
        shutil.rmtree(tmp, ignore_errors=True)
        attrs = dict(lay.attrs)
        attrs["pendula_sweep"] = lay.identity
        try:
            g = zarr.open_group(tmp, mode="w", zarr_format=3, attributes=_jsonable(attrs))
            comp = BloscCodec(cname="zstd", clevel=5, shuffle="shuffle")
            for name, (vals, cattrs) in lay.coords.items():
                vals = np.asarray(vals)
                a = g.create_array(name, shape=vals.shape, dtype=vals.dtype, chunks=vals.shape or (1,),
                                   dimension_names=(name,), attributes=_jsonable(cattrs), compressors=comp)
                a[...] = vals
            for name, var in lay.variables.items():
                g.create_array(name, shape=lay.shape_of(name), dtype=var.dtype, chunks=lay.chunk_shape(name),
                               dimension_names=var.dims, attributes=_jsonable(var.attrs), fill_value=var.fill_value,
                               compressors=comp)
            g.create_group(COMMITS, attributes={"about": "one completion record per finished chunk"})
            with warnings.catch_warnings():
                # zarr says consolidated metadata is not (yet) in the v3 specification; xarray reads it
                warnings.simplefilter("ignore")
                zarr.consolidate_metadata(tmp)
            for root, dirs, files in os.walk(tmp):
                for f in files:
                    _fsync_path(pathlib.Path(root, f))
                _fsync_path(pathlib.Path(root), directory=True)
            os.replace(tmp, self.path)
        except BaseException:
            shutil.rmtree(tmp, ignore_errors=True)   # a failed build (a full disk, Ctrl-C) leaves nothing
            raise
        _fsync_path(self.out, directory=True)
        self._group = zarr.open_group(self.path, mode="r+", use_consolidated=False)

    # -- chunks ----------------------------------------------------------------------------
    def chunk_files(self, name: str, i: int) -> pathlib.Path:
        """The file of variable ``name``'s chunk i (Zarr v3 default chunk keys)."""
        nd = len(self.layout.variables[name].dims)
        return self.path.joinpath(name, "c", str(i), *(["0"] * (nd - 1)))

    def _record_path(self, i: int) -> pathlib.Path:
        return self.path / COMMITS / f"c{i:06d}" / "zarr.json"

    def _describe(self, i: int) -> str:
        lo, hi = self.layout.rows_of(i)
        return f"chunk {i} (rows {lo}..{hi - 1} of '{self.layout.first}')"

    def _verify(self) -> set[int]:
        """The chunks whose records and data check out; the others are named and forgotten."""
        done = set()
        for i in range(self.layout.nchunks):
            rec = self._record_path(i)
            if not rec.exists():
                continue
            why = self._check_chunk(i, rec)
            if why is None:
                done.add(i)
            else:
                self._warn(f"{self._describe(i)} {why}; it is computed again")
                self._forget(i)
        return done

    def _check_chunk(self, i: int, rec: pathlib.Path) -> str | None:
        lay = self.layout
        lo, hi = lay.rows_of(i)
        try:
            meta = json.loads(rec.read_text())
            r = meta["attributes"]
            recorded = (r["chunk"], list(r["rows"]), r["coords_sha256"], dict(r["sha256"]), list(r["shape"]),
                        dict(r["files_sha256"]))
        except Exception as exc:   # noqa: BLE001 - any damage to the record
            return f"has an unreadable completion record {rec} ({type(exc).__name__})"
        if recorded[0] != i or recorded[1] != [lo, hi]:
            return f"has the completion record of chunk {recorded[0]} (rows {recorded[1]}) in {rec}"
        if recorded[4] != lay.grid_shape(i):
            return f"was completed with shape {recorded[4]}, the plan {lay.grid_shape(i)} ({rec})"
        if recorded[2] != lay.coords_digest(i):
            return f"was completed for other coordinates than the plan's ({rec})"
        for name in lay.variables:
            f = self.chunk_files(name, i)
            want = recorded[3].get(name)
            # the file's bytes first: a damaged compressed file is never handed to the decoder (Blosc may
            # decode a truncated frame without an error, from whatever lies past its end)
            if _file_digest(f) != recorded[5].get(name, ""):
                return (f"does not match the checksum recorded when it was completed ({f}: "
                        f"{'missing' if not f.exists() else f'{f.stat().st_size} bytes'})")
            try:
                a = self._group[name][lo:hi]
            except Exception as exc:   # noqa: BLE001 - truncated, emptied, garbled chunk files
                return f"cannot be read from {f} ({type(exc).__name__}: {exc})"
            if a.shape != lay.shape_of(name, i):
                return f"has shape {a.shape} in {f}, the plan {lay.shape_of(name, i)}"
            if _digest(a) != want:
                return f"does not match the checksum recorded when it was completed ({f})"
        return None

    def _forget(self, i: int) -> None:
        rec = self._record_path(i)
        rec.unlink(missing_ok=True)
        shutil.rmtree(rec.parent, ignore_errors=True)

    def write_chunk(self, i: int, arrays: dict) -> None:
        """Write chunk i (arrays by variable name, rows of the chunk only) and commit it."""
        lay = self.layout
        lo, hi = lay.rows_of(i)
        self._forget(i)
        sums = {}
        for name, var in lay.variables.items():
            a = np.ascontiguousarray(arrays[name], dtype=var.dtype)
            if a.shape != lay.shape_of(name, i):
                raise ValueError(f"chunk {i} of '{name}' has shape {a.shape}, the plan {lay.shape_of(name, i)}")
            self._group[name][lo:hi] = a
            sums[name] = _digest(a)
        files = {}
        for name in lay.variables:                  # the data reach the disk before the record does
            f = self.chunk_files(name, i)
            files[name] = _file_digest(f)           # None: Zarr wrote no file (every value the fill value)
            _fsync_path(f)
            _fsync_path(f.parent, directory=True)
        rec = self._record_path(i)
        rec.parent.mkdir(exist_ok=True)
        record = {"chunk": i, "rows": [lo, hi], "shape": lay.grid_shape(i),
                  "coords_sha256": lay.coords_digest(i), "sha256": sums, "files_sha256": files,
                  "writer_pid": os.getpid()}
        _write_json_atomic(rec, {"zarr_format": 3, "node_type": "group", "attributes": record})
        _fsync_path(rec.parent.parent, directory=True)
        self.done.add(i)

    def dataset(self):
        """The store as a lazy (dask-backed) xarray Dataset, with the layout's attributes on its variables."""
        xr = require("xarray", "sweep", "pendula.sweep")

        # the arrays' own metadata (checked on opening), not the consolidated copy
        ds = xr.open_zarr(self.path.resolve(), consolidated=False)
        for name, var in self.layout.variables.items():
            ds[name].attrs = dict(var.attrs)
        for name, (_, cattrs) in self.layout.coords.items():
            ds[name].attrs = dict(cattrs)
        ds.attrs = {}
        return ds

"""The sweep store (out/sweep.zarr): a Zarr v3 store with CF attributes,
bit-identical to the in-memory run for every measure, one writer at a time
(a lock naming its holder), and a resume that checks every chunk against the
plan: each kind of damage is named in a warning and computed again."""

import json
import os
import pathlib
import shutil
import subprocess
import sys
import threading
import time
import warnings

import numpy as np
import pytest

import pendula
from pendula import Scene

xr = pytest.importorskip("xarray")
zarr = pytest.importorskip("zarr")
from pendula._store import StoreBusyError, SweepStoreWarning  # noqa: E402

# 24 x 2 final-well grid, 2 rows per chunk: 12 chunks whose contents differ
OVER = {"v0": np.linspace(0.0, 4.0, 24), "damping": [0.05, 0.2]}
KW = dict(over=OVER, measure="final_well", chunk_points=4, rtol=1e-8, atol=1e-10)
SCENE = Scene(damping=0.1)


@pytest.fixture(scope="module")
def reference():
    return pendula.sweep(SCENE, **KW)


@pytest.fixture
def complete(tmp_path, reference):
    """A complete store, and the in-memory result it must equal."""
    out = tmp_path / "o"
    ds = pendula.sweep(SCENE, out=out, **KW)
    assert ds.identical(reference)
    return out, reference


def resume_warns(out, reference, match):
    """Resume: the damage is named in a SweepStoreWarning, the result is the in-memory one,
    and the store is sound again (a second resume is silent)."""
    with pytest.warns(SweepStoreWarning, match=match) as rec:
        ds = pendula.sweep(SCENE, out=out, **KW)
    assert ds.identical(reference)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        again = pendula.sweep(SCENE, out=out, **KW)
    assert again.identical(reference)
    return [str(w.message) for w in rec]


# --- the store's form ---------------------------------------------------------------------

def test_store_is_zarr_v3_with_cf_attributes_and_compression(complete):
    out, ref = complete
    g = zarr.open_group(out / "sweep.zarr", mode="r")
    assert g.metadata.zarr_format == 3
    assert g.attrs["Conventions"].startswith("CF-")
    for name in ("well", "t_decided", "v0", "damping"):
        a = g[name]
        assert a.attrs["units"] and a.attrs["long_name"], name
        assert a.compressors, name     # compressed (Blosc zstd)
    st = g["status"]
    codes = st.attrs["flag_values"]
    assert codes == sorted(int(k) for k in json.loads(g.attrs["status_codes"]))
    assert len(st.attrs["flag_meanings"].split()) == len(codes)
    assert g["well"].attrs["units"] == "1" and g["t_decided"].attrs["units"] == "s"
    assert g["v0"].attrs["units"] == "rad s-1" and g["damping"].attrs["units"] == "s-1"
    # one sweep chunk is one Zarr chunk of each variable
    assert g["well"].chunks == (2, 2) and g["status"].dtype == np.int32


def test_store_opens_in_plain_xarray_without_warnings(complete):
    out, ref = complete
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ds = xr.open_zarr(out / "sweep.zarr")
    np.testing.assert_array_equal(ds.well.values, ref.well.values)
    assert ds.status.dtype == np.int32


def test_store_compresses(tmp_path):
    # a 200 x 50 map: the status chunks (mostly 0) must take far less than their raw size
    out = tmp_path / "c"
    pendula.sweep(SCENE, over={"v0": np.linspace(0, 4, 200), "damping": np.linspace(0.1, 0.3, 50)},
                  measure="final_well", out=out, chunk_points=10000, rtol=1e-6, atol=1e-8)
    f = out / "sweep.zarr" / "status" / "c" / "0" / "0"
    assert f.stat().st_size < 0.2 * 200 * 50 * 4


@pytest.mark.parametrize("measure,over,kw", [
    ("final_well", {"v0": np.linspace(0, 4, 7), "damping": [0.1, 0.3]}, {}),
    ("locked", {"v0": [0.0, 2.0, 6.0]}, {"t_max": 100.0}),
    ("mean_velocity", {"torque": [1.1, 1.5, 2.0]}, {"transient": 20.0, "t_max": 50.0}),
    ("poincare", {"drive_amplitude": [0.9, 1.2, 1.5]}, {"transient": 30.0, "samples": 3}),
    ("lyapunov", {"drive_amplitude": [0.9, 1.5]}, {"transient": 20.0, "t_max": 60.0}),
])
def test_store_bit_identical_to_in_memory_for_every_measure(tmp_path, measure, over, kw):
    s = Scene(damping=0.5 if measure in ("poincare", "lyapunov") else 0.1, torque=0.5 if measure == "locked" else 0.0,
              drive_frequency=2 / 3 if measure in ("poincare", "lyapunov") else 0.0,
              drive_amplitude=0.9 if measure in ("poincare", "lyapunov") else 0.0)
    mem = pendula.sweep(s, over=over, measure=measure, chunk_points=2, **kw)
    disk = pendula.sweep(s, over=over, measure=measure, chunk_points=2, out=tmp_path / measure, **kw)
    assert disk.identical(mem)
    again = pendula.sweep(s, over=over, measure=measure, chunk_points=2, out=tmp_path / measure, **kw)
    assert again.identical(mem)
    exported = tmp_path / f"{measure}.nc"
    disk.to_netcdf(exported, engine="scipy")          # NetCDF stays as an export
    back = xr.open_dataset(exported, engine="scipy").load()
    for v in mem.data_vars:
        np.testing.assert_array_equal(back[v].values, mem[v].values)


def test_store_of_another_sweep_is_refused(complete):
    out, _ = complete
    with pytest.raises(ValueError, match="different sweep"):
        pendula.sweep(SCENE, out=out, **{**KW, "rtol": 1e-7})


def test_out_that_is_a_file_is_refused(tmp_path):
    f = tmp_path / "f"
    f.write_text("x")
    with pytest.raises(NotADirectoryError, match="out"):
        pendula.sweep(SCENE, out=f, **KW)


# --- one writer at a time ---------------------------------------------------------------------

HOLD = """
import sys, time
from pendula._store import StoreLock
import pathlib
lock = StoreLock(pathlib.Path(sys.argv[1]) / "sweep.lock", pathlib.Path(sys.argv[1]) / "sweep.zarr")
lock.acquire()
print("held", flush=True)
time.sleep(120)
"""


def test_store_in_use_is_refused_naming_store_and_holder_then_stale_lock_taken_over(tmp_path, reference):
    out = tmp_path / "o"
    out.mkdir()
    holder = subprocess.Popen([sys.executable, "-c", HOLD, str(out)], stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "held"
        with pytest.raises(StoreBusyError) as err:
            pendula.sweep(SCENE, out=out, **KW)
        msg = str(err.value)
        assert str(out / "sweep.zarr") in msg and f"pid {holder.pid}" in msg, msg
        assert not (out / "sweep.zarr").exists()       # the refused sweep wrote nothing
    finally:
        holder.kill()
        holder.wait()
        holder.stdout.close()
    # the holder died without releasing: its lock file (with its pid) is stale and taken over
    assert str(holder.pid) in (out / "sweep.lock").read_text()
    ds = pendula.sweep(SCENE, out=out, **KW)
    assert ds.identical(reference)
    assert not (out / "sweep.lock").exists()


def test_two_sweeps_on_the_same_out_second_refused_first_completes(tmp_path):
    over = {"v0": np.linspace(0.0, 4.0, 60), "damping": [0.05, 0.1, 0.2]}
    kw = dict(over=over, measure="final_well", chunk_points=3, rtol=1e-10, atol=1e-12, threads=1)
    out = tmp_path / "o"
    result = {}

    def first():
        try:
            result["ds"] = pendula.sweep(SCENE, out=out, **kw)
        except BaseException as exc:   # reported below
            result["exc"] = exc
    t = threading.Thread(target=first)
    t.start()
    t0 = time.time()
    while not (out / "sweep.lock").exists() and t.is_alive() and time.time() - t0 < 60:
        time.sleep(0.005)
    if t.is_alive():
        with pytest.raises(StoreBusyError, match=f"pid {os.getpid()}"):
            pendula.sweep(SCENE, out=out, **kw)
    t.join(120)
    assert "exc" not in result, result.get("exc")
    assert result["ds"].identical(pendula.sweep(SCENE, **kw))
    assert not [p for p in out.rglob("*") if p.name.endswith((".tmp", ".partial"))]


# --- damage found on resume -----------------------------------------------------------------

def chunk_file(out, var, i):
    return out / "sweep.zarr" / var / "c" / str(i) / "0"


def test_resume_truncated_chunk_is_named_and_recomputed(complete):
    out, ref = complete
    f = chunk_file(out, "well", 3)
    with open(f, "r+b") as fh:
        fh.truncate(5)
    msgs = resume_warns(out, ref, "chunk 3 ")
    assert any(str(f) in m for m in msgs), msgs


def test_resume_emptied_chunk_is_named_and_recomputed(complete):
    out, ref = complete
    f = chunk_file(out, "t_decided", 5)
    f.write_bytes(b"")
    msgs = resume_warns(out, ref, "chunk 5 ")
    assert any(str(f) in m for m in msgs), msgs


def test_resume_halved_chunk_is_named_and_recomputed(complete):
    out, ref = complete
    f = chunk_file(out, "status", 7)
    b = f.read_bytes()
    f.write_bytes(b[: len(b) // 2])
    resume_warns(out, ref, "chunk 7 .*status")


def test_resume_chunk_copied_from_another_position_is_named_and_recomputed(complete):
    out, ref = complete
    src, dst = chunk_file(out, "well", 10), chunk_file(out, "well", 1)
    assert src.read_bytes() != dst.read_bytes()       # they hold different wells
    shutil.copyfile(src, dst)
    msgs = resume_warns(out, ref, "chunk 1 .*checksum")
    assert any(str(dst) in m for m in msgs), msgs


def test_resume_deleted_chunk_file_is_named_and_recomputed(complete):
    out, ref = complete
    chunk_file(out, "well", 11).unlink()
    resume_warns(out, ref, "chunk 11 ")


def test_resume_completion_record_copied_from_another_chunk_is_named_and_recomputed(complete):
    out, ref = complete
    commits = out / "sweep.zarr" / "commits"
    shutil.copyfile(commits / "c000008" / "zarr.json", commits / "c000002" / "zarr.json")
    resume_warns(out, ref, "chunk 2 .*record of chunk 8")


def test_resume_garbled_completion_record_is_named_and_recomputed(complete):
    out, ref = complete
    rec = out / "sweep.zarr" / "commits" / "c000004" / "zarr.json"
    rec.write_text(rec.read_text()[:40])
    resume_warns(out, ref, "chunk 4 .*unreadable completion record")


def test_resume_damaged_coordinate_is_rewritten(complete):
    out, ref = complete
    (out / "sweep.zarr" / "v0" / "c" / "0").write_bytes(b"\0" * 7)
    resume_warns(out, ref, "coordinate 'v0'")


def test_resume_unreadable_store_metadata_rebuilds_the_store(complete):
    out, ref = complete
    (out / "sweep.zarr" / "well" / "zarr.json").write_text("{")
    resume_warns(out, ref, "built again")


def test_resume_damaged_consolidated_metadata_is_written_again(complete):
    out, ref = complete
    p = out / "sweep.zarr" / "zarr.json"
    meta = json.loads(p.read_text())
    meta["consolidated_metadata"]["metadata"]["well"]["shape"] = [25, 2]
    p.write_text(json.dumps(meta))
    resume_warns(out, ref, "consolidated metadata")
    assert xr.open_zarr(out / "sweep.zarr").well.shape == (24, 2)


def test_resume_removes_temporaries_of_a_dead_writer(complete):
    out, ref = complete
    (out / ".sweep.zarr.999999.tmp").mkdir()
    partial = chunk_file(out, "well", 0).with_suffix(".0123abcd.partial")
    partial.write_bytes(b"partial")
    rec_tmp = out / "sweep.zarr" / "commits" / "c000000" / ".zarr.json.999999.tmp"
    rec_tmp.write_text("{")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ds = pendula.sweep(SCENE, out=out, **KW)
    assert ds.identical(ref)
    assert not (out / ".sweep.zarr.999999.tmp").exists() and not partial.exists() and not rec_tmp.exists()


def test_chunk_data_and_record_fsynced_before_the_commit_rename(tmp_path, monkeypatch, reference):
    """Each completion record is renamed into place only after the chunk's data
    files and the record's temporary file were fsynced."""
    import pendula._store as store
    events = []
    real_fsync, real_replace = os.fsync, os.replace

    def fsync(fd):
        events.append(("fsync", os.readlink(f"/proc/self/fd/{fd}")))
        return real_fsync(fd)

    def replace(a, b):
        events.append(("replace", str(a), str(b)))
        return real_replace(a, b)
    monkeypatch.setattr(store.os, "fsync", fsync)
    monkeypatch.setattr(store.os, "replace", replace)
    out = tmp_path / "o"
    ds = pendula.sweep(SCENE, out=out, **KW)
    assert ds.identical(reference)
    root = str((out / "sweep.zarr").resolve())
    commits = [k for k, e in enumerate(events) if e[0] == "replace" and "/commits/c" in e[2]]
    assert len(commits) == 12
    for k in commits:
        i = int(pathlib.Path(events[k][2]).parent.name[1:])
        synced = {e[1] for e in events[:k] if e[0] == "fsync"}
        for var in ("well", "t_decided", "status"):
            assert f"{root}/{var}/c/{i}/0" in synced, (i, var)
        assert str(pathlib.Path(events[k][1]).resolve()) in synced


def test_two_cli_sweeps_on_the_same_output_second_exits_5_naming_the_store(tmp_path):
    """The second `pendula sweep` on an output folder in use exits 5 with one line naming the store and
    the first sweep's pid, and touches nothing; the first, killed afterwards, resumes to the right result."""
    scene = tmp_path / "s.nml"
    scene.write_text("&scene\n damping = 0.1\n grid = 'v0', 'damping'\n grid1_range = 0, 4, 60\n"
                     " grid2 = 0.05, 0.1, 0.2\n measure = 'final_well'\n rtol = 1e-12\n atol = 1e-14\n/\n")
    for attempt in range(3):     # on a loaded machine the first may end before the second starts: again
        out = tmp_path / f"o{attempt}"
        cmd = [sys.executable, "-m", "pendula", "sweep", str(scene), "-o", str(out), "-q", "--chunk-points", "3",
               "--threads", "1"]
        first = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        try:
            t0 = time.time()
            while not (out / "sweep.lock").exists() and first.poll() is None and time.time() - t0 < 60:
                time.sleep(0.005)
            second = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
            refused = first.poll() is None
        finally:
            first.kill()
            first.wait()
            first.stderr.close()
        if refused:
            break
    assert refused, "the first sweep ended before the second started, three times"
    assert second.returncode == 5, second.stderr
    lines = second.stderr.strip().splitlines()
    assert len(lines) == 1 and str(out / "sweep.zarr") in lines[0] and f"pid {first.pid}" in lines[0], lines
    # the killed first sweep left a stale lock; the same command takes it over and completes the store
    subprocess.run(cmd, check=True, capture_output=True, timeout=300)
    ds = xr.open_zarr(out / "sweep.zarr").load()
    ref = pendula.sweep(Scene.from_file(scene), chunk_points=3)
    assert ds.drop_attrs().identical(ref.drop_attrs())


def test_resume_after_seeded_random_damage_always_gives_the_in_memory_result(complete):
    """Bytes flipped, files cut at random lengths, zero-filled, grown, swapped: whatever the damage,
    the resumed result is the in-memory one, and a damaged chunk is never trusted silently."""
    out, ref = complete
    rng = np.random.default_rng(2026)
    warned = 0
    for _ in range(8):
        var = str(rng.choice(["well", "t_decided", "status"]))
        i = int(rng.integers(12))
        f = chunk_file(out, var, i)
        b = bytearray(f.read_bytes())
        kind = int(rng.integers(5))
        if kind == 0:
            k = int(rng.integers(len(b)))
            b[k] ^= 1 << int(rng.integers(8))
        elif kind == 1:
            b = b[: int(rng.integers(len(b)))]
        elif kind == 2:
            b = bytearray(len(b))
        elif kind == 3:
            b += rng.bytes(int(rng.integers(1, 64)))
        else:
            b = bytearray(chunk_file(out, var, (i + 1 + int(rng.integers(11))) % 12).read_bytes())
        f.write_bytes(bytes(b))
        with warnings.catch_warnings(record=True) as rec:
            warnings.simplefilter("always")
            ds = pendula.sweep(SCENE, out=out, **KW)
        assert ds.identical(ref), (var, i, kind)
        warned += any(issubclass(w.category, SweepStoreWarning) for w in rec)
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            assert pendula.sweep(SCENE, out=out, **KW).identical(ref)
    assert warned >= 4

"""The uncertainty recheck of final-well points near basin boundaries:
a point whose grid neighbour answers differently is computed again at 1000
times tighter tolerances and marked uncertain (status 4) where its answer
changes.  Neighbours across chunk edges (pendula.sweep) and across block edges
(pendula-run) count: the result depends on the grid alone."""

import math
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import pendula
from pendula import Scene

xr = pytest.importorskip("xarray")
solve_ivp = pytest.importorskip("scipy.integrate").solve_ivp


def scipy_well(v0, beta):
    """The well from a long scipy run at tight tolerance (independent of the kernel's stop test)."""
    sol = solve_ivp(lambda t, y: [y[1], -math.sin(y[0]) - beta * y[1]], (0, 40.0 / beta), [0.0, v0],
                    method="DOP853", rtol=1e-13, atol=1e-15)
    return round(sol.y[0, -1] / (2 * math.pi))


def boundary_v0(beta=0.1, lo=2.0, hi=3.0):
    """v0 where the well changes 0 -> 1 (bisection on the kernel at rtol 1e-12)."""
    s = Scene(damping=beta)
    w = lambda v: float(pendula.sweep(s, over={"v0": [v]}, measure="final_well", rtol=1e-12, atol=1e-14).well[0])
    wl = w(lo)
    for _ in range(45):
        m = 0.5 * (lo + hi)
        if w(m) == wl:
            lo = m
        else:
            hi = m
    return 0.5 * (lo + hi)


@pytest.fixture(scope="module")
def vstar():
    v = boundary_v0()
    # independent check that it is the 0 | 1 boundary
    assert scipy_well(v - 1e-5, 0.1) == 0 and scipy_well(v + 1e-5, 0.1) == 1
    return v


def test_recheck_sees_neighbours_across_chunk_edges(vstar):
    # spacing 2e-7 across the boundary at rtol 1e-5: the loose answers flip
    # below the true boundary, so some points change when rechecked
    v0 = vstar + 2e-7 * np.arange(-12, 9)
    kw = dict(over={"v0": v0}, measure="final_well", rtol=1e-5, atol=1e-7)
    whole = pendula.sweep(Scene(damping=0.1), **kw)
    one_per_chunk = pendula.sweep(Scene(damping=0.1), chunk_points=1, **kw)
    assert int((whole.status == 4).sum()) >= 1
    # with one point per chunk every neighbour is across a chunk edge
    assert whole.identical(one_per_chunk)
    # an uncertain point is one whose loose answer is not the right one; the grid's point at vstar
    # itself lies on the boundary (to the bisection's 1e-14), where no tolerance decides the well
    for k in np.flatnonzero((whole.status.values == 4) & (np.abs(v0 - vstar) > 1e-9)):
        loose = pendula.sweep(Scene(damping=0.1), over={"v0": [v0[k]]}, measure="final_well", rtol=1e-5,
                              atol=1e-7).well.item()
        assert loose != scipy_well(v0[k], 0.1)


def test_recheck_resume_bit_identical(vstar, tmp_path):
    v0 = vstar + 2e-7 * np.arange(-12, 9)
    kw = dict(over={"v0": v0, "damping": [0.1, 0.1 + 1e-9]}, measure="final_well", rtol=1e-5, atol=1e-7,
              chunk_points=6)
    first = pendula.sweep(Scene(damping=0.1), out=tmp_path / "o", **kw)
    # a "killed" run: some chunks never committed; the resumed run recomputes them
    records = sorted((tmp_path / "o" / "sweep.zarr" / "commits").glob("c*/zarr.json"))
    assert len(records) == 7
    for c in records[1::2]:
        c.unlink()
    resumed = pendula.sweep(Scene(damping=0.1), out=tmp_path / "o", **kw)
    assert resumed.load().identical(first.load())
    assert int((resumed.status == 4).sum()) >= 1


def _pendula_run(*args):
    exe = pathlib.Path(sys.executable).parent / "pendula-run"
    return subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True)


def test_pendula_run_recheck_across_blocks_matches_python(vstar, tmp_path):
    # 2049 points per row: pendula-run computes one row of v0 per block (4096
    # points), so every v0 neighbour is across a block edge
    v0 = vstar + 2e-7 * np.arange(-7, 2)
    scene = tmp_path / "b.nml"
    scene.write_text("&scene\n damping = 0.1\n grid = 'v0', 'torque'\n grid1 = " + ", ".join(repr(float(x)) for x in v0)
                     + "\n grid2_range = 0, 1e-14, 2049\n measure = 'final_well'\n rtol = 1e-5\n atol = 1e-7\n/\n")
    r = _pendula_run(scene, "-o", tmp_path / "b.csv")
    assert r.returncode == 0, r.stderr
    tab = np.loadtxt(tmp_path / "b.csv", delimiter=",", comments="#", skiprows=2)
    ds = pendula.sweep(Scene.from_file(scene), chunk_points=2049)
    st = ds.status.values.ravel()
    assert (st == 4).sum() >= 1 and np.array_equal(tab[:, 4], st)
    assert np.array_equal(tab[:, 2], ds.well.values.ravel(), equal_nan=True)
    # the rows next to the boundary are uncertain across the whole row
    assert np.array_equal(st.reshape(len(v0), -1), ds.status.values)


@pytest.mark.skipif(not pathlib.Path("/dev/full").exists(), reason="needs /dev/full")
@pytest.mark.parametrize("measure", ["final_well", "lyapunov"])
def test_pendula_run_sweep_csv_full_disk_is_exit_5(tmp_path, measure):
    # the sweep CSV goes through the checked writer: a device is refused and left as it was,
    # and a write that fails (a file-size limit stands in for a full disk) is exit 5, the error named
    import resource
    import signal
    import subprocess
    scene = tmp_path / "f.nml"
    scene.write_text("&scene\n damping = 0.5\n drive_frequency = 0.6666666666666666\n"
                     f" grid = 'v0'\n grid1_range = 0, 3, 7\n measure = '{measure}'\n sweep_t_max = 100\n/\n")
    r = _pendula_run(scene, "-o", "/dev/full")
    assert r.returncode == 5, (r.returncode, r.stderr)
    assert "/dev/full" in r.stderr and "not a regular file" in r.stderr
    assert pathlib.Path("/dev/full").is_char_device()

    def small_disk():
        resource.setrlimit(resource.RLIMIT_FSIZE, (100, 100))
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)

    exe = pathlib.Path(sys.executable).parent / "pendula-run"
    r = subprocess.run([str(exe), str(scene), "-o", str(tmp_path / "full.csv")], capture_output=True, text=True,
                       preexec_fn=small_disk, timeout=300)
    assert r.returncode == 5, (r.returncode, r.stderr)
    assert "full.csv" in r.stderr and "too large" in r.stderr
    assert not (tmp_path / "full.csv").exists()
    # and a sweep CSV to a file is complete and leaves no temporary behind
    r = _pendula_run(scene, "-o", tmp_path / "ok.csv")
    assert r.returncode == 0, r.stderr
    assert len((tmp_path / "ok.csv").read_text().splitlines()) == 2 + 7
    assert not list(tmp_path.glob("*.part"))


def test_pendula_run_recheck_three_axes_matches_python(tmp_path):
    # neighbours along the second and third axes too (2400 points per row: one row per block)
    scene = tmp_path / "c.nml"
    scene.write_text("&scene\n damping = 0.1\n grid = 'v0', 'torque', 'theta0'\n grid1_range = 2.2037, 2.2039, 5\n"
                     " grid2_range = 0, 1e-3, 40\n grid3_range = 0, 1e-3, 60\n measure = 'final_well'\n"
                     " rtol = 1e-4\n atol = 1e-6\n/\n")     # loose enough that some answer changes on recheck
    r = _pendula_run(scene, "-o", tmp_path / "c.csv")
    assert r.returncode == 0, r.stderr
    tab = np.loadtxt(tmp_path / "c.csv", delimiter=",", comments="#", skiprows=2)
    ds = pendula.sweep(Scene.from_file(scene), chunk_points=2400)
    st = ds.status.values.ravel()
    assert (st == 4).sum() >= 1 and np.array_equal(tab[:, -1], st)
    assert np.array_equal(tab[:, 3], ds.well.values.ravel(), equal_nan=True)

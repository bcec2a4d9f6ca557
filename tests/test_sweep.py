"""Sweeps: every measure against an independent scipy solve_ivp
reference at random grid points, thread and Dask invariance, resume after a
kill, scene grid fields, the I-V hysteresis loop."""

import math
import pathlib
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import pendula
from pendula import Scene
from pendula.sweeps import grid_of

xr = pytest.importorskip("xarray")
solve_ivp = pytest.importorskip("scipy.integrate").solve_ivp


def rhs(eps, beta, tau, amp=0.0, om=0.0, ph=0.0):
    return lambda t, y: [y[1], -eps * math.sin(y[0]) - beta * y[1] + tau + amp * math.cos(om * t + ph)]


def scipy_final_well(eps, beta, tau, th0, v0, rtol):
    """Integrate long enough for the energy to be far below any barrier, then
    read the well off the resting angle: independent of the kernel's stop test."""
    t_end = 40.0 / beta
    sol = solve_ivp(rhs(eps, beta, tau), (0, t_end), [th0, v0], method="DOP853", rtol=rtol, atol=rtol * 1e-2)
    ths = math.asin(tau / eps)
    return round((sol.y[0, -1] - ths) / (2 * math.pi))


def test_final_well_random_points_against_scipy():
    rng = np.random.default_rng(14)
    v0 = rng.uniform(0.0, 4.0, 5)
    beta = np.exp(rng.uniform(math.log(0.05), math.log(0.4), 4))   # log-uniform: scales vary
    ds = pendula.sweep(Scene(damping=0.1), over={"v0": v0, "damping": beta}, measure="final_well")
    checked = 0
    for i, a in enumerate(v0):
        for j, b in enumerate(beta):
            r1 = scipy_final_well(1.0, b, 0.0, 0.0, a, 1e-10)
            r2 = scipy_final_well(1.0, b, 0.0, 0.0, a, 1e-12)
            if r1 != r2:
                continue   # the reference itself is uncertain there
            st = int(ds.status[i, j])
            assert st in (0, 4)
            if st == 0:
                assert ds.well[i, j] == r2, (a, b)
                checked += 1
    assert checked >= 15


def test_final_well_suzuki_slip_v0_2p3_beta_0p04_is_well_2():
    # Suzuki & Suzuki, section 7.2.1 list n = 1: a slip (the known-slips page: n = 2)
    ds = pendula.sweep(Scene(damping=0.04), over={"v0": [2.3]}, measure="final_well")
    assert ds.well.item() == 2 == scipy_final_well(1.0, 0.04, 0.0, 0.0, 2.3, 1e-12)


def test_final_well_with_torque_against_scipy():
    rng = np.random.default_rng(7)
    taus = rng.uniform(-0.4, 0.4, 4)
    ds = pendula.sweep(Scene(damping=0.16, v0=2.6), over={"torque": taus}, measure="final_well")
    for k, t in enumerate(taus):
        if int(ds.status[k]) == 0:
            assert ds.well[k] == scipy_final_well(1.0, 0.16, t, 0.0, 2.6, 1e-12)


def test_final_well_not_applicable_without_damping_refused_with_drive():
    ds = pendula.sweep(Scene(), over={"v0": [1.0]}, measure="final_well")
    assert int(ds.status[0]) == 2 and np.isnan(ds.well[0])
    # a driven orbit settles in no well: the capability table refuses the drive, naming its field
    with pytest.raises(ValueError, match="drive_amplitude"):
        pendula.sweep(Scene(damping=0.1, drive_amplitude=0.5, drive_frequency=1.0), over={"v0": [1.0]},
                      measure="final_well")
    with pytest.raises(ValueError, match="drive_amplitude"):
        pendula.sweep(Scene(damping=0.1, drive_frequency=1.0), over={"drive_amplitude": [0.0, 0.5]},
                      measure="final_well")


def test_final_well_not_settled_by_limit_is_reported():
    # beta tiny, t_max short: not trapped yet; NaN and status 1, never a guess
    ds = pendula.sweep(Scene(damping=1e-4), over={"v0": [3.0]}, measure="final_well", t_max=50.0)
    assert int(ds.status[0]) == 1 and np.isnan(ds.well[0])


def test_boundary_points_uncertain_or_right():
    # a fine grid across the first boundary in v0 (near 2.1 for beta = 0.1)
    v0 = np.linspace(2.0, 2.3, 21)
    ds = pendula.sweep(Scene(damping=0.2), over={"v0": v0}, measure="final_well", rtol=1e-6, atol=1e-8)
    for k, a in enumerate(v0):
        if int(ds.status[k]) == 0:
            assert ds.well[k] == scipy_final_well(1.0, 0.2, 0.0, 0.0, a, 1e-12)


def test_mean_velocity_against_scipy():
    rng = np.random.default_rng(3)
    taus = rng.uniform(1.05, 2.0, 3)   # above eps: every orbit runs
    ds = pendula.sweep(Scene(damping=0.3), over={"torque": taus}, measure="mean_velocity",
                       transient=50.0, t_max=200.0)
    for k, t in enumerate(taus):
        sol = solve_ivp(rhs(1.0, 0.3, t), (0, 250), [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14,
                        dense_output=True)
        ref = (sol.sol(250)[0] - sol.sol(50)[0]) / 200.0
        assert abs(ds.mean_velocity[k] - ref) < 1e-7 * abs(ref)   # same definition, both at tight tolerance
        assert ds.mean_velocity_err[k] < 0.05 * ref


def test_locked_and_running():
    # tau = 0.5 < eps: from rest locked; from a fast start with small damping: running (hysteresis)
    ds = pendula.sweep(Scene(damping=0.05, torque=0.5), over={"v0": [0.0, 6.0]}, measure="locked", t_max=300.0)
    assert ds.locked.values.tolist() == [1.0, 0.0]
    sol = solve_ivp(rhs(1.0, 0.05, 0.5), (0, 600), [0.0, 6.0], method="DOP853", rtol=1e-12, atol=1e-14)
    assert sol.y[1, -100:].min() > 0   # scipy: still running


def test_poincare_period1_against_scipy():
    beta, om, amp = 0.5, 2.0 / 3.0, 0.9
    s = Scene(damping=beta, drive_amplitude=amp, drive_frequency=om)
    ds = pendula.sweep(s, over={"drive_amplitude": [amp]}, measure="poincare", transient=300.0, samples=5)
    tp = 2 * math.pi / om
    n_tr = math.ceil(300.0 / tp)
    ts = tp * np.arange(n_tr + 1, n_tr + 6)
    sol = solve_ivp(rhs(1.0, beta, 0.0, amp, om), (0, ts[-1]), [0.0, 0.0], method="DOP853", rtol=1e-12,
                    atol=1e-14, t_eval=ts)
    th = (sol.y[0] + math.pi) % (2 * math.pi) - math.pi
    np.testing.assert_allclose(ds.theta.values[0], th, atol=1e-6)
    np.testing.assert_allclose(ds.v.values[0], sol.y[1], atol=1e-6)
    assert np.ptp(ds.theta.values[0]) < 1e-6   # period 1: one stroboscopic point


def test_poincare_transient_in_periods_of_each_points_own_drive():
    """A drive_frequency axis: each point skips ceil(transient / T) of its own
    periods T = 2 pi / Omega (not the base scene's), and a base frequency of 0
    does not mean no transient.  Against scipy at each point's own times."""
    beta, amp, transient = 0.5, 0.9, 40.0
    s = Scene(damping=beta, drive_amplitude=amp, drive_frequency=0.0)
    oms = [0.5, 2.0 / 3.0, 1.3]
    ds = pendula.sweep(s, over={"drive_frequency": oms}, measure="poincare", transient=transient, samples=3)
    for i, om in enumerate(oms):
        tp = 2 * math.pi / om
        n_tr = math.ceil(transient / tp)
        ts = tp * np.arange(n_tr + 1, n_tr + 4)
        sol = solve_ivp(rhs(1.0, beta, 0.0, amp, om), (0, ts[-1]), [0.0, 0.0], method="DOP853", rtol=1e-12,
                        atol=1e-14, t_eval=ts)
        th = (sol.y[0] + math.pi) % (2 * math.pi) - math.pi
        np.testing.assert_allclose(ds.theta.values[i], th, atol=1e-6)
        np.testing.assert_allclose(ds.v.values[i], sol.y[1], atol=1e-6)


def test_threads_1_and_2_identical():
    over = {"v0": np.linspace(0, 4, 40), "damping": [0.05, 0.1, 0.2]}
    a = pendula.sweep(Scene(damping=0.1), over=over, measure="final_well", threads=1)
    b = pendula.sweep(Scene(damping=0.1), over=over, measure="final_well", threads=2)
    assert a.identical(b)


def test_dask_localcluster_same_as_threads(tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    over = {"v0": np.linspace(0, 4, 12), "damping": [0.05, 0.2]}
    local = pendula.sweep(Scene(damping=0.1), over=over, measure="final_well", chunk_points=4)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cl, distributed.Client(cl) as client:
        dist = pendula.sweep(Scene(damping=0.1), over=over, measure="final_well", chunk_points=4,
                             client=client, out=tmp_path / "d")
    assert local.identical(dist)


def test_resume_after_kill(tmp_path):
    scene = tmp_path / "s.nml"
    scene.write_text("&scene\n damping = 0.1\n grid = 'v0', 'damping'\n grid1_range = 0, 4, 80\n"
                     " grid2_range = 0.05, 0.3, 30\n measure = 'final_well'\n rtol = 1e-12\n atol = 1e-14\n/\n")
    def start_and_kill(out):
        cmd = [sys.executable, "-m", "pendula", "sweep", str(scene), "-o", str(out), "-q",
               "--chunk-points", "60", "--threads", "1"]
        proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        t0 = time.time()
        commits = out / "sweep.zarr" / "commits"
        while time.time() - t0 < 60:
            n = len(list(commits.glob("c*/zarr.json"))) if commits.exists() else 0
            if n >= 3 or proc.poll() is not None:
                break
            time.sleep(0.02)
        killed = proc.poll() is None
        proc.send_signal(signal.SIGKILL)
        _, err = proc.communicate()
        n = len(list(commits.glob("c*/zarr.json")))
        return cmd, killed, n, err

    # on a loaded shared machine the kill may come too late: try again in a fresh folder
    for attempt in range(3):
        out = tmp_path / f"o{attempt}"
        cmd, killed, n_before, err = start_and_kill(out)
        if killed and 0 < n_before < 40:
            break
    assert killed and 0 < n_before < 40, f"the run was not interrupted mid-way ({killed}, {n_before}, {err!r})"
    subprocess.run(cmd + ["--netcdf"], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    resumed = xr.open_zarr(out / "sweep.zarr").load()
    full = pendula.sweep(Scene.from_file(scene), chunk_points=60, threads=2)
    assert resumed.drop_attrs().identical(full.drop_attrs())
    exported = xr.open_dataset(out / "sweep.nc", engine="scipy").load()
    assert exported.drop_attrs().identical(full.drop_attrs())
    # partial files of the killed run are cleaned up, and the lock is released
    left = [p for p in out.rglob("*") if p.name.endswith((".tmp", ".partial")) or p.name == "sweep.lock"]
    assert not left, left


def test_scene_grid_fields_and_errors():
    s = Scene.from_namelist("&scene\n damping = 0.1\n grid = 'v0', 'torque'\n grid1 = 1, 2.5\n"
                            " grid2_range = -0.1, 0.3, 5\n measure = 'locked'\n/\n")
    g = grid_of(s)
    assert g["v0"].tolist() == [1.0, 2.5] and np.allclose(g["torque"], np.linspace(-0.1, 0.3, 5))
    assert Scene.from_namelist(s.to_namelist()) == s
    bad = ["grid = 'v0'\n measure = 'final_well'",                       # no values
           "grid = 'v0'\n grid1 = 1\n grid1_range = 0, 1, 3\n measure = 'locked'",   # both
           "grid = 'length'\n grid1 = 1\n measure = 'locked'",              # not griddable
           "grid = 'v0'\n grid1 = 1\n measure = 'final_wel'",               # misspelt
           "grid = 'v0'\n grid1 = 1",                                       # no measure
           "grid = 'v0'\n grid1_range = 0, 1, 2.5\n measure = 'locked'",    # count not whole
           "grid2 = 1, 2"]                                                  # axis 2 not named
    for b in bad:
        with pytest.raises(pendula.SceneError):
            Scene.from_namelist(f"&scene\n damping = 0.1\n {b}\n/\n")


def test_sweep_bad_arguments():
    with pytest.raises(ValueError, match="over"):
        pendula.sweep(Scene(damping=0.1), over={"length": [1.0]}, measure="final_well")
    with pytest.raises(ValueError, match="measure"):
        pendula.sweep(Scene(damping=0.1), over={"v0": [1.0]}, measure="nope")
    with pytest.raises(ValueError, match="damping"):
        pendula.sweep(Scene(damping=0.1), over={"damping": [-1.0]}, measure="final_well")
    with pytest.raises(ValueError, match="over"):
        pendula.sweep(Scene(damping=0.1), over={"v0": [np.nan]}, measure="final_well")


def test_iv_curve_hysteresis_switch_and_retrap():
    beta = 0.05
    taus = np.round(np.arange(0.0, 1.2001, 0.02), 10)
    r = pendula.iv_curve(Scene(damping=beta), taus, "both", transient=100.0, t_max=200.0)
    up_tau, up_v = r.torque.values, r.mean_velocity.sel(direction="up").values
    # switching to running on the way up at tau = eps (the first grid point >= 1)
    assert up_v[up_tau < 1.0].max() == 0.0 and up_v[up_tau > 1.0].min() > 1.0
    dn_tau, dn_v = r.torque.values[::-1], r.mean_velocity.sel(direction="down").values[::-1]   # in the order run
    retrap = dn_tau[dn_v > 0].min()
    law = 4 * beta / math.pi   # Stewart-McCumber, small beta
    assert abs(retrap - law) <= 0.03, (retrap, law)
    # running branch: <v> ~ tau / beta far above (the ohmic line), within 5 %
    assert abs(dn_v[0] - 1.2 / beta) < 0.05 * 1.2 / beta


def _pendula_run(*args):
    exe = pathlib.Path(sys.executable).parent / "pendula-run"
    return subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True)


def test_pendula_run_sweep_scene_matches_python(tmp_path):
    scene = tmp_path / "r.nml"
    scene.write_text("&scene\n damping = 0.1\n torque = 0.05\n grid = 'v0', 'damping'\n"
                     " grid1_range = 0.3, 3.7, 9\n grid2 = 0.07, 0.21\n measure = 'final_well'\n/\n")
    r = _pendula_run(scene, "-o", tmp_path / "r.csv")
    assert r.returncode == 0, r.stderr
    tab = np.loadtxt(tmp_path / "r.csv", delimiter=",", comments="#", skiprows=2)
    ds = pendula.sweep(Scene.from_file(scene))
    assert np.array_equal(tab[:, 0], np.repeat(ds.v0.values, 2))       # same grid, bit for bit
    assert np.array_equal(tab[:, 1], np.tile(ds.damping.values, 9))
    ok = ds.status.values.ravel() == 0     # Python marks boundary points it cannot decide (status 4)
    assert ok.sum() >= 15
    assert np.array_equal(tab[ok, 2], ds.well.values.ravel()[ok])


def test_pendula_run_sweep_scene_errors_name_the_field(tmp_path):
    for body, word in (("grid = 'v0'\n measure = 'final_well'", "grid1"),
                       ("grid = 'length'\n grid1 = 1\n measure = 'locked'", "grid"),
                       ("grid = 'v0'\n grid1 = 1\n measure = 'final_wel'", "measure"),
                       ("grid = 'v0'\n grid1_range = 0, 1, 2.5\n measure = 'locked'", "grid1_range")):
        f = tmp_path / "bad.nml"
        f.write_text(f"&scene\n damping = 0.1\n {body}\n/\n")
        r = _pendula_run(f)
        assert r.returncode == 2 and word in r.stderr, (body, r.stderr)


def test_docstring_examples_run():
    import doctest

    import importlib
    mod = importlib.import_module("pendula.sweeps")   # the module (pendula.sweep is the function)
    failures, tried = doctest.testmod(mod, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert tried >= 2 and failures == 0


def test_measures_match_single_simulate_runs():
    # final_well and mean_velocity at random points against pendula.simulate of the same scene
    rng = np.random.default_rng(21)
    pts = [(float(rng.uniform(0.5, 3.5)), float(np.exp(rng.uniform(math.log(0.08), math.log(0.3)))),
            float(rng.uniform(-0.3, 0.3))) for _ in range(4)]
    for v0, b, tau in pts:
        s = Scene(v0=v0, damping=b, torque=tau)
        ds = pendula.sweep(s, over={"v0": [v0]}, measure="final_well")
        tr = pendula.simulate(s.replace(t_end=40.0 / b, n_samples=2))
        n_sim = round((tr.theta[-1] - math.asin(tau)) / (2 * math.pi))
        if int(ds.status[0]) == 0:
            assert ds.well.item() == n_sim, (v0, b, tau)
    s = Scene(damping=0.2, torque=1.3)
    ds = pendula.sweep(s, over={"torque": [1.3]}, measure="mean_velocity", transient=40.0, t_max=100.0)
    tr = pendula.simulate(s.replace(t_start=0.0, t_end=140.0, n_samples=351))   # samples at t = 0, 0.4, ...
    ref = (tr.theta[-1] - tr.theta[100]) / 100.0
    assert abs(ds.mean_velocity.item() - ref) < 1e-7 * ref


def test_iv_curve_starting_at_a_high_torque_ramps_instead_of_stepping():
    beta = 0.05
    taus = np.round(np.arange(0.9, 1.0, 0.02), 10)
    # a step from rest at theta = 0 to tau = 0.9 swings past the saddle pi - asin(0.9): running
    step = pendula.iv_curve(Scene(damping=beta), taus, "up", transient=100.0, t_max=200.0, start="scene")
    assert step.mean_velocity.sel(direction="up").values[0] > 1.0
    # the adiabatic ramp from zero torque stays locked below tau = eps
    ramp = pendula.iv_curve(Scene(damping=beta), taus, "up", transient=100.0, t_max=200.0)
    assert np.all(ramp.mean_velocity.sel(direction="up").values == 0.0)


def test_iv_curve_down_branch_alone_starts_where_the_up_ramp_ends():
    beta = 0.05
    taus = np.round(np.arange(0.0, 1.2001, 0.04), 10)
    both = pendula.iv_curve(Scene(damping=beta), taus, "both", transient=100.0, t_max=200.0)
    down = pendula.iv_curve(Scene(damping=beta), taus, "down", transient=100.0, t_max=200.0)
    np.testing.assert_array_equal(down.mean_velocity.sel(direction="down"), both.mean_velocity.sel(direction="down"))


def test_iv_curve_from_a_given_state():
    beta = 0.1
    r = pendula.iv_curve(Scene(damping=beta), [0.5], "up", transient=100.0, t_max=200.0, start=(0.0, 10.0))
    # running from v = 10 at tau = 0.5 > 4 beta / pi: it stays running near tau / beta
    assert abs(float(r.mean_velocity.sel(direction="up", torque=0.5)) - 0.5 / beta) < 0.1 * 0.5 / beta
    with pytest.raises(ValueError, match="start"):
        pendula.iv_curve(Scene(damping=beta), [0.5], "up", start=(0.0, math.nan))
    with pytest.raises(ValueError, match="start"):
        pendula.iv_curve(Scene(damping=beta), [0.5], "up", start="rest")


def test_iv_curve_is_a_dataset_with_cf_attributes_and_takes_a_path(tmp_path):
    f = tmp_path / "iv.nml"
    f.write_text("&scene damping = 0.2 /")
    r = pendula.iv_curve(f, [0.5, 1.1], "both", transient=50.0, t_max=100.0)
    assert r.mean_velocity.dims == ("direction", "torque") and list(r.direction.values) == ["up", "down"]
    assert r.mean_velocity.attrs["units"] == "rad s-1" and list(r.status.attrs["flag_values"])[0] == 0
    assert float(r.mean_velocity.sel(direction="up", torque=0.5)) == 0.0


def test_iv_curve_t_avg_is_the_deprecated_name_of_t_max():
    s = Scene(damping=0.2)
    with pytest.warns(DeprecationWarning, match="t_max"):
        old = pendula.iv_curve(s, [0.5, 1.1], "up", transient=50.0, t_avg=100.0)
    new = pendula.iv_curve(s, [0.5, 1.1], "up", transient=50.0, t_max=100.0)
    np.testing.assert_array_equal(old.mean_velocity, new.mean_velocity)
    with pytest.raises(TypeError, match="t_max"):
        pendula.iv_curve(s, [0.5], "up", t_max=100.0, t_avg=100.0)

"""Sweeps, I-V curves, the cord loop, spectra and the file writers under a
careless user, a full disk and Ctrl-C: one test per class of failure.

Classes: crash (absurd thread counts), silent wrong numbers (a clipped well
index, angles beyond 2^52), silent wrong physics (a sweep of a model it does
not run), cannot stop (SIGINT in every long kernel loop), destructive writes
(devices, folders, missing parents), CLI tracebacks and partial files,
leftover temporaries (SIGTERM, failures), checks missing or misleading, and
the one CSV number format of pendula-run and Python.
"""

from __future__ import annotations

import json
import math
import os
import pathlib
import resource
import signal
import subprocess
import sys
import time

import mpmath as mp
import numpy as np
import pytest

import pendula
from pendula import Scene

BIN = pathlib.Path(sys.executable).parent
DAMPED = Scene(damping=0.1)
DRIVEN = Scene(damping=0.5, drive_frequency=2 / 3, drive_amplitude=1.2)
MEASURES = ("final_well", "mean_velocity", "locked", "poincare", "lyapunov")
OTHER_MODELS = {
    "gravity": dict(gravity="inverse-square", gravity_distance=1.2),
    "cycloid": dict(guide="cycloid"),
    "cord": dict(cord="flexible"),
}


def _base(measure):
    return DRIVEN if measure in ("poincare", "lyapunov") else DAMPED


def _cli(*args, **kw):
    return subprocess.run([str(BIN / "pendula"), *map(str, args)], capture_output=True, text=True, timeout=600,
                          **kw)


def _run(*args, **kw):
    return subprocess.run([str(BIN / "pendula-run"), *map(str, args)], capture_output=True, text=True,
                          timeout=600, **kw)


def _one_line(err: str) -> bool:
    return len(err.strip().splitlines()) == 1 and "Traceback" not in err


def _small_disk():
    """A file-size limit of 100 bytes stands in for a full disk (writes fail with EFBIG)."""
    resource.setrlimit(resource.RLIMIT_FSIZE, (100, 100))
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)


SWEEP_NML = "&scene\n damping = 0.1\n grid = 'v0'\n grid1 = 0.5, 1.5, 2.5\n measure = 'final_well'\n" \
            " sweep_t_max = 100\n/\n"


# ------------------------------------------------------------------ crash: thread counts

@pytest.mark.parametrize("threads", [10 ** 6, 2 ** 40, -1, 257])
def test_crash_absurd_thread_count_is_refused_with_the_rule(threads):
    with pytest.raises(ValueError, match=r"threads must be between 0 and 256"):
        pendula.sweep(DAMPED, over={"v0": [0.5, 2.5]}, measure="final_well", threads=threads)


def test_crash_cli_thread_and_worker_counts_are_exit_2(tmp_path):
    scene = tmp_path / "sw.nml"
    scene.write_text(SWEEP_NML)
    for opt, value in (("--threads", 1000000), ("--workers", -1), ("--chunk-points", 0)):
        r = _cli("sweep", scene, "-o", tmp_path / "o", "-q", opt, value)
        assert r.returncode == 2, (opt, r.stderr)
        assert opt in r.stderr and _one_line(r.stderr)


def test_crash_threads_at_the_limit_agree_with_one_thread():
    a = pendula.sweep(DAMPED, over={"v0": np.linspace(0.5, 3.0, 9)}, measure="final_well", threads=1)
    b = pendula.sweep(DAMPED, over={"v0": np.linspace(0.5, 3.0, 9)}, measure="final_well", threads=256)
    assert np.array_equal(a.well.values, b.well.values, equal_nan=True)


# ------------------------------------------------------------------ silent wrong numbers: the well index

@pytest.mark.parametrize("theta0", [2.0 ** 40, -(2.0 ** 40) + 0.5, 3.7e13, 2.0 ** 52])
def test_silent_wrong_number_well_of_a_huge_angle_is_64_bit(theta0):
    # at rest at theta0: trapped at once in the well of theta0 (no torque: wells centred on 2 pi n)
    ds = pendula.sweep(DAMPED, over={"theta0": [theta0]}, measure="final_well", t_max=50)
    with mp.workdps(60):
        n = int(mp.floor((mp.mpf(theta0) + mp.pi) / (2 * mp.pi)))
    assert int(ds.status[0]) == 0 and ds.well.values[0] == float(n)


@pytest.mark.parametrize("theta0", [2.0 ** 53, -(2.0 ** 60), 1e308])
def test_silent_wrong_number_angle_beyond_2_52_is_refused_naming_theta0(theta0):
    with pytest.raises(ValueError, match="theta0"):
        pendula.sweep(DAMPED, over={"theta0": [theta0]}, measure="final_well")
    with pytest.raises(ValueError, match="theta0"):
        pendula.sweep(DAMPED.replace(theta0=theta0), over={"v0": [0.0]}, measure="final_well")
    with pytest.raises(ValueError, match="theta0"):
        pendula.iv_curve(Scene(damping=0.2, theta0=theta0), [0.5])


def test_silent_wrong_number_pendula_run_refuses_a_huge_angle_naming_theta0(tmp_path):
    scene = tmp_path / "a.nml"
    scene.write_text("&scene\n damping = 0.1\n grid = 'theta0'\n grid1 = 0.0, 1e16\n measure = 'final_well'\n/\n")
    r = _run(scene, "-o", tmp_path / "a.csv")
    assert r.returncode == 2 and "theta0" in r.stderr and not (tmp_path / "a.csv").exists()


# ------------------------------------------------------------------ silent wrong physics: the scene's model

@pytest.mark.parametrize("model", sorted(OTHER_MODELS))
@pytest.mark.parametrize("measure", MEASURES)
def test_silent_wrong_physics_sweep_of_another_model_names_it(model, measure):
    scene = _base(measure).replace(**OTHER_MODELS[model])
    with pytest.raises(NotImplementedError, match=f"model '{model}'"):
        pendula.sweep(scene, over={"v0": [0.5]}, measure=measure, t_max=10.0)


@pytest.mark.parametrize("model", sorted(OTHER_MODELS))
def test_silent_wrong_physics_iv_curve_of_another_model_names_it(model):
    with pytest.raises(NotImplementedError, match=f"model '{model}'"):
        pendula.iv_curve(Scene(damping=0.2, **OTHER_MODELS[model]), [0.5, 1.5], t_max=10.0)


def test_silent_wrong_physics_pendula_run_sweep_of_another_model_is_exit_3(tmp_path):
    scene = tmp_path / "g.nml"
    scene.write_text(SWEEP_NML.replace("/\n", " gravity = 'inverse-square'\n gravity_distance = 1.2\n/\n"))
    r = _run(scene, "-o", tmp_path / "g.csv")
    assert r.returncode == 3 and "model 'gravity'" in r.stderr and not (tmp_path / "g.csv").exists()
    r = _cli("sweep", scene, "-o", tmp_path / "o", "-q")
    assert r.returncode == 3 and "model 'gravity'" in r.stderr and _one_line(r.stderr)


# ------------------------------------------------------------------ cannot stop: SIGINT in every long loop

def _stops_on_sigint(code: str, wait: float = 1.0):
    p = subprocess.Popen([sys.executable, "-c", "import pendula, numpy as np\nprint('start', flush=True)\n" + code
                          + "\nprint('finished', flush=True)"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "start"
    time.sleep(wait)
    t0 = time.monotonic()
    p.send_signal(signal.SIGINT)
    try:
        out, err = p.communicate(timeout=30)   # a hang fails here
    except subprocess.TimeoutExpired:
        p.kill()
        pytest.fail("the call did not stop on SIGINT")
    assert "finished" not in out, "the call ended before the signal: make it longer"
    assert p.returncode != 0 and "KeyboardInterrupt" in err, err[-500:]
    return time.monotonic() - t0


@pytest.mark.parametrize("measure", MEASURES)
def test_cannot_stop_sweep_stops_on_sigint(measure):
    scene = "Scene(damping=0.5, drive_frequency=2/3, drive_amplitude=1.2)" if measure in ("poincare", "lyapunov") \
        else "Scene(damping=1e-4, torque=0.5)"
    extra = ", samples=100000" if measure == "poincare" else ""
    _stops_on_sigint(f"from pendula import Scene\npendula.sweep({scene}, over={{'v0': np.linspace(0.1, 3, 4)}}, "
                     f"measure='{measure}', t_max=1e8, transient=1e7{extra}, threads=1)")


def test_cannot_stop_iv_curve_stops_on_sigint():
    _stops_on_sigint("pendula.iv_curve(pendula.Scene(damping=1e-3), [0.5, 1.5], t_max=1e8, transient=1e7)")


def test_cannot_stop_cord_loop_stops_on_sigint():
    # the conservative cord at xi = 0.777 with restitution 0 flips without end: ~2 s per 10^6 time units
    _stops_on_sigint("s = pendula.Scene(cord='flexible', v0=2.0811054754625005, max_flips=10**8)\n"
                     "pendula.simulate(s, [0.0, 1e10])")


def test_cannot_stop_hybrid_cord_loop_stops_on_sigint():
    _stops_on_sigint("s = pendula.Scene(cord='flexible', v0=2.0811054754625005, max_flips=10**8, damping=1e-9)\n"
                     "pendula.simulate(s, [0.0, 1e6])")


def test_cannot_stop_long_spectra_stop_on_sigint():
    # FFTW_MEASURE of 2^22 samples plans for minutes without its time limit (10 s per length)
    dt = _stops_on_sigint("t = np.arange(1 << 22) * 0.01\npendula.spectra(t, np.sin(t), measure=True)")
    assert dt < 25


def test_cannot_stop_absurd_work_is_refused_up_front():
    with pytest.raises(ValueError, match="t_max must be at most 1e\\+08"):
        pendula.sweep(DAMPED, over={"v0": [1.0]}, measure="mean_velocity", t_max=1e15)
    with pytest.raises(ValueError, match="transient must be at most"):
        pendula.iv_curve(Scene(damping=0.2), [0.5], transient=1e12)
    with pytest.raises(ValueError, match="grid points"):
        pendula.sweep(DAMPED, over={"v0": np.zeros(10 ** 5) + 1, "theta0": np.zeros(10 ** 4)}, measure="final_well")
    with pytest.raises(ValueError, match="sizes must be between 4 and 134217728"):
        pendula.precompute_wisdom([1 << 30], path="/nonexistent/w")


def test_cannot_stop_the_process_stays_usable_after_a_cancelled_sweep():
    # xarray imported first: the Ctrl-C lands in the kernel's long sweep, not in the lazy import (a Ctrl-C
    # halfway through an import is tests/test_fuzz_classes.py's case), however slow the machine
    code = ("import signal, threading, os, xarray\n"
            "threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()\n"
            "try:\n"
            "    pendula.sweep(pendula.Scene(damping=1e-4, torque=0.5), over={'v0': [3.0, 2.9]}, "
            "measure='mean_velocity', t_max=1e8, threads=1)\n"
            "except KeyboardInterrupt:\n"
            "    print('interrupted', flush=True)\n"
            "ds = pendula.sweep(pendula.Scene(damping=0.04), over={'v0': [1.0, 2.3, 3.0]}, measure='final_well')\n"
            "print(ds.well.values.tolist())\n")
    r = subprocess.run([sys.executable, "-c", "import pendula\n" + code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout.split() [0] == "interrupted" and "[0.0, 2.0, 5.0]" in r.stdout


# ------------------------------------------------------------------ destructive writes

@pytest.mark.skipif(not pathlib.Path("/dev/full").exists(), reason="needs /dev/full")
def test_destructive_write_wisdom_never_replaces_a_device(tmp_path):
    before = os.stat("/dev/full")
    with pytest.raises(OSError, match="not a regular file"):
        pendula.precompute_wisdom([64], path="/dev/full")
    after = os.stat("/dev/full")
    assert pathlib.Path("/dev/full").is_char_device() and after.st_rdev == before.st_rdev
    assert not list(pathlib.Path("/dev").glob(".full.*"))


def test_destructive_write_wisdom_refuses_a_folder_and_a_missing_parent(tmp_path):
    with pytest.raises(IsADirectoryError):
        pendula.precompute_wisdom([64], path=tmp_path)
    with pytest.raises(FileNotFoundError, match="does not exist"):
        pendula.precompute_wisdom([64], path=tmp_path / "no" / "such" / "w")
    assert not (tmp_path / "no").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == []
    w = pendula.precompute_wisdom([64], path=tmp_path / "w")
    assert w.is_file() and w.stat().st_size > 0 and sorted(p.name for p in tmp_path.iterdir()) == ["w"]


def test_destructive_write_wisdom_cli_is_one_line():
    r = _cli("wisdom", "1000000000000", "--path", "/nonexistent/w")
    assert r.returncode == 2 and "sizes must be between 4 and" in r.stderr and _one_line(r.stderr)
    r = _cli("wisdom", "64", "--path", "/nonexistent/folder/w")
    assert r.returncode == 5 and "does not exist" in r.stderr and _one_line(r.stderr)


def test_destructive_write_python_writer_refuses_a_fifo_and_leaves_it(tmp_path):
    from pendula._files import atomic_path
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    with pytest.raises(OSError, match="not a regular file"):
        with atomic_path(fifo) as tmp:
            tmp.write_text("x")
    assert fifo.is_fifo() and sorted(p.name for p in tmp_path.iterdir()) == ["pipe"]


# ------------------------------------------------------------------ CLI tracebacks and partial files

@pytest.mark.parametrize("target", ["file", "/dev/full"])
def test_cli_tracebacks_sweep_output_errors_are_exit_5_on_one_line(tmp_path, target):
    scene = tmp_path / "sw.nml"
    scene.write_text(SWEEP_NML)
    out = tmp_path / "FILE" if target == "file" else pathlib.Path(target)
    if target == "file":
        out.write_text("keep me")
    r = _cli("sweep", scene, "-o", out, "-q")
    assert r.returncode == 5, r.stderr
    assert str(out) in r.stderr and _one_line(r.stderr)
    if target == "file":
        assert out.read_text() == "keep me"


def test_cli_tracebacks_full_disk_leaves_nothing_under_a_final_name(tmp_path):
    scene = tmp_path / "sw.nml"
    scene.write_text(SWEEP_NML)
    out = tmp_path / "o"
    r = _cli("sweep", scene, "-o", out, "-q", preexec_fn=_small_disk)
    assert r.returncode == 5, r.stderr
    assert _one_line(r.stderr) and "too large" in r.stderr
    names = [p.name for p in out.rglob("*")]
    assert "sweep.nc" not in names and "sweep.png" not in names and "sweep.zarr" not in names
    assert not [n for n in names if n.endswith(".part") or n.endswith(".tmp")]


def test_cli_tracebacks_run_and_sweep_succeed_with_room(tmp_path):
    scene = tmp_path / "sw.nml"
    scene.write_text(SWEEP_NML)
    r = _cli("sweep", scene, "-o", tmp_path / "o", "-q", "--netcdf")
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "o" / "sweep.zarr").is_dir() and (tmp_path / "o" / "sweep.png").stat().st_size > 1000
    assert (tmp_path / "o" / "sweep.nc").is_file()


# ------------------------------------------------------------------ leftovers

def test_leftovers_pendula_run_sigterm_and_sigint_remove_the_temporary(tmp_path):
    scene = tmp_path / "long.nml"
    scene.write_text("&scene\n damping = 0.01\n t_end = 1e6\n n_samples = 20000000\n/\n")
    for sig in (signal.SIGTERM, signal.SIGINT):
        out = tmp_path / "big.csv"
        p = subprocess.Popen([str(BIN / "pendula-run"), str(scene), "-o", str(out)], stderr=subprocess.PIPE)
        deadline = time.monotonic() + 60
        while not list(tmp_path.glob(".big.csv.*.part")) and time.monotonic() < deadline:
            time.sleep(0.05)
        time.sleep(0.5)
        p.send_signal(sig)
        p.wait(timeout=60)
        assert p.returncode == -sig
        assert sorted(x.name for x in tmp_path.iterdir()) == ["long.nml"]


def test_leftovers_pendula_run_cord_failure_leaves_no_flip_log(tmp_path):
    # a damped flexible cord over a span beyond the work limit fails after the table and the flip
    # log were opened: exit 4, and neither file nor temporary remains (the flip log's included)
    scene = tmp_path / "c.nml"
    scene.write_text("&scene\n cord = 'flexible'\n v0 = 2.0811054754625005\n damping = 1e-9\n t_end = 1e12\n"
                     " n_samples = 3\n/\n")
    r = _run(scene, "-o", tmp_path / "c.csv")
    assert r.returncode == 4 and "work limit" in r.stderr, r.stderr
    assert sorted(x.name for x in tmp_path.iterdir()) == ["c.nml"]


def test_leftovers_pendula_run_write_error_leaves_nothing(tmp_path):
    scene = tmp_path / "t.nml"
    scene.write_text("&scene\n v0 = 1.0\n t_end = 100.0\n n_samples = 1001\n outputs = 'trajectory', 'period'\n/\n")
    r = _run(scene, "-o", tmp_path / "t.csv", preexec_fn=_small_disk)
    assert r.returncode == 5 and "too large" in r.stderr
    assert sorted(x.name for x in tmp_path.iterdir()) == ["t.nml"]
    r = _run(scene, "-o", tmp_path / "no" / "t.csv")
    assert r.returncode == 5 and "No such file" in r.stderr and not (tmp_path / "no").exists()


# ------------------------------------------------------------------ checks missing or misleading

@pytest.mark.parametrize("kw,what", [
    (dict(rtol=-1.0), "rtol"), (dict(atol=float("nan")), "atol"), (dict(t_max=float("inf")), "t_max"),
    (dict(transient=-1.0), "transient"), (dict(rtol="1e-9"), "rtol"), (dict(t_max=True), "t_max"),
])
def test_checks_iv_curve_names_the_bad_argument(kw, what):
    with pytest.raises((TypeError, ValueError), match=what):
        pendula.iv_curve(Scene(damping=0.2), [0.5], **kw)


def test_checks_iv_curve_needs_damping():
    with pytest.raises(ValueError, match="damping"):
        pendula.iv_curve(Scene(damping=0.0), [0.5])


@pytest.mark.parametrize("values", [["1.0", "2.5"], b"12", "12", [1.0, None], [True, False], [[1.0], [2.0, 3.0]],
                                    np.array(["1.0"]), np.ma.masked_array([1.0, 2.0], mask=[0, 1]), [],
                                    [1.0, float("nan")], [10 ** 400]])
def test_checks_over_values_are_numbers_only(values):
    with pytest.raises((TypeError, ValueError), match=r"over\['v0'\]"):
        pendula.sweep(DAMPED, over={"v0": values}, measure="final_well")


def test_checks_masked_array_without_masked_values_is_its_data():
    a = pendula.sweep(DAMPED, over={"v0": np.ma.masked_array([1.0, 2.5], mask=[0, 0])}, measure="final_well")
    b = pendula.sweep(DAMPED, over={"v0": [1.0, 2.5]}, measure="final_well")
    assert np.array_equal(a.well.values, b.well.values)
    with pytest.raises(ValueError, match="masked"):
        pendula.ellipk(np.ma.masked_array([0.1, 0.2], mask=[0, 1]))


@pytest.mark.parametrize("samples", [1.5, "3", True, 0, -1, 3.0, 10 ** 6])
def test_checks_samples_is_a_whole_number_in_range(samples):
    with pytest.raises((TypeError, ValueError), match="samples"):
        pendula.sweep(DRIVEN, over={"v0": [1.0]}, measure="poincare", samples=samples, t_max=10.0)


@pytest.mark.parametrize("threads", [1.5, "2", True, None])
def test_checks_threads_is_a_whole_number(threads):
    with pytest.raises(TypeError, match="threads"):
        pendula.sweep(DAMPED, over={"v0": [1.0]}, measure="final_well", threads=threads)


def test_checks_same_argument_same_verdict_in_sweep_and_iv_curve():
    for kw in (dict(rtol=0.0), dict(atol=-1.0), dict(rtol=float("inf")), dict(rtol=2.0)):
        with pytest.raises(ValueError) as a:
            pendula.sweep(DAMPED, over={"v0": [1.0]}, measure="mean_velocity", **kw)
        with pytest.raises(ValueError) as b:
            pendula.iv_curve(Scene(damping=0.2), [0.5], **kw)
        assert str(a.value) == str(b.value)


def test_checks_status_codes_cover_every_status_the_kernel_gives():
    ds = pendula.sweep(DAMPED, over={"v0": [1.0]}, measure="final_well")
    codes = {int(k) for k in json.loads(ds.attrs["status_codes"])}
    kernel = {0, 1, 2, 3, 4, 5} | {100 + s for s in (1, 2, 3, 5, 6, 7, 8, 9, 10)}
    assert kernel <= codes and {105, 106, 107} <= codes


@pytest.mark.parametrize("call,name", [
    (lambda: pendula.flip_sequence(2 ** 40), "n"), (lambda: pendula.flip_sequence(2.0), "n"),
    (lambda: pendula.cycloid_geometry(1, n=10 ** 8), "n"), (lambda: pendula.cycloid_geometry(1, n="5"), "n"),
])
def test_checks_absurd_sizes_are_refused_naming_the_argument(call, name):
    with pytest.raises((TypeError, ValueError), match=rf"^{name} must"):
        call()


# ------------------------------------------------------------------ one CSV number format

def test_csv_same_digits_from_pendula_run_and_python(tmp_path):
    scene = tmp_path / "s.nml"
    scene.write_text("&scene\n v0 = 1.7\n theta0 = 0.1\n t_end = 3.3\n n_samples = 12\n"
                     " sweep = 'v0'\n sweep_values = 1.7, 0.1\n outputs = 'trajectory', 'period'\n/\n")
    r = _run(scene, "-o", tmp_path / "run.csv")
    assert r.returncode == 0, r.stderr
    from pendula.run import run_scene
    py = run_scene(Scene.from_file(scene), tmp_path / "py", stem="s", progress=False)

    def numbers(path):
        return [ln for ln in pathlib.Path(path).read_text().splitlines() if ln and ln[0] not in "#" and ln[0].isdigit()]

    a = numbers(tmp_path / "run.csv")
    b = numbers(next(f for f in py if f.name == "s.csv"))
    assert a == b and any(",1.7," in ln or ln.startswith("1.7,") for ln in a)
    assert all("E+" not in ln for ln in a)
    oa = numbers(tmp_path / "run_orbits.csv")
    ob = numbers(next(f for f in py if f.name == "s_orbits.csv"))
    assert oa == ob
    # and every number reads back as the same double
    for ln in a:
        for x in ln.split(","):
            assert float("%.17g" % float(x)) == float(x)


def test_csv_no_column_name_twice(tmp_path):
    from pendula._files import gallery_dir
    from pendula.run import run_scene
    src = gallery_dir() / "fig13_omega_vs_v0.nml"
    files = run_scene(Scene.from_namelist(src.read_text()), tmp_path, stem="fig13", progress=False)
    for f in files:
        if f.suffix == ".csv":
            head = next(ln for ln in f.read_text().splitlines() if ln and not ln.startswith("#"))
            cols = head.split(",")
            assert len(cols) == len(set(cols)), (f.name, cols)
    from pendula._files import write_csv
    with pytest.raises(ValueError, match="v0"):
        write_csv(tmp_path / "x.csv", Scene(), ["v0", "v0"], np.zeros((1, 2)))
    assert not (tmp_path / "x.csv").exists()


def test_leftovers_pendula_command_sigterm_leaves_no_staging(tmp_path):
    scene = tmp_path / "long.nml"
    scene.write_text("&scene\n damping = 0.01\n t_end = 1e5\n n_samples = 11\n method = 'rk4'\n dt = 1e-3\n/\n")
    out = tmp_path / "o"
    out.mkdir()
    p = subprocess.Popen([str(BIN / "pendula"), "run", str(scene), "-o", str(out), "-q"], stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60
    while not list(out.iterdir()) and time.monotonic() < deadline:
        time.sleep(0.05)
    time.sleep(1.0)
    p.send_signal(signal.SIGTERM)
    p.wait(timeout=60)
    assert p.returncode == 128 + signal.SIGTERM
    assert list(out.iterdir()) == []


def test_cli_tracebacks_huge_number_in_a_scene_file_is_one_line(tmp_path):
    scene = tmp_path / "big.nml"
    scene.write_text("&scene\n theta0 = " + "1" * 5000 + "\n/\n")
    for cmd in ("run", "sweep"):
        r = _cli(cmd, scene, "-o", tmp_path / "o")
        assert r.returncode == 2 and _one_line(r.stderr), r.stderr



@pytest.mark.parametrize("t_avg", [5e-324, 1e-300, 1e-17])
def test_silent_wrong_number_window_below_the_transient_resolution_is_refused(t_avg):
    # transient + t_avg / 2 == transient: <v> came out 0 (or NaN) with status 0 "decided"
    with pytest.raises(ValueError, match="t_max .* below the resolution of transient"):
        pendula.iv_curve(Scene(damping=0.3), [0.5, 1.5], transient=5.0, t_max=t_avg)
    with pytest.raises(ValueError, match="t_max .* below the resolution of transient"):
        pendula.sweep(Scene(damping=0.3, torque=1.5), over={"v0": [1.0]}, measure="mean_velocity",
                      transient=5.0, t_max=t_avg)

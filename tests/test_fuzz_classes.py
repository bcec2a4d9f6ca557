"""The causes a fuzz of the newest surfaces found, one test per class of cause.

Each class is one mechanism that was missing or bypassed (docs/source/bad_input.rst
states the promise); each test holds every cause of its class with the fuzz's
own inputs, named in a comment by the reproducer that found it:

1. long work that cannot be stopped, or has no limit
2. extreme but valid input, silently wrong
3. arguments checked by hand, not by the one checker (python/pendula/_checks.py)
4. scene text: one reader (the kernel's), one verdict, one message in both programs
5. files: one writer, which never destroys what pendula did not write
6. the programs: one line on standard error and a documented exit status
7. without the optional extras: each function works, or names the extra to install

Child processes start with SIGINT restored to its default, so that no test
depends on how the runner was started (in the background SIGINT is ignored).
"""

from __future__ import annotations

import contextlib
import json
import os
import pathlib
import resource
import signal
import subprocess
import sys
import time
import warnings

import numpy as np
import pytest

import pendula
from conftest import venv_bin

ROOT = pathlib.Path(__file__).resolve().parents[1]


def _default_sigint():
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _limited(megabytes):
    """A preexec_fn: SIGINT at its default and at most this much address space."""
    def go():
        _default_sigint()
        lim = megabytes * 1024 * 1024
        resource.setrlimit(resource.RLIMIT_AS, (lim, lim))
    return go


def _py(code: str, *args, timeout=120, cwd=None, hide=(), preexec_fn=_default_sigint, env=None):
    """``python -c code args`` with the modules ``hide`` made unimportable."""
    head = "".join(f"import sys; sys.modules[{m!r}] = None\n" for m in hide)
    return subprocess.run([sys.executable, "-c", head + code, *map(str, args)], capture_output=True, text=True,
                          timeout=timeout, cwd=cwd, preexec_fn=preexec_fn, env=env)


def _pendula(*args, hide=(), timeout=120, cwd=None, preexec_fn=_default_sigint, env=None):
    """The ``pendula`` command (through pendula.cli.main) with the modules ``hide`` made unimportable."""
    code = "from pendula.cli import main\nif __name__ == '__main__':\n    sys.exit(main(sys.argv[1:]))\n"
    return _py("import sys\n" + code, *args, hide=hide, timeout=timeout, cwd=cwd, preexec_fn=preexec_fn, env=env)


def _one_line(r, status):
    """Failed with ``status``: exactly one line on standard error, no traceback."""
    lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
    assert r.returncode == status, (r.returncode, r.stderr[-2000:])
    assert "Traceback" not in r.stderr and len(lines) == 1, r.stderr[-2000:]
    return lines[0]


def _scene(tmp_path, body, name="s.nml"):
    p = tmp_path / name
    p.write_text("&scene\n" + body + "\n/\n")
    return p


def _stops_within(code, after, within, *args):
    """Start ``python -c code``, send SIGINT ``after`` seconds later; True if it ends ``within`` seconds of it."""
    p = subprocess.Popen([sys.executable, "-c", code, *map(str, args)], stdout=subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL, preexec_fn=_default_sigint)
    try:
        try:
            p.wait(after)
            return True            # done before the signal: nothing to stop
        except subprocess.TimeoutExpired:
            p.send_signal(signal.SIGINT)
        try:
            p.wait(within)
            return True
        except subprocess.TimeoutExpired:
            return False
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()


# --------------------------------------------------------------------------- 1. long work


def test_long_work_stops_on_ctrl_c_and_has_a_bounded_identity(tmp_path):
    # d14: a short span that takes many steps (stiff damping) is an interruptible call too
    code = "import pendula\npendula.find_events(pendula.Scene(theta0=1.0, damping=1e5), 'turning', t_end=900.0)\n"
    assert _stops_within(code, 3.0, 5.0), "find_events ran on more than 5 s after SIGINT"

    # Ctrl-C during the lazy import of an extra (xarray takes a second to import) leaves the process usable:
    # the half-made modules are forgotten, and the next sweep imports them again, whole
    # (the Ctrl-C is raised by an import hook at xarray.core.dataset, halfway through xarray's import, so
    # the test does not depend on how fast the machine imports)
    code = ("import sys, pendula\nfrom pendula._optional import require\n"
            "class CtrlC:\n"
            "    def find_spec(self, name, path=None, target=None):\n"
            "        if name == 'xarray.core.dataset':\n"
            "            sys.meta_path.remove(self)\n            raise KeyboardInterrupt\n"
            "        return None\n"
            "sys.meta_path.insert(0, CtrlC())\n"
            "try:\n    require('xarray', 'xarray', 'pendula.sweep')\n    print('imported first')\n"
            "except KeyboardInterrupt:\n    print('interrupted')\n"
            "ds = pendula.sweep(pendula.Scene(damping=0.04), over={'v0': [1.0, 2.3, 3.0]}, measure='final_well')\n"
            "print(ds.well.values.tolist())\n")
    r = _py(code)
    assert r.returncode == 0 and r.stdout.split()[-3:] == ["[0.0,", "2.0,", "5.0]"], r.stderr[-1500:]
    assert r.stdout.split()[0] == "interrupted", r.stdout

    # x02: a store's identity does not grow with its grid (10^6 points: a few hundred bytes, not 20 MB)
    from pendula._sweep_engine import Plan, layout_of
    scene = pendula.Scene(damping=0.5)
    plan = Plan(scene, {"v0": np.linspace(0.0, 3.0, 1_000_000)}, "final_well", 1e-10, 1e-12, 1.0, 0.0, 1, 20000)
    small = Plan(scene, {"v0": np.linspace(0.0, 3.0, 10)}, "final_well", 1e-10, 1e-12, 1.0, 0.0, 1, 20000)
    big_id, small_id = layout_of(plan).identity, layout_of(small).identity
    assert len(big_id) < 2000 and abs(len(big_id) - len(small_id)) < 40, len(big_id)
    assert big_id != small_id                    # still names the grid: its length, ends and checksum
    moved = Plan(scene, {"v0": np.r_[np.linspace(0.0, 3.0, 9), 3.0 + 1e-15]}, "final_well", 1e-10, 1e-12, 1.0,
                  0.0, 1, 20000)
    assert layout_of(moved).identity != small_id   # one ulp-sized change of one value is another sweep
    # and the store written records that identity, bounded
    pendula.sweep(scene, over={"v0": np.linspace(0.0, 3.0, 2000)}, measure="final_well", t_max=1.0,
                  out=tmp_path / "o")
    meta = sum(p.stat().st_size for p in (tmp_path / "o").rglob("zarr.json"))
    assert meta < 200_000, meta

    # z05: Ctrl-C of sweep(client=c) stops the workers' kernels; the client runs a new task at once
    code = r'''
import os, signal, threading, time, pendula
from distributed import Client, LocalCluster
if __name__ == "__main__":
    cl = LocalCluster(n_workers=1, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None)
    c = Client(cl)
    threading.Timer(3.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    try:
        pendula.sweep(pendula.Scene(damping=0.0), over={"v0": [0.1, 0.2, 0.3]}, measure="mean_velocity",
                      transient=0.0, t_max=1e8, client=c, chunk_points=1)
        print("RESULT finished")
    except KeyboardInterrupt:
        t0 = time.time()
        try:
            c.submit(sum, [1, 2], pure=False).result(timeout=10)
            print("RESULT ran %.1f" % (time.time() - t0))
        except Exception as e:
            print("RESULT stuck %s" % type(e).__name__)
    c.close(); cl.close()
'''
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                         start_new_session=True, preexec_fn=_default_sigint)
    try:
        out, _ = p.communicate(timeout=90)
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
    result = [ln for ln in out.splitlines() if ln.startswith("RESULT")]
    assert result and result[-1].startswith("RESULT ran"), out


# --------------------------------------------------------------------------- 2. extreme valid input


def test_extreme_valid_input_is_right_or_refused_never_silently_wrong(tmp_path):
    import mpmath

    # d07: an event level that is NaN, or beyond 2^52 (level + 2 pi k has no fraction left), is refused
    for sc, kind, level in ((pendula.Scene(theta0=0.5), "theta", float("nan")),
                            (pendula.Scene(v0=3.0), "theta_mod_2pi", 2.0 ** 60)):
        with pytest.raises(ValueError, match="level"):
            pendula.find_events(sc, kind, level=level, t_end=20.0)
    # ... and at 2^52 it is still answered: the rotation crosses level + 2 pi k every turn
    ev = pendula.find_events(pendula.Scene(v0=3.0), "theta_mod_2pi", level=2.0 ** 52, t_end=20.0)
    assert ev.t.size > 3

    # d09: a drive phase beyond 2^10 is refused naming it (1e17 gave another trajectory, 1e300 a constant drive)
    base = dict(theta0=1.0, damping=0.1, drive_amplitude=1.0, drive_frequency=1.0, t_end=10.0, n_samples=3)
    for ph in (1e17, 1e300, -1025.0):
        with pytest.raises(pendula.SceneError, match="drive_phase"):
            pendula.Scene(drive_phase=ph, **base)
    # within the bound the answer is that of the phase reduced exactly (mpmath), to the integrator's tolerance
    ph = 1000.0
    with mpmath.workdps(50):
        red = float(mpmath.fmod(mpmath.mpf(ph), 2 * mpmath.pi))
    far = pendula.simulate(pendula.Scene(drive_phase=ph, rtol=1e-12, atol=1e-14, **base))
    near = pendula.simulate(pendula.Scene(drive_phase=red, rtol=1e-12, atol=1e-14, **base))
    assert abs(far.v[-1] - near.v[-1]) < 1e-9 and abs(far.theta[-1] - near.theta[-1]) < 1e-9
    # pendula-run gives the same verdict, as a field and as a sweep axis, in Python too
    f = _scene(tmp_path, "theta0 = 1.0, damping = 0.1, drive_amplitude = 1.0, drive_frequency = 1.0, "
                         "drive_phase = 1e17")
    r = subprocess.run([venv_bin("pendula-run"), str(f), "--check"], capture_output=True, text=True,
                       preexec_fn=_default_sigint)
    assert r.returncode == 2 and "drive_phase" in r.stderr, r.stderr
    g = _scene(tmp_path, "damping = 0.5, drive_amplitude = 1.2, drive_frequency = 0.7\n grid = 'drive_phase'\n"
                         " grid1 = 0.0, 1e17\n measure = 'final_well'", "grid.nml")
    r = subprocess.run([venv_bin("pendula-run"), str(g), "--check"], capture_output=True, text=True,
                       preexec_fn=_default_sigint)
    assert r.returncode == 2 and "drive_phase" in r.stderr, r.stderr
    with pytest.raises(pendula.SceneError, match="drive_phase"):
        pendula.Scene.from_file(g)
    with pytest.raises(ValueError, match="drive_phase"):
        pendula.sweep(pendula.Scene(damping=0.5, drive_amplitude=1.2, drive_frequency=0.7),
                      over={"drive_phase": [0.0, 1e17]}, measure="final_well")


# --------------------------------------------------------------------------- 3. the one checker


def test_arguments_checked_by_the_one_checker_name_the_argument(tmp_path):
    t = np.arange(64) * 0.1
    s = pendula.spectrum(t, np.sin(t))
    w = tmp_path / "w"
    # c10: the spectrum helpers; c18: precompute_wisdom; d06: find_events / numerical_period
    cases = [
        (lambda: pendula.fourier_series(0.0, 1.5, 1.0, n=True), TypeError, "n"),
        (lambda: pendula.fourier_series(0.0, 1.5, 1.0, n=2.0), TypeError, "n"),
        (lambda: s.harmonics(True), TypeError, "n"),
        (lambda: pendula.odd_harmonics_above(s, n_max=0), ValueError, "n_max"),
        (lambda: pendula.odd_harmonics_above(s, threshold="1e-6"), TypeError, "threshold"),
        (lambda: pendula.odd_harmonics_above("spectrum"), TypeError, "spec"),
        (lambda: pendula.spectrum(t, np.sin(t), window=["hann"]), TypeError, "window"),
        (lambda: pendula.spectrum(t, np.sin(t), window="hamming"), ValueError, "window"),
        (lambda: pendula.precompute_wisdom(64, path=w), TypeError, "sizes"),
        (lambda: pendula.precompute_wisdom([64], path=123), TypeError, "path"),
        (lambda: pendula.precompute_wisdom([64], path=w, progress="no"), TypeError, "progress"),
        (lambda: pendula.find_events(None), TypeError, "scene"),
        (lambda: pendula.find_events(3.0), TypeError, "scene"),
        (lambda: pendula.numerical_period({"v0": 1.0}), TypeError, "scene"),
        (lambda: pendula.numerical_period(3.0), TypeError, "scene"),
    ]
    for call, kind, name in cases:
        with pytest.raises(kind, match=rf"\b{name}\b"):
            call()
    assert not w.exists()                         # nothing written by a refused call
    # z01, z02: a client that is an address, an out that is no path or empty
    sc = pendula.Scene(damping=0.5)
    with pytest.raises(TypeError, match="client"):
        pendula.sweep(sc, over={"v0": [1.0, 2.0]}, measure="final_well", client="tcp://127.0.0.1:8786")
    with pytest.raises(TypeError, match=r"\bout\b"):
        pendula.sweep(sc, over={"v0": [1.0, 2.0]}, measure="final_well", out=123)
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        with pytest.raises(ValueError, match=r"\bout\b"):
            pendula.sweep(sc, over={"v0": [1.0, 2.0]}, measure="final_well", out="")
        assert sorted(os.listdir(tmp_path)) == []  # nothing written into the current folder
    finally:
        os.chdir(cwd)
    # z09: chunk_points = sys.maxsize is one chunk of the grid (capped at the axis), stored and right
    ds = pendula.sweep(sc, over={"v0": [1.0, 2.3]}, measure="final_well", out=tmp_path / "big",
                       chunk_points=sys.maxsize)
    assert ds.well.values.tolist() == [0.0, 0.0]
    # z04: a closed client is a ValueError naming the client
    from distributed import Client, LocalCluster
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cl = LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None)
        c = Client(cl)
        c.close()
        try:
            with pytest.raises(ValueError, match="client"):
                pendula.sweep(sc, over={"v0": [1.0, 2.0]}, measure="final_well", client=c)
        finally:
            cl.close()


# --------------------------------------------------------------------------- 4. scene text


def _both_programs(path, tmp_path):
    """(exit, message) of ``pendula run PATH`` and of ``pendula-run PATH --check``, prefixes removed."""
    a = _pendula("run", path, "-o", tmp_path / "o", "-q", preexec_fn=_limited(1500))
    b = subprocess.run([venv_bin("pendula-run"), str(path), "--check"], capture_output=True, text=True, timeout=30,
                       preexec_fn=_default_sigint)
    return ((a.returncode, a.stderr.strip().removeprefix("pendula run: ")),
            (b.returncode, b.stderr.strip().removeprefix("pendula-run: ")))


def test_scene_text_one_reader_gives_one_verdict_and_one_message(tmp_path):
    utf16 = tmp_path / "utf16.nml"                      # c05: what Windows PowerShell's '>' writes
    utf16.write_bytes("&scene\n  v0 = 1.5\n/\n".encode("utf-16"))
    folder = tmp_path / "folder.nml"                    # c06: a folder where the file should be
    folder.mkdir()
    nul = tmp_path / "nul.nml"
    nul.write_bytes(b"&scene\n  v0 = 1.5\x00\n/\n")
    big = tmp_path / "big.nml"
    big.write_bytes(b"&scene\n  v0 = 1.5\n/\n" + b"!" * (17 << 20))
    fifo = tmp_path / "fifo.nml"
    os.mkfifo(fifo)
    for path, words in ((utf16, "not UTF-8"), (folder, "a folder"), (nul, "NUL"), (big, "16 MiB"),
                        (fifo, "not a regular file"), (pathlib.Path("/dev/zero"), "not a regular file")):
        # c17: /dev/zero is refused at once by both (it was read until memory ran out)
        a, b = _both_programs(path, tmp_path)
        assert a == b and a[0] == 2 and words in a[1] and "\n" not in a[1], (path.name, a, b)
    # a UTF-8 byte-order mark is accepted by both, as Windows editors write one
    bom = tmp_path / "bom.nml"
    bom.write_bytes(b"\xef\xbb\xbf&scene\n  v0 = 1.5, t_end = 2.0, n_samples = 5\n  outputs = 'trajectory'\n/\n")
    a, b = _both_programs(bom, tmp_path)
    assert a[0] == 0 and b[0] == 0, (a, b)
    assert pendula.Scene.from_file(bom).v0 == 1.5
    assert pendula.Scene.from_namelist("\ufeff&scene v0 = 1.5 /").v0 == 1.5
    # c16: a NUL in a word field is refused naming that field, never cut short nor blamed on another
    for field, kw in (("name", dict(name="ab\x00cd")), ("method", dict(method="rk4\x00")),
                      ("cord", dict(cord="rigid\x00")), ("outputs", dict(outputs=("trajectory\x00",)))):
        with pytest.raises(pendula.SceneError, match=rf"field '{field}'"):
            pendula.Scene(v0=1.5, **kw)


# --------------------------------------------------------------------------- 5. files: one writer


def test_files_one_writer_never_destroys_foreign_folders(tmp_path):
    sc = pendula.Scene(damping=0.5)
    over = {"v0": [1.0, 2.0]}

    def sweep_into(out):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return pendula.sweep(sc, over=over, measure="final_well", out=out)

    # z03: a sweep.zarr that is not this sweep's store is refused and left as it was
    foreign = {
        "a user's folder": lambda p: (p.mkdir(), (p / "notes.txt").write_text("results of last month\n")),
        "a file": lambda p: p.write_text("not a folder\n"),
        "a newer Zarr": lambda p: (p.mkdir(), (p / "zarr.json").write_text(
            json.dumps({"zarr_format": 4, "node_type": "group", "attributes": {}}))),
        "unreadable metadata": lambda p: (p.mkdir(), (p / "zarr.json").write_text("{")),
    }
    for what, make in foreign.items():
        out = tmp_path / what.replace(" ", "_").replace("'", "")
        out.mkdir()
        make(out / "sweep.zarr")
        before = {q.relative_to(out): q.read_bytes() for q in out.rglob("*") if q.is_file()}
        with pytest.raises(ValueError, match="not a pendula sweep store"):
            sweep_into(out)
        after = {q.relative_to(out): q.read_bytes() for q in out.rglob("*") if q.is_file()}
        assert after == before, what
    # another sweep's store is refused and left too
    other = tmp_path / "other"
    pendula.sweep(sc, over={"v0": [1.0, 3.0]}, measure="final_well", out=other)
    before = {q: q.read_bytes() for q in other.rglob("*") if q.is_file()}
    with pytest.raises(ValueError, match="different sweep"):
        sweep_into(other)
    assert {q: q.read_bytes() for q in other.rglob("*") if q.is_file()} == before

    # z07: sweep.lock as a symlink: the linked file is never opened; a FIFO there is refused and left
    precious = tmp_path / "notes.txt"
    text = "my notes, not a lock file\n" * 40
    precious.write_text(text)
    out = tmp_path / "linked"
    out.mkdir()
    (out / "sweep.lock").symlink_to(precious)
    assert sweep_into(out).well.values.tolist() == [0.0, 0.0]
    assert precious.read_text() == text
    out = tmp_path / "fifo"
    out.mkdir()
    os.mkfifo(out / "sweep.lock")
    with pytest.raises(OSError, match="FIFO"):
        sweep_into(out)
    assert (out / "sweep.lock").is_fifo()

    # c13: an output name that is a symlink to a file: the link is replaced, the file it points to left,
    # by every writer (pendula run, pendula-run, pendula wisdom)
    scene = _scene(tmp_path, "  v0 = 1.5, t_end = 5.0, n_samples = 11\n  outputs = 'trajectory'")
    run_out = tmp_path / "out"
    run_out.mkdir()
    targets = {}
    for name, link in (("run", run_out / "s.csv"), ("native", tmp_path / "native.csv"),
                       ("wisdom", tmp_path / "wisdom")):
        targets[name] = (link, tmp_path / f"{name}.target")
        targets[name][1].write_text("old\n")
        link.symlink_to(targets[name][1])
    assert _pendula("run", scene, "-o", run_out, "-q").returncode == 0
    assert subprocess.run([venv_bin("pendula-run"), str(scene), "-o", str(tmp_path / "native.csv")],
                          capture_output=True, preexec_fn=_default_sigint).returncode == 0
    assert _pendula("wisdom", "64", "--path", tmp_path / "wisdom").returncode == 0
    for name, (link, target) in targets.items():
        assert not link.is_symlink() and link.stat().st_size > 0 and target.read_text() == "old\n", name

    # x01: the documented rule and the behaviour agree: an output folder is made with its parents,
    # the folder of a file must exist
    rule = " ".join((ROOT / "docs" / "source" / "bad_input.rst").read_text().split())
    assert "is made with its missing parents" in rule and "never created" not in rule
    r = _pendula("run", "-q", scene, "-o", tmp_path / "r" / "a" / "b")
    assert r.returncode == 0 and (tmp_path / "r" / "a" / "b" / "s.csv").is_file()
    sweep_into(tmp_path / "s" / "a" / "b")
    assert (tmp_path / "s" / "a" / "b" / "sweep.zarr" / "zarr.json").is_file()
    r = subprocess.run([venv_bin("pendula-run"), str(scene), "-o", str(tmp_path / "missing" / "o.csv")],
                       capture_output=True, text=True, preexec_fn=_default_sigint)
    assert r.returncode == 5 and not (tmp_path / "missing").exists(), r.stderr
    with pytest.raises(FileNotFoundError):
        pendula.precompute_wisdom([64], path=tmp_path / "missing" / "w")
    assert not (tmp_path / "missing").exists()


# --------------------------------------------------------------------------- 6. the programs


def test_programs_fail_on_one_line_with_a_documented_exit_status(tmp_path):
    scene = _scene(tmp_path, "  v0 = 1.5, t_end = 5.0, n_samples = 11")
    a_file = tmp_path / "a_file"
    a_file.write_text("a file, not a folder\n")
    # c07, c08: a file where the output folder should be: exit 5, one line (run, spectrum, demo, accuracy)
    for args in (("run", scene), ("spectrum", scene), ("demo",),
                 ("accuracy", "integrators", "--quick", "--periods", "100")):
        _one_line(_pendula(*args, "-o", a_file, "-q"), 5)
        assert a_file.read_text() == "a file, not a folder\n"
    # c11: --periods is checked before the study runs
    for periods in ("nan", "-1", "0"):
        _one_line(_pendula("accuracy", "integrators", "--quick", "-q", "--periods", periods,
                           "-o", tmp_path / "p", timeout=30), 2)
    assert not (tmp_path / "p").exists()
    # c12: a reference file that is not one: exit 2, one line naming the file
    for kind, text in {"empty": "", "malformed": "func,x,mc,v1,v2,v3\nK,,1.0\nx,y,z\n",
                       "truncated": "func,x,mc,v1,v2,v3\nK,,1.0,1.5707963267948966\nK,,0.5,1.85407467730137"}.items():
        ref = tmp_path / f"{kind}.csv"
        ref.write_text(text)
        assert str(ref) in _one_line(_pendula("accuracy", "elliptic", "--reference", ref), 2)
    # c09: the installed command works from any folder (its reference ships with the package)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    r = _pendula("accuracy", "integrators", "--quick", "-q", "--periods", "100", "-o", "out", cwd=elsewhere,
                 timeout=300)
    assert r.returncode == 0 and (elsewhere / "out" / "work_precision.json").is_file(), r.stderr[-1000:]
    # c14, c15: a scene at the limits (n_samples = 1e8) with too little memory: exit 4, one line, both programs
    huge = _scene(tmp_path, "  v0 = 1.5, t_end = 100.0, n_samples = 100000000\n  outputs = 'trajectory'", "huge.nml")
    _one_line(_pendula("run", huge, "-o", tmp_path / "h", "-q", preexec_fn=_limited(2500), timeout=120), 4)
    r = subprocess.run([venv_bin("pendula-run"), str(huge), "-o", str(tmp_path / "h.csv")], capture_output=True,
                       text=True, timeout=120, preexec_fn=_limited(1500))
    assert "memory" in _one_line(r, 4) and "Error termination" not in r.stderr
    # the gfortran runtime adds no note to a scene whose number underflows (1e-400 reads as 0)
    tiny = _scene(tmp_path, "  v0 = 1e-400", "tiny.nml")
    r = subprocess.run([venv_bin("pendula-run"), str(tiny), "--check"], capture_output=True, text=True,
                       preexec_fn=_default_sigint)
    assert r.returncode == 0 and r.stderr == "", r.stderr
    # z08: a sweep under two seconds draws no progress bar into a redirected standard error
    sweep_scene = _scene(tmp_path, "  damping = 0.5\n  grid = 'v0'\n  grid1 = 1.0, 2.0\n  measure = 'final_well'",
                         "tiny_sweep.nml")
    r = _pendula("sweep", sweep_scene, "-o", tmp_path / "sw")
    assert r.returncode == 0 and "%|" not in r.stderr and "chunk/s" not in r.stderr, r.stderr
    # z06: a Dask worker that dies (KilledWorker, as the OOM killer leaves it): exit 4, pendula's one line
    code = ("import sys, types, distributed.scheduler, pendula._cluster as cl\n"
            "def dead(*a, **k):\n"
            "    raise distributed.scheduler.KilledWorker('_run_task-0', "
            "types.SimpleNamespace(address='tcp://127.0.0.1:1'), 0)\n"
            "cl.run_chunks = dead\n"
            "from pendula.cli import main\n"
            "if __name__ == '__main__':\n    sys.exit(main(sys.argv[1:]))\n")
    long_scene = _scene(tmp_path, "  damping = 0.0\n  grid = 'v0'\n  grid1 = 0.1, 0.2\n  measure = 'mean_velocity'\n"
                                  "  sweep_t_max = 1e8\n  sweep_transient = 0.0", "long.nml")
    r = _py(code, "sweep", long_scene, "-o", tmp_path / "dead", "--chunk-points", "1", "--workers", "1", "-q",
            timeout=120)
    last = [ln for ln in r.stderr.splitlines() if ln.strip()][-1]
    assert r.returncode == 4 and last.startswith("pendula sweep:") and "KilledWorker" in last, r.stderr[-2000:]
    assert "Traceback" not in r.stderr
    # Ctrl-C on pendula run and pendula sweep: one line, exit 130, nothing half-written
    long_run = _scene(tmp_path, "  v0 = 1.5, damping = 0.1, drive_amplitude = 1.2, drive_frequency = 0.7\n"
                                "  t_end = 1e7, n_samples = 1000\n  outputs = 'trajectory'", "long_run.nml")
    for args, out in ((("run", long_run), tmp_path / "int_run"), (("sweep", long_scene), tmp_path / "int_sweep")):
        p = subprocess.Popen([sys.executable, "-m", "pendula", *map(str, args), "-o", str(out)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, preexec_fn=_default_sigint)
        time.sleep(5.0)
        p.send_signal(signal.SIGINT)
        _, err = p.communicate(timeout=60)
        lines = [ln for ln in err.splitlines() if ln.strip()]
        assert p.returncode == 130 and len(lines) == 1 and "interrupted" in lines[0], err[-2000:]
        assert not [q for q in out.rglob("*") if q.name.endswith(".part") or q.name.startswith(".pendula-")]


# --------------------------------------------------------------------------- 7. without the extras


def test_without_the_optional_extras_each_function_works_or_names_the_extra(tmp_path):
    scene = _scene(tmp_path, "  v0 = 1.5, t_end = 5.0, n_samples = 11\n  outputs = 'trajectory', 'theta_t'")
    # c01: without matplotlib the CSV table is written; the figure's extra is named (exit 6, one line)
    r = _pendula("run", scene, "-o", tmp_path / "o1", "-q", hide=("matplotlib",))
    assert "pendula[plot]" in _one_line(r, 6)
    table = tmp_path / "o1" / "s.csv"
    assert table.is_file() and not (tmp_path / "o1" / "s_theta_t.png").exists()
    ref = pendula.simulate(pendula.Scene.from_file(scene))
    got = np.array([[float(x) for x in ln.split(",")[:3]] for ln in table.read_text().splitlines()
                    if ln and ln[0] not in "#t"])
    assert np.array_equal(got[:, 1], ref.theta) and np.array_equal(got[:, 0], ref.t)
    # c02: without tqdm the run works, progress on (the default): bars are simply not drawn
    r = _pendula("run", scene, "-o", tmp_path / "o2", hide=("tqdm", "tqdm.auto"))
    assert r.returncode == 0 and (tmp_path / "o2" / "s.csv").is_file(), r.stderr
    # c03: pendula accuracy integrators without scipy or matplotlib: one line naming the extra, before the study
    for missing, extra in (("scipy", "bench"), ("matplotlib", "accuracy")):
        r = _pendula("accuracy", "integrators", "--quick", "-q", "-o", tmp_path / f"o3{missing}", hide=(missing,),
                     timeout=60)
        assert f"pendula[{extra}]" in _one_line(r, 6)
        assert not (tmp_path / f"o3{missing}" / "work_precision.json").exists()
    # c04: pendula sweep --netcdf without scipy: one line naming the extra, before the sweep
    sw = _scene(tmp_path, "  damping = 0.1, grid = 'v0', grid1 = 1.0, 2.0, measure = 'final_well'\n"
                          "  sweep_t_max = 50, sweep_transient = 5", "sw.nml")
    r = _pendula("sweep", sw, "-o", tmp_path / "o4", "--netcdf", "-q", hide=("scipy",))
    assert "pendula[sweep]" in _one_line(r, 6)
    # the light extra: a sweep in memory needs xarray alone (pendula[xarray]); its absence names that extra
    r = _py("import pendula\npendula.sweep(pendula.Scene(damping=0.5), over={'v0': [1.0]}, measure='final_well')\n",
            hide=("xarray",))
    assert "pip install 'pendula[xarray]'" in r.stderr
    r = _py("import pendula\nds = pendula.sweep(pendula.Scene(damping=0.5), over={'v0': [1.0, 2.3]}, "
            "measure='final_well')\nprint(ds.well.values.tolist())\n", hide=("dask", "distributed", "zarr"))
    assert r.returncode == 0 and r.stdout.strip() == "[0.0, 0.0]", r.stderr[-1000:]

"""Fuzz (hypothesis, derandomized, a few seconds): every public function on any
float (NaN, inf, subnormal, huge) and awkward shapes.  The outcome is a finite
value, or NaN with a RuntimeWarning, or a ValueError/TypeError naming the
problem; never a crash, a hang or another exception type."""

import math
import warnings

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pendula
from pendula import Scene, SceneError

SETTINGS = dict(max_examples=120, derandomize=True, deadline=None, suppress_health_check=list(HealthCheck))
wild = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.sampled_from(
    [0.0, -0.0, 5e-324, -5e-324, 1e-310, 1e308, -1e308, 1.0, 1.0 - 2**-53, 1.0 + 2**-52, math.pi, 2.0]))
arrays = st.one_of(wild, st.lists(wild, min_size=0, max_size=6).map(np.array),
                   st.lists(wild, min_size=4, max_size=4).map(lambda v: np.array(v).reshape(2, 2)))
ALLOWED = (ValueError, TypeError)


def outcome(f, *args, **kw):
    """Run f; return its result, checking the NaN-with-warning rule."""
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        try:
            out = f(*args, **kw)
        except ALLOWED as exc:
            assert str(exc), "an error must say what is wrong"
            return None
    if hasattr(out, "__dataclass_fields__"):   # Orbit, Trajectory, Events, Spectrum: their numbers
        out = tuple(getattr(out, k) for k in out.__dataclass_fields__
                    if isinstance(getattr(out, k), (float, np.ndarray)))
    values = out if isinstance(out, tuple) else (out,)
    # NaN may come out without a warning only where a NaN or an infinity went in
    inputs_nan = any(np.any(~np.isfinite(np.asarray(a, dtype=float))) for a in (*args, *kw.values())
                     if isinstance(a, (float, np.ndarray)) and np.asarray(a).dtype.kind == "f")
    for val in values:
        arr = np.asarray(val, dtype=float)
        if np.any(np.isnan(arr)) and not inputs_nan:
            assert any(issubclass(x.category, RuntimeWarning) for x in w), f"NaN without a warning: {f.__name__}"
    return out


@settings(**SETTINGS)
@given(arrays)
def test_complete_integrals_and_nome(m):
    for f in (pendula.ellipk, pendula.ellipe, pendula.nome):
        outcome(f, m)
        outcome(f, None, mc=m)


@settings(**SETTINGS)
@given(arrays, arrays)
def test_incomplete_integrals_and_jacobi(x, m):
    outcome(pendula.ellipf, x, m)
    outcome(pendula.ellipeinc, x, m)
    outcome(pendula.ellipj, x, m)
    outcome(pendula.ellipj, x, None, mc=m)


@settings(**SETTINGS)
@given(wild, wild, wild, arrays)
def test_exact_motion_and_orbit(theta0, v0, eps, t):
    outcome(pendula.exact_motion, theta0, v0, eps, t)
    outcome(pendula.orbit, theta0, v0, eps)
    outcome(pendula.energy, theta0, v0, eps)


small = st.floats(-5.0, 5.0)
fields = st.fixed_dictionaries({}, optional={
    "v0": wild, "theta0": wild, "eps": wild, "damping": wild, "torque": wild, "drive_amplitude": wild,
    "drive_frequency": wild, "t_end": st.one_of(wild, st.floats(-50, 50)), "dt": wild, "rtol": wild,
    "atol": wild, "method": st.sampled_from(["auto", "rk4", "gauss6", "dop853", "dopri5", "verlet", "exact"]),
    "n_samples": st.integers(-3, 50), "cord": st.sampled_from(["rigid", "flexible"]),
    "restitution": st.one_of(wild, st.floats(0.0, 1.0))})


@settings(**SETTINGS)
@given(fields, st.one_of(st.none(), st.lists(st.floats(-30, 30), max_size=5)))
def test_simulate_any_scene(kw, t):
    try:
        scene = Scene(**kw)
    except SceneError:
        return
    if scene.method in ("rk4", "gauss6", "verlet") and not scene.dt > 0:
        scene = scene.replace(dt=0.05)
    outcome(pendula.simulate, scene, t)


@settings(**SETTINGS)
@given(small, small, st.floats(0.01, 5.0), st.one_of(wild, st.floats(0.1, 50)),
       st.sampled_from(["turning", "theta", "theta_mod_2pi", "apex"]))
def test_find_events_and_numerical_period(theta0, v0, eps, t_end, kind):
    s = Scene(theta0=theta0, v0=v0, eps=eps)
    outcome(pendula.find_events, s, kind, t_end=t_end)
    if abs(v0) > 1e-3 or abs(theta0) > 1e-3:
        try:
            outcome(pendula.numerical_period, s, periods=3)
        except RuntimeError as exc:   # fewer than two events: said, not a wrong number
            assert "events" in str(exc)


@settings(**SETTINGS)
@given(st.integers(0, 70), st.one_of(wild, st.floats(-1, 1)), st.sampled_from([None, "hann", "bad"]))
def test_spectrum_any_signal(n, value, window):
    t = np.arange(n) * 0.1
    x = np.full(n, value) + np.sin(t)
    if outcome(pendula.spectrum, t, x, window=window) is not None:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            spec = pendula.spectrum(t, x, window=window)
        outcome(lambda: spec.fundamental)


# ---------------------------------------------------------------- sweeps, I-V curves, the sweep CLI, the wisdom writer
# Seeded and short in `make test`; PENDULA_FUZZ_EXAMPLES=3000 (by hand) runs that many unseeded inputs per test.
# A sweep's outcome: a dataset whose decided points (status 0) hold finite numbers and whose
# statuses are all documented, or a ValueError/TypeError naming the argument, or a
# NotImplementedError naming the model; never a crash, a hang or another exception.

import contextlib  # noqa: E402
import io  # noqa: E402
import json  # noqa: E402
import os  # noqa: E402
import pathlib  # noqa: E402
import stat as _stat  # noqa: E402
import tempfile  # noqa: E402

from hypothesis import assume, event  # noqa: E402

FUZZ_N = int(os.environ.get("PENDULA_FUZZ_EXAMPLES", "0"))
NEW = dict(max_examples=FUZZ_N or 25, derandomize=not FUZZ_N, deadline=None, suppress_health_check=list(HealthCheck))
MEASURES = ("final_well", "mean_velocity", "locked", "poincare", "lyapunov")
MODELS = {None: {}, "gravity": dict(gravity="linear", gravity_gradient=0.2), "cycloid": dict(guide="cycloid"),
          "cord": dict(cord="flexible")}
anything = st.one_of(
    wild, st.integers(-2 ** 70, 2 ** 70), st.booleans(), st.none(), st.text(max_size=4), st.binary(max_size=3),
    st.lists(wild, max_size=3), st.lists(st.text(max_size=3), min_size=1, max_size=2),
    st.sampled_from([np.int64(3), np.float32(1.5), np.bool_(True), 1j, 10 ** 400, np.array([1.0, 2.0]),
                     np.ma.masked_array([1.0, 2.0], mask=[0, 1]), np.ma.masked_array([1.0], mask=[0]),
                     np.array(["1.0"]), 2 ** 40, -1, 0, 1, 2, 257, 1e-12, 1e-300, 2.0 ** 52, 2.0 ** 53]))
KEYWORDS = ("rtol", "atol", "t_max", "transient", "samples", "threads", "chunk_points", "over_values", "over_key",
            "measure", "theta0")


def _cheap_value(key, value, measure):
    """Valid but costly values are not what this fuzz is about: keep a run short.  (A speed
    |v0| = 1e308 is honest but slow: ~5 s per point to report status 107, too many steps.)"""
    if isinstance(value, (list, tuple, np.ndarray)) and key in ("over_values", "theta0", "torques"):
        try:
            a = np.asarray(value, dtype=float)
            return not np.any(np.abs(a[np.isfinite(a)]) > 1e6)
        except (TypeError, ValueError, OverflowError):
            return True
    if key in ("over_values", "torques", "damping") and isinstance(value, (int, float, np.number)) \
            and not isinstance(value, (bool, np.bool_)):
        try:
            return not abs(float(value)) > 1e6
        except OverflowError:
            return True
    try:
        v = float(value)
    except (TypeError, ValueError, OverflowError):
        return True
    if isinstance(value, (bool, np.bool_)) or not math.isfinite(v):
        return True
    if key in ("t_max", "transient") and abs(v) > 60:
        return False
    if key == "samples" and abs(v) > 50:
        return False
    if key in ("rtol", "atol") and 0 < v < 1e-11:
        return False
    if key == "chunk_points" and 0 < v < 1:
        return True
    return True


def _sweep_outcome(f, *args, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        try:
            out = f(*args, **kw)
        except (ValueError, TypeError, NotImplementedError) as exc:
            assert str(exc), "an error must say what is wrong"
            event(f"refused: {type(exc).__name__}")
            return None
    event("ran")
    return out


def _check_dataset(ds):
    codes = {int(k) for k in json.loads(ds.attrs["status_codes"])}
    st_ = ds.status.values
    assert set(np.unique(st_).tolist()) <= codes, np.unique(st_)
    for name in ds.data_vars:
        if name == "status":
            continue
        vals = ds[name].values
        decided = st_ == 0
        if vals.ndim > st_.ndim:
            decided = decided[..., None]
        assert np.all(np.isfinite(vals[np.broadcast_to(decided, vals.shape)])), name


@settings(**NEW)
@given(st.sampled_from(MEASURES), st.sampled_from(KEYWORDS), anything, st.sampled_from(list(MODELS)))
def test_sweep_any_keyword(measure, key, value, model):
    assume(_cheap_value(key, value, measure))
    base = Scene(damping=0.5, drive_frequency=2 / 3, drive_amplitude=1.2) if measure in ("poincare", "lyapunov") \
        else Scene(damping=0.5)
    base = base.replace(**MODELS[model])
    kw = dict(over={"v0": [0.5, 2.5]}, measure=measure, t_max=20.0, transient=0.0, samples=2, threads=1)
    if key == "over_values":
        kw["over"] = {"v0": value}
    elif key == "over_key":
        kw["over"] = {value: [1.0]} if isinstance(value, (str, int, float, type(None))) else value
    elif key == "theta0":
        kw["over"] = {"theta0": [value] if not isinstance(value, (list, np.ndarray)) else value}
    else:
        kw[key] = value
    if key == "over_values" or key == "theta0":
        try:
            n = len(kw["over"][next(iter(kw["over"]))])
            assume(n <= 8)
        except TypeError:
            pass
    ds = _sweep_outcome(pendula.sweep, base, **kw)
    if ds is not None:
        assert model is None, "a sweep ran a model it does not run"
        _check_dataset(ds)


@settings(**NEW)
@given(st.sampled_from(("rtol", "atol", "t_avg", "transient", "torques", "direction", "damping", "theta0")),
       anything, st.sampled_from(list(MODELS)))
def test_iv_curve_any_keyword(key, value, model):
    assume(_cheap_value("t_max" if key in ("t_avg", "transient") else key, value, "mean_velocity"))
    kw = dict(transient=5.0, t_avg=10.0)
    scene = dict(damping=0.3, **MODELS[model])
    torques = [0.5, 1.5]
    direction = "both"
    if key == "torques":
        torques = value
        try:
            assume(len(value) <= 8)
        except TypeError:
            pass
    elif key == "direction":
        direction = value
    elif key in ("damping", "theta0"):
        try:
            scene[key] = value
            s = Scene(**scene)
        except (SceneError, TypeError, ValueError):
            return
    else:
        kw[key] = value
    try:
        s = Scene(**scene)
    except SceneError:
        return
    r = _sweep_outcome(pendula.iv_curve, s, torques, direction, **kw)
    if r is not None:
        assert model is None
        for tau, vm, err, status in r.values():
            ok = status == 0
            assert np.all(np.isfinite(vm[ok])) and np.all(np.isfinite(err[ok]))


_SWEEP_FIELDS = {
    "grid1": ["0.5, 2.5", "'a', 'b'", "1e999", "nan", "", "3*1.0", "2.0**53", "1e300, -1e300"],
    "measure": ["'final_well'", "'poincare'", "'bogus'", "''", "1"],
    "sweep_t_max": ["20", "-1", "0", "1e15", "nan", "'x'"],
    "sweep_samples": ["2", "0", "-5", "1.5", "100000000"],
    "damping": ["0.5", "0", "-1", "1e308"],
    "theta0": ["0", "1e16", "1e308", "-4503599627370496"],
    "gravity": ["'uniform'", "'linear'"],
}
_OPTS = [[], ["--threads", "1000000"], ["--threads", "-1"], ["--workers", "-1"], ["--chunk-points", "0"],
         ["--threads", "2"], ["--chunk-points", "1"]]


@settings(**{**NEW, "max_examples": max(1, (FUZZ_N or 25) // 3)})
@given(st.lists(st.tuples(st.sampled_from(sorted(_SWEEP_FIELDS)), st.integers(0, 7)), max_size=2),
       st.sampled_from(_OPTS), st.sampled_from(["folder", "folder", "file", "missing-parent", "dev"]))
def test_sweep_cli_any_scene_and_options(changes, opts, target):
    from pendula.cli import main
    # a valid sweep scene (the first value of each field) with up to two fields changed
    fields = {k: v[0] for k, v in _SWEEP_FIELDS.items()}
    for k, i in changes:
        fields[k] = _SWEEP_FIELDS[k][i % len(_SWEEP_FIELDS[k])]
    with tempfile.TemporaryDirectory() as d:
        d = pathlib.Path(d)
        extra = " gravity_gradient = 0.2\n" if fields["gravity"] == "'linear'" else ""
        body = "".join(f" {k} = {v}\n" for k, v in fields.items())
        (d / "s.nml").write_text(f"&scene\n grid = 'v0'\n{body}{extra} drive_frequency = 0.6\n/\n")
        out = {"folder": d / "o", "file": d / "f", "missing-parent": d / "no" / "o", "dev": pathlib.Path("/dev/null")}[target]
        if target == "file":
            out.write_text("keep")
        err = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            code = main(["sweep", str(d / "s.nml"), "-o", str(out), "-q", *opts])
        assert code in (0, 2, 3, 4, 5), code
        event(f"exit {code}")
        if code:
            assert len(err.getvalue().strip().splitlines()) == 1, err.getvalue()
        if code == 0:
            assert (out / "sweep.zarr").is_dir() and (out / "sweep.png").is_file()
        leftovers = [p.name for p in d.rglob("*") if p.name.endswith((".part", ".tmp"))]
        assert not leftovers, leftovers
        if target == "file":
            assert out.read_text() == "keep"
        assert _stat.S_ISCHR(os.stat("/dev/null").st_mode)


@settings(**NEW)
@given(st.one_of(anything, st.lists(st.one_of(st.integers(-5, 300), anything), max_size=3)),
       st.sampled_from(["file", "folder", "missing-parent", "dev", "existing"]))
def test_wisdom_writer_any_sizes_and_path(sizes, target):
    if isinstance(sizes, (list, tuple)):
        assume(all(not (isinstance(n, int) and n > 4096) for n in sizes))
    elif isinstance(sizes, (int, np.integer)) and not isinstance(sizes, bool):
        sizes = [sizes]
        assume(sizes[0] <= 4096)
    with tempfile.TemporaryDirectory() as d:
        d = pathlib.Path(d)
        path = {"file": d / "w", "folder": d, "missing-parent": d / "no" / "w", "dev": pathlib.Path("/dev/null"),
                "existing": d / "old"}[target]
        if target == "existing":
            path.write_text("old wisdom")
        try:
            got = pendula.precompute_wisdom(sizes if sizes is not None else [64], path=path)
        except (ValueError, TypeError, OSError) as exc:
            assert str(exc)
            if target == "existing":
                assert path.read_text() == "old wisdom"
        else:
            assert target in ("file", "existing") and got.is_file() and got.stat().st_size > 0
        names = sorted(p.name for p in d.iterdir())
        assert names in ([], ["w"], ["old"]), names
        assert _stat.S_ISCHR(os.stat("/dev/null").st_mode)

"""A force of one's own: a C function pointer (ctypes from a library compiled here with the
system cc, a numba cfunc when numba is installed, an integer address) or, slowly, a Python callable.

The reference is the built-in effect the force restates: -b v is linear damping, so a user force
-0.1 v must reproduce damping = 0.1 to 1e-8 (both runs at rtol 1e-13; they differ in rounding only).
"""

import ctypes
import math
import os
import shutil
import signal
import subprocess

import numpy as np
import pytest

import pendula

TIGHT = dict(rtol=1e-13, atol=1e-15)
C_SOURCE = r"""
#include <math.h>
double linear_damping(double t, double theta, double v, const double *p) { return -p[0] * v; }
double nan_after(double t, double theta, double v, const double *p) { return t > p[0] ? NAN : 0.0; }
double magnet(double t, double theta, double v, const double *p) { return -p[0] * sin(theta) / pow(1.0 + p[1] - cos(theta), 1.5); }
"""


def _default_sigint():
    signal.signal(signal.SIGINT, signal.SIG_DFL)


@pytest.fixture(scope="module")
def clib(tmp_path_factory):
    cc = shutil.which("cc")
    if cc is None:
        pytest.skip("no C compiler (cc) on this machine")
    d = tmp_path_factory.mktemp("force")
    src, lib = d / "force.c", d / "libforce.so"
    src.write_text(C_SOURCE)
    subprocess.run([cc, "-O2", "-shared", "-fPIC", str(src), "-o", str(lib), "-lm"], check=True,
                   preexec_fn=_default_sigint if os.name == "posix" else None)
    so = ctypes.CDLL(str(lib))
    for name in ("linear_damping", "nan_after", "magnet"):
        f = getattr(so, name)
        f.restype = ctypes.c_double
        f.argtypes = [ctypes.c_double, ctypes.c_double, ctypes.c_double, ctypes.POINTER(ctypes.c_double)]
    return so


T = np.linspace(0.0, 30.0, 61)


def _damped():
    return pendula.simulate(pendula.Scene(theta0=1.0, v0=0.5, damping=0.1, **TIGHT), T)


def test_ctypes_force_reproduces_damping(clib):
    ref = _damped()
    tr = pendula.simulate(pendula.Scene(theta0=1.0, v0=0.5, **TIGHT), T, force=clib.linear_damping,
                          force_params=[0.1])
    assert tr.method == "dop853"
    assert np.max(np.abs(tr.theta - ref.theta)) < 1e-8 and np.max(np.abs(tr.v - ref.v)) < 1e-8


def test_integer_address_force_reproduces_damping(clib):
    addr = ctypes.cast(clib.linear_damping, ctypes.c_void_p).value
    tr = pendula.simulate(pendula.Scene(theta0=1.0, v0=0.5, **TIGHT), T, force=addr, force_params=(0.1,))
    assert np.max(np.abs(tr.theta - _damped().theta)) < 1e-8


def test_python_callable_force_is_the_slow_path():
    tr = pendula.simulate(pendula.Scene(theta0=1.0, v0=0.5, **TIGHT), T, force=lambda t, th, v, p: -p[0] * v,
                          force_params=[0.1])
    assert np.max(np.abs(tr.theta - _damped().theta)) < 1e-8


def test_numba_cfunc_force_reproduces_damping():
    numba = pytest.importorskip("numba")
    from numba import types

    @numba.cfunc(types.double(types.double, types.double, types.double, types.CPointer(types.double)))
    def lin(t, th, v, p):
        return -p[0] * v
    for f in (lin, lin.address):
        tr = pendula.simulate(pendula.Scene(theta0=1.0, v0=0.5, **TIGHT), T, force=f, force_params=[0.1])
        assert np.max(np.abs(tr.theta - _damped().theta)) < 1e-8


def test_force_with_fixed_step_and_gauss(clib):
    # rk4 and gauss6 evaluate the whole right-hand side: the force joins them (same as damping there)
    for meth in ("rk4", "gauss6"):
        sc = pendula.Scene(theta0=1.0, v0=0.5, method=meth, dt=0.01)
        a = pendula.simulate(sc, T, force=clib.linear_damping, force_params=[0.1])
        b = pendula.simulate(sc.replace(damping=0.1), T)
        assert np.max(np.abs(a.theta - b.theta)) < 1e-12


def test_force_refused_by_splitting_methods(clib):
    with pytest.raises(ValueError, match="'method'"):
        pendula.simulate(pendula.Scene(theta0=1.0, method="verlet", dt=0.01), T, force=clib.linear_damping,
                         force_params=[0.1])


def test_force_with_friction_and_pivot(clib):
    # the force joins the switching stretches and the pivot
    sc = pendula.Scene(theta0=1.0, friction=0.02, pivot_amplitude=0.01, pivot_frequency=10.0, **TIGHT)
    a = pendula.simulate(sc, T, force=clib.linear_damping, force_params=[0.1])
    b = pendula.simulate(sc.replace(damping=0.1), T)
    assert np.max(np.abs(a.theta - b.theta)) < 1e-8


def test_periodic_orbit_with_force(clib):
    # the driven damped pendulum's cycle with its damping given as a force: same orbit, same multipliers
    sc = pendula.Scene(drive_amplitude=0.9, drive_frequency=2 / 3)
    a = pendula.periodic_orbit(sc, guess=(0.5, 0.5), force=clib.linear_damping, force_params=[0.5])
    b = pendula.periodic_orbit(sc.replace(damping=0.5), guess=(0.5, 0.5))
    assert abs(a.theta - b.theta) < 1e-8 and abs(a.v - b.v) < 1e-8
    assert np.max(np.abs(a.multipliers - b.multipliers)) < 1e-6    # its Jacobian by central differences


def test_nan_force_stops_with_time_and_state(clib):
    with pytest.raises(ValueError, match=r"after t = .*theta = .*v = "):
        pendula.simulate(pendula.Scene(theta0=1.0), T, force=clib.nan_after, force_params=[7.0])


def test_python_force_exception_is_raised():
    def bad(t, th, v, p):
        raise ZeroDivisionError("inside the force")
    with pytest.raises(ZeroDivisionError, match="inside the force"):
        pendula.simulate(pendula.Scene(theta0=1.0), T, force=bad)


@pytest.mark.parametrize("f, err", [(None, TypeError), (3.5, TypeError), ("f", TypeError), (0, ValueError),
                                    (-5, ValueError)])
def test_bad_force_is_a_clear_error(f, err):
    with pytest.raises(err, match="force"):
        pendula.simulate(pendula.Scene(theta0=1.0), T, force=f, force_params=[0.1])


def test_ctypes_force_without_signature_refused(clib):
    so_f = clib.magnet
    g = ctypes.CDLL(so_f.__class__.__module__ and clib._name).magnet    # restype not set: int
    with pytest.raises(TypeError, match="restype"):
        pendula.simulate(pendula.Scene(theta0=1.0), T, force=g, force_params=[0.1, 1.0])


@pytest.mark.parametrize("params", ["ab", [[1.0, 2.0], [3.0, 4.0]], [math.nan], ["x"]])
def test_bad_force_params_are_clear_errors(clib, params):
    with pytest.raises((TypeError, ValueError), match="force_params"):
        pendula.simulate(pendula.Scene(theta0=1.0), T, force=clib.linear_damping, force_params=params)


def test_force_refused_on_cord_and_cycloid(clib):
    for sc in (pendula.Scene(theta0=0.5, guide="cycloid"),):
        with pytest.raises(ValueError, match="user force"):
            pendula.simulate(sc, T, force=clib.linear_damping, force_params=[0.1])


def test_sweep_with_force_reproduces_damping(clib):
    # the force from every OpenMP thread: a mean-velocity and a lyapunov sweep with the damping given as
    # a C force agree with the built-in damping's sweep (the same sums in another order: to rounding)
    grid = {"drive_amplitude": [0.5, 0.9]}      # periodic attractors: rounding does not grow
    base = pendula.Scene(drive_frequency=2 / 3, theta0=0.2)
    for measure, kw in (("mean_velocity", dict(t_max=100.0, transient=50.0)),
                        ("lyapunov", dict(t_max=200.0, transient=50.0))):
        a = pendula.sweep(base, over=grid, measure=measure, force=clib.linear_damping, force_params=[0.5],
                          threads=2, **kw)
        b = pendula.sweep(base.replace(damping=0.5), over=grid, measure=measure, threads=2, **kw)
        var = "mean_velocity" if measure == "mean_velocity" else "lyapunov"
        # decided, or (a mean velocity over whole drive periods) phase-locked: status 6
        assert np.all(np.isin(a.status.values, (0, 6)))
        assert np.array_equal(a.status.values, b.status.values)
        assert np.allclose(a[var].values, b[var].values, rtol=0, atol=1e-6)


def test_sweep_force_final_well_refused_by_name(clib):
    # the final well is judged by the undriven pendulum's energy: a user force is refused at the door
    with pytest.raises(ValueError, match="force"):
        pendula.sweep(pendula.Scene(damping=0.1), over={"v0": [1.0, 2.0]}, measure="final_well",
                      force=clib.linear_damping, force_params=[0.0])


def test_sweep_force_refused_with_a_store(clib, tmp_path):
    with pytest.raises(ValueError, match="'force' and 'out'"):
        pendula.sweep(pendula.Scene(damping=0.1), over={"v0": [1.0]}, measure="mean_velocity",
                      force=clib.linear_damping, force_params=[0.1], out=tmp_path / "s.zarr")


def test_force_params_of_the_wrong_length_for_nparams():
    def lin(t, th, v, p):
        return -p[0] * v
    lin.nparams = 1
    with pytest.raises(ValueError, match="force_params: the force reads 1"):
        pendula.simulate(pendula.Scene(theta0=1.0), T, force=lin, force_params=[0.1, 0.2])
    assert np.isfinite(pendula.simulate(pendula.Scene(theta0=1.0), T, force=lin, force_params=[0.1]).theta).all()

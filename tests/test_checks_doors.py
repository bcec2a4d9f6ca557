"""The one checker at doors other than simulate's: a force's address and return value through the
dynamics, the plot functions' arguments, and a damaged store's folder of completion records.

The references are the promises of docs/source/bad_input.rst: a wrong kind or value is a TypeError or
ValueError naming the argument; a store damaged inside is built again, with a warning naming what.
"""

import ctypes
import os
import shutil

import numpy as np
import pytest

import pendula
from pendula import Scene

DRIVEN = Scene(damping=0.5, drive_amplitude=0.9, drive_frequency=2 / 3)
PROTO = ctypes.CFUNCTYPE(ctypes.c_double, ctypes.c_double, ctypes.c_double, ctypes.c_double,
                         ctypes.POINTER(ctypes.c_double))


@pytest.mark.parametrize("force", [2**63, 2**64 - 1, PROTO()], ids=["2**63", "2**64-1", "NULL"])
def test_force_address_out_of_range_is_named_by_periodic_orbit(force):
    with pytest.raises(ValueError, match="force"):
        pendula.periodic_orbit(DRIVEN, guess=(0.5, 0.5), force=force, force_params=[1.0])


@pytest.mark.parametrize("ret", [np.array([0.0]), "0.0", True, None], ids=["array", "str", "bool", "None"])
def test_python_force_returning_a_non_real_is_named_by_periodic_orbit(ret):
    with pytest.raises(TypeError, match="force must return a real number"):
        pendula.periodic_orbit(DRIVEN, guess=(0.5, 0.5), force=lambda t, th, v, p: ret, force_params=[0.1])


def test_python_force_returning_a_numpy_real_is_taken():
    po = pendula.periodic_orbit(DRIVEN, guess=(0.5, 0.5), force=lambda t, th, v, p: np.float64(0.0))
    ref = pendula.periodic_orbit(DRIVEN, guess=(0.5, 0.5))
    assert abs(po.theta - ref.theta) < 1e-9 and abs(po.v - ref.v) < 1e-9


def test_plot_arguments_are_named():
    pytest.importorskip("matplotlib")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pendula.plot as pp

    tr = pendula.simulate(Scene(theta0=1.0, t_end=50.0, n_samples=512))
    sp = tr.spectrum()
    for call, name, exc in [(lambda: pp.phase(None), "tr", TypeError), (lambda: pp.trajectory(sp), "tr", TypeError),
                            (lambda: pp.spectrum(sp, harmonics=0), "harmonics", ValueError),
                            (lambda: pp.spectrum(sp, harmonics=2.5), "harmonics", TypeError),
                            (lambda: pp.phase(tr, separatrix="yes"), "separatrix", TypeError),
                            (lambda: pp.basins(42), "am", TypeError), (lambda: pp.fractions([1, 2]), "ds", TypeError),
                            (lambda: pp.phase(tr, ax=plt), "ax", TypeError)]:
        with pytest.raises(exc, match=name):
            call()
        plt.close("all")


def test_store_with_an_empty_commits_folder_is_rebuilt(tmp_path):
    pytest.importorskip("zarr")
    s = Scene(damping=0.1)
    grid = {"v0": np.linspace(0, 4, 8)}
    out = tmp_path / "o"
    ref = pendula.sweep(s, grid, "final_well", out=out, chunk_points=4).well.values.copy()
    commits = os.path.join(out, "sweep.zarr", "commits")
    shutil.rmtree(commits)
    os.mkdir(commits)                     # a folder under the name, but not the group of records
    from pendula._store import SweepStoreWarning
    with pytest.warns(SweepStoreWarning, match="commits"):
        again = pendula.sweep(s, grid, "final_well", out=out, chunk_points=4).well.values
    np.testing.assert_array_equal(again, ref)

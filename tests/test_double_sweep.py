"""The double pendulum's flip-time map as a sweep (DoublePendulum.flip_sweep): the same numbers, bit for
bit, as the one-piece map (DoublePendulum.flip_map, itself checked against SciPy's events in
test_double_motion.py) whatever the chunking, the thread count, a resumption of a stopped store or a Dask
cluster; a store of another map refused; bad arguments named."""

import shutil

import numpy as np
import pytest

import pendula

xr = pytest.importorskip("xarray")
pytest.importorskip("zarr")

TH1 = np.linspace(-3.0, 3.0, 7)
TH2 = np.linspace(-2.9, 3.1, 6)
KW = dict(t_max=8.0, rtol=1e-8, atol=1e-8)


@pytest.fixture(scope="module")
def reference():
    return pendula.DoublePendulum().flip_map(TH1, TH2, **KW)


def same(a, b):
    """Bit for bit (NaN equal to NaN, inf to inf)."""
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def check_equal(ds, fm):
    assert ds.time.dims == ("theta1", "theta2")
    assert same(ds.theta1.values, fm.theta1) and same(ds.theta2.values, fm.theta2)
    assert same(ds.time.values, fm.time) and same(ds.check.values, fm.check)
    assert np.array_equal(ds.forbidden.values.astype(bool), fm.forbidden)
    assert np.array_equal(ds.unresolved.values.astype(bool), fm.unresolved)
    assert np.all(ds.status.values == 0)


def test_flip_sweep_in_memory_equals_flip_map_for_any_chunking_and_threads(reference):
    dp = pendula.DoublePendulum()
    assert np.isfinite(reference.time).any() and reference.forbidden.any()   # all three kinds of pixel present
    for chunk_points, threads in ((6, 1), (13, 2), (1000, 0)):
        ds = dp.flip_sweep(TH1, TH2, chunk_points=chunk_points, threads=threads, progress=False, **KW)
        check_equal(ds, reference)


def test_flip_sweep_store_resumed_after_a_lost_chunk_is_bit_identical(tmp_path, reference):
    dp = pendula.DoublePendulum()
    out = tmp_path / "flip"
    ds = dp.flip_sweep(TH1, TH2, out=out, chunk_points=12, threads=2, progress=False, **KW)   # 2 rows a chunk
    check_equal(ds.load(), reference)
    commits = out / "sweep.zarr" / "commits"
    assert len(list(commits.glob("c*/zarr.json"))) == 4
    # a run stopped before chunk 1's record was written: the next run computes that chunk alone again
    shutil.rmtree(commits / "c000001")
    again = dp.flip_sweep(TH1, TH2, out=out, chunk_points=12, threads=1, progress=False, **KW)
    check_equal(again.load(), reference)
    assert len(list(commits.glob("c*/zarr.json"))) == 4
    opened = xr.open_zarr(out / "sweep.zarr")
    check_equal(opened.load(), reference)
    assert opened.attrs["t_max"] == KW["t_max"] and opened.time.attrs["units"] == "1"


def test_flip_sweep_store_of_another_map_is_refused(tmp_path):
    dp = pendula.DoublePendulum()
    out = tmp_path / "flip"
    dp.flip_sweep(TH1[:2], TH2, out=out, progress=False, **KW)
    with pytest.raises(ValueError, match="sweep"):
        pendula.DoublePendulum(m2=2.0).flip_sweep(TH1[:2], TH2, out=out, progress=False, **KW)


def test_flip_sweep_on_a_dask_cluster_equals_flip_map(reference):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        ds = pendula.DoublePendulum().flip_sweep(TH1, TH2, client=client, chunk_points=12, progress=False, **KW)
    check_equal(ds, reference)


@pytest.mark.parametrize("kw, match", [
    (dict(theta1=[4.0]), "theta1"), (dict(theta2=[]), "theta2"), (dict(t_max=-1.0), "t_max"),
    (dict(chunk_points=0), "chunk_points"), (dict(progress="yes"), "progress"), (dict(client="tcp://x:1"), "client"),
    (dict(agree=0.0), "agree")])
def test_flip_sweep_bad_arguments_named(kw, match):
    args = dict(theta1=TH1[:2], theta2=TH2[:2], progress=False)
    args.update(kw)
    with pytest.raises((ValueError, TypeError), match=match):
        pendula.DoublePendulum().flip_sweep(args.pop("theta1"), args.pop("theta2"), **args)


def test_flip_sweep_dataset_draws_the_same_figure_as_the_flip_map(reference):
    pytest.importorskip("matplotlib")
    import matplotlib.pyplot as plt

    import pendula.plot

    ds = pendula.DoublePendulum().flip_sweep(TH1, TH2, progress=False, **KW)
    a, b = pendula.plot.flip_map(ds), pendula.plot.flip_map(reference)
    for ma, mb in zip(a.collections, b.collections):
        assert same(np.ma.filled(ma.get_array(), -7.0), np.ma.filled(mb.get_array(), -7.0))
    assert [t.get_text() for t in a.get_legend().get_texts()] == [t.get_text() for t in b.get_legend().get_texts()]
    plt.close("all")


def test_flip_sweep_on_worker_processes_into_a_store_equals_flip_map(tmp_path, reference):
    """Two worker processes (the plan pickled to them, the chunks computed there and written by this
    process): the stored map equals the one-piece map bit for bit."""
    import logging

    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None, silence_logs=logging.CRITICAL) as cluster, \
            distributed.Client(cluster, timeout=60) as client:
        client.wait_for_workers(2, timeout=60)
        ds = pendula.DoublePendulum().flip_sweep(TH1, TH2, out=tmp_path / "flip", client=client, chunk_points=6,
                                                 progress=False, **KW)
        check_equal(ds.load(), reference)


def test_flip_map_to_xarray_is_the_sweeps_dataset(reference):
    ds = pendula.DoublePendulum().flip_sweep(TH1, TH2, progress=False, **KW)
    fx = reference.to_xarray()
    for name in ("time", "check", "forbidden", "unresolved", "status", "theta1", "theta2"):
        assert same(fx[name].values, ds[name].values), name
        assert fx[name].attrs.keys() == ds[name].attrs.keys()
    assert {k: fx.attrs[k] for k in ("t_max", "rtol", "agree")} == {k: ds.attrs[k] for k in ("t_max", "rtol", "agree")}

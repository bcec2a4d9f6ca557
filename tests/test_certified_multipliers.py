"""Certified Floquet multipliers: the residuals every periodic orbit and branch point carries, and a
stability verdict that does not depend on the integrator's tolerance.

References: Liouville's formula det M = exp(-damping T) (closed form), the trivial multiplier 1 of an
autonomous orbit (closed form), and scipy's DOP853 at rtol 1e-12 on the variational equations for the
multipliers themselves.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pendula
from pendula import Scene

BETA, OMEGA = 0.5, 2 / 3
CASCADE = Scene(damping=BETA, drive_amplitude=1.0, drive_frequency=OMEGA)
TD = 2 * math.pi / OMEGA
#: the first doubling of the asymmetric period-1 orbit (data/continuation_reference.json) and its state
PD1, PD1_STATE = 1.0663728624552025, (-2.334757364214882, 1.2526032124106485)
TOLERANCES = (1e-8, 1e-10, 1e-12)


@pytest.fixture(scope="module")
def tree():
    # the symmetric orbit, its two asymmetric children and their period-2 children: stable and unstable points
    return pendula.bifurcation_tree(CASCADE, (0.1, 1.9), "drive_amplitude", 1.0805, depth=2)


def scipy_multipliers(x, A, k):
    """The multipliers of the k-period map at x from scipy's variational equations (rtol 1e-12)."""
    def rhs(t, y):
        th, v, a, b, c, d = y
        dc = -math.cos(th)
        return [v, -BETA * v - math.sin(th) + A * math.cos(OMEGA * t), b, dc * a - BETA * b, d, dc * c - BETA * d]
    s = solve_ivp(rhs, (0.0, k * TD), [x[0], x[1], 1.0, 0.0, 0.0, 1.0], method="DOP853", rtol=1e-12, atol=1e-12)
    y = s.y[:, -1]
    return np.linalg.eigvals(np.array([[y[2], y[4]], [y[3], y[5]]]))


def test_liouville_residual_of_every_point_of_the_tree(tree):
    for br in tree.branches():
        T = br.period * TD
        # det M = exp(-damping T): 1e-8 relative plus 1e-12 |mu_1|^2, the flow's error on the monodromy's
        # entries (as along the attracting route in tests/test_continuation.py)
        tol = 1e-8 * np.exp(-BETA * T) + 1e-12 * np.maximum(1.0, np.abs(br.multipliers[:, 0])) ** 2
        assert np.all(br.det_residual <= tol)
        det = np.prod(br.multipliers, axis=1).real
        # the residual is of det M itself: the product of the multipliers agrees to rounding
        np.testing.assert_allclose(np.abs(det - np.exp(-BETA * T)), br.det_residual, rtol=0, atol=1e-14)
        assert np.all(np.isnan(br.trivial_residual))
    for bif in tree.branch.bifurcations:
        assert bif.det_residual <= 1e-12 and math.isnan(bif.trivial_residual)


def test_verdict_is_the_same_at_three_tolerances_and_agrees_with_scipy(tree):
    rng = np.random.default_rng(6)
    points = [(br, i) for br in tree.branches() for i in range(len(br))]
    chosen = [points[j] for j in rng.choice(len(points), size=10, replace=False)]
    stable_seen = set()
    for br, i in chosen:
        A, k = float(br.values[i]), int(br.period[i])
        mu_ref = scipy_multipliers((br.theta[i], br.v[i]), A, k)
        verdict = bool(np.all(np.abs(mu_ref) < 1))
        assert br.stable[i] == verdict and br.certified[i]
        for r in TOLERANCES:
            # Newton's tolerance above the flow's noise at that rtol
            po = pendula.periodic_orbit(CASCADE.replace(drive_amplitude=A), (br.theta[i], br.v[i]), k=k, rtol=r,
                                        atol=r, tol=max(1e-11, 1e3 * r))
            assert po.multiplier_error == pytest.approx(100 * r * (1 + np.linalg.norm(po.monodromy)) ** 2)
            if po.certified:
                assert po.stable == verdict, (A, k, r)
            assert po.det_residual <= po.multiplier_error
        # the tightest tolerance certifies every point away from a bifurcation (the margins here exceed 1e-4)
        assert po.certified
        stable_seen.add(verdict)
    assert stable_seen == {True, False}        # both verdicts were tested


@pytest.mark.parametrize("offset", [-1e-9, 1e-9])
def test_verdict_next_to_a_doubling_is_not_certified_at_a_loose_tolerance(offset):
    sc = CASCADE.replace(drive_amplitude=PD1 + offset)
    loose = pendula.periodic_orbit(sc, PD1_STATE, rtol=1e-8, atol=1e-8, tol=1e-5)
    # the multiplier is -1 +- 4e-8 there: within the error 4e-6 of a flow at rtol 1e-8, so no verdict is claimed
    assert not loose.certified
    tight = pendula.periodic_orbit(sc, PD1_STATE, rtol=1e-12, atol=1e-12)
    if tight.certified:
        assert tight.stable == (offset < 0)


@pytest.mark.parametrize("offset", [-1e-6, 1e-6])
def test_verdict_a_little_further_from_the_doubling_is_certified_at_every_tolerance(offset):
    sc = CASCADE.replace(drive_amplitude=PD1 + offset)
    for r in TOLERANCES:
        po = pendula.periodic_orbit(sc, PD1_STATE, rtol=r, atol=r, tol=max(1e-11, 1e3 * r))
        assert po.certified and po.stable == (offset < 0), r


def test_located_bifurcations_on_the_attracting_route_are_not_certified():
    br = pendula.continue_orbit(CASCADE, (0.1, 1.9), "drive_amplitude", 1.0795, follow="stable")
    on = np.isin(br.values, [b.value for b in br.bifurcations])
    assert on.sum() == 3
    # at a located bifurcation a multiplier is +1 or -1 to the test function's error: no verdict
    assert not np.any(br.certified[on]) and np.all(br.certified[~on])


def test_trivial_multiplier_of_the_running_orbit_certifies_it():
    br = pendula.continue_orbit(Scene(damping=0.3, torque=1.5), (0.0, 5.0), "torque", 0.0)
    # the trivial multiplier is 1 exactly: measured within 1e-12 while the period is short; it drifts to
    # about 1e-7 as the orbit nears the saddle and the monodromy grows (its eigenvalue 1 becomes
    # ill-conditioned): the certificate says how far the multipliers can be trusted
    short = br.period < 6.0
    assert np.all(br.trivial_residual[short] < 1e-11)
    assert np.all(br.trivial_residual < 1e-6)
    det = np.exp(-0.3 * br.period)
    assert np.all(br.det_residual <= 1e-8 * det + 1e-11)
    assert np.all(br.certified) and np.all(br.stable)

"""Whole bifurcation diagrams (bifurcation_tree) against independent computations.

References: data/continuation_reference.json (data/gen_continuation_reference.py: scipy's DOP853 at
1e-13 on the equation and its variational equations, Newton on the stroboscopic map, brentq on
1 -+ tr M + det M) for every branch point of the tree, and scipy's solve_ivp at rtol 1e-12 here for
the stroboscopic map that carries each point of a k-cycle to the next.
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pendula
from pendula import Scene

REF = json.loads((Path(__file__).resolve().parents[1] / "data" / "continuation_reference.json").read_text())
BETA, OMEGA = 0.5, 2 / 3
CASCADE = Scene(damping=BETA, drive_amplitude=1.0, drive_frequency=OMEGA)
POINTS = REF["cascade"]["points"]
#: past the third doubling (period 4 -> 8, at about 1.082084), before the fourth (about 1.082678)
STOP = POINTS[3]["value"] + 3e-4


@pytest.fixture(scope="module")
def tree():
    return pendula.bifurcation_tree(CASCADE, (0.1, 1.9), "drive_amplitude", STOP, depth=4)


def strobe(x, A):
    """One drive period of the driven pendulum from x at t = 0 (scipy, rtol 1e-12)."""
    s = solve_ivp(lambda t, y: [y[1], -BETA * y[1] - math.sin(y[0]) + A * math.cos(OMEGA * t)],
                  (0.0, 2 * math.pi / OMEGA), x, method="DOP853", rtol=1e-12, atol=1e-12)
    return s.y[:, -1]


def test_tree_holds_both_pitchfork_children_and_each_doubling(tree):
    got = [(node.generation, int(node.branch.period[0])) for node in tree.walk()]
    assert got == [(0, 1), (1, 1), (2, 2), (3, 4), (4, 8), (1, 1), (2, 2), (3, 4), (4, 8)]
    assert len(tree) == 9
    # every branch reached the stop (the range's edge): none lost to an error
    assert all(b.end == "stop" for b in tree.branches())
    # the two pitchfork children are two orbits (mirror images), born at the one pitchfork
    a, b = tree.children
    assert a.origin is b.origin and a.origin.kind == "pitchfork"
    assert a.branch.values[-1] == b.branch.values[-1] == STOP
    assert abs(a.branch.theta[-1] - b.branch.theta[-1]) > 0.1


def test_tree_branch_points_against_scipy(tree):
    # 1e-8 in the drive amplitude, as for the attracting route (tests/test_continuation.py): the flows of
    # both are accurate to about 1e-12 and the test functions' roots move by that over |d psi / dA| > 1
    want = {(p["kind"], p["k"]): p["value"] for p in POINTS}
    seen = []
    for node in tree.walk():
        for bif in node.branch.bifurcations:
            key = (bif.kind, int(bif.period))
            assert key in want, bif
            assert abs(bif.value - want[key]) < 1e-8, (bif, want[key])
            seen.append(key)
    # the root's pitchfork once; each doubling of periods 1, 2, 4 once in each mirror child's subtree
    assert sorted(seen) == sorted([("pitchfork", 1)] + 2 * [("period-doubling", k) for k in (1, 2, 4)])
    # each child starts at its origin (the first point next to it: the child's offset is c hb^2)
    for node in list(tree.walk())[1:]:
        assert abs(node.branch.values[0] - node.origin.value) < 1e-3


def test_children_k_cycles_map_onto_each_other_under_the_stroboscopic_map(tree):
    rng = np.random.default_rng(44)
    for node in tree.walk():
        br = node.branch
        k = int(br.period[0])
        assert br.cycle.shape == (len(br), k, 2)
        np.testing.assert_array_equal(br.cycle[:, 0, 0], br.theta)
        np.testing.assert_array_equal(br.cycle[:, 0, 1], br.v)
        away = np.flatnonzero(np.abs(np.abs(br.multipliers[:, 0]) - 1) > 1e-3)
        for i in rng.choice(away, size=min(3, len(away)), replace=False):
            A = float(br.values[i])
            for j in range(k):
                y = strobe(br.cycle[i, j], A)
                nxt = br.cycle[i, (j + 1) % k]
                # 1e-8: Newton's tolerance 1e-11 and the flows' 1e-12, times the map's growth over one period
                assert abs(math.remainder(y[0] - nxt[0], 2 * math.pi)) < 1e-8, (k, i, j)
                assert abs(y[1] - nxt[1]) < 1e-8, (k, i, j)
            if k > 1:
                # a cycle of period k, not of a divisor: its points are distinct
                assert np.min(np.abs(br.cycle[i, 1:, 1] - br.cycle[i, 0, 1])) > 1e-6


def test_stability_changes_at_the_branch_points(tree):
    for node in tree.walk():
        br = node.branch
        for bif in br.bifurcations:
            # supercritical: the parent attracts before its branch point, repels after it
            before = br.values < bif.value - 1e-9
            after = br.values > bif.value + 1e-9
            assert np.all(br.stable[before]) and not np.any(br.stable[after]), (node.generation, bif)
        for child in node.children:
            # the child is born attracting (its multiplier 1 - O(hb^2))
            assert child.branch.stable[0]


def test_depth_zero_is_the_one_branch_of_continue_orbit():
    stop = 1.01
    tree = pendula.bifurcation_tree(CASCADE, (0.1, 1.9), "drive_amplitude", stop, depth=0)
    br = pendula.continue_orbit(CASCADE, (0.1, 1.9), "drive_amplitude", stop)
    assert len(tree) == 1 and tree.children == ()
    np.testing.assert_array_equal(tree.branch.values, br.values)
    assert [b.value for b in tree.branch.bifurcations] == [b.value for b in br.bifurcations]
    assert tree.missing == ("pitchfork at drive_amplitude = %r: the depth 0 is reached" % br.bifurcations[0].value,)


def test_branch_cycle_of_the_attracting_route_has_every_period():
    stop = POINTS[2]["value"] + 1e-3       # past the doubling of the period-2 orbit
    br = pendula.continue_orbit(CASCADE, (0.1, 1.9), "drive_amplitude", stop, follow="stable")
    assert br.cycle.shape[1] == 4
    for i in range(len(br)):
        k = int(br.period[i])
        assert np.all(np.isfinite(br.cycle[i, :k])) and np.all(np.isnan(br.cycle[i, k:]))
    i = len(br) - 1
    y = strobe(br.cycle[i, 3], float(br.values[i]))
    assert abs(math.remainder(y[0] - br.cycle[i, 0, 0], 2 * math.pi)) < 1e-8


@pytest.mark.parametrize("depth, error", [(-1, ValueError), (13, ValueError), (1.5, TypeError), ("2", TypeError)])
def test_depth_out_of_range_is_named(depth, error):
    with pytest.raises(error, match="depth"):
        pendula.bifurcation_tree(CASCADE, (0.1, 1.9), "drive_amplitude", 1.01, depth=depth)


def test_bad_param_is_named_as_in_continue_orbit():
    with pytest.raises(ValueError, match="param"):
        pendula.bifurcation_tree(CASCADE, (0.1, 1.9), "colour", 1.01)


def test_child_that_cannot_go_on_keeps_what_it_traced(monkeypatch):
    # a corrector that fails on the period-2 orbit after its first steps stands for a child the steps cannot
    # follow: that branch ends with the error and keeps its points; the rest of the tree is traced
    from pendula.dynamics import continuation as C
    from pendula.dynamics.periodic import NewtonError
    real = C._Tracer.correct

    def failing(self, prob, Upred, n, U0, maxit=C._MAXIT):
        if prob.k == 2:          # counted per tracer: each period-2 branch takes a few steps, then fails
            self.test_calls = getattr(self, "test_calls", 0) + 1
            if self.test_calls > 6:
                raise NewtonError("no convergence", maxit, 1.0, (Upred[:2], Upred[2]))
        return real(self, prob, Upred, n, U0, maxit)
    monkeypatch.setattr(C._Tracer, "correct", failing)
    tree = pendula.bifurcation_tree(CASCADE, (0.1, 1.9), "drive_amplitude", 1.07, depth=2)
    ends = [(int(b.period[0]), b.end) for b in tree.branches()]
    assert [k for k, _ in ends] == [1, 1, 2, 1, 2]
    failed = [(k, e) for k, e in ends if e.startswith("error")]
    assert [k for k, _ in failed] == [2, 2]
    assert all("drive_amplitude" in e for _, e in failed)
    for node in tree.walk():
        assert len(node.branch) >= 2           # the first point and the steps before the failure
    assert all(e == "stop" for k, e in ends if k == 1)


def test_branch_points_keep_their_cycle_and_certificates(tree):
    for node in tree.walk():
        for bif in node.branch.bifurcations:
            k = int(bif.period)
            assert bif.cycle.shape == (k, 2)
            assert (bif.cycle[0, 0], bif.cycle[0, 1]) == (bif.theta, bif.v)
            # the k-cycle closes under scipy's stroboscopic map: its residual is Newton's (1e-11) plus the
            # flows' error over a period (measured up to 1.3e-11 here); 1e-9 leaves a margin of 75
            x = bif.cycle[-1]
            y = strobe(x, bif.value)
            assert abs(math.remainder(y[0] - bif.cycle[0, 0], 2 * math.pi)) < 1e-9
            assert abs(y[1] - bif.cycle[0, 1]) < 1e-9
            assert bif.det_residual < 1e-12 and math.isnan(bif.trivial_residual)
    ds = tree.children[0].children[0].branch.to_xarray()
    assert dict(ds.sizes)["cycle"] == 2
    assert {"cycle_theta", "cycle_v", "det_residual", "certified"} <= set(ds.data_vars)

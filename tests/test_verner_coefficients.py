"""Verner's 9(8) pair of the kernel (method 'vern9'): the Butcher order conditions.

Every rooted tree t of order <= 9 (486 trees) gives one condition b . Phi(t) = 1 / gamma(t)
(Butcher; Hairer, Norsett & Wanner, Solving ODEs I, section II.2).  They are checked for the
45-digit coefficients (data/verner98_coefficients.csv) to 1e-35, for the doubles the kernel
uses (kernel/integrators/pendula_rk_tables.inc) to 1e-13, and for the embedded weights
b - e to order 8 only (some order-9 condition fails by far more: the estimate measures).
"""

import functools
import pathlib
import re
import sys

import mpmath as mp
import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "data"))
from gen_rk_tables import verner98_matrices  # noqa: E402

TABLE = ROOT / "kernel" / "integrators" / "pendula_rk_tables.inc"


@functools.lru_cache(maxsize=None)
def trees(n):
    """Canonical rooted trees with n nodes: a tree is the sorted tuple of its children."""
    if n == 1:
        return [()]
    out = set()

    def build(remaining, max_child, acc):
        if remaining == 0:
            out.add(tuple(sorted(acc)))
            return
        for k in range(min(remaining, max_child), 0, -1):
            for t in trees(k):
                build(remaining - k, k, acc + [t])
    build(n - 1, n - 1, [])
    return sorted(out)


def order(t):
    return 1 + sum(order(c) for c in t)


def gamma(t):
    g = order(t)
    for c in t:
        g *= gamma(c)
    return g


def elementary_weights(A):
    """t -> Phi(t), the vector over the stages of the elementary weights of tree t (memoised)."""
    s = len(A)
    memo = {}

    def phi(t):   # vector over stages
        if t not in memo:
            v = [1] * s
            for ch in t:
                p = phi(ch)
                ap = [sum(A[i][j] * p[j] for j in range(s)) for i in range(s)]
                v = [v[i] * ap[i] for i in range(s)]
            memo[t] = v
        return memo[t]
    return phi


def residuals(c, A, b, max_order):
    """max |b . Phi(t) - 1/gamma(t)| per order, for the tableau (any number type)."""
    s = len(b)
    phi = elementary_weights(A)
    res = {}
    for n in range(1, max_order + 1):
        res[n] = max(abs(sum(b[i] * phi(t)[i] for i in range(s)) - mp.mpf(1) / gamma(t)) for t in trees(n))
    return res


def test_tree_counts_are_the_known_ones():
    assert [len(trees(n)) for n in range(1, 10)] == [1, 1, 2, 4, 9, 20, 48, 115, 286]


@pytest.fixture(scope="module")
def exact():
    mp.mp.dps = 50
    return verner98_matrices()


def test_verner_rows_sum_to_the_nodes(exact):
    c, A, b, e = exact
    assert max(abs(sum(A[i]) - c[i]) for i in range(16)) < mp.mpf("1e-40")


def test_verner_weights_satisfy_all_conditions_to_order_nine(exact):
    c, A, b, e = exact
    res = residuals(c, A, b, 9)
    assert max(res.values()) < mp.mpf("1e-35"), res


def test_verner_embedded_weights_are_of_order_eight_exactly(exact):
    c, A, b, e = exact
    bhat = [b[i] - e[i] for i in range(16)]
    res = residuals(c, A, bhat, 9)
    assert max(res[n] for n in range(1, 9)) < mp.mpf("1e-35"), res
    assert res[9] > mp.mpf("1e-6"), res


def stored(name):
    text = TABLE.read_text()
    m = re.search(rf"real\(dp\), parameter :: {name}\((0:\d+)(?:, (0:\d+))?\) = (?:reshape\()?\[(.*?)\]", text, re.S)
    assert m, name
    vals = [float(v.replace("_dp", "")) for v in re.findall(r"-?[0-9.]+(?:[eE][-+]?\d+)?_dp", m.group(3))]
    n = int(m.group(1).split(":")[1]) + 1
    a = np.array(vals)
    return a.reshape((n, int(m.group(2).split(":")[1]) + 1), order="F") if m.group(2) else a


def test_verner_doubles_of_the_kernel_satisfy_the_conditions(exact):
    mp.mp.dps = 30
    c, A, b = stored("v9_c"), stored("v9_a"), stored("v9_b")
    res = residuals([mp.mpf(x) for x in c], [[mp.mpf(x) for x in r] for r in A], [mp.mpf(x) for x in b], 9)
    assert max(res.values()) < 1e-13, res
    # and each double is its exact coefficient rounded
    ce, Ae, be, ee = exact
    assert all(float(x) == y for x, y in zip(be, b)) and all(float(x) == y for x, y in zip(ce, c))


# ---------------------------------------------------------------- the interpolant

def test_verner_interpolant_extends_the_rows_to_their_nodes():
    """The five stages of the interpolant (data/verner98_interpolant.csv) sum to their nodes, and
    stage 17 is the step's own new point (the row of b, at c = 1)."""
    from gen_rk_tables import verner98_interpolant
    c, A, _ = verner98_interpolant()
    _, _, b, _ = verner98_matrices()
    assert max(abs(sum(A[i]) - c[i]) for i in range(16, 21)) < mp.mpf(10) ** -38
    assert c[16] == 1 and max(abs(A[16][j] - b[j]) for j in range(16)) < mp.mpf(10) ** -38


def test_verner_interpolant_ends_on_the_step():
    """b_i(1) = sum_k P_ik is the pair's own 9th-order weight b_i (0 for the five new stages)."""
    from gen_rk_tables import verner98_interpolant
    _, _, P = verner98_interpolant()
    _, _, b, _ = verner98_matrices()
    assert max(abs(sum(P[i]) - (b[i] if i < 16 else 0)) for i in range(21)) < mp.mpf(10) ** -34   # 40 digits, sums of 8


def test_verner_interpolant_satisfies_the_continuous_conditions_to_order_eight():
    """A continuous extension of order 8: for every tree t with r <= 8 nodes and every power k of
    x, sum_i P_ik Phi_i(t) = [k == r] / gamma(t) (Owren & Zennaro; Hairer, Norsett & Wanner I,
    section II.6), so that b(x) . Phi(t) = x^r / gamma(t).  To 1e-35 (the published 40 digits);
    and inside the step (x = 1/2) an order-9 condition fails: the interpolant is of order 8, one
    less than the pair."""
    from gen_rk_tables import verner98_interpolant
    worst, miss = continuous_residuals(*verner98_interpolant())
    assert worst < mp.mpf(10) ** -35, worst
    assert miss > mp.mpf(10) ** -6


def continuous_residuals(c, A, P):
    """The largest miss of the continuous conditions of orders 1-8 of the weights P (sum_i P_ik Phi_i(t)
    = [k == r] / gamma(t) for every tree t of r <= 8 nodes and power k of x), and the largest miss of
    the order-9 conditions b(x) . Phi(t) = x^9 / gamma(t) at x = 1/2 (at x = 1 the weights are the
    pair's own)."""
    s = len(c)
    phi = elementary_weights(A)
    worst = 0
    for r in range(1, 9):
        for t in trees(r):
            ph = phi(t)
            for k in range(8):
                want = mp.mpf(1) / gamma(t) if k + 1 == r else 0
                worst = max(worst, abs(sum(P[i][k] * ph[i] for i in range(s)) - want))
    x = mp.mpf(1) / 2
    miss = max(abs(sum(sum(P[i][k] * x ** (k + 1) for k in range(8)) * phi(t)[i] for i in range(s))
                   - x ** 9 / gamma(t)) for t in trees(9))
    return worst, miss

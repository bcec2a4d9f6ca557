"""Verner's 'most efficient' 8(7) pair of the kernel (method 'vern8'): the Butcher order conditions.

Every rooted tree t of order <= 8 (200 trees) gives one condition b . Phi(t) = 1 / gamma(t)
(Butcher; Hairer, Norsett & Wanner, Solving ODEs I, section II.2), enumerated here (the trees and
elementary weights of tests/test_verner_coefficients.py).  They are checked in mpmath at 50 digits
for the exact rationals (data/verner87_coefficients.csv) to 1e-45, for the embedded weights b - e
to order 7 (and some order-8 condition fails: the estimate measures), for the doubles the kernel
uses (kernel/integrators/pendula_rk_tables.inc) to 1e-13; the interpolant's continuous conditions
to order 8 for its published 40 digits (data/verner87_interpolant.csv) to 1e-35.
"""

import pathlib
import sys

import mpmath as mp
import pytest

from test_verner_coefficients import continuous_residuals, elementary_weights, residuals, stored, trees

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "data"))
from gen_rk_tables import verner87_interpolant, verner87_matrices  # noqa: E402

S = 13


@pytest.fixture(scope="module")
def exact():
    mp.mp.dps = 50
    return verner87_matrices()


def test_verner87_is_explicit_with_thirteen_stages(exact):
    c, A, b, e = exact
    assert len(c) == len(b) == S and all(A[i][j] == 0 for i in range(S) for j in range(i, S))


def test_verner87_rows_sum_to_the_nodes(exact):
    c, A, b, e = exact
    assert max(abs(sum(A[i]) - c[i]) for i in range(S)) < mp.mpf("1e-45")


def test_verner87_weights_satisfy_all_conditions_to_order_eight(exact):
    c, A, b, e = exact
    res = residuals(c, A, b, 8)
    assert max(res.values()) < mp.mpf("1e-45"), res


def test_verner87_weights_are_not_of_order_nine(exact):
    """The pair is of order 8, no more: some order-9 condition fails (by Verner's T_92-sized terms)."""
    c, A, b, e = exact
    assert residuals(c, A, b, 9)[9] > mp.mpf("1e-8")


def test_verner87_embedded_weights_are_of_order_seven_exactly(exact):
    c, A, b, e = exact
    bhat = [b[i] - e[i] for i in range(S)]
    res = residuals(c, A, bhat, 8)
    assert max(res[n] for n in range(1, 8)) < mp.mpf("1e-45"), res
    assert res[8] > mp.mpf("1e-6"), res


def test_verner87_doubles_of_the_kernel_satisfy_the_conditions(exact):
    """The doubles miss each condition by rounding alone: at most (order + 1) eps times the same sum
    with every coefficient replaced by its magnitude (the weights reach 31 and the matrix 124, so
    the sums reach 1e3 and the misses 1.3e-13)."""
    mp.mp.dps = 30
    c, A, b, e = stored("v8_c"), stored("v8_a"), stored("v8_b"), stored("v8_e")
    Am, bm = [[mp.mpf(x) for x in r] for r in A], [mp.mpf(x) for x in b]
    res = residuals([mp.mpf(x) for x in c], Am, bm, 8)
    phi_abs = elementary_weights([[abs(x) for x in r] for r in Am])
    for n in range(1, 9):
        scale = max(sum(abs(bm[i]) * phi_abs(t)[i] for i in range(S)) for t in trees(n))
        assert res[n] <= (n + 1) * mp.mpf(2) ** -52 * scale, (n, res[n], scale)
    # and each double is its exact coefficient rounded
    ce, Ae, be, ee = exact
    assert [float(x) for x in be] == list(b) and [float(x) for x in ce] == list(c)
    assert [float(x) for x in ee] == list(e)
    assert all(float(Ae[i][j]) == A[i][j] for i in range(S) for j in range(S))


# ---------------------------------------------------------------- the interpolant

@pytest.fixture(scope="module")
def extended():
    mp.mp.dps = 50
    return verner87_interpolant()


def test_verner87_interpolant_extends_the_rows_to_their_nodes(extended, exact):
    """The eight stages of the interpolant sum to their nodes, and stage 14 is the step's own new
    point (the row of b, at c = 1): its f is the next step's first stage."""
    c, A, _ = extended
    _, _, b, _ = exact
    # 40 significant digits of entries up to 45: each off by 1e-38 at most, rows of 12
    assert max(abs(sum(A[i]) - c[i]) for i in range(S, 21)) < mp.mpf(10) ** -36
    assert c[S] == 1 and max(abs(A[S][j] - b[j]) for j in range(S)) < mp.mpf(10) ** -38
    assert all(A[i][j] == 0 for i in range(21) for j in range(i, 21))


def test_verner87_interpolant_ends_on_the_step(extended, exact):
    """b_i(1) = sum_k P_ik is the pair's own 8th-order weight b_i (0 for the eight new stages); the
    published 40 digits of coefficients up to 1.4e6 hold 1e-34 each, sums of 8."""
    _, _, P = extended
    _, _, b, _ = exact
    assert max(abs(sum(P[i]) - (b[i] if i < S else 0)) for i in range(21)) < mp.mpf(10) ** -32


def test_verner87_interpolant_satisfies_the_continuous_conditions_to_order_eight(extended):
    """A continuous extension of order 8: for every tree t with r <= 8 nodes and every power k of
    x, sum_i P_ik Phi_i(t) = [k == r] / gamma(t) (Owren & Zennaro; Hairer, Norsett & Wanner I,
    section II.6), so that b(x) . Phi(t) = x^r / gamma(t).  To 1e-32 (the published 40 digits of
    coefficients up to 1.4e6: 1e-34 each); and inside the step (x = 1/2) an order-9 condition fails."""
    worst, miss = continuous_residuals(*extended)
    assert worst < mp.mpf(10) ** -32, worst
    assert miss > mp.mpf(10) ** -8


def test_verner87_kernel_interpolant_doubles_are_the_published_values_rounded(extended):
    c, A, P = extended
    ci, Ai, Pi = stored("v8i_c"), stored("v8i_a"), stored("v8i_p")
    assert [float(x) for x in c[S:]] == list(ci)
    assert all(float(A[S + i][j]) == Ai[i][j] for i in range(8) for j in range(21))
    assert all(float(P[i][k]) == Pi[i][k] for i in range(21) for k in range(8))

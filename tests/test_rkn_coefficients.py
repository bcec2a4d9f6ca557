"""The Runge-Kutta-Nystrom pair of the kernel (Dormand & Prince's RKN6(4)6FD, method 'dprkn6').

Its coefficients are read from the kernel's table (kernel/integrators/pendula_rk_tables.inc,
written by data/gen_rk_tables.py) and checked here against the order conditions the way a
transcription error would show: one step of the stored doubles, carried out in mpmath at
40 digits on a nonlinear, time-dependent second-order system q'' = f(t, q) whose every
elementary differential is nonzero, against mpmath's own Taylor ODE solver.  If every order
condition up to order 6 holds, the local error of the 6th-order weights falls as h^7
(positions and velocities); the embedded 4th-order weights fall as h^5, and not faster
(otherwise the error estimate would measure nothing).  One wrong digit in any coefficient
drops the observed order to below 6.
"""

import mpmath as mp
import numpy as np
import pytest

from test_verner_coefficients import stored     # a table of the kernel's pendula_rk_tables.inc as doubles


def f(t, q):
    """A coupled nonlinear test system with explicit time dependence."""
    return [-mp.sin(q[0]) + q[1] ** 2 / 3 + mp.cos(2 * t) / 2, -q[0] * q[1] + mp.exp(-q[1] / 2) - mp.sin(t) / 4]


def rkn_step(h, q, v, t=0):
    c, A, b, bp = stored("n6_c"), stored("n6_a"), stored("n6_b"), stored("n6_bp")
    eb, ebp = stored("n6_eb"), stored("n6_ebp")
    F = []
    for i in range(6):
        Q = [q[d] + mp.mpf(c[i]) * h * v[d] + h * h * sum(mp.mpf(A[i, j]) * F[j][d] for j in range(i))
             for d in range(2)]
        F.append(f(t + mp.mpf(c[i]) * h, Q))
    q1 = [q[d] + h * v[d] + h * h * sum(mp.mpf(b[i]) * F[i][d] for i in range(6)) for d in range(2)]
    v1 = [v[d] + h * sum(mp.mpf(bp[i]) * F[i][d] for i in range(6)) for d in range(2)]
    # the embedded pair's solution: the weights minus the stored differences
    q1e = [q1[d] - h * h * sum(mp.mpf(eb[i]) * F[i][d] for i in range(6)) for d in range(2)]
    v1e = [v1[d] - h * sum(mp.mpf(ebp[i]) * F[i][d] for i in range(6)) for d in range(2)]
    return q1 + v1, q1e + v1e


def local_errors():
    mp.mp.dps = 40
    q0, v0 = [mp.mpf("0.7"), mp.mpf("-0.4")], [mp.mpf("0.3"), mp.mpf("1.1")]
    sol = mp.odefun(lambda t, y: [y[2], y[3]] + f(t, y[:2]), 0, q0 + v0)
    hs = [mp.mpf(1) / 5, mp.mpf(1) / 10, mp.mpf(1) / 20]
    main, emb = [], []
    for h in hs:
        exact = sol(h)
        y, ye = rkn_step(h, q0, v0)
        main.append(float(max(abs(y[k] - exact[k]) for k in range(4))))
        emb.append(float(max(abs(ye[k] - exact[k]) for k in range(4))))
    return main, emb


@pytest.fixture(scope="module")
def errors():
    return local_errors()


def test_rkn6_weights_satisfy_the_order_conditions_to_order_six(errors):
    main, _ = errors
    slopes = [np.log2(main[k] / main[k + 1]) for k in range(2)]
    assert all(s > 6.5 for s in slopes), (main, slopes)


def test_rkn6_embedded_weights_are_of_order_four_exactly(errors):
    _, emb = errors
    slopes = [np.log2(emb[k] / emb[k + 1]) for k in range(2)]
    assert all(4.5 < s < 5.7 for s in slopes), (emb, slopes)


def test_rkn6_last_stage_is_the_next_first_stage():
    # FSAL: stage 6 sits at c = 1 with the row of the position weights, so its
    # position is the step's result and its force is the next step's first
    c, A, b = stored("n6_c"), stored("n6_a"), stored("n6_b")
    assert c[5] == 1.0 and c[0] == 0.0
    assert np.array_equal(A[5], b)

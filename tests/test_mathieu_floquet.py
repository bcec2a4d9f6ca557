"""The Floquet solution me_nu(z, q) of non-integer order against independent references.

The reference: mpmath at 30 digits, the Hill matrix of rows nu + 2m, m = -M..M
(diagonal (nu + 2m)^2, couplings q), its eigenvalue nearest nu^2 continued
(the one with the largest component at m = 0 for these q), the eigenvector
normalised to unit norm with c_0 > 0 (DLMF 28.14.4), summed at the points.
The equation itself: mpmath's Taylor integrator of y'' + (a - 2 q cos 2z) y = 0
from me's own value and slope at z = 0, compared at z = 1.3.
"""

import math

import mpmath
import numpy as np
import pytest

import pendula

EPS = np.finfo(float).eps
RNG = np.random.default_rng(20261204)
# special orders and q, and random ones (seeded)
CASES = [(0.5, 1.0), (1.5, -3.0), (0.25, 10.0), (2.7, 0.3), (0.9, 25.0)] + \
    [(float(RNG.uniform(0.05, 4.0)), float(RNG.uniform(-20.0, 20.0))) for _ in range(3)]
POINTS = np.concatenate([[0.0, math.pi / 2, 2.0], RNG.uniform(-4.0, 4.0, 3)])


def _reference(nu, q, z):
    """me_nu(z, q) and its derivative from a 30-digit Hill matrix of 2 half + 1 rows
    (half = 12 + 2 sqrt|q|: the coefficients have fallen below 1e-30 there)."""
    half = int(12 + 2 * math.sqrt(abs(q)))
    with mpmath.workdps(30):
        n = 2 * half + 1
        a = mpmath.zeros(n, n)
        for i in range(n):
            s = mpmath.mpf(nu) + 2 * (i - half)
            a[i, i] = s * s
            if i + 1 < n:
                a[i, i + 1] = a[i + 1, i] = mpmath.mpf(q)
        ev, vec = mpmath.eigsy(a)
        # the level continuing nu^2: the same index as at q = 0 (levels never cross)
        order = sorted(range(n), key=lambda i: abs(mpmath.mpf(nu) + 2 * (i - half)))
        rank = order.index(half)
        idx = sorted(range(n), key=lambda i: ev[i])[rank]
        c = [vec[i, idx] for i in range(n)]
        if c[half] < 0:
            c = [-x for x in c]
        out = []
        for zi in z:
            me = mpmath.mpc(0)
            dme = mpmath.mpc(0)
            for i in range(n):
                s = mpmath.mpf(nu) + 2 * (i - half)
                e = mpmath.expj(s * mpmath.mpf(float(zi)))
                me += c[i] * e
                dme += 1j * s * c[i] * e
            out.append((complex(me), complex(dme)))
        return ev[idx], out


@pytest.mark.parametrize("nu,q", CASES)
def test_against_a_30_digit_hill_matrix(nu, q):
    """Absolute error: the coefficients have unit norm; eps times the largest order
    summed times |z| (each term's phase carries eps (nu + 2m) z), to 2 such units
    (measured: 0.22 for me, 0.15 for its derivative over the order)."""
    lam, ref = _reference(nu, q, POINTS)
    me, dme = pendula.mathieu_me(nu, q, POINTS)
    scale = max(1.0, nu + 2 * math.sqrt(abs(q))) * np.max(np.abs(POINTS))
    for k, (r, dr) in enumerate(ref):
        assert abs(me[k] - r) <= 2 * EPS * scale, (k, me[k], r)
        assert abs(dme[k] - dr) <= 2 * EPS * scale * max(1.0, nu + 2 * math.sqrt(abs(q))), (k, dme[k], dr)
    # and the characteristic value of the same level is mathieu_a's
    assert abs(float(pendula.mathieu_a(nu, q)) - float(lam)) <= 4 * EPS * max(1.0, abs(float(lam)))


def test_solves_the_equation_by_taylor_integration():
    """mpmath's odefun (Taylor series at 30 digits) from me's value and slope at 0."""
    nu, q = 0.7, 4.0
    a = float(pendula.mathieu_a(nu, q))
    me0, dme0 = pendula.mathieu_me(nu, q, 0.0)
    me1, _ = pendula.mathieu_me(nu, q, 1.3)
    with mpmath.workdps(30):
        for part in (lambda x: x.real, lambda x: x.imag):
            f = mpmath.odefun(lambda t, y: [y[1], -(a - 2 * q * mpmath.cos(2 * t)) * y[0]],
                              0, [part(me0), part(dme0)])
            assert abs(float(f(1.3)[0]) - part(me1)) < 1e-13


def test_floquet_property_and_normalisation():
    nu, q = 1.3, -7.0
    z = np.linspace(0.0, math.pi, 257)[:-1]
    me, _ = pendula.mathieu_me(nu, q, z)
    shifted, _ = pendula.mathieu_me(nu, q, z + math.pi)
    np.testing.assert_allclose(shifted, np.exp(1j * nu * math.pi) * me, atol=1e-14)
    # DLMF 28.14.4: the mean over a period pi of me_nu(z) me_nu(-z) is sum c^2 = 1
    back, _ = pendula.mathieu_me(nu, q, -z)
    assert abs(np.mean(me * back) - 1.0) < 1e-14


def test_q_zero_is_the_exponential():
    z = np.linspace(-3, 3, 7)
    me, dme = pendula.mathieu_me(2.5, 0.0, z)
    np.testing.assert_allclose(me, np.exp(2.5j * z), atol=1e-15)
    np.testing.assert_allclose(dme, 2.5j * np.exp(2.5j * z), atol=1e-14)


def test_integer_order_is_refused():
    with pytest.raises(ValueError, match="nu must not be an integer"):
        pendula.mathieu_me(2, 1.0, 0.3)


@pytest.mark.parametrize("nu", [0.0, -0.5, float("nan"), 2e4])
def test_order_out_of_range(nu):
    with pytest.raises(ValueError, match="nu"):
        pendula.mathieu_me(nu, 1.0, 0.3)


def test_q_out_of_range_and_malformed():
    with pytest.raises(ValueError, match="q"):
        pendula.mathieu_me(0.5, 2e10, 0.3)
    with pytest.raises(TypeError, match="z"):
        pendula.mathieu_me(0.5, 1.0, "zero")

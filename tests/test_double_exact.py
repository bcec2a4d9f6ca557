"""The double pendulum's exact parts: normal modes and the forbidden flip region.

References: the closed forms omega^2 = (2 -+ sqrt 2) g/l (equal point masses
and lengths) and 3 -+ 6/sqrt(7) (two equal uniform rods), derived by hand
from the matrices; for any masses and lengths the roots of det(K - w M) = 0
in mpmath at 50 digits (scipy's eigh as a looser peer); for the forbidden region a
brute-force search, over a fine grid of the other arm's angle, of the least
potential energy at which each arm passes the top.  Tolerances: the
quadratic's roots are formed without cancellation, so 4 eps for the closed
forms and against mpmath (the inputs are the exact double matrices).
"""

import math

import mpmath as mp
import numpy as np
import pytest
import scipy.linalg

import pendula
from conftest import EPS


def test_equal_point_masses_and_lengths():
    for g, ln in [(1.0, 1.0), (9.81, 0.7)]:
        nm = pendula.double_pendulum_modes(l1=ln, l2=ln, g=g)
        want = np.array([2 - math.sqrt(2), 2 + math.sqrt(2)]) * g / ln
        assert np.all(np.abs(nm.omega ** 2 / want - 1) <= 4 * EPS)
        assert np.all(np.abs(nm.shapes[1] - [math.sqrt(2), -math.sqrt(2)]) <= 8 * EPS)
        assert np.allclose(nm.period, 2 * np.pi / nm.omega, rtol=2 * EPS, atol=0)


def test_equal_uniform_rods():
    nm = pendula.double_pendulum_modes(rods=True)
    want = np.array([3 - 6 / math.sqrt(7), 3 + 6 / math.sqrt(7)])
    assert np.all(np.abs(nm.omega ** 2 / want - 1) <= 4 * EPS)


@pytest.mark.parametrize("rods", [False, True])
def test_any_masses_and_lengths_against_mpmath(rods):
    """The eigenvalues of the exact double matrices at 50 digits; scipy's eigh
    (a peer, not the reference) was up to 8e-13 off on these."""
    mp.mp.dps = 50
    rng = np.random.default_rng(7)
    for _ in range(200):
        m1, m2, l1, l2 = 10 ** rng.uniform(-2, 2, 4)
        g = 10 ** rng.uniform(-1, 1)
        nm = pendula.double_pendulum_modes(m1, m2, l1, l2, g, rods=rods)
        # the matrices from the exact double parameters (rounded matrices would
        # lose det M to cancellation for m1 << m2: 2000 eps seen)
        p1, p2, q1, q2, gg = map(mp.mpf, (m1, m2, l1, l2, g))
        if rods:
            mm = mp.matrix([[(p1 / 3 + p2) * q1 ** 2, p2 * q1 * q2 / 2], [p2 * q1 * q2 / 2, p2 * q2 ** 2 / 3]])
            kk = mp.matrix([[gg * q1 * (p1 / 2 + p2), 0], [0, gg * p2 * q2 / 2]])
        else:
            mm = mp.matrix([[(p1 + p2) * q1 ** 2, p2 * q1 * q2], [p2 * q1 * q2, p2 * q2 ** 2]])
            kk = mp.matrix([[gg * q1 * (p1 + p2), 0], [0, gg * p2 * q2]])
        a = mm[0, 0] * mm[1, 1] - mm[0, 1] * mm[1, 0]
        b = -(kk[0, 0] * mm[1, 1] + kk[1, 1] * mm[0, 0])
        c = kk[0, 0] * kk[1, 1]
        sq = mp.sqrt(b * b - 4 * a * c)
        want = [(-b - sq) / (2 * a), (-b + sq) / (2 * a)]
        assert all(abs(nm.omega[k] / mp.sqrt(want[k]) - 1) <= 4 * EPS for k in range(2))
        assert np.allclose(nm.omega ** 2, scipy.linalg.eigh(nm.stiffness, nm.mass, eigvals_only=True),
                           rtol=1e-9, atol=0)
        # each shape: theta2 / theta1 = (K11 - w M11) / (w M12) of the exact w (a difference that
        # cancels where w is near K11 / M11: relative to the size of its terms)
        for k in range(2):
            ratio = (kk[0, 0] - want[k] * mm[0, 0]) / (want[k] * mm[0, 1])
            terms = (kk[0, 0] + want[k] * mm[0, 0]) / (want[k] * mm[0, 1])
            assert abs(nm.shapes[1, k] - ratio) <= 16 * EPS * terms
            assert nm.shapes[0, k] == 1.0
        assert nm.shapes[1, 0] > 0 > nm.shapes[1, 1]


@pytest.mark.parametrize("rods", [False, True])
def test_forbidden_region_against_a_brute_force_energy_search(rods):
    rng = np.random.default_rng(11)
    grid = np.linspace(-np.pi, np.pi, 20001)
    c = 0.5 if rods else 1.0
    for _ in range(20):
        m1, m2, l1, l2 = 10 ** rng.uniform(-1, 1, 4)
        a, b = (c * m1 + m2) * l1, c * m2 * l2

        def v(t1, t2):
            return -(a * np.cos(t1) + b * np.cos(t2))

        # the least energy with arm 1 at the top (any arm 2), and with arm 2 at the top
        need1 = v(np.pi, grid).min()
        need2 = v(grid, np.pi).min()
        t1, t2 = rng.uniform(-np.pi, np.pi, (2, 2000))
        e = v(t1, t2)
        want = (e < need1) & (e < need2)
        got = pendula.flip_forbidden(t1, t2, m1, m2, l1, l2, rods=rods)
        clear = np.abs(e - np.minimum(need1, need2)) > 1e-6 * (a + b)
        assert np.array_equal(got[clear], want[clear])
        assert want.any() and (~want).any()


def test_equal_point_masses_boundary_is_2cos1_plus_cos2_equal_1():
    t1 = np.linspace(-np.pi, np.pi, 301)[:, None]
    t2 = np.linspace(-np.pi, np.pi, 301)[None, :]
    q = 2 * np.cos(t1) + np.cos(t2)
    got = pendula.flip_forbidden(t1, t2)
    away = np.abs(q - 1) > 1e-12
    assert np.array_equal(got[away], (q > 1)[away])


@pytest.mark.parametrize("field", ["m1", "m2", "l1", "l2", "g"])
@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, math.inf])
def test_bad_parameters_name_the_field(field, bad):
    with pytest.raises(ValueError, match=field):
        pendula.double_pendulum_modes(**{field: bad})
    if field != "g":
        with pytest.raises(ValueError, match=field):
            pendula.flip_forbidden(0.1, 0.2, **{field: bad})


def test_bad_angles_and_flags():
    with pytest.raises(TypeError, match="theta1"):
        pendula.flip_forbidden("a", 0.0)
    with pytest.raises(TypeError, match="rods"):
        pendula.double_pendulum_modes(rods="yes")

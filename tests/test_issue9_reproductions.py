"""Issue 9's seven reproductions, one test per class, against mpmath at 60
digits on the exact doubles given (the references are computed here, from
mpmath's own Jacobi functions and incomplete integrals, never from pendula).

Error: max over outputs of |got - ref| / max(1, |ref|), in eps; the bound is
the 4 eps README promises (before the fixes: 138, 990, 201, 8.5, 12.9, 6.5
and 12.6 eps).
"""

import math

import numpy as np
import pytest

import pendula
from conftest import EPS

mp = pytest.importorskip("mpmath")


def worst(got, ref):
    return max(abs(float(g) - float(r)) / max(1.0, abs(float(r))) for g, r in zip(got, ref)) / EPS


def jacobi_ref(u, m=None, mc=None):
    """sn, cn, dn at the exact doubles u and m (or m = 1 - mc, formed at 60 digits)."""
    with mp.workdps(60):
        mm = mp.mpf(m) if mc is None else 1 - mp.mpf(mc)
        return [mp.re(mp.ellipfun(f, mp.mpf(u), m=mm)) for f in ("sn", "cn", "dn")]


def exact_ref(theta0, v0, eps, t):
    """theta(t), v(t) from mpmath's Jacobi functions and F at 60 digits."""
    with mp.workdps(60):
        e, th, tt = mp.mpf(eps), mp.mpf(theta0), mp.mpf(t)
        w = mp.mpf(v0) / (2 * mp.sqrt(e))
        n = mp.nint(th / (2 * mp.pi))
        s0 = mp.sin((th - 2 * mp.pi * n) / 2)
        k2 = s0**2 + w**2
        if k2 < 1:
            k = mp.sqrt(k2)
            u = mp.ellipf(mp.atan2(s0 / k, w / k), k2) + mp.sqrt(e) * tt
            sn, cn, dn = (mp.ellipfun(f, u, m=k2) for f in ("sn", "cn", "dn"))
            return [2 * mp.pi * n + 2 * mp.atan2(k * sn, dn), 2 * k * mp.sqrt(e) * cn]
        m, k, d = 1 / k2, mp.sqrt(k2), mp.sign(w)
        u = mp.ellipf(d * th / 2, m) + k * mp.sqrt(e) * tt
        sn, cn, dn = (mp.ellipfun(f, u, m=m) for f in ("sn", "cn", "dn"))
        am = mp.atan2(sn, cn)
        am += 2 * mp.pi * mp.nint((mp.pi * u / (2 * mp.ellipk(m)) - am) / (2 * mp.pi))
        return [2 * d * am, 2 * d * k * mp.sqrt(e) * dn]


def test_sn_cn_dn_m_0_1_large_u_complement_not_exact():
    assert worst(pendula.ellipj(4321.0, 0.1)[:3], jacobi_ref(4321.0, 0.1)) <= 4


def test_sn_cn_dn_m_negative_given_as_m():
    u, m = 8995.998064126703, -0.02466547534144602
    assert worst(pendula.ellipj(u, m)[:3], jacobi_ref(u, m)) <= 4


def test_sn_cn_dn_m_above_1_given_through_mc_negative():
    got = pendula.ellipj(4000.0, None, mc=-0.3)[:3]
    assert worst(got, jacobi_ref(4000.0, mc=-0.3)) <= 4


@pytest.mark.parametrize("case, state", [
    ("libration_backward_near_separatrix",
     (0.020930595066905505, -8.385491450457506, 17.6876402535619, -210.23364519040825)),
    ("at_rest_just_below_the_top", (3.141592517359584, 0.0, 0.02937813085620228, 3857.0778419421413)),
    ("theta0_beyond_pi_wrapped", (9.029273466318742, -1.2098453762295358, 0.27437433661753097,
                                  7.182386296230817)),
])
def test_exact_motion(case, state):
    th0, v0, eps, t = state
    th, v = pendula.exact_motion(th0, v0, eps, [t])
    assert worst([th[0], v[0]], exact_ref(*state)) <= 4, case


def test_incomplete_E_m_slightly_above_1_near_the_domain_edge():
    with mp.workdps(60):
        ref = mp.re(mp.ellipe(mp.mpf(1.566), mp.mpf(1.00001)))
    assert worst([pendula.ellipeinc(1.566, 1.00001)], [ref]) <= 4


def test_the_reference_formulas_agree_with_an_independent_ode_solution():
    """The exact_ref formulas themselves, checked once against mpmath's Taylor
    ODE solver (independent of elliptic functions) at a short time."""
    th0, v0, eps, t = 9.029273466318742, -1.2098453762295358, 0.27437433661753097, 1.5
    with mp.workdps(30):
        f = mp.odefun(lambda s, y: [y[1], -mp.mpf(eps) * mp.sin(y[0])], 0, [mp.mpf(th0), mp.mpf(v0)])
        y = f(mp.mpf(t))
    ref = exact_ref(th0, v0, eps, t)
    assert abs(float(y[0] - ref[0])) < 1e-20 and abs(float(y[1] - ref[1])) < 1e-20
    assert math.isfinite(float(ref[0]))

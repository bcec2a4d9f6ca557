"""sn, cn, dn near m = 1 at double-double arguments, RELATIVE to themselves,
against mpmath (data/jacobi_near1_reference.csv, written once by
data/gen_jacobi_near1_reference.py; mc log-uniform down to 1e-300, given
exactly through mc, u = (2j+1) K + d with j up to 50).

The exact pendulum near its separatrix is v = 2 k sqrt(eps) cn(u | m): there cn
and dn are tiny for long stretches, and their error relative to 1 (what the
reference grids measure) says nothing about their error relative to
themselves.  Bounds, with the reason:
* next to cn's zeros (|d| >= 1e-6 min(1, K/2)): 2 eps.  The kernel computes
  cn(K - w) = sqrt(mc) sd(w) from tn^2(w) at the small w itself (each element
  with its own duplication count) and puts the argument's low part back to
  first order; measured 1.5.
* anywhere on the period for mc < 2^-60: 3 eps.  There sn, cn, dn come from
  their first-order expansion about m = 1 (sinh, cosh from expm1; the terms
  left out are below 2^-64); measured 1.5 (sn 1.0).
* anywhere for 1e-18 <= mc <= 1e-2 (the duplications): 10 eps.  A measured
  limit: cn ~ sech(x) is computed from tn^2 by ~log2(8K) duplications whose
  relative errors (~1.5 ulp a step, the first ones equivalent to relative
  errors of the argument) are amplified by cn's condition number x tanh x,
  up to K/2 ~ 20 here; measured 8.9 (sn 0.9).  The expansion about m = 1 would
  need terms of order mc^2 and beyond to reach up to 1e-2.
"""

import csv

import numpy as np
import pytest

from conftest import EPS
from pendula import _kernel


def load(data_dir):
    with (data_dir / "jacobi_near1_reference.csv").open() as fh:
        rows = list(csv.reader(fh))[2:]
    out = {}
    for r in rows:
        out.setdefault(r[0], []).append([float(x) for x in r[1:]])
    return {k: np.array(v) for k, v in out.items()}


@pytest.fixture(scope="module")
def ref(data_dir):
    return load(data_dir)


def relative_errors(a):
    """Relative errors (eps) of sn, cn, dn at each row (uh, ul, mc, sn, cn, dn)."""
    err = np.empty((len(a), 3))
    for i, (uh, ul, mc, *want) in enumerate(a):
        got = _kernel.ellipj_dd_v(np.array([uh]), np.array([ul]), 1.0 - mc, mc)[:3]
        err[i] = [abs(g[0] - w) / abs(w) / EPS for g, w in zip(got, want)]
    return err


def check(a, bound, what):
    assert len(a) >= 250, "the reference file lost points"
    err = relative_errors(a)
    i, k = np.unravel_index(np.argmax(err), err.shape)
    assert err[i, k] <= bound, (f"{what}: {'sn cn dn'.split()[k]} {err[i, k]:.3g} eps relative "
                                f"at u = {a[i, 0]!r} + {a[i, 1]!r}, mc = {a[i, 2]!r}")


def test_cn_dn_relative_next_to_the_zeros_of_cn_near_m_equal_1(ref):
    a = ref["near_zero"]
    assert np.max(np.abs(a[:, 4])) < 1e-3          # the class is what it says: cn small
    check(a, 2.0, "next to cn's zeros")


def test_cn_dn_relative_over_the_period_for_mc_below_2_to_minus_60(ref):
    a = ref["anywhere"]
    a = a[a[:, 2] < 2.0**-60]
    check(a, 3.0, "mc < 2^-60, anywhere")


def test_cn_dn_relative_over_the_period_for_mc_between_1e_18_and_1e_2(ref):
    check(ref["anywhere_dup"], 10.0, "1e-18 <= mc <= 1e-2, anywhere")


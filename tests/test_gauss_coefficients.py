"""Gauss-Legendre coefficients of the kernel in the mu form.

The energy drift of long Gauss runs came from coefficients that miss the
symplecticity condition in floating point (data/brouwer/).  Here the stored
doubles are read from the kernel's table and checked against mpmath: the
condition mu_ij + mu_ji = 1 must hold exactly (Fractions, no tolerance), and
each mu_ij must be a_ij / b_j to within one ulp (the larger of each pair is
rounded once; the smaller is 1 minus it, exact, hence within an ulp of the larger).
"""

import pathlib
import re
from fractions import Fraction

import mpmath as mp
import numpy as np
import pytest

TABLE = pathlib.Path(__file__).resolve().parents[1] / "kernel" / "integrators" / "pendula_rk_tables.inc"


def stored(name, s):
    text = TABLE.read_text()
    m = re.search(rf"{name}\(0:{s - 1}, 0:{s - 1}\) = reshape\(\[(.*?)\], \[{s}, {s}\]\)", text, re.S)
    assert m, name
    vals = [float(v.replace("_dp", "")) for v in re.findall(r"-?[0-9.]+(?:[eE][-+]?\d+)?_dp", m.group(1))]
    return np.array(vals).reshape((s, s), order="F")


def exact(s):
    mp.mp.dps = 40
    if s == 2:
        r = mp.sqrt(3)
        A = [[mp.mpf(1) / 4, mp.mpf(1) / 4 - r / 6], [mp.mpf(1) / 4 + r / 6, mp.mpf(1) / 4]]
        b = [mp.mpf(1) / 2] * 2
    else:
        r = mp.sqrt(15)
        A = [[mp.mpf(5) / 36, mp.mpf(2) / 9 - r / 15, mp.mpf(5) / 36 - r / 30],
             [mp.mpf(5) / 36 + r / 24, mp.mpf(2) / 9, mp.mpf(5) / 36 - r / 24],
             [mp.mpf(5) / 36 + r / 30, mp.mpf(2) / 9 + r / 15, mp.mpf(5) / 36]]
        b = [mp.mpf(5) / 18, mp.mpf(4) / 9, mp.mpf(5) / 18]
    return A, b


@pytest.mark.parametrize("name,s", [("g2_mu", 2), ("g3_mu", 3)])
def test_gauss_mu_form_is_exactly_symplectic_in_floating_point(name, s):
    mu = stored(name, s)
    for i in range(s):
        for j in range(s):
            assert Fraction(mu[i, j]) + Fraction(mu[j, i]) == 1, (i, j)


@pytest.mark.parametrize("name,s", [("g2_mu", 2), ("g3_mu", 3)])
def test_gauss_mu_form_matches_the_exact_coefficients(name, s):
    mu = stored(name, s)
    A, b = exact(s)
    for i in range(s):
        for j in range(s):
            want = A[i][j] / b[j]
            assert abs(mp.mpf(mu[i, j]) - want) <= np.spacing(max(abs(float(want)), 0.5)), (i, j)

"""Fold and period-doubling curves in two fields against independent computations.

References: data/bifurcation_curve_reference.json (data/gen_bifurcation_curve_reference.py: scipy's
DOP853 at rtol 1e-12 on the equation with its variational equations, Newton on the stroboscopic map,
brentq on the multipliers' condition), and scipy's solve_ivp here at random points of a curve (the
defining equations P(x) = x and the multiplier +1 or -1, evaluated by scipy at pendula's points).
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pendula
from pendula import Scene

REF = json.loads((Path(__file__).resolve().parents[1] / "data" / "bifurcation_curve_reference.json").read_text())
BETA = REF["beta"]


def _scipy_map(x, A, omega, beta=BETA, tau=0.0):
    """(P(x) - x, M) over one drive period, by scipy at rtol 1e-12 (the equation and its variations)."""
    def rhs(t, y):
        th, v, a, b, c, d = y
        s = -math.cos(th)
        return [v, -beta * v - math.sin(th) + A * math.cos(omega * t) + tau, b, s * a - beta * b, d, s * c - beta * d]
    sol = solve_ivp(rhs, (0.0, 2 * math.pi / omega), [x[0], x[1], 1, 0, 0, 1], method="DOP853", rtol=1e-12,
                    atol=1e-12)
    y = sol.y[:, -1]
    return y[:2] - np.asarray(x), np.array([[y[2], y[4]], [y[3], y[5]]])


@pytest.fixture(scope="module")
def period_doubling():
    sc = Scene(damping=BETA, drive_amplitude=1.0, drive_frequency=2 / 3)
    br = pendula.continue_orbit(sc, (0.1, 1.9), "drive_amplitude", 1.07, follow="stable")
    return br.bifurcations[-1]


@pytest.fixture(scope="module")
def folds():
    sc = Scene(damping=BETA, drive_amplitude=0.2, drive_frequency=0.5)
    br = pendula.continue_orbit(sc, (0.0, 0.0), "drive_amplitude", 1.0)
    return [b for b in br.bifurcations if b.kind == "fold"]


def test_period_doubling_curve_against_scipy(period_doubling):
    # 1e-8 in A: the reference's brentq runs to 1e-14, ours to the corrector's 1e-11; both flows are
    # accurate to about 1e-12, which moves a root by about 1e-12 / |dg/dA| (|dg/dA| of order 10)
    assert period_doubling.kind == "period-doubling"
    for p in REF["period_doubling"]:
        if abs(p["omega"] - 2 / 3) < 1e-12:
            assert abs(period_doubling.value - p["A"]) < 1e-8
            continue
        curve = pendula.continue_bifurcation(period_doubling, "drive_frequency", p["omega"])
        assert curve.end == "stop" and curve.second[-1] == p["omega"]
        assert abs(curve.first[-1] - p["A"]) < 1e-8, (p, curve.first[-1])
        assert abs(curve.theta[-1] - p["theta"]) < 1e-7 and abs(curve.v[-1] - p["v"]) < 1e-7
        assert np.min(np.abs(curve.multipliers[-1] + 1)) < 1e-8


def test_fold_curves_against_scipy(folds):
    upper, lower = sorted(folds, key=lambda b: -b.value)
    for p in REF["fold"]:
        start = upper if p["fold"] == "upper" else lower
        if p["omega"] == 0.5:
            assert abs(start.value - p["A"]) < 1e-8
            continue
        curve = pendula.continue_bifurcation(start, "drive_frequency", p["omega"])
        assert curve.end == "stop" and curve.second[-1] == p["omega"]
        assert abs(curve.first[-1] - p["A"]) < 1e-8, (p, curve.first[-1])
        assert abs(curve.theta[-1] - p["theta"]) < 1e-7 and abs(curve.v[-1] - p["v"]) < 1e-7


def test_defining_equations_hold_at_random_points_by_scipy(period_doubling, folds):
    # scipy's map at pendula's points: the orbit closes and the multiplier is -1 (+1) to the flows'
    # accuracy; a point off the curve by dA would show |1 + tr M + det M| of about 10 dA
    rng = np.random.default_rng(2024)
    pd_curve = pendula.continue_bifurcation(period_doubling, "drive_frequency", 0.62)
    fold_curve = pendula.continue_bifurcation(max(folds, key=lambda b: b.value), "drive_frequency", 0.58)
    for curve, lam in ((pd_curve, -1.0), (fold_curve, 1.0)):
        for i in rng.choice(len(curve), size=3, replace=False):
            r, M = _scipy_map((curve.theta[i], curve.v[i]), curve.first[i], curve.second[i])
            assert np.max(np.abs(r)) < 1e-9
            assert abs(np.linalg.det(M - lam * np.eye(2))) < 1e-8


def test_fold_curves_meet_at_a_cusp(folds):
    # from the upper fold the curve passes the cusp (near omega 0.613) and comes back to omega 0.5 as
    # the lower fold: one cusp, where the curve turns in omega, and the fold's coefficient a changes sign
    upper, lower = sorted(folds, key=lambda b: -b.value)
    curve = pendula.continue_bifurcation(upper, "drive_frequency", 0.7)
    assert curve.end.startswith("turned back to drive_frequency = 0.5")
    assert abs(curve.first[-1] - lower.value) < 1e-8
    kinds = [p.kind for p in curve.points]
    assert kinds == ["cusp"]
    cusp = curve.points[0]
    assert abs(cusp.values[1] - np.max(curve.second)) < 1e-4
    i = int(np.argmax(curve.second))
    assert np.sign(curve.coefficient[i - 2]) == -np.sign(curve.coefficient[i + 2])
    # scipy at the cusp: the quadratic coefficient <p, B(q, q)> / 2 by central differences is zero within
    # its error (h^2 + 1e-12 / h at h = 1e-4, times |M|), where a point of the curve 0.01 away has |a| > 0.1
    x = np.array([cusp.theta, cusp.v])
    _, M = _scipy_map(x, *cusp.values)
    mu, V = np.linalg.eig(M)
    q = np.real(V[:, np.argmin(np.abs(mu - 1))])
    muT, W = np.linalg.eig(M.T)
    pv = np.real(W[:, np.argmin(np.abs(muT - 1))])
    pv = pv / (pv @ q)
    h = 1e-4
    Mp, Mm = _scipy_map(x + h * q, *cusp.values)[1], _scipy_map(x - h * q, *cusp.values)[1]
    a = 0.5 * pv @ ((Mp - Mm) @ q) / (2 * h)
    assert abs(a) < 1e-5 * (1 + np.linalg.norm(M)) ** 2
    assert np.min(np.abs(curve.coefficient[[i - 3, i + 3]])) > 0.01


def test_period_doubling_is_supercritical_along_the_cascade(period_doubling):
    curve = pendula.continue_bifurcation(period_doubling, "drive_frequency", 0.7)
    # the cascade's doubling is supercritical (the stable child appears past it): c > 0 in Kuznetsov's sign
    assert np.all(curve.coefficient > 0)
    assert curve.points == ()


def test_a_curve_reaching_a_fields_edge_ends_there_with_its_reason(period_doubling):
    # the doubling followed in the damping down to 0, then from a point near there in damping as the
    # first field: the curve meets damping = 0 (the end of its range) and is returned, not lost
    to_zero = pendula.continue_bifurcation(period_doubling, "damping", 0.0)
    assert to_zero.end == "stop" and to_zero.second[-1] == 0.0
    i = int(np.argmin(np.abs(to_zero.second - 0.03)))
    sc = Scene(damping=float(to_zero.second[i]) + 0.005, drive_amplitude=float(to_zero.first[i]),
               drive_frequency=2 / 3)
    br = pendula.continue_orbit(sc, (to_zero.theta[i], to_zero.v[i]), "damping", float(to_zero.second[i]) - 0.005)
    pd = [b for b in br.bifurcations if b.kind == "period-doubling"][0]
    assert abs(pd.value - to_zero.second[i]) < 1e-8      # the same curve, crossed in the other field
    curve = pendula.continue_bifurcation(pd, "drive_amplitude", 0.3)
    assert curve.end == "edge: damping = 0.0, the end of its range"
    assert curve.first[-1] == 0.0 and abs(curve.second[-1] - to_zero.first[-1]) < 1e-7
    assert len(curve) > 2


def test_bad_arguments_name_the_argument(period_doubling):
    with pytest.raises(ValueError, match="second_param"):
        pendula.continue_bifurcation(period_doubling, "drive_amplitude", 1.2)
    with pytest.raises(ValueError, match="second_param"):
        pendula.continue_bifurcation(period_doubling, "no_such_field", 1.2)
    with pytest.raises(ValueError, match="stop"):
        pendula.continue_bifurcation(period_doubling, "drive_frequency", -0.5)
    with pytest.raises(ValueError, match="stop"):
        pendula.continue_bifurcation(period_doubling, "damping", -0.1)
    with pytest.raises(ValueError, match="stop"):
        pendula.continue_bifurcation(period_doubling, "drive_frequency", 2 / 3)
    with pytest.raises(TypeError, match="point"):
        pendula.continue_bifurcation((1.0, 2.0), "drive_frequency", 0.7)
    bare = pendula.Bifurcation("period-doubling", 1.0, 1.0, 0.0, 0.0, np.array([-1.0, 0.1]))
    with pytest.raises(ValueError, match="point"):
        pendula.continue_bifurcation(bare, "drive_frequency", 0.7)


@pytest.fixture(scope="module")
def pitchfork():
    sc = Scene(damping=BETA, drive_amplitude=1.0, drive_frequency=2 / 3)
    pf = pendula.continue_orbit(sc, (0.1, 1.9), "drive_amplitude", 1.01).bifurcations[0]
    assert pf.kind == "pitchfork"
    return pf


def test_pitchfork_curve_against_scipy(pitchfork):
    # the symmetric orbit's pitchfork, followed as the flip of the half-period map; the reference solves
    # 1 + tr DG + det DG = 0 by brentq on scipy's half-period map (1e-8 as for the other curves)
    for p in REF["pitchfork"]:
        if abs(p["omega"] - 2 / 3) < 1e-12:
            assert abs(pitchfork.value - p["A"]) < 1e-8
            continue
        curve = pendula.continue_bifurcation(pitchfork, "drive_frequency", p["omega"])
        assert curve.kind == "pitchfork" and curve.end == "stop"
        assert abs(curve.first[-1] - p["A"]) < 1e-8, (p, curve.first[-1])
        assert abs(curve.theta[-1] - p["theta"]) < 1e-7 and abs(curve.v[-1] - p["v"]) < 1e-7
        # the whole orbit's multipliers: +1 and exp(-beta T) / 1
        assert np.min(np.abs(curve.multipliers[-1] - 1)) < 1e-8
        assert curve.coefficient[-1] > 0          # supercritical, as continue_orbit's follow='stable' meets it


def test_a_pitchfork_in_the_torque_is_refused_by_name(pitchfork):
    with pytest.raises(ValueError, match="second_param: 'torque' breaks the symmetry"):
        pendula.continue_bifurcation(pitchfork, "torque", 0.1)


def test_a_neimark_sacker_point_is_refused_by_name():
    sc = Scene(damping=BETA, drive_amplitude=1.0, drive_frequency=2 / 3)
    ns = pendula.Bifurcation("neimark-sacker", 1.0, 1.0, 0.0, 0.0, np.array([1.0, 1.0]), sc, "drive_amplitude")
    with pytest.raises(NotImplementedError, match="point: a neimark-sacker"):
        pendula.continue_bifurcation(ns, "drive_frequency", 0.7)


def test_a_field_the_orbit_does_not_depend_on_is_refused(period_doubling):
    with pytest.raises(ValueError, match="second_param"):
        pendula.continue_bifurcation(period_doubling, "theta0", 0.5)


def test_retrapping_curve_against_scipy():
    # the homoclinic (retrapping) torque followed in the damping: the reference bisects, at each damping,
    # on whether scipy's unstable manifold of the saddle passes the next saddle (1e-8 as in
    # tests/test_continuation.py; measured 4e-15..1e-14)
    ref = json.loads((Path(__file__).resolve().parents[1] / "data" / "continuation_reference.json").read_text())
    rows = ref["retrapping"]
    br = pendula.continue_orbit(Scene(damping=rows[0]["damping"], torque=1.5), (0.0, 5.0), "torque", 0.0)
    hom = br.bifurcations[0]
    assert hom.kind == "homoclinic" and abs(hom.value - rows[0]["torque"]) < 1e-8
    for r in rows[1:]:
        curve = pendula.continue_bifurcation(hom, "damping", r["damping"])
        assert curve.kind == "homoclinic" and curve.end == "stop" and curve.second[-1] == r["damping"]
        assert abs(curve.first[-1] - r["torque"]) < 1e-8, (r, curve.first[-1])
    # McCumber and Stewart: 4 damping / pi for small damping (the first points, within O(damping^2))
    assert abs(curve.first[0] - 4 * 0.1 / math.pi) < 0.01

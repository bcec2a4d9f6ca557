"""The Shapiro steps' edges as fold curves (Arnold tongues) against independent computations.

References: data/shapiro_tongue_reference.json (data/gen_shapiro_tongue_reference.py: scipy's DOP853
at rtol 1e-12, Newton in (v, torque) at each phase of the section, brentq on det(M - I) for the
extremes of the torque), and the high-frequency limit of the overdamped junction: widths
2 abs(J_n(a_eff)) with a_eff the phase's linear response a / (Omega sqrt(Omega^2 + beta^2)) (Likharev,
*Dynamics of Josephson Junctions and Circuits*, section 10.2), whose error falls as 1 / (beta Omega)^2.
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.special import jv

import pendula
from pendula import Scene

REF = json.loads((Path(__file__).resolve().parents[1] / "data" / "shapiro_tongue_reference.json").read_text())


@pytest.mark.parametrize("n", [1, 2])
def test_step_edges_against_scipy(n):
    # 1e-8 in the torque: the reference's brentq runs to 1e-14 in the phase, ours to the corrector's 1e-11;
    # both flows are accurate to about 1e-12
    sc = Scene(damping=REF["beta"], drive_amplitude=1.0, drive_frequency=REF["omega"])
    for p in (p for p in REF["edges"] if p["n"] == n):
        tongue = pendula.shapiro_tongue(sc, n, p["A"])
        assert (tongue.lower.end, tongue.upper.end) == ("stop", "stop")
        assert tongue.lower.second[-1] == p["A"] == tongue.upper.second[-1]
        lo, hi = tongue.edges()
        assert abs(lo[-1] - p["lower"]) < 1e-8, (p, lo[-1])
        assert abs(hi[-1] - p["upper"]) < 1e-8, (p, hi[-1])
        assert tongue.lower.winding == n and tongue.upper.winding == n


@pytest.mark.parametrize("n, x", [(1, 0.5), (2, 1.5)])
def test_overdamped_high_frequency_limit_of_the_widths(n, x):
    # damping 20 (beta_c = 1 / 400): the RSJ frequency beta Omega = 10, 20; rf amplitude x beta Omega
    # (x the Bessel argument).  The width approaches 2 abs(J_n(a_eff)) with an error of order
    # 1 / (beta Omega)^2: below 0.5 / (beta Omega)^2, and falling by about 4 when the frequency doubles
    beta = 20.0
    errors = []
    for wr in (10.0, 20.0):
        om, a = wr / beta, x * wr
        tongue = pendula.shapiro_tongue(Scene(damping=beta, drive_amplitude=a, drive_frequency=om), n, 1.001 * a)
        width = tongue.upper.first[0] - tongue.lower.first[0]
        aeff = a / (om * math.sqrt(om * om + beta * beta))
        err = abs(width - 2 * abs(jv(n, aeff)))
        assert err < 0.5 / wr ** 2, (n, wr, width, err)
        errors.append(err)
    assert 3.0 < errors[0] / errors[1] < 5.0, errors


def test_the_step_holds_its_locked_orbit_between_the_edges():
    # between the edges an attracting locked orbit (winding 1) exists (strong damping); 0.05 beyond the
    # upper edge Newton finds no locked orbit from any of eight phases
    sc = Scene(damping=1.0, drive_amplitude=1.0, drive_frequency=2.0)
    tongue = pendula.shapiro_tongue(sc, 1, 1.3)
    lo, hi = tongue.edges()
    mid = sc.replace(torque=0.5 * (lo[-1] + hi[-1]), drive_amplitude=1.3)
    found = []
    for th in np.linspace(-np.pi, np.pi, 8, endpoint=False):
        try:
            found.append(pendula.periodic_orbit(mid, guess=(th, 2.0), winding=1))
        except ValueError:
            pass
    assert any(po.stable for po in found) and any(not po.stable for po in found)
    beyond = sc.replace(torque=hi[-1] + 0.05, drive_amplitude=1.3)
    for th in np.linspace(-np.pi, np.pi, 8, endpoint=False):
        with pytest.raises(ValueError):
            pendula.periodic_orbit(beyond, guess=(th, 2.0), winding=1, maxit=40)


def test_bad_arguments_name_the_argument():
    sc = Scene(damping=1.0, drive_amplitude=1.0, drive_frequency=2.0)
    with pytest.raises(ValueError, match="n"):
        pendula.shapiro_tongue(sc, 0, 1.2)
    with pytest.raises(ValueError, match="stop"):
        pendula.shapiro_tongue(sc, 1, -1.0)
    with pytest.raises(ValueError, match="stop"):
        pendula.shapiro_tongue(sc, 1, 1.0)
    with pytest.raises(ValueError, match="scene"):
        pendula.shapiro_tongue(Scene(damping=1.0), 1, 1.2)
    with pytest.raises(ValueError, match="scene"):
        pendula.shapiro_tongue(sc.replace(damping=0.0), 1, 1.2)
    with pytest.raises(TypeError, match="scene"):
        pendula.shapiro_tongue("junction", 1, 1.2)


def test_junction_tongue_in_amperes_is_the_reduced_tongue_times_the_critical_current():
    j = pendula.Junction(2e-6, 10.0, 1e-11)
    t = j.shapiro_tongue(1, 2e-6, 20e9, 2.4e-6)
    sc = j.scene(0.0, 2e-6, 20e9)
    ref = pendula.shapiro_tongue(sc, 1, 1.2)
    e = t.lab_edges()
    for key, curve in (("lower", ref.lower), ("upper", ref.upper)):
        np.testing.assert_allclose(e[f"{key}_bias"], 2e-6 * curve.first, rtol=1e-13)
        np.testing.assert_allclose(e[f"{key}_rf"], 2e-6 * curve.second, rtol=1e-13)
    assert e["lower_rf"][-1] == pytest.approx(2.4e-6, rel=1e-15)
    with pytest.raises(ValueError, match="critical_current"):
        ref.lab_edges()
    with pytest.raises(ValueError, match="capacitance"):
        pendula.Junction(2e-6, 10.0, 0.0).shapiro_tongue(1, 2e-6, 20e9, 2.4e-6)


def test_fractional_step_edges_satisfy_the_fold_conditions_by_scipy():
    # the step 1/2 (one turn in two drive periods) of a junction with damping 1 and rf frequency 1: at the
    # last point of each edge scipy's two-period map advances the state by one turn, and det(M - I) = 0
    # (a point off the edge by d torque shows det(M - I) of about |d det / d torque| d, here above 1 d)
    from scipy.integrate import solve_ivp
    sc = Scene(damping=1.0, drive_amplitude=1.0, drive_frequency=1.0)
    tongue = pendula.shapiro_tongue(sc, 1, 1.2, q=2)
    assert tongue.q == 2 and "n=1/2" in repr(tongue)
    for edge in (tongue.lower, tongue.upper):
        tau, a, th, v = edge.first[-1], edge.second[-1], edge.theta[-1], edge.v[-1]

        def rhs(t, y):
            s = -math.cos(y[0])
            return [y[1], -y[1] - math.sin(y[0]) + a * math.cos(t) + tau, y[3], s * y[2] - y[3], y[5],
                    s * y[4] - y[5]]
        y = solve_ivp(rhs, (0.0, 4 * math.pi), [th, v, 1, 0, 0, 1], method="DOP853", rtol=1e-12, atol=1e-12).y[:, -1]
        assert abs(y[0] - th - 2 * math.pi) < 1e-9 and abs(y[1] - v) < 1e-9
        M = np.array([[y[2], y[4]], [y[3], y[5]]])
        assert abs(np.linalg.det(M - np.eye(2))) < 1e-8
    assert tongue.lower.first[-1] < tongue.upper.first[-1]

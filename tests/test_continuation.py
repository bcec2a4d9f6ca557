"""Continuation of periodic orbits and equilibria against independent computations.

References: data/continuation_reference.json (data/gen_continuation_reference.py: scipy's DOP853 at
1e-13 on the equation and its variational equations, Newton on the map, brentq on the multipliers'
test functions, bisection on the saddle's unstable manifold), scipy's solve_ivp here for the defining
condition at a fold, Liouville's det M = exp(-damping T), numpy's roots of the linearisation, and the
closed form |torque| = eps of the saddle-node.
"""

import json
import math
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.integrate import solve_ivp

import pendula
from pendula import Scene

REF = json.loads((Path(__file__).resolve().parents[1] / "data" / "continuation_reference.json").read_text())
#: the retrapping torque near beta*, where it reaches 1 (data/gen_retrapping_reference.py)
RETRAP = json.loads((Path(__file__).resolve().parents[1] / "data" / "retrapping_reference.json").read_text())
EPS = np.finfo(np.float64).eps
CASCADE = Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2 / 3)


@pytest.fixture(scope="module")
def cascade_branch():
    po = pendula.periodic_orbit(CASCADE, guess=(0.1, 1.9))
    last = REF["cascade"]["points"][-1]["value"]
    # a little past the fourth doubling, before the fifth (at about 1.082806)
    return pendula.continue_orbit(CASCADE, (po.theta, po.v), "drive_amplitude", last + 1e-4, follow="stable")


def test_cascade_pitchfork_and_doublings_against_scipy(cascade_branch):
    # 1e-8 in the drive amplitude: the reference's brentq runs to 1e-14, ours to about 1e-12; the flows of
    # both are accurate to about 1e-12, which moves a root by about 1e-12 / |d psi / dA| (|d psi/dA| > 1)
    got = [(b.kind, b.period) for b in cascade_branch.bifurcations]
    want = [(p["kind"], float(p["k"])) for p in REF["cascade"]["points"]]
    assert got == want
    for b, p in zip(cascade_branch.bifurcations, REF["cascade"]["points"]):
        assert abs(b.value - p["value"]) < 1e-8, (b, p)
        target = 1.0 if b.kind == "pitchfork" else -1.0
        assert np.min(np.abs(b.multipliers - target)) < 1e-6


def test_cascade_follows_the_attracting_orbit_doubling_its_period(cascade_branch):
    br = cascade_branch
    assert br.end == "stop"
    # the segments: the symmetric orbit, its asymmetric child, then the children of period 2, 4, 8, 16
    assert list(np.unique(br.segment)) == [0, 1, 2, 3, 4, 5]
    for seg, k in zip(range(6), (1, 1, 2, 4, 8, 16)):
        assert np.all(br.period[br.segment == seg] == k)
    # every point but the located bifurcations (multiplier 1 or -1 to the Newton tolerance) attracts
    on_bif = np.isin(br.values, [b.value for b in br.bifurcations])
    assert np.all(br.stable[~on_bif])
    # the parameter grows along the attracting route (supercritical bifurcations)
    assert np.all(np.diff(br.values) > -1e-12)


def test_feigenbaum_ratio_of_the_doubling_intervals(cascade_branch):
    v = [b.value for b in cascade_branch.bifurcations if b.kind == "period-doubling"]
    d = np.diff(v)
    ratios = d[:-1] / d[1:]
    # Feigenbaum's delta = 4.6692...: the first ratios of a flow approach it to about 1e-2 (4.671, 4.664)
    assert np.all(np.abs(ratios - 4.6692016) < 0.02), ratios


def test_multipliers_along_a_branch_equal_periodic_orbits(cascade_branch):
    br = cascade_branch
    rng = np.random.default_rng(7)
    # isolated orbits only: at a located bifurcation a multiplier is 1 or -1 and the orbit of the k-fold
    # map is determined only to about the square root of Newton's tolerance along its null vector
    isolated = np.flatnonzero(~np.isin(br.values, [b.value for b in br.bifurcations]))
    for i in rng.choice(isolated, size=6, replace=False):
        sc = CASCADE.replace(drive_amplitude=float(br.values[i]))
        po = pendula.periodic_orbit(sc, guess=(br.theta[i], br.v[i]), k=int(br.period[i]))
        assert abs(po.theta - br.theta[i]) < 1e-8 and abs(po.v - br.v[i]) < 1e-8
        # the same orbit and the same flow: multipliers agree to the orbit's accuracy times |dM/dx|
        np.testing.assert_allclose(po.multipliers, br.multipliers[i], rtol=0, atol=1e-7)


def test_liouville_det_along_every_branch(cascade_branch):
    # det M = exp(-damping T): T = k 2 pi / omega for the driven branch, the period for the autonomous one
    # to 1e-8 relative, plus 1e-12 |mu_1|^2: the monodromy's entries carry the flow's error (about 1e-12
    # of their size), so the determinant of a period-8 orbit (6.5e-9 from entries of order 1) does too
    for br, beta in ((cascade_branch, 0.5), (_retrapping_branch(0.3), 0.3)):
        det = np.prod(br.multipliers, axis=1).real
        T = br.period * 2 * math.pi / (2 / 3) if br is cascade_branch else br.period
        want = np.exp(-beta * T)
        tol = 1e-8 * want + 1e-12 * np.maximum(1.0, np.abs(br.multipliers[:, 0])) ** 2
        assert np.all(np.abs(det - want) <= tol)


def _retrapping_branch(beta):
    return pendula.continue_orbit(Scene(damping=beta, torque=1.5), (0.0, 5.0), "torque", 0.0)


@pytest.mark.parametrize("entry", REF["retrapping"] + RETRAP["retrapping"], ids=lambda e: f"damping={e['damping']}")
def test_homoclinic_retrapping_torque_against_scipy_manifold(entry):
    # 1e-8: the reference bisects to 2e-15 on the outcome of the unstable manifold integrated at 1e-13;
    # ours solves the manifolds' splitting to 1e-14; both flows good to about 1e-12
    br = _retrapping_branch(entry["damping"])
    (h,) = br.bifurcations
    assert h.kind == "homoclinic" and h.period == math.inf
    assert abs(h.value - entry["torque"]) < 1e-8
    assert br.end.startswith("homoclinic")
    # the period grows without bound as the branch nears it
    assert br.period[-1] > 3 * br.period[0]


@pytest.mark.parametrize("entry", [e for e in RETRAP["retrapping"] if e["one_minus_torque"] < 1e-2],
                         ids=lambda e: f"damping={e['damping']}")
def test_manifold_splitting_sign_near_the_saddle_node_birth(entry):
    # the sign of the manifolds' splitting either side of the reference's retrapping torque, down to
    # 1 - tau = 1e-13 (a saddle nearly degenerate, lu ~ 4e-7): positive above tau_h (the running orbit
    # exists), negative or None (the unstable manifold falls back) below it
    from pendula.dynamics.homoclinic import _splitting
    beta, d = entry["damping"], entry["one_minus_torque"]
    for above in (1e-13, 0.5 * d):
        assert _splitting(Scene(damping=beta, torque=1.0 - above), 1, 1e-12, 1e-12) > 0
    below = _splitting(Scene(damping=beta, torque=1.0 - 1.5 * d), 1, 1e-12, 1e-12)
    assert below is None or below < 0


@pytest.mark.parametrize("beta", [1.2, 1.25, 2.0])
def test_retrapping_beyond_critical_damping_ends_on_snic_at_torque_one(beta):
    # beyond beta* the rest points are born on the running orbit at torque 1 (no homoclinic torque below
    # 1: the reference generator's bisection of beta*); the branch ends there, at 1 to rounding, in a
    # bounded number of points (not creeping towards it), its period growing without bound
    assert beta > RETRAP["beta_star"]
    br = _retrapping_branch(beta)
    (b,) = br.bifurcations
    assert b.kind == "snic" and b.period == math.inf
    assert abs(b.value - 1.0) <= 4 * EPS
    assert br.end.startswith("snic")
    assert len(br) < 200 and br.values.min() > 1.0
    assert br.period[-1] > 10 * br.period[0]
    # just past the birth the saddle's unstable manifold falls back onto the next node, short of the next
    # saddle (scipy's check, independent of pendula; the gap between the two is 2.8e-5)
    from scipy.integrate import solve_ivp
    tau = 1.0 - 1e-10
    ths = math.pi - math.asin(tau)
    lu = 0.5 * (-beta + math.sqrt(beta * beta + 4 * math.cos(math.asin(tau))))
    ev = (lambda t, y: y[1]); ev.terminal, ev.direction = True, -1
    s = solve_ivp(lambda t, y: [y[1], -beta * y[1] - math.sin(y[0]) + tau], (0, 1e4), [ths + 0.05, 0.05 * lu],
                  method="Radau", rtol=1e-10, atol=1e-14, events=ev)
    assert s.y[0, -1] < ths + 2 * math.pi - 1e-5 and abs(s.y[1, -1]) < 1e-6


def test_retrapping_just_below_critical_damping_is_a_homoclinic_within_1e8_of_one():
    # between 1.193 (1 - tau_h = 2.1e-9 in the reference) and beta* the retrapping torque lies in
    # (1 - 2.1e-9, 1): the homoclinic, not the saddle-node, ends the branch, within 1e-8 of it
    beta = 0.5 * (1.193 + RETRAP["beta_star"])
    (b,) = _retrapping_branch(beta).bifurcations
    assert b.kind == "homoclinic"
    assert 1.0 - 2.2e-9 < b.value < 1.0


def test_stewart_mccumber_small_damping_limit():
    # the retrapping torque 4 beta / pi (1 + O(beta^2)) for small damping (Stewart; McCumber)
    beta = 0.05
    (h,) = _retrapping_branch(beta).bifurcations
    assert abs(h.value / (4 * beta / math.pi) - 1) < 3 * beta * beta


def test_fold_is_passed_and_satisfies_its_defining_condition():
    # the softening resonance of the weakly damped pendulum: the period-1 response turns at a fold
    sc = Scene(damping=0.1, drive_amplitude=0.2, drive_frequency=0.6)
    br = pendula.continue_orbit(sc, (0.3152727, 0.0179069), "drive_frequency", 1.1)
    (f,) = [b for b in br.bifurcations if b.kind == "fold"]
    # passed: the branch goes on beyond the turn, back to lower frequencies, and stays on one side of it
    assert br.values.max() <= f.value + 1e-12 and br.values[-1] < f.value - 0.05
    # the defining condition with scipy: det(M - I) = 0 for the orbit at the fold
    w = f.value

    def rhs(t, y):
        th, v, a, b, c, d = y
        dth = -math.cos(th)
        return [v, -0.1 * v - math.sin(th) + 0.2 * math.cos(w * t), b, dth * a - 0.1 * b, d, dth * c - 0.1 * d]
    s = solve_ivp(rhs, (0, 2 * math.pi / w), [f.theta, f.v, 1, 0, 0, 1], method="DOP853", rtol=1e-13, atol=1e-13)
    y = s.y[:, -1]
    M = np.array([[y[2], y[4]], [y[3], y[5]]])
    assert max(abs(y[0] - f.theta), abs(y[1] - f.v)) < 1e-9
    assert abs(np.linalg.det(M - np.eye(2))) < 1e-8


def test_to_xarray_has_point_multiplier_and_cycle_dims(cascade_branch):
    ds = cascade_branch.to_xarray()
    # the cycle dimension: the longest k-cycle on the attracting route (period 16 after the fourth doubling)
    assert dict(ds.sizes) == {"point": len(cascade_branch), "multiplier": 2, "cycle": 16}
    np.testing.assert_array_equal(ds["drive_amplitude"].values, cascade_branch.values)
    assert ds["multipliers"].dtype.kind == "c"


# ---------------------------------------------------------------- equilibria

@pytest.mark.parametrize("eps", [1.0, 0.37, 2.5e3, 1e-3])
def test_saddle_node_where_torque_equals_eps_exactly(eps):
    eb = pendula.continue_equilibria(Scene(damping=0.2, eps=eps), "torque", 1.7 * eps, points=7)
    (b,) = eb.bifurcations
    assert b.kind == "saddle-node" and b.value == eps
    # the kernel's rest points along the branch against numpy's roots of lambda^2 + beta lambda + c
    for tau, eqs in zip(eb.values, eb.equilibria):
        assert len(eqs) == (2 if tau < eps else 0 if tau > eps else 1)
        for e in eqs:
            c = eps * math.cos(e.theta)
            ref = np.sort_complex(np.roots([1.0, 0.2, c]))
            np.testing.assert_allclose(np.sort_complex(e.eigenvalues), ref, rtol=1e-12, atol=1e-12 * eps)


@settings(max_examples=40, deadline=None)
@given(eps=st.floats(1e-3, 1e3), beta=st.floats(0.0, 3.0), up=st.booleans())
def test_saddle_node_bisected_to_the_last_double(eps, beta, up):
    # from either side, in the torque: the saddle-node at |tau| = eps to the bit (the kernel meets it exactly)
    start, stop = (0.3 * eps, 2 * eps) if up else (-2 * eps, -0.3 * eps)
    eb = pendula.continue_equilibria(Scene(damping=beta, eps=eps, torque=start), "torque", stop, points=5)
    (b,) = eb.bifurcations
    assert b.value == (eps if up else -eps)


def test_branch_through_the_pitchfork_goes_on_unstable():
    # follow='branch': the symmetric orbit is followed past its pitchfork, unstable beyond it
    po = pendula.periodic_orbit(CASCADE, guess=(0.1, 1.9))
    br = pendula.continue_orbit(CASCADE, (po.theta, po.v), "drive_amplitude", 1.02)
    (b,) = br.bifurcations
    assert b.kind == "pitchfork" and br.end == "stop"
    assert np.all(br.stable[br.values < b.value - 1e-9]) and not np.any(br.stable[br.values > b.value + 1e-9])
    # the symmetry holds along it: theta(T/2) = -theta(0), v(T/2) = -v(0), by scipy
    i = len(br) // 2
    a = float(br.values[i])

    def rhs(t, y):
        return [y[1], -0.5 * y[1] - math.sin(y[0]) + a * math.cos(2 * t / 3)]
    s = solve_ivp(rhs, (0, 1.5 * math.pi), [br.theta[i], br.v[i]], method="DOP853", rtol=1e-12, atol=1e-12)
    assert abs(math.remainder(s.y[0, -1] + br.theta[i], 2 * math.pi)) < 1e-8 and abs(s.y[1, -1] + br.v[i]) < 1e-8


def test_equilibria_trace_is_minus_damping_no_hopf():
    eb = pendula.continue_equilibria(Scene(damping=0.3, torque=0.4), "damping", 0.0, points=13)
    assert eb.bifurcations == ()
    for beta, eqs in zip(eb.values, eb.equilibria):
        for e in eqs:
            assert abs(e.eigenvalues.sum().real + beta) < 1e-14


# ---------------------------------------------------------------- bad input

def test_param_not_a_scene_field_or_not_numeric():
    with pytest.raises(ValueError, match="dampin"):
        pendula.continue_orbit(CASCADE, (0.1, 1.9), "dampin", 1.1)
    with pytest.raises(ValueError, match="method"):
        pendula.continue_orbit(CASCADE, (0.1, 1.9), "method", 1.1)
    with pytest.raises(TypeError, match="param"):
        pendula.continue_orbit(CASCADE, (0.1, 1.9), 3, 1.1)
    with pytest.raises(ValueError, match="dampin"):
        pendula.continue_equilibria(Scene(), "dampin", 1.0)


def test_param_that_does_not_apply_is_named():
    with pytest.raises(ValueError, match="theta0"):
        pendula.continue_orbit(CASCADE, (0.1, 1.9), "theta0", 1.0)
    with pytest.raises(ValueError, match="cord_length"):
        pendula.continue_orbit(CASCADE, (0.1, 1.9), "cord_length", 2.0)
    running = Scene(damping=0.1, torque=0.5)
    with pytest.raises(ValueError, match="drive_frequency"):
        pendula.continue_orbit(running, (0.0, 5.0), "drive_frequency", 1.0)
    with pytest.raises(ValueError, match="drive_amplitude"):
        pendula.continue_orbit(running, (0.0, 5.0), "drive_amplitude", 1.0)


def test_stop_on_the_wrong_side_is_named():
    with pytest.raises(ValueError, match="stop"):
        pendula.continue_orbit(CASCADE, (0.1, 1.9), "drive_amplitude", -0.5)
    with pytest.raises(ValueError, match="stop"):
        pendula.continue_orbit(CASCADE, (0.1, 1.9), "drive_amplitude", 1.0)
    with pytest.raises(ValueError, match="stop"):
        pendula.continue_orbit(CASCADE, (0.1, 1.9), "damping", math.inf)


def test_guess_that_does_not_converge_says_where():
    sc = Scene(damping=0.1, torque=0.05)      # below the retrapping torque: no running orbit
    with pytest.raises(ValueError, match="guess"):
        pendula.continue_orbit(sc, (0.0, 0.5), "torque", 1.0)
    with pytest.raises(ValueError, match="got to"):
        pendula.continue_orbit(CASCADE, (0.1, 1.9), "drive_amplitude", 1.1, winding=7)


def test_follow_stable_from_an_unstable_orbit_is_refused():
    sc = CASCADE.replace(drive_amplitude=1.07)
    po = pendula.periodic_orbit(sc, guess=(-0.2, 2.2))     # inside the first doubling: period 1 unstable
    assert not po.stable
    with pytest.raises(ValueError, match="follow"):
        pendula.continue_orbit(sc, (po.theta, po.v), "drive_amplitude", 1.08, follow="stable")


def test_fold_that_cannot_be_passed_is_a_continuation_error(monkeypatch):
    # a corrector that always fails stands for a fold the steps cannot pass: the error names the field
    # and where, and hands back the part of the branch traced
    from pendula.dynamics import continuation as C
    from pendula.dynamics.periodic import NewtonError
    real = C._Tracer.correct
    calls = {"n": 0}

    def failing(self, prob, Upred, n, U0, maxit=C._MAXIT):
        calls["n"] += 1
        if calls["n"] > 3:
            raise NewtonError("no convergence", maxit, 1.0, (Upred[:2], Upred[2]))
        return real(self, prob, Upred, n, U0, maxit)
    monkeypatch.setattr(C._Tracer, "correct", failing)
    with pytest.raises(pendula.ContinuationError, match="drive_amplitude") as info:
        pendula.continue_orbit(CASCADE, (0.1, 1.9), "drive_amplitude", 1.01)
    assert len(info.value.branch) >= 1


def test_ctrl_c_stops_a_long_continuation():
    code = textwrap.dedent("""
        import signal, sys, time
        signal.signal(signal.SIGINT, signal.default_int_handler)
        import pendula
        sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2/3)
        print("ready", flush=True)
        try:
            pendula.continue_orbit(sc, (0.1, 1.9), "drive_amplitude", 1.08, step=2e-6)
        except KeyboardInterrupt:
            print("interrupted", time.monotonic(), flush=True)
            sys.exit(0)
        sys.exit(3)
    """)
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True,
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        assert p.stdout.readline().strip() == "ready"
        import time
        time.sleep(1.5)
        p.send_signal(signal.SIGINT)
        out, _ = p.communicate(timeout=10)
        assert p.returncode == 0 and "interrupted" in out
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()

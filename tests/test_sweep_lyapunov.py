"""The lyapunov measure of sweeps against independent references:
the closed form of the linearised undriven pendulum, Floquet multipliers of a
period-1 orbit from a scipy monodromy matrix, Liouville's sum rule
lambda1 + lambda2 = -beta, and a stored scipy solve_ivp reference for the
chaotic amplitudes (data/lyapunov/gen_reference.py)."""

import json
import math
import pathlib

import numpy as np
import pytest

import pendula
from pendula import Scene
from test_sweep import _pendula_run     # the batch program pendula-run beside this Python

xr = pytest.importorskip("xarray")
solve_ivp = pytest.importorskip("scipy.integrate").solve_ivp

REF = pathlib.Path(__file__).resolve().parents[1] / "data" / "lyapunov" / "lyapunov_reference.json"
CLASSIC = dict(damping=0.5, drive_frequency=2.0 / 3.0, eps=1.0)


def lyap(scene, over, **kw):
    return pendula.sweep(scene, over=over, measure="lyapunov", **kw)


def linear_exponents(beta, eps):
    """max and min Re((-beta +- sqrt(beta^2 - 4 eps)) / 2): the closed form."""
    r = np.sqrt(complex(beta * beta - 4 * eps))
    ev = sorted([((-beta + r) / 2).real, ((-beta - r) / 2).real])
    return ev[1], ev[0]


def oscillation_bound(beta, eps, t_avg):
    """How far a finite-window estimate may sit from the exponent for the
    linear system w' = A w, A = [[0, 1], [-eps, -beta]] with complex
    eigenvalues mu +- i w: A = P R P^-1 with R = mu I + rotation, so
    |w(t)| / (e^(mu t) |w(0)|) lies in [1/cond(P), cond(P)]; the estimate
    (1/T) log(|w(T)| / |w(0)|) is within log(cond(P)) / T of mu (log(cond^2)
    covers both ends)."""
    a = np.array([[0.0, 1.0], [-eps, -beta]])
    val, vec = np.linalg.eig(a)
    v = vec[:, np.argmax(val.imag)]
    p = np.column_stack([v.real, v.imag])
    return 2.0 * math.log(np.linalg.cond(p)) / t_avg


@pytest.mark.parametrize("theta0", [0.0, 1e-7])
def test_undriven_underdamped_equilibrium_closed_form(theta0):
    # random (beta, eps) with beta^2 < 4 eps, log-uniform: scales vary
    rng = np.random.default_rng(141)
    t_avg = 3000.0
    for _ in range(4):
        eps = float(np.exp(rng.uniform(math.log(0.2), math.log(5.0))))
        beta = float(np.exp(rng.uniform(math.log(0.05), math.log(1.9 * math.sqrt(eps)))))
        ds = lyap(Scene(eps=eps, damping=beta, theta0=theta0), {"damping": [beta]}, transient=100.0,
                  t_max=t_avg, rtol=1e-11, atol=1e-13)
        l1, l2 = linear_exponents(beta, eps)
        assert l1 == l2 == -beta / 2
        tol = oscillation_bound(beta, eps, t_avg) + 1e-9   # the window's bounded oscillation + integration
        assert int(ds.status[0]) == 0
        assert abs(float(ds.lyapunov[0]) - l1) <= tol, (beta, eps, float(ds.lyapunov[0]), l1, tol)
        # Liouville: the sum is -beta for every orbit, whatever the window
        assert abs(float(ds.lyapunov[0] + ds.lyapunov2[0]) + beta) <= 1e-9


@pytest.mark.parametrize("theta0", [0.0, 1e-7])
def test_undriven_overdamped_equilibrium_closed_form(theta0):
    rng = np.random.default_rng(142)
    for _ in range(4):
        eps = float(np.exp(rng.uniform(math.log(0.2), math.log(5.0))))
        beta = float(2.0 * math.sqrt(eps) * np.exp(rng.uniform(math.log(1.1), math.log(6.0))))
        ds = lyap(Scene(eps=eps, damping=beta, theta0=theta0), {"damping": [beta]}, transient=100.0,
                  t_max=1000.0, rtol=1e-11, atol=1e-13)
        l1, l2 = linear_exponents(beta, eps)
        # real eigenvalues: after the transient the tangent lies on the slow
        # eigenvector to exp(-(l1 - l2) t_tr) < 1e-20, so only integration error is left
        assert abs(float(ds.lyapunov[0]) - l1) <= 1e-8 * max(1.0, abs(l1)), (beta, eps)
        assert abs(float(ds.lyapunov2[0]) - l2) <= 1e-8 * max(1.0, abs(l2)), (beta, eps)
        # the eigenvector is fixed: the blocks agree, the convergence estimate is tiny
        assert float(ds.lyapunov_err[0]) <= 1e-8


def test_undriven_critical_damping_closed_form():
    # beta^2 = 4 eps: a Jordan block, |w(t)| = e^(-beta t/2) |(I + N t) w|, N = A + beta/2;
    # the estimate is within log(1 + |N| (t_tr + T)) / T of -beta/2
    eps, beta, t_tr, t_avg = 0.7, 2.0 * math.sqrt(0.7), 50.0, 4000.0
    ds = lyap(Scene(eps=eps, damping=beta), {"damping": [beta]}, transient=t_tr, t_max=t_avg,
              rtol=1e-11, atol=1e-13)
    n = np.array([[beta / 2, 1.0], [-eps, -beta / 2]])
    tol = math.log(1 + np.linalg.norm(n, 2) * (t_tr + t_avg + 2 * math.pi / math.sqrt(eps))) / t_avg
    assert abs(float(ds.lyapunov[0]) + beta / 2) <= tol
    assert abs(float(ds.lyapunov[0] + ds.lyapunov2[0]) + beta) <= 1e-9


def _monodromy(amp, th0, v0):
    """Floquet multipliers of the driven orbit through (th0, v0) at drive phase 0:
    scipy solve_ivp over one period on the orbit and the identity's columns."""
    om, beta = CLASSIC["drive_frequency"], CLASSIC["damping"]
    T = 2 * math.pi / om

    def f(t, y):
        c = -math.cos(y[0])
        return [y[1], -math.sin(y[0]) - beta * y[1] + amp * math.cos(om * t),
                y[3], c * y[2] - beta * y[3], y[5], c * y[4] - beta * y[5]]

    sol = solve_ivp(f, (0, T), [th0, v0, 1.0, 0.0, 0.0, 1.0], method="DOP853", rtol=1e-12, atol=1e-14)
    y = sol.y[:, -1]
    return np.array([[y[2], y[4]], [y[3], y[5]]]), T


def test_period1_orbit_A0p9_negative_and_floquet():
    amp = 0.9
    s = Scene(**CLASSIC, drive_amplitude=amp)
    # period 1 (the poincare measure): the stroboscopic points coincide
    pc = pendula.sweep(s, over={"drive_amplitude": [amp]}, measure="poincare", transient=3000.0, samples=8,
                       rtol=1e-11, atol=1e-13)
    assert np.ptp(pc.theta.values[0]) < 1e-8 and np.ptp(pc.v.values[0]) < 1e-8
    ds = lyap(s, {"drive_amplitude": [amp]}, transient=1000.0, t_max=3000.0, rtol=1e-11, atol=1e-13)
    l1, l2 = float(ds.lyapunov[0]), float(ds.lyapunov2[0])
    assert l1 < -0.05
    # the independent reference: the multipliers of the monodromy matrix on the cycle
    m, T = _monodromy(amp, float(pc.theta.values[0, 0]), float(pc.v.values[0, 0]))
    mu, vec = np.linalg.eig(m)
    ref = sorted(np.log(np.abs(mu)) / T)[::-1]
    # Liouville on the reference: det M = exp(-beta T)
    assert abs(np.linalg.det(m) - math.exp(-0.5 * T)) < 1e-9 * math.exp(-0.5 * T)
    if abs(mu[0].imag) > 0:
        # complex multipliers (|mu| = exp(-beta T / 2)): the kernel's window is
        # whole periods from a stroboscopic time, where the tangent map is M^n =
        # P (|mu| R)^n P^-1 with R a rotation: as for the linear case, the
        # estimate is within 2 log cond(P) / (n T) of log|mu| / T
        n_avg = math.ceil(3000.0 / T - 1e-12)
        p = np.column_stack([vec[:, 0].real, vec[:, 0].imag])
        tol = 2 * math.log(np.linalg.cond(p)) / (n_avg * T) + 1e-9
    else:
        tol = 1e-7   # real multipliers: convergence is geometric
    assert abs(l1 - ref[0]) <= tol, (l1, ref)
    # the sum rule, tight: lambda1 + lambda2 = -beta (trace of the Jacobian)
    assert abs(l1 + l2 + 0.5) <= 1e-9


def _reference():
    return json.loads(REF.read_text())


@pytest.mark.parametrize("amp", [1.15, 1.5])
def test_chaotic_amplitude_positive_against_scipy_reference(amp):
    ref = _reference()
    row = next(r for r in ref["points"] if r["amp"] == amp)
    s = Scene(**CLASSIC, drive_amplitude=amp)
    T = 2 * math.pi / CLASSIC["drive_frequency"]
    ds = lyap(s, {"drive_amplitude": [amp]}, transient=ref["n_transient_periods"] * T,
              t_max=ref["n_average_periods"] * T, rtol=1e-10, atol=1e-12)
    l1, err = float(ds.lyapunov[0]), float(ds.lyapunov_err[0])
    assert l1 > 0.05 and row["lambda1"] > 0.05
    # two independent estimates of one ergodic average: within 4 combined standard errors
    assert abs(l1 - row["lambda1"]) <= 4 * math.hypot(err, row["err"]), (l1, err, row)
    assert abs(l1 + float(ds.lyapunov2[0]) + 0.5) <= 1e-8


def test_random_amplitudes_against_scipy_reference():
    ref = _reference()
    T = 2 * math.pi / CLASSIC["drive_frequency"]
    amps = [r["amp"] for r in ref["points"]]
    ds = lyap(Scene(**CLASSIC, drive_amplitude=1.0), {"drive_amplitude": amps},
              transient=ref["n_transient_periods"] * T, t_max=ref["n_average_periods"] * T, rtol=1e-10, atol=1e-12)
    for k, r in enumerate(ref["points"]):
        l1, err = float(ds.lyapunov[k]), float(ds.lyapunov_err[k])
        # 4 combined standard errors, and at least the reference's integration level
        assert abs(l1 - r["lambda1"]) <= 4 * math.hypot(err, r["err"]) + 1e-6, (r, l1, err)


def test_threads_1_and_2_identical_and_point_equals_single_call():
    amps = np.array([0.93, 1.07, 1.15, 1.28, 1.41, 1.5])
    kw = dict(transient=300.0, t_max=600.0, rtol=1e-9, atol=1e-11)
    s = Scene(**CLASSIC, drive_amplitude=1.0)
    a = lyap(s, {"drive_amplitude": amps}, threads=1, **kw)
    b = lyap(s, {"drive_amplitude": amps}, threads=2, chunk_points=4, **kw)
    assert a.identical(b)
    for k in (0, 3, 5):
        one = lyap(s, {"drive_amplitude": [amps[k]]}, **kw)
        for v in ("lyapunov", "lyapunov_err", "lyapunov2", "status"):
            assert one[v].values[0] == a[v].values[k]


def test_lyapunov_drive_frequency_axis_rounds_per_point():
    # the transient and window are whole periods of each point's own drive:
    # a point with another frequency equals the single call at that frequency
    s = Scene(**CLASSIC, drive_amplitude=1.2)
    kw = dict(transient=200.0, t_max=400.0, rtol=1e-9, atol=1e-11)
    ds = lyap(s, {"drive_frequency": [0.5, 2.0 / 3.0]}, **kw)
    one = lyap(s.replace(drive_frequency=0.5), {"drive_amplitude": [1.2]}, **kw)
    assert ds.lyapunov.values[0] == one.lyapunov.values[0]


def test_pendula_run_lyapunov_scene_matches_python(tmp_path):
    scene = tmp_path / "l.nml"
    scene.write_text("&scene\n damping = 0.5\n drive_frequency = 0.6666666666666666\n drive_amplitude = 1\n"
                     " grid = 'drive_amplitude'\n grid1_range = 0.9, 1.5, 5\n measure = 'lyapunov'\n"
                     " sweep_transient = 300\n sweep_t_max = 600\n rtol = 1e-9\n atol = 1e-11\n/\n")
    r = _pendula_run(scene, "-o", tmp_path / "l.csv")
    assert r.returncode == 0, r.stderr
    lines = (tmp_path / "l.csv").read_text().splitlines()
    assert lines[1] == "drive_amplitude,lyapunov,lyapunov_err,lyapunov2,status"
    tab = np.loadtxt(tmp_path / "l.csv", delimiter=",", comments="#", skiprows=2)
    ds = pendula.sweep(Scene.from_file(scene))
    assert np.array_equal(tab[:, 1], ds.lyapunov.values)      # the same kernel, bit for bit
    assert np.array_equal(tab[:, 3], ds.lyapunov2.values)
    assert np.array_equal(tab[:, 4], ds.status.values)


def test_lyapunov_bad_arguments():
    s = Scene(**CLASSIC, drive_amplitude=1.2)
    with pytest.raises(ValueError, match="t_max"):
        lyap(s, {"drive_amplitude": [1.2]}, t_max=0.0)
    with pytest.raises(ValueError, match="transient"):
        lyap(s, {"drive_amplitude": [1.2]}, transient=-1.0)
    # a window too long to count: refused up front naming t_max (the sweep's limit 1e8), never a hang
    with pytest.raises(ValueError, match="t_max must be at most 1e\\+08"):
        lyap(s, {"drive_amplitude": [1.2]}, t_max=1e300)


def test_lyapunov_gallery_scenes_are_the_demo_sweeps():
    from pendula.demos.sweeps import LYAPUNOV_FULL, LYAPUNOV_SMALL
    folder = REF.parents[1] / "scenes" / "sweeps"
    small = Scene.from_file(folder / "driven_lyapunov_small.nml")
    full = Scene.from_file(folder / "driven_lyapunov.nml")
    assert small.replace(name="") == LYAPUNOV_SMALL and full.replace(name="") == LYAPUNOV_FULL
    assert small.measure == full.measure == "lyapunov"


@pytest.mark.parametrize("how", ["torque", "drive_of_frequency_0"])
def test_torqued_equilibrium_closed_form(how):
    # at the equilibrium theta_s = asin(tau / eps) the linearisation has
    # stiffness eps cos(theta_s): exponents (-beta +- sqrt(beta^2 - 4 eps cos theta_s)) / 2
    eps, beta, tau = 1.3, 3.1, 0.4
    ths = math.asin(tau / eps)
    if how == "torque":
        s = Scene(eps=eps, damping=beta, torque=tau, theta0=ths)
    else:
        # A cos(0 t + phi) with A cos(phi) = tau: a constant force, the same motion
        s = Scene(eps=eps, damping=beta, drive_amplitude=2 * tau, drive_phase=math.pi / 3, theta0=ths)
    ds = lyap(s, {"eps": [eps]}, transient=50.0, t_max=500.0, rtol=1e-11, atol=1e-13)
    l1, l2 = linear_exponents(beta, eps * math.cos(ths))
    assert int(ds.status[0]) == 0
    assert abs(float(ds.lyapunov[0]) - l1) <= 1e-8 * abs(l1)
    assert abs(float(ds.lyapunov2[0]) - l2) <= 1e-8 * abs(l2)


def test_atol_0_at_the_equilibrium_is_a_reported_failure():
    # pure relative error control on v = 0 (round-off only) cannot be met: the
    # step shrinks to nothing; reported as the integrator's failure (100 + 5,
    # step underflow, or 100 + 6, the non-finite state the shrinking step runs
    # into: which comes first depends on the last bits of the vectorised libm,
    # and differs between the native and the -fcheck=all debug build), NaN out
    s = Scene(damping=3.1, torque=0.4, theta0=math.asin(0.4))
    ds = lyap(s, {"damping": [3.1]}, transient=50.0, t_max=500.0, rtol=1e-11, atol=0.0)
    assert int(ds.status[0]) in (105, 106) and np.isnan(ds.lyapunov[0]) and np.isnan(ds.lyapunov2[0])

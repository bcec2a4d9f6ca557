"""Huygens' cycloidal pendulum (Prusa & Tuma, section 4): closed form at
every amplitude, checked against independent references (mpmath quadrature of
the physics, mpmath's ODE solver, the rigid pendulum's exact solution)."""

import math
import subprocess

import mpmath as mp
import numpy as np
import pytest

import pendula
from pendula import Scene, SceneError
from pendula.systems.cycloid import cycloid_motion, cycloid_period

from conftest import EPS, pendula_run_table, venv_bin

RNG = np.random.default_rng(1313)


def amplitudes():
    """log-uniform random amplitudes from 1e-6 to the cusp, and the cusp itself"""
    a = np.exp(RNG.uniform(math.log(1e-6), math.log(math.pi / 2), 12))
    return [*a, 1e-6, 1.0, math.pi / 2]


@pytest.mark.parametrize("r", [0.25, 0.1, 1.7])
def test_period_independent_of_amplitude_to_the_cusp(r):
    # s(t + k T) = s(t) for every amplitude: the motion is simple harmonic in s.
    # Rounding: s is 4r sin(theta0) times cos(2 pi k) with an argument error of
    # a few ulps of 2 pi k, second order at a maximum: a few eps of 4r.
    for th0 in amplitudes():
        sc = Scene(guide="cycloid", cycloid_radius=r, eps=2.3, theta0=th0)
        T = cycloid_period(sc)
        assert T == pytest.approx(4 * math.pi * math.sqrt(r / 2.3), rel=2 * EPS)
        _, _, s, sd = cycloid_motion(sc, [0.0, T, 2 * T, 5 * T])
        assert np.abs(s - s[0]).max() <= 8 * EPS * 4 * r
        assert np.abs(sd).max() <= 8 * EPS * 4 * r * math.sqrt(2.3 / (4 * r)) * 5 * 2 * math.pi


def test_tautochrone_descent_time_from_every_height():
    # Abel (section 4.2): the time to slide to the lowest point on the cycloid
    # x = R(phi + sin phi), y = R(1 - cos phi) is the same from every height.
    # Reference: the energy integral along the curve, by mpmath's tanh-sinh
    # quadrature (it handles the inverse-square-root endpoint), at 30 digits.
    mp.mp.dps = 30
    R, g = mp.mpf("0.37"), mp.mpf("9.81")
    for phi0 in [mp.mpf(x) for x in (1e-3, 0.3, 1.0, 2.0, 3.0, 3.14159)]:
        y0 = R * (1 - mp.cos(phi0))

        def dt(phi):
            ds = R * mp.sqrt((1 + mp.cos(phi)) ** 2 + mp.sin(phi) ** 2)
            drop = 2 * R * mp.sin((phi0 + phi) / 2) * mp.sin((phi0 - phi) / 2)   # y0 - y, no cancellation
            return ds / mp.sqrt(2 * g * drop)

        t_desc = mp.quad(dt, [0, phi0])
        # tanh-sinh at 30 digits with the inverse-square-root endpoint: good to ~1e-17 here
        assert abs(t_desc / (mp.pi * mp.sqrt(R / g)) - 1) < mp.mpf("1e-15")
    mp.mp.dps = 15
    # and the kernel's path reaches s = 0 at T/4 from every starting angle (at rest)
    for th0 in amplitudes():
        sc = Scene(guide="cycloid", theta0=th0, g=9.81, length=4 * 0.37)
        T = cycloid_period(sc)
        _, _, s, _ = cycloid_motion(sc, [T / 4])
        assert abs(s[0]) <= 4 * EPS * 4 * sc.cycloid_radius


def test_small_amplitude_matches_rigid_pendulum_to_order_theta0_squared():
    # R = l/4: the same small-oscillation frequency; over one period the phases
    # part by 2 pi theta0^2/16, so |theta_cyc - theta_rigid| / theta0 ~ theta0^2.
    rel = []
    for th0 in (1e-1, 1e-2, 1e-3):
        sc = Scene(guide="cycloid", theta0=th0, eps=1.0)
        t = np.linspace(0, 2 * math.pi, 400)
        th_c = pendula.simulate(sc, t).theta
        th_r, _ = pendula.exact_motion(th0, 0.0, 1.0, t)
        rel.append(np.abs(th_c - th_r).max() / th0)
    for a, b in zip(rel, rel[1:]):
        assert 80 < a / b < 120          # shrinks like theta0^2 (factor 100 per decade)
    assert rel[-1] < 1e-6


@pytest.mark.parametrize("torque", [0.0, 0.05])
def test_energy_conserved(torque):
    # E = s'^2/2 + w2 s^2/2 - tau s is conserved; rounding of s and s' (a few
    # ulps of 4r) allows a few eps of the energy scale w2 (4r)^2.
    for th0 in amplitudes()[:-1]:
        sc = Scene(guide="cycloid", theta0=th0 * 0.7, v0=0.1 * th0, torque=torque)
        t = RNG.uniform(-50, 50, 200)
        tr = pendula.simulate(sc, t)
        e0 = pendula.simulate(sc, [0.0]).energy[0]
        assert np.abs(tr.energy - e0).max() <= 16 * EPS * (0.5 * sc.eps + abs(torque))


@pytest.mark.parametrize("beta,tau,amp,om", [
    (0.3, 0.0, 0.0, 0.0),            # under-damped
    (2.0, 0.0, 0.0, 0.0),            # critical (w2 = 1, beta = 2)
    (5.0, 0.02, 0.0, 0.0),           # over-damped, with torque
    (0.1, 0.0, 0.05, 1.7),           # damped and driven
    (0.0, 0.0, 0.01, 1.0),           # undamped exact resonance (secular)
    (0.0, -0.03, 0.02, 0.63),        # undamped, driven off resonance, with torque
])
def test_damped_driven_against_mpmath_ode(beta, tau, amp, om):
    # Reference: mpmath's Taylor ODE solver at 25 digits on s'' + beta s' + s = tau + A cos(om t + 0.4)
    sc = Scene(guide="cycloid", theta0=0.3, v0=-0.2, damping=beta, torque=tau, drive_amplitude=amp,
               drive_frequency=om, drive_phase=0.4)
    r = sc.cycloid_radius
    s0, v0 = 4 * r * math.sin(0.3), 4 * r * math.cos(0.3) * -0.2
    mp.mp.dps = 25
    f = mp.odefun(lambda t, y: [y[1], -beta * y[1] - y[0] + tau + amp * mp.cos(om * t + mp.mpf("0.4"))],
                  0, [mp.mpf(s0), mp.mpf(v0)])
    ts = [0.37, 1.9, 4.4, 7.0]
    ref = [f(t) for t in ts]
    mp.mp.dps = 15
    _, _, s, sd = cycloid_motion(sc, ts)
    for k in range(len(ts)):
        # the initial state is rounded to doubles; cancellation between the steady and transient parts
        # costs a few digits when the driven response is large: 1e-13 absolute on a scale of 4r = 1
        assert abs(s[k] - float(ref[k][0])) <= 1e-13
        assert abs(sd[k] - float(ref[k][1])) <= 1e-13


def test_involute_of_the_cheek_is_the_path():
    # Section 4.3: unwrapping the cord (length 4R) from the cheek traces the path.
    # The involute is rebuilt here from the cheek's points alone: arc length by
    # mpmath quadrature of the cheek's speed, tangent by mpmath's derivative.
    R = 0.8
    geo = pendula.cycloid_geometry(R, n=201)
    # the cheeks returned lie on x = R(p - sin p), y = R(3 + cos p)
    p = np.linspace(0.0, math.pi, 201)
    assert np.abs(geo.cheek_right - R * np.array([p - np.sin(p), 3 + np.cos(p)])).max() <= 8 * EPS * R
    assert np.abs(geo.cheek_left[0] + geo.cheek_right[0]).max() == 0.0
    mp.mp.dps = 30

    def cheek(q):
        return mp.matrix([R * (q - mp.sin(q)), R * (3 + mp.cos(q))])

    for theta in RNG.uniform(0.01, math.pi / 2 - 0.01, 8):
        q = mp.mpf(2 * theta)
        d = mp.matrix([mp.diff(lambda z: cheek(z)[0], q), mp.diff(lambda z: cheek(z)[1], q)])
        speed = mp.sqrt(d[0] ** 2 + d[1] ** 2)
        arc = mp.quad(lambda z: mp.sqrt(mp.diff(lambda w: cheek(w)[0], z) ** 2
                                        + mp.diff(lambda w: cheek(w)[1], z) ** 2), [0, q])
        end = cheek(q) + (4 * R - arc) * d / speed
        wrapped, contact, bob = geo.cord(float(theta))
        assert abs(float(end[0]) - bob[0]) <= 8 * EPS * R and abs(float(end[1]) - bob[1]) <= 8 * EPS * R
        assert abs(float(cheek(q)[0]) - contact[0]) <= 8 * EPS * R
        # the bob is on the path returned by cycloid_geometry (phi = 2 theta)
        assert bob[0] == pytest.approx(R * (2 * theta + math.sin(2 * theta)), abs=4 * EPS * R)
    mp.mp.dps = 15


def test_cusp_amplitude_is_allowed_beyond_is_an_error():
    sc = Scene(guide="cycloid", theta0=math.pi / 2)
    with pytest.warns(RuntimeWarning, match="cusp"):
        tr = pendula.simulate(sc, [0.0, 1.0])
    assert math.isnan(tr.v[0]) and math.isfinite(tr.v[1])
    with pytest.raises(SceneError, match="theta0.*cusp"):
        Scene(guide="cycloid", theta0=1.6)
    with pytest.raises(ValueError, match="cusp"):
        pendula.simulate(Scene(guide="cycloid", theta0=1.5, v0=2.0), np.linspace(0, 2, 201))
    # an undamped resonant drive grows until it runs off the cheeks
    with pytest.raises(ValueError, match="cusp"):
        pendula.simulate(Scene(guide="cycloid", theta0=0.1, drive_amplitude=0.05, drive_frequency=1.0,
                               t_end=200, n_samples=2001))


def test_effects_without_meaning_on_the_guide_are_errors():
    with pytest.raises(SceneError, match="cord"):
        Scene(guide="cycloid", cord="flexible")
    with pytest.raises(SceneError, match="gravity"):
        Scene(guide="cycloid", gravity="linear", gravity_gradient=0.1)
    with pytest.raises(SceneError, match="method.*closed form"):
        Scene(guide="cycloid", method="rk4", dt=0.01)
    with pytest.raises(SceneError, match="cycloid_radius"):
        Scene(guide="cycloid", cycloid_radius=-1.0)
    with pytest.raises(SceneError, match="cycloid_radius"):
        Scene(cycloid_radius=0.3)
    with pytest.raises(ValueError, match="never integrated"):
        pendula.simulate(Scene(guide="cycloid", theta0=0.2), [1.0], method="dop853")


def test_torque_shifts_the_centre():
    # a constant force along the path: the oscillation is centred on s = tau / w2
    sc = Scene(guide="cycloid", torque=0.1, theta0=0.0)
    T = cycloid_period(sc)
    _, _, s, _ = cycloid_motion(sc, [T / 2])
    assert s[0] == pytest.approx(2 * 0.1 / 1.0, rel=8 * EPS)


def test_pendula_run_cycloid_scene_matches_python(tmp_path):
    data, f = pendula_run_table(tmp_path, " guide = 'cycloid', cycloid_radius = 0.3, theta0 = 1.2, v0 = 0.1,\n damping = 0.05, t_end = 30, n_samples = 301")
    tr = pendula.simulate(Scene.from_file(f), data[:, 0])   # the same kernel code at the same times
    assert np.abs(data[:, 1] - tr.theta).max() <= 4 * EPS
    assert np.abs(data[:, 3] - tr.energy).max() <= 1e-15
    bad = tmp_path / "bad.nml"
    bad.write_text("&scene\n guide = 'cycloid', method = 'rk4', dt = 0.1\n/\n")
    p = subprocess.run([venv_bin("pendula-run"), str(bad)], capture_output=True, text=True)
    assert p.returncode == 2 and "method" in p.stderr and "closed form" in p.stderr


def test_non_finite_times_give_nan_with_a_warning():
    sc = Scene(guide="cycloid", theta0=1.0)
    with pytest.warns(RuntimeWarning, match="non-finite"):
        tr = pendula.simulate(sc, [np.nan, np.inf, 1.0])
    assert np.isnan(tr.theta[:2]).all() and np.isfinite(tr.theta[2])


@pytest.mark.parametrize("body,name", [
    ("guide = 'cycloid', theta0 = 1.6", "theta0"),
    ("guide = 'cycloid', cycloid_radius = 0.0", "cycloid_radius"),
    ("cycloid_radius = 0.3", "cycloid_radius"),
    ("guide = 'cycloid', cord = 'flexible'", "cord"),
    ("guide = 'cycloid', gravity = 'linear', gravity_gradient = 0.1", "gravity"),
])
def test_both_readers_refuse_the_same_cycloid_scenes(tmp_path, body, name):
    f = tmp_path / "bad.nml"
    f.write_text(f"&scene\n {body}\n/\n")
    with pytest.raises(SceneError, match=name):
        Scene.from_file(f)
    p = subprocess.run([venv_bin("pendula-run"), str(f)], capture_output=True, text=True)
    assert p.returncode == 2 and name in p.stderr, p.stderr


def test_prusa_tuma_involute_formula_4_22_slip():
    # Source 003 (4.21) with L = 4R, evaluated by mpmath, is [0, -2R] + [R(p + sin p), -R(1 + cos p)]
    # (the hanging cord reaches -4R at p = 0), not the printed (4.22) [0, -R] + [R(p - sin p), -R(1 + cos p)].
    mp.mp.dps = 30
    R = mp.mpf("0.7")
    for p in (mp.mpf("0.3"), mp.mpf(2), mp.mpf(3)):
        f = (4 * R - mp.quad(lambda x: 2 * R * mp.sin(x / 2), [0, p])) / (2 * R * mp.sin(p / 2))
        g = (R * (p - mp.sin(p)) + f * R * (1 - mp.cos(p)), -R * (1 - mp.cos(p)) - f * R * mp.sin(p))
        assert abs(g[0] - R * (p + mp.sin(p))) < 1e-25 and abs(g[1] - (-2 * R - R * (1 + mp.cos(p)))) < 1e-25
        assert abs(g[1] - (-R - R * (1 + mp.cos(p)))) > 0.5 * R        # the printed shift is R short
    mp.mp.dps = 15


def test_sweep_beyond_the_cusp_is_refused_before_output(tmp_path):
    f = tmp_path / "s.nml"
    f.write_text("&scene\n guide = 'cycloid', sweep = 'theta0', sweep_values = 0.5, 1.7\n/\n")
    with pytest.raises(SceneError, match="theta0"):
        Scene.from_file(f)
    out = tmp_path / "o.csv"
    p = subprocess.run([venv_bin("pendula-run"), str(f), "-o", str(out)], capture_output=True, text=True)
    assert p.returncode == 2 and "theta0" in p.stderr and not out.exists()


# ------------------------------------------------------------ corners: heavy damping, bad arguments, cusps

def _overdamped_theta_mp(eps, r, beta, theta0, t):
    mp.mp.dps = 60
    eps, r, beta, theta0, t = (mp.mpf(x) for x in (eps, r, beta, theta0, t))
    w2 = eps / (4 * r)
    h = beta / 2
    mu = mp.sqrt(h * h - w2)
    r1, r2 = -w2 / (h + mu), -h - mu
    s0 = 4 * r * mp.sin(theta0)
    a = -r2 * s0 / (r1 - r2)
    return mp.asin((a * mp.exp(r1 * t) + (s0 - a) * mp.exp(r2 * t)) / (4 * r))


@pytest.mark.parametrize("damping", [1e3, 1e8, 3.7e59, 1e160, 1e300])
def test_heavy_damping_keeps_the_slow_decay(damping):
    # the slow root -(h - mu) = -w2 / (h + mu), never h - mu (which cancels to nothing)
    sc = Scene(guide="cycloid", theta0=1.0, damping=damping)
    w2 = sc.eps / (4 * sc.cycloid_radius)
    t = np.array([100.0, 0.01 * damping / w2, 2.0 * damping / w2])
    th = cycloid_motion(sc, t)[0]
    for ti, got in zip(t, th):
        ref = float(_overdamped_theta_mp(sc.eps, sc.cycloid_radius, damping, 1.0, ti))
        assert abs(got - ref) <= 8 * EPS * abs(ref)


def test_cycloid_period_of_a_number_names_the_scene_argument():
    with pytest.raises(TypeError, match="scene must be a pendula.Scene"):
        cycloid_period(0.25)
    with pytest.raises(ValueError, match="guide"):
        cycloid_period(Scene(theta0=0.5))


def test_period_and_simulate_agree_on_a_scene_beyond_the_cusps():
    # the kernel's scene rule refuses the conservative orbit that reaches the cusps when the scene is made,
    # so simulate, period and cycloid_period cannot disagree on it; the field is named
    with pytest.raises(pendula.SceneError, match="field 'v0'.*cusps"):
        Scene(guide="cycloid", v0=10.0)
    # the same state with damping is a scene; the damped orbit still reaches a cusp: simulate refuses it
    # at run time, and the period (of the conservative motion, which reaches the cusps) is refused too
    sc = Scene(guide="cycloid", v0=10.0, damping=0.01)
    with pytest.raises(ValueError, match="cusp"):
        pendula.simulate(sc)
    with pytest.raises(ValueError, match="cusp"):
        cycloid_period(sc)


def test_cycloid_geometry_bounds_its_points():
    with pytest.raises(ValueError, match="n must be"):
        pendula.cycloid_geometry(1.0, n=10 ** 8)
    with pytest.raises(TypeError, match="R must be"):
        pendula.cycloid_geometry("1.0")

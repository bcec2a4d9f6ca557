"""The pendulum on a flexible cord (Garfinkel 1957, seed 000).

Every check here reads the simulated flips (departure, parabola, re-entry root,
jerk) and compares them with independent references: Garfinkel's closed-form
map f and his relations (eqs. 13-17), mpmath roots of f at 50 digits, his
printed tables (to their printed digits), and the jumping-pendulum special
values of Goriely, Boulanger and Leroy (Am. J. Phys. 74, 2006).
"""

import math
import warnings

import mpmath as mp
import numpy as np
import pytest

import pendula
from pendula import Scene, cord_state, flip_map, flip_sequence

EPS = 1.0


def v0_of(xi, eps=EPS):
    """Speed at the bottom for Garfinkel's energy xi: v^2 - 2 eps = 3 eps xi."""
    return math.sqrt(eps * (3.0 * xi + 2.0))


def run(xi, max_flips=1, t_end=200.0, n=3, **kw):
    sc = Scene(cord="flexible", v0=v0_of(xi, kw.pop("eps", EPS)), t_end=t_end, n_samples=n,
               max_flips=max_flips, **kw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # NaN after the max_flips stop: intended here
        return pendula.simulate(sc)


# ------------------------------------------------------------ the closed forms against mpmath

def f_mp(x):
    x = mp.mpf(x)
    return x - mp.mpf(64) / 3 * (x * (1 - x * x)) ** 3


def test_flip_sequence_against_mpmath():
    mp.mp.dps = 50
    xs = [mp.mpf(-2) / 3, mp.mpf(0), mp.findroot(f_mp, 0.236), mp.findroot(f_mp, 0.751)]
    while len(xs) < 14:
        target = xs[len(xs) - 2]
        xs.append(mp.findroot(lambda x: f_mp(x) - target, (mp.mpf("0.5458"), mp.mpf(1)), solver="bisect"))
    got = flip_sequence(14)
    # about 1 ulp per inversion; 1e-14 absolute leaves room for the growth of f^-1's slope
    assert np.max(np.abs(got - np.array([float(x) for x in xs]))) < 1e-14
    # Garfinkel's printed terms (3 decimals, eq. 17)
    np.testing.assert_allclose(got[:9], [-0.667, 0.0, 0.236, 0.751, 0.791, 0.889, 0.899, 0.930, 0.935],
                               atol=5e-4)
    assert np.all(np.diff(got) > 0) and got[-1] < 1


def test_flip_map_outside_is_identity_and_nan_propagates():
    x = np.array([-2 / 3, -0.1, 1.0, 1.0 + 1e-15, 7.0])
    assert np.array_equal(flip_map(x), x)
    assert math.isnan(flip_map(math.nan))
    with pytest.raises(TypeError):
        flip_map("a")


def test_cord_state_index():
    assert cord_state(-0.5) == 0 and cord_state(0.1) == 1 and cord_state(0.5) == 2
    assert cord_state(0.777) == 3 and cord_state(1.5) == math.inf and cord_state(1.0) == math.inf
    with pytest.warns(RuntimeWarning):
        assert math.isnan(cord_state(-1.0))


# ------------------------------------------------------------ the map from simulated flips

def test_simulated_map_against_closed_form():
    rng = np.random.default_rng(12)
    xs = np.concatenate([rng.uniform(0, 1, 150), 10 ** rng.uniform(-9, -1, 40), 1 - 10 ** rng.uniform(-9, -1, 40),
                         [0.236, 0.5, 3 ** -0.5, 2 ** -0.5, 0.751, 0.999999]])
    worst = 0.0
    for x in xs:
        tr = run(float(x))
        fl = tr.flips
        assert fl["xi_before"].size == 1
        # the departure energy is the initial one (exact circle: energy conserved to rounding)
        assert abs(fl["xi_before"][0] - x) < 4e-16 * 8
        ref = float(f_mp(fl["xi_before"][0]))
        err = abs(fl["xi_after"][0] - ref)
        # relative to |f| away from f's zeros; near them the absolute error is what the energy allows
        worst = max(worst, err / max(abs(ref), 1e-3))
        # theta_return = 2 pi - 3 theta_leave (mod 2 pi), eq. 13.2
        d = (fl["theta_return"][0] - (2 * np.pi - 3 * fl["theta_leave"][0])) % (2 * np.pi)
        assert min(d, 2 * np.pi - d) < 1e-12
        # eq. 13.1: flight time 4 sqrt(xi (1 - xi^2)) / omega (xi as simulated: the bottom speed fixes xi only
        # to an absolute 1e-16, so small xi are known to the simulation better than x)
        xb = fl["xi_before"][0]
        assert fl["t_return"][0] - fl["t_leave"][0] == pytest.approx(4 * math.sqrt(xb * (1 - xb * xb)), rel=1e-12)
    assert worst < 1e-12


def test_table1_from_simulation():
    # Garfinkel's Table 1: x, f(x), theta1, theta2 (degrees), printed to the digits given
    table = [(0.0, 0.000, 90.0, 90.0), (0.1, 0.079, 95.7, 72.8), (0.2, 0.049, 101.5, 55.4),
             (0.3, -0.134, 107.5, 37.6), (0.4, -0.409, 113.6, 19.3), (0.5, -0.625, 120.0, 0.0),
             (0.6, -0.608, 126.9, -20.6), (0.7, -0.271, 134.4, -43.3), (0.8, 0.290, 143.1, -69.4),
             (0.9, 0.793, 154.2, -102.5)]
    for x, f, th1, th2 in table:
        if x == 0.0:
            tr = run(1e-12)  # xi = 0 has no flight; its limit
        else:
            tr = run(x)
        fl = tr.flips
        assert fl["xi_after"][0] == pytest.approx(f, abs=5.1e-4)
        assert math.degrees(fl["theta_leave"][0]) == pytest.approx(th1, abs=0.051)
        t2 = math.degrees(math.remainder(fl["theta_return"][0], 2 * math.pi))
        assert t2 == pytest.approx(th2, abs=0.051)


def test_stationary_values_and_zeros_from_simulated_flips():
    xs = np.linspace(0.001, 0.999, 999)
    fs = np.array([run(float(x)).flips["xi_after"][0] for x in xs])
    i = int(np.argmin(fs))
    j = int(np.argmax(fs[:400]))
    # grid spacing 1e-3: the argmin is within a grid step of 0.5458 (seed README: the print 0.544 is a slip)
    assert abs(xs[i] - 0.5458) < 1.5e-3 and fs[i] == pytest.approx(-0.6547, abs=1e-4)
    # max f = f(0.1305) = 0.08547 (mpmath); Garfinkel prints +0.086 = f(0.130), a rounding slip (README)
    assert abs(xs[j] - 0.1305) < 1.5e-3 and fs[j] == pytest.approx(0.08547, abs=1e-5)
    sign = np.nonzero(np.diff(np.sign(fs)))[0]
    assert np.allclose(xs[sign], [0.236, 0.751], atol=1.5e-3)


def test_special_values_from_simulation():
    rng = np.random.default_rng(5)
    xs = np.sort(np.concatenate([rng.uniform(0.3, 0.9, 300), [3 ** -0.5, 2 ** -0.5, 0.5 * math.sqrt(3 - math.sqrt(3)) + 1e-7]]))
    loss, amp, sense, vsense = [], [], [], []
    for x in xs:
        fl = run(float(x)).flips
        loss.append(fl["xi_before"][0] - fl["xi_after"][0])
        amp.append(abs(math.sin((fl["theta_leave"][0] - fl["theta_return"][0]) / 2)))
        sense.append(math.remainder(fl["theta_return"][0], 2 * math.pi))
        vsense.append(fl["v_return"][0] * fl["v_leave"][0])
    loss, amp, sense, vsense = map(np.array, (loss, amp, sense, vsense))
    assert xs[np.argmax(loss)] == pytest.approx(3 ** -0.5, abs=5e-3)
    assert xs[np.argmax(amp)] == pytest.approx(2 ** -0.5, abs=5e-3)
    assert np.max(amp) == pytest.approx(1.0, abs=1e-12)
    # theta2 changes sign (the boundary between flips that return on the near side and the far side) at
    # xi = 1/2: Garfinkel prints 0.5 [3 - 3^1/2]^1/2 = 0.563, which is not where theta2 = 0 (see README)
    k = np.nonzero(np.diff(np.sign(sense)))[0]
    assert len(k) == 1 and 0.49 < xs[k[0]] <= 0.5 <= xs[k[0] + 1] < 0.51
    # the sense of rotation reverses ("oscillatory" flips) below 0.5 (3 - 3^1/2)^1/2 = 0.563, as Garfinkel
    # prints; there theta2' = 0 (the OCR lost the dot: theta2 = 0 is at xi = 1/2, above)
    xb = 0.5 * math.sqrt(3 - math.sqrt(3))
    assert np.all(vsense[xs < xb - 1e-9] < 0) and np.all(vsense[xs > xb + 1e-9] > 0)


def test_example_xi_0777():
    tr = run(0.777, max_flips=300, t_end=1e6)
    fl = tr.flips
    assert cord_state(0.777) == 3
    assert cord_state(fl["xi_after"][0]) == 1  # one flip: state 3 -> 1
    assert np.all(cord_state(fl["xi_after"]) == 1)
    assert np.all(np.diff(fl["xi_after"]) < 0) and fl["xi_after"][-1] < 0.05
    # the max angle converges to pi/2: departure at arccos(-xi)
    assert abs(fl["theta_leave"][-1] % (2 * np.pi) - np.pi / 2) < 0.05 or \
        abs(fl["theta_leave"][-1] % (2 * np.pi) - 3 * np.pi / 2) < 0.05


def test_table2_from_runs():
    xs = flip_sequence(14)
    for k in range(0, 13):
        x = 0.5 * (xs[k] + xs[k + 1]) if k else -0.3
        extra = 50 if k % 2 else 0
        tr = run(float(x), max_flips=k // 2 + extra + 5, t_end=2e4)
        states = cord_state(np.concatenate([[x], tr.flips["xi_after"]]))
        assert states[0] == k
        if k % 2 == 0:
            assert tr.flips["xi_after"].size == k // 2  # N = [k/2], then oscillation forever
            assert states[-1] == 0 and tr.stats["stop_reason"] == "t_end"
        else:
            n1 = int(np.argmax(states == 1))
            assert n1 == k // 2  # [k/2] flips to reach state 1, then flipping on
            assert tr.flips["xi_after"].size > n1 + 40 and np.all(states[n1:] == 1)
        assert np.all(np.diff(states) == -2) if k % 2 == 0 else np.all(np.diff(states[:n1 + 1]) == -2)


# ------------------------------------------------------------ hard cases

def test_departure_is_tangential_reentry_not_at_departure():
    for x in (1e-14, 1e-10, 1e-6, 0.3):
        fl = run(x).flips
        tau = fl["t_return"][0] - fl["t_leave"][0]
        xb = fl["xi_before"][0]
        assert abs(xb - x) < 1e-15
        assert tau > 0 and tau == pytest.approx(4 * math.sqrt(xb * (1 - xb * xb)), rel=1e-12)


def test_very_short_flight_xi_to_zero():
    fl = run(1e-12).flips
    xb = fl["xi_before"][0]
    assert fl["xi_before"].size == 1 and abs(xb - 1e-12) < 1e-15
    assert fl["t_return"][0] - fl["t_leave"][0] == pytest.approx(4 * math.sqrt(xb), rel=1e-12)


def test_xi_to_one_and_just_above():
    fl = run(1 - 1e-9).flips
    assert fl["xi_before"].size == 1
    assert fl["xi_after"][0] == pytest.approx(float(f_mp(1 - 1e-9)), abs=1e-15)
    sc = Scene(cord="flexible", v0=v0_of(1 + 1e-9), t_end=50, n_samples=501)
    a, b = pendula.simulate(sc), pendula.simulate(sc.replace(cord="rigid"))
    assert a.flips["xi_before"].size == 0 and np.array_equal(a.theta, b.theta) and np.all(a.r == 1)


def test_state_one_ten_thousand_flips():
    sc = Scene(cord="flexible", v0=v0_of(0.2), t_end=1e9, n_samples=2, max_flips=10_000)
    with pytest.warns(RuntimeWarning, match="max_flips"):
        tr = pendula.simulate(sc)
    fl = tr.flips
    assert tr.stats["flips"] == 10_000 and tr.stats["stop_reason"] == "max_flips"
    assert np.all(np.diff(fl["xi_after"]) < 0) and np.all(fl["xi_after"] > 0)
    assert np.max(np.abs(fl["xi_after"] - flip_map(fl["xi_before"]))) < 1e-15
    assert np.array_equal(fl["xi_before"][1:], fl["xi_after"][:-1])
    # f(x) ~ x - 64/3 x^3: x_n ~ (3 / (128 n))^1/2 for large n
    assert fl["xi_after"][-1] == pytest.approx(math.sqrt(3 / (128 * 10_000)), rel=0.05)
    assert math.isnan(tr.theta[-1])


def test_flight_through_the_pivot():
    # v0^2 = (2 + 3^1/2) eps: xi = 3^-1/2, the parabola passes through the pivot
    for eps in (1.0, 9.81):
        sc = Scene(cord="flexible", eps=eps, v0=math.sqrt((2 + math.sqrt(3)) * eps), t_end=10, n_samples=2,
                   max_flips=1)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            tr = pendula.simulate(sc)
        th1 = tr.flips["theta_leave"][0]
        v1 = math.sqrt(eps / math.sqrt(3))
        t_star = tr.flips["t_leave"][0] - math.tan(th1) / v1  # x(t*) = 0 on the parabola
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            pt = pendula.simulate(sc, [t_star])
        assert pt.r[0] < 1e-14


def test_reentry_at_the_bottom():
    sc = Scene(cord="flexible", v0=math.sqrt(3.5), t_end=10, n_samples=2, max_flips=1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        fl = pendula.simulate(sc).flips
    assert abs(math.remainder(fl["theta_return"][0], 2 * math.pi)) < 1e-14


def test_damping_with_flexible_cord():
    sc = Scene(cord="flexible", v0=v0_of(0.777), damping=0.01, t_end=60, n_samples=601, rtol=1e-12, atol=1e-14)
    tr = pendula.simulate(sc)
    fl = tr.flips
    assert tr.method == "dop853" and fl["xi_before"].size >= 1
    # the departure is where the tension vanishes: cos theta1 = -xi with v1^2 = eps xi
    th1 = fl["theta_leave"][0]
    i = np.searchsorted(tr.t, fl["t_leave"][0])
    assert fl["xi_before"][0] < 0.777  # damping lost energy before the first flight
    assert fl["xi_after"][0] == pytest.approx(float(f_mp(fl["xi_before"][0])), abs=1e-9)
    assert math.cos(th1) == pytest.approx(-fl["xi_before"][0], abs=1e-9)
    assert np.all(np.abs(tr.r[: i] - 1) < 1e-15)
    with pytest.raises(ValueError, match="rk4"):
        pendula.simulate(sc.replace(method="rk4", dt=0.01))


def test_no_flight_is_the_rigid_pendulum():
    for extra in ({}, {"damping": 0.05}, {"torque": 0.1, "damping": 0.2}):
        sc = Scene(cord="flexible", v0=1.2, t_end=40, n_samples=401, **extra)
        # the cord integrates its circles by dop853 under 'auto' (its tension event needs the dense
        # output); the rigid scene by the same method gives the same numbers
        a = pendula.simulate(sc)
        b = pendula.simulate(sc.replace(cord="rigid"), method=a.method)
        assert np.array_equal(a.theta, b.theta) and np.array_equal(a.v, b.v)
        assert a.flips["t_leave"].size == 0


def test_restitution_bounces_and_stays_inside():
    sc = Scene(cord="flexible", v0=v0_of(0.5), restitution=0.5, t_end=40, n_samples=4001, max_flips=200,
               min_flight=1e-6)
    tr = pendula.simulate(sc)
    assert np.nanmax(tr.r) <= 1 + 1e-12
    e0 = tr.flips["xi_after"][0]
    assert e0 > flip_map(0.5)  # a springy cord loses less than the inelastic jerk


def test_bad_scene_fields():
    for bad in ({"restitution": 1.0}, {"restitution": -0.1}, {"max_flips": -1}, {"min_flight": -1.0},
                {"max_flips": 1.5}):
        with pytest.raises(ValueError, match=list(bad)[0]):
            Scene(cord="flexible", **bad)
    with pytest.raises(ValueError, match="forward"):
        pendula.simulate(Scene(cord="flexible", v0=1.0), [-1.0, 0.0])


# ------------------------------------------------------------ the compiled path: pendula-run

def test_pendula_run_flexible_cord_matches_python(tmp_path, data_dir):
    import subprocess

    from conftest import venv_bin

    scene = data_dir / "scenes" / "cord_example_0777.nml"
    p = subprocess.run([venv_bin("pendula-run"), str(scene), "-o", str(tmp_path / "c.csv")],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    def numbers(path, cols):
        lines = [ln for ln in path.read_text().splitlines() if ln and ln[0] not in "#tm"]
        return np.array([[float(x) for x in ln.split(",")[cols]] for ln in lines])

    tab = numbers(tmp_path / "c.csv", slice(0, 7))
    log = numbers(tmp_path / "c_flips.csv", slice(1, 9))
    tr = pendula.simulate(Scene.from_file(scene), tab[:, 0])  # at pendula-run's own time grid
    # the same kernel code on both paths: equal to the last bit the CSV keeps (17 digits)
    np.testing.assert_allclose(tab[:, 1], tr.theta, rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(tab[:, 4:7], np.column_stack([tr.x, tr.y, tr.r]), rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(log[:, 5], tr.flips["xi_after"], rtol=1e-15, atol=1e-17)
    assert log.shape[0] == tr.stats["flips"] > 10


def test_pendula_run_damped_flexible_cord_is_the_same_kernel_run(tmp_path, data_dir):
    """The damped cord (the hybrid loop: circle integrated to the tension event) runs whole in
    the kernel for pendula-run and for pendula.simulate alike: equal to the CSV's 17 digits."""
    import subprocess

    from conftest import venv_bin

    scene = data_dir / "scenes" / "cord_damped.nml"
    p = subprocess.run([venv_bin("pendula-run"), str(scene), "-o", str(tmp_path / "d.csv")],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    lines = [ln for ln in (tmp_path / "d.csv").read_text().splitlines() if ln and ln[0] not in "#t"]
    tab = np.array([[float(x) for x in ln.split(",")[:7]] for ln in lines])
    log = [ln.split(",") for ln in (tmp_path / "d_flips.csv").read_text().splitlines() if ln and ln[0].isdigit()]
    tr = pendula.simulate(Scene.from_file(scene), tab[:, 0])
    assert tr.method == "dop853" and tr.stats["flips"] == len(log) >= 1
    np.testing.assert_allclose(tab[:, 1], tr.theta, rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(tab[:, 4:7], np.column_stack([tr.x, tr.y, tr.r]), rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose([float(r[6]) for r in log], tr.flips["xi_after"], rtol=1e-15, atol=1e-17)
    # a fixed-step method cannot locate the tension event: exit 2 naming the field
    bad = tmp_path / "rk4.nml"
    bad.write_text(scene.read_text().replace("&scene", "&scene\n method = 'rk4', dt = 0.01", 1))
    q = subprocess.run([venv_bin("pendula-run"), str(bad), "-o", str(tmp_path / "b.csv")],
                       capture_output=True, text=True)
    assert q.returncode == 2 and "method" in q.stderr and not (tmp_path / "b.csv").exists()


def test_gallery_cord_scenes_run():
    for name in ("cord_example_0777", "cord_through_pivot", "cord_damped"):
        from pendula.cli import gallery_dir

        tr = pendula.simulate(Scene.from_file(gallery_dir() / f"{name}.nml"))
        assert tr.stats["flips"] >= 1 and np.all(np.isfinite(tr.theta)) and np.all(tr.r <= 1 + 1e-15)


def test_damped_state_one_many_flips_no_event_storm():
    # state k = 1 with weak damping: ever smaller flips, each found once, with a bounded step count
    sc = Scene(cord="flexible", v0=v0_of(0.2), damping=1e-4, t_end=6000, n_samples=7)
    tr = pendula.simulate(sc)
    fl = tr.flips
    n = fl["xi_before"].size
    assert n > 100 and tr.stats["stop_reason"] == "t_end"
    assert np.all(np.diff(fl["xi_before"]) < 0) and np.all(fl["xi_after"] < fl["xi_before"])
    assert np.all(fl["t_return"] > fl["t_leave"]) and np.all(fl["t_leave"][1:] > fl["t_return"][:-1])
    assert tr.stats["steps"] / n < 1000  # no collapse of the step near the departures
    # between flips the energy leaks by damping only; at each flip the jerk takes f's share
    np.testing.assert_allclose(fl["xi_after"], flip_map(fl["xi_before"]), rtol=0, atol=1e-9)
    # the end: the energy falls below 0 and the bob oscillates on the circle, taut (r = 1)
    assert fl["xi_after"][-1] < 0.0005 and np.all(tr.r[np.isfinite(tr.r)] <= 1 + 1e-15)


@pytest.mark.parametrize("text, field", [("restitution = 1.0", "restitution"), ("restitution = -0.5", "restitution"),
                                         ("max_flips = -3", "max_flips"), ("min_flight = -1e-3", "min_flight")])
def test_bad_cord_fields_in_both_readers(tmp_path, text, field):
    import subprocess

    from conftest import venv_bin

    body = f"&scene\n cord = 'flexible', v0 = 2.0\n {text}\n/\n"
    with pytest.raises(ValueError, match=field):
        Scene.from_namelist(body)
    f = tmp_path / "bad.nml"
    f.write_text(body)
    p = subprocess.run([venv_bin("pendula-run"), str(f), "-o", str(tmp_path / "o.csv")], capture_output=True,
                       text=True)
    assert p.returncode == 2 and field in p.stderr and not (tmp_path / "o.csv").exists()


def test_restitution_with_damping_integrated_loop_agrees_with_closed_form_at_zero_damping():
    # the integrated path (hybrid loop, cubic re-entry root) against the compiled exact path: the same
    # scene with damping 1e-300 (an effect, so integrated at rtol 1e-12) and 0 (exact)
    base = Scene(cord="flexible", v0=v0_of(0.5), restitution=0.4, min_flight=1e-6, t_end=15, n_samples=151,
                 rtol=1e-12, atol=1e-14)
    a = pendula.simulate(base)
    b = pendula.simulate(base.replace(damping=1e-300))
    assert b.method == "dop853" and a.method == "exact"
    n = min(a.flips["t_leave"].size, b.flips["t_leave"].size)
    assert n >= 3
    # integrated departures agree with the closed form to the integrator's tolerance
    np.testing.assert_allclose(b.flips["t_return"][:n], a.flips["t_return"][:n], rtol=0, atol=1e-8)
    np.testing.assert_allclose(b.flips["xi_after"][:n], a.flips["xi_after"][:n], rtol=0, atol=1e-8)
    assert np.nanmax(b.r) <= 1 + 1e-12


# ------------------------------------------------------------ argument checks

def test_cord_state_with_no_terms_names_nmax():
    with pytest.raises(ValueError, match="nmax"):
        cord_state(0.5, nmax=0)
    with pytest.raises(ValueError, match="nmax"):
        cord_state(0.5, nmax=2.5)


def test_flip_sequence_beyond_its_limit_is_refused():
    with pytest.raises(ValueError, match="n must be between 0 and"):
        flip_sequence(2 ** 40)

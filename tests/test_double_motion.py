"""The double pendulum integrated: path, energy error, flip-time map, Lyapunov spectrum.

References, all independent of pendula's kernel:

* the path: SciPy's solve_ivp (DOP853, rtol = atol = 1e-13) on Lagrange's
  equations in (theta, omega), written here from the Lagrangian (a mass-matrix
  solve each step), not from pendula's canonical form;
* small amplitude: the exact normal modes omega^2 = (2 -+ sqrt 2) g/l and the
  general 2x2 eigenproblem (scipy.linalg.eigh) for other masses and lengths;
* the flip time: solve_ivp with a terminal event abs(theta_i) = pi;
* the Jacobian of Hamilton's equations: central differences of the kernel's
  right-hand side checked against the Lagrangian right-hand side.
"""

import math

import numpy as np
import pytest
import scipy.linalg
from scipy.integrate import solve_ivp

import pendula

CASES = {
    "equal_point_masses": dict(),
    "unequal_point_masses": dict(m1=0.7, m2=1.9, l1=1.3, l2=0.6, g=9.81),
    "compound_rods": dict(m1=2.0, m2=0.5, l1=0.8, l2=1.1, rods=True),
    "damped_point_masses": dict(m1=1.2, m2=0.8, l1=1.0, l2=1.5, damping=[0.3, 0.1]),
}


def _coefficients(m1=1.0, m2=1.0, l1=1.0, l2=1.0, g=1.0, rods=False, damping=0.0):
    """a, b, c of T = (a w1^2 + c w2^2)/2 + b cos(d) w1 w2, gA, gB of V, the damping: from the Lagrangian."""
    k = np.broadcast_to(np.asarray(damping, float), (2,))
    if rods:   # uniform rods: I = m l^2 / 3 about an end, centre of mass at l/2
        a, b, c = (m1 / 3 + m2) * l1 ** 2, m2 * l1 * l2 / 2, m2 * l2 ** 2 / 3
        ga, gb = g * (m1 / 2 + m2) * l1, g * m2 * l2 / 2
    else:
        a, b, c = (m1 + m2) * l1 ** 2, m2 * l1 * l2, m2 * l2 ** 2
        ga, gb = g * (m1 + m2) * l1, g * m2 * l2
    return a, b, c, ga, gb, k


def _lagrange_rhs(kw):
    a, b, c, ga, gb, k = _coefficients(**kw)

    def rhs(t, y):
        th1, th2, w1, w2 = y
        d = th1 - th2
        m = np.array([[a, b * math.cos(d)], [b * math.cos(d), c]])
        r = np.array([-b * math.sin(d) * w2 ** 2 - ga * math.sin(th1) - k[0] * w1,
                      b * math.sin(d) * w1 ** 2 - gb * math.sin(th2) - k[1] * w2])
        return [w1, w2, *np.linalg.solve(m, r)]
    return rhs


def _energy(kw, th1, th2, w1, w2):
    a, b, c, ga, gb, _ = _coefficients(**kw)
    return (0.5 * (a * w1 ** 2 + c * w2 ** 2) + b * np.cos(th1 - th2) * w1 * w2
            + ga * (1 - np.cos(th1)) + gb * (1 - np.cos(th2)))


@pytest.mark.parametrize("case", sorted(CASES))
def test_path_against_scipy_on_random_states(case):
    # the span is short (t = 4) because the motion is chaotic: differences of 1e-13 grow by e^(lambda t);
    # both codes run at 1e-13 (gauss6 with 1000 steps per fast normal period: local error ~ (2 pi / 1000)^7),
    # so agreement to 1e-9 (relative to the state's size) tests the equations and the integration, not the chaos
    kw = CASES[case]
    dp = pendula.DoublePendulum(**kw)
    rng = np.random.default_rng(20261204)
    t = np.linspace(0.0, 4.0, 9)
    methods = ["dop853"] if "damping" in kw else ["dop853", "gauss6"]
    for _ in range(4):
        y0 = np.concatenate([rng.uniform(-math.pi, math.pi, 2), rng.uniform(-1.5, 1.5, 2)])
        ref = solve_ivp(_lagrange_rhs(kw), (0, t[-1]), y0, method="DOP853", rtol=1e-13, atol=1e-13, t_eval=t).y
        for method in methods:
            run = dp.simulate(t, *y0, method=method, rtol=1e-13, atol=1e-13,
                              dt=t[1] / math.ceil(t[1] / (float(dp.modes().period[1]) / 1000)))
            got = np.stack([run.theta1, run.theta2, run.omega1, run.omega2])
            err = np.max(np.abs(got - ref) / (1 + np.abs(ref)))
            assert err < 1e-9, (case, method, y0, err)
            want_e = _energy(kw, *ref)
            assert np.max(np.abs(run.energy.values - want_e)) < 1e-9 * (1 + abs(want_e[0]))


def _energy_drift(dp, swings, step, th1, th2, nout):
    """The run's relative energy error and the largest abs(E - E0) over its first and its second half."""
    period = float(dp.modes().period[0])
    t = np.linspace(0.0, swings * period, nout)
    run = dp.simulate(t, th1, th2, dt=t[1] / math.ceil(t[1] / step))
    assert run.attrs["method"] == "gauss6"
    err = np.abs(run.energy_error.values)
    return run.attrs["energy_error_max"], err[: nout // 2].max(), err[nout // 2:].max()


@pytest.mark.parametrize("case", ["equal_point_masses", "compound_rods"])
def test_energy_error_small_on_a_chaotic_orbit(case):
    # a chaotic orbit over 1e3 slow swings at step 0.02 (h omega ~ 0.1 at the fastest): the symplectic
    # method's error is that of its modified energy, O(h^6), below 1e-8 of the energy with both arms up
    # (measured 2.4e-9 for equal point masses); it wanders with the region the orbit visits
    rel, _, _ = _energy_drift(pendula.DoublePendulum(**CASES[case]), 1e3, 0.02, 2.0, 2.5, 2001)
    assert rel < 1e-8


@pytest.mark.parametrize("case", ["equal_point_masses", "compound_rods"])
def test_energy_bounded_without_drift_on_a_regular_orbit(case):
    # a large regular swing from (0.8, 1.0) over 2e3 slow swings at step 0.1: the energy error
    # oscillates; its largest value over the second half equals that over the first to 50 %
    # (a drift linear in t would double it); measured 1.63e-10 both halves for equal point masses
    rel, first, second = _energy_drift(pendula.DoublePendulum(**CASES[case]), 2e3, 0.1, 0.8, 1.0, 4001)
    assert rel < 1e-8
    assert second <= 1.5 * first + 1e-15, (first, second)


def test_energy_bounded_over_1e5_swings():
    # the same over 1e5 slow swings (t = 8.2e5, 8.2e6 steps)
    rel, first, second = _energy_drift(pendula.DoublePendulum(), 1e5, 0.1, 0.8, 1.0, 100001)
    assert rel < 1e-8
    assert second <= 1.5 * first + 1e-15, (first, second)


def test_dop853_energy_error_is_reported():
    # the error-controlled pair drifts; the reported error is E(t) - E(0), checked against the Lagrangian energy
    kw = CASES["unequal_point_masses"]
    run = pendula.DoublePendulum(**kw).simulate(np.linspace(0, 50, 11), 1.0, -2.0, method="dop853", rtol=1e-6,
                                                atol=1e-6)
    e = _energy(kw, run.theta1.values, run.theta2.values, run.omega1.values, run.omega2.values)
    assert np.allclose(run.energy_error.values, e - e[0], rtol=0, atol=1e-9 * abs(e[0]))
    assert run.attrs["energy_error_max"] > 1e-12


@pytest.mark.parametrize("case", ["equal_point_masses", "unequal_point_masses", "compound_rods"])
def test_small_amplitude_frequencies_equal_normal_modes(case):
    # amplitude 1e-5 along a mode shape: theta1(t) = eps cos(omega t) up to the nonlinear shift O(eps^2)
    # (phase error ~ 1e-10 x omega t) and the integration error (gauss6, 200 steps per fast period)
    kw = CASES[case]
    dp = pendula.DoublePendulum(**kw)
    a, b, c, ga, gb, _ = _coefficients(**kw)
    w2, vec = scipy.linalg.eigh(np.diag([ga, gb]), np.array([[a, b], [b, c]]))
    nm = dp.modes()
    assert np.allclose(nm.omega, np.sqrt(w2), rtol=1e-13, atol=0)
    for k in range(2):
        eps = 1e-5
        v = vec[:, k] / vec[0, k]
        period = 2 * math.pi / math.sqrt(w2[k])
        nstep = 200
        t = np.arange(0, 10 * nstep + 1) * (period / nstep)
        run = dp.simulate(t, eps * v[0], eps * v[1], method="gauss6", dt=period / nstep)
        want = eps * np.cos(math.sqrt(w2[k]) * t)
        assert np.max(np.abs(run.theta1.values - want)) < 1e-5 * eps
        assert np.max(np.abs(run.theta2.values - v[1] * want)) < 1e-5 * eps * max(1, abs(v[1]))


@pytest.mark.parametrize("case", sorted(CASES))
def test_jacobian_against_central_differences(case):
    # the variational equations' Jacobian in closed form against central differences (step 1e-6:
    # error ~ 1e-12 truncation + 1e-10 rounding, relative to the entries' scale)
    dp = pendula.DoublePendulum(**CASES[case])
    rng = np.random.default_rng(7)
    for _ in range(5):
        y = np.concatenate([rng.uniform(-3, 3, 2), rng.uniform(-2, 2, 2)])
        jac = dp._state(y[:, None])[3]
        fd = np.zeros((4, 4))
        for j in range(4):
            e = np.zeros(4)
            e[j] = 1e-6
            fd[:, j] = (dp._state((y + e)[:, None])[2][:, 0] - dp._state((y - e)[:, None])[2][:, 0]) / 2e-6
        assert np.max(np.abs(jac - fd)) < 1e-8 * (1 + np.max(np.abs(jac)))


def test_flip_map_forbidden_pixels_skipped_and_times_against_scipy():
    dp = pendula.DoublePendulum()
    th1 = np.linspace(-3.0, 3.0, 13)
    th2 = np.linspace(-3.0, 3.0, 11)
    fm = dp.flip_map(th1, th2, t_max=30.0, rtol=1e-11, atol=1e-11)
    g1, g2 = np.meshgrid(th1, th2, indexing="ij")
    assert np.array_equal(fm.forbidden, 2 * np.cos(g1) + np.cos(g2) > 1)
    assert np.all(np.isinf(fm.time[fm.forbidden]))
    assert not fm.unresolved[fm.forbidden].any()
    kw = CASES["equal_point_masses"]
    rng = np.random.default_rng(3)
    cand = np.argwhere(~fm.forbidden & ~fm.unresolved)
    for i, j in cand[rng.choice(len(cand), 6, replace=False)]:
        ev = [lambda t, y, j=jj: abs(y[j]) - math.pi for jj in (0, 1)]
        for e in ev:
            e.terminal = True
        sol = solve_ivp(_lagrange_rhs(kw), (0, 30.0), [th1[i], th2[j], 0, 0], method="DOP853", rtol=1e-13,
                        atol=1e-13, events=ev)
        hits = [te[0] for te in sol.t_events if te.size]
        want = min(hits) if hits else math.inf
        if math.isinf(want):
            assert math.isinf(fm.time[i, j])
        else:
            # a resolved pixel agrees with the tighter run to 1e-3; with SciPy at 1e-13 to 1e-6 relative
            assert abs(fm.time[i, j] - want) < 1e-6 * want, (th1[i], th2[j], fm.time[i, j], want)


def test_flip_map_same_on_any_thread_count_and_loose_tolerance_marks_more_unresolved():
    dp = pendula.DoublePendulum()
    th = np.linspace(-3.1, 3.1, 12)
    one = dp.flip_map(th, th, t_max=40.0, threads=1)
    two = dp.flip_map(th, th, t_max=40.0, threads=2)
    assert np.array_equal(one.time, two.time) and np.array_equal(one.check, two.check)
    loose = dp.flip_map(th, th, t_max=40.0, rtol=1e-3, atol=1e-3)
    assert loose.unresolved.sum() > one.unresolved.sum()
    fin = np.isfinite(loose.time) & np.isfinite(loose.check)
    a, b = np.where(fin, loose.time, 1.0), np.where(fin, loose.check, 1.0)
    moved = np.abs(a - b) > 1e-3 * np.maximum(a, b)
    assert np.array_equal(loose.unresolved[fin], moved[fin])


def test_lyapunov_sum_zero_and_pairs_conservative():
    # Hamiltonian: the exponents come in pairs +-lambda.  With the symplectic frame (the last Gram-Schmidt
    # vector J times the first) and a symplectic method the pairing holds to rounding at any span: the
    # linearised step has determinant one and maps symplectic complements to symplectic complements;
    # DOP853 (not symplectic) pairs to its tolerance
    dp = pendula.DoublePendulum()
    for ls in (dp.lyapunov(2.0, 2.5, t=500.0), dp.lyapunov(2.0, 2.5, t=500.0, method="gauss4"),
               pendula.DoublePendulum(**CASES["compound_rods"]).lyapunov(2.0, 2.5, t=300.0)):
        assert abs(ls.total) < 1e-13
        assert np.max(np.abs(ls.pairing)) < 1e-13, ls
        assert ls.exponents[0] > 0.2             # a chaotic orbit (measured 0.46 to 0.50)
    ls = dp.lyapunov(2.0, 2.5, t=200.0, method="dop853", dt=0.1, rtol=1e-11, atol=1e-11)
    assert np.max(np.abs(ls.pairing)) < 1e-9 and ls.exponents[0] > 0.2
    # a regular orbit: the exponents tend to zero as 1/t (measured 2.4e-3 at t = 2000)
    reg = dp.lyapunov(0.8, 1.0, t=1000.0)
    assert np.max(np.abs(reg.exponents)) < 0.02


def test_lyapunov_damped_sum_is_the_mean_contraction():
    # the sum of the exponents is the time average of the divergence of Hamilton's equations,
    # -(k1 dw1/dp1 + k2 dw2/dp2), evaluated here along SciPy's path from the Lagrangian form
    kw = CASES["damped_point_masses"]
    dp = pendula.DoublePendulum(**kw)
    a, b, c, _, _, k = _coefficients(**kw)
    ls = dp.lyapunov(2.0, 1.0, t=40.0, dt=0.1, every=1)
    sol = solve_ivp(_lagrange_rhs(kw), (0, 40.0), [2.0, 1.0, 0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-12,
                    dense_output=True)
    tt = np.linspace(0, 40.0, 40001)
    d = sol.sol(tt)[0] - sol.sol(tt)[1]
    det = a * c - (b * np.cos(d)) ** 2
    div = -(k[0] * c + k[1] * a) / det
    want = np.trapezoid(div, tt) / 40.0
    assert abs(ls.total - want) < 1e-6 * abs(want)


def test_bad_input_names_the_field():
    with pytest.raises(ValueError, match="l1"):
        pendula.DoublePendulum(l1=-1.0)
    with pytest.raises(ValueError, match="m2"):
        pendula.DoublePendulum(m2=0.0)
    with pytest.raises(ValueError, match="damping"):
        pendula.DoublePendulum(damping=[0.1, -0.2])
    with pytest.raises(ValueError, match="theta1"):
        pendula.DoublePendulum().flip_map([4.0], [0.0])
    with pytest.raises(ValueError, match="t must be ascending"):
        pendula.DoublePendulum().simulate([1.0, 0.5], 1.0)
    with pytest.raises(ValueError, match="step grid"):
        pendula.DoublePendulum().simulate([0.0, 0.013], 1.0, method="gauss6", dt=0.01)


def test_poincare_section_against_scipy_events_and_on_the_energy_shell():
    # SciPy's DOP853 at 1e-13 with the event theta1 = 0 (increasing) from the same start: the first crossings'
    # (theta2, p2) agree to 1e-8 (regular orbit, gauss6 with 400 steps per fast period); every point's energy
    # equals the asked energy to 1e-9 of the energy with both arms up
    kw = CASES["unequal_point_masses"]
    dp = pendula.DoublePendulum(**kw)
    a, b, c, ga, gb, _ = _coefficients(**kw)
    e = 0.3 * float(dp.energy(math.pi, math.pi))
    dt = float(dp.modes().period[1]) / 400
    sec = dp.poincare(e, [0.3, -0.2], [0.1, 0.0], t_max=30.0, dt=dt)
    assert np.all(sec["count"].values >= 5)
    assert np.nanmax(sec.energy_error.values) < 1e-9
    for k, (t20, p20) in enumerate([(0.3, 0.1), (-0.2, 0.0)]):
        # the start: p1 from the energy, then (w1, w2) = M^-1 p
        cd = math.cos(t20)
        det = a * c - (b * cd) ** 2
        v = gb * (1 - math.cos(t20))
        p1 = (b * cd * p20 + math.sqrt((b * cd * p20) ** 2 - c * (a * p20 ** 2 - 2 * det * (e - v)))) / c
        w = np.linalg.solve([[a, b * cd], [b * cd, c]], [p1, p20])
        assert abs(_energy(kw, 0.0, t20, *w) - e) < 1e-12 * e

        def up(t, y):
            return y[0]      # theta1 = 0 from below (the orbit librates: below the flip energy of arm 1)
        up.direction = 1
        sol = solve_ivp(_lagrange_rhs(kw), (0, 30.0), [0.0, t20, *w], method="DOP853", rtol=1e-13, atol=1e-13,
                        events=up)
        ys = sol.y_events[0]
        ys = ys[sol.t_events[0] > 0][:5]     # drop the start itself
        p2 = b * np.cos(ys[:, 0] - ys[:, 1]) * ys[:, 2] + c * ys[:, 3]
        t2 = np.mod(ys[:, 1] + np.pi, 2 * np.pi) - np.pi
        assert np.max(np.abs(sec.theta2.values[k, :5] - t2)) < 1e-8
        assert np.max(np.abs(sec.p2.values[k, :5] - p2)) < 1e-8


def test_poincare_start_outside_the_energy_shell_is_nan_with_a_warning():
    dp = pendula.DoublePendulum()
    with pytest.warns(RuntimeWarning, match="outside the energy shell"):
        sec = dp.poincare(0.1, [0.0, 3.0], [0.0, 0.0], t_max=20.0)
    assert sec["count"].values[0] > 0 and sec["count"].values[1] == 0
    assert np.all(np.isnan(sec.theta2.values[1]))


def test_flip_map_plot_marks_the_three_kinds_of_pixel():
    pytest.importorskip("matplotlib")
    import matplotlib
    matplotlib.use("Agg")
    import pendula.plot
    th = np.linspace(-3, 3, 9)
    fm = pendula.DoublePendulum().flip_map(th, th, t_max=10.0)
    ax = pendula.plot.flip_map(fm)
    assert [t.get_text() for t in ax.get_legend().get_texts()] == [
        "cannot flip (energy)", "no flip by t = 10", "unresolved"]
    with pytest.raises(TypeError, match="fm"):
        pendula.plot.flip_map(fm.time)


def test_empty_times_and_axes_are_refused_by_name():
    dp = pendula.DoublePendulum()
    with pytest.raises(ValueError, match="t must hold"):
        dp.simulate([], 1.0)
    with pytest.raises(ValueError, match="theta1 must hold"):
        dp.flip_map([], [0.5])
    with pytest.raises(ValueError, match="t must hold"):
        pendula.FoucaultPendulum(latitude=10.0).simulate([], 0.1)


def test_animation_of_the_double_pendulum_draws_both_arms(tmp_path):
    PIL = pytest.importorskip("PIL.Image")
    pytest.importorskip("matplotlib")
    import pendula.plot
    from pendula.animation import _double_arms
    dp = pendula.DoublePendulum(l1=1.0, l2=0.5)
    run = dp.simulate(np.linspace(0.0, 2.0, 9), theta1=1.0, theta2=-0.5)
    x1, y1, x2, y2 = _double_arms(run)
    assert np.allclose(np.hypot(x1, y1), 1.0) and np.allclose(np.hypot(x2 - x1, y2 - y1), 0.5)
    with PIL.open(pendula.plot.animate(run, tmp_path / "double.gif", dpi=20)) as im:
        assert im.n_frames == 9
    with pytest.raises(TypeError, match="tr"):
        pendula.plot.animate(run.drop_vars("theta2"), tmp_path / "x.gif")



@pytest.mark.parametrize("rods, w2", [(False, (2 - math.sqrt(2), 2 + math.sqrt(2))),
                                      (True, (3 - 6 / math.sqrt(7), 3 + 6 / math.sqrt(7)))])
def test_spectra_of_the_angles_show_each_normal_mode_at_its_closed_form_frequency(rods, w2):
    """pendula.spectra (FFTW) of theta1(t) and theta2(t) from DoublePendulum.simulate, swung at amplitude
    1e-4 along one mode for 32 periods of the closed-form frequency (omega^2 = (2 -+ sqrt 2) g/l for equal
    point masses, 3 -+ 6/sqrt 7 for equal uniform rods), sampled 2048 times.  A line at exactly that
    frequency falls on bin 32 and leaks nothing; one off by a relative d leaks a share growing as d^2 of
    its power into the other bins (measured here: 4.7e-11 at d = 1e-7, 3.4e-10 at 3e-7).  Asked: the other
    bins hold less than 1e-11 of each angle's power (measured 1.2e-12: the frequency within about 5e-8;
    the amplitude's own shift is of order 1e-9); the two angles' amplitude ratio is the mode shape's
    theta2/theta1 within 1e-4 (+-sqrt 2 for point masses)."""
    dp = pendula.DoublePendulum(rods=rods)
    nm = dp.modes()
    for k in range(2):
        om = math.sqrt(w2[k])
        t = np.arange(2048) * (32 * 2 * math.pi / om / 2048)
        q = 1e-4 * nm.shapes[:, k]
        run = dp.simulate(t, theta1=float(q[0]), theta2=float(q[1]))
        s1, s2 = pendula.spectra(run.time, [run.theta1, run.theta2])
        for s in (s1, s2):
            assert int(np.argmax(s.power[1:])) + 1 == 32
            assert 1 - s.power[32] / s.power[1:].sum() < 1e-11
        assert s2.amplitude[32] / s1.amplitude[32] == pytest.approx(abs(nm.shapes[1, k]), rel=1e-4)
    if not rods:
        assert abs(nm.shapes[1, 0]) == pytest.approx(math.sqrt(2), rel=1e-12)

"""Friction, drag, the vibrating pivot: against references written from the equations alone.

- friction: mpmath (30 digits) solves the energy balance eps (cos b - cos a) + (tau - mu s)(b - a) = 0
  for each turning point and integrates dtheta / sqrt(2 K) between them (tanh-sinh, which takes
  the inverse square-root ends); pendula's exact turning points (GSL) and its integrated path
  (DOP853 stopped and restarted at v = 0 events) must meet them within 1e-9 (the brief's bound;
  both are near 1e-13, the integrator's rtol);
- drag: scipy's DOP853 at rtol 1e-13, restarted where v changes sign with the sign of the drag term
  fixed on each stretch, to t = 40: states within 1e-9 (a few hundred times the tolerance);
- pivot: the inverted state theta = pi of the vibrating pivot is a periodic orbit; its Floquet
  multipliers from scipy's monodromy of the linear equation phi'' = (eps - a W^2 cos W t) phi
  (- beta phi') at rtol 1e-13 within 1e-8; its stability threshold in a tends to Kapitza's
  sqrt(2 eps) / W as W grows.
"""

import math

import mpmath as mp
import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pendula

TIGHT = dict(rtol=1e-13, atol=1e-15)


# ---------------------------------------------------------------- friction: the energy balance in mpmath

def _mp_turning_points(eps, tau, mu, theta0, v0, n):
    """The first n turning points (t, theta) and whether it sticks, from the energy balance alone."""
    mp.mp.dps = 30
    eps, tau, mu = mp.mpf(eps), mp.mpf(tau), mp.mpf(mu)
    out = []
    t, th, va = mp.mpf(0), mp.mpf(theta0), mp.mpf(v0)
    if va == 0:
        out.append((t, th))
    while len(out) < n:
        if va == 0:
            f = tau - eps * mp.sin(th)
            if abs(f) <= mu:
                return out, True
            s = mp.sign(f)
        else:
            s = mp.sign(va)
        a = th

        def K(x):
            return va**2 / 2 + eps * (mp.cos(x) - mp.cos(a)) + (tau - mu * s) * (x - a)
        # bracket the first zero of K along s (K > 0 just after a), then bisect-and-polish
        step, x = mp.pi / 256, a
        while True:
            x2 = x + s * step
            if K(x2) <= 0 and x2 != a:
                break
            x = x2
        lo, hi = (x, x2) if s > 0 else (x2, x)
        b = mp.findroot(K, (lo, hi), solver="anderson") if va != 0 or abs(x - a) > 0 else None
        if va == 0 and abs(x - a) == 0:
            b = mp.findroot(lambda y: K(y) / (y - a), (lo, hi), solver="anderson")
        # (abs: tanh-sinh samples within 1e-30 of the ends, where K rounds to either sign)
        dt = mp.quad(lambda y: 1 / mp.sqrt(2 * abs(K(y))), sorted([a, b]))
        t, th, va = t + dt, b, mp.mpf(0)
        out.append((t, th))
    return out, None


@pytest.mark.parametrize("theta0, v0, mu, tau, eps", [
    (1.0, 0.0, 0.05, 0.0, 1.0),        # released from rest: the amplitude falls by 2 mu / eps a swing
    (2.5, 0.0, 0.13, 0.0, 2.0),        # large amplitude, another eps
    (0.3, 1.2, 0.04, 0.0, 1.0),        # started with a speed
    (1.2, 0.0, 0.08, 0.03, 1.0),       # with a torque: the stick is off-centre
])
def test_friction_turning_points_against_mpmath(theta0, v0, mu, tau, eps):
    sc = pendula.Scene(theta0=theta0, v0=v0, friction=mu, torque=tau, eps=eps, **TIGHT)
    tp = pendula.friction_turning_points(sc)
    ref, stuck = _mp_turning_points(eps, tau, mu, theta0, v0, len(tp.angles) + 1)
    assert stuck is True and tp.stuck
    assert len(ref) == len(tp.angles)
    t_ref = np.array([float(r[0]) for r in ref])
    th_ref = np.array([float(r[1]) for r in ref])
    assert np.max(np.abs(tp.angles - th_ref)) < 1e-9
    assert np.max(np.abs(tp.times - t_ref)) < 1e-9
    assert tp.stick_angle == tp.angles[-1] and abs(tp.stick_time - t_ref[-1]) < 1e-9
    # the integrated path (v = 0 events, restarts, the stick) through the same points
    tr = pendula.simulate(sc, np.append(t_ref, t_ref[-1] + 50.0))
    assert np.max(np.abs(tr.theta[:-1] - th_ref)) < 1e-9
    assert np.max(np.abs(tr.v[:-1])) < 1e-9
    assert tr.theta[-1] == tr.theta[-2] and tr.v[-1] == 0.0       # stuck for good


def test_friction_random_amplitudes_against_mpmath():
    rng = np.random.default_rng(31)
    for theta0, mu in zip(rng.uniform(0.2, 2.8, 3), rng.uniform(0.03, 0.3, 3)):
        tp = pendula.friction_turning_points(pendula.Scene(theta0=theta0, friction=mu))
        ref, _ = _mp_turning_points(1.0, 0.0, mu, theta0, 0.0, len(tp.angles))
        assert np.max(np.abs(tp.angles - [float(r[1]) for r in ref])) < 1e-9
        assert np.max(np.abs(tp.times - [float(r[0]) for r in ref])) < 1e-9


def test_friction_small_amplitude_decays_linearly():
    # small angles: each half swing loses 2 mu / eps of amplitude (the linear oscillator with Coulomb friction)
    tp = pendula.friction_turning_points(pendula.Scene(theta0=0.01, friction=1e-4))
    amps = np.abs(tp.angles)
    assert np.allclose(-np.diff(amps)[:10], 2e-4, rtol=2e-4)


def test_friction_stuck_from_rest_inside_the_cone():
    # |eps sin theta0| <= mu: the bob never moves
    tr = pendula.simulate(pendula.Scene(theta0=0.05, friction=0.1), [0.0, 1.0, 100.0])
    assert np.all(tr.theta == 0.05) and np.all(tr.v == 0.0)


def test_friction_release_by_the_drive():
    # at rest at theta = 0 with F = -A sin(W t): stuck while A |sin W t| <= mu, then slides with s = -1
    mu, A, W = 0.1, 0.2, 1.0
    sc = pendula.Scene(friction=mu, drive_amplitude=A, drive_frequency=W, drive_phase=math.pi / 2, **TIGHT)
    tr_ = math.asin(mu / A) / W
    t = np.array([0.5 * tr_, tr_ * (1 - 1e-9), tr_ + 0.3, tr_ + 0.6])
    out = pendula.simulate(sc, t)
    assert out.theta[0] == 0.0 and out.theta[1] == 0.0 and out.v[1] == 0.0

    def rhs(tt, y):   # the slide after the release: s = -1 (friction +mu) until v returns to 0
        return [y[1], -math.sin(y[0]) + A * math.cos(W * tt + math.pi / 2) + mu]
    ref = solve_ivp(rhs, (tr_, tr_ + 0.6), [0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-15,
                    t_eval=t[2:])
    assert np.all(ref.y[1] < 0)
    assert np.max(np.abs(out.theta[2:] - ref.y[0])) < 1e-9 and np.max(np.abs(out.v[2:] - ref.y[1])) < 1e-9


# ---------------------------------------------------------------- drag: scipy restarted at v = 0

def _scipy_drag(eps, gamma, beta, A, W, theta0, v0, t_eval):
    def turn(tt, y, s):
        return y[1]
    turn.terminal = True
    t0, y0, out = 0.0, np.array([theta0, v0]), {}
    while t0 < t_eval[-1]:
        s = math.copysign(1.0, y0[1]) if y0[1] != 0 else math.copysign(
            1.0, -eps * math.sin(y0[0]) + A * math.cos(W * t0))

        def rhs(tt, y):
            return [y[1], -eps * math.sin(y[0]) - gamma * s * y[1] ** 2 - beta * y[1] + A * math.cos(W * tt)]
        ev = lambda tt, y: y[1]   # noqa: E731
        ev.terminal, ev.direction = True, -s
        want = t_eval[t_eval > t0]
        sol = solve_ivp(rhs, (t0, t_eval[-1]), y0, method="DOP853", rtol=1e-13, atol=1e-15, events=ev,
                        dense_output=True)
        tend = sol.t_events[0][0] if sol.status == 1 else t_eval[-1]
        for tt in want[want <= tend]:
            out[tt] = sol.sol(tt)
        t0, y0 = (tend, np.array([sol.y_events[0][0][0], 0.0])) if sol.status == 1 else (t_eval[-1], None)
    return np.array([out[tt] for tt in t_eval[1:]]).T


@pytest.mark.parametrize("gamma, beta, A, W", [(0.1, 0.0, 0.0, 0.0), (0.3, 0.05, 0.0, 0.0), (0.2, 0.0, 0.5, 0.8)])
def test_drag_against_scipy_restarted(gamma, beta, A, W):
    t = np.linspace(0.0, 40.0, 81)
    sc = pendula.Scene(theta0=2.0, v0=0.5, drag=gamma, damping=beta, drive_amplitude=A, drive_frequency=W,
                       **TIGHT)
    tr = pendula.simulate(sc, t)
    ref = _scipy_drag(1.0, gamma, beta, A, W, 2.0, 0.5, t)
    assert np.max(np.abs(tr.theta[1:] - ref[0])) < 1e-9
    assert np.max(np.abs(tr.v[1:] - ref[1])) < 1e-9


def test_drag_decays_slower_than_linear_damping_at_small_speed():
    # quadratic drag vanishes faster than linear damping as v -> 0: the late amplitude is larger
    t = np.linspace(0, 200, 2001)
    q = pendula.simulate(pendula.Scene(theta0=1.0, drag=0.5), t)
    lin = pendula.simulate(pendula.Scene(theta0=1.0, damping=0.05), t)
    assert np.max(np.abs(q.theta[-200:])) > np.max(np.abs(lin.theta[-200:]))


# ---------------------------------------------------------------- the vibrating pivot

def _scipy_inverted_monodromy(eps, a, W, beta=0.0):
    T = 2 * math.pi / W

    def rhs(t, y):
        k = eps - a * W * W * math.cos(W * t)
        return [y[1], k * y[0] - beta * y[1], y[3], k * y[2] - beta * y[3]]
    sol = solve_ivp(rhs, (0, T), [1.0, 0.0, 0.0, 1.0], method="DOP853", rtol=1e-13, atol=1e-15)
    y = sol.y[:, -1]
    return np.array([[y[0], y[2]], [y[1], y[3]]])


@pytest.mark.parametrize("a, W, beta", [(0.1, 20.0, 0.0), (0.05, 20.0, 0.0), (0.2, 10.0, 0.1), (0.3, 3.0, 0.0)])
def test_pivot_inverted_multipliers_against_scipy(a, W, beta):
    sc = pendula.Scene(pivot_amplitude=a, pivot_frequency=W, damping=beta)
    po = pendula.periodic_orbit(sc, guess=(math.pi, 0.0), rtol=1e-13, atol=1e-15)
    assert abs(abs(po.theta) - math.pi) < 1e-12 and abs(po.v) < 1e-12
    ref = np.linalg.eigvals(_scipy_inverted_monodromy(1.0, a, W, beta))
    assert abs(np.max(np.abs(po.multipliers)) - np.max(np.abs(ref))) < 1e-8


def _threshold(W, multipliers):
    """The least a at which the inverted state is stable (bisection on max |mu| - 1)."""
    lo, hi = 0.5 * math.sqrt(2) / W, 2.0 * math.sqrt(2) / W
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if np.max(np.abs(multipliers(mid))) > 1 + 1e-9:
            lo = mid
        else:
            hi = mid
    return hi


def test_pivot_kapitza_threshold():
    # the threshold from pendula's multipliers agrees with scipy's, and a W / sqrt(2 eps) -> 1 as W grows
    ratios = []
    for W in (20.0, 40.0):
        mine = _threshold(W, lambda a: pendula.periodic_orbit(
            pendula.Scene(pivot_amplitude=a, pivot_frequency=W), guess=(math.pi, 0.0)).multipliers)
        ref = _threshold(W, lambda a: np.linalg.eigvals(_scipy_inverted_monodromy(1.0, a, W)))
        assert abs(mine - ref) < 1e-7 * ref
        ratios.append(mine * W / math.sqrt(2))
    assert abs(ratios[1] - 1) < abs(ratios[0] - 1) and abs(ratios[1] - 1) < 0.01


def test_pivot_inverted_pendulum_stands_up():
    tr = pendula.simulate(pendula.Scene(theta0=math.pi - 0.2, pivot_amplitude=0.1, pivot_frequency=30.0,
                                        t_end=30.0, n_samples=3001))
    assert np.min(tr.theta) > math.pi - 0.5 and np.max(tr.theta) < math.pi + 0.5
    tr0 = pendula.simulate(pendula.Scene(theta0=math.pi - 0.2, t_end=30.0, n_samples=3001))
    assert np.min(tr0.theta) < 0.5            # without the pivot it falls


# ---------------------------------------------------------------- fields, combinations, bad input

@pytest.mark.parametrize("field, value", [("friction", -0.1), ("drag", -1.0), ("friction", math.nan),
                                          ("drag", math.inf)])
def test_negative_or_nonfinite_coefficient_names_field(field, value):
    with pytest.raises(pendula.SceneError, match=f"'{field}'"):
        pendula.Scene(**{field: value})


def test_pivot_without_frequency_is_an_error():
    with pytest.raises(pendula.SceneError, match="'pivot_frequency'.*'pivot_amplitude'"):
        pendula.Scene(pivot_amplitude=0.1)


@pytest.mark.parametrize("effect", [dict(friction=0.1), dict(drag=0.1), dict(pivot_amplitude=0.1, pivot_frequency=5)])
@pytest.mark.parametrize("model, field", [(dict(cord="flexible"), "cord"), (dict(guide="cycloid"), "guide")])
def test_effect_with_refused_model_names_both_fields(effect, model, field):
    name = next(iter(effect))
    with pytest.raises(pendula.SceneError, match=f"fields '{name}' and '{field}'"):
        pendula.Scene(**effect, **model)


@pytest.mark.parametrize("effect", [dict(friction=0.1), dict(drag=0.1)])
@pytest.mark.parametrize("method", ["rk4", "verlet", "gsl-rk8pd", "vern9", "exact"])
def test_switching_effect_with_method_without_events_names_both_fields(effect, method):
    name = next(iter(effect))
    with pytest.raises(pendula.SceneError, match=f"fields '{name}' and 'method'"):
        pendula.Scene(**effect, method=method, dt=0.01)


@pytest.mark.parametrize("effect", [dict(friction=0.1), dict(drag=0.1), dict(pivot_amplitude=0.1, pivot_frequency=5)])
def test_effects_work_with_every_field_model(effect):
    # non-uniform gravity, damping, torque and drive all combine with each new effect
    for extra in (dict(gravity="linear", gravity_gradient=0.2), dict(damping=0.1, torque=0.05),
                  dict(drive_amplitude=0.3, drive_frequency=0.7)):
        tr = pendula.simulate(pendula.Scene(theta0=1.0, t_end=10.0, n_samples=11, **effect, **extra))
        assert np.all(np.isfinite(tr.theta)) and tr.method == "dop853"


def test_pivot_exact_method_refused():
    with pytest.raises(pendula.SceneError, match="'method'"):
        pendula.Scene(pivot_amplitude=0.1, pivot_frequency=5.0, method="exact")


def test_effect_fields_round_trip_through_namelist():
    s = pendula.Scene(friction=0.1, drag=0.2, pivot_amplitude=0.05, pivot_frequency=12.0)
    assert pendula.Scene.from_namelist(s.to_namelist()) == s
    assert s.effects == ("friction", "drag", "pivot")


def test_models_list_the_new_effects():
    rigid = next(m for m in pendula.models() if m.name == "rigid")
    for e in ("friction", "drag", "pivot", "force"):
        assert e in rigid.effects


def test_friction_turning_points_refuses_other_effects():
    with pytest.raises(ValueError, match="'friction'"):
        pendula.friction_turning_points(pendula.Scene(theta0=1.0))
    with pytest.raises(ValueError, match="'drive'|'damping'"):
        pendula.friction_turning_points(pendula.Scene(theta0=1.0, friction=0.1, damping=0.1))


def test_backward_times_refused_with_friction():
    with pytest.raises(ValueError, match="forward"):
        pendula.simulate(pendula.Scene(theta0=1.0, friction=0.1), [-1.0, 0.0])


def test_events_refused_with_friction():
    with pytest.raises(NotImplementedError, match="'friction'"):
        pendula.find_events(pendula.Scene(v0=1.5, friction=0.05, t_end=50), "turning")


def test_drag_turning_events_match_the_simulated_zeros_of_v():
    # find_events integrates drag's -gamma v|v| directly (a C1 force, error-controlled): the turning
    # times agree with simulate's located switches (its path has v = 0 there)
    sc = pendula.Scene(v0=1.5, drag=0.05, t_end=30, **TIGHT)
    ev = pendula.find_events(sc, "turning")
    tr = pendula.simulate(sc, ev.t)
    assert np.max(np.abs(tr.v)) < 1e-9


@pytest.mark.parametrize("effect", [dict(friction=0.1), dict(pivot_amplitude=0.1, pivot_frequency=20.0)])
def test_equilibria_refused_with_friction_or_pivot(effect):
    with pytest.raises(ValueError, match="friction|pivot"):
        pendula.equilibria(pendula.Scene(**effect))


@pytest.mark.parametrize("effect", [dict(friction=0.1), dict(drag=0.1), dict(pivot_amplitude=0.1, pivot_frequency=20.0)])
def test_numerical_period_refused_with_effects(effect):
    with pytest.raises(ValueError, match="conservative"):
        pendula.numerical_period(pendula.Scene(theta0=1.0, **effect))


def test_pivot_lyapunov_sweep_against_scipy_monodromy():
    # the damped inverted state is an attractor above Kapitza's threshold: the exponents a lyapunov
    # sweep measures from near the top are log|mu| / T of scipy's monodromy of the linearisation
    sc = pendula.Scene(damping=0.5, pivot_amplitude=0.15, pivot_frequency=20.0, theta0=math.pi - 0.05)
    ly = pendula.sweep(sc, over={"pivot_amplitude": [0.15, 0.3]}, measure="lyapunov", transient=40.0,
                       t_max=200.0, rtol=1e-12, atol=1e-14)
    for k, a in enumerate((0.15, 0.3)):
        mu = np.sort(np.abs(np.linalg.eigvals(_scipy_inverted_monodromy(1.0, a, 20.0, 0.5))))[::-1]
        ref = np.log(mu) / (2 * math.pi / 20.0)
        assert ly.status.values[k] == 0
        # the sweep's own convergence estimate bounds its error (block averages over the window)
        assert abs(ly.lyapunov.values[k] - ref[0]) < 3 * ly.lyapunov_err.values[k] + 1e-6
        assert abs(ly.lyapunov.values[k] + ly.lyapunov2.values[k] + 0.5) < 1e-8      # Liouville: -beta


def test_pivot_attractor_map_finds_the_top_and_the_bottom():
    sc = pendula.Scene(damping=0.5, pivot_amplitude=0.15, pivot_frequency=20.0)
    am = pendula.attractor_map(sc, {"theta0": np.linspace(-np.pi, np.pi, 8), "v0": np.linspace(-2, 2, 8)},
                               transient=100.0, samples=8)
    assert sorted(a.kind for a in am.attractors) == ["periodic", "periodic"]
    tops = sorted(abs(float(a.theta[0])) for a in am.attractors)
    assert tops[0] < 1e-8 and abs(tops[1] - math.pi) < 1e-8


def test_pivot_poincare_without_drive_samples_the_pivot_period():
    sc = pendula.Scene(damping=0.5, pivot_amplitude=0.15, pivot_frequency=20.0, theta0=0.3)
    pc = pendula.sweep(sc, over={"v0": [0.0]}, measure="poincare", transient=0.0, samples=3, rtol=1e-12,
                       atol=1e-14)
    ref = pendula.simulate(sc.replace(rtol=1e-12, atol=1e-14), [2 * math.pi / 20.0 * k for k in (1, 2, 3)])
    assert np.max(np.abs(pc.theta.values[0] - ref.theta)) < 1e-9


@pytest.mark.parametrize("method, knobs", [("dop853", TIGHT), ("dopri5", dict(rtol=1e-13, atol=1e-15)),
                                           ("dprkn6", dict(rtol=1e-12, atol=1e-14)), ("vern9", TIGHT),
                                           ("gsl-rk8pd", TIGHT), ("yoshida8", dict(dt=0.002)),
                                           ("gauss6", dict(dt=0.002)), ("verlet", dict(dt=1e-4))])
def test_pivot_path_with_every_integrator_against_scipy(method, knobs):
    # the pivot's force aW^2 cos(W t) sin(theta) reaches every integrator (the splittings' kick too)
    a, W = 0.1, 20.0
    t = np.linspace(0.0, 10.0, 11)
    ref = solve_ivp(lambda tt, y: [y[1], -(1.0 - a * W * W * math.cos(W * tt)) * math.sin(y[0])], (0, 10.0),
                    [3.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-15, t_eval=t)
    tr = pendula.simulate(pendula.Scene(theta0=3.0, pivot_amplitude=a, pivot_frequency=W, method=method, **knobs), t)
    tol = 1e-5 if method == "verlet" else 1e-9     # verlet: second order, dt = 1e-4
    assert np.max(np.abs(tr.theta - ref.y[0])) < tol


# ---------------------------------------------------------------- the effects in sweeps

def _wrap(th):
    return (np.asarray(th) + math.pi) % (2 * math.pi) - math.pi


def test_friction_final_well_sweep_matches_simulate():
    # an undriven pendulum with dry friction stops in a well; the sweep's energy test decides which,
    # and the simulated path (stretches between v = 0 events) sticks in the same one
    sc = pendula.Scene(friction=0.05)
    v0s = [1.0, 2.3, 3.0, 4.5]
    fw = pendula.sweep(sc, over={"v0": v0s}, measure="final_well", t_max=2000.0)
    assert np.all(fw.status.values == 0)
    for v0, well in zip(v0s, fw.well.values):
        tr = pendula.simulate(sc.replace(v0=v0), [0.0, 500.0])
        assert tr.v[-1] == 0.0 and round(tr.theta[-1] / (2 * math.pi)) == well


@pytest.mark.parametrize("effect", [dict(drag=0.3), dict(friction=0.05), dict(pivot_amplitude=0.05, pivot_frequency=0.7)])
def test_poincare_sweep_with_effect_matches_simulate(effect):
    W = 0.7
    # damped: a periodic attractor, where the two runs' rounding does not grow
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.2, drive_frequency=W, rtol=1e-12, atol=1e-14, **effect)
    pc = pendula.sweep(sc, over={"v0": [0.0]}, measure="poincare", transient=10.0, samples=3)
    n_tr = math.ceil(10.0 * W / (2 * math.pi))
    ref = pendula.simulate(sc, [2 * math.pi / W * k for k in range(n_tr + 1, n_tr + 4)])
    assert pc.status.values[0] == 0
    assert np.max(np.abs(pc.theta.values[0] - _wrap(ref.theta))) < 1e-8
    assert np.max(np.abs(pc.v.values[0] - ref.v)) < 1e-8


def test_lyapunov_sweep_with_friction_refused_by_name():
    # dry friction sticks: no variational flow (the capability table refuses it at the door, where every point
    # used to say 'does not apply')
    with pytest.raises(ValueError, match="friction"):
        pendula.sweep(pendula.Scene(friction=0.05, drive_amplitude=1.2, drive_frequency=0.7), over={"v0": [0.0]},
                      measure="lyapunov", transient=10.0, t_max=50.0)

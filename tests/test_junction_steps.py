"""Shapiro steps: a phase-locked driven orbit reports <v> = n Omega exactly.

The reference is scipy's DOP853 at tight tolerance written from the equation
alone: the stroboscopic map (one drive period) of
theta'' = -sin(theta) - beta theta' + tau + A cos(Omega t), iterated until it
repeats; the phase advance over one period is then 2 pi n to 1e-10, and the
step number n is read from it.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pendula
from pendula import Scene

AC = dict(damping=1.0, drive_amplitude=1.0, drive_frequency=1.0)


def scipy_phase_advance(tau, beta=1.0, amp=1.0, omega=1.0, periods=60):
    """The phase advance over the last drive period and the change of the
    stroboscopic state (reduced mod 2 pi) over it, from rest."""
    period = 2 * math.pi / omega

    def rhs(t, y):
        return [y[1], -math.sin(y[0]) - beta * y[1] + tau + amp * math.cos(omega * t)]
    ts = period * np.arange(periods + 1)
    sol = solve_ivp(rhs, (0.0, ts[-1]), [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-13, t_eval=ts)
    th, v = sol.y
    adv = th[-1] - th[-2]
    n = round(adv / (2 * math.pi))
    return n, abs(adv - 2 * math.pi * n), abs(v[-1] - v[-2])


@pytest.mark.parametrize("tau, n", [(0.3, 0), (0.6, 0), (1.1, 1), (1.3, 1)])
def test_locked_bias_reports_n_omega_exactly(tau, n):
    n_ref, miss, dv = scipy_phase_advance(tau)
    assert n_ref == n and miss < 1e-10 and dv < 1e-10     # scipy: the map repeats with a 2 pi n advance
    ds = pendula.sweep(Scene(**AC), over={"torque": [tau]}, measure="mean_velocity", transient=100.0,
                       t_max=200.0)
    assert ds.mean_velocity.item() == n * 1.0            # exactly, not to a tolerance
    assert ds.step.item() == n and int(ds.status.item()) == 6
    assert ds.mean_velocity_err.item() == 0.0


def test_iv_curve_staircase_over_torque_0_to_2():
    tau = np.linspace(0.0, 2.0, 41)
    r = pendula.iv_curve(Scene(**AC), tau, "up", transient=100.0, t_max=200.0)
    up = r.sel(direction="up")
    for t, n in [(0.3, 0), (0.6, 0), (1.1, 1), (1.3, 1)]:
        assert up.mean_velocity.sel(torque=t, method="nearest").item() == n
        assert up.step.sel(torque=t, method="nearest").item() == n
    locked = up.status.values == 6
    # every locked point sits on p Omega / q exactly; every other has no step
    np.testing.assert_array_equal(up.mean_velocity.values[locked], up.step.values[locked] * 1.0)
    assert np.all(np.isnan(up.step.values[~locked]))
    assert "locked" in up.status.attrs["flag_meanings"]


def test_unlocked_error_bar_covers_a_long_average():
    # off the steps: the windowed mean over 200 time units against scipy's over 400 periods;
    # the error bar must cover the difference (up to the long average's own windowing)
    omega, beta, amp = 1.0, 1.0, 1.0
    for tau in (1.6, 1.9):
        ds = pendula.sweep(Scene(**AC), over={"torque": [tau]}, measure="mean_velocity", transient=100.0,
                           t_max=200.0)
        assert int(ds.status.item()) == 0 and math.isnan(ds.step.item())
        period = 2 * math.pi / omega

        def rhs(t, y):
            return [y[1], -math.sin(y[0]) - beta * y[1] + tau + amp * math.cos(omega * t)]
        n = 400
        ts = period * np.arange(n + 1)
        sol = solve_ivp(rhs, (0.0, ts[-1]), [0.0, 0.0], method="DOP853", rtol=1e-8, atol=1e-10, t_eval=ts)
        th = sol.y[0]
        k0 = 100
        ref = (th[-1] - th[k0]) / (ts[-1] - ts[k0])
        resid = th[k0:] - ref * ts[k0:]
        ref_err = (resid.max() - resid.min()) / (ts[-1] - ts[k0])
        assert abs(ds.mean_velocity.item() - ref) <= ds.mean_velocity_err.item() + ref_err, tau


def test_driven_window_is_whole_periods():
    # Omega = 0.7: a window of 100 is rounded up to 16 whole periods (an even number);
    # the point from rest at tau = 1.9 runs unlocked, its <v> that of scipy over those periods
    omega = 0.7
    s = Scene(damping=1.0, drive_amplitude=1.0, drive_frequency=omega)
    tau = 1.9
    ds = pendula.sweep(s, over={"torque": [tau]}, measure="mean_velocity", transient=30.0, t_max=100.0)
    assert int(ds.status.item()) == 0        # not locked: the window's average
    period = 2 * math.pi / omega
    k_tr, k_avg = math.ceil(30.0 / period), 2 * math.ceil(100.0 / period / 2)

    def rhs(t, y):
        return [y[1], -math.sin(y[0]) - 1.0 * y[1] + tau + 1.0 * math.cos(omega * t)]
    ts = period * np.array([k_tr, k_tr + k_avg])
    sol = solve_ivp(rhs, (0.0, ts[-1]), [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-13, t_eval=ts)
    ref = (sol.y[0][1] - sol.y[0][0]) / (ts[1] - ts[0])
    assert abs(ds.mean_velocity.item() - ref) < 1e-7 * abs(ref)     # same definition, both at tight tolerance


def test_step_width_follows_the_bessel_law_in_the_overdamped_limit():
    # beta = 10 (beta_c = 0.01), Omega_c = Omega beta = 10, a / Omega_c = 1.2: the n = 1 step spans
    # 2 |J_1(1.2)| = 0.996 I_c in the limit (Barone and Paterno, section 11.2).  Its edges by bisection to
    # 0.005 I_c; on the step: locked with step 1, or (too slow near an edge to lock within 240 periods) a
    # mean velocity within 1e-3 Omega of Omega.  Allowed: 5 % for the finite Omega_c and beta_c, plus the
    # bisection's resolution.
    from scipy.special import jv
    beta, omega, x = 10.0, 1.0, 1.2
    period = 2 * math.pi / omega
    s = Scene(damping=beta, drive_amplitude=x * omega * beta, drive_frequency=omega, rtol=1e-9, atol=1e-11)

    def on_step(bias):
        ds = pendula.sweep(s, over={"torque": [bias]}, measure="mean_velocity", transient=200 * period,
                           t_max=40 * period)
        if int(ds.status.item()) == 6:
            return ds.step.item() == 1
        return abs(ds.mean_velocity.item() / omega - 1) < 1e-3

    centre = math.hypot(beta * omega, 1.0)   # the ohmic bias of <v> = Omega, near the step's middle
    assert on_step(centre)
    edges = []
    for far in (centre - 1.5, centre + 1.5):
        assert not on_step(far)
        inside, outside = centre, far
        while abs(outside - inside) > 0.005:
            mid = 0.5 * (inside + outside)
            inside, outside = (mid, outside) if on_step(mid) else (inside, mid)
        edges.append(inside)
    width = edges[1] - edges[0]
    assert abs(width - 2 * abs(jv(1, x))) < 0.05 * 2 * abs(jv(1, x)) + 0.01, width


def test_pendula_run_sweep_csv_has_the_step_and_locked_status(tmp_path):
    from conftest import pendula_run_table
    tab, scene = pendula_run_table(tmp_path, " damping = 1.0\n drive_amplitude = 1.0\n drive_frequency = 1.0\n"
                                   " grid = 'torque'\n grid1 = 0.3, 1.1, 1.6\n measure = 'mean_velocity'\n"
                                   " sweep_transient = 100\n sweep_t_max = 200")
    lines = (tmp_path / "o.csv").read_text().splitlines()
    assert lines[1] == "torque,mean_velocity,mean_velocity_err,step,status" and "6 locked" in lines[0]
    ds = pendula.sweep(Scene.from_file(scene))
    np.testing.assert_array_equal(tab[:, 1], ds.mean_velocity.values)
    np.testing.assert_array_equal(tab[:, 3], ds.step.values)
    assert tab[:, 4].tolist() == [6, 6, 0] and tab[:2, 1].tolist() == [0.0, 1.0]

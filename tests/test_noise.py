"""Thermal noise: the Langevin integrator (BAOAB) against equilibrium
statistical mechanics and Kramers' rate, its weak order, and its
reproducibility.

References, all independent of pendula: the Gibbs density
exp(-(v^2/2 - cos theta) / T) gives <v^2> = T and <cos theta> =
I1(1/T) / I0(1/T) (scipy.special); Kramers' moderate-to-strong damping rate
of the tilted washboard (Kramers 1940; Hanggi, Talkner and Borkovec, Rev.
Mod. Phys. 62 (1990) section IV) written here from the formula.  Every run is
seeded: a test gives the same numbers on every run and cannot flake; the
statistical allowances (5 standard errors from batch means, p ~ 6e-7 for a
normal mean) say how unlikely a failure of a correct integrator would be.
"""

import math
import os
import signal
import subprocess
import sys

import numpy as np
import pytest
from scipy.special import i0e, i1e

import pendula
from pendula import Scene, SceneError, _kernel


def _moments(temp, h, nbatch, time_per_batch, beta=2.0, seed=7, index=0):
    nper = int(round(time_per_batch / h))
    v2, cth, st = _kernel.langevin_moments_v(1.0, beta, 0.0, temp, seed, index, h, int(round(100 / h)), nbatch,
                                             nper, np.zeros(1, np.int32))
    assert st == 0
    return v2, cth


@pytest.mark.parametrize("temp", [0.25, 1.0])
def test_equilibrium_v2_and_cos_theta_match_gibbs(temp):
    # h = 0.05: BAOAB's bias in <v^2> is about -T (h w)^2 / 4 <= 6.3e-4 T (w <= sqrt(eps) = 1); measured
    # below (test_weak_order_two_in_dt) as -0.19 h^2 at T = 0.5, inside this allowance
    h = 0.05
    v2, cth = _moments(temp, h, 40, 5000.0)
    se_v2 = v2.std(ddof=1) / math.sqrt(v2.size)
    se_c = cth.std(ddof=1) / math.sqrt(cth.size)
    bias = temp * h * h / 4
    assert abs(v2.mean() - temp) < 5 * se_v2 + bias, (v2.mean(), se_v2)
    exact_cos = i1e(1 / temp) / i0e(1 / temp)        # the ratio of exponentially scaled Bessel functions
    assert abs(cth.mean() - exact_cos) < 5 * se_c + bias, (cth.mean(), exact_cos, se_c)
    assert se_v2 < 0.01 * temp                        # the run is long enough to say something


def test_weak_order_two_in_dt():
    # the bias of <v^2> at three steps h, 2^(1/2) h, 2 h: slope 2 on a log-log fit (weak order 2);
    # each bias is >= 30 standard errors of its run, so the fitted order is known to about +-0.1
    temp = 0.5
    hs = np.array([0.4, 0.4 * math.sqrt(2), 0.8])
    bias, se = [], []
    for h in hs:
        v2, _ = _moments(temp, h, 50, 20000.0)
        bias.append(abs(v2.mean() / temp - 1))
        se.append(v2.std(ddof=1) / math.sqrt(v2.size) / temp)
    bias, se = np.array(bias), np.array(se)
    assert np.all(bias > 10 * se)
    order = np.polyfit(np.log(hs), np.log(bias), 1)[0]
    assert abs(order - 2.0) < 0.3, order


def _kramers(i, beta, temp):
    s = math.sqrt(1 - i * i)
    wa = math.sqrt(s)                       # attempt and barrier frequency of the washboard: (1 - i^2)^(1/4)
    du = 2 * (s - i * math.acos(i))
    a = beta / (2 * wa)
    return wa / (2 * math.pi) * (math.sqrt(1 + a * a) - a) * math.exp(-du / temp), du


def test_escape_rate_matches_kramers_moderate_damping():
    # tilt 0.5, beta = 1 (alpha = beta / 2 w_b = 0.54: moderate damping, beta S_b / T ~ 30, far from the
    # energy-diffusion regime), barrier dU / T = 5.  The mean first-passage time to one radian beyond the
    # barrier's top, over 300 escapes (standard error 1/sqrt(300) = 5.8 %); Kramers' formula is
    # asymptotic in T / dU: an allowance of 10 % for the finite barrier, on top of 4 standard errors.
    tau, beta = 0.5, 1.0
    _, du = _kramers(tau, beta, 1.0)
    temp = du / 5.0
    rate, _ = _kramers(tau, beta, temp)
    top = math.pi - math.asin(tau)
    n = 300
    times, st = _kernel.langevin_escape_v(1.0, beta, tau, temp, 11, 0.1, top + 1.0, 1e7, n, 0,
                                          np.zeros(1, np.int32))
    assert st == 0 and np.all(np.isfinite(times))
    measured = 1.0 / times.mean()
    assert abs(measured / rate - 1) < 4 / math.sqrt(n) + 0.10, measured / rate


def test_same_seed_same_path_bit_for_bit_other_seed_other_path():
    s = Scene(damping=0.5, torque=0.3, noise=0.2, seed=42, t_end=50.0, n_samples=101)
    a, b = pendula.simulate(s), pendula.simulate(s)
    np.testing.assert_array_equal(a.theta, b.theta)
    np.testing.assert_array_equal(a.v, b.v)
    c = pendula.simulate(s.replace(seed=43))
    assert not np.array_equal(a.theta, c.theta)
    assert a.method == "langevin"


def test_noisy_sweep_same_on_any_thread_count_and_chunking(tmp_path):
    s = Scene(damping=0.5, noise=0.3, seed=9)
    over = {"torque": np.linspace(0.0, 1.2, 7), "drive_amplitude": [0.0, 0.3]}
    kw = dict(measure="mean_velocity", transient=10.0, t_max=40.0)
    one = pendula.sweep(s, over=over, threads=1, **kw)
    two = pendula.sweep(s, over=over, threads=2, chunk_points=4, **kw)
    stored = pendula.sweep(s, over=over, threads=2, chunk_points=6, out=tmp_path, **kw)
    again = pendula.sweep(s, over=over, threads=1, chunk_points=6, out=tmp_path, **kw)   # a resume: all done
    for ds in (two, stored, again):
        np.testing.assert_array_equal(one.mean_velocity.values, ds.mean_velocity.values)
        np.testing.assert_array_equal(one.mean_velocity_err.values, ds.mean_velocity_err.values)
    assert np.all(one.status.values == 0)


def test_escape_and_switching_samples_same_on_any_thread_count():
    z = np.zeros(1, np.int32)
    a, _ = _kernel.langevin_escape_v(1.0, 1.0, 0.5, 0.15, 3, 0.1, 3.0, 1e6, 6, 1, z)
    b, _ = _kernel.langevin_escape_v(1.0, 1.0, 0.5, 0.15, 3, 0.1, 3.0, 1e6, 6, 2, z)
    np.testing.assert_array_equal(a, b)
    a, _ = _kernel.junction_switching_v(1.0, 0.2, 1e-3, 3, 0.1, 1.2, 6, 1, z)
    b, _ = _kernel.junction_switching_v(1.0, 0.2, 1e-3, 3, 0.1, 1.2, 6, 2, z)
    np.testing.assert_array_equal(a, b)


def test_same_path_in_a_fresh_process_with_other_threads():
    code = ("import pendula, numpy as np; s = pendula.Scene(damping=0.5, noise=0.2, seed=5, t_end=20.0, "
            "n_samples=5); print(repr(pendula.simulate(s).theta.tolist()))")
    env = dict(os.environ, OMP_NUM_THREADS="1")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True,
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL)).stdout
    here = pendula.simulate(Scene(damping=0.5, noise=0.2, seed=5, t_end=20.0, n_samples=5)).theta.tolist()
    assert eval(out) == here


def test_noise_without_damping_is_refused_naming_noise():
    with pytest.raises(SceneError, match="'noise'.*damping"):
        Scene(noise=0.1)


def test_negative_or_infinite_noise_is_refused():
    for bad in (-0.1, math.inf, math.nan):
        with pytest.raises(SceneError, match="'noise'"):
            Scene(damping=0.1, noise=bad)


def test_bad_seed_is_refused():
    for bad in (-1, 1.5, 2 ** 54):
        with pytest.raises(SceneError, match="'seed'"):
            Scene(damping=0.1, noise=0.1, seed=bad)


def test_noise_with_another_method_or_model_is_refused():
    with pytest.raises(SceneError, match="'method'"):
        Scene(damping=0.1, noise=0.1, method="rk4", dt=0.01)
    with pytest.raises(SceneError, match="'noise'.*rigid"):
        Scene(damping=0.1, noise=0.1, guide="cycloid")


def test_noise_runs_forward_only():
    with pytest.raises(ValueError, match="forward"):
        pendula.simulate(Scene(damping=0.1, noise=0.1), [-1.0, 0.0])


def test_noise_scene_file_round_trip():
    s = Scene(damping=0.3, noise=0.05, seed=123456789)
    back = Scene.from_namelist(s.to_namelist())
    assert back == s and back.effects == ("damping", "noise")


def test_noisy_sweep_of_a_deterministic_measure_is_refused():
    with pytest.raises(ValueError, match="'noise'"):
        pendula.sweep(Scene(damping=0.3, noise=0.1), over={"v0": [0.0]}, measure="final_well")


def test_pendula_run_noisy_sweep_equals_pendula_sweep_bit_for_bit(tmp_path):
    from conftest import pendula_run_table, venv_bin
    body = (" damping = 0.5\n noise = 0.3\n seed = 17\n grid = 'torque', 'v0'\n grid1_range = 0.0, 1.2, 5\n"
            " grid2 = 0.0, 1.0\n measure = 'mean_velocity'\n sweep_transient = 10\n sweep_t_max = 40")
    tab, scene = pendula_run_table(tmp_path, body)
    ds = pendula.sweep(Scene.from_file(scene), chunk_points=3)
    np.testing.assert_array_equal(tab[:, 2], ds.mean_velocity.values.ravel())
    np.testing.assert_array_equal(tab[:, 3], ds.mean_velocity_err.values.ravel())
    bad = tmp_path / "bad.nml"
    bad.write_text(scene.read_text().replace("'mean_velocity'", "'final_well'"))
    r = subprocess.run([venv_bin("pendula-run"), str(bad), "-o", str(tmp_path / "b.csv")], capture_output=True,
                       text=True)
    assert r.returncode != 0 and "'noise'" in r.stderr


def test_underdamped_escape_rate_matches_buttiker_harris_landauer_not_kramers():
    # beta = 0.05 (Q = omega_a / beta = 18.6), tilt 0.5, dU / T = 5: beta S_b / T ~ 2, the turnover to
    # energy diffusion, where Kramers' moderate-damping factor (0.97) overestimates the rate and the
    # Buttiker-Harris-Landauer interpolation a = 4 / (sqrt(1 + Q T / 1.8 dU) + 1)^2 (Phys. Rev. B 28 (1983)
    # 1268) holds to about 20 % (its accuracy as an interpolation), on top of 4 standard errors of 300 escapes
    tau, beta = 0.5, 0.05
    s = math.sqrt(1 - tau * tau)
    wa = math.sqrt(s)
    du = 2 * (s - tau * math.acos(tau))
    temp = du / 5.0
    tst = wa / (2 * math.pi) * math.exp(-du / temp)
    q = wa / beta
    bhl = 4 / (math.sqrt(1 + q * temp / (1.8 * du)) + 1) ** 2 * tst
    kramers, _ = _kramers(tau, beta, temp)
    n = 300
    times, st = _kernel.langevin_escape_v(1.0, beta, tau, temp, 11, 0.1, math.pi - math.asin(tau) + 1.0, 1e7, n,
                                          0, np.zeros(1, np.int32))
    assert st == 0 and np.all(np.isfinite(times))
    measured = 1.0 / times.mean()
    assert abs(measured / bhl - 1) < 4 / math.sqrt(n) + 0.20, measured / bhl
    assert measured / kramers < 1 - 4 / math.sqrt(n), measured / kramers
    # the library's rate is the same law
    j = pendula.Junction(1e-6, 1.0, 1e-12, temperature=1.0)
    jj = pendula.Junction(1e-6, 1 / (j.plasma_frequency * 1e-12 * beta), 1e-12,
                          temperature=temp * j.josephson_energy / 1.380649e-23)
    assert jj.escape_rate(tau * 1e-6, "underdamped") / jj.plasma_frequency == pytest.approx(bhl, rel=1e-9)
    assert jj.escape_rate(tau * 1e-6) / jj.plasma_frequency == pytest.approx(kramers, rel=1e-9)

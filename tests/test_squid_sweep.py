"""The dc SQUID's voltage map over (flux, bias) and its V-Φ curve on both branches.

Each grid point of DCSquid.sweep starts from rest and is measured as the V-Φ curve's first point (which is
checked against SciPy in test_squid_dynamics.py); here: the map is that measurement, bit for bit, on any
thread count and after a resume; against SciPy's RCSJ integration from rest and the overdamped closed form
(make test-full); and the hysteretic V-Φ branches against the static critical current and SciPy.
"""

import math
import pathlib
import shutil

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from pendula.junction import FLUX_QUANTUM
from pendula.squid import DCSquid

I0 = 10e-6
R = 10.0


def _squid(beta_l, beta_c, temperature=0.0):
    c = beta_c * FLUX_QUANTUM / (2 * math.pi * I0 * R * R)
    return DCSquid(I0, R, c, beta_l * FLUX_QUANTUM / (2 * I0), temperature=temperature)


def _scipy_mean_velocity(beta_l, beta_c, flux, bias, y0=None, t_skip=400.0, span=400.0):
    """⟨s'⟩ of the two RCSJ junctions (time 1/ω_c), β_c φ_k'' + φ_k' + sin φ_k = i/2 ∓ j, from y0 (default
    rest at ±πΦ/Φ₀); the period from SciPy's events at s = 2πk after t_skip.  Returns (⟨s'⟩, final state)."""
    k = 1 / (math.pi * beta_l)

    def rhs(t, y):
        p1, p2, v1, v2 = y
        j = k * (p1 - p2 - 2 * math.pi * flux)
        return [v1, v2, (bias / 2 - j - v1 - math.sin(p1)) / beta_c, (bias / 2 + j - v2 - math.sin(p2)) / beta_c]

    y0 = [math.pi * flux, -math.pi * flux, 0.0, 0.0] if y0 is None else y0
    a = solve_ivp(rhs, (0, t_skip), y0, method="DOP853", rtol=1e-12, atol=1e-14)
    b = solve_ivp(rhs, (t_skip, t_skip + span), a.y[:, -1], method="DOP853", rtol=1e-12, atol=1e-14,
                  events=lambda t, y: math.sin((y[0] + y[1]) / 4))
    te = b.t_events[0]
    assert te.size > 10
    return 2 * math.pi * (te.size - 1) / (te[-1] - te[0])


def test_sweep_points_are_the_v_phi_measurement_from_rest():
    """β_L = 1, β_c = 0.5: every point of the map is the V-Φ curve's measurement at that flux from rest
    (the same numbers exactly), on one thread and on two."""
    sq = _squid(1.0, 0.5)
    fl, cur = [0.1, 0.35], [1.0 * I0, 2.5 * I0]
    m1 = sq.sweep(fl, cur, threads=1)
    m2 = sq.sweep(fl, cur, threads=2)
    assert m1.voltage.dims == ("flux", "current") and m1.voltage.attrs["units"] == "V"
    assert m1.bias.values.tolist() == [1.0, 2.5]
    assert np.array_equal(m1.voltage.values, m2.voltage.values)
    for r, c in ((0, 0), (1, 1)):
        one = sq.v_phi_curve(cur[c], [fl[r]])
        assert float(m1.voltage[r, c]) == float(one.voltage[0])
        assert float(m1.voltage_err[r, c]) == float(one.voltage_err[0])
    assert abs(float(m1.voltage[0, 0])) < 1e-12 * I0 * R       # Ic(0.1) = 1.9 I0: at rest
    assert float(m1.voltage[1, 1]) > 0.5 * I0 * R              # running


def test_noisy_sweep_is_the_same_on_any_thread_count_and_after_a_resume(tmp_path):
    """Seeded noise keyed by grid point: threads 1 and 2, and a Zarr store with one row's completion record
    removed (computed again on the rerun), all give the same numbers; two rows of the same flux draw
    different noise (their points have their own streams)."""
    sq = _squid(1.0, 0.5, temperature=4.2)
    fl, cur = [0.1, 0.1, 0.3], [1.8 * I0, 2.2 * I0]
    kw = dict(paths=3, seed=4, t_max=1e-9)
    a = sq.sweep(fl, cur, threads=1, **kw)
    b = sq.sweep(fl, cur, threads=2, **kw)
    assert np.array_equal(a.voltage.values, b.voltage.values)
    assert a.voltage.values[0, 0] != a.voltage.values[1, 0]
    out = tmp_path / "map"
    c = sq.sweep(fl, cur, out=out, **kw)
    assert np.array_equal(a.voltage.values, c.voltage.values)
    assert c.attrs["seed"] == 4 and c.attrs["method"] == "baoab"
    shutil.rmtree(pathlib.Path(out) / "sweep.zarr" / "commits" / "c000001")
    d = sq.sweep(fl, cur, out=out, **kw)
    assert np.array_equal(a.voltage.values, d.voltage.values)
    with pytest.raises(ValueError, match="out"):
        _squid(1.0, 0.5, temperature=4.2).sweep(fl, cur, out=out, paths=3, seed=5, t_max=1e-9)


def test_bad_arguments_of_the_sweep_are_named(tmp_path):
    sq = _squid(1.0, 0.5)
    with pytest.raises(ValueError, match="fluxes"):
        sq.sweep([], [I0])
    with pytest.raises(ValueError, match="currents"):
        sq.sweep([0.1], [np.nan])
    with pytest.raises(TypeError, match="progress"):
        sq.sweep([0.1], [I0], progress="yes")
    f = tmp_path / "a_file"
    f.write_text("x")
    with pytest.raises(OSError, match="out"):
        sq.sweep([0.1], [I0], out=f)


def test_sweep_from_rest_matches_scipy():
    """β_L = 1, β_c = 0.5, two running points from rest: within pendula's error plus 1e-10 relative."""
    sq = _squid(1.0, 0.5)
    m = sq.sweep([0.35], [2.0 * I0, 2.5 * I0])
    for c, i in enumerate((2.0, 2.5)):
        ref = I0 * R * _scipy_mean_velocity(1.0, 0.5, 0.35, i)
        v, err = float(m.voltage[0, c]), float(m.voltage_err[0, c])
        assert abs(v - ref) <= err + 1e-10 * ref, (i, v, ref, err)


def test_sweep_of_the_overdamped_small_screening_squid_matches_the_closed_form():
    """β_L = β_c = 1e-2: V = (R/2) √(I² − Ic²), Ic = 2I₀ abs(cos πΦ/Φ₀), within 1e-3 relative (the
    corrections are of second order, 1e-4), and zero below Ic."""
    sq = _squid(1e-2, 1e-2)
    m = sq.sweep([0.2, 0.4], [1.0 * I0, 2.2 * I0])
    for r, f in enumerate((0.2, 0.4)):
        ic = 2 * abs(math.cos(math.pi * f))
        for c, i in enumerate((1.0, 2.2)):
            v = float(m.voltage[r, c])
            if i < ic:
                assert abs(v) < 1e-9 * I0 * R
            else:
                ref = 0.5 * I0 * R * math.sqrt(i * i - ic * ic)
                assert abs(v / ref - 1) < 1e-3, (f, i, v, ref)


def test_v_phi_curve_of_a_hysteretic_squid_has_two_branches():
    """β_L = 1, β_c = 4 at I = 1.2 I₀, the flux swept 0 → 1 → 0: where I > Ic(Φ) (0.4 < Φ/Φ₀ < 0.6) both
    branches run; beside that window the branch that arrives running keeps running (its retrapping
    current is below 1.2 I₀) while the other is still at rest: at 0.3 Φ₀ the way up is at rest and the way
    down runs, at 0.7 Φ₀ the reverse."""
    sq = _squid(1.0, 4.0)
    fl = np.linspace(0.0, 1.0, 11)
    r = sq.v_phi_curve(1.2 * I0, fl, direction="both")
    up, down = r.mean_velocity.sel(direction="up").values, r.mean_velocity.sel(direction="down").values
    ic = np.array([sq.critical_current(f) / I0 for f in fl[3:8]])
    above = np.zeros(fl.size, dtype=bool)
    above[3:8] = ic < 1.2
    assert above[3:8].tolist() == [False, False, True, False, False]   # and Ic rises away from Φ₀/2
    assert np.all(up[above] > 0.1) and np.all(down[above] > 0.1)
    assert abs(up[3]) < 1e-9 and down[3] > 0.1
    assert up[7] > 0.1 and abs(down[7]) < 1e-9
    assert np.all(np.abs(up[:4]) < 1e-9) and np.all(np.abs(down[8:]) < 1e-9)
    single = sq.v_phi_curve(1.2 * I0, fl, direction="down")
    assert "direction" not in single.voltage.dims and str(single.direction.values) == "down"


def test_v_phi_running_branch_of_a_hysteretic_squid_matches_scipy():
    """The way down at 0.3 Φ₀ (I = 1.2 I₀ below Ic = 1.52 I₀, running): SciPy started from rest at
    2.5 I₀ (running), then at 1.2 I₀ from that state, within pendula's error plus 1e-9 relative."""
    sq = _squid(1.0, 4.0)
    fl = np.linspace(0.0, 1.0, 11)
    r = sq.v_phi_curve(1.2 * I0, fl, direction="both")
    v, err = float(r.voltage.sel(direction="down")[3]), float(r.voltage_err.sel(direction="down")[3])
    k = 1 / math.pi

    def rhs(t, y, bias):
        p1, p2, v1, v2 = y
        j = k * (p1 - p2 - 2 * math.pi * 0.3)
        return [v1, v2, (bias / 2 - j - v1 - math.sin(p1)) / 4.0, (bias / 2 + j - v2 - math.sin(p2)) / 4.0]

    a = solve_ivp(rhs, (0, 400), [0.3 * math.pi, -0.3 * math.pi, 0, 0], args=(2.5,), method="DOP853",
                  rtol=1e-12, atol=1e-14)
    ref = I0 * R * _scipy_mean_velocity(1.0, 4.0, 0.3, 1.2, y0=a.y[:, -1], t_skip=800.0)
    assert abs(v - ref) <= err + 1e-9 * ref, (v, ref, err)

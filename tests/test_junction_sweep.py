"""Junction.sweep and Junction.steps in laboratory units, and the junction's figures (plot.iv, plot.steps).

References: the conversions written again here from the CODATA constants (h, e, k_B exact) and the
stated formulas (I_rf = sqrt(2 P / Z), P = 1 mW 10^(dBm / 10)); locked points checked against scipy's
DOP853 stroboscopic map written from the equation (the phase advances 2 pi n per rf period).
"""

import json
import math
import pathlib

import matplotlib
import numpy as np
import pytest
from scipy.integrate import solve_ivp

import pendula
import pendula.plot
from pendula import Junction
from pendula.junction import FLUX_QUANTUM

matplotlib.use("Agg")

DATA = pathlib.Path(__file__).resolve().parents[1] / "data" / "junction"

H, E, KB = 6.62607015e-34, 1.602176634e-19, 1.380649e-23
PHI0 = H / (2 * E)


def scipy_advance(beta, tau, amp, omega, periods=300):
    """The phase advance over the last rf period, from rest, and the change of (theta mod 2 pi, v) over it."""
    T = 2 * math.pi / omega
    sol = solve_ivp(lambda t, y: [y[1], -math.sin(y[0]) - beta * y[1] + tau + amp * math.cos(omega * t)],
                    (0.0, periods * T), [0.0, 0.0], method="DOP853", rtol=1e-11, atol=1e-12,
                    t_eval=T * np.array([periods - 1, periods]))
    return sol.y[0, 1] - sol.y[0, 0], abs(sol.y[1, 1] - sol.y[1, 0])


def test_sweep_axes_in_laboratory_units_and_locked_points_against_scipy():
    ic, r, c = 1e-6, 18.0, 1e-12
    j = Junction(ic, r, c)
    wp = math.sqrt(2 * math.pi * ic / (PHI0 * c))
    beta = 1 / (wp * r * c)
    f = 8e9
    bias = np.array([0.3e-6, 1.1e-6, 1.3e-6])
    m = j.sweep({"bias": bias, "rf_current": [1e-6]}, rf_frequency=f, threads=1)
    assert m.bias.attrs["units"] == "A" and m.rf_current.attrs["units"] == "A"
    assert m.voltage.attrs["units"] == "V" and m.voltage_err.attrs["units"] == "V"
    np.testing.assert_allclose(m.torque.values, bias / ic, rtol=1e-15)
    omega = 2 * math.pi * f / wp
    for k, b in enumerate(bias):
        st, step, v = int(m.status.values[k, 0]), m.step.values[k, 0], m.voltage.values[k, 0]
        adv, dv = scipy_advance(beta, b / ic, 1.0, omega)
        n = round(adv / (2 * math.pi))
        if st == 6:                                  # locked: exactly n f Phi_0, and scipy's orbit repeats
            assert step == n and abs(adv - 2 * math.pi * n) < 1e-7 and dv < 1e-7
            assert v == pytest.approx(n * f * PHI0, rel=1e-12)
    assert int(m.status.values[0, 0]) == 6 and m.step.values[0, 0] == 0.0


def test_sweep_over_rf_power_converts_at_the_stated_impedance():
    j = Junction(1e-6, 18.0, 1e-12)
    p = np.array([-70.0, -60.0, -52.5])
    m = j.sweep({"bias": [0.5e-6], "rf_power": p}, rf_frequency=8e9, impedance=50.0, threads=1)
    amp = np.sqrt(2 * 1e-3 * 10 ** (p / 10) / 50.0) / 1e-6
    np.testing.assert_allclose(m.drive_amplitude.values, amp, rtol=1e-14)
    assert m.rf_power.attrs["units"] == "dBm"


def test_sweep_over_temperature_sets_the_reduced_noise():
    ic, r, c = 1e-6, 18.0, 1e-12
    j = Junction(ic, r, c)
    temps = np.array([0.5, 2.0])
    m = j.sweep({"bias": [1.5e-6], "temperature": temps}, threads=1, seed=3)
    assert m.voltage.dims == ("temperature", "bias") and m.temperature.attrs["units"] == "K"
    ej = PHI0 * ic / (2 * math.pi)
    # each temperature's voltage is the pendulum's at noise k_B T / E_J, the same seed and window
    for k, t in enumerate(temps):
        s = pendula.Scene(eps=1.0, damping=j.damping, torque=1.5, noise=KB * t / ej, seed=3)
        ref = pendula.sweep(s, over={"torque": [1.5]}, measure="mean_velocity", transient=200.0, t_max=400.0,
                            threads=1)
        assert m.mean_velocity.values[k, 0] == ref.mean_velocity.values[0]


def test_sweep_into_a_zarr_store_gives_the_same_voltages(tmp_path):
    pytest.importorskip("zarr")
    j = Junction(1e-6, 18.0, 1e-12)
    over = {"bias": [0.3e-6, 0.9e-6, 1.6e-6], "rf_current": [0.5e-6, 1e-6]}
    mem = j.sweep(over, rf_frequency=8e9, threads=1)
    disk = j.sweep(over, rf_frequency=8e9, threads=1, out=tmp_path / "map")
    np.testing.assert_array_equal(disk.voltage.values, mem.voltage.values)
    assert disk.voltage.attrs["units"] == "V" and disk.bias.attrs["units"] == "A"
    with pytest.raises(ValueError, match="out"):
        j.sweep({"bias": [0.5e-6], "temperature": [1.0]}, out=tmp_path / "hot")


def test_sweep_bad_input_names_the_argument():
    j = Junction(1e-6, 18.0, 1e-12)
    with pytest.raises(ValueError, match="impedance"):
        j.sweep({"bias": [0.5e-6], "rf_power": [-60.0]}, rf_frequency=8e9)
    with pytest.raises(ValueError, match="temperature"):
        j.sweep({"bias": [0.5e-6], "temperature": [-1.0]})
    with pytest.raises(ValueError, match="flux"):
        j.sweep({"flux": [0.0]})
    with pytest.raises(ValueError, match="rf_frequency"):
        j.sweep({"bias": [0.5e-6], "rf_current": [1e-6]})
    with pytest.raises(ValueError, match="rf_power"):
        j.sweep({"rf_current": [1e-6], "rf_power": [-60.0]}, rf_frequency=8e9, impedance=50.0)


def test_plot_iv_takes_the_junctions_curve_in_microamperes_and_microvolts():
    j = Junction(1e-6, 18.0, 1e-12)
    f = 8e9
    cur = np.linspace(0.0, 1.6e-6, 9)
    r = j.iv_curve(cur, rf_current=1e-6, rf_frequency=f)
    ax = pendula.plot.iv(r)
    assert ax.get_xlabel() == "bias current I (µA)" and ax.get_ylabel() == "dc voltage V (µV)"
    x, y = ax.lines[0].get_data()
    np.testing.assert_array_equal(x, cur * 1e6)
    np.testing.assert_array_equal(y, r.voltage.values[0] * 1e6)
    assert any(t.get_text().startswith("n = ") for t in ax.texts)
    matplotlib.pyplot.close("all")


def test_plot_steps_draws_the_step_map_and_refuses_other_datasets():
    j = Junction(1e-6, 18.0, 1e-12)
    m = j.sweep({"bias": np.linspace(0, 1.5e-6, 6), "rf_current": [0.5e-6, 1e-6]}, rf_frequency=8e9, threads=1)
    ax = pendula.plot.steps(m)
    assert ax.get_xlabel() == "dc bias current I (µA)" and ax.get_ylabel() == "rf current I_rf (µA)"
    mesh = ax.collections[0]
    st = m.step.transpose("rf_current", "bias").values
    shown = np.ma.getdata(mesh.get_array()).reshape(st.shape)
    whole = np.isfinite(st) & (st == np.round(st)) & (st <= 8)
    np.testing.assert_array_equal(shown[whole], st[whole])
    with pytest.raises(ValueError, match="step map"):
        pendula.plot.steps(j.iv_curve([0.0, 1e-6]))
    matplotlib.pyplot.close("all")


RSJ = json.loads((DATA / "rsj_step_edges.json").read_text())["rows"]


@pytest.mark.parametrize("a, omega", [(0.5, 0.3), (1.0, 1.0)])
def test_steps_edges_of_the_overdamped_junction_bracket_scipy_bisection(a, omega):
    # Junction.steps on a grid of 0.01 I_c: each step's true edge (SciPy's, to 1e-12) lies between the
    # outermost locked bias and the next grid bias, as the table says
    ic, r = 10e-6, 30.0
    j = Junction(ic, r, 0.0)
    f = omega * j.characteristic_frequency / (2 * math.pi)
    cur = np.round(np.arange(-1.0, 2.5001, 0.01), 10) * ic
    s = j.steps(cur, a * ic, f)
    for row in (x for x in RSJ if x["a"] == a and x["omega"] == omega):
        k = np.flatnonzero(s.order.values == row["n"])
        assert k.size == 1
        k = int(k[0])
        lo, hi = row["lower"] * ic, row["upper"] * ic
        assert s.lower.values[k] - s.lower_gap.values[k] < lo <= s.lower.values[k] + 1e-9 * ic
        assert s.upper.values[k] - 1e-9 * ic <= hi < s.upper.values[k] + s.upper_gap.values[k]
        assert s.width.values[k] == s.upper.values[k] - s.lower.values[k]
        assert s.voltage.values[k] == row["n"] * f * FLUX_QUANTUM


def test_steps_refuses_bad_arguments_naming_them():
    j = Junction(1e-6, 18.0, 1e-12)
    with pytest.raises(ValueError, match="rf_current"):
        j.steps([0.0, 1e-6], 0.0, 1e9)
    with pytest.raises(ValueError, match="rf_frequency"):
        j.steps([0.0, 1e-6], 1e-6, 0.0)
    with pytest.raises(ValueError, match="direction"):
        j.steps([0.0, 1e-6], 1e-6, 1e9, direction="both")
    with pytest.raises(ValueError, match="currents"):
        j.steps([1e-6, 0.0], 1e-6, 1e9)

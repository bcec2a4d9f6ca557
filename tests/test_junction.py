"""pendula.Junction: the RCSJ junction in laboratory units.

References: the CODATA 2018 exact constants (h, e, k_B), the textbook
definitions of the plasma frequency, the Stewart-McCumber parameter and the
Josephson energy (Tinkham, Introduction to Superconductivity, section 6.3),
the Josephson relation V = n h f / 2e of a Shapiro step, and the
Fulton-Dunkleberger switching distribution computed here with scipy's quad
from Kramers' rate.
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad

import pendula
from pendula import Junction

H, E, KB = 6.62607015e-34, 1.602176634e-19, 1.380649e-23
HBAR = H / (2 * math.pi)


def test_derived_quantities_from_the_definitions():
    rng = np.random.default_rng(5)
    for _ in range(5):
        ic, r, c, t = 10 ** rng.uniform(-8, -4), 10 ** rng.uniform(0, 3), 10 ** rng.uniform(-15, -11), rng.uniform(0, 4)
        j = Junction(ic, r, c, t)
        wp = math.sqrt(2 * E * ic / (HBAR * c))                    # sqrt(2 e I_c / (hbar C))
        assert j.plasma_frequency == pytest.approx(wp, rel=1e-14)
        assert j.stewart_mccumber == pytest.approx(2 * E * ic * r * r * c / HBAR, rel=1e-14)
        assert j.damping == pytest.approx(1 / math.sqrt(j.stewart_mccumber), rel=1e-14)
        assert j.josephson_energy == pytest.approx(HBAR * ic / (2 * E), rel=1e-14)
        assert j.noise == pytest.approx(KB * t / (HBAR * ic / (2 * E)), rel=1e-14, abs=0)


def test_scene_fields():
    j = Junction(2e-6, 5.0, 3e-13, temperature=0.1)
    s = j.scene(1.5e-6, rf_current=0.4e-6, rf_frequency=7e9, seed=4)
    assert (s.eps, s.torque, s.drive_amplitude, s.seed) == (1.0, 0.75, 0.2, 4)
    assert s.drive_frequency == pytest.approx(2 * math.pi * 7e9 / j.plasma_frequency, rel=1e-15)
    assert s.damping == pytest.approx(j.damping, rel=1e-15) and s.noise == pytest.approx(j.noise, rel=1e-15)


@pytest.mark.parametrize("f", [5e9, 12.5e9])
def test_shapiro_step_voltages_are_n_h_f_over_2e(f):
    # a junction with beta = 1 and the drive at the plasma frequency's scale: steps n = 0, 1, 2
    c = 1e-12
    ic = 1e-6
    wp = math.sqrt(2 * E * ic / (HBAR * c))
    j = Junction(ic, 1 / (wp * c), c)                                    # beta = 1 exactly (up to rounding)
    omega = 2 * math.pi * f / wp
    r = j.iv_curve(np.linspace(0.0, 2.5, 26) * ic * max(omega, 0.3), rf_current=ic, rf_frequency=f)
    locked = r.status.values[0] == 6
    assert locked.sum() >= 3
    n = r.step.values[0][locked]
    want = n * H * f / (2 * E)
    got = r.voltage.values[0][locked]
    np.testing.assert_allclose(got[n != 0], want[n != 0], rtol=1e-9, atol=0)
    assert np.all(got[n == 0] == 0.0)
    assert r.voltage.attrs["units"] == "V" and r.current.attrs["units"] == "A"
    np.testing.assert_allclose(r.torque.values, r.current.values / ic, rtol=1e-15)


def test_ohmic_line_far_above_the_critical_current():
    # at I >> I_c the junction is its resistor: V -> I R (to O((I_c / I)^2))
    j = Junction(1e-6, 10.0, 1e-13)
    r = j.iv_curve([20e-6], transient=50 / j.plasma_frequency, t_max=200 / j.plasma_frequency)
    v = float(r.voltage.item())
    assert v == pytest.approx(20e-6 * 10.0, rel=2e-3)


def test_zero_capacitance_names_the_overdamped_model():
    # C = 0 is the overdamped junction (tests/test_junction_lab.py); the pendulum's scene refuses it
    with pytest.raises(ValueError, match="'capacitance'.*overdamped"):
        Junction(1e-6, 10.0, 0.0).scene(0.5e-6)


@pytest.mark.parametrize("kw, name", [(dict(temperature=-1.0), "temperature"), (dict(resistance=0.0), "resistance"),
                                      (dict(critical_current=-1e-6), "critical_current")])
def test_bad_junction_parameters_name_the_field(kw, name):
    args = dict(critical_current=1e-6, resistance=10.0, capacitance=1e-12)
    args.update(kw)
    with pytest.raises(ValueError, match=f"'{name}'"):
        Junction(**args)


def test_rf_frequency_without_current_names_rf_current():
    j = Junction(1e-6, 10.0, 1e-12)
    with pytest.raises(ValueError, match="'rf_current'"):
        j.scene(0.5e-6, rf_frequency=1e9)
    with pytest.raises(ValueError, match="'rf_frequency'"):
        j.scene(0.5e-6, rf_current=1e-7)
    with pytest.raises(TypeError, match="'bias'"):
        j.scene("1 uA")


def test_switching_at_zero_temperature_is_refused():
    with pytest.raises(ValueError, match="'temperature'"):
        Junction(1e-6, 10.0, 1e-12).switching_currents(1.0, 10, 0)


def _fd_moments(beta, temp, rate):
    """Mean and width of the Fulton-Dunkleberger density with Kramers' rate (reduced units), by quad."""
    def gamma(i):
        s = math.sqrt(1 - i * i)
        wa = math.sqrt(s)
        a = beta / (2 * wa)
        return wa / (2 * math.pi) * (math.sqrt(1 + a * a) - a) * math.exp(-2 * (s - i * math.acos(i)) / temp)

    def density(i):
        return gamma(i) / rate * math.exp(-quad(gamma, 0.0, i, limit=200)[0] / rate)
    norm = quad(density, 0.0, 1.0, limit=200, points=[0.3, 0.5])[0]
    mean = quad(lambda i: i * density(i), 0.0, 1.0, limit=200, points=[0.3, 0.5])[0] / norm
    var = quad(lambda i: (i - mean) ** 2 * density(i), 0.0, 1.0, limit=200, points=[0.3, 0.5])[0] / norm
    return norm, mean, math.sqrt(var)


def test_switching_currents_match_fulton_dunkleberger():
    # beta = 1 (beta_c = 1), T = 0.2 E_J, a ramp of 2e-4 I_c per 1 / omega_p: the junction switches near
    # 0.43 I_c where the barrier is 4 T high (Kramers' formula holds: moderate damping, beta S_b / T >> 1).
    # 300 ramps: the mean is known to 1/sqrt(300) of the width (4 standard errors allowed) plus 0.01 I_c for
    # the finite barrier (a 10 % error of the rate moves the mean by T / |dU/di| * 0.1 ~ 0.01); the width
    # to 1/sqrt(2 * 300) (4 of those) plus 5 %.
    ic, c = 1e-6, 1e-12
    wp = math.sqrt(2 * E * ic / (HBAR * c))
    ej = HBAR * ic / (2 * E)
    j = Junction(ic, 1 / (wp * c), c, temperature=0.2 * ej / KB)
    assert j.damping == pytest.approx(1.0, rel=1e-12) and j.noise == pytest.approx(0.2, rel=1e-12)
    rate = 2e-4 * ic * wp
    n = 300
    s = j.switching_currents(rate, n, seed=5, dt=0.1)
    assert np.all(np.isfinite(s.samples)) and s.counts.sum() == n
    norm, mean, width = _fd_moments(1.0, 0.2, 2e-4)
    assert norm == pytest.approx(1.0, abs=1e-4)
    assert abs(s.mean / ic - mean) < 4 * width / math.sqrt(n) + 0.01, (s.mean / ic, mean)
    assert abs(s.width / ic / width - 1) < 4 / math.sqrt(2 * n) + 0.05, (s.width / ic, width)
    # the library's density is the same law: it integrates to 1 and peaks where quad's does
    grid = np.linspace(0.0, 1.0, 4001) * ic
    p = j.switching_density(grid, rate)
    assert float(np.sum(p) * (grid[1] - grid[0])) == pytest.approx(1.0, abs=1e-3)
    assert float(np.sum(grid * p) * (grid[1] - grid[0])) / ic == pytest.approx(mean, abs=1e-3)


def test_switching_samples_reproducible_bit_for_bit():
    j = Junction(1e-6, 18.0, 1e-12, temperature=0.5)
    rate = 1e-3 * 1e-6 * j.plasma_frequency
    a = j.switching_currents(rate, 8, seed=2, threads=1)
    b = j.switching_currents(rate, 8, seed=2, threads=2)
    np.testing.assert_array_equal(a.samples, b.samples)
    c = j.switching_currents(rate, 8, seed=3)
    assert not np.array_equal(a.samples, c.samples)


def test_noisy_iv_curve_in_volts():
    # thermal noise rounds the I-V curve: below I_c the phase diffuses and a small voltage appears
    ic, c = 1e-6, 1e-12
    wp = math.sqrt(2 * E * ic / (HBAR * c))
    ej = HBAR * ic / (2 * E)
    j = Junction(ic, 1 / (wp * c), c, temperature=0.3 * ej / KB)
    r = j.iv_curve([0.0, 0.8e-6, 3e-6], t_max=2000 / wp, seed=1)
    v = r.voltage.values[0]
    assert np.all(r.status.values == 0)
    assert abs(v[0]) < 5 * r.voltage_err.values[0][0] + 1e-12   # no bias: no mean voltage
    assert v[1] > 5 * r.voltage_err.values[0][1]                    # phase diffusion below I_c
    assert v[2] == pytest.approx(3e-6 * j.resistance, rel=0.05)     # ohmic far above

"""The junction in the laboratory: escape, switching at any ramp rate, the overdamped junction, rf, bias order.

References, each independent of the code under test:
- the RSJ dc I-V V = R sqrt(I^2 - I_c^2) evaluated by mpmath at 30 digits;
- the RSJ Shapiro step edges of data/gen_rsj_step_edges.py (SciPy DOP853,
  minimize_scalar and brentq, written from the equation alone);
- the escape rates written again here in mpmath from the formulas (Mel'nikov
  and Meshkov's turnover formula, the Caldeira-Leggett rate as in Martinis,
  Devoret and Clarke 1987, section II), with mpmath.quad for the barrier
  orbit's action and Mel'nikov's integral;
- the Fulton-Dunkleberger means and widths of data/gen_switching_reference.py
  (mpmath at 25 digits, from the formulas and the CODATA constants alone);
- pendula's direct Langevin ramps (Junction.switching_currents), an
  independent route to the same distribution where both can run.
"""

import json
import math
import pathlib

import mpmath as mp
import numpy as np
import pytest

import pendula
from pendula import Junction
from pendula.escape import (crossover_temperature, escape_rate, quantum_rate, switching_distribution,
                            thermal_rate)
from pendula.rf import rf_current

H, E, KB = 6.62607015e-34, 1.602176634e-19, 1.380649e-23
HBAR = H / (2 * math.pi)
PHI0 = H / (2 * E)
DATA = pathlib.Path(__file__).resolve().parents[1] / "data" / "junction"


# ------------------------------------------------------------------ the overdamped junction

def test_rsj_dc_iv_matches_the_closed_form_to_1e_12():
    # every region: below I_c, next to I_c (1 + 10^-k, where I^2 - I_c^2 cancels), far above, negative;
    # plus seeded random biases.  mpmath at 30 digits evaluates R sqrt(I^2 - I_c^2).
    ic, r = 10e-6, 30.0
    j = Junction(ic, r, 0.0)
    rng = np.random.default_rng(11)
    i = np.concatenate([[0.0, 0.5, 1.0, 1 + 1e-15, 1 + 1e-12, 1 + 1e-9, 1 + 1e-6, 1.001, 2.0, 1e3, -1.5, -1 - 1e-10],
                        rng.uniform(-3, 3, 40), 1 + 10 ** rng.uniform(-14, 0, 20)])
    bias = i * ic
    got = j.dc_voltage(bias)
    mp.mp.dps = 30
    for b, v in zip(bias, got):
        bb = mp.mpf(float(b))
        want = mp.sign(bb) * r * mp.sqrt(bb * bb - mp.mpf(ic) ** 2) if abs(bb) > ic else mp.mpf(0)
        if want == 0:
            assert v == 0.0, (b, v)
        else:
            assert abs(v - want) <= 1e-12 * abs(want), (b, v, want)


def test_rsj_iv_curve_without_rf_is_the_closed_form():
    j = Junction(10e-6, 30.0, 0.0)
    cur = np.linspace(0, 40e-6, 41)
    r = j.iv_curve(cur, direction="both")
    np.testing.assert_array_equal(r.voltage.sel(direction="up").values, j.dc_voltage(cur))
    np.testing.assert_array_equal(r.voltage.sel(direction="down").values, j.dc_voltage(cur))
    assert r.voltage.attrs["units"] == "V" and r.current.attrs["units"] == "A"


def _reference_edges():
    return json.loads((DATA / "rsj_step_edges.json").read_text())["rows"]


@pytest.mark.parametrize("row", _reference_edges(), ids=lambda r: f"a{r['a']:.3g}-w{r['omega']:.3g}-n{r['n']}")
def test_rsj_step_edges_match_scipy_bisection(row):
    # both sides integrate the map to 1e-12 and locate the edge to 1e-11 (bisection) and 1e-12 (brentq):
    # the gap F(x) - x is known to ~1e-11 and moves with the bias at a rate of order 1, so the edges
    # agree to ~1e-11; 1e-9 allows a hundredfold.
    ic, r = 10e-6, 30.0
    j = Junction(ic, r, 0.0)
    f = row["omega"] * j.characteristic_frequency / (2 * math.pi)
    s = j.shapiro_steps(row["a"] * ic, f, orders=[row["n"]])
    assert abs(s["lower"][0] / ic - row["lower"]) < 1e-9
    assert abs(s["upper"][0] / ic - row["upper"]) < 1e-9
    assert s["voltage"][0] == row["n"] * f * PHI0


def test_rsj_every_bias_on_a_step_is_reported_locked():
    # the 10 uA, 30 ohm junction at 100 GHz, 10 uA rf: biases inside the edges of steps 0..3 report
    # status 6 and V = n f Phi_0 exactly; biases outside every step are not locked
    ic, r, f = 10e-6, 30.0, 100e9
    j = Junction(ic, r, 0.0)
    s = j.shapiro_steps(10e-6, f, orders=[0, 1, 2, 3])
    cur = np.linspace(0.0, s["upper"][-1] * 1.2, 121)
    iv = j.iv_curve(cur, rf_current=10e-6, rf_frequency=f)
    st, v, step = iv.status.values[0], iv.voltage.values[0], iv.step.values[0]
    margin = 1e-9 * ic
    for n, lo, hi in zip(s["order"], s["lower"], s["upper"]):
        inside = (cur > lo + margin) & (cur < hi - margin)
        assert inside.sum() >= 2
        assert np.all(st[inside] == 6) and np.all(step[inside] == n)
        assert np.all(v[inside] == n * f * PHI0)
    on_any = np.zeros(cur.size, bool)
    for lo, hi in zip(s["lower"], s["upper"]):
        on_any |= (cur >= lo - margin) & (cur <= hi + margin)
    top = cur < s["upper"][-1]
    assert np.all(st[top & ~on_any] == 0)
    # off the steps the voltage lies strictly between its neighbours' steps, within the error bound
    off = top & ~on_any
    assert np.all(np.abs(v[off] / (f * PHI0) - np.round(v[off] / (f * PHI0))) > 0)


def test_rsj_off_step_voltage_within_its_bound_of_scipy():
    # off the steps the rotation number of the circle map is F^K(0) / (2 pi K) within 1 / K: the library's
    # K = 2000 periods against SciPy's DOP853 (rtol 1e-11) over 400 periods, each with its bound
    from scipy.integrate import solve_ivp
    ic, r = 10e-6, 30.0
    j = Junction(ic, r, 0.0)
    a, omega = 1.0, 1.0
    f = omega * j.characteristic_frequency / (2 * math.pi)
    k = 400
    for i in (0.9, 1.8):
        iv = j.iv_curve([i * ic], rf_current=a * ic, rf_frequency=f)
        assert iv.status.values[0][0] == 0
        v = iv.voltage.values[0][0] / (ic * r)                   # <phi'> in units of omega_c
        bound = iv.voltage_err.values[0][0] / (ic * r)
        assert bound == pytest.approx(omega / 2000, rel=1e-12)
        sol = solve_ivp(lambda t, y: i + a * np.cos(omega * t) - np.sin(y), (0, k * 2 * np.pi / omega), [0.0],
                        method="DOP853", rtol=1e-11, atol=1e-11)
        ref = sol.y[0, -1] / (k * 2 * np.pi / omega)
        assert abs(v - ref) <= bound + omega / k, (i, v, ref)


def test_rsj_refuses_what_needs_a_plasma_frequency_naming_capacitance():
    j = Junction(10e-6, 30.0, 0.0)
    hot = Junction(10e-6, 30.0, 0.0, temperature=1.0)
    for call in (lambda: j.scene(1e-6), lambda: j.plasma_frequency, lambda: hot.switching_currents(1.0, 10),
                 lambda: thermal_rate(j, 1e-6, 1.0), lambda: switching_distribution(j, 1.0)):
        with pytest.raises(ValueError, match="capacitance"):
            call()
    with pytest.raises(ValueError, match="'capacitance'"):
        Junction(10e-6, 30.0, 1e-12).dc_voltage(1e-6)
    with pytest.raises(ValueError, match="'capacitance'"):
        Junction(10e-6, 30.0, -1e-12)
    with pytest.raises(NotImplementedError, match="'temperature'"):
        Junction(10e-6, 30.0, 0.0, temperature=1.0).iv_curve([0.0, 20e-6])


# ------------------------------------------------------------------ escape rates

def _mp_rates(ic, r, c, t, i):
    """Thermal (Mel'nikov-Meshkov) and tunnelling (Caldeira-Leggett) rates in 1/s, mpmath, from the formulas."""
    mp.mp.dps = 30
    ic, r, c, t, i = (mp.mpf(x) for x in (ic, r, c, t, i))
    hbar = mp.mpf(H) / (2 * mp.pi)
    wp = mp.sqrt(2 * mp.mpf(E) * ic / (hbar * c))
    ej = hbar * ic / (2 * mp.mpf(E))
    wa = wp * (1 - i * i) ** mp.mpf(0.25)
    du = 2 * ej * (mp.sqrt(1 - i * i) - i * mp.acos(i))
    kt = mp.mpf(KB) * t
    # action of the orbit at the barrier's energy, in J s: 2 int sqrt(2 m (U_b - U)) dphi with the mass
    # m = hbar^2 C / (2e)^2 and U = -E_J (cos phi + i phi); integrated in units of sqrt(m E_J) (mpmath.quad's
    # error control is absolute: the integrand must be of order 1)
    top, bottom = mp.pi - mp.asin(i), mp.asin(i)
    u = lambda p: -(mp.cos(p) + i * p)  # noqa: E731
    turn = mp.findroot(lambda p: u(p) - u(top), (top - 2 * mp.pi, bottom), solver="illinois", verify=False)
    turn = mp.findroot(lambda p: u(p) - u(top), turn, solver="newton", verify=False)
    assert abs(u(turn) - u(top)) < 1e-25
    m = hbar ** 2 * c / (2 * mp.mpf(E)) ** 2
    sb = mp.sqrt(m * ej) * 2 * mp.quad(lambda p: mp.sqrt(max(2 * (u(top) - u(p)), 0)), [turn, bottom, top])
    gamma = 1 / (r * c)                                      # the friction rate
    delta = gamma * sb / kt
    a = mp.exp(mp.quad(lambda x: mp.log(-mp.expm1(-delta * (x * x + 0.25))) / (x * x + 0.25),
                       [0, mp.inf]) / mp.pi)
    alpha = gamma / (2 * wa)
    thermal = a * (mp.sqrt(1 + alpha ** 2) - alpha) * wa / (2 * mp.pi) * mp.exp(-du / kt)
    b = mp.mpf("7.2") * du / (hbar * wa)
    q = wa * r * c
    quantum = mp.sqrt(120 * mp.pi * b) * wa / (2 * mp.pi) * mp.exp(-b * (1 + mp.mpf("0.87") / q))
    return thermal, quantum


@pytest.mark.parametrize("ic, r, c, t, i", [
    (10e-6, 30.0, 1e-12, 4.2, 0.8), (10e-6, 30.0, 1e-12, 4.2, 0.93), (10e-6, 30.0, 1e-12, 0.02, 0.985),
    (1e-6, 1e4, 1e-12, 0.3, 0.6),      # weak damping (Q ~ 500): Mel'nikov's factor far from 1
    (1e-6, 5.0, 1e-12, 1.0, 0.5),      # strong damping: Kramers' factor far from 1
    (3.1e-6, 120.0, 4.7e-13, 1.3, 0.9)])
def test_rates_match_the_formulas_in_mpmath(ic, r, c, t, i):
    # the library's quadratures (48-point Gauss-Legendre for the action, an 801-point sinh trapezoid for
    # Mel'nikov's integral, 64 bisections for the turning point) against mpmath at 30 digits: 1e-10
    j = Junction(ic, r, c, temperature=t)
    th, qu = _mp_rates(ic, r, c, t, i)
    got_t = thermal_rate(j, i * ic)[()]
    got_q = quantum_rate(j, i * ic)[()]
    assert abs(got_t / float(th) - 1) < 1e-10, (got_t, th)
    if qu > mp.mpf("1e-290"):
        assert abs(got_q / float(qu) - 1) < 1e-10, (got_q, qu)
    else:                                    # below the doubles: 0 or a subnormal, never a wrong number
        assert got_q < 1e-280
    assert escape_rate(j, i * ic)[()] == max(got_t, got_q)


def test_thermal_rate_reaches_both_damping_limits():
    # Mel'nikov's factor: energy diffusion (Delta << 1: Gamma -> Delta omega_a / 2 pi exp(-dU/kT)) and
    # Kramers' spatial diffusion (Delta >> 1: A -> 1): checked against those limits written out here
    ic, c, t, i = 1e-6, 1e-12, 0.05, 0.7
    for r, limit in ((1e9, "energy"), (1.0, "kramers")):
        j = Junction(ic, r, c, temperature=t)
        th, _ = _mp_rates(ic, r, c, t, i)
        got = thermal_rate(j, i * ic)[()]
        if limit == "kramers":
            wa = j.plasma_frequency * (1 - i * i) ** 0.25
            alpha = 1 / (2 * wa * r * c)
            du = 2 * j.josephson_energy * (math.sqrt(1 - i * i) - i * math.acos(i))
            kram = (math.sqrt(1 + alpha ** 2) - alpha) * wa / (2 * math.pi) * math.exp(-du / (KB * t))
            assert got == pytest.approx(kram, rel=1e-6)
        else:
            assert got == pytest.approx(float(th), rel=1e-10)
    j = Junction(ic, 1e9, c, temperature=t)
    assert thermal_rate(j, i * ic)[()] < 1e-3 * thermal_rate(Junction(ic, 1e3, c, temperature=t), i * ic)[()]


@pytest.mark.parametrize("beta", [0.02, 0.2, 1.0])
def test_thermal_rate_against_langevin_escapes_at_three_dampings(beta):
    # tilt 0.5, barrier dU = 5 k_B T; 300 escapes of pendula's Langevin integrator (seeded), their mean
    # first-passage time to one radian beyond the barrier's top: standard error 1 / sqrt(300) = 5.8 %.
    # The turnover formula is asymptotic in k_B T / dU: 10 % allowed for the finite barrier on top of
    # 4 standard errors.  Measured (rate over formula): 0.80 at beta = 0.02 (Delta = 0.9, energy diffusion),
    # 0.96 at 0.2, 0.90 at 1; at dU = 7 k_B T: 0.78, 0.96, 0.98.
    from pendula import _kernel
    ic, c = 1e-6, 1e-12
    wp = math.sqrt(2 * E * ic / (HBAR * c))
    ej = HBAR * ic / (2 * E)
    tau = 0.5
    s = math.sqrt(1 - tau * tau)
    temp = 2 * (s - tau * math.acos(tau)) / 5.0
    j = Junction(ic, 1 / (beta * wp * c), c, temperature=temp * ej / KB)
    formula = thermal_rate(j, tau * ic)[()] / wp
    n = 300
    times, st = _kernel.langevin_escape_v(1.0, beta, tau, temp, 11, 0.1, math.pi - math.asin(tau) + 1.0, 1e7, n,
                                          0, np.zeros(1, np.int32))
    assert st == 0 and np.all(np.isfinite(times))
    assert abs(1.0 / times.mean() / formula - 1) < 4 / math.sqrt(n) + 0.10


def test_crossover_temperature_of_a_10_uA_1_pF_junction():
    # T_cr = hbar omega_R / (2 pi k_B), omega_R = omega_a (sqrt(1 + alpha^2) - alpha), alpha = 1 / (2 omega_a R C)
    # (Grabert and Weiss 1984), from the constants: about 0.19 K at zero bias, lower at the switching bias
    ic, c = 10e-6, 1e-12
    wp = math.sqrt(2 * E * ic / (HBAR * c))
    for r in (30.0, 1e6):
        j = Junction(ic, r, c)
        for i in (0.0, 0.9, 0.99):
            wa = wp * (1 - i * i) ** 0.25
            alpha = 1 / (2 * wa * r * c)
            want = HBAR * wa * (math.sqrt(1 + alpha ** 2) - alpha) / (2 * math.pi * KB)
            assert crossover_temperature(j, i * ic)[()] == pytest.approx(want, rel=1e-13)
    undamped = HBAR * wp / (2 * math.pi * KB)
    assert 0.19 < undamped < 0.22
    # at moderate damping (30 ohm: Q = 2.9 at 0.95 I_c) the thermal rate is the larger at T_cr (its exponent
    # 2 pi dU / (hbar omega_R) is below the tunnelling one 7.2 dU / (hbar omega_a) (1 + 0.87 / Q)) and the
    # smaller at T_cr / 2 (the exponent doubles): tunnelling takes over between them
    j = Junction(ic, 30.0, c)
    tcr = crossover_temperature(j, 0.95 * ic)[()]
    assert thermal_rate(j, 0.95 * ic, temperature=tcr)[()] > quantum_rate(j, 0.95 * ic)[()]
    assert thermal_rate(j, 0.95 * ic, temperature=0.5 * tcr)[()] < quantum_rate(j, 0.95 * ic)[()]


# ------------------------------------------------------------------ switching distributions

def _reference_switching():
    return json.loads((DATA / "switching_reference.json").read_text())["cases"]


@pytest.mark.parametrize("case", _reference_switching(),
                         ids=lambda c: f"{c['temperature']}K-{c['ramp_rate']}Aps-{c['critical_current']}A")
def test_switching_mean_and_width_match_the_mpmath_integral(case):
    # the reference's own spread (120 against 180 panels) is below 1e-16 and its thermal prefactor is a
    # Chebyshev fit good to 1e-13 (stored with it).  The library's rates agree with mpmath to ~1e-13 and its
    # panels are exact to rounding: the mean to ~1e-14, the width (a difference of moments) to ~1e-12;
    # allowed 1e-12 and 1e-10.
    j = Junction(case["critical_current"], case["resistance"], case["capacitance"], temperature=case["temperature"])
    d = switching_distribution(j, case["ramp_rate"])
    assert abs(d.mean / case["mean"] - 1) < 1e-12, (d.mean, case["mean"])
    assert abs(d.width / case["width"] - 1) < 1e-10, (d.width, case["width"])
    assert d.at_critical == 0.0


def test_switching_density_is_a_density_and_at_slower_ramps_lower():
    j = Junction(10e-6, 30.0, 1e-12, temperature=4.2)
    d = switching_distribution(j, 1.0, np.linspace(0, 10e-6, 20001))
    step = d.currents[1] - d.currents[0]
    assert float(np.sum(d.density) * step) == pytest.approx(1.0, abs=1e-6)
    assert float(np.sum(d.density * d.currents) * step) == pytest.approx(d.mean, rel=1e-7)
    slow = switching_distribution(j, 1e-3)
    assert slow.mean < d.mean
    cold = switching_distribution(j, 1.0, temperature=0.02)
    assert cold.mean > d.mean and cold.width < d.width


def test_switching_distribution_agrees_with_langevin_ramps():
    # beta = 1, k_B T = 0.2 E_J, a ramp of 2e-4 I_c per 1 / omega_p: 300 Langevin ramps (seeded) against the
    # Fulton-Dunkleberger integral.  The sample mean has a standard error of width / sqrt(300) = 0.058 widths,
    # so 0.3 widths is 5.2 standard errors: a correct integral fails with probability < 2e-7 (the seed makes
    # the run the same every time).  Measured: 0.041 widths apart, the width 8 % wider.
    ic, c = 1e-6, 1e-12
    wp = math.sqrt(2 * E * ic / (HBAR * c))
    ej = HBAR * ic / (2 * E)
    j = Junction(ic, 1 / (wp * c), c, temperature=0.2 * ej / KB)
    rate = 2e-4 * ic * wp
    s = j.switching_currents(rate, 300, seed=5, dt=0.1)
    d = switching_distribution(j, rate)
    assert abs(s.mean - d.mean) < 0.3 * d.width, ((s.mean - d.mean) / d.width)
    assert s.width == pytest.approx(d.width, rel=4 / math.sqrt(600) + 0.1)


# ------------------------------------------------------------------ rf as the laboratory states it

def test_rf_current_from_power_and_voltage():
    rng = np.random.default_rng(3)
    for dbm, z in zip(rng.uniform(-90, 10, 20), rng.uniform(1, 1000, 20)):
        i = rf_current(power_dbm=float(dbm), impedance=float(z))
        assert 0.5 * i * i * z == pytest.approx(1e-3 * 10 ** (dbm / 10), rel=1e-14)     # P = I^2 Z / 2
    assert rf_current(voltage=2e-3, source_impedance=1e3) == pytest.approx(2e-6, rel=1e-15)
    assert rf_current(current=3e-6) == 3e-6


# ------------------------------------------------------------------ bad input, named

@pytest.mark.parametrize("call, name, exc", [
    (lambda: rf_current(power_dbm=-20.0), "impedance", ValueError),
    (lambda: rf_current(voltage=1e-3), "source_impedance", ValueError),
    (lambda: rf_current(impedance=50.0), "impedance", ValueError),
    (lambda: rf_current(power_dbm=-20.0, impedance=0.0), "impedance", ValueError),
    (lambda: rf_current(current=1e-6, power_dbm=-20.0, impedance=50.0), "exactly one", TypeError),
    (lambda: thermal_rate(Junction(1e-6, 10.0, 1e-12), 0.5e-6, temperature=-1.0), "temperature", ValueError),
    (lambda: Junction(1e-6, 10.0, 1e-12, temperature=-0.1), "temperature", ValueError),
    (lambda: switching_distribution(Junction(1e-6, 10.0, 1e-12, 1.0), -1.0, temperature=-1.0), "ramp_rate",
     ValueError),
    (lambda: switching_distribution(Junction(1e-6, 10.0, 1e-12, 1.0), 0.0), "ramp_rate", ValueError),
    (lambda: switching_distribution(Junction(1e-6, 10.0, 1e-12, 1.0), float("inf")), "ramp_rate", ValueError),
    (lambda: Junction(1e-6, 10.0, 1e-12, 1.0).switching_currents(0.0, 10), "ramp_rate", ValueError),
    (lambda: switching_distribution("junction", 1.0), "junction", TypeError),
    (lambda: Junction(1e-6, 10.0, 1e-12).iv_curve([2e-6, 1e-6, 0.0], direction="up"), "currents", ValueError),
    (lambda: Junction(1e-6, 10.0, 1e-12).iv_curve([2e-6, 1e-6, 0.0], direction="down"), "currents", ValueError),
    (lambda: Junction(1e-6, 10.0, 0.0).iv_curve([0.0, 2e-6, 1e-6], direction="both"), "currents", ValueError),
    (lambda: Junction(1e-6, 10.0, 1e-12).iv_curve([0.0, 1e-6], direction="sideways"), "direction", ValueError),
    (lambda: Junction(1e-6, 10.0, 0.0).shapiro_steps(0.0, 1e9), "rf_current", ValueError),
    (lambda: Junction(1e-6, 10.0, 0.0).shapiro_steps(1e-6, 1e9, orders=[1.5]), "orders", ValueError),
])
def test_bad_input_names_the_argument(call, name, exc):
    with pytest.raises(exc, match=name):
        call()


def test_ascending_currents_are_ramped_up_and_labelled_so():
    # a hysteretic junction (beta_c = 16): between the retrapping current and I_c the up branch is at zero
    # voltage and the down branch running -- the labels follow the ramp
    ic, c = 1e-6, 1e-12
    wp = math.sqrt(2 * E * ic / (HBAR * c))
    j = Junction(ic, 4 / (wp * c), c)
    r = j.iv_curve([0.0, 0.6e-6, 1.3e-6], direction="both", transient=100 / wp, t_max=200 / wp)
    up, down = r.voltage.sel(direction="up").values, r.voltage.sel(direction="down").values
    assert up[1] == 0.0 and down[1] > 0.0
    assert pendula.junction.Junction is Junction

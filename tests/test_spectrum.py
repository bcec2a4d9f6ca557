"""Spectra (FFTW) against the exact Fourier series of the pendulum.

Tolerances, with the reason: eight whole periods sampled at 4096 points put
every line on a bin, so the FFT amplitude equals the Fourier coefficient up to
aliasing of harmonics above the Nyquist frequency (below 1e-30 here) and
rounding of the 4096-term sums: 1e-9 relative is the issue's bound; we
measure 3e-14 at v0 = 1.9 and 4e-15 at 1.9991, and at worst 1.4e-11 at
v0 = 0.5, for its 7th harmonic, whose amplitude is only 1e-6 of the
fundamental's (an absolute error of 1e-17).
"""

import numpy as np
import pytest

import pendula


def sampled(v0, eps=1.0, n=4096, periods=8):
    o = pendula.orbit(0.0, v0, eps)
    t = np.arange(n) * (periods * o.period / n)
    theta, _ = pendula.exact_motion(0.0, v0, eps, t)
    if o.regime == "rotation":
        theta = theta - o.omega * t
    return o, t, theta


@pytest.mark.parametrize("v0,eps", [(0.5, 1.0), (1.9, 1.0), (1.9991, 1.0), (1.2, 9.81)])
def test_libration_harmonics_match_the_exact_series(v0, eps):
    o, t, theta = sampled(v0, eps)
    s = pendula.spectrum(t, theta)
    omega, b = pendula.fourier_series(0.0, v0, eps, 4)
    got = s.harmonics(4)
    lead = b > 1e-6 * b[0]
    assert np.all(np.abs(got[lead] / b[lead] - 1) < 1e-9)
    assert abs(s.fundamental / omega - 1) < 1e-12
    # omega = pi sqrt(eps) / (2K)
    assert abs(omega / (np.pi * np.sqrt(eps) / (2 * pendula.ellipk(o.m, o.mc))) - 1) < 1e-14


def test_rotation_harmonics_match_the_exact_series():
    o, t, x = sampled(2.5)
    s = pendula.spectrum(t, x)
    omega, c = pendula.fourier_series(0.0, 2.5, 1.0, 3)
    dw = s.omega[1]
    bins = [int(round(j * omega / dw)) for j in (1, 2, 3)]
    assert np.all(np.abs(s.amplitude[bins] / c - 1) < 1e-9)


def test_parseval_and_numpy_agree():
    _, t, theta = sampled(1.981)
    s = pendula.spectrum(t, theta)
    n = t.size
    ms = np.mean(theta**2)
    parts = s.amplitude[0] ** 2 + 0.5 * np.sum(s.amplitude[1:-1] ** 2) + s.amplitude[-1] ** 2
    assert abs(parts / ms - 1) < 1e-12
    ref = 2 * np.abs(np.fft.rfft(theta)) / n
    ref[0] /= 2
    ref[-1] /= 2
    assert np.abs(s.amplitude - ref).max() < 1e-13 * np.abs(ref).max()


def test_more_odd_harmonics_stand_out_as_v0_approaches_2():
    counts = []
    for v0 in (0.5, 1.6, 1.9, 1.981, 1.9962, 1.9991, 1.999995):
        _, t, theta = sampled(v0)
        above = pendula.odd_harmonics_above(pendula.spectrum(t, theta), 1e-6)
        assert all(h % 2 == 1 for h in above)
        counts.append(len(above))
    assert counts == sorted(counts) and counts[-1] > counts[0] + 4


def test_one_plan_for_a_sweep_gives_the_same_spectra():
    n = 2048
    t = np.arange(n) * 0.01
    sig = np.array([np.sin(k * t) + 0.1 * np.cos(3 * k * t) for k in (1.0, 2.0, 3.0)])
    many = pendula.spectra(t, sig)
    for s1, x in zip(many, sig):
        s2 = pendula.spectrum(t, x)
        assert np.array_equal(s1.power, s2.power)
    nan = pendula.spectrum(t, np.full(n, np.nan))
    assert np.all(np.isnan(nan.power))                      # NaN in, NaN out


def test_hann_window_keeps_the_amplitude_of_a_line():
    n = 1024
    t = np.arange(n) * (2 * np.pi / n)          # one period of sin(t): bin 1... use 10 periods
    x = 0.7 * np.sin(10 * t)
    s = pendula.spectrum(t, x, window="hann")
    assert s.amplitude[10] == pytest.approx(0.7, rel=1e-12)
    assert s.fundamental == pytest.approx(10.0, rel=1e-3)


def test_damped_run_has_a_drifting_frequency_and_no_crash():
    sc = pendula.Scene(v0=1.9, damping=0.02, rtol=1e-10)
    t = np.linspace(0, 400, 8192)
    tr = pendula.simulate(sc, t)
    first = pendula.spectrum(t[:4096], tr.theta[:4096] - tr.theta[:4096].mean(), window="hann")
    second = pendula.spectrum(t[4096:], tr.theta[4096:] - tr.theta[4096:].mean(), window="hann")
    # the amplitude decays, so the frequency rises towards sqrt(eps) = 1
    assert first.fundamental < second.fundamental < 1.0 + 0.01


@pytest.mark.parametrize("t,x,what", [
    (np.array([0.0, 1.0, 3.0, 4.0, 5.0]), np.zeros(5), "uniform"),
    (np.arange(3.0), np.zeros(3), "at least 4"),
    (np.arange(8.0), np.zeros(7), "shape"),
    (np.array([0.0, 1.0, np.nan, 3.0, 4.0]), np.zeros(5), "finite"),
])
def test_bad_spectrum_input(t, x, what):
    with pytest.raises(ValueError, match=what):
        pendula.spectrum(t, x)


def test_unknown_window_and_separatrix():
    with pytest.raises(ValueError, match="window"):
        pendula.spectrum(np.arange(8.0), np.zeros(8), window="hamming")
    with pytest.raises(ValueError, match="separatrix"):
        pendula.fourier_series(0.0, 2.0)


# ---------------------------------------------------------------- degenerate input

def test_no_signals_give_no_spectra():
    assert pendula.spectra(np.arange(64.0), np.empty((0, 64))) == []


@pytest.mark.parametrize("n", [0, 1, 2, 3])
def test_too_short_records_are_refused(n):
    with pytest.raises(ValueError, match="at least 4"):
        pendula.spectrum(np.arange(float(n)), np.zeros(n))


# (1e-150: its power 1e-300 is still a normal double; amplitudes below ~1e-154
# have powers that underflow, a limit of storing |A|^2)
@pytest.mark.parametrize("value", [0.0, 1.0, -3.7e5, 1e-150])
def test_constant_signal_has_no_fundamental(value):
    t = np.arange(256) * 0.1
    s = pendula.spectrum(t, np.full(256, value))
    with pytest.warns(RuntimeWarning, match="no fundamental"):
        assert np.isnan(s.fundamental)
    with pytest.warns(RuntimeWarning):
        assert np.all(np.isnan(s.harmonics(3)))
    # the constant itself is in bin 0, exactly up to rounding of the sum
    assert abs(s.amplitude[0] - abs(value)) <= 1e-13 * abs(value)


def test_a_small_line_on_a_large_offset_is_still_found():
    # amplitude 1e-9 of the offset: far above the rounding floor (1e3 eps)
    t = np.arange(1024) * (2 * np.pi / 1024)
    s = pendula.spectrum(t, 1.0 + 1e-9 * np.sin(5 * t))
    assert s.fundamental == pytest.approx(5.0, rel=1e-12)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_signal_has_no_fundamental(bad):
    t = np.arange(128) * 0.1
    x = np.sin(t)
    x[17] = bad
    s = pendula.spectrum(t, x)
    assert not np.all(np.isfinite(s.power))
    with pytest.warns(RuntimeWarning, match="not finite"):
        assert np.isnan(s.fundamental)
    with pytest.warns(RuntimeWarning):
        assert pendula.odd_harmonics_above(s) == []


def test_non_finite_signal_does_not_spoil_its_neighbours_in_a_sweep():
    t = np.arange(128) * 0.1
    x = np.array([np.sin(t), np.sin(t), np.sin(2 * t)])
    x[1, 3] = np.nan
    many = pendula.spectra(t, x)
    assert np.array_equal(many[0].power, pendula.spectrum(t, x[0]).power)
    assert np.array_equal(many[2].power, pendula.spectrum(t, x[2]).power)
    assert np.all(np.isnan(many[1].power))


@pytest.mark.parametrize("t,what", [
    (np.r_[np.arange(10.0), 10.5, np.arange(11.0, 16.0)], "uniform"),     # one jittered sample
    (np.arange(16.0)[::-1], "uniform"),                                  # decreasing
    (np.zeros(16), "uniform"),                                           # no spacing
    (np.r_[np.arange(15.0), np.inf], "finite"),
])
def test_non_uniform_or_non_finite_times_are_refused(t, what):
    with pytest.raises(ValueError, match=what):
        pendula.spectrum(t, np.zeros(t.size))


def test_odd_length_and_smallest_length_match_numpy():
    rng = np.random.default_rng(7)
    for n in (4, 5, 7, 33, 1001):
        x = rng.standard_normal(n)
        s = pendula.spectrum(np.arange(n) * 0.5, x)
        ref = 2 * np.abs(np.fft.rfft(x)) / n
        ref[0] /= 2
        if n % 2 == 0:
            ref[-1] /= 2
        # both are O(eps log n) accurate: compare at 1e-13 of the largest line
        assert np.abs(s.amplitude - ref).max() < 1e-13 * ref.max(), n
        assert np.allclose(s.omega, 2 * np.pi * np.arange(n // 2 + 1) / (n * 0.5), rtol=1e-15, atol=0)


# ---------------------------------------------------------------- FFTW wisdom cache

_CHILD = """
import warnings, numpy as np, pendula
warnings.simplefilter("always")
t = np.arange(256) * 0.1
x = np.sin(3 * t) + 0.25 * np.cos(7 * t)
s = pendula.spectrum(t, x)
ref = 2 * np.abs(np.fft.rfft(x)) / 256; ref[0] /= 2; ref[-1] /= 2
assert np.abs(s.amplitude - ref).max() < 1e-13 * ref.max()
print("SPECTRUM-OK")
"""


def _child(env_path, code=_CHILD):
    import os
    import subprocess
    import sys

    env = dict(os.environ, PENDULA_WISDOM=str(env_path))
    return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("content", [
    "garbage (not wisdom at all",
    "(fftw-2.1.5 fftw_wisdom #x0 #x0 #x0 #x0\n  (fftw_codelet_n1_4 0 #x0 #x0 #x0 #x0 #x0 #x0 #x0)\n)\n",   # foreign FFTW
    "",
])
def test_corrupt_or_foreign_wisdom_is_ignored_with_a_warning(tmp_path, content):
    path = tmp_path / "fftw-wisdom"
    path.write_text(content)
    r = _child(path)
    assert r.returncode == 0, r.stderr
    assert "SPECTRUM-OK" in r.stdout
    assert "ignored" in r.stderr and "RuntimeWarning" in r.stderr


def test_missing_wisdom_is_silent_and_saved_wisdom_is_used(tmp_path):
    path = tmp_path / "sub" / "fftw-wisdom"
    r = _child(path)
    assert r.returncode == 0 and "SPECTRUM-OK" in r.stdout and "Warning" not in r.stderr, r.stderr
    made = _child(path, "import pendula; print(pendula.precompute_wisdom([256, 100]))")
    assert made.returncode == 0, made.stderr
    assert path.read_text().startswith("(fftw-3")
    r = _child(path)
    assert r.returncode == 0 and "SPECTRUM-OK" in r.stdout and "Warning" not in r.stderr, r.stderr


def test_wisdom_sizes_are_checked():
    with pytest.raises(ValueError, match="sizes"):
        pendula.precompute_wisdom([2])

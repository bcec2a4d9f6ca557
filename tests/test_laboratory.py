"""pendula.Pendulum: the pendulum in metres, seconds and degrees, against closed forms.

References, independent of pendula's kernel:

* the small-angle period 2 pi sqrt(l / g) (Galileo; Huygens 1673);
* the exact period 4 sqrt(l / g) K(m), m = sin^2(theta0 / 2), with K from
  mpmath's ``ellipk`` at 60 digits (the release at 180 degrees needs 1 - m = 3.7e-33 kept);
* the exact motion sin(theta / 2) = k cd(sqrt(g / l) t | m), k = sin(theta0 / 2),
  the bob released from rest (Lawden, Elliptic Functions and Applications,
  section 5.2), with mpmath's ``ellipfun`` at 60 digits.

Tolerances: the kernel's period and motion are within a few eps of the exact
values (the accuracy report); here the conversion to degrees and the scaling
by sqrt(l / g) add a few roundings, so 1e-13 relative (about 500 eps) is the
bound, loose enough for any libm, tight enough to catch a wrong unit, a lost
factor 2 or a time that is not in seconds.
"""

import math
import pathlib

import numpy as np
import pytest

import pendula

mpmath = pytest.importorskip("mpmath")

RTOL = 1e-13

#: (length m, g m/s^2, amplitude deg): a classroom pendulum, a long one on the Moon, a short one near the top
CASES = [(1.0, 9.80665, 30.0), (2.5, 1.625, 5.0), (0.2, 9.81, 170.0), (0.75, 9.80665, 90.0)]


def _exact_period(length, g, amp_deg):
    with mpmath.workdps(60):
        # the release angle the pendulum starts from: the double nearest amp_deg in radians
        m = mpmath.sin(mpmath.mpf(math.radians(amp_deg)) / 2) ** 2
        return float(4 * mpmath.sqrt(mpmath.mpf(length) / g) * mpmath.ellipk(m))


def _exact_angle_deg(length, g, amp_deg, t):
    with mpmath.workdps(60):
        k = mpmath.sin(mpmath.mpf(math.radians(amp_deg)) / 2)
        w = mpmath.sqrt(mpmath.mpf(g) / length)
        return [float(mpmath.degrees(2 * mpmath.asin(k * mpmath.ellipfun("cd", w * mpmath.mpf(float(ti)), k ** 2))))
                for ti in t]


@pytest.mark.parametrize("length,g,amp", CASES)
def test_period_against_4K_in_mpmath(length, g, amp):
    p = pendula.Pendulum(length, g=g, amplitude_deg=amp)
    assert p.period == pytest.approx(_exact_period(length, g, amp), rel=RTOL)
    assert p.frequency == pytest.approx(1.0 / _exact_period(length, g, amp), rel=RTOL)


def test_small_swings_have_galileos_period():
    # at 0.01 degrees T / T0 - 1 = theta0^2 / 16 = 1.9e-9: the exact period is T0 to that
    p = pendula.Pendulum(0.994, amplitude_deg=0.01)
    t0 = 2 * math.pi * math.sqrt(0.994 / 9.80665)
    assert p.small_angle_period == pytest.approx(t0, rel=1e-15)
    assert p.period == pytest.approx(t0, rel=2.5e-9)
    assert p.period > t0


def test_the_seconds_pendulum_beats_seconds():
    """A 0.994 m pendulum at standard gravity takes about one second a swing (2 s a period)."""
    assert pendula.Pendulum(0.994, amplitude_deg=1.0).period == pytest.approx(2.0, abs=2e-3)


@pytest.mark.parametrize("length,g,amp", CASES)
def test_motion_in_degrees_and_seconds_against_mpmath_cd(length, g, amp):
    p = pendula.Pendulum(length, g=g, amplitude_deg=amp)
    rng = np.random.default_rng(20260)
    t = np.concatenate([[0.0, p.period / 4, p.period / 2, p.period], rng.uniform(-3, 3, 12) * p.period])
    sw = p.motion(t)
    ref = np.array(_exact_angle_deg(length, g, amp, t))
    assert np.allclose(sw.angle, ref, rtol=0, atol=RTOL * 180 * 4)
    assert sw.angle[0] == pytest.approx(amp, rel=1e-15)
    assert sw.angle[2] == pytest.approx(-amp, rel=RTOL)
    # angular velocity in deg/s: energy conservation, v^2 / 2 = (g / l)(cos theta - cos theta0), in degrees
    w2 = g / length
    vel = np.sqrt(2 * w2 * np.maximum(np.cos(np.radians(ref)) - math.cos(math.radians(amp)), 0.0))
    assert np.allclose(np.abs(sw.angular_velocity), np.degrees(vel), rtol=0,
                       atol=1e-9 * math.degrees(math.sqrt(w2)))


def test_the_scene_is_eps_g_over_l_in_seconds():
    p = pendula.Pendulum(2.0, g=9.0, amplitude_deg=60.0, damping=0.25)
    assert p.scene.eps == 4.5 and p.scene.damping == 0.25
    assert p.scene.theta0 == math.radians(60.0)
    # the swing's trajectory is the library's, in radians, on the same clock
    sw = p.motion([0.0, 1.0, 2.0])
    assert np.array_equal(sw.trajectory.t, sw.t)
    assert np.array_equal(np.degrees(sw.trajectory.theta), sw.angle)


def test_damping_in_inverse_seconds_decays_as_exp_minus_beta_t_over_2():
    """Small swings of the damped pendulum: theta = A exp(-beta t / 2) cos(w t) + ..., w^2 = g / l - beta^2 / 4."""
    beta = 0.2
    p = pendula.Pendulum(1.0, amplitude_deg=0.5, damping=beta)
    t = np.linspace(0.0, 20.0, 2001)
    sw = p.motion(t)
    w = math.sqrt(9.80665 - beta ** 2 / 4)
    lin = 0.5 * np.exp(-beta * t / 2) * (np.cos(w * t) + beta / (2 * w) * np.sin(w * t))
    # the nonlinearity at 0.5 degrees shifts the angle by about theta0^2 / 16 of a swing: < 1e-4 of 0.5 degrees
    assert np.max(np.abs(sw.angle - lin)) < 2e-4 * 0.5 * 20


def test_damped_pendulum_has_no_period_but_says_why():
    p = pendula.Pendulum(1.0, amplitude_deg=10.0, damping=0.1)
    with pytest.raises(ValueError, match="numerical_period"):
        p.period
    assert "damping 0.1/s" in repr(p)


def test_released_at_180_degrees_it_falls_off_the_top_after_a_long_period():
    """180 degrees is the double nearest pi, 1.2e-16 below it: a libration with a long, finite period
    (4 sqrt(l/g) K(m), m = 1 - 3.7e-33), never inf nor NaN."""
    p = pendula.Pendulum(1.0, amplitude_deg=180.0)
    assert p.period == pytest.approx(_exact_period(1.0, 9.80665, 180.0), rel=RTOL)
    assert 40 < p.period < 60


def test_repr_is_one_short_line():
    r = repr(pendula.Pendulum(1.0, amplitude_deg=30.0))
    assert r.startswith("Pendulum(length=1 m") and "period 2.0413 s" in r and "\n" not in r
    sw = pendula.Pendulum(1.0, amplitude_deg=30.0).motion(np.linspace(0, 10, 5001))
    assert len(repr(sw)) < 200 and "5001 samples" in repr(sw)


@pytest.mark.parametrize("kwargs,exc,field", [
    ({"length": 0.0}, ValueError, "length"), ({"length": -1.0}, ValueError, "length"),
    ({"length": "1 m"}, TypeError, "length"), ({"length": 1.0, "g": 0.0}, ValueError, "'g'"),
    ({"length": 1.0, "g": math.nan}, ValueError, "'g'"), ({"length": 1.0, "amplitude_deg": 181.0}, ValueError,
                                                          "amplitude_deg"),
    ({"length": 1.0, "amplitude_deg": -1.0}, ValueError, "amplitude_deg"),
    ({"length": 1.0, "damping": -0.1}, ValueError, "damping"), ({"length": True}, TypeError, "length"),
])
def test_bad_parameters_name_the_field(kwargs, exc, field):
    with pytest.raises(exc, match=field):
        pendula.Pendulum(**kwargs)


def test_bad_times_are_refused():
    p = pendula.Pendulum(1.0, amplitude_deg=10.0)
    with pytest.raises(ValueError, match="t"):
        p.motion([0.0, math.nan])


# ---------------------------------------------------------------- the animation

def test_animate_writes_a_gif_with_one_frame_per_sample(tmp_path):
    PIL = pytest.importorskip("PIL.Image")
    pytest.importorskip("matplotlib")
    import pendula.plot

    tr = pendula.Pendulum(1.0, amplitude_deg=45.0).motion(np.linspace(0.0, 2.0, 12)).trajectory
    out = pendula.plot.animate(tr, tmp_path / "swing.gif", fps=10, dpi=30)
    assert out == tmp_path / "swing.gif"
    with PIL.open(out) as im:
        assert im.format == "GIF" and im.n_frames == 12
    # only the file: no staging folder or temporary file left beside it
    assert sorted(p.name for p in tmp_path.iterdir()) == ["swing.gif"]


def test_animate_thins_to_max_frames(tmp_path):
    PIL = pytest.importorskip("PIL.Image")
    import pendula.plot

    tr = pendula.simulate(pendula.Scene(v0=1.5, t_end=10.0, n_samples=101))
    with PIL.open(pendula.plot.animate(tr, tmp_path / "a.gif", max_frames=10, dpi=20)) as im:
        assert im.n_frames == 10      # every 11th of 101 samples: 0, 11, ..., 99


def test_animate_refuses_an_unknown_suffix_and_bad_arguments(tmp_path):
    import pendula.plot

    tr = pendula.simulate(pendula.Scene(v0=1.0, t_end=1.0, n_samples=3))
    with pytest.raises(ValueError, match="suffix"):
        pendula.plot.animate(tr, tmp_path / "a.avi")
    with pytest.raises(TypeError, match="tr"):
        pendula.plot.animate("not a trajectory", tmp_path / "a.gif")
    with pytest.raises(ValueError, match="fps"):
        pendula.plot.animate(tr, tmp_path / "a.gif", fps=0.0)
    with pytest.raises(FileNotFoundError):
        pendula.plot.animate(tr, tmp_path / "missing" / "a.gif")
    assert list(tmp_path.iterdir()) == []


def test_animate_mp4_needs_ffmpeg_and_says_so(tmp_path, monkeypatch):
    import matplotlib.animation as animation

    import pendula.plot

    tr = pendula.simulate(pendula.Scene(v0=1.0, t_end=1.0, n_samples=3))
    monkeypatch.setattr(animation.writers, "is_available", lambda name: name != "ffmpeg")
    with pytest.raises(RuntimeError, match="ffmpeg"):
        pendula.plot.animate(tr, tmp_path / "a.mp4")
    assert not pathlib.Path(tmp_path / "a.mp4").exists()

"""The spherical pendulum's exact path against independent references.

data/spherical_reference.csv (data/gen_spherical_reference.py) holds mpmath
values at 40 digits from quadratures of the first integrals (no Jacobi
functions, no Carlson integrals): the path at exact double times for seeded
random states in every region (generic, next to the conical orbit, the upper
hemisphere and next to the top, tiny and huge L_z, eps from 1e-2 to 1e2,
t up to 1e12), the polar period and the azimuth advance.  Closed forms: the
conical orbit, Airy's precession rate as the small-amplitude limit, the
planar pendulum's exact path as the limit L_z -> 0.

Tolerances, with the reason: the inputs are exact doubles and the roots are
found in quadruple precision, the phase is carried in double-double and
reduced by whole polar periods, so what is left is a few roundings of the
final values: theta within 4 eps of |theta| and its rate within 4 eps of the
rate's scale (its largest size on the orbit, where a zero crossing leaves no
relative accuracy), the azimuth within 4 eps of max(|phi|, its advance per
period) (its two R_J terms, GSL's, are each good to about 2 eps; the
advance per period is formed in quadruple precision, so it does not grow
with t), phi' within 6 eps (L / (x (2 - x)) gathers the roundings of sn^2
and cn^2 in both factors), periods and advances within 4 eps.  Measured
worst: 3 eps (theta, phi, the rates), 4.4 eps (phi').
"""

import csv
import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import pendula
from conftest import EPS


def reference(data_dir, kind):
    with (data_dir / "spherical_reference.csv").open() as fh:
        rd = csv.DictReader(ln for ln in fh if not ln.startswith("#"))
        return [r for r in rd if r["kind"] == kind]


def _f(r, *keys):
    return [float(r[k]) for k in keys]


def _rate_scale(o):
    """The largest |theta'| and |phi'| on the orbit, from the energy and L_z."""
    kin = o.energy - 2 * o.eps * math.sin(o.theta_min / 2) ** 2
    return math.sqrt(2 * max(kin, 0.0)), abs(o.lz) / math.sin(o.theta_min) ** 2 if o.lz else 0.0


def test_thirty_to_sixty_degrees_published_period_and_apsidal_angle(data_dir):
    exact = [r for r in reference(data_dir, "fact") if r["case"] == "thirty_sixty_exact"][0]
    per, adv = _f(exact, "period", "advance")
    # the generator's own quadrature agrees with the published values (it asserts 1e-12)
    assert abs(per - 3.3829713541618) < 1e-12
    assert abs(math.degrees(adv / 2) - 111.683552423557) < 1e-11
    dbl = [r for r in reference(data_dir, "fact") if r["case"] == "thirty_sixty_doubles"][0]
    th0, td0, pd0, eps, per_d, adv_d = _f(dbl, "theta0", "theta_dot0", "phi_dot0", "eps", "period", "advance")
    o = pendula.spherical_orbit(th0, td0, pd0, eps)
    assert abs(o.period / per_d - 1) <= 4 * EPS
    assert abs(o.azimuth_advance / adv_d - 1) <= 4 * EPS
    assert abs(o.apsidal_angle / (adv_d / 2) - 1) <= 4 * EPS
    assert math.degrees(o.theta_min) == pytest.approx(30, abs=1e-12)
    assert math.degrees(o.theta_max) == pytest.approx(60, abs=1e-12)


CASES = ["generic", "near_conical", "near_conical_moving", "upper_hemisphere", "near_top", "tiny_lz",
         "huge_lz", "eps"]


@pytest.mark.parametrize("case", CASES)
def test_path_against_mpmath_quadrature(data_dir, case):
    rows = [r for r in reference(data_dir, "path") if r["case"] == case]
    assert len(rows) >= 6
    worst = {"theta": 0.0, "phi": 0.0, "theta_dot": 0.0, "phi_dot": 0.0, "period": 0.0, "advance": 0.0}
    for r in rows:
        th0, td0, pd0, eps, t = _f(r, "theta0", "theta_dot0", "phi_dot0", "eps", "t")
        th, ph, thd, phd, per, adv = _f(r, "theta", "phi", "theta_dot", "phi_dot", "period", "advance")
        o = pendula.spherical_orbit(th0, td0, pd0, eps)
        p = o.path([t])
        s_th, s_ph = _rate_scale(o)
        worst["theta"] = max(worst["theta"], abs(p.theta[0] - th) / abs(th) / EPS)
        worst["phi"] = max(worst["phi"], abs(p.phi[0] - ph) / max(abs(ph), abs(adv)) / EPS)
        worst["theta_dot"] = max(worst["theta_dot"], abs(p.theta_dot[0] - thd) / s_th / EPS)
        worst["phi_dot"] = max(worst["phi_dot"], abs(p.phi_dot[0] - phd) / max(abs(phd), 1e-300) / EPS)
        worst["period"] = max(worst["period"], abs(o.period / per - 1) / EPS)
        worst["advance"] = max(worst["advance"], abs(o.azimuth_advance / adv - 1) / EPS)
    # phi' = L / (x (2 - x)) gathers the roundings of sn^2 and cn^2 in both factors: 6 eps
    assert max(v for k, v in worst.items() if k != "phi_dot") <= 4.0 and worst["phi_dot"] <= 6.0, worst


def test_no_drift_at_t_1e12(data_dir):
    rows = [r for r in reference(data_dir, "path") if abs(float(r["t"])) == 1e12]
    assert len(rows) >= 10
    for r in rows:
        th0, td0, pd0, eps, t, th, ph = _f(r, "theta0", "theta_dot0", "phi_dot0", "eps", "t", "theta", "phi")
        p = pendula.spherical_orbit(th0, td0, pd0, eps).path([t])
        assert abs(p.theta[0] - th) <= 4 * EPS * abs(th)
        assert abs(p.phi[0] - ph) <= 4 * EPS * abs(ph)


def test_planar_motion_is_the_planar_exact_path():
    t = np.linspace(-30, 30, 601)
    for th0, v0 in [(0.3, 0.0), (1.0, 1.2), (2.5, -0.4), (0.0, 2.5), (0.0, 2.0)]:
        p = pendula.spherical_orbit(th0, v0, 0.0).path(t, phi0=0.7)
        theta, v = pendula.exact_motion(th0, v0, 1.0, t)
        assert np.array_equal(p.theta, theta) and np.array_equal(p.theta_dot, v)
        assert np.all(p.phi == 0.7) and np.all(p.phi_dot == 0.0)


@pytest.mark.parametrize("lz", [1e-40, 1e-20, -1e-20])
def test_planar_limit_within_2_eps_of_the_planar_path(lz):
    """L_z -> 0: the bob passes next to the bottom, the azimuth jumps by pi
    there, and the position is the planar pendulum's to 2 eps (L_z <= 1e-20:
    the true departures, the closest approach theta_min and the apsides'
    turning, are O(L_z), below an ulp)."""
    t = np.linspace(-25, 25, 2001)
    for th0, v0 in [(0.4, 0.0), (1.3, 0.5), (2.8, 0.1), (1.0, 2.3)]:
        o = pendula.spherical_orbit(th0, v0, lz / math.sin(th0) ** 2)
        p = o.path(t)
        theta, v = pendula.exact_motion(th0, v0, 1.0, t)
        x_sph = np.sin(p.theta) * np.cos(p.phi)
        y_sph = np.sin(p.theta) * np.sin(p.phi)
        # the true departures: the closest approach to the bottom, and the apsides' turning
        # (Airy's precession, O(L_z) per period) times the swing's size
        slack = 4 * o.theta_min + 2 * math.sin(o.theta_max) * np.abs(t / o.period) * abs(
            o.azimuth_advance - math.copysign(math.pi, lz))
        # (the planar angle, unwrapped in a rotation, is itself good to 2 eps of |theta|)
        assert np.all(np.abs(x_sph - np.sin(theta)) <= 2 * EPS * np.maximum(1, np.abs(theta)) + slack)
        # y measures the azimuth's error, 4 eps of its scale pi (the x above is first order in it)
        assert np.all(np.abs(y_sph) <= 4 * EPS * math.pi * np.abs(np.sin(p.theta)) + slack)
        # the polar angle is the planar angle's distance from the bottom (wrapped for a rotation)
        d = np.abs(np.angle(np.exp(1j * theta)))
        assert np.all(np.abs(p.theta - d) <= 2 * EPS * np.maximum(1, np.abs(theta)) + slack)


def test_conical_orbit_closed_form():
    """theta stays put, phi grows as phi' t; the polar period and apsidal angle
    are those of the small oscillations about the cone:
    Omega^2 = eps (1 + 3 cos^2) / cos (Landau and Lifshitz, section 14)."""
    for th0, eps in [(math.pi / 3, 1.0), (0.2, 4.0), (1.5, 0.25)]:
        w = math.sqrt(eps / math.cos(th0))
        o = pendula.spherical_orbit(th0, 0.0, w, eps)
        om = math.sqrt(eps * (1 + 3 * math.cos(th0) ** 2) / math.cos(th0))
        # (the rate is rounded: the orbit is within an ulp of the cone, not on it)
        assert o.theta_min == pytest.approx(th0, rel=4 * EPS) and o.theta_max == pytest.approx(th0, rel=4 * EPS)
        assert o.period == pytest.approx(2 * math.pi / om, rel=8 * EPS)
        assert o.apsidal_angle == pytest.approx(math.pi * w / om, rel=8 * EPS)
        t = np.array([0.0, 1.0, 1e3, 1e6])
        p = o.path(t)
        assert np.all(np.abs(p.theta - th0) <= 4 * EPS * th0)
        assert np.all(np.abs(p.phi - w * t) <= 4 * EPS * np.maximum(w * t, 1))
        assert np.all(np.abs(p.theta_dot) <= 4 * EPS * w)


def test_airy_precession_is_the_small_amplitude_limit():
    """Airy: the apsides of a small ellipse with semi-axes a, b (units of l)
    turn at 3 omega a b / 8; the exact rate differs by O(a^2 + b^2)."""
    for a, ratio in [(0.1, 0.5), (0.03, 0.2), (0.01, 0.7), (0.003, 0.3)]:
        b = ratio * a
        # start at the end of the major axis, moving at the ellipse's speed omega b
        o = pendula.spherical_orbit(math.asin(a), 0.0, b / a)
        aa, bb = math.sin(o.theta_max), math.sin(o.theta_min)
        airy = 3 * aa * bb / 8
        assert abs(o.precession_rate / airy - 1) <= 1.0 * (aa * aa + bb * bb)
    # and the correction shrinks as a^2
    errs = []
    for a in [0.04, 0.02, 0.01]:
        o = pendula.spherical_orbit(math.asin(a), 0.0, 0.5 / math.sqrt(1 - a * a))
        aa, bb = math.sin(o.theta_max), math.sin(o.theta_min)
        errs.append(abs(o.precession_rate / (3 * aa * bb / 8) - 1))
    assert errs[0] / errs[1] == pytest.approx(4, rel=0.05) and errs[1] / errs[2] == pytest.approx(4, rel=0.05)


states = st.tuples(st.floats(0.01, 3.1), st.floats(-3, 3), st.floats(-3, 3).filter(lambda x: abs(x) > 1e-6),
                   st.floats(0.1, 10))


@settings(max_examples=60, deadline=None, derandomize=True)
@given(states)
def test_energy_and_lz_conserved_along_the_path(s):
    th0, td0, pd0, eps = s
    o = pendula.spherical_orbit(th0, td0, pd0, eps)
    p = o.path(np.linspace(-50, 50, 201))
    # each value of the path to 4 eps, carried through the formulas' derivatives (near the
    # top sin(theta) is small and its relative error eps theta / sin(theta) large)
    th, thd, phd = p.theta, p.theta_dot, p.phi_dot
    sn, cs = np.sin(th), np.cos(th)
    d_th = 4 * EPS * th
    tol_e = 8 * EPS * (thd ** 2 + (sn * phd) ** 2 + eps) + np.abs(sn * cs * phd ** 2 + eps * sn) * d_th
    tol_l = 8 * EPS * abs(o.lz) + np.abs(2 * sn * cs * phd) * d_th
    assert np.all(np.abs(p.energy - o.energy) <= tol_e)
    assert np.all(np.abs(p.lz - o.lz) <= tol_l)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(states)
def test_time_reversal(s):
    th0, td0, pd0, eps = s
    t = np.linspace(0, 40, 81)
    o = pendula.spherical_orbit(th0, td0, pd0, eps)
    fwd = o.path(t)
    back = pendula.spherical_orbit(th0, -td0, -pd0, eps).path(-t)
    s_th, _ = _rate_scale(o)
    assert np.all(np.abs(fwd.theta - back.theta) <= 4 * EPS * fwd.theta)
    assert np.all(np.abs(fwd.theta_dot + back.theta_dot) <= 8 * EPS * s_th)
    assert np.all(np.abs(fwd.phi - back.phi) <= 8 * EPS * np.maximum(np.abs(fwd.phi), abs(o.azimuth_advance)))


def test_one_polar_period_later_the_same_state():
    o = pendula.spherical_orbit(0.9, 0.3, -0.8, 2.0)
    t = np.array([0.0, o.period, 1000 * o.period])
    p = o.path(t)
    # the period and t are rounded (half an ulp each): the state moves by its rate times that
    dt = EPS * t
    assert np.all(np.abs(p.theta - 0.9) <= 4 * EPS + 0.3 * dt)
    assert abs(p.phi[1] - o.azimuth_advance) <= 4 * EPS * abs(o.azimuth_advance) + 0.8 * dt[1]
    assert abs(p.phi[2] - 1000 * o.azimuth_advance) <= 4 * EPS * 1000 * abs(o.azimuth_advance) + 0.8 * dt[2]


# ---------------------------------------------------------------- hard cases, each named


def test_pole_with_an_azimuthal_rate_is_undefined():
    with pytest.raises(ValueError, match="phi_dot0 must be 0 at the pole"):
        pendula.spherical_orbit(0.0, 1.0, 0.5)


def test_pole_at_rest_in_azimuth_is_the_planar_swing_through_the_bottom():
    o = pendula.spherical_orbit(0.0, 1.0, 0.0)
    assert o.planar and o.theta_min == 0.0
    p = o.path([0.0, 1.0])
    assert p.theta[0] == 0.0 and p.theta_dot[0] == 1.0


def test_upside_down_double_pi_with_spin_stays_near_the_top():
    # np.pi is 1.2e-16 below pi: sin^2 = 1.5e-32, L_z tiny but resolved
    o = pendula.spherical_orbit(np.pi, 0.0, 1.0)
    assert not o.planar and o.theta_max == pytest.approx(np.pi, abs=1e-15)
    p = o.path([0.0, 5.0, 10.0])
    assert np.all(np.isfinite(p.theta)) and p.theta[0] == pytest.approx(np.pi, abs=4 * EPS)
    assert np.all(p.theta[1:] < p.theta[0])


def test_lz_below_1e_100_is_refused_naming_phi_dot0():
    pendula.spherical_orbit(1.0, 0.5, 1e-95)
    with pytest.raises(ValueError, match="phi_dot0 = 0 for the planar"):
        pendula.spherical_orbit(1.0, 0.5, 1e-101)


def test_huge_rates_are_refused_beyond_1e100():
    pendula.spherical_orbit(1.0, 1e90, 1e90)
    with pytest.raises(ValueError, match="1e100"):
        pendula.spherical_orbit(1.0, 0.0, 1e101)


@pytest.mark.parametrize("kwargs, field", [
    (dict(theta0=-0.1), "theta0"), (dict(theta0=3.2), "theta0"), (dict(theta0=math.nan), "theta0"),
    (dict(theta_dot0=math.inf), "theta_dot0"), (dict(phi_dot0=math.nan), "phi_dot0"),
    (dict(eps=0.0), "eps"), (dict(eps=-1.0), "eps"), (dict(eps=math.inf), "eps")])
def test_bad_state_names_the_field(kwargs, field):
    args = dict(theta0=1.0, theta_dot0=0.2, phi_dot0=0.3, eps=1.0)
    args.update(kwargs)
    with pytest.raises(ValueError, match=field):
        pendula.spherical_orbit(**args)


def test_bad_arguments_of_the_path_name_the_field():
    o = pendula.spherical_orbit(1.0, 0.2, 0.3)
    with pytest.raises(ValueError, match="phi0"):
        o.path([1.0], phi0=math.nan)
    with pytest.raises(TypeError, match="t must be"):
        o.path("1.0")
    with pytest.raises(ValueError, match="length"):
        o.path([1.0]).position(-1.0)
    with pytest.raises(TypeError, match="theta0"):
        pendula.spherical_orbit("1", 0.0, 0.0)


def test_infinite_time_gives_nan_and_a_warning():
    o = pendula.spherical_orbit(1.0, 0.2, 0.3)
    with pytest.warns(RuntimeWarning, match="infinite"):
        p = o.path([1.0, math.inf])
    assert np.isfinite(p.theta[0]) and np.isnan(p.theta[1]) and np.isnan(p.phi[1])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert np.isnan(o.path([math.nan]).theta[0])


wild = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.sampled_from(
    [0.0, -0.0, 5e-324, 1e-310, 1e308, -1e308, 1.0, math.pi, np.pi, 2.0, 1e-101, 1e101]))


@settings(max_examples=150, deadline=None, derandomize=True)
@given(wild, wild, wild, wild, wild)
def test_fuzz_any_floats_give_a_path_or_a_named_error(th0, td0, pd0, eps, t):
    """Never a crash, a hang or a silently wrong number: a finite path (or NaN with a
    warning at an infinite time), or a ValueError naming a field."""
    try:
        o = pendula.spherical_orbit(th0, td0, pd0, eps)
    except ValueError as exc:
        assert any(f in str(exc) for f in ("theta0", "theta_dot0", "phi_dot0", "eps"))
        return
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        p = o.path([0.0, t])
    assert p.theta[0] == pytest.approx(th0, rel=8 * EPS, abs=1e-300) or (o.planar and th0 == 0.0)
    values = np.array([p.theta, p.phi, p.theta_dot, p.phi_dot])
    if not np.all(np.isfinite(values)):
        # NaN only at t = 1: an infinite time or beyond 2**48 half periods, with a warning
        assert np.all(np.isfinite(values[:, 0])) and np.all(np.isnan(values[:, 1]))
        assert math.isnan(t) or any(x.category is RuntimeWarning for x in w)


def test_plot_marks_the_published_apsidal_angle_between_a_lowest_and_the_next_highest_point(data_dir):
    """pendula.plot.spherical on the orbit between 30 and 60 degrees: the rays of its view from above end at
    the bob's horizontal distance sin 30 and sin 60 degrees (a lowest and a highest point), the angle between
    them is the published apsidal angle 111.683552423557 degrees (mpmath quadrature), and so is the arc's."""
    pytest.importorskip("matplotlib")
    import matplotlib.pyplot as plt

    import pendula.plot

    dbl = [r for r in reference(data_dir, "fact") if r["case"] == "thirty_sixty_doubles"][0]
    th0, td0, pd0, eps = _f(dbl, "theta0", "theta_dot0", "phi_dot0", "eps")
    for sign in (1.0, -1.0):      # either sense of turning
        o = pendula.spherical_orbit(th0, td0, sign * pd0, eps)
        top, side = pendula.plot.spherical(o, periods=2.0, samples=400)
        rays = [ln for ln in top.get_lines() if ln.get_label().startswith("to ")]
        assert [ln.get_label() for ln in rays] == ["to a lowest point", "to the next highest point"]
        ends = [(ln.get_xdata()[1], ln.get_ydata()[1]) for ln in rays]
        # theta is quadratic in the time error at a turning point: the radii to 1e-12
        assert math.hypot(*ends[0]) == pytest.approx(0.5, abs=1e-12)
        assert math.hypot(*ends[1]) == pytest.approx(math.sqrt(3) / 2, abs=1e-12)
        turn = math.atan2(ends[1][1], ends[1][0]) - math.atan2(ends[0][1], ends[0][0])
        turn = (turn + math.pi) % (2 * math.pi) - math.pi
        # the turning point found to ~1e-9 in time, the azimuth moving at most ~2 per unit time
        assert math.degrees(sign * turn) % 360 == pytest.approx(111.683552423557, abs=1e-6)
        arc = [ln for ln in top.get_lines() if ln.get_label() == "_apsidal angle"][0]
        ang = np.unwrap(np.arctan2(arc.get_ydata(), arc.get_xdata()))
        assert math.degrees(sign * (ang[-1] - ang[0])) == pytest.approx(111.683552423557, abs=1e-6)
        heights = sorted(ln.get_ydata()[0] for ln in side.get_lines() if ln.get_linestyle() == "--")
        assert heights == pytest.approx([-math.cos(math.pi / 6), -math.cos(math.pi / 3)], abs=1e-12)
        plt.close("all")


def test_plot_refuses_what_is_not_an_orbit_naming_it():
    pytest.importorskip("matplotlib")
    import pendula.plot

    o = pendula.spherical_orbit(0.6, 0.0, 1.0)
    with pytest.raises(TypeError, match="orbit"):
        pendula.plot.spherical(o.path([0.0]))
    with pytest.raises(ValueError, match="periods"):
        pendula.plot.spherical(o, periods=0.0)
    with pytest.raises(TypeError, match="axs"):
        pendula.plot.spherical(o, axs="top")

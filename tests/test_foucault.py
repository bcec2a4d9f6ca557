"""The Foucault pendulum: the spherical pendulum in the frame of the turning Earth.

References, independent of the integrated path:

* at a pole the Earth's frame turns about the vertical only, so the inertial
  motion is exactly the spherical pendulum: the path equals pendula's exact
  spherical solution (elliptic functions, checked against mpmath in
  tests/test_spherical.py) turned by -Omega_E t;
* at the equator a swing in the east-west plane stays in it (the Coriolis
  force of a northward Omega on a velocity in that plane lies in the plane):
  no precession at all;
* the precession split: Coriolis -Omega_E sin(latitude) in closed form, Airy's
  part from the exact spherical solution, whose small-ellipse limit is Airy's
  3 omega a b / 8 (tests/test_spherical.py); what is left (the horizontal
  Earth rate, the centrifugal force) is O(Omega_E^2 / omega) per unit of the
  Coriolis rate, below 1e-5 of it for a museum pendulum.
"""

import math

import numpy as np
import pytest

import pendula


@pytest.mark.parametrize("pole", [90.0, -90.0])
def test_path_at_a_pole_is_the_exact_spherical_path_turned(pole):
    # an exaggerated Earth rate (0.05 of omega) so that the frame matters; g = l = 1
    rate = 0.05
    fp = pendula.FoucaultPendulum(latitude=pole, length=1.0, g=1.0, earth_rate=rate)
    oz = rate * math.copysign(1.0, pole)
    rng = np.random.default_rng(42)
    t = np.sort(rng.uniform(0.0, 60.0, 25))
    for th0, thd0, phd0 in [(0.4, 0.0, 0.0), (0.9, 0.3, 0.5), (0.2, -0.1, -0.8)]:
        run = fp.simulate(t, th0, azimuth=0.3, theta_dot0=thd0, phi_dot0=phd0, rtol=1e-13)
        path = pendula.spherical_orbit(th0, thd0, phd0 + oz, 1.0).path(t, phi0=0.3)
        phi = path.phi - oz * t
        want = np.stack([np.sin(path.theta) * np.cos(phi), np.sin(path.theta) * np.sin(phi), -np.cos(path.theta)])
        got = np.stack([run.x, run.y, run.z])
        # DOP853 at 1e-13 over 60 time units (about 10 swings): 1e-10 of the length
        assert np.max(np.abs(got - want)) < 1e-10, (th0, thd0, phd0)
        assert np.max(np.abs(run.constraint_error.values)) < 1e-11


def test_equator_east_west_swing_does_not_precess():
    fp = pendula.FoucaultPendulum(latitude=0.0, length=67.0)
    run = fp.simulate(np.linspace(0, 3000, 301), 0.1, azimuth=0.0)
    assert np.max(np.abs(run.y.values)) < 1e-12 * 67.0
    pr = fp.precession(0.1, swings=50)
    assert pr.coriolis == 0.0 and pr.airy == 0.0
    assert abs(pr.measured) < 1e-15


@pytest.mark.parametrize("latitude", [48.85, -33.9, 12.0, 71.0])
def test_precession_is_coriolis_plus_exact_airy(latitude):
    # the Pantheon's 67 m pendulum at 0.05 rad, released from rest or opened into an ellipse (seeded):
    # the residual is below 1e-5 of the Coriolis rate (measured 4e-7 at 48.85 degrees)
    rng = np.random.default_rng(int(latitude * 100) % 2**32)
    fp = pendula.FoucaultPendulum(latitude=latitude, length=67.0)
    for phd in [0.0, rng.uniform(-2e-3, 2e-3)]:
        pr = fp.precession(0.05, phi_dot0=phd, swings=100)
        assert pr.coriolis == -pendula.systems.foucault.EARTH_RATE * math.sin(math.radians(latitude))
        assert abs(pr.residual) < 1e-5 * abs(pr.coriolis), pr
        if phd != 0.0:       # an ellipse: the Airy part is no longer negligible
            assert abs(pr.airy) > 0.005 * abs(pr.coriolis)


def test_airy_part_of_a_release_from_rest_is_airys_formula():
    # released from rest in the Earth's frame, the bob has in the non-turning frame the azimuthal rate
    # Omega_z: a thin ellipse of semi-axes a = theta0 l and b ~ Omega_z theta0 l / omega, so the Airy part
    # tends to 3 omega a b / (8 l^2) = 3 Omega_z theta0^2 / 8 (relative error O(theta0^2))
    fp = pendula.FoucaultPendulum(latitude=48.85, length=67.0)
    oz = fp.earth_rate * math.sin(math.radians(48.85))
    for th0 in [0.01, 0.03]:
        pr = fp.precession(th0, swings=20)
        assert abs(pr.airy / (3 * oz * th0 ** 2 / 8) - 1) < 2 * th0 ** 2


def test_damped_swing_decays_at_half_the_drag_rate():
    gamma = 1e-3
    fp = pendula.FoucaultPendulum(latitude=45.0, length=10.0, damping=gamma)
    per = fp.period
    t = np.arange(0, 400 * 64 + 1) * (per / 64)
    run = fp.simulate(t, 0.01)
    late = np.max(run.theta.values[-64:])
    # the small-swing amplitude decays as exp(-gamma t / 2) (the drag's shift of the frequency is
    # O(gamma^2), the sampling error of the maximum O((2 pi / 64)^2 / 8) = 1e-3 relative)
    assert abs(late / (0.01 * math.exp(-gamma * t[-1] / 2)) - 1) < 2e-3


def test_anisotropic_support_splits_the_frequencies():
    # no Earth rate: a small swing east has omega^2 = (g/l)(1 + ae), north (g/l)(1 + an); the period is
    # read from the zero crossings of x (or y), checked to 1e-5 (the amplitude's shift is ~theta0^2/16 = 6e-7)
    ae, an = 0.02, -0.01
    fp = pendula.FoucaultPendulum(latitude=45.0, length=2.0, g=9.81, earth_rate=0.0, anisotropy=(ae, an))
    for az, a, comp in [(0.0, ae, "x"), (math.pi / 2, an, "y")]:
        w = math.sqrt(9.81 / 2.0 * (1 + a))
        t = np.linspace(0.0, 20 * 2 * math.pi / w, 20001)
        u = getattr(fp.simulate(t, 0.003, azimuth=az), comp).values
        i = np.flatnonzero((u[:-1] > 0) & (u[1:] <= 0))
        tz = t[i] - u[i] * (t[i + 1] - t[i]) / (u[i + 1] - u[i])
        period = np.mean(np.diff(tz))
        assert abs(period * w / (2 * math.pi) - 1) < 1e-5, (comp, period)
    with pytest.raises(ValueError, match="anisotropy"):
        pendula.FoucaultPendulum(latitude=10.0, anisotropy=(-1.0, 0.0))
    with pytest.raises(ValueError, match="anisotropy"):
        pendula.FoucaultPendulum(latitude=10.0, anisotropy=(0.1, 0.2, 0.3))


def test_bad_input_names_the_field():
    for lat in (91.0, -90.5):
        with pytest.raises(ValueError, match="latitude"):
            pendula.FoucaultPendulum(latitude=lat)
    with pytest.raises(ValueError, match="latitude"):
        pendula.FoucaultPendulum(latitude=math.nan)
    with pytest.raises(ValueError, match="length"):
        pendula.FoucaultPendulum(latitude=10.0, length=-1.0)
    with pytest.raises(ValueError, match="damping"):
        pendula.FoucaultPendulum(latitude=10.0, damping=-0.1)
    fp = pendula.FoucaultPendulum(latitude=10.0)
    with pytest.raises(ValueError, match="phi_dot0"):
        fp.simulate([0.0, 1.0], 0.0, phi_dot0=0.1)
    with pytest.raises(ValueError, match="theta0"):
        fp.precession(0.0)
    with pytest.raises(ValueError, match="theta0"):
        fp.simulate([0.0, 1.0], 2.0)

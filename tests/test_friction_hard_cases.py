"""Hard cases of friction_turning_points, each named for its case, against mpmath.

The reference is written from the energy balance alone: the turning point is mpmath's root of
K(theta) = v_a^2/2 + eps (cos theta - cos theta_a) + (tau - mu s)(theta - theta_a) at 40 digits,
and the time of the stretch is the integral of dtheta / sqrt(2 K) by tanh-sinh, the interval
split at theta_a + s x0 4^k (x0 = v_a^2 / (2 |K'(theta_a)|), where 1/v has its near singularity
behind a slow start), at the middle and at x_b/2 4^-k before the turning point, where 1/v has
its inverse square root (there K is formed as (theta - theta_b) times its divided difference,
so that it keeps its relative accuracy).  Each reference is computed at 30 and at 40 digits (more by the digits of v0^2 for a slow start), and the two
must agree to 1e-22.  Errors are relative (the time) and in eps.
"""

import math

import numpy as np
import pytest

import pendula
from conftest import EPS

mp = pytest.importorskip("mpmath")


def first_turning_mp(theta0, v0, eps, mu, tau=0.0, dps=40):
    """(time, angle) of the first turning point after the start (v0 /= 0) at dps digits."""
    with mp.workdps(dps):
        e, t_, m_ = mp.mpf(eps), mp.mpf(tau), mp.mpf(mu)
        a, va = mp.mpf(theta0), mp.mpf(v0)
        s = mp.sign(va)

        def K(th):
            return va**2 / 2 + e * (mp.cos(th) - mp.cos(a)) + (t_ - m_ * s) * (th - a)
        dK = s * (-e * mp.sin(a) + t_ - m_ * s)          # dK/dx at the start, x = s (theta - a)
        # bracket the first zero of K along s: below the turning point K > 0
        x, step = mp.mpf(0), mp.mpf(1) / 128
        if dK < 0 and va**2 / 2 / -dK < step:
            step = va**2 / -dK                           # a turning point closer than the step
        while K(a + s * (x + step)) > 0:
            x += step
        xb = mp.findroot(lambda y: K(a + s * y), (x, x + step), solver="anderson")
        pts = [mp.mpf(0)]
        x0 = va**2 / (2 * abs(dK)) if dK != 0 else xb
        k = 0
        while x0 * 4**k < xb / 2:
            if x0 * 4**k > 0:
                pts.append(x0 * 4**k)
            k += 1
        pts += [xb / 2, xb]
        b = a + s * xb

        def K_end(z):
            # K at the distance z before the turning point, K(theta) - K(b) written as
            # (theta - b) times the divided difference, so that it keeps its relative accuracy
            # where tanh-sinh samples within 1e-30 of the turning point
            return s * z * (e * mp.sin(b - s * z / 2) * mp.sinc(z / 2) - t_ + m_ * s)
        T = mp.quad(lambda y: 1 / mp.sqrt(2 * K(a + s * y)), pts[:-1]) \
            + mp.quad(lambda z: 1 / mp.sqrt(2 * K_end(z)), [0] + [xb / 2 / 4**k for k in range(24, -1, -1)])
        return T, b


def reference(theta0, v0, eps, mu, tau=0.0):
    # digits for the distance to a turning point as close as v0^2 (K cancels to v0^2 there)
    extra = int(max(0.0, -2.0 * math.log10(abs(v0))))
    t1, a1 = first_turning_mp(theta0, v0, eps, mu, tau, 30 + extra)
    t2, a2 = first_turning_mp(theta0, v0, eps, mu, tau, 40 + extra)
    assert abs(t1 - t2) <= mp.mpf("1e-22") * abs(t2) and abs(a1 - a2) <= mp.mpf("1e-22") * (1 + abs(a2))
    return t2, a2


def kappa(theta0, v0, eps, mu, tau=0.0):
    """The condition number of the starting acceleration g0 = s (tau - eps sin theta0) - mu in its
    terms: where friction just holds against gravity, g0 is a small difference, and a correctly
    rounded sin theta0 (half an ulp) is already kappa/2 eps of it, and of a time set by it."""
    s = math.copysign(1.0, v0)
    return (abs(eps * math.sin(theta0)) + abs(tau) + mu) / abs(s * (tau - eps * math.sin(theta0)) - mu)


def time_bound(*scene):
    """4 eps plus what the rounding of the starting force can cause (kappa / 2 eps)."""
    return 4.0 + 0.5 * kappa(*scene)


def errors(theta0, v0, eps, mu, tau=0.0):
    sc = pendula.Scene(theta0=theta0, v0=v0, eps=eps, friction=mu, torque=tau)
    tp = pendula.friction_turning_points(sc, max_points=1)
    T, A = reference(theta0, v0, eps, mu, tau)
    e_t = abs(float((mp.mpf(tp.times[0]) - T) / T)) / EPS
    e_a = abs(float(mp.mpf(tp.angles[0]) - A)) / max(1.0, abs(float(A))) / EPS
    return e_t, e_a


def slow_start_scenes(n, seed):
    """Seeded scenes started with a small speed (1e-12 to 1e-2) in any direction."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        eps = float(np.exp(rng.uniform(math.log(0.1), math.log(3.0))))
        mu = float(rng.uniform(0.01, 0.5)) * eps
        th0 = float(rng.uniform(-3.0, 3.0))
        v0 = float(rng.choice([-1, 1]) * np.exp(rng.uniform(math.log(1e-12), math.log(1e-2))))
        out.append((th0, v0, eps, mu))
    return out


def test_friction_slow_start_first_turning_point():
    """A start with speed 2.7e-6 where the force speeds the bob up: "GSL's root finder or
    quadrature failed" (QAWS on 1/sqrt(v0^2 + 2 g x), whose singularity lies 1.8e-11 behind the
    start; 43 of 54 such scenes failed).  Now the root is found in the distance travelled and the
    first half integrated in pieces graded geometrically from that distance.  The first turning
    time within 4 eps relative plus kappa/2 (time_bound), the angle within 4 eps."""
    sc = (-2.670108716062698, 2.7104744231518978e-06, 0.7310579414162125, 0.12479919326948863)
    e_t, e_a = errors(*sc)
    assert e_t <= time_bound(*sc) and e_a <= 4


def test_friction_slow_starts_hunted():
    """Fresh seeded slow starts (speed 1e-12 to 1e-2, either direction, either sign of the
    force): every one answered, the first turning time within 4 eps relative plus kappa/2, the
    angle within 4 eps (a turning point 1e-11 away keeps its relative accuracy: the root is found in the
    distance travelled, not in theta)."""
    for sc in slow_start_scenes(12, 20261203):
        e_t, e_a = errors(*sc)
        assert e_t <= time_bound(*sc) and e_a <= 4, (sc, e_t, e_a)


def test_friction_moving_start_first_turning_time():
    """From a moving start the first turning time was off by up to 3e5 eps relative (QAWS on a
    nearly singular integrand, with the turning point's absolute error in theta); seeded starts
    at speeds 0.01 to 3, with and without a torque below friction: within 4 eps plus kappa/2."""
    rng = np.random.default_rng(7)
    for _ in range(8):
        eps = float(rng.uniform(0.3, 3.0))
        mu = float(rng.uniform(0.02, 0.4))
        tau = float(rng.choice([0.0, rng.uniform(-0.9, 0.9) * mu]))
        th0 = float(rng.uniform(-3.0, 3.0))
        v0 = float(rng.choice([-1, 1]) * np.exp(rng.uniform(math.log(0.01), math.log(3.0))))
        e_t, e_a = errors(th0, v0, eps, mu, tau)
        assert e_t <= time_bound(th0, v0, eps, mu, tau) and e_a <= 4, (th0, v0, eps, mu, tau, e_t, e_a)


def test_friction_refusal_names_the_search_window_not_a_torque():
    """A fast bob without torque (v0 = 30, friction 0.001) stops after about 4.5e5 rad; it was
    refused with "the bob never stops: the torque keeps it turning".  Now the refusal says that
    the turning point lies beyond the 2e4 rad computed, and names no torque."""
    with pytest.raises(ValueError) as e:
        pendula.friction_turning_points(pendula.Scene(v0=30.0, friction=0.001))
    msg = str(e.value)
    assert "beyond 2e4 rad" in msg and "torque" not in msg and "never stops" not in msg


def test_friction_runaway_only_with_a_torque_at_least_friction():
    """The runaway is decided by the energy balance: with tau - mu s >= 0 along the motion,
    K(x + 2 pi) >= K(x), so a stretch without a turning point in one turn never has one.  A
    torque above friction with a fast start runs away (and says so); a bob that needs 1e3 rad
    to stop is answered, its stop after the last turning point."""
    with pytest.raises(ValueError, match="torque"):
        pendula.friction_turning_points(pendula.Scene(v0=5.0, friction=0.1, torque=0.2))
    tp = pendula.friction_turning_points(pendula.Scene(v0=10.0, friction=0.05))
    # the energy balance from the start to the first turning point (the distance is about
    # (v0^2 / 2) / mu = 1e3 rad, the cosines within 2 eps of it)
    travel = tp.angles[0] - 0.0
    assert abs(0.5 * 10.0**2 + (math.cos(tp.angles[0]) - 1.0) - 0.05 * travel) < 1e-10 * travel
    assert tp.stuck


def test_friction_turning_point_inside_a_dip_between_search_steps():
    """Started 1.7e-6 rad/s downhill next to the top where friction just exceeds gravity's pull
    (theta0 = 2.998, mu = 0.44 against eps sin theta0 = 0.426): the bob stops 9e-11 rad on, and
    K dips below zero there and rises again well within the search's step of pi/64; the fixed
    steps passed over it, a later root was taken and the quadrature failed through K < 0.  Now
    the steps are bounded by where K could reach zero (|K''| <= eps).  Then the time was 127 eps
    off: sin(theta0 + s x/2) rounded its argument to ulp(theta0), magnified by 1/g0 ~ 68; now by
    the addition theorem.  The time within 4 eps relative plus kappa/2 (kappa = 59 here, measured
    4.5 eps), the angle within 4 eps, and the bob stuck there."""
    sc = (2.9981238546234383, -1.6571581854485232e-06, 2.971693689177179, 0.4396117733943705)
    e_t, e_a = errors(*sc)
    assert e_t <= time_bound(*sc) and e_a <= 4
    tp = pendula.friction_turning_points(pendula.Scene(theta0=sc[0], v0=sc[1], eps=sc[2], friction=sc[3]))
    assert tp.stuck and len(tp.angles) == 1 and abs(tp.angles[0] - sc[0]) < 1e-9

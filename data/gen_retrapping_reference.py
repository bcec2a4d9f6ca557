"""Reference retrapping (homoclinic) torques of the damped pendulum near the damping where they reach 1.

    theta'' = -beta theta' - sin(theta) + tau

Written independently of pendula (no import of it), with scipy alone.  For a damping beta the running
orbit of a torqued pendulum ends, as the torque falls, where it meets the saddle at pi - asin(tau): the
saddle's unstable manifold then just reaches the next saddle (a homoclinic orbit).  As beta grows the
retrapping torque tau_h grows to 1 = eps, where the saddle and the node are born; beyond that damping,
beta*, the running orbit ends at tau = 1 itself, on the saddle-node of the rest points (the saddle and
the node are born on the orbit, and its period diverges), and there is no homoclinic torque below 1.

Method: the two manifolds as graphs v(theta), integrated in the angle (dv/dtheta = -beta - (sin theta -
tau) / v), so that the slow passage by a nearly degenerate saddle costs nothing: the saddle's unstable
manifold from a displacement 1e-3 of the saddle-node gap along its unstable eigenvector (the error of
the linear start lies across the manifold and dies away as it leaves), forward to the section midway
between the next node and the next saddle; the next saddle's stable manifold backward from it to the
same section.  The force near a saddle is written sin theta - sin theta_s = 2 cos((theta + theta_s)/2)
sin((theta - theta_s)/2), free of cancellation (the torque is then sin theta_s, within 1e-16 of tau).
scipy's Radau (implicit: across the manifold the flow contracts at beta / v, stiff by a saddle) at
rtol = 1e-13, atol = 1e-16.  The unstable manifold passes the next saddle when it
reaches the section above the stable one; it falls back when v reaches 0 first (it ends on the node).
1 - tau_h is bisected (on its logarithm, then on itself to 1e-13) between 1e-13 and 0.999, and
beta* on whether the manifold passes at 1 - tau = 1e-13.

Points: 0.5 (against the scipy reference of data/continuation_reference.json), seven dampings up to
beta* (1.15 ... 1.193, where 1 - tau_h falls towards 0) and three seeded random ones in [1.0, beta*).  Output: data/retrapping_reference.json.

Run: python data/gen_retrapping_reference.py   (about seven minutes)

Agreement: at beta = 0.5 it gives 1 - tau_h = 0.40261679915, 5.4e-10 from the time-parametrised bisection
of data/continuation_reference.json (the linear start's error, not yet died away on this weakly stiff
manifold): the points are good to about 1e-9.
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

RTOL = 1e-13
#: the absolute tolerance at the rounding level of the force: the manifold starts where v is 1e-14 or less
ATOL = 1e-16


def passes(beta: float, delta: float) -> bool:
    """Whether the unstable manifold of the saddle at tau = 1 - delta passes the next saddle."""
    tau = 1.0 - delta
    c = math.sqrt(delta * (2.0 - delta))          # cos(asin(tau)), exact for small delta
    thn = math.atan2(tau, c)                      # the node; the saddle is pi - thn, the next 2 pi on
    ths = math.pi - thn
    gap = ths - thn
    nxt = ths + 2 * math.pi
    target = nxt - 0.5 * gap
    lu = 0.5 * (-beta + math.sqrt(beta * beta + 4 * c))
    ls = 0.5 * (-beta - math.sqrt(beta * beta + 4 * c))
    d = 1e-3 * min(gap, 1.0)

    def slope(th, v, centre):
        # (sin th - tau) with tau = sin(centre) (the saddle's angle), written without cancellation
        f = 2.0 * math.cos(0.5 * (th + centre)) * math.sin(0.5 * (th - centre))
        return [-beta - f / v[0]]

    def jac(th, v, centre):
        f = 2.0 * math.cos(0.5 * (th + centre)) * math.sin(0.5 * (th - centre))
        return [[f / (v[0] * v[0])]]

    def fell(th, v, centre):
        return v[0] - 1e-300
    fell.terminal, fell.direction = True, -1
    # Radau (implicit, order 5): across the manifold the flow contracts at beta / v, stiff near a saddle
    up = solve_ivp(slope, (ths + d, target), [lu * d], args=(ths,), method="Radau", jac=jac, rtol=RTOL,
                   atol=ATOL, events=fell)
    if up.status == 1 or up.y[0, -1] <= 0:
        return False                               # v reached 0: it falls back, onto the node
    down = solve_ivp(slope, (nxt - d, target), [-ls * d], args=(nxt,), method="Radau", jac=jac, rtol=RTOL,
                     atol=ATOL)
    assert down.status == 0 and down.y[0, -1] > 0
    return bool(up.y[0, -1] > down.y[0, -1])


def retrapping(beta: float) -> float | None:
    """1 - tau_h by bisection on log(1 - tau); None when the manifold does not pass at 1 - tau = 1e-13."""
    lo, hi = 1e-13, 0.999                          # passes at lo (tau above tau_h), not at hi
    if not passes(beta, lo):
        return None
    assert not passes(beta, hi)
    while hi - lo > 1e-13:
        mid = math.sqrt(lo * hi) if hi > 4 * lo else 0.5 * (lo + hi)
        if passes(beta, mid):
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def beta_star() -> float:
    lo, hi = 1.18, 1.2                             # passes at 1 - tau = 1e-13 for lo, not for hi
    assert passes(lo, 1e-13) and not passes(hi, 1e-13)
    while hi - lo > 1e-12:
        mid = 0.5 * (lo + hi)
        if passes(mid, 1e-13):
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def main():
    t0 = time.time()
    bstar = beta_star()
    print(f"beta* = {bstar!r}")
    rng = np.random.default_rng(20261203)
    betas = [0.5, 1.15, 1.185, 1.188, 1.19, 1.191, 1.192, 1.193] + sorted(rng.uniform(1.0, bstar, 3).tolist())
    points = []
    for b in betas:
        d = retrapping(b)
        points.append({"damping": b, "torque": 1.0 - d, "one_minus_torque": d})
        print(f"beta = {b!r}: 1 - tau_h = {d!r}  ({time.time() - t0:.0f} s)", flush=True)
    data = {"equation": "theta'' = -beta theta' - sin(theta) + tau",
            "method": "scipy DOP853 rtol=atol=1e-13 on the saddle's unstable manifold (displacement 1e-6 of the "
                      "saddle-node gap); bisection on whether it passes the next saddle",
            "beta_star": bstar, "retrapping": points}
    path = Path(__file__).with_name("retrapping_reference.json")
    path.write_text(json.dumps(data, indent=1) + "\n")
    print(f"wrote {path} in {time.time() - t0:.0f} s")


if __name__ == "__main__":
    main()

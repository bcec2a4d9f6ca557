"""Shapiro plateaus of the hysteretic 10 uA / 1 pF / 30 ohm junction at 10 GHz: an independent reference.

The RCSJ junction in reduced units (time 1 / omega_p, currents in I_c),
theta'' + beta theta' + sin(theta) = i + a cos(Omega t), written here from
the CODATA constants and the equation alone (pendula is not imported),
integrated by the classical fourth-order Runge-Kutta method with a fixed
step of one drive period T = 2 pi / Omega over STEPS (numpy, all plateaus
at once, one lane each).

A plateau n of the drive a is the range of bias over which the phase-locked
orbit of rotation number n (n turns per drive period) persists, followed by
continuation from a bias i0 inside it, up and down:

* the locked orbit at i0: from rest-like starts (theta0 on 16 phases,
  v0 = n Omega), iterated 600 periods; the first start whose stroboscopic
  phase has no slip over the last 300 periods (below) is on the plateau;
* continuation: the bias moves by DELTA I_c at a time, AHEAD biases at
  once, each started from the last locked state and run PERIODS periods;
  locked when x_k = theta_k - 2 pi n k stays within a band narrower than
  2 pi over the last 3 PERIODS / 4 and ends within pi of where it began (a
  phase slip moves it by 2 pi); the first unlocked one ends the
  continuation;
* the edge: between the last locked bias and the first unlocked one,
  bisected BISECTIONS times, each trial started from the last locked state
  and run 2 PERIODS periods.

A bias a distance mu past a saddle-node edge slips once per about
pi / sqrt(mu) periods, so a slip-free window of P periods places the edge
within about (pi / P)^2 I_c (2e-4 at P = 225) on the locked side: below the
resolution of the I-V grids that are checked against it (0.005 I_c).
The integration's own error: the same run at 384 steps per period
(--steps 384 --raw FILE), then --combine FILE stores the largest change
of an edge as ``edge_step_change``.

Run: python data/gen_junction_plateaus.py; python data/gen_junction_plateaus.py --steps 384 --raw /tmp/p384.json;
     python data/gen_junction_plateaus.py --combine /tmp/p384.json   (each a few minutes on one core)
"""

import json
import math
import pathlib
import platform
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE / "junction" / "rcsj_plateaus.json"

H_PLANCK = 6.62607015e-34
E_CHARGE = 1.602176634e-19
PHI0 = H_PLANCK / (2 * E_CHARGE)
IC, R, C, F = 10e-6, 30.0, 1e-12, 10e9
OMEGA_P = math.sqrt(2 * math.pi * IC / (PHI0 * C))
BETA = 1.0 / (OMEGA_P * R * C)
OMEGA = 2 * math.pi * F / OMEGA_P

# (rf current A, step n, a bias inside the plateau A): one plateau for each of n = 1 ... 6
PLATEAUS = [(11e-6, 1, 0.7e-6), (13e-6, 2, 1.45e-6), (20e-6, 3, 2.1e-6), (6e-6, 4, 4.3e-6),
            (9e-6, 5, 3.1e-6), (10e-6, 6, 4.1e-6)]
DELTA = 0.002          # continuation step, I_c
PERIODS = 300          # periods per continuation step
AHEAD = 4              # continuation biases run at once per lane
BISECTIONS = 6


def run(state, tau, amp, periods, steps):
    """Iterate the stroboscopic map of every lane: returns the end state and theta at each period."""
    th, v = state[0].copy(), state[1].copy()
    h = 2 * math.pi / OMEGA / steps
    wt = OMEGA * h
    out = np.empty((periods, th.size))

    def acc(x, y, t):
        return -np.sin(x) - BETA * y + tau + amp * math.cos(OMEGA * t)
    for k in range(periods):
        for s in range(steps):
            t = s * h            # the drive's phase restarts each period (whole periods)
            k1x, k1v = v, acc(th, v, t)
            k2x, k2v = v + 0.5 * h * k1v, acc(th + 0.5 * h * k1x, v + 0.5 * h * k1v, t + 0.5 * h)
            k3x, k3v = v + 0.5 * h * k2v, acc(th + 0.5 * h * k2x, v + 0.5 * h * k2v, t + 0.5 * h)
            k4x, k4v = v + h * k3v, acc(th + h * k3x, v + h * k3v, t + h)
            th = th + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
            v = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
        out[k] = th
    del wt
    return np.array([th, v]), out


def locked(thetas, n, keep):
    """No phase slip over the last `keep` periods: x_k = theta_k - 2 pi n k within a band narrower than
    2 pi (a slip moves it by 2 pi) and back within pi of where it was (no net slip)."""
    k = np.arange(thetas.shape[0])[:, None]
    x = thetas[-keep:] - 2 * math.pi * n * k[-keep:]
    return ((x.max(axis=0) - x.min(axis=0)) < 2 * math.pi) & (np.abs(x[-1] - x[0]) < math.pi)


def plateaus(steps):
    amps = np.array([a / IC for a, _, _ in PLATEAUS])
    ns = np.array([n for _, n, _ in PLATEAUS], dtype=float)
    i0 = np.array([b / IC for _, _, b in PLATEAUS])
    m = len(PLATEAUS)
    # the locked orbit at i0: 16 starting phases per plateau
    ph = np.repeat(np.linspace(-math.pi, math.pi, 16, endpoint=False)[None, :], m, axis=0).ravel()
    st = np.array([ph, np.repeat(ns * OMEGA, 16)])
    st, th = run(st, np.repeat(i0, 16), np.repeat(amps, 16), 600, steps)
    ok = locked(th, np.repeat(ns, 16), 300).reshape(m, 16)
    if not ok.any(axis=1).all():
        raise RuntimeError(f"no locked orbit found at i0 for plateaus {np.flatnonzero(~ok.any(axis=1))}")
    first = ok.argmax(axis=1)
    start = st.reshape(2, m, 16)[:, np.arange(m), first]
    # lanes: (plateau, direction) -> continuation down (-1) and up (+1), AHEAD biases at a time, each
    # started from the last locked state; the first unlocked one ends the lane
    lane_p = np.repeat(np.arange(m), 2)
    sign = np.tile([-1.0, 1.0], m)
    n, amp = ns[lane_p], amps[lane_p]
    state = start[:, lane_p]
    last = i0[lane_p].copy()
    active = np.ones(2 * m, bool)
    edge_lo = np.full(2 * m, np.nan)
    edge_hi = np.full(2 * m, np.nan)
    ahead = np.arange(1, AHEAD + 1)
    while active.any():
        lanes = np.flatnonzero(active)
        tau = (last[lanes, None] + sign[lanes, None] * DELTA * ahead[None, :]).ravel()
        st0 = np.repeat(state[:, lanes], AHEAD, axis=1)
        new, th = run(st0, tau, np.repeat(amp[lanes], AHEAD), PERIODS, steps)
        ok = locked(th, np.repeat(n[lanes], AHEAD), 3 * PERIODS // 4).reshape(lanes.size, AHEAD)
        new = new.reshape(2, lanes.size, AHEAD)
        tau = tau.reshape(lanes.size, AHEAD)
        for r, j in enumerate(lanes):
            bad = np.flatnonzero(~ok[r])
            if bad.size == 0:
                last[j], state[:, j] = tau[r, -1], new[:, r, -1]
                continue
            b = bad[0]
            if b > 0:
                last[j], state[:, j] = tau[r, b - 1], new[:, r, b - 1]
            active[j] = False
            edge_lo[j], edge_hi[j] = last[j], tau[r, b]
    saved = state.copy()
    # bisection between the last locked bias and the first unlocked one, from the last locked state
    good, bad = edge_lo.copy(), edge_hi.copy()
    for _ in range(BISECTIONS):
        mid = 0.5 * (good + bad)
        new, th = run(saved, mid, amp, 2 * PERIODS, steps)
        ok = locked(th, n, 3 * PERIODS // 2)
        good = np.where(ok, mid, good)
        bad = np.where(ok, bad, mid)
        saved = np.where(ok[None, :], new, saved)
    edge = 0.5 * (good + bad)
    return [{"rf_current": PLATEAUS[p][0], "n": PLATEAUS[p][1], "inside": PLATEAUS[p][2],
             "lower": edge[2 * p] * IC, "upper": edge[2 * p + 1] * IC,
             "bracket": float(max(abs(good[2 * p] - bad[2 * p]), abs(good[2 * p + 1] - bad[2 * p + 1])) * IC),
             "start_theta": float(start[0, p]), "start_v": float(start[1, p])} for p in range(m)]


def main():
    """Default: the reference at 256 steps per period.  --steps N --raw FILE: the plateaus alone at N
    steps (the check of the integration, run beside it); --combine FILE: store the largest change of
    an edge between the reference and FILE as edge_step_change."""
    args = sys.argv[1:]
    if "--combine" in args:
        other = json.loads(pathlib.Path(args[args.index("--combine") + 1]).read_text())
        ref = json.loads(OUT.read_text())
        ref["edge_step_change"] = max(max(abs(a["lower"] - b["lower"]), abs(a["upper"] - b["upper"]))
                                      for a, b in zip(ref["plateaus"], other["plateaus"]))
        ref["edge_step_change_steps"] = other["steps"]
        OUT.write_text(json.dumps(ref, indent=1) + "\n")
        print(ref["edge_step_change"])
        return
    steps = int(args[args.index("--steps") + 1]) if "--steps" in args else 256
    t0 = time.time()
    ref = plateaus(steps)
    if "--raw" in args:
        pathlib.Path(args[args.index("--raw") + 1]).write_text(json.dumps({"steps": steps, "plateaus": ref}))
        return
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(json.dumps({
        "junction": {"critical_current": IC, "resistance": R, "capacitance": C, "rf_frequency": F},
        "reduced": {"damping": BETA, "drive_frequency": OMEGA},
        "method": "classical RK4, 256 steps per drive period; continuation by 0.002 I_c from 'inside', "
                  "300 periods each (4 biases ahead at once from the last locked state), locked = no phase "
                  "slip (theta_k - 2 pi n k within a band < 2 pi, back within pi); edges bisected 6 times "
                  "from the last locked state (600 periods each)",
        "edge_step_change": None, "plateaus": ref,
        "python": platform.python_version(), "numpy": np.__version__, "seconds": round(time.time() - t0, 1),
    }, indent=1) + "\n")
    print(json.dumps(ref, indent=1), file=sys.stderr)


if __name__ == "__main__":
    main()

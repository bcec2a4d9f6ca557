"""What a dc SQUID's I-V and V-Φ curves cost: pendula.DCSquid against JoSIM at equal voltage accuracy.

JoSIM (Delport, Jackman, le Roux and Fourie 2019, IEEE Trans. Appl. Supercond. 29, 1300705) is the
open-source transient simulator of superconducting circuits; it is a peer, not a dependency:
tools/build_josim.sh builds it from its public source (set JOSIM to the josim-cli executable; default
/tmp/josim/build/josim-cli).

The circuit: the symmetric dc SQUID of Tesche and Clarke (1977, section 2), two equal RCSJ junctions
(I0 = 10 µA, shunt R = 10 Ω, C = 0.16 pF: β_c = 0.49) in a loop of L = 51.7 pH (β_L = 0.5), the bias
fed to the middle of the loop (L/2 in each arm), the flux applied through a mutual inductance to one
arm.  In JoSIM each junction is its RCSJ model with the gap voltage moved to 1 V (out of reach: a pure
RCSJ junction, RN = R0 = R) and no noise.

The curves: the I-V curve at Φ = 0.25 Φ0 over 16 bias currents (10 .. 40 µA) and the V-Φ curve at
25 µA over 11 fluxes (0 .. 0.5 Φ0), each a ramp (every point starts from the state the last one
ended in), every point a transient of 100/ω_c then a window of 400/ω_c.  JoSIM runs a whole curve in
one transient simulation (a piecewise-linear bias or flux control current stepping through the points,
1 ps ramps), printing both junction phases every step or every 0.05 ps, whichever is longer (the
linear interpolation of the phases between printed points then errs by about 1e-7 of the voltage,
below JoSIM's own error; printing fewer points spares it most of the time spent writing its output).

The voltage: the mean of the junctions' phase velocity over the whole turns inside each window,
(Φ0/2π) 2π(k_b − k_a)/(t_b − t_a) (JoSIM's phases linearly interpolated between its steps; pendula
does the same with its dense output).  The reference: the same equations in reduced units integrated
by SciPy's DOP853 at rtol 1e-12 along the same ramp, the whole-turn crossings solved on its dense
output (brentq).  A code's error is the largest voltage difference from the reference over the
curve, in units of I0 R (= 100 µV).

Equal accuracy: pendula runs at rtol 1e-3, 1e-4, 1e-6, 1e-8, JoSIM at time steps of 0.2, 0.1, 0.05,
0.025, 0.0125 ps (its fixed-step second-order scheme); JoSIM's time at pendula's error is interpolated
in log-log between its bracketing runs
(outside their range, extrapolated along the line through its two nearest runs, and flagged: JoSIM's
finest step is less accurate than pendula's loosest tolerance, so every ratio printed is of that
kind; the ratio of pendula's loosest run to JoSIM's finest, a bound needing no extrapolation, is
printed beside it).  Times: pendula's whole iv_curve / v_phi_curve call (best of 3);
JoSIM's wall time of the josim-cli process (best of 2; reading its CSV output into numpy is not
counted).  A benchmark, not a test.

    .venv/bin/python data/bench/squid_josim_cost.py     # writes data/bench/squid_josim_cost.json
"""

import json
import math
import os
import platform
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import pendula

HERE = Path(__file__).resolve().parent
JOSIM = os.environ.get("JOSIM", "/tmp/josim/build/josim-cli")

PHI0 = 2.067833848e-15            # h / 2e (CODATA 2018, exact)
I0, R, C, L = 10e-6, 10.0, 0.16e-12, 51.7e-12
WC = 2 * math.pi * I0 * R / PHI0  # ω_c
BETA_L = 2 * L * I0 / PHI0
BETA_C = WC * R * C
TR, TW = 100.0, 400.0             # transient and window per point, in 1/ω_c
IV_FLUX, IV_CURRENTS = 0.25, np.linspace(10e-6, 40e-6, 16)
VPHI_CURRENT, VPHI_FLUXES = 25e-6, np.linspace(0.0, 0.5, 11)
PENDULA_RTOLS = (1e-3, 1e-4, 1e-6, 1e-8)
PRINT_STEP = 0.05e-12               # JoSIM's phases printed no finer than this (its output is half its time)
JOSIM_STEPS = (0.2e-12, 0.1e-12, 0.05e-12, 0.025e-12, 0.0125e-12)


# ---------------------------------------------------------------- the reference (SciPy, reduced units)
def whole_turn_velocity(times, s_of_t, t_grid, s_grid):
    """⟨s'⟩ over the whole turns of s inside the window: crossings of 2πk found on a grid, then refined
    by s_of_t (a callable: brentq; None: linear interpolation)."""
    k_a = math.floor(s_grid[0] / (2 * math.pi)) + 1
    k_b = math.floor(np.max(s_grid) / (2 * math.pi))
    if k_b - k_a < 2:
        return (s_grid[-1] - s_grid[0]) / (t_grid[-1] - t_grid[0])
    run_max = np.maximum.accumulate(s_grid)
    hits = []
    for k in (k_a, k_b):
        lev = 2 * math.pi * k
        j = int(np.searchsorted(run_max, lev))
        t0, t1 = t_grid[j - 1], t_grid[j]
        if s_of_t is None:
            s0, s1 = s_grid[j - 1], s_grid[j]
            hits.append(t0 + (lev - s0) / (s1 - s0) * (t1 - t0))
        else:
            hits.append(brentq(lambda t: s_of_t(t) - lev, t0, t1, xtol=1e-14, rtol=1e-15))
    return 2 * math.pi * (k_b - k_a) / (hits[1] - hits[0])


def reference_curve(biases, fluxes):
    """The mean velocities ⟨s'⟩ (in ω_c) along a ramp of (bias/I0, flux/Φ0) points."""
    k = 1.0 / (math.pi * BETA_L)
    y = np.array([math.pi * fluxes[0], -math.pi * fluxes[0], 0.0, 0.0])
    out = []
    for b, f in zip(biases, fluxes):
        def rhs(t, y, b=b, f=f):
            j = k * (y[0] - y[1] - 2 * math.pi * f)
            return [y[2], y[3], (b / 2 - j - math.sin(y[0]) - y[2]) / BETA_C,
                    (b / 2 + j - math.sin(y[1]) - y[3]) / BETA_C]
        y = solve_ivp(rhs, (0, TR), y, method="DOP853", rtol=1e-12, atol=1e-14).y[:, -1]
        sol = solve_ivp(rhs, (0, TW), y, method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)
        tg = np.linspace(0, TW, int(TW / 0.02) + 1)
        sg = sol.sol(tg)[:2].mean(axis=0)
        out.append(whole_turn_velocity(None, lambda t: float(sol.sol(t)[:2].mean()), tg, sg))
        y = sol.y[:, -1]
        shift = 2 * math.pi * math.floor((y[0] + y[1]) / (4 * math.pi) + 0.5)
        y = y - np.array([shift, shift, 0, 0])
    return np.array(out)


# ---------------------------------------------------------------- JoSIM
LX, KC = L / 2, 0.5                # the flux's control inductor and its coupling to one arm
MUTUAL = KC * math.sqrt(L / 2 * LX)  # Φ = M Ix


def josim_netlist(biases_a, ix_a, step):
    """A netlist stepping the bias and the flux control current through the points (1 ps ramps)."""
    seg = (TR + TW) / WC
    ramp = 1e-12

    def pwl(vals):
        pts = ["0 0"]
        for n, v in enumerate(vals):
            pts.append(f"{n * seg + ramp:.9e} {v:.9e}")
            if n + 1 < len(vals):
                pts.append(f"{(n + 1) * seg:.9e} {v:.9e}")
        return "pwl(" + " ".join(pts) + ")"
    ib, ix = pwl(biases_a), pwl(ix_a)
    return "\n".join([
        "* symmetric dc SQUID, RCSJ junctions (gap voltage out of reach), flux through a mutual inductance",
        f".model rcsj jj(rtype=0, vg=1, icrit={I0:.9e}, rn={R:.9e}, r0={R:.9e}, cap={C:.9e})",
        f"IB 0 top {ib}",
        f"L1 top a {L / 2:.9e}",
        f"L2 top b {L / 2:.9e}",
        "B1 a 0 rcsj area=1",
        "B2 b 0 rcsj area=1",
        f"IX 0 ctl {ix}",
        f"LX ctl 0 {LX:.9e}",
        f"K1 LX L1 {KC}",
        f".tran {step:.9e} {len(biases_a) * seg:.9e} 0 {max(step, PRINT_STEP):.9e} DST",
        ".print phase B1",
        ".print phase B2",
        ".end", ""])


def josim_curve(biases_a, fluxes, step, reps=2):
    nl = josim_netlist(biases_a, np.asarray(fluxes) * PHI0 / MUTUAL, step)
    with tempfile.TemporaryDirectory() as d:
        cir, csv = Path(d) / "squid.cir", Path(d) / "out.csv"
        cir.write_text(nl)
        best = float("inf")
        for _ in range(reps):
            t0 = time.perf_counter()
            subprocess.run([JOSIM, "-o", str(csv), str(cir)], check=True, stdout=subprocess.DEVNULL)
            best = min(best, time.perf_counter() - t0)
        import pandas   # xarray's dependency: a fast CSV reader
        data = pandas.read_csv(csv).to_numpy()
    t, s = data[:, 0] * WC, 0.5 * (data[:, 1] + data[:, 2])
    seg = TR + TW
    out = []
    for n in range(len(biases_a)):
        m = (t >= n * seg + TR) & (t <= (n + 1) * seg)
        out.append(whole_turn_velocity(None, None, t[m], s[m]))
    return np.abs(np.array(out)), best


# ---------------------------------------------------------------- the comparison
def equal_error_time(err, runs):
    """JoSIM's time at the error err: log-log interpolation between its bracketing runs (inside: True);
    outside their range, the straight line in log-log through its two nearest runs (inside: False)."""
    le = np.log([r["error"] for r in runs])
    lt = np.log([r["s"] for r in runs])
    o = np.argsort(le)
    le, lt = le[o], lt[o]
    x = math.log(err)
    if le[0] <= x <= le[-1]:
        return float(np.exp(np.interp(x, le, lt))), True
    a, b = (0, 1) if x < le[0] else (-2, -1)
    slope = (lt[b] - lt[a]) / (le[b] - le[a])
    return float(np.exp(lt[a] + slope * (x - le[a]))), False


def timed(fn, repeat):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main():
    sq = pendula.DCSquid(I0, R, C, L)
    curves = {
        "iv": (IV_CURRENTS, np.full(IV_CURRENTS.size, IV_FLUX),
               lambda rtol: sq.iv_curve(IV_CURRENTS, IV_FLUX, transient=TR / WC, t_max=TW / WC, rtol=rtol)
               .mean_velocity.values[0]),
        "v_phi": (np.full(VPHI_FLUXES.size, VPHI_CURRENT), VPHI_FLUXES,
                  lambda rtol: sq.v_phi_curve(VPHI_CURRENT, VPHI_FLUXES, transient=TR / WC, t_max=TW / WC,
                                              rtol=rtol).mean_velocity.values),
    }
    rec = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
           "machine": platform.processor() or platform.machine(), "cores": os.cpu_count(),
           "pendula": pendula.__version__, "josim": JOSIM,
           "squid": {"I0_A": I0, "R_ohm": R, "C_F": C, "L_H": L, "beta_l": BETA_L, "beta_c": BETA_C},
           "window": {"transient_over_wc": TR, "window_over_wc": TW}, "curves": {}}
    for name, (cur, flux, pend) in curves.items():
        ref = reference_curve(cur / I0, flux)
        pruns = []
        for rtol in PENDULA_RTOLS:
            tp, vel = timed(lambda: pend(rtol), 3)
            pruns.append({"rtol": rtol, "error": float(np.max(np.abs(vel - ref))), "s": tp})
        jruns = []
        for step in JOSIM_STEPS:
            vel, tj = josim_curve(cur, flux, step)
            jruns.append({"step_s": step, "error": float(np.max(np.abs(vel - ref))), "s": tj})
        rows = []
        for p in pruns:
            tj, inside = equal_error_time(p["error"], jruns)
            rows.append(p | {"josim_s_at_pendula_error": tj, "interpolated": inside,
                             "ratio_josim_over_pendula": tj / p["s"]})
            print(f"{name:6s} rtol={p['rtol']:.0e}  pendula {p['s']:8.3f} s  error {p['error']:.1e} I0R   "
                  f"JoSIM at that error {tj:8.3f} s  ratio {tj / p['s']:7.1f}{'' if inside else ' (extrapolated)'}",
                  flush=True)
        fine = min(jruns, key=lambda j: j["error"])
        loose = max(pruns, key=lambda p: p["error"])
        bound = {"josim_finest_step_s": fine["step_s"], "josim_finest_error": fine["error"],
                 "josim_finest_s": fine["s"],
                 "pendula_loosest_rtol": loose["rtol"], "pendula_loosest_error": loose["error"],
                 "pendula_loosest_s": loose["s"], "ratio": fine["s"] / loose["s"]}
        print(f"{name:6s} bound: JoSIM's finest run (error {fine['error']:.1e}) {fine['s']:.3f} s over pendula's "
              f"loosest (error {loose['error']:.1e}) {loose['s']:.3f} s = {bound['ratio']:.1f}")
        for j in jruns:
            print(f"{name:6s} JoSIM step {j['step_s'] * 1e12:.3f} ps  {j['s']:8.3f} s  error {j['error']:.1e} I0R")
        rec["curves"][name] = {"reference_mean_velocity": ref.tolist(), "pendula": rows, "josim": jruns,
                               "bound_without_extrapolation": bound}
    rec["load_average_at_end"] = os.getloadavg()
    (HERE / "squid_josim_cost.json").write_text(json.dumps(rec, indent=1) + "\n")


if __name__ == "__main__":
    main()

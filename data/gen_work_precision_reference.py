"""Write data/work_precision_reference.json: the reference solutions of the work-precision study.

Every problem of the study (python/pendula/studies/workprecision.py, PROBLEMS) is

    theta'' = -eps sin(theta) - beta theta' + tau + A cos(Omega t + phase),

and its reference is an explicit Taylor-series integration in mpmath at 45
significant digits, written here from the equation alone (no code of pendula,
SciPy, SUNDIALS or GSL is used): the Taylor coefficients of theta, v = theta',
sin(theta) and cos(theta) come from the usual recurrences

    (k+1) theta_{k+1} = v_k
    (k+1) v_{k+1}     = -eps s_k - beta v_k + tau [k = 0] + A Omega^k / k! cos(Omega t0 + phase + k pi / 2)
    (k+1) s_{k+1}     =  sum_{j=1}^{k+1} j theta_j c_{k+1-j}
    (k+1) c_{k+1}     = -sum_{j=1}^{k+1} j theta_j s_{k+1-j}

(s = sin theta, c = cos theta; Moore, Interval Analysis, 1966, ch. 11; Jorba &
Zou, Exp. Math. 14 (2005) section 2), summed by Horner at a fixed step that
lands on every output time.

The reference's own accuracy is shown by two integrations with different order
and step (order 30 at h = 1/16 against order 24 at h = 1/12 of a time unit):
their largest difference over all outputs is stored per problem
(``reference_check``) and must be below 1e-20 (the script refuses otherwise).

The double-precision floor of each problem (the error that a 1-ulp change of
the initial state makes over the run) is the difference between the reference
and the same integration from v0 + ulp(max(|v0|, 1)) (one unit in the last
place of v0, or of 1 when |v0| < 1: the state is of order 1), also stored.

Usage:  python data/gen_work_precision_reference.py [PROBLEM ...]
(all problems: about 10 minutes on one core; naming problems recomputes only those
and keeps the others of the stored file)
"""

from __future__ import annotations

import json
import math
import pathlib
import sys
import time

import mpmath as mp

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE / "work_precision_reference.json"

sys.path.insert(0, str(HERE.parent / "python"))
# the problem definitions are data: read them from the study without importing the compiled package
_src = (HERE.parent / "python" / "pendula" / "studies" / "workprecision.py").read_text()
_ns: dict = {}
exec(compile(_src.split("# ---- end of problem definitions")[0], "workprecision.py", "exec"), _ns)
PROBLEMS = _ns["PROBLEMS"]
N_OUT = _ns["N_OUT"]

DPS = 45


def taylor_run(p, theta0, v0, order, steps_per_unit, n_out):
    """theta and v at the n_out + 1 output times k t_end / n_out (k = 0..n_out)."""
    eps = mp.mpf(p["eps"])
    beta = mp.mpf(p.get("beta", 0.0))
    tau = mp.mpf(p.get("tau", 0.0))
    amp = mp.mpf(p.get("amp", 0.0))
    om = mp.mpf(p.get("omega", 0.0))
    ph = mp.mpf(p.get("phase", 0.0))
    t_end = mp.mpf(p["t_end"])
    dt_out = t_end / n_out
    sub = max(1, int(round(float(dt_out) * steps_per_unit)))
    h = dt_out / sub
    th, v = mp.mpf(theta0), mp.mpf(v0)
    ths, vs = [th], [v]
    # factorial-scaled powers of Omega for the drive's coefficients
    omk = [mp.mpf(1)]
    for k in range(1, order + 1):
        omk.append(omk[-1] * om / k)
    halfpi = mp.pi / 2
    t0 = mp.mpf(0)
    for _ in range(n_out):
        for _ in range(sub):
            T = [th]
            V = [v]
            S = [mp.sin(th)]
            C = [mp.cos(th)]
            phase0 = om * t0 + ph
            for k in range(order):
                f = -eps * S[k]
                if beta:
                    f -= beta * V[k]
                if k == 0 and tau:
                    f += tau
                if amp:
                    f += amp * omk[k] * mp.cos(phase0 + k * halfpi)
                T.append(V[k] / (k + 1))
                V.append(f / (k + 1))
                k1 = k + 1
                ss = mp.mpf(0)
                cc = mp.mpf(0)
                for j in range(1, k1 + 1):
                    jt = j * T[j]
                    ss += jt * C[k1 - j]
                    cc += jt * S[k1 - j]
                S.append(ss / k1)
                C.append(-cc / k1)
            th_new = T[order]
            v_new = V[order]
            for k in range(order - 1, -1, -1):
                th_new = th_new * h + T[k]
                v_new = v_new * h + V[k]
            th, v = th_new, v_new
            t0 += h
        ths.append(th)
        vs.append(v)
    return ths, vs


def main():
    mp.mp.dps = DPS
    out = {"generator": "data/gen_work_precision_reference.py", "digits": DPS,
           "method": "Taylor series in mpmath: order 30 at h = 1/16 (check: order 24 at h = 1/12)",
           "n_out": N_OUT, "problems": {}}
    only = sys.argv[1:]
    if only:
        out["problems"] = json.loads(OUT.read_text())["problems"]
    for name, p in PROBLEMS.items():
        if only and name not in only:
            continue
        t0 = time.time()
        ths, vs = taylor_run(p, p["theta0"], p["v0"], 30, 16, N_OUT)
        ths2, vs2 = taylor_run(p, p["theta0"], p["v0"], 24, 12, N_OUT)
        check = max(max(abs(a - b) for a, b in zip(ths, ths2)), max(abs(a - b) for a, b in zip(vs, vs2)))
        if not check < mp.mpf("1e-20"):
            raise SystemExit(f"{name}: the two Taylor integrations differ by {mp.nstr(check, 3)} (> 1e-20)")
        # the double-precision floor: the same problem from v0 + 1 ulp
        v0p = float(p["v0"]) + math.ulp(max(abs(float(p["v0"])), 1.0))
        thp, vp = taylor_run(p, p["theta0"], v0p, 24, 12, N_OUT)
        floor_final = float(abs(thp[-1] - ths2[-1]))
        floor_max = float(max(abs(a - b) for a, b in zip(thp, ths2)))
        out["problems"][name] = {
            "params": p,
            "t": [mp.nstr(mp.mpf(p["t_end"]) * k / N_OUT, 30) for k in range(N_OUT + 1)],
            "theta": [mp.nstr(x, 35) for x in ths],
            "v": [mp.nstr(x, 35) for x in vs],
            "reference_check": float(check),
            "floor_error_final": floor_final,
            "floor_error_max": floor_max,
            "floor_perturbation": f"v0 + {math.ulp(max(abs(float(p['v0'])), 1.0)):.3g}",
        }
        print(f"{name}: check {float(check):.2e}, floor final {floor_final:.2e} max {floor_max:.2e}, "
              f"{time.time() - t0:.0f} s", flush=True)
    OUT.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()

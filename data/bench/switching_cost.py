"""The cost of a switching-current distribution: the Fulton-Dunkleberger integral against Langevin ramps.

Two questions, timed in one run, interleaved, best of ``--repeat`` wall times (the machine is shared; its
load average is recorded before and after):

* at a laboratory ramp (the 10 uA, 1 pF, 30 ohm junction at 4.2 K and 20 mK, 1 A/s and 1 mA/s): the cost
  of ``pendula.switching_distribution`` (mean, width and the density on 401 currents).  Direct Langevin
  ramps cannot run there (a ramp of 1 A/s is 6e-7 I_c per 1 / omega_p: about 2e7 steps a ramp);
  their cost is estimated from the measured cost per step below.
* at a ramp where both run (beta = 1, k_B T = 0.2 E_J, 2e-4 I_c per 1 / omega_p, dt = 0.1): the
  integral against ``Junction.switching_currents`` with ``--n`` ramps (1,000 by default), the ratio of
  their times and the measured overlap (the difference of the means in widths, the widths' ratio).

Wall and process CPU times are both recorded (the Langevin ramps run on ``--threads`` OpenMP threads: their
CPU time is summed over the threads).  The record goes to data/bench/switching_cost.json with the machine
and the date.

    python data/bench/switching_cost.py [--n 1000] [--repeat 3] [--threads 2]
"""

import json
import math
import os
import pathlib

import pendula
from pendula.escape import switching_distribution
from pendula.junction import BOLTZMANN, PLANCK, ELEMENTARY_CHARGE
from pendula.studies.bench import machine_record
from _bench_timing import cost_arguments, timed

OUT = pathlib.Path(__file__).with_name("switching_cost.json")


def main():
    ap = cost_arguments(__doc__, 1000, "Langevin ramps", "OpenMP threads of the Langevin ramps")
    a = ap.parse_args()
    load0 = os.getloadavg()
    lab = pendula.Junction(10e-6, 30.0, 1e-12)
    ic, c = 1e-6, 1e-12
    hbar = PLANCK / (2 * math.pi)
    wp = math.sqrt(2 * ELEMENTARY_CHARGE * ic / (hbar * c))
    ej = hbar * ic / (2 * ELEMENTARY_CHARGE)
    both = pendula.Junction(ic, 1 / (wp * c), c, temperature=0.2 * ej / BOLTZMANN)
    rate_both = 2e-4 * ic * wp
    labs = [(t, r) for t in (4.2, 0.02) for r in (1.0, 1e-3)]
    best = {f"integral_{t}K_{r}Aps": math.inf for t, r in labs}
    best.update({"integral_where_both_run": math.inf, "langevin": math.inf})
    cpu = dict.fromkeys(best, math.inf)
    out = {}
    for _ in range(a.repeat):
        for t, r in labs:
            w, cp, d = timed(lambda: switching_distribution(lab, r, temperature=t))
            k = f"integral_{t}K_{r}Aps"
            best[k], cpu[k] = min(best[k], w), min(cpu[k], cp)
            out[k] = {"mean_A": d.mean, "width_A": d.width, "at_critical": d.at_critical}
        w, cp, d = timed(lambda: switching_distribution(both, rate_both))
        k = "integral_where_both_run"
        best[k], cpu[k] = min(best[k], w), min(cpu[k], cp)
        w, cp, s = timed(lambda: both.switching_currents(rate_both, a.n, seed=7, dt=0.1, threads=a.threads))
        best["langevin"], cpu["langevin"] = min(best["langevin"], w), min(cpu["langevin"], cp)
    # Langevin steps taken: each ramp runs to its switch (about i_sw / (r dt) steps)
    steps = float(sum(x / ic for x in s.samples)) / (2e-4 * 0.1)
    per_step = best["langevin"] / steps
    for t, r in labs:
        k = f"integral_{t}K_{r}Aps"
        i_sw = out[k]["mean_A"] / lab.critical_current
        rr = r / (lab.critical_current * lab.plasma_frequency)
        out[k]["langevin_estimate_s_for_n_ramps"] = a.n * i_sw / (rr * 2 * math.pi / 100) * per_step
    rec = {
        "what": "switching distribution: Fulton-Dunkleberger integral (pendula.switching_distribution) against "
                "direct Langevin ramps (Junction.switching_currents), interleaved, best of --repeat wall times",
        "n_ramps": a.n, "repeat": a.repeat, "threads": a.threads,
        "machine": machine_record(), "load_average_before": list(load0), "load_average_after": list(os.getloadavg()),
        "best_wall_s": best, "best_process_cpu_s": cpu,
        "ratio_langevin_to_integral_where_both_run": best["langevin"] / best["integral_where_both_run"],
        "cpu_ratio_langevin_to_integral_where_both_run": cpu["langevin"] / cpu["integral_where_both_run"],
        "where_both_run": {"beta": 1.0, "kT_over_EJ": 0.2, "ramp_Ic_per_inverse_plasma_frequency": 2e-4,
                           "dt": 0.1, "langevin_mean_A": s.mean, "langevin_width_A": s.width,
                           "integral_mean_A": d.mean, "integral_width_A": d.width,
                           "mean_difference_in_widths": (s.mean - d.mean) / d.width,
                           "standard_error_in_widths": s.width / d.width / math.sqrt(a.n),
                           "width_ratio": s.width / d.width, "langevin_seconds_per_step": per_step},
        "laboratory": out}
    OUT.write_text(json.dumps(rec, indent=1) + "\n")
    print(json.dumps({k: rec[k] for k in ("best_wall_s", "best_process_cpu_s",
                                           "ratio_langevin_to_integral_where_both_run",
                                           "cpu_ratio_langevin_to_integral_where_both_run", "where_both_run")},
                     indent=1))


if __name__ == "__main__":
    main()

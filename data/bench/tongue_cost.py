"""What a Shapiro tongue costs: pendula.shapiro_tongue (damping 1, drive_frequency 2, step n = 1) from rf
amplitude 0.05 to 4 with at least 100 points on each edge, against its peer, the scipy computation of
the same edges at one rf amplitude (data/gen_shapiro_tongue_reference.py: DOP853 at 1e-12 on the
variational equations, Newton in (v, torque) over 96 phases, brentq on det(M - I)), timed at three
amplitudes and compared per edge point (the scipy run finds both edges of one amplitude at a time).
Prints wall and CPU seconds and the ratio; nothing asserts a time.

    .venv/bin/python data/bench/tongue_cost.py     # writes data/bench/tongue_cost.json
"""

import json
import os
import platform
from pathlib import Path

import pendula
from _bench_timing import reference_script, timed

HERE = Path(__file__).resolve().parent


def run_pendula():
    sc = pendula.Scene(damping=1.0, drive_amplitude=0.05, drive_frequency=2.0)
    t = pendula.shapiro_tongue(sc, 1, 4.0, step=0.01)
    return len(t.lower), len(t.upper), t.lower.end, t.upper.end


def main():
    ref = reference_script("gen_shapiro_tongue_reference.py", "gen_tongue_ref")
    wall, cpu, (nl, nu, el, eu) = timed(run_pendula)
    print(f"pendula.shapiro_tongue n = 1, rf amplitude 0.05 -> 4: {nl} + {nu} points, ends {el!r}, {eu!r}: "
          f"{wall:.2f} s wall, {cpu:.2f} s CPU ({wall / (nl + nu) * 1e3:.1f} ms per edge point)")
    rows = []
    for a in (0.5, 1.5, 3.0):
        w, c, out = timed(lambda a=a: ref.edges(1, a, 2.0))
        rows.append((a, w, c))
        print(f"scipy edges at rf amplitude {a}: {out[0][0]:.12f} {out[1][0]:.12f}: {w:.2f} s wall "
              f"({w / 2 * 1e3:.0f} ms per edge point)")
    per_scipy = sum(r[1] for r in rows) / (2 * len(rows))
    per_pendula = wall / (nl + nu)
    print(f"ratio per edge point, scipy / pendula: {per_scipy / per_pendula:.0f}")
    rec = {"machine": platform.machine(), "cpus": os.cpu_count(), "pendula_wall_s": wall, "pendula_cpu_s": cpu,
           "points": [nl, nu], "scipy_rows": rows, "ratio_per_edge_point": per_scipy / per_pendula}
    (HERE / "tongue_cost.json").write_text(json.dumps(rec, indent=1))


if __name__ == "__main__":
    main()

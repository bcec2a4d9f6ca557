"""What the cascade costs: continue_orbit from A = 1.0 (damping 0.5, drive_frequency 2/3) with
follow='stable' to just past the fifth bifurcation (the pitchfork and four period doublings),
against its peer, the scipy computation of the same five points (data/gen_continuation_reference.py:
DOP853 at 1e-13 on the variational equations, Newton, brentq).  The two are interleaved, pendula
best of three, scipy best of two; wall and CPU seconds.  The target: the pendula call under 2 minutes.

    .venv/bin/python data/bench/continuation_cost.py     # writes data/bench/continuation_cost.json
"""

import json
import os
import platform
import time
from pathlib import Path

import pendula
from _bench_timing import reference_script, timed

HERE = Path(__file__).resolve().parent


def run_pendula():
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2 / 3)
    po = pendula.periodic_orbit(sc, guess=(0.1, 1.9))
    # past the fifth bifurcation (the doubling of the period-8 orbit at 1.0826784), before the sixth
    br = pendula.continue_orbit(sc, (po.theta, po.v), "drive_amplitude", 1.08275, follow="stable")
    return [(b.kind, b.period, b.value) for b in br.bifurcations], len(br)


def main():
    ref = reference_script("gen_continuation_reference.py", "gen_ref")
    pend, peer = [], []
    for i in range(3):
        pend.append(timed(run_pendula))
        if i < 2:
            peer.append(timed(ref.cascade))
    bp = min(pend, key=lambda r: r[0])
    bs = min(peer, key=lambda r: r[0])
    bifs, npoints = bp[2]
    assert len(bifs) == 5, bifs
    diff = max(abs(b[2] - p["value"]) for b, p in zip(bifs, bs[2]))
    rec = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
           "machine": platform.processor() or platform.machine(), "cores": os.cpu_count(),
           "load_average": os.getloadavg(), "pendula": pendula.__version__,
           "task": "continue_orbit(follow='stable') from A=1.0 to the fifth bifurcation (damping 0.5, "
                   "drive_frequency 2/3)",
           "rows": {"pendula": {"wall_s": bp[0], "cpu_s": bp[1], "all_wall_s": [r[0] for r in pend],
                                "points": npoints,
                                "bifurcations": [[k, p, v] for k, p, v in bifs]},
                    "scipy": {"wall_s": bs[0], "cpu_s": bs[1], "all_wall_s": [r[0] for r in peer],
                              "what": "gen_continuation_reference.cascade(): the same five points by "
                                      "brentq on the multipliers (no continuation)"}},
           "max_difference_of_the_five_values": diff,
           "ratio_wall": bs[0] / bp[0], "ratio_cpu": bs[1] / bp[1], "target_s": 120.0}
    print(f"pendula {bp[0]:.2f} s wall ({bp[1]:.2f} s CPU), scipy {bs[0]:.2f} s wall ({bs[1]:.2f} s CPU): "
          f"ratio {rec['ratio_wall']:.1f} (wall), {rec['ratio_cpu']:.1f} (CPU); values agree to {diff:.1e}")
    (HERE / "continuation_cost.json").write_text(json.dumps(rec, indent=1) + "\n")


if __name__ == "__main__":
    main()

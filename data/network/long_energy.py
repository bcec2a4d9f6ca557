"""The conservative chain's energy over 10^6 periods with the symplectic Gauss-Legendre methods.

A nonlinear chain of 4 pendula (K = 0.5, phases 0.6 sin(i) at rest), Gauss-Legendre of order 6 and 4
at 25 steps per small-oscillation period 2π: the largest relative energy error in each decade of
periods (10^k .. 10^(k+1)), run in chunks of 10^5 periods from the state the last chunk ended in.
Bounded error shows as a flat row; a drift would grow tenfold per decade.

    .venv/bin/python data/network/long_energy.py          # writes data/network/long_energy.json
"""

import json
import math
import os
import platform
import time
from pathlib import Path

import numpy as np

import pendula

HERE = Path(__file__).resolve().parent
PERIODS = 10 ** 6
CHUNK = 10 ** 5
PER_PERIOD = 25
SAMPLE = 5          # energy sampled every 5 periods


def run(method):
    n = 4
    net = pendula.Network(n, topology="chain", strength=0.5)
    h = 2 * math.pi / PER_PERIOD
    phi, v = 0.6 * np.sin(np.arange(1, n + 1)), np.zeros(n)
    e0 = float(net.energy(phi, v))
    worst = {}
    done = 0
    while done < PERIODS:
        steps = np.arange(SAMPLE, CHUNK + 1, SAMPLE) * PER_PERIOD
        out = net.simulate(steps * h, phi, v, method=method, dt=h)
        err = np.abs(out.energy.values - e0) / e0
        periods = done + np.arange(SAMPLE, CHUNK + 1, SAMPLE)
        for p, e in zip(periods, err):
            dec = int(math.floor(math.log10(p)))
            worst[dec] = max(worst.get(dec, 0.0), float(e))
        phi, v = out.phi.values[-1], out.v.values[-1]
        done += CHUNK
        print(method, done, f"{err.max():.3e}", flush=True)
    return {f"1e{k}..1e{k + 1}": worst[k] for k in sorted(worst)}


def main():
    t0 = time.time()
    rows = {m: run(m) for m in ("gauss6", "gauss4")}
    rec = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
           "machine": platform.processor() or platform.machine(), "cores": os.cpu_count(),
           "pendula": pendula.__version__, "seconds": time.time() - t0,
           "task": f"chain of 4, K=0.5, {PER_PERIOD} steps a period, {PERIODS} periods: "
                   "largest relative energy error per decade of periods",
           "rows": rows}
    (HERE / "long_energy.json").write_text(json.dumps(rec, indent=1) + "\n")
    print(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()

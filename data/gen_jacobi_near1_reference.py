"""Generate data/jacobi_near1_reference.csv: sn, cn, dn near m = 1 at
double-double arguments, from mpmath (independent of pendula), for the
relative accuracy of small cn and dn (tests/test_jacobi_near1.py).

The exact pendulum near its separatrix evaluates v = 2 k sqrt(eps) cn(u | m)
with m -> 1 (mc down to 1e-300) and a phase u carried in double-double; there
cn and dn are tiny for long stretches, and what matters is their error
relative to themselves, not to 1.  Two classes, mc log-uniform in
[1e-300, 1e-2] (given through mc, exactly), j uniform in [0, 50]:
  near_zero  u = (2j+1) K + d, |d| log-uniform in [1e-6, 1] min(1, K/2), random
             sign: next to a zero of cn (|cn| ~ sqrt(mc) |d|);
  anywhere   u = (2j+1) K + d, d uniform in [-K, K]: cn ~ sech(|d|) down to
             sqrt(mc), the stretch where the pendulum creeps over the top;
  anywhere_dup  as anywhere with mc log-uniform in [1e-18, 1e-2] only: the
             parameters that the duplications serve (below 2^-60 the kernel
             takes the expansion about m = 1).
The argument is uh + ul with uh = fl(u), ul = fl(u - uh); the reference is
taken at uh + ul exactly.  Every value is computed at two precisions (40 and
80 digits beyond those that 1 - mc needs) and must agree to 1e-30 relative.

Usage:  python data/gen_jacobi_near1_reference.py [--n 300]   (about a minute)
"""

import argparse
import csv
import math
import pathlib
import random

import mpmath as mp

OUT = pathlib.Path(__file__).with_name("jacobi_near1_reference.csv")


def values(uh, ul, mc, dps):
    with mp.workdps(dps):
        m = 1 - mp.mpf(mc)
        u = mp.mpf(uh) + mp.mpf(ul)
        return [mp.ellipfun(f, u, m=m) for f in ("sn", "cn", "dn")]


def point(rng, case):
    mc = 10 ** rng.uniform(-18 if case == "anywhere_dup" else -300, -2)
    dps = 40 + int(-math.log10(mc))
    with mp.workdps(dps):
        K = mp.ellipk(1 - mp.mpf(mc))
        j = rng.randrange(0, 51)
        if case == "near_zero":
            d = rng.choice([-1, 1]) * 10 ** rng.uniform(-6, 0) * min(1.0, float(K) / 2)
        else:
            d = rng.uniform(-1, 1) * float(K)
        u = (2 * j + 1) * K + d
        uh = float(u)
        ul = float(u - uh)
    a = values(uh, ul, mc, dps)
    b = values(uh, ul, mc, 2 * dps)
    for p, q in zip(a, b):
        assert abs(p - q) <= mp.mpf("1e-30") * abs(q), (case, uh, ul, mc)
    return [case, repr(uh), repr(ul), repr(mc)] + [repr(float(v)) for v in b]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=300, help="points per class")
    args = ap.parse_args()
    rng = random.Random(20261123)
    rows = [point(rng, case) for case in ("near_zero", "anywhere", "anywhere_dup") for _ in range(args.n)]
    with OUT.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["# mpmath " + mp.__version__ + "; data/gen_jacobi_near1_reference.py"])
        w.writerow(["case", "uh", "ul", "mc", "sn", "cn", "dn"])
        w.writerows(rows)
    print(f"wrote {len(rows)} points to {OUT}")


if __name__ == "__main__":
    main()

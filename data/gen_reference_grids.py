"""Generate data/reference_grids.csv.gz: random reference points for every
public function of pendula's elliptic kernel and exact motion, per regime,
with values from mpmath at high precision (independent of pendula).

Each class draws its points log-uniformly across its domain (never round
numbers), from a fixed seed, so that a hole like "m = 0.2, u of a few
thousand periods" cannot hide between grid lines.  Every value is computed at
two precisions and must agree to 1e-30 relative (mpmath's ellipfun needs many
more digits for large u next to m = 1), otherwise the point is recomputed at a
higher precision.

Classes (the parameter is given to pendula as the test says: "via m" or "via mc"):
  jac_m_small    sn cn dn, 0 <= m < 0.5 via m, |u| up to 1e4 periods
  jac_m_mid      sn cn dn, 0.5 <= m < 1 via m
  jac_m_near1_m  sn cn dn, m = 1 - 10^-x via m (x in [1, 16])
  jac_m_near1_mc sn cn dn, mc in [1e-300, 0.5] via mc
  jac_m_neg      sn cn dn, m < 0 via m (|m| in [1e-12, 1e4])
  jac_m_gt1_m    sn cn dn, m > 1 via m (m - 1 in [1e-15, 1e4])
  jac_m_gt1_mc   sn cn dn, m > 1 via mc < 0
  k_*, e_*       K and E in each regime of m <= 1 (via m and via mc)
  nome_*         the nome, 0 <= m <= 1 via m and via mc
  f_*, einc_*    F(phi|m), E(phi|m): |phi| up to 1e4 pi for m <= 1; m > 1 inside the domain
  exact_*        theta(t), v(t): libration, rotation, near the separatrix (both sides),
                 near the top (at rest and moving), wrapped starts (|theta0| > pi);
                 each forward and backward in time, t up to 1e4 periods
  period_*       periods of librations and rotations

The second set (--set edges, data/reference_grids_edges.csv.gz, 1000 draws per class) holds the
places where a value is ill-conditioned in its own inputs or a formula
changes, each drawn log-uniformly next to the place:
  am_*           the amplitude am(u|m) in every class of m: 0 <= m < 0.5,
                 0.5 <= m < 1, mc down to 1e-300, m < 0 (to -1e12), m > 1 via m
                 and via mc; am_edge_*: m > 1 with u next to an odd multiple
                 of the quarter period K(1/m)/sqrt(m), where sn = +-1/sqrt(m)
                 and m - 1 down to 1e-100 (via mc)
  jac_m_neg_far  sn cn dn for m from -1e3 to -1e100
  f_halfpi_*, einc_halfpi_*   phi next to N pi/2 (|N| up to 1e4, odd and
                 even; 1e-17 to 1e-3 relative, or one ulp), m in [-10, 1) via m,
                 mc down to 1e-300 via mc
  f_edge_*, einc_edge_*       m > 1 (m - 1 from 1e-16 to 1e3, via m and via
                 mc < 0), phi next to the edge of the real domain
                 asin(1/sqrt(m)), on both sides (beyond it the reference is NaN)
  exact_huge_theta0_*         theta(t), v(t) with |theta0| from 1e3 to 2^52,
                 every regime, forward and backward, t up to 1e4 periods
The reference of am(u|m): atan2(sn, cn) made continuous for m <= 1 by
am - pi u / (2K) being within pi/2 of 0, confirmed by F(am|m) = u (a second
route); asin(sn) = atan2(sn, cn) with cn > 0 for m > 1.

Usage:  python data/gen_reference_grids.py [--n 2000] [--jobs 2]   (about 20 min on 2 cores)
        python data/gen_reference_grids.py --set edges --n 1000   (22 min on 2 busy cores)
"""

import argparse
import csv
import gzip
import math
import multiprocessing as mpr
import pathlib
import random
import sys

import mpmath as mp

sys.path.insert(0, str(pathlib.Path(__file__).parent))
from gen_exact_reference import closed_form, k2_of  # noqa: E402  (the same closed form, one copy)

OUT = pathlib.Path(__file__).with_name("reference_grids.csv.gz")
OUT_EDGES = pathlib.Path(__file__).with_name("reference_grids_edges.csv.gz")
COLUMNS = ["cls", "x0", "x1", "x2", "x3", "r0", "r1", "r2"]


def loguni(rng, lo, hi):
    return 10 ** rng.uniform(math.log10(lo), math.log10(hi))


# ---------------------------------------------------------------- references

def jac(u, m):
    u, m = mp.mpf(u), mp.mpf(m)
    return [mp.re(mp.ellipfun(f, u, m=m)) for f in ("sn", "cn", "dn")]


def amplitude(u, m):
    """am(u|m): atan2(sn, cn), for m <= 1 on the branch where am - pi u/(2K)
    lies within pi/2 of 0 (am and pi u/(2K) both pass j pi/2 at u = j K and
    am is monotone between), for m > 1 in [-pi/2, pi/2] (cn > 0 there)."""
    u = mp.mpf(u)
    sn, cn = (mp.re(mp.ellipfun(f, u, m=m)) for f in ("sn", "cn"))
    a = mp.atan2(sn, cn)
    if m < 1:
        a += 2 * mp.pi * mp.nint((mp.pi * u / (2 * mp.ellipk(m)) - a) / (2 * mp.pi))
        # a second route: F(am|m) = u
        back = mp.ellipf(a, m)
        if abs(back - u) > mp.mpf("1e-25") * max(1, abs(u)):
            raise RuntimeError(f"am({u}|{m}): F(am) = {back}")
    return a


def motion(theta0, v0, eps, t):
    """theta(t), v(t) from the closed form of data/gen_exact_reference.py."""
    return list(closed_form(theta0, v0, eps, t))


def period(theta0, v0, eps):
    k2 = k2_of(theta0, v0, eps)
    e = mp.mpf(eps)
    if k2 < 1:
        return [4 * mp.ellipk(k2) / mp.sqrt(e)]
    return [2 * mp.ellipk(1 / k2) / (mp.sqrt(k2) * mp.sqrt(e))]


def param(x, via):
    """The exact parameter m from what pendula is given (m itself, or 1 - mc)."""
    return mp.mpf(x) if via == "m" else 1 - mp.mpf(x)


def reference(cls, x):
    kind = cls.split("_")[0]
    via = "mc" if cls.endswith("_mc") else "m"
    if kind == "jac":
        return jac(x[0], param(x[1], via))
    if kind == "am":
        return [amplitude(x[0], param(x[1], via))]
    if kind == "k":
        return [mp.ellipk(param(x[0], via))]
    if kind == "e":
        return [mp.ellipe(param(x[0], via))]
    if kind == "nome":
        m = param(x[0], via)
        return [mp.exp(-mp.pi * mp.ellipk(1 - m) / mp.ellipk(m))]
    if kind in ("f", "einc"):
        phi, m = mp.mpf(x[0]), param(x[1], via)
        if m > 1 and (abs(phi) >= mp.pi / 2 or m * mp.sin(phi) ** 2 > 1):
            return [mp.nan]          # the path from 0 leaves the real domain: pendula must give NaN
        f = mp.ellipf if kind == "f" else mp.ellipe
        return [mp.re(f(phi, m))]
    if kind == "exact":
        return motion(*x[:4])
    if kind == "period":
        return period(*x[:3])
    raise ValueError(cls)


def stable(cls, x):
    # enough digits to hold the parameter 1 - mc (mc down to 1e-300) and then 40 more
    small = [abs(v) for v in x[:2] if v != 0] if cls.endswith("_mc") else []
    dps = 40 + (int(-math.log10(min(small))) if small and min(small) < 1 else 0)
    if cls.startswith(("jac", "am")) and abs(x[1]) > 1:
        dps += int(math.log10(abs(x[1])))      # mpmath's transformations of a large |m|
    if cls.startswith("exact") and abs(x[0]) > 1e3:
        dps += int(math.log10(abs(x[0])))      # the reduction of theta0
    while True:
        with mp.workdps(dps):
            a = reference(cls, x)
        with mp.workdps(2 * dps):
            b = reference(cls, x)
        if all((mp.isnan(p) and mp.isnan(q)) or abs(p - q) <= mp.mpf("1e-30") * max(abs(q), mp.mpf("1e-300"))
               for p, q in zip(a, b)):
            return [float(v) for v in b]
        dps *= 2
        if dps > 2000:
            raise RuntimeError(f"{cls} {x}: mpmath does not settle")


# ---------------------------------------------------------------- points

def points(n, seed):
    rng = random.Random(seed)
    out = []

    def u_for(m_exact):
        # |u| log-uniform from 1e-3 to 1e4 periods (4K), random sign
        K = float(mp.ellipk(m_exact)) if m_exact < 1 else float(mp.ellipk(1 / m_exact)) / math.sqrt(m_exact)
        return rng.choice([-1, 1]) * loguni(rng, 1e-3, 4e4 * max(K, 1e-3))

    for _ in range(n):
        m = rng.uniform(0, 0.5) if rng.random() < 0.5 else loguni(rng, 1e-300, 0.5)
        out.append(("jac_m_small", [u_for(m), m]))
        m = rng.uniform(0.5, 1.0)
        out.append(("jac_m_mid", [u_for(m), m]))
        m = 1 - 10 ** -rng.uniform(1, 16)
        out.append(("jac_m_near1_m", [u_for(m), m]))
        mc = loguni(rng, 1e-300, 0.5)
        K = math.log(4 / math.sqrt(mc)) + 1.0   # K(1 - mc) to within its scale
        out.append(("jac_m_near1_mc", [rng.choice([-1, 1]) * loguni(rng, 1e-3, 4e4 * K), mc]))
        m = -loguni(rng, 1e-12, 1e4)
        out.append(("jac_m_neg", [u_for(m), m]))
        m = 1 + loguni(rng, 1e-15, 1e4)
        out.append(("jac_m_gt1_m", [u_for(m), m]))
        mc = -loguni(rng, 1e-15, 1e4)
        out.append(("jac_m_gt1_mc", [u_for(1 - mc), mc]))
        # complete integrals and the nome
        for fam in ("k", "e"):
            out.append((f"{fam}_neg", [-loguni(rng, 1e-12, 1e6)]))
            out.append((f"{fam}_small", [rng.uniform(0, 0.5) if rng.random() < 0.5 else loguni(rng, 1e-300, 0.5)]))
            out.append((f"{fam}_mid", [rng.uniform(0.5, 1.0)]))
            out.append((f"{fam}_near1_mc", [loguni(rng, 1e-300, 0.5)]))
        out.append(("nome_m", [rng.uniform(0, 1) if rng.random() < 0.5 else loguni(rng, 1e-300, 1)]))
        out.append(("nome_mc", [loguni(rng, 1e-300, 1)]))
        # incomplete integrals
        for fam in ("f", "einc"):
            phi = rng.choice([-1, 1]) * loguni(rng, 1e-6, 1e4 * math.pi)
            out.append((f"{fam}_m", [phi, rng.uniform(-10, 1) if rng.random() < 0.5 else 1 - loguni(rng, 1e-15, 1)]))
            out.append((f"{fam}_near1_mc", [phi, loguni(rng, 1e-300, 0.5)]))
            m = 1 + loguni(rng, 1e-12, 1e3)
            edge = math.asin(1 / math.sqrt(m))
            phi = rng.choice([-1, 1]) * edge * (1 - loguni(rng, 1e-15, 1))
            out.append((f"{fam}_gt1_m", [phi, m]))
        # the exact motion
        eps = loguni(rng, 1e-3, 1e3)
        se = math.sqrt(eps)
        sgn = rng.choice([-1, 1])
        # libration, rotation
        th0 = rng.uniform(-math.pi, math.pi)
        k2lo = math.sin(th0 / 2) ** 2
        v0 = sgn * 2 * se * math.sqrt(max(0.0, rng.uniform(0, 1) - k2lo)) if k2lo < 1 else 0.0
        out.append(("exact_libration", [th0, v0, eps]))
        out.append(("exact_rotation", [th0, sgn * 2 * se * math.sqrt(1 + loguni(rng, 1e-3, 1e3)), eps]))
        # next to the separatrix, below and above
        d = loguni(rng, 1e-15, 1e-3)
        out.append(("exact_near_separatrix", [0.0 if rng.random() < 0.5 else rng.uniform(-3, 3),
                                              sgn * 2 * se * (1 + rng.choice([-1, 1]) * d), eps]))
        # near the top: at rest or moving slowly
        th0 = sgn * (math.pi - loguni(rng, 1e-15, 1e-2))
        out.append(("exact_near_top", [th0, 0.0 if rng.random() < 0.5 else rng.choice([-1, 1]) * loguni(rng, 1e-12, 1e-2) * se, eps]))
        # wrapped starts
        th0 = rng.choice([-1, 1]) * rng.uniform(math.pi, 1e3)
        out.append(("exact_wrapped", [th0, rng.uniform(-3, 3) * se, eps]))
    return timed_rows(out, rng, 30, periods=True)


def edge_points(n, seed):
    """The second set (see the module docstring)."""
    rng = random.Random(seed)
    out = []
    sign = lambda: rng.choice([-1, 1])  # noqa: E731

    def quarter(m):
        # the quarter period of sn(u|m) in u: K(m), or K(1/m)/sqrt(m) for m > 1
        with mp.workdps(30):
            return float(mp.ellipk(m)) if m < 1 else float(mp.ellipk(1 / m) / mp.sqrt(m))

    def u_for(m):
        q = quarter(m)
        return sign() * loguni(rng, 1e-3 * min(1.0, q), 4e4 * q)

    for _ in range(n):
        # the amplitude in every class of m
        m = rng.uniform(0, 0.5) if rng.random() < 0.5 else loguni(rng, 1e-300, 0.5)
        out.append(("am_m_small", [u_for(m), m]))
        m = rng.uniform(0.5, 1.0)
        out.append(("am_m_mid", [u_for(m), m]))
        mc = loguni(rng, 1e-300, 0.5)
        K = math.log(4 / math.sqrt(mc)) + 1.0
        out.append(("am_m_near1_mc", [sign() * loguni(rng, 1e-3, 4e4 * K), mc]))
        m = -loguni(rng, 1e-12, 1e12)
        out.append(("am_m_neg", [u_for(m), m]))
        m = 1 + loguni(rng, 1e-15, 1e4)
        out.append(("am_m_gt1_m", [u_for(m), m]))
        mc = -loguni(rng, 1e-15, 1e4)
        out.append(("am_m_gt1_mc", [u_for(1 - mc), mc]))
        # next to sn = +-1/k: u = (2j + 1) K(1/m)/k (1 + delta)
        for cls, d in (("am_edge_m", loguni(rng, 1e-15, 1e3)), ("am_edge_mc", loguni(rng, 1e-100, 1e3))):
            x = max(1 + d, math.nextafter(1.0, 2.0)) if cls.endswith("_m") else -d
            with mp.workdps(40 + max(0, int(-math.log10(d)))):
                mm = param(x, "m" if cls.endswith("_m") else "mc")
                q = mp.ellipk(1 / mm) / mp.sqrt(mm)
                j = 2 * int(loguni(rng, 1, 1e3)) + 1
                u = float(sign() * j * q * (1 + sign() * loguni(rng, 1e-17, 1e-2)))
            out.append((cls, [u, x]))
        # sn cn dn far below m = 0
        m = -loguni(rng, 1e3, 1e100)
        out.append(("jac_m_neg_far", [u_for(m), m]))
        # F and E(phi) next to multiples of pi/2
        for fam in ("f", "einc"):
            for via in ("m", "mc"):
                nq = sign() * int(loguni(rng, 1, 1e4))
                with mp.workdps(40):
                    phi = float(nq * mp.pi / 2)
                if rng.random() < 0.2:
                    phi = math.nextafter(phi, sign() * math.inf)
                else:
                    phi *= 1 + sign() * loguni(rng, 1e-17, 1e-3)
                if via == "m":
                    x = rng.uniform(-10, 1) if rng.random() < 0.5 else 1 - loguni(rng, 1e-15, 1)
                else:
                    x = loguni(rng, 1e-300, 0.5)
                out.append((f"{fam}_halfpi_{via}", [phi, x]))
        # F and E(phi) next to the edge of the real domain for m > 1
        for fam in ("f", "einc"):
            for via in ("m", "mc"):
                d = loguni(rng, 1e-16, 1e3)
                x = max(1 + d, math.nextafter(1.0, 2.0)) if via == "m" else -d
                with mp.workdps(40 + 16):
                    mm = param(x, via)
                    edge = mp.asin(1 / mp.sqrt(mm))
                    phi = float(sign() * edge * (1 + sign() * loguni(rng, 1e-17, 1e-3)))
                out.append((f"{fam}_edge_{via}", [phi, x]))
        # the exact motion from a huge theta0
        eps = loguni(rng, 1e-3, 1e3)
        th0 = sign() * loguni(rng, 1e3, 2.0**52)
        out.append(("exact_huge_theta0", [th0, rng.uniform(-3, 3) * math.sqrt(eps), eps]))
    return timed_rows(out, rng, 60, periods=False)


def timed_rows(out, rng, dps, periods):
    """The rows of the points `out`: each exact-motion start (theta0, v0, eps) once forward and once
    backward in time, to 1e4 of its periods (the period found at `dps` digits; a start on the
    separatrix is dropped), with `periods` also a row for its period; the other points as they are."""
    rows = []
    for cls, x in out:
        if cls.startswith("exact"):
            th0, v0, eps = x
            with mp.workdps(dps):
                k2 = k2_of(th0, v0, eps)
                if k2 == 1:
                    continue
                P = float(period(th0, v0, eps)[0])
            for direction in (1, -1):
                t = direction * loguni(rng, 1e-3, 1e4 * P)
                rows.append((cls + ("_fwd" if direction > 0 else "_bwd"), [th0, v0, eps, t]))
            if periods:
                rows.append(("period_" + ("libration" if k2 < 1 else "rotation"), [th0, v0, eps]))
        else:
            rows.append((cls, x))
    return rows


def work(item):
    cls, x = item
    try:
        return cls, x, stable(cls, x)
    except (ValueError, ZeroDivisionError, RuntimeError) as exc:
        return cls, x, None


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=2000, help="points per class")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--seed", type=int, default=20261123)
    ap.add_argument("--set", choices=("main", "edges"), default="main",
                    help="main: every function in every regime; edges: the ill-conditioned places")
    ap.add_argument("--out", default=None, help="default: data/reference_grids.csv.gz or ..._edges.csv.gz")
    args = ap.parse_args(argv)
    if args.out is None:
        args.out = str(OUT if args.set == "main" else OUT_EDGES)
    items = points(args.n, args.seed) if args.set == "main" else edge_points(args.n, args.seed)
    done = []
    with mpr.Pool(args.jobs) as pool:
        for k, res in enumerate(pool.imap(work, items, chunksize=16)):
            done.append(res)
            if k % 2000 == 0:
                print(f"  {k}/{len(items)}", file=sys.stderr, flush=True)
    with gzip.open(args.out, "wt", newline="") as fh:
        fh.write(f"# generated by data/gen_reference_grids.py --set {args.set} with mpmath {mp.__version__}, "
                 f"seed {args.seed}, {args.n} draws per class\n")
        w = csv.writer(fh)
        w.writerow(COLUMNS)
        skipped = 0
        for cls, x, r in done:
            if r is None:
                skipped += 1
                continue
            xs = (list(x) + [""] * 4)[:4]
            rs = (list(r) + [""] * 3)[:3]
            w.writerow([cls] + [repr(float(v)) if v != "" else "" for v in xs]
                       + [repr(float(v)) if v != "" else "" for v in rs])
    print(f"wrote {len(done) - skipped} rows to {args.out} ({skipped} skipped)")


if __name__ == "__main__":
    main()

"""Reference Mathieu characteristic values and transmon levels at high precision.

Writes data/mathieu_reference.csv and data/transmon_reference.csv.

Mathieu values (50 digits, mpmath):

* where the Hill matrix is small (at most 60 rows), mpmath's symmetric
  eigenvalue solver (``mp.eigsy``, Jacobi rotations) on the truncated matrix,
  the value picked by sorting; the truncation is checked by recomputing with
  20 more rows on each side (agreement to 1e-40 is required);
* otherwise (large |q| or order) the root of the Hill continued fraction
  split at the row of the eigenvector's largest component (secant in mp),
  started from a bracket that is certified by mp Sturm counts of the
  truncated matrix, and the index is checked again by counts just below and
  above the root; truncation checked as above.

Neither route is the kernel's (double-precision bisection with a
twisted-factorisation bound); the counts decide only which eigenvalue is
meant, never its digits.

Points: published values (Abramowitz and Stegun, Table 20.1 as printed; the
value a_5(21) = 37.462613226 quoted against SciPy), integer orders 0..15
against random q of both signs from 1e-8 to 1e4, non-integer orders (random
and next to integers), pairs next to the double points a_n ~ b_n+1 at large
q, orders to 1000, and |q| up to 1e8.  All random points are seeded.

Transmon levels (40 digits): eigenvalues of H = 4 E_C (n - n_g)^2 - E_J
cos phi in the charge basis n = -K..K by mp.eigsy, at E_J/E_C = 1, 5, 20,
50, 100 and several n_g, K raised until the six lowest levels agree to 1e-35.

The Mathieu functions ce_n, se_n (30 digits): data/mathieu_function_reference.csv,
from the eigenvectors of the one-sided matrices (mp.eigsy), twelve (n, q)
cases of both signs of q at seven points each.

Run: .venv/bin/python data/gen_mathieu_reference.py [mathieu] [transmon] [functions]
(all by default; about ten minutes on a quiet machine)
"""

from __future__ import annotations

import csv
import math
import pathlib
import random

import mpmath as mp

HERE = pathlib.Path(__file__).resolve().parent
EIGSY_MAX = 60


def family(kind: str, nu):
    """(fam, offset, index) of the matrix holding kind_nu: fam 0 bi-infinite
    (rows k, order nu + 2k), 1..4 the one-sided matrices of DLMF 28.4."""
    if nu != int(nu):
        return 0, nu, int(math.floor(nu))
    n = int(nu)
    if kind == "a":
        return (1, 0, n // 2) if n % 2 == 0 else (2, 1, (n - 1) // 2)
    return (3, 1, (n - 1) // 2) if n % 2 == 1 else (4, 2, n // 2 - 1)


def rows(fam, nu, q, half):
    """Diagonal and squared couplings of the window of orders |s| <= half."""
    nu = mp.mpf(nu)
    q = mp.mpf(q)
    if fam == 0:
        k0 = int(mp.ceil((-half - nu) / 2))
        k1 = int(mp.floor((half - nu) / 2))
        d = [(nu + 2 * k) ** 2 for k in range(k0, k1 + 1)]
        e2 = [q * q] * (len(d) - 1)
        # index: rows of order |nu + 2k| < nu are -nu < k < 0
        first = k0
    else:
        base = {1: 0, 2: 1, 3: 1, 4: 2}[fam]
        n = int((half - base) // 2) + 1
        d = [mp.mpf(base + 2 * i) ** 2 for i in range(n)]
        e2 = [q * q] * (n - 1)
        if fam == 1:
            e2[0] = 2 * q * q
        if fam == 2:
            d[0] = 1 + q
        if fam == 3:
            d[0] = 1 - q
        first = 0
    return d, e2, first


def window_index(fam, nu, m, first):
    if fam == 0:
        return sum(1 for k in range(first, 0) if abs(nu + 2 * k) < nu)
    return m


def count(d, e2, x):
    c = 0
    t = d[0] - x
    if t < 0:
        c += 1
    for i in range(1, len(d)):
        if t == 0:
            t = mp.mpf("1e-80")
        t = d[i] - x - e2[i - 1] / t
        if t < 0:
            c += 1
    return c


def by_eigsy(d, e2, j):
    n = len(d)
    a = mp.matrix(n, n)
    for i in range(n):
        a[i, i] = d[i]
        if i + 1 < n:
            a[i, i + 1] = a[i + 1, i] = mp.sqrt(e2[i])
    ev = sorted(mp.eigsy(a, eigvals_only=True))
    return ev[j]


def by_fraction(d, e2, j, guess):
    """Root of the continued fraction split at the twist row, from a bracket
    around guess certified by Sturm counts."""
    w = mp.mpf("1e-6") * max(1, abs(guess))
    lo, hi = guess - w, guess + w
    while count(d, e2, lo) > j:
        lo -= w
        w *= 4
    while count(d, e2, hi) <= j:
        hi += w
        w *= 4
    for _ in range(30):   # a few bisections: the bracket then holds one root well
        mid = (lo + hi) / 2
        if count(d, e2, mid) > j:
            hi = mid
        else:
            lo = mid
    x0 = (lo + hi) / 2

    def gamma(x, c=None):
        n = len(d)
        up = [mp.mpf(0)] * n
        dn = [mp.mpf(0)] * n
        for i in range(1, n):
            dn[i] = e2[i - 1] / (d[i - 1] - x - dn[i - 1])
        for i in range(n - 2, -1, -1):
            up[i] = e2[i] / (d[i + 1] - x - up[i + 1])
        g = [d[i] - x - dn[i] - up[i] for i in range(n)]
        if c is None:
            c = min(range(n), key=lambda i: abs(g[i]))
        return g[c], c

    _, c = gamma(x0)
    root = mp.findroot(lambda x: gamma(x, c)[0], (lo, hi), solver="anderson", tol=mp.mpf(10) ** (-2 * mp.mp.dps + 10))
    eps = mp.mpf(10) ** (-mp.mp.dps + 8) * max(1, abs(root))
    assert count(d, e2, root - eps) <= j < count(d, e2, root + eps), "index check failed"
    return root


def char_value(kind, nu, q, guess=None):
    fam, _, m = family(kind, nu)
    nuq = mp.mpf(nu)
    aq = abs(mp.mpf(q))
    p = mp.sqrt(nuq ** 2 + 6 * aq)
    results = []
    for extra in (0, 40):
        half = p + 40 + 12 * max(0, mp.log10(max(aq, 1))) * 2 + extra
        d, e2, first = rows(fam, nu, q, half)
        j = window_index(fam, nu, m, first)
        if len(d) <= EIGSY_MAX:
            results.append(by_eigsy(d, e2, j))
        else:
            g = guess if guess is not None else mp.mpf(nu) ** 2
            results.append(by_fraction(d, e2, j, mp.mpf(g)))
    assert abs(results[0] - results[1]) <= mp.mpf(10) ** -40 * max(1, abs(results[1])), (kind, nu, q)
    return results[1], len(d)


def asymptotic_guess(kind, nu, q):
    """A starting value only (the counts certify the bracket): DLMF 28.8.1."""
    if abs(q) < 10 or nu != int(nu):
        return None
    h = math.sqrt(abs(q))
    n = int(nu)
    if q < 0 and n % 2 == 1:
        kind = "b" if kind == "a" else "a"
    s = 2 * n + 1 if kind == "a" else 2 * n - 1
    return -2 * abs(q) + 2 * s * h - (s * s + 1) / 8


def mathieu_points():
    rnd = random.Random(20261203)
    pts = []   # (kind, nu, q, source)
    # published: Abramowitz and Stegun, Table 20.1 (8D as printed), and the
    # value quoted against SciPy's mathieu_a(5, 21)
    printed = [("a", 0, 5.0, "-5.80004602"), ("b", 1, 5.0, "-5.79008060"), ("a", 1, 5.0, "1.85818754"),
               ("b", 2, 5.0, "2.09946045"), ("a", 2, 5.0, "7.44910974"),
               ("a", 0, 25.0, "-40.25677955"), ("b", 1, 25.0, "-40.25677898"),
               ("a", 1, 25.0, "-21.31489969"), ("b", 2, 25.0, "-21.31486062"), ("a", 2, 25.0, "-3.52216473"),
               ("a", 5, 21.0, "37.462613226")]
    for kind, n, q, v in printed:
        pts.append((kind, float(n), q, "published", v))
    for n in range(16):
        for _ in range(4):
            q = rnd.choice([-1, 1]) * 10 ** rnd.uniform(-8, 4)
            pts.append(("a", float(n), q, "integer", ""))
            if n >= 1:
                pts.append(("b", float(n), q, "integer", ""))
    for _ in range(70):
        nu = rnd.uniform(0, 12)
        q = rnd.choice([-1, 1]) * 10 ** rnd.uniform(-8, 4)
        pts.append(("a", nu, q, "non-integer", ""))
    for n in range(4):   # next to the integers: the values approach b_n from below and a_n from above (q > 0)
        for dnu in (1e-9, 1e-4):
            q = 10 ** rnd.uniform(-1, 2)
            pts.append(("a", n + dnu, q, "near-integer", ""))
            if n >= 1:
                pts.append(("a", n - dnu, q, "near-integer", ""))
    for q in (60.0, 250.0, 1000.0, 4000.0):   # double points a_n ~ b_n+1
        for n in range(4):
            pts.append(("a", float(n), q, "double-point", ""))
            pts.append(("b", float(n + 1), q, "double-point", ""))
    for nu, q in ((50.0, 30.0), (50.5, 700.0), (100.0, 2000.0), (250.25, 3.0), (1000.0, 1e4), (999.5, 1e5)):
        pts.append(("a", nu, q, "large-order", ""))
        if nu == int(nu):
            pts.append(("b", nu, q, "large-order", ""))
    for q in (1e5, -1e6, 1e7, 1e8):
        pts.append(("a", 0.0, q, "huge-q", ""))
        pts.append(("b", 1.0, q, "huge-q", ""))
        pts.append(("a", 2.5, q, "huge-q", ""))
        pts.append(("a", 7.0, q, "huge-q", ""))
    return pts


def transmon_rows():
    out = []
    rnd = random.Random(42)
    ngs = ["0", "0.5", "0.25", "0.125", "0.37", "-0.2", "1.3"] + [repr(rnd.uniform(0, 1)) for _ in range(3)]
    for ratio in (1, 5, 20, 50, 100):
        for ng_s in ngs:
            ng = mp.mpf(float(ng_s))
            prev = None
            for K in (20, 30, 40, 60):
                n = 2 * K + 1
                h = mp.matrix(n, n)
                for i in range(n):
                    k = i - K
                    h[i, i] = 4 * (k - ng) ** 2
                    if i + 1 < n:
                        h[i, i + 1] = h[i + 1, i] = -mp.mpf(ratio) / 2
                ev = sorted(mp.eigsy(h, eigvals_only=True))[:6]
                if prev is not None and max(abs(a - b) for a, b in zip(ev, prev)) < mp.mpf("1e-35"):
                    break
                prev = ev
            else:
                raise RuntimeError("charge basis did not converge")
            for m, e in enumerate(ev):
                out.append({"EJ_over_EC": ratio, "n_g": ng_s, "m": m, "E_over_EC": mp.nstr(e, 40)})
            print("transmon", ratio, ng_s, "K =", K, flush=True)
    return out


def main(parts=("mathieu", "transmon", "functions")):
    if "mathieu" in parts:
        write_mathieu()
    if "transmon" in parts:
        write_transmon()
    if "functions" in parts:
        write_functions()


def write_functions():
    """ce_n, se_n and their derivatives (30 digits): the eigenvector of the
    one-sided matrix by mp.eigsy (rows grown until the coefficients agree to
    1e-28), normalised by DLMF 28.4.9-12, signed so that ce_n(0) > 0 and
    se_n'(0) > 0, summed at the points."""
    mp.mp.dps = 30
    rnd = random.Random(7)
    cases = [("ce", 0, 1.0), ("ce", 1, 2.0), ("se", 1, 2.0), ("se", 2, 5.0), ("ce", 3, -3.0),
             ("se", 3, -3.0), ("ce", 2, 25.0), ("ce", 5, 21.0), ("se", 6, -40.0), ("ce", 0, 1e-6),
             ("ce", 4, 0.3), ("se", 4, 150.0)]
    out = []
    for kind, n, q in cases:
        fam, base, m = family("a" if kind == "ce" else "b", n)
        prev = None
        for half in (40 + 2 * n + 4 * math.sqrt(abs(q)), 60 + 2 * n + 5 * math.sqrt(abs(q))):
            d, e2, _ = rows(fam, n, q, half)
            nr = len(d)
            a = mp.matrix(nr, nr)
            for i in range(nr):
                a[i, i] = d[i]
                if i + 1 < nr:
                    a[i, i + 1] = a[i + 1, i] = (1 if q >= 0 else -1) * mp.sqrt(e2[i])
            ev, vec = mp.eigsy(a)
            order = sorted(range(nr), key=lambda i: ev[i])
            y = [vec[i, order[m]] for i in range(nr)]
            if fam == 1:
                y[0] = y[0] / mp.sqrt(2)
            orders = [base + 2 * i for i in range(nr)]
            s = sum(y) if kind == "ce" else sum(o * c for o, c in zip(orders, y))
            if s < 0:
                y = [-c for c in y]
            if prev is not None:
                assert max(abs(u - v) for u, v in zip(y, prev)) < mp.mpf("1e-28"), (kind, n, q)
            prev = y + [mp.mpf(0)] * 20
        zs = [0.0, math.pi / 2, 1.0] + [rnd.uniform(0, 2 * math.pi) for _ in range(4)]
        for z in zs:
            zm = mp.mpf(z)
            if kind == "ce":
                v = sum(c * mp.cos(o * zm) for c, o in zip(y, orders))
                dv = -sum(o * c * mp.sin(o * zm) for c, o in zip(y, orders))
            else:
                v = sum(c * mp.sin(o * zm) for c, o in zip(y, orders))
                dv = sum(o * c * mp.cos(o * zm) for c, o in zip(y, orders))
            out.append({"kind": kind, "n": n, "q": repr(q), "z": repr(z),
                        "value": mp.nstr(v, 28), "derivative": mp.nstr(dv, 28)})
        print("function", kind, n, q, flush=True)
    write_csv("mathieu_function_reference.csv", out)


def write_mathieu():
    mp.mp.dps = 50
    rows_out = []
    for kind, nu, q, source, printed in mathieu_points():
        val, n = char_value(kind, nu, q, asymptotic_guess(kind, nu, q))
        rows_out.append({"kind": kind, "nu": repr(float(nu)), "q": repr(float(q)), "source": source,
                         "value": mp.nstr(val, 45), "printed": printed, "rows": n})
        print(kind, nu, q, mp.nstr(val, 20), n, flush=True)
    write_csv("mathieu_reference.csv", rows_out)


def write_transmon():
    mp.mp.dps = 40
    tr = transmon_rows()
    write_csv("transmon_reference.csv", tr)



def write_csv(name, rows):
    """The rows (dicts with the same keys, in order) as data/NAME, a header line first."""
    with open(HERE / name, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

if __name__ == "__main__":
    import sys

    main(tuple(sys.argv[1:]) or ("mathieu", "transmon", "functions"))

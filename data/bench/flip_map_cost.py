"""The cost of Heyl's flip-time map of the double pendulum: pendula against SciPy and a compiled numba
peer on the same pixels, in one run.

A benchmark, not a test (no time is asserted).  The map: 1000 x 1000 pixels, theta1 and theta2 on
linspace(-pi, pi, 1000), from rest, equal point masses and lengths (g = l = 1), searched up to
t_max = 30, every pixel run at rtol and at rtol / 10 (as DoublePendulum.flip_map does, to mark the
unresolved ones); pixels where the energy forbids a flip (2 cos theta1 + cos theta2 > 1, exact) are
skipped by every code.  The whole map is too long for this shared 2-core machine, so whole rows of it
(strips of 1000 pixels at seeded random theta1) are timed and the map's time is extrapolated as
1000 times the mean strip (the rows' costs differ: the spread is printed).

The peers, each doing the same two runs per pixel:
  * pendula: DoublePendulum.flip_map on the strip, one thread;
  * numba: numbalsoda's dop853 (Hairer's DOP853 in C++) called from a numba-compiled loop over the
    pixels, the right-hand side a numba cfunc; the path is output on pendula's grid (a tenth of the
    fast normal mode's period) in chunks of 16 grid steps, the first grid interval where abs(theta_i)
    passes pi is located and the crossing polished by Newton's method on the integrated path (the
    same scheme as pendula's: equal work, equal accuracy);
  * diffrax: Dopri8 under jax.jit and jax.vmap over the strip's pixels that may flip (float64), the
    flip a diffrax Event (max(abs(theta1), abs(theta2)) = pi, its root by Newton); compile time
    excluded (one warm-up call per strip size);
  * SciPy: solve_ivp (DOP853, terminal events abs(theta_i) = pi, a NumPy-free right-hand side), on
    a seeded random sample of each strip's pixels (its cost per pixel extrapolated).
Equal accuracy: every code's flip times against SciPy's DOP853 at rtol 1e-13 with events (the reference)
on the sampled pixels, as the median relative error over the pixels whose flip time is not chaotic
(within 1e-3 of the reference).  pendula runs at rtol = atol = 1e-10; the peers at 1e-10, 1e-11 and
1e-12 (their error at equal rtol is larger than pendula's), and each peer's time at pendula's error is
interpolated in log-log between its runs.

Run: .venv/bin/python data/bench/flip_map_cost.py [strips] [scipy_pixels_per_strip]
     (`make bench-peers` installs numba, numbalsoda, diffrax and jax; writes data/bench/flip_map_cost.json)
     .venv/bin/python data/bench/flip_map_cost.py --whole [numba_rtol]
     the whole 1000 x 1000 map, not extrapolated: pendula (rtol 1e-10) and the numba peer (default rtol
     1e-11, its rtol nearest pendula's error in the strips), one thread each, one after the other; the
     two maps' flip times compared pixel by pixel (writes data/bench/flip_map_whole.json)
"""

import json
import math
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

import pendula

HERE = Path(__file__).resolve().parent
SIDE = 1000
T_MAX = 30.0
RTOL = 1e-10


def scipy_flip(th1, th2, t_max, rtol):
    def rhs(t, y):
        t1, t2, w1, w2 = y
        d = t1 - t2
        c, s = math.cos(d), math.sin(d)
        r1 = -s * w2 * w2 - 2.0 * math.sin(t1)
        r2 = s * w1 * w1 - math.sin(t2)
        det = 2.0 - c * c                       # M = [[2, c], [c, 1]]
        return [w1, w2, (r1 - c * r2) / det, (2.0 * r2 - c * r1) / det]

    evs = []
    for j in (0, 1):
        def ev(t, y, j=j):
            return abs(y[j]) - math.pi
        ev.terminal = True
        evs.append(ev)
    sol = solve_ivp(rhs, (0.0, t_max), [th1, th2, 0.0, 0.0], method="DOP853", rtol=rtol, atol=rtol, events=evs)
    hits = [te[0] for te in sol.t_events if te.size]
    return min(hits) if hits else math.inf


def numba_peer():
    """The compiled peer: a function (theta1, theta2s, t_max, rtol) -> flip times, all in numba."""
    import numba as nb
    from numbalsoda import dop853, lsoda_sig

    @nb.cfunc(lsoda_sig)
    def rhs(t, u_, du_, p_):
        u = nb.carray(u_, (4,))
        du = nb.carray(du_, (4,))
        d = u[0] - u[1]
        c, s = math.cos(d), math.sin(d)
        r1 = -s * u[3] * u[3] - 2.0 * math.sin(u[0])
        r2 = s * u[2] * u[2] - math.sin(u[1])
        det = 2.0 - c * c
        du[0] = u[2]
        du[1] = u[3]
        du[2] = (r1 - c * r2) / det
        du[3] = (2.0 * r2 - c * r1) / det
    ptr = rhs.address
    h = 0.1 * 2 * math.pi / math.sqrt(2 + math.sqrt(2))   # a tenth of the fast mode's period
    chunk = 16

    @nb.njit
    def flip_one(th1, th2, t_max, rtol, data):
        u = np.array([th1, th2, 0.0, 0.0])
        t = 0.0
        while t < t_max:
            m = chunk
            if t + m * h > t_max:
                m = int(math.ceil((t_max - t) / h))
            te = np.empty(m + 1)
            for k in range(m + 1):
                te[k] = min(t + k * h, t_max)
            us, ok = dop853(ptr, u, te, data, rtol, rtol)
            if not ok:
                return np.nan
            for k in range(1, m + 1):
                for j in range(2):
                    if abs(us[k, j]) >= math.pi:
                        # Newton on the path from the grid point before: abs(theta_j(t)) = pi
                        a = us[k - 1, j]
                        b = us[k, j]
                        sg = 1.0 if b > 0 else -1.0
                        ts = te[k - 1] + (math.pi - sg * a) / (sg * b - sg * a) * (te[k] - te[k - 1])
                        for _ in range(12):
                            if not ts > te[k - 1]:
                                ts = te[k - 1] + 1e-3 * (te[k] - te[k - 1])
                            tt = np.array([te[k - 1], ts])
                            ys, ok = dop853(ptr, us[k - 1].copy(), tt, data, rtol, rtol)
                            f = sg * ys[1, j] - math.pi
                            step = f / (sg * ys[1, 2 + j])
                            ts -= step
                            if abs(step) <= 1e-15 * ts:
                                break
                        return ts
            u = us[m].copy()
            t = te[m]
        return np.inf

    @nb.njit
    def strip(th1, th2s, t_max, rtol):
        data = np.zeros(1)
        out = np.full(th2s.size, np.inf)
        for i in range(th2s.size):
            if 2 * math.cos(th1) + math.cos(th2s[i]) > 1:     # the energy forbids a flip
                continue
            out[i] = flip_one(th1, th2s[i], t_max, rtol, data)
            flip_one(th1, th2s[i], t_max, rtol / 10, data)    # the map's second run
        return out
    strip(1.0, np.array([2.0, 3.0]), 2.0, 1e-6)               # compile
    return strip


def equal_error_time(err, runs):
    """A code's time at the error err, interpolated in log-log between its runs (flag: inside their range)."""
    le = np.log([r[0] for r in runs])
    lt = np.log([r[1] for r in runs])
    o = np.argsort(le)
    return float(np.exp(np.interp(np.log(err), le[o], lt[o]))), bool(le.min() <= np.log(err) <= le.max())


def median_error(times, ref):
    """The median relative error of flip times against the reference over the pixels that flip, at t > 0,
    in both, and whose flip time is not chaotic (within 1e-3 of the reference)."""
    ok = np.isfinite(ref) & np.isfinite(times) & (ref > 0)
    e = np.abs(times[ok] - ref[ok]) / ref[ok]
    e = e[e < 1e-3]
    return float(np.median(e)) if e.size else float("nan")


def diffrax_peer():
    """diffrax's Dopri8 under jax.jit and jax.vmap over a strip's pixels, the flip as a diffrax Event
    (max(abs(theta1), abs(theta2)) - pi, its root by optimistix's Newton): (theta1, theta2s, t_max, rtol)
    -> flip times, each pixel also run at rtol / 10 as the map does."""
    import jax
    jax.config.update("jax_enable_x64", True)
    import diffrax
    import jax.numpy as jnp
    import optimistix as optx

    def f(t, y, args):
        d = y[0] - y[1]
        c, s = jnp.cos(d), jnp.sin(d)
        r1 = -s * y[3] * y[3] - 2.0 * jnp.sin(y[0])
        r2 = s * y[2] * y[2] - jnp.sin(y[1])
        det = 2.0 - c * c
        return jnp.stack([y[2], y[3], (r1 - c * r2) / det, (2.0 * r2 - c * r1) / det])

    def cond(t, y, args, **kwargs):
        return jnp.maximum(jnp.abs(y[0]), jnp.abs(y[1])) - jnp.pi

    def flip(y0, rtol, t_max):
        sol = diffrax.diffeqsolve(diffrax.ODETerm(f), diffrax.Dopri8(), 0.0, t_max, None, y0,
                                  stepsize_controller=diffrax.PIDController(rtol=rtol, atol=rtol),
                                  event=diffrax.Event(cond, root_finder=optx.Newton(rtol=1e-13, atol=1e-13)),
                                  saveat=diffrax.SaveAt(t1=True), max_steps=10**6, throw=False)
        # a pixel on the top (abs(theta) = pi at t = 0) ends at once: its event time is 0
        return jnp.where(sol.event_mask, sol.ts[-1], jnp.inf)
    batch = jax.jit(jax.vmap(flip, in_axes=(0, None, None)), static_argnums=(2,))

    def strip(th1, th2s, t_max, rtol):
        out = np.full(th2s.size, np.inf)
        allowed = np.flatnonzero(~(2 * np.cos(th1) + np.cos(th2s) > 1))
        if allowed.size:
            y0 = jnp.asarray(np.stack([np.full(allowed.size, th1), th2s[allowed], np.zeros(allowed.size),
                                       np.zeros(allowed.size)], 1))
            out[allowed] = np.asarray(batch(y0, rtol, t_max))
            batch(y0, rtol / 10, t_max).block_until_ready()      # the map's second run
        return out

    def warm(th1, th2s, t_max):   # compile for this strip's batch size (rtol is traced: one compilation)
        allowed = np.flatnonzero(~(2 * np.cos(th1) + np.cos(th2s) > 1))
        if allowed.size:
            batch(jnp.zeros((allowed.size, 4)), 1e-6, t_max).block_until_ready()
    return strip, warm


def main(strips: int = 3, n_scipy: int = 12) -> None:
    grid = np.linspace(-math.pi, math.pi, SIDE)
    rng = np.random.default_rng(20261204)
    rows = rng.choice(SIDE, strips, replace=False)
    dp = pendula.DoublePendulum()
    peer = numba_peer()
    dfx, dfx_warm = diffrax_peer()
    dp.flip_map([1.0], [2.0, 3.0], t_max=2.0, threads=1)      # warm
    peer_rtols = (RTOL, RTOL / 10, RTOL / 100)                # the peers' runs, to reach pendula's error
    rec_rows = []
    got = {"pendula": ([], [])} | {f"{c}@{r:.0e}": ([], []) for c in ("numba", "diffrax", "scipy")
                                        for r in peer_rtols}
    cost = {k: 0.0 for k in got}
    for r in rows:
        th1 = float(grid[r])
        allowed = np.flatnonzero(~(2 * np.cos(th1) + np.cos(grid) > 1))
        sample = rng.choice(allowed, min(n_scipy, allowed.size), replace=False) if allowed.size else allowed
        ref = np.array([scipy_flip(th1, grid[i], T_MAX, 1e-13) for i in sample])
        row = {"theta1": th1, "allowed_pixels": int(allowed.size), "scipy_pixels_timed": int(sample.size)}
        t0 = time.perf_counter()
        tp = dp.flip_map([th1], grid, t_max=T_MAX, rtol=RTOL, atol=RTOL, threads=1).time[0]
        row["pendula_s"] = time.perf_counter() - t0
        got["pendula"][0].extend(np.asarray(tp)[sample]); got["pendula"][1].extend(ref)
        dfx_warm(th1, grid, T_MAX)
        for rt in peer_rtols:
            t0 = time.perf_counter()
            td = dfx(th1, grid, T_MAX, rt)
            row[f"diffrax_s@{rt:.0e}"] = time.perf_counter() - t0
            got[f"diffrax@{rt:.0e}"][0].extend(td[sample]); got[f"diffrax@{rt:.0e}"][1].extend(ref)
            t0 = time.perf_counter()
            tn = peer(th1, grid, T_MAX, rt)
            row[f"numba_s@{rt:.0e}"] = time.perf_counter() - t0
            got[f"numba@{rt:.0e}"][0].extend(tn[sample]); got[f"numba@{rt:.0e}"][1].extend(ref)
            t0 = time.perf_counter()
            ts = np.array([scipy_flip(th1, grid[i], T_MAX, rt) for i in sample])
            for i in sample:
                scipy_flip(th1, grid[i], T_MAX, rt / 10)
            row[f"scipy_s@{rt:.0e}"] = (time.perf_counter() - t0) / max(1, sample.size) * allowed.size
            got[f"scipy@{rt:.0e}"][0].extend(ts); got[f"scipy@{rt:.0e}"][1].extend(ref)
        rec_rows.append(row)
        print(f"strip theta1 = {th1:+.4f} ({allowed.size} pixels may flip): pendula {row['pendula_s']:7.3f} s   "
              + "   ".join(f"numba rtol {rt:.0e} {row[f'numba_s@{rt:.0e}']:7.3f} s" for rt in peer_rtols)
              + "   " + "   ".join(f"diffrax rtol {rt:.0e} {row[f'diffrax_s@{rt:.0e}']:7.3f} s" for rt in peer_rtols)
              + f"   scipy rtol {RTOL:.0e} {row[f'scipy_s@{RTOL:.0e}']:8.2f} s (from {sample.size} pixels)",
              flush=True)
    err = {k: median_error(np.array(v[0]), np.array(v[1])) for k, v in got.items()}
    mean = {k: float(np.mean([row[k] for row in rec_rows])) for k in rec_rows[0] if k.endswith("_s") or "_s@" in k}
    summary = {"pendula": {"error": err["pendula"], "map_s": mean["pendula_s"] * SIDE}}
    for c in ("numba", "diffrax", "scipy"):
        runs = [(err[f"{c}@{rt:.0e}"], mean[f"{c}_s@{rt:.0e}"]) for rt in peer_rtols]
        t_eq, inside = equal_error_time(err["pendula"], runs)
        summary[c] = {"runs": [{"rtol": rt, "error": e, "map_s": t * SIDE} for rt, (e, t) in zip(peer_rtols, runs)],
                      "map_s_at_pendula_error": t_eq * SIDE, "interpolated": inside,
                      "ratio_peer_over_pendula": t_eq / mean["pendula_s"]}
    print("median relative error of the flip times vs SciPy rtol 1e-13 (non-chaotic sampled pixels): "
          + ", ".join(f"{k} {v:.1e}" for k, v in err.items()))
    print(f"the 1000 x 1000 map, extrapolated from {strips} strips (one thread), at pendula's error "
          f"{err['pendula']:.1e}: pendula {summary['pendula']['map_s'] / 60:.1f} min, "
          f"numba {summary['numba']['map_s_at_pendula_error'] / 60:.1f} min, "
          f"diffrax {summary['diffrax']['map_s_at_pendula_error'] / 60:.1f} min, "
          f"scipy {summary['scipy']['map_s_at_pendula_error'] / 3600:.1f} h;  ratios numba/pendula "
          f"{summary['numba']['ratio_peer_over_pendula']:.2f}"
          f"{'' if summary['numba']['interpolated'] else ' (extrapolated)'}, diffrax/pendula "
          f"{summary['diffrax']['ratio_peer_over_pendula']:.2f}"
          f"{'' if summary['diffrax']['interpolated'] else ' (extrapolated)'}, scipy/pendula "
          f"{summary['scipy']['ratio_peer_over_pendula']:.1f}"
          f"{'' if summary['scipy']['interpolated'] else ' (extrapolated)'}")
    rec = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
           "machine": platform.processor() or platform.machine(), "cores": os.cpu_count(),
           "load_average_at_end": os.getloadavg(), "pendula": pendula.__version__,
           "task": f"flip-time map {SIDE}x{SIDE}, t_max {T_MAX}, pendula at rtol {RTOL} (and rtol/10 per pixel), "
                   "the peers at rtol, rtol/10, rtol/100 (each pixel also at a tenth of that), one thread",
           "strips": rec_rows, "median_relative_error": err, "summary": summary}
    (HERE / "flip_map_cost.json").write_text(json.dumps(rec, indent=1) + "\n")


def whole(numba_rtol: float = 1e-11) -> None:
    """The whole map by pendula and by the numba peer, each timed over all its rows."""
    grid = np.linspace(-math.pi, math.pi, SIDE)
    dp = pendula.DoublePendulum()
    peer = numba_peer()
    dp.flip_map([1.0], [2.0, 3.0], t_max=2.0, threads=1)      # warm
    t0 = time.perf_counter()
    fm = dp.flip_map(grid, grid, t_max=T_MAX, rtol=RTOL, atol=RTOL, threads=1)
    t_pendula = time.perf_counter() - t0
    print(f"pendula: the whole map in {t_pendula / 60:.2f} min (one thread)", flush=True)
    t0 = time.perf_counter()
    tn = np.stack([peer(float(a), grid, T_MAX, numba_rtol) for a in grid])
    t_numba = time.perf_counter() - t0
    print(f"numba peer at rtol {numba_rtol:.0e}: the whole map in {t_numba / 60:.2f} min (one thread)", flush=True)
    tp = np.asarray(fm.time)
    both = np.isfinite(tp) & np.isfinite(tn)
    rel = np.abs(tp[both] - tn[both]) / tn[both]
    same_verdict = float(np.mean(np.isfinite(tp) == np.isfinite(tn)))
    print(f"ratio numba / pendula {t_numba / t_pendula:.2f}; flip times of the two maps: median relative "
          f"difference {np.median(rel):.1e} over {both.sum()} pixels that flip in both; the same verdict "
          f"(flips by t_max or not) on {100 * same_verdict:.2f} % of pixels")
    rec = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
           "machine": platform.processor() or platform.machine(), "cores": os.cpu_count(),
           "load_average_at_end": os.getloadavg(), "pendula": pendula.__version__,
           "task": f"the whole flip-time map {SIDE}x{SIDE}, t_max {T_MAX}, pendula at rtol {RTOL}, numba peer at "
                   f"rtol {numba_rtol} (each pixel also at a tenth of its rtol), one thread each, in turn",
           "pendula_s": t_pendula, "numba_s": t_numba, "ratio_numba_over_pendula": t_numba / t_pendula,
           "median_relative_difference": float(np.median(rel)), "pixels_flipping_in_both": int(both.sum()),
           "same_verdict_fraction": same_verdict, "unresolved_pendula": int(np.sum(fm.unresolved))}
    (HERE / "flip_map_whole.json").write_text(json.dumps(rec, indent=1) + "\n")


if __name__ == "__main__":
    if sys.argv[1:2] == ["--whole"]:
        whole(*(float(a) for a in sys.argv[2:3]))
    else:
        main(*(int(a) for a in sys.argv[1:3]))

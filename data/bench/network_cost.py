"""What a chain of pendula costs: pendula.Network.simulate (DOP853) against its peers in one run, on the
Frenkel-Kontorova chain

    φ_i'' = −sin φ_i + K (φ_{i+1} − 2 φ_i + φ_{i−1}),  free ends, K = 1,

N = 2, 16, 256, 4096, from a smooth wave φ_i(0) = 0.5 sin(2πi/N + 0.3), over t = 0 .. 10.

The peers: SciPy's solve_ivp (DOP853, the right-hand side vectorised in numpy); numbalsoda's dop853
(Hairer's DOP853 in C++, the right-hand side a numba cfunc); diffrax's Dopri8 under jax.jit (float64,
PID step control, only the end state saved; compile time excluded: the first call is a warm-up).  vmap
is diffrax's answer to a batch: the main cells are one trajectory each (jit alone), and a batch cell
(64 chains of 16 from seeded random phases) maps diffrax's solve over the batch with jax.vmap,
pendula runs it in one call (phi0 of 64 rows, OpenMP threads: the machine's cores) and numbalsoda loops.

Equal error: every code runs at several rtol (atol rtol/100); each run's error is the largest
difference of the state at t = 10 from SciPy's DOP853 at rtol 1e-13 (the reference, not pendula's
output); a peer's time at pendula's error is interpolated in log-log between the peer's two bracketing
runs (flagged when pendula's error lies outside the peer's range).  Each timing is the best of several
calls (fewer for the slow SciPy runs at N = 4096).  Where the time of pendula's call goes is
recorded beside it: the kernel's own share (the private binding pendula._kernel.network_simulate_v
called directly, a diagnostic, not a public path), the rest being the Python wrapper's checks and the
xarray Dataset it builds.  Peers that are not installed are listed as such
(`make bench-peers` installs them).

    .venv/bin/python data/bench/network_cost.py     # writes data/bench/network_cost.json
"""

import json
import os
import platform
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

import pendula

HERE = Path(__file__).resolve().parent
SIZES = (2, 16, 256, 4096)
RTOLS = (1e-6, 1e-8, 1e-10)                          # pendula's runs
PEER_RTOLS = (1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11)  # the peers' runs, to bracket pendula's errors
T_END = 10.0
K = 1.0
PEERS = ("scipy", "numbalsoda", "diffrax")


def rhs_factory(n):
    def f(t, y):
        q, v = y[:n], y[n:]
        lap = np.zeros(n)
        lap[:-1] += q[1:] - q[:-1]
        lap[1:] += q[:-1] - q[1:]
        return np.concatenate([v, -np.sin(q) + K * lap])
    return f


def timed(fn, repeat):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def installed(name):
    try:
        __import__(name)
        return True
    except ImportError:
        return False


def scipy_runner(n, y0):
    f = rhs_factory(n)

    def run(rtol):
        return solve_ivp(f, (0, T_END), y0, method="DOP853", rtol=rtol, atol=rtol / 100).y[:, -1]
    return run


def numbalsoda_runner(n, y0):
    import numba as nb
    from numbalsoda import dop853, lsoda_sig

    @nb.cfunc(lsoda_sig)
    def rhs(t, u_, du_, p_):
        u = nb.carray(u_, (2 * n,))
        du = nb.carray(du_, (2 * n,))
        for i in range(n):
            du[i] = u[n + i]
            lap = 0.0
            if i > 0:
                lap += u[i - 1] - u[i]
            if i < n - 1:
                lap += u[i + 1] - u[i]
            du[n + i] = -np.sin(u[i]) + K * lap
    ptr = rhs.address
    teval = np.array([0.0, T_END])

    def run(rtol):
        usol, ok = dop853(ptr, y0, teval, rtol=rtol, atol=rtol / 100, mxstep=10**7)
        if not ok:
            raise RuntimeError("numbalsoda dop853 failed")
        return usol[-1]
    run.ptr = ptr
    return run


def diffrax_runner(n, y0):
    import jax
    jax.config.update("jax_enable_x64", True)
    import diffrax
    import jax.numpy as jnp

    def f(t, y, args):
        q, v = y[:n], y[n:]
        lap = jnp.zeros(n).at[:-1].add(q[1:] - q[:-1]).at[1:].add(q[:-1] - q[1:])
        return jnp.concatenate([v, -jnp.sin(q) + K * lap])

    @jax.jit
    def solve(y, rtol):
        sol = diffrax.diffeqsolve(diffrax.ODETerm(f), diffrax.Dopri8(), 0.0, T_END, None, y,
                                  stepsize_controller=diffrax.PIDController(rtol=rtol, atol=rtol / 100),
                                  saveat=diffrax.SaveAt(t1=True), max_steps=10**6)
        return sol.ys[-1]
    yj = jnp.asarray(y0)

    def run(rtol):
        return np.asarray(solve(yj, rtol).block_until_ready())
    run(1e-6)   # compile once (rtol is traced, so one compilation serves every tolerance)
    return run


def kernel_seconds(net, y0, rtol):
    """The kernel's share of a simulate call: the binding called directly (a diagnostic)."""
    from pendula import _kernel
    from pendula.systems.network import _METHOD_CODE
    edges = net._edges()
    tt, counts = np.array([0.0, T_END]), np.zeros(2, dtype=np.int64)

    def run():
        out = _kernel.network_simulate_v(*edges, _METHOD_CODE["dop853"], y0, tt, counts, rtol, rtol / 100, 0.0,
                                         np.zeros(1, dtype=np.int32))
        if out[2] != 0:
            raise RuntimeError(f"kernel status {out[2]}")
    return timed(run, 5)[0]


RUNNERS = {"scipy": scipy_runner, "numbalsoda": numbalsoda_runner, "diffrax": diffrax_runner}

BATCH_N, BATCH = 16, 64     # the batch task: 64 chains of 16 from seeded random phases


def batch_cell(avail):
    """The batch task (where vmap applies): BATCH chains of BATCH_N from seeded random initial phases, each
    to t = 10.  pendula runs the batch in one call (Network.simulate with phi0 of B x N rows, on OpenMP
    threads); numbalsoda loops over the chains;
    diffrax maps one jit-compiled solve over the batch with jax.vmap.  Error: the largest over the batch
    against SciPy at rtol 1e-13; times at equal error as in the main table."""
    n = BATCH_N
    rng = np.random.default_rng(20261204)
    phis = rng.uniform(-1.0, 1.0, (BATCH, n))
    y0s = np.concatenate([phis, np.zeros((BATCH, n))], axis=1)
    ref = np.array([scipy_runner(n, y)(1e-13) for y in y0s])
    net = pendula.Network(n, topology="chain", strength=K)

    def pend(rtol):     # the whole batch in one call (phi0 of BATCH x n rows), on OpenMP's threads
        run = net.simulate([0.0, T_END], phis, 0.0, rtol=rtol, atol=rtol / 100)
        return np.concatenate([run.phi.values[:, -1], run.v.values[:, -1]], axis=1)
    runners = {}
    if "numbalsoda" in avail:
        one = numbalsoda_runner(n, y0s[0])
        from numbalsoda import dop853

        def nbs(rtol, ptr=one.ptr):
            return np.array([dop853(ptr, y, np.array([0.0, T_END]), rtol=rtol, atol=rtol / 100,
                                    mxstep=10**7)[0][-1] for y in y0s])
        runners["numbalsoda"] = nbs
    if "diffrax" in avail:
        runners["diffrax"] = diffrax_batch_runner(n, y0s)
    rows = []
    pruns = []
    for rtol in RTOLS:
        tp, y = timed(lambda: pend(rtol), 3)
        pruns.append((rtol, float(np.max(np.abs(y - ref))), tp))
    peer = {}
    for name, run in runners.items():
        peer[name] = []
        for rtol in PEER_RTOLS:
            t, y = timed(lambda: run(rtol), 3)
            peer[name].append((rtol, float(np.max(np.abs(y - ref))), t))
    for rtol, err, tp in pruns:
        row = {"n": n, "batch": BATCH, "rtol": rtol, "pendula_error": err, "pendula_s": tp}
        line = f"batch {BATCH} x N={n} rtol={rtol:.0e}  pendula {tp * 1e3:8.3f} ms err {err:.1e} |"
        for name, runs in peer.items():
            le = np.log([r[1] for r in runs])
            lt = np.log([r[2] for r in runs])
            o = np.argsort(le)
            t_eq = float(np.exp(np.interp(np.log(err), le[o], lt[o])))
            inside = bool(le.min() <= np.log(err) <= le.max())
            row[name] = {"runs": [{"rtol": r[0], "error": r[1], "s": r[2]} for r in runs],
                         "s_at_pendula_error": t_eq, "interpolated": inside, "ratio_peer_over_pendula": t_eq / tp}
            line += f" {name} {t_eq * 1e3:8.3f} ms x{t_eq / tp:6.2f}{'' if inside else '*'}"
        rows.append(row)
        print(line, flush=True)
    return rows


def diffrax_batch_runner(n, y0s):
    import jax
    jax.config.update("jax_enable_x64", True)
    import diffrax
    import jax.numpy as jnp

    def f(t, y, args):
        q, v = y[:n], y[n:]
        lap = jnp.zeros(n).at[:-1].add(q[1:] - q[:-1]).at[1:].add(q[:-1] - q[1:])
        return jnp.concatenate([v, -jnp.sin(q) + K * lap])

    def solve(y, rtol):
        sol = diffrax.diffeqsolve(diffrax.ODETerm(f), diffrax.Dopri8(), 0.0, T_END, None, y,
                                  stepsize_controller=diffrax.PIDController(rtol=rtol, atol=rtol / 100),
                                  saveat=diffrax.SaveAt(t1=True), max_steps=10**6)
        return sol.ys[-1]
    batch = jax.jit(jax.vmap(solve, in_axes=(0, None)))
    yj = jnp.asarray(y0s)

    def run(rtol):
        return np.asarray(batch(yj, rtol).block_until_ready())
    run(1e-6)   # compile once
    return run


def main():
    avail = [p for p in PEERS if installed(p)]
    rows = []
    for n in SIZES:
        phi0 = 0.5 * np.sin(2 * np.pi * np.arange(n) / n + 0.3)
        y0 = np.concatenate([phi0, np.zeros(n)])
        ref = scipy_runner(n, y0)(1e-13) if n < 4096 else solve_ivp(
            rhs_factory(n), (0, T_END), y0, method="DOP853", rtol=1e-13, atol=1e-15).y[:, -1]
        net = pendula.Network(n, topology="chain", strength=K)
        runners = {p: RUNNERS[p](n, y0) for p in avail}
        pend = []
        for rtol in RTOLS:
            tp, run = timed(lambda: net.simulate([0.0, T_END], phi0, 0.0, rtol=rtol, atol=rtol / 100), 5)
            yp = np.concatenate([run.phi.values[-1], run.v.values[-1]])
            pend.append((rtol, float(np.max(np.abs(yp - ref))), tp, int(run.attrs["steps"]),
                         kernel_seconds(net, y0, rtol)))
        peer_runs = {}
        for p, run in runners.items():
            reps = 1 if (p == "scipy" and n >= 4096) else (3 if p == "scipy" else 7)
            rt = PEER_RTOLS if not (p == "scipy" and n >= 4096) else (1e-6, 1e-8, 1e-10, 1e-11)
            peer_runs[p] = []
            for rtol in rt:
                tpeer, y = timed(lambda: run(rtol), reps)
                peer_runs[p].append((rtol, float(np.max(np.abs(y - ref))), tpeer))
        for rtol, err, tp, steps, tk in pend:
            row = {"n": n, "rtol": rtol, "pendula_error": err, "pendula_s": tp, "pendula_steps": steps,
                   "pendula_kernel_s": tk}
            line = f"N={n:5d} rtol={rtol:.0e}  pendula {tp * 1e3:8.3f} ms (kernel {tk * 1e3:8.3f}) err {err:.1e} |"
            for p, runs in peer_runs.items():
                le = np.log([r[1] for r in runs])
                lt = np.log([r[2] for r in runs])
                order = np.argsort(le)
                t_eq = float(np.exp(np.interp(np.log(err), le[order], lt[order])))
                inside = bool(le.min() <= np.log(err) <= le.max())
                row[p] = {"runs": [{"rtol": r[0], "error": r[1], "s": r[2]} for r in runs],
                          "s_at_pendula_error": t_eq, "interpolated": inside, "ratio_peer_over_pendula": t_eq / tp}
                line += f" {p} {t_eq * 1e3:8.3f} ms x{t_eq / tp:6.2f}{'' if inside else '*'}"
            rows.append(row)
            print(line, flush=True)
    batch_rows = batch_cell(avail)
    print("kernel: the share of pendula's call spent in the kernel; "
          "x: the peer's time at pendula's error over pendula's time (> 1: pendula faster); "
          "*: extrapolated beyond the peer's runs")
    rec = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
           "machine": platform.processor() or platform.machine(), "cores": os.cpu_count(),
           "load_average_at_end": os.getloadavg(), "pendula": pendula.__version__,
           "peer_versions": {p: __import__(p).__version__ for p in avail if hasattr(__import__(p), "__version__")},
           "task": f"FK chain, free ends, K={K}, t = 0..{T_END}; pendula DOP853, SciPy DOP853, numbalsoda "
                   "dop853, diffrax Dopri8 (jit); error vs SciPy DOP853 rtol 1e-13",
           "peers_not_installed": [p for p in PEERS if p not in avail],
           "rows": rows, "batch_rows": batch_rows}
    (HERE / "network_cost.json").write_text(json.dumps(rec, indent=1) + "\n")


if __name__ == "__main__":
    main()

"""Energy error of Gauss6 variants (brouwer.f90): RMS growth exponent and figure."""
import sys, pathlib
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

here = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
out = pathlib.Path(sys.argv[2] if len(sys.argv) > 2 else "brouwer.png")
NDIV = int(sys.argv[3]) if len(sys.argv) > 3 else 1000
H = 6.743001419250385 / NDIV
names = {"0": "a/b form (pendula)", "1": "mu form, mu_ij + mu_ji = 1 exactly"}
stops = {"0": "stop when increments stop decreasing", "1": "stop at 0 or the 2nd rise"}
sines = {"0": "libm sin", "1": "x87 sinl, rounded"}
fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
rows = []
for f in "01":
    ax = axes[int(f)]
    for s in "01":
        for q in "01":
            p = here / f"r_{f}{s}{q}.txt"
            if not p.exists():
                continue
            d = np.loadtxt(p)
            n, e = d[:, 0], d[:, 1]
            edges = np.geomspace(n[0], n[-1] * 1.0001, 11)
            nc, rms = [], []
            for a, b in zip(edges[:-1], edges[1:]):
                sel = (n >= a) & (n < b)
                if sel.any():
                    nc.append(np.sqrt(a * b)); rms.append(np.sqrt(np.mean(e[sel] ** 2)))
            slope = np.polyfit(np.log(nc), np.log(rms), 1)[0]
            # mean signed error in the last decade / steps: a drift per step
            late = n > n[-1] / 10
            drift = np.polyfit(n[late], e[late], 1)[0]
            rows.append((names[f], stops[s], sines[q], slope, np.abs(e).max(), drift))
            ax.loglog(n, np.maximum(np.abs(e), 1e-19), ".", ms=2,
                      label=f"{stops[s]}, {sines[q]}: exponent {slope:.2f}")
    nn = np.geomspace(n[0], n[-1], 10)
    ax.loglog(nn, 1.1e-16 * H * np.sqrt(nn), "k--", lw=0.8, label="eps h sqrt(N) (Brouwer's law, compensated sums)")
    ax.set_title(names[f], fontsize=10)
    ax.set_xlabel(f"steps N (h = T/{NDIV}, v0 = 1, eps = 1)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
axes[0].set_ylabel("|E - E0|")
fig.suptitle(f"Gauss6 round-off: which ingredient drifts? ({n[-1]:.0e} steps = {n[-1] / NDIV:.0e} periods)", fontsize=11)
fig.tight_layout()
fig.savefig(out, dpi=110)
print("| form | stopping rule | sine | RMS growth exponent | max abs dE | late slope of dE per step |")
print("|---|---|---|---:|---:|---:|")
for r in rows:
    print(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]:.2f} | {r[4]:.1e} | {r[5]:.1e} |")

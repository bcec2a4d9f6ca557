"""
Equilibria of the torqued damped pendulum and their stability
==============================================================

θ'' + β θ' + sin θ = τ rests where sin θ = τ: at θ* = asin τ (a stable
spiral, or a node when β² > 4 cos θ*) and at π − asin τ (a saddle), until
the two merge in a saddle-node at τ = 1 and the pendulum must run
(Suzuki & Suzuki, section 7.1), followed in τ by
:func:`pendula.continue_equilibria`, which locates the saddle-nodes (black
crosses) at abs(τ) = 1 exactly.  Right: the real parts of the eigenvalues,
λ² + βλ + cos θ* = 0.
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula

beta = 0.3
taus = np.linspace(-1.2, 1.2, 481)
colors = {"stable spiral": "tab:blue", "stable node": "tab:green",
          "saddle": "tab:red",
          "saddle-node": "k"}
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
seen = set()
eb = pendula.continue_equilibria(
    pendula.Scene(damping=beta, torque=float(taus[0])), "torque",
    float(taus[-1]), points=len(taus))
for tau, eqs in zip(eb.values, eb.equilibria):
    for e in eqs:
        label = e.kind if e.kind not in seen else None
        seen.add(e.kind)
        ax1.plot(tau, e.theta, ".", ms=3, color=colors.get(e.kind, "0.5"),
                 label=label)
        ax2.plot([tau, tau], e.eigenvalues.real, ".", ms=2,
                 color=colors.get(e.kind, "0.5"))
ax1.set(xlabel="torque τ / ε", ylabel="θ*", title=f"rest points, β = {beta}")
for b in eb.bifurcations:
    ax1.plot(b.value, b.theta, "kx", ms=8)
ax1.legend(fontsize=8, markerscale=3)
ax2.axhline(0, color="0.6", lw=0.8)
ax2.set(xlabel="torque τ / ε", ylabel="Re λ",
        title="eigenvalues of the linearisation")
fig.tight_layout()
plt.show()

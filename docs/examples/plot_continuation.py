"""
Continuation: the period-doubling cascade and the retrapping torque
===================================================================

The driven damped pendulum θ'' + 0.5 θ' + sin θ = A cos(2t/3), followed in
the drive amplitude A by :func:`pendula.continue_orbit` from A = 1.0 with
``follow='stable'``: the symmetric period-1 orbit breaks its symmetry at a
pitchfork, then its period doubles again and again.  Solid: the attracting
route; dashed: the orbits left behind at each bifurcation, continued on
unstable (``follow='branch'``); dots: the bifurcations, each located by
solving its test function.  Grey: the brute-force orbit diagram, the
stroboscopic points after a transient (:func:`pendula.sweep`, measure
``poincare``).  Each orbit of period k is drawn with its k points on the
section (top; enlarged below it).

Third: the ratios of successive doubling intervals against Feigenbaum's
δ = 4.6692.  Bottom: the retrapping torque of the undriven pendulum (the
homoclinic end of the running orbit, continued in the torque) against the
damping, with Stewart-McCumber's 4β/π for small damping and the lowest
running torque of :func:`pendula.iv_curve`'s down branch beside it.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

import pendula

drive = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2 / 3)
TD = 2 * math.pi / drive.drive_frequency
A_END = 1.0829

po = pendula.periodic_orbit(drive, guess=(0.1, 1.9))
route = pendula.continue_orbit(
    drive, (po.theta, po.v), "drive_amplitude", A_END, follow="stable"
)

# the branches left behind: from each bifurcation on, the parent continued
# unstable
left = []
for b in route.bifurcations:
    sc = drive.replace(drive_amplitude=b.value + 1e-6)
    try:
        p = pendula.periodic_orbit(sc, guess=(b.theta, b.v), k=int(b.period))
        left.append(
            pendula.continue_orbit(
                sc, (p.theta, p.v), "drive_amplitude", A_END, k=int(b.period)
            )
        )
    except ValueError:
        pass


def section_points(br):
    """All k points of each orbit on the section t = 0 mod the drive period."""
    out = []
    for a, th, v, k in zip(br.values, br.theta, br.v, br.period):
        k = int(k)
        sc = drive.replace(
            drive_amplitude=float(a),
            theta0=float(th),
            v0=float(v),
            t_end=k * TD,
            n_samples=k + 1,
            method="dop853",
            rtol=1e-11,
            atol=1e-11,
        )
        tr = pendula.simulate(sc)
        out.append((a, np.asarray(tr.v[:-1])))
    return out


# the orbit diagram from the continued orbit's state at A = 1.0 (other
# attractors coexist: from rest
# the pendulum lands on another one)
amps = np.linspace(1.0, A_END, 300)
diagram = pendula.sweep(
    drive.replace(theta0=po.theta, v0=po.v, rtol=1e-9, atol=1e-11),
    over={"drive_amplitude": amps},
    measure="poincare",
    transient=800.0,
    samples=32,
)
curves = [
    (section_points(br), br, "-" if br is route else "--")
    for br in [route] + left
]

# one panel a row, so that the figure fits the page's column at full size
fig, (ax, axz, axr, axh) = plt.subplots(4, 1, figsize=(7, 17),
                                        layout="constrained")
v = diagram.v.values
for a, lo, title in (
    (ax, 1.0, "attracting route (solid), left behind (dashed)"),
    (axz, 1.077, "the cascade, enlarged"),
):
    a.plot(
        np.repeat(amps, v.shape[1]),
        v.ravel(),
        ".",
        ms=2.5,
        color="0.7",
        zorder=0,
        label="sweep (poincare)",
    )
    for pts, br, style in curves:
        kmax = max(len(p[1]) for p in pts)
        for seg in np.unique(br.segment):
            idx = np.nonzero(br.segment == seg)[0]
            for j in range(kmax):
                xs = [pts[i][0] for i in idx if j < len(pts[i][1])]
                ys = [pts[i][1][j] for i in idx if j < len(pts[i][1])]
                if len(xs) > 1:
                    a.plot(
                        xs,
                        ys,
                        style,
                        color="C0" if style == "-" else "C3",
                        lw=0.9,
                    )
    for b in route.bifurcations:
        a.plot(b.value, b.v, "o", color="k", ms=4)
    a.set_xlim(lo, A_END)
    a.set_xlabel("drive amplitude A")
    a.set_ylabel("v on the section")
    a.set_title(title)
for b in route.bifurcations[:2]:
    ax.annotate(
        f"{b.kind}\nA = {b.value:.8f}",
        (b.value, b.v),
        fontsize=8,
        xytext=(4, -22),
        textcoords="offset points",
    )
axz.set_ylim(1.6, 2.1)

pd = np.array(
    [b.value for b in route.bifurcations if b.kind == "period-doubling"]
)
gaps = np.diff(pd)
ratios = gaps[:-1] / gaps[1:]
axr.plot(np.arange(1, len(ratios) + 1), ratios, "o-", label="continuation")
axr.axhline(4.6692016, color="k", ls=":", label="Feigenbaum δ")
axr.set_xlabel("n")
axr.set_ylabel("(A_n - A_(n-1)) / (A_(n+1) - A_n)")
axr.set_ylim(4.5, 4.8)
axr.legend()
axr.set_title("ratios of doubling intervals")

betas = np.array([0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 1.1])
taus = []
for beta in betas:
    br = pendula.continue_orbit(
        pendula.Scene(damping=float(beta), torque=1.5),
        (0.0, 6.0),
        "torque",
        0.0,
    )
    taus.append(br.bifurcations[-1].value if br.bifurcations else math.nan)
axh.plot(betas, taus, "o-", label="homoclinic (continuation)")
# beside it, the I-V sweep's own figure: the lowest torque still running on the
# down branch
torques = np.round(np.arange(0.02, 1.205, 0.01), 2)
iv_betas = np.array([0.1, 0.3, 0.5, 0.7, 0.9])
iv_tau = []
for beta in iv_betas:
    r = pendula.iv_curve(
        pendula.Scene(damping=float(beta)),
        torques,
        "down",
        transient=200.0,
        t_max=200.0,
    )
    down = r.mean_velocity.sel(direction="down").values
    running = torques[down > 0.1]
    iv_tau.append(running.min() if len(running) else math.nan)
axh.plot(
    iv_betas,
    iv_tau,
    "x",
    color="C2",
    ms=9,
    label="iv_curve, down branch (torque step 0.01)",
)
bb = np.linspace(0, 1.2, 50)
axh.plot(bb, 4 * bb / math.pi, "k:", label="4β/π (Stewart-McCumber)")
axh.axhline(1.0, color="0.6", lw=0.8)
axh.set_xlabel("damping β")
axh.set_ylabel("retrapping torque")
axh.legend()
axh.set_title("retrapping torque")
plt.show()

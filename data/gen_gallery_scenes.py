"""Write the default gallery, data/scenes/*.nml: one scene per figure family of the
source notes (Suzuki & Suzuki 2008; Prusa & Tuma 2022).  The scene files are
committed; this script records how their long value lists were made.

Usage:  python data/gen_gallery_scenes.py
"""

import pathlib

import numpy as np

D = pathlib.Path(__file__).with_name("scenes")


def fmt(vals):
    out, line = [], []
    for v in vals:
        line.append(repr(float(v)))
        if len(line) == 6:
            out.append(", ".join(line))
            line = []
    if line:
        out.append(", ".join(line))
    return ",\n                 ".join(out)


def scene(fname, comment, **kw):
    lines = [f"! {c}" for c in comment.splitlines()] + ["&scene"]
    for k, v in kw.items():
        if k == "sweep_values":
            lines.append(f"  sweep_values = {fmt(v)}")
        elif k == "outputs":
            lines.append("  outputs = " + ", ".join(f"'{o}'" for o in v))
        elif isinstance(v, str):
            lines.append(f"  {k} = '{v}'")
        else:
            lines.append(f"  {k} = {v!r}")
    lines.append("/")
    (D / fname).write_text("\n".join(lines) + "\n")


def main():
    D.mkdir(parents=True, exist_ok=True)
    lin = list(np.round(np.linspace(0.05, 1.95, 39), 10))
    scene("fig5a_theta_t_libration.nml",
          "Suzuki & Suzuki Fig. 5(a): theta(t) for eps = 1, v0 = 1.70 ... 1.95 (libration).",
          name="Fig 5a: theta(t), v0 = 1.70-1.95", eps=1.0, theta0=0.0, t_end=30.0, n_samples=1501,
          outputs=["trajectory", "theta_t"], sweep="v0", sweep_values=[1.7, 1.75, 1.8, 1.85, 1.9, 1.95])
    scene("fig5b_theta_t_near_separatrix.nml",
          "Suzuki & Suzuki Fig. 5(b)-(d): theta(t) as v0 approaches 2 from below, and v0 = 2 exactly\n"
          "(the separatrix: theta -> pi monotonically, where the source's NDSolve failed).",
          name="Fig 5b-d: theta(t), v0 -> 2 from below", eps=1.0, theta0=0.0, t_end=60.0, n_samples=3001,
          outputs=["trajectory", "theta_t"], sweep="v0",
          sweep_values=[1.995, 1.998, 1.9996, 1.99999, 1.999998, 2.0])
    scene("fig11_theta_t_rotation.nml",
          "Suzuki & Suzuki section 3.1: the rotating pendulum (k > 1), the angle unwrapped.",
          name="theta(t), rotation v0 > 2", eps=1.0, theta0=0.0, t_end=30.0, n_samples=1501,
          outputs=["trajectory", "theta_t", "v_t"], sweep="v0", sweep_values=[2.000001, 2.001, 2.05, 2.3, 3.0])
    scene("fig4_phase_portrait.nml",
          "Suzuki & Suzuki Fig. 4: phase portrait for eps = 1, E = 0.5 ... 3.5 (v0 = sqrt(2E)),\n"
          "with the separatrix E = 2.",
          name="Fig 4: phase portrait, E = 0.5-3.5", eps=1.0, theta0=0.0, t_start=-10.0, t_end=10.0,
          n_samples=4001, outputs=["phase"], sweep="v0",
          sweep_values=[float(np.sqrt(2 * E)) for E in (0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5)])
    scene("fig7_phase_near_separatrix.nml",
          "Suzuki & Suzuki Fig. 7: phase-space orbits for v0 = 1.80 ... 1.99.",
          name="Fig 7: phase space, v0 = 1.80-1.99", eps=1.0, theta0=0.0, t_start=-20.0, t_end=20.0,
          n_samples=4001, outputs=["phase"], sweep="v0",
          sweep_values=[1.8, 1.85, 1.9, 1.95, 1.96, 1.97, 1.98, 1.99])
    scene("fig13_omega_vs_v0.nml",
          "Suzuki & Suzuki Figs. 8, 11, 13: omega against v0 on both sides of v0 = 2 (eps = 1).",
          name="Fig 13: omega vs v0", eps=1.0, theta0=0.0, outputs=["omega", "period"], sweep="v0",
          sweep_values=lin + [1.99, 1.999, 2.001, 2.01] + list(np.round(np.linspace(2.05, 3.95, 39), 10)))
    tc = [10.0 ** (-k) for k in range(1, 13)]
    scene("fig9_12_critical_omega.nml",
          "Suzuki & Suzuki Figs. 9 and 12: omega near v0 = 2 from below and above, against t = |v0 - 2|,\n"
          "with the asymptotes (pi/2)/ln(4/sqrt(t)) and pi/ln(4/sqrt(t)) (ratio 2).",
          name="Figs 9, 12: critical behaviour of omega", eps=1.0, theta0=0.0, outputs=["omega"],
          sweep="v0", sweep_values=[2.0 - t for t in tc] + [2.0 + t for t in tc])
    scene("fig10_theta_max_vs_v0.nml",
          "Suzuki & Suzuki Fig. 10: theta_max = 2 arcsin(v0 / (2 sqrt(eps))) against v0,\n"
          "beside the small-angle line 2 v0.",
          name="Fig 10: theta_max vs v0", eps=1.0, theta0=0.0, outputs=["theta_max"], sweep="v0",
          sweep_values=lin + [1.99, 1.999, 1.9999])
    scene("period_series.nml",
          "Prusa & Tuma section 3: T/T0 = 1 + theta0^2/16 + 11 theta0^4/3072 + ... against the exact period.",
          name="period series vs exact", eps=1.0, v0=0.0, outputs=["series"], sweep="theta0",
          sweep_values=list(np.round(np.linspace(0.05, 3.1, 62), 10)))
    scene("poincare_lindstedt.nml",
          "Prusa & Tuma section 3: Poincare-Lindstedt (orders 1, 3, 5, 7) against the exact solution, 0 <= t <= 50.",
          name="Poincare-Lindstedt error vs amplitude", eps=1.0, v0=0.0, t_end=50.0, n_samples=2001,
          outputs=["lindstedt"], sweep="theta0",
          sweep_values=[0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 1.5, 2.0, 2.5])
    scene("fig6_spectra_near_separatrix.nml",
          "Suzuki & Suzuki sections 2.4 and 6: FFT power spectra of theta(t) (eight whole periods,\n"
          "4096 samples each, one FFTW plan for the sweep): the odd harmonics multiply as v0 -> 2.",
          name="Fig 6: spectra of theta(t), v0 -> 2", eps=1.0, theta0=0.0, n_samples=4096,
          outputs=["spectrum"], sweep="v0", sweep_values=[0.5, 1.6, 1.9, 1.981, 1.9962, 1.9991, 1.999995])
    scene("spectrum_damped.nml",
          "The spectrum of a damped run (beta = 0.02, v0 = 1.9, 0 <= t <= 400, Hann window):\n"
          "no line, the frequency drifts upward as the amplitude decays.",
          name="spectrum of a damped pendulum", eps=1.0, v0=1.9, damping=0.02, t_end=400.0,
          n_samples=8192, outputs=["spectrum", "theta_t"], sweep="damping", sweep_values=[0.005, 0.02])


if __name__ == "__main__":
    main()

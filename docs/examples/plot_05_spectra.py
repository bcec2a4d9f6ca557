"""
Spectra near the separatrix
===========================

Suzuki & Suzuki, section 6 and Fig. 6 (gallery scene
``fig6_spectra_near_separatrix``): the power spectrum of θ(t) over eight
whole periods (4096 samples, FFTW).  Only odd harmonics appear, and as v0
approaches 2 more of them stand out: the amplitudes fall like q^(n/2) in the
nome q of the orbit, and q → 1 at the separatrix.  The dots are the exact
Fourier amplitudes from :func:`pendula.fourier_series`.
"""

import matplotlib.pyplot as plt
import numpy as np

import pendula

fig, ax = plt.subplots(figsize=(8, 4.5))
for v0 in [0.5, 1.9, 1.9962, 1.999995]:
    T = pendula.orbit(0.0, v0).period
    t = np.arange(4096) * (8 * T / 4096)
    spec = pendula.spectrum(t, pendula.exact_motion(0.0, v0, 1.0, t)[0])
    line, = ax.semilogy(spec.omega / spec.fundamental,
                        spec.power / spec.power.max(), lw=0.8,
                        label=f"v0 = {v0:g}: odd harmonics above 1e-6: "
                              f"{pendula.odd_harmonics_above(spec)[-1]}")
    omega, amps = pendula.fourier_series(0.0, v0, 1.0, 10)
    n = 2 * np.arange(amps.size) + 1
    ax.semilogy(n, (amps / amps[0]) ** 2, "o", ms=3, color=line.get_color())
ax.set(xlim=(0, 20), ylim=(1e-30, 2), xlabel="ω / ω1 (harmonic number)",
       ylabel="power / power of the fundamental",
       title="odd harmonics multiply as v0 → 2")
ax.legend(fontsize=7, loc="upper right")
fig.tight_layout()
plt.show()

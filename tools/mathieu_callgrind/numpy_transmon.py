"""numpy's batched eigvalsh of the charge-basis transmon (E_J/E_C = 50, ncut = 13, the
cutoff of 1e-12 agreement) at 1,000 offset charges, ``reps`` times."""
import sys

import numpy as np

reps, ncut, ej, ec = int(sys.argv[1]), 13, 50.0, 1.0
ng = np.linspace(-1.0, 1.0, 1000)


def hamiltonians():
    n = np.arange(-ncut, ncut + 1)
    h = np.zeros((len(ng), n.size, n.size))
    i = np.arange(n.size)
    h[:, i, i] = 4 * ec * (n[None, :] - ng[:, None]) ** 2
    h[:, i[:-1], i[1:]] = -ej / 2
    h[:, i[1:], i[:-1]] = -ej / 2
    return h


for _ in range(reps):
    np.linalg.eigvalsh(hamiltonians())

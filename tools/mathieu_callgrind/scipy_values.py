"""SciPy's mathieu_a on the points of a file (``n q`` a line after the count), ``reps`` times."""
import sys

import numpy as np
import scipy.special as sp

d = np.loadtxt(sys.argv[1], skiprows=1)
reps = int(sys.argv[2])
n, q = d[:, 0].copy(), d[:, 1].copy()
sp.mathieu_a(n[:2], q[:2])
for _ in range(reps):
    sp.mathieu_a(n, q)

"""The benchmark's points: orders 0..10, q log-uniform from 1e-2 to qmax (seeded), one file each."""
import sys

import numpy as np

rng = np.random.default_rng(7)
for qmax in (10, 1000):
    n = rng.integers(0, 11, 2000)
    q = 10 ** rng.uniform(-2, np.log10(qmax), 2000)
    with open(f"{sys.argv[1]}/pts{qmax}.txt", "w") as f:
        f.write(f"{len(n)}\n")
        for a, b in zip(n, q):
            f.write(f"{int(a)} {float(b)!r}\n")

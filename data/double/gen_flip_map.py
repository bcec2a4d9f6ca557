"""The flip-time map of the guide's figure (docs/source/guide/double.md).

Equal point masses and lengths, g = l = 1, released from rest at the
centres of a 161 x 161 grid of cells over [-pi, pi]^2 (no start exactly at
the top), searched up to t = 100 at rtol = atol =
1e-10 and again at a tenth of both (DoublePendulum.flip_map).  Stored as
float32 flip times (inf: no flip), the forbidden and unresolved masks in
flip_map.npz beside this script.  Run: python data/double/gen_flip_map.py
(a few minutes on two cores).
"""

from pathlib import Path

import numpy as np

import pendula

HERE = Path(__file__).resolve().parent


def main() -> None:
    n = 161
    th = -np.pi + (np.arange(n) + 0.5) * (2 * np.pi / n)
    fm = pendula.DoublePendulum().flip_map(th, th, t_max=100.0, rtol=1e-10, atol=1e-10)
    np.savez_compressed(HERE / "flip_map.npz", theta1=fm.theta1, theta2=fm.theta2,
                        time=fm.time.astype(np.float32), check=fm.check.astype(np.float32),
                        forbidden=fm.forbidden, unresolved=fm.unresolved,
                        meta=np.array([fm.t_max, fm.rtol, fm.agree]))
    print(fm)


if __name__ == "__main__":
    main()

"""Shapiro plateaus in laboratory units: every bias on a plateau reported locked, and the step table.

References, both written without pendula:
- data/gen_junction_plateaus.py: the hysteretic 10 uA / 1 pF / 30 ohm junction at 10 GHz (beta_c = 27),
  one plateau for each of n = 1 ... 6, followed by continuation from a bias inside it with a numpy RK4
  stroboscopic map, its edges bisected where the phase first slips (data/junction/rcsj_plateaus.json);
- data/gen_rsj_step_edges.py: the overdamped junction's step edges by SciPy (DOP853, minimize_scalar,
  brentq) to 1e-12 (data/junction/rsj_step_edges.json).
"""

import json
import math
import pathlib

import numpy as np
import pytest

import pendula
from pendula import Junction
from pendula.junction import FLUX_QUANTUM

DATA = pathlib.Path(__file__).resolve().parents[1] / "data" / "junction"
PLATEAUS = json.loads((DATA / "rcsj_plateaus.json").read_text())
GRID = 0.005      # the reduced bias grid of the checks, I_c


@pytest.mark.parametrize("row", PLATEAUS["plateaus"], ids=lambda r: f"n{r['n']}")
def test_every_bias_on_the_plateau_reports_locked_with_default_settings(row):
    # the junction's defaults (transient 200, window 400 inverse plasma frequencies), each branch started
    # on the reference's locked orbit at the bias inside and ramped to past each edge: every bias between
    # the reference's edges reports status 'locked' on step n
    jc = PLATEAUS["junction"]
    j = Junction(jc["critical_current"], jc["resistance"], jc["capacitance"])
    ic, n = jc["critical_current"], row["n"]
    scene = j.scene(0.0, row["rf_current"], jc["rf_frequency"])
    start = (row["start_theta"] - 2 * math.pi * round(row["start_theta"] / (2 * math.pi)), row["start_v"])
    i0, lo, hi = row["inside"] / ic, row["lower"] / ic, row["upper"] / ic
    tol = row["bracket"] / ic + 1e-3        # the reference's bracket and its slip-window bound (4e-4)
    up = i0 + GRID * np.arange(0, math.ceil((hi - i0) / GRID) + 2)
    down = i0 - GRID * np.arange(0, math.ceil((i0 - lo) / GRID) + 2)[::-1]
    checked = 0
    for torques, direction in ((up, "up"), (down, "down")):
        r = pendula.iv_curve(scene, torques, direction, transient=200.0, t_max=400.0, start=start)
        st, step = r.status.values[0], r.step.values[0]
        inside = (torques > lo + tol) & (torques < hi - tol)
        checked += inside.sum()
        assert np.all(st[inside] == 6) and np.all(step[inside] == n), (direction, torques[inside][st[inside] != 6])
    assert checked >= 3


def test_the_n4_plateau_the_fixed_window_missed_reports_locked_on_the_ramp():
    # the case that a fixed window of 24 periods missed: 6 uA of rf, biases 4.08-4.28 uA reported unlocked
    # at V / V1 = 3.99999; on the up ramp from zero every bias from where the ramp lands on the n = 4 step
    # to the reference's upper edge reports locked, and Junction.steps' upper edge is the reference's to
    # the grid's resolution
    jc = PLATEAUS["junction"]
    row = next(r for r in PLATEAUS["plateaus"] if r["n"] == 4)
    j = Junction(jc["critical_current"], jc["resistance"], jc["capacitance"])
    cur = np.round(np.arange(3.9, 5.0001, 0.02) * 1e-6, 12)
    s = j.steps(cur, row["rf_current"], jc["rf_frequency"])
    k = int(np.flatnonzero(s.order.values == 4)[0])
    assert s.lower.values[k] <= 4.08e-6 and s.upper.values[k] >= 4.28e-6
    assert s.lower.values[k] >= row["lower"] - row["bracket"]
    assert s.upper.values[k] <= row["upper"] + row["bracket"] + 1e-3 * jc["critical_current"]
    assert s.upper.values[k] + s.upper_gap.values[k] >= row["upper"] - row["bracket"] - 1e-3 * jc["critical_current"]
    assert s.voltage.values[k] == 4 * jc["rf_frequency"] * FLUX_QUANTUM
    assert s.voltage.attrs["units"] == "V" and s.lower.attrs["units"] == "A"



"""Attractor labels against long runs by SciPy alone (data/attractors/longrun_reference.json, made by
data/gen_attractor_longrun_reference.py: 600 seeded random points of each 150 x 150 grid over theta0 in
[-pi, pi], v0 in [-3, 3], integrated 400-600 drive periods at rtol 1e-10 and 1e-12; a point is stable when
both tolerances end on the same cycle and a perturbation grows by at most 1e6 along its orbit, so that its
label is resolved by the integration: 511 points at A = 1.07, 406 at A = 1.15).

- A = 1.07, damping 0.5, Omega 2/3: two period-2 attractors with intermixed basins;
- A = 1.15, damping 0.2, Omega 2/3: two period-3 cycles 0.09-0.2 apart on the section, whose cells of the
  default width overlap; orbits pass by one cycle on their way to the other.

At least 99.5 % of the stable points must get the long run's attractor.
"""

import json
import math
import pathlib

import numpy as np
import pytest

import pendula
from pendula.dynamics.attractor_maps import (RECURRENCE_DEFAULTS, _AttractorPlan, _attractor_block, _raw,
                                             recurrence_options)
from pendula.dynamics.attractors import AttractorSet

pytest.importorskip("xarray")

REF = json.loads((pathlib.Path(__file__).resolve().parents[1] / "data" / "attractors" /
                  "longrun_reference.json").read_text())


def section_dist(t1, v1, t2, v2):
    return max(abs((t1 - t2 + math.pi) % (2 * math.pi) - math.pi), abs(v1 - v2))


def case_scene(case):
    return pendula.Scene(damping=case["damping"], drive_amplitude=case["drive_amplitude"],
                         drive_frequency=case["drive_frequency"])


def reference_points(case):
    n = REF["grid"]
    th = np.linspace(REF["theta0"][0], REF["theta0"][1], n)[case["i_theta0"]]
    v = np.linspace(REF["v0"][0], REF["v0"][1], n)[case["j_v0"]]
    return th, v, np.array(case["labels"]), np.array(case["stable"], dtype=bool)


def test_period3_cycles_0_09_apart_label_passing_orbits_only_once_confirmed():
    # the labelling core alone (no coarser map to inherit from): every reference point run against the two
    # reference cycles (SciPy's, refined by Newton there), whose points lie 0.094, 0.106 and 0.2 apart
    case = REF["cases"]["1.15"]
    sc = case_scene(case)
    opts = recurrence_options({})
    found = AttractorSet(opts["cell"], opts["merge_tol"], opts["consecutive"], opts["consecutive_chaotic"])
    for c in case["cycles"]:
        found.add_periodic(c["period"], 0, c["theta"], c["v"], np.eye(2))
    assert len(found.items) == 2
    radii = [found.confirm_radius(i) for i in range(2)]
    assert all(0 < r < 0.03 for r in radii)          # close: a quarter of 0.094
    th, v, ref, stable = reference_points(case)
    zero = np.zeros(1)
    plan = _AttractorPlan(sc, {"theta0": zero, "v0": zero.copy()}, opts, 20000)
    p = plan.params_at(np.zeros(th.size, dtype=np.int64))
    p[6], p[7] = th, v
    # at the tolerances of the map's boundary recheck (the loose ones are the recheck's business)
    out, _, _, st = _attractor_block(plan, np.asfortranarray(p), found.table(), opts["recheck_rtol"],
                                     opts["recheck_atol"], 1, 0)
    got = _raw(out, st)
    # an orbit that confirmed a cycle by Newton itself (a new periodic find, -2) is the reference cycle its
    # first point lies on
    for q in np.flatnonzero(got == -2):
        for ci, c in enumerate(case["cycles"]):
            if c["period"] == out[2, q] and min(section_dist(a, b, out[12, q], out[13, q])
                                               for a, b in zip(c["theta"], c["v"])) < 1e-3:
                got[q] = ci
    agree = (got == ref)[stable].mean()
    assert agree >= 0.995, f"{agree:.4f} of {stable.sum()} stable points agree"


@pytest.mark.parametrize("name", ["1.07", "1.15"])
def test_default_map_agrees_with_scipy_long_runs_on_995_permille_of_stable_points(name):
    case = REF["cases"][name]
    n = REF["grid"]
    m = pendula.attractor_map(case_scene(case), {"theta0": np.linspace(-math.pi, math.pi, n),
                                                 "v0": np.linspace(-3.0, 3.0, n)})
    lab = m.dataset.attractor.values
    ours = np.full(lab.shape, -9)
    for a in m.attractors:
        for j, c in enumerate(case["cycles"]):
            if c["period"] == a.period and min(section_dist(c["theta"][0], c["v"][0], t, v)
                                               for t, v in zip(a.theta, a.v)) < 1e-6:
                ours[lab == a.label] = j
    _, _, ref, stable = reference_points(case)
    got = ours[case["i_theta0"], case["j_v0"]]
    agree = (got == ref)[stable].mean()
    assert agree >= 0.995, f"A = {name}: {agree:.4f} of {stable.sum()} stable points agree"
    assert RECURRENCE_DEFAULTS["cell"] == m.dataset.attrs["cell"]


def test_separated_attractors_keep_the_cell_rule_and_close_ones_get_a_radius():
    # A = 1.35 (two period-1 rotations) and A = 1.07 (two period-2 cycles, SciPy's reference cycles): every
    # pair more than four cells apart, so the cells alone label, exactly as without the radius (no extra cost
    # where attractors are separated); A = 1.15: a quarter of the closest approach, 0.0234
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.35, drive_frequency=2 / 3)
    am = pendula.attractor_map(sc, {"theta0": np.linspace(-2, 2, 5), "v0": np.linspace(-3, 3, 5)})
    cases = {"1.35": [(a.period, a.theta, a.v) for a in am.attractors]}
    for name in ("1.07", "1.15"):
        cases[name] = [(c["period"], c["theta"], c["v"]) for c in REF["cases"][name]["cycles"]]
    cell = RECURRENCE_DEFAULTS["cell"]
    for name, cycles in cases.items():
        found = AttractorSet(cell, 1e-3, 2, 10)
        for k, th, v in cycles:
            found.add_periodic(k, 0, th, v, np.eye(2))
        radii = [found.confirm_radius(i) for i in range(len(found.items))]
        sep = min(section_dist(a, b, c, d) for a, b in zip(*cycles[0][1:]) for c, d in zip(*cycles[1][1:]))
        if name == "1.15":
            assert radii == pytest.approx([sep / 4] * 2, rel=1e-12) and abs(sep - 0.0937) < 1e-3
        else:
            assert sep > 4 * cell and radii == [0.0, 0.0]
        kcell, klab, need, cth, cv, catt, crad = found.table()
        assert np.array_equal(crad, radii) and (catt.size == 6) == (name == "1.15")

"""The step-size controller of the adaptive pairs: Gustafsson's PI control
(pendula_integrators: pi_controller) against pure I control (beta = 0, the
controller of Hairer's DOP853 as published), on the five problems of the
work-precision study at rtol = atol = 1e-3 ... 1e-12.

Counts, not time: the steps the controller rejects and the right-hand-side
evaluations it spends.  The errors are measured against the study's stored
Taylor-series reference (data/work_precision_reference.json, 35 digits).
"""

import numpy as np
import pytest

import pendula
from pendula import _kernel
from pendula.studies.workprecision import PROBLEMS, _KCODES, _params, errors, load_reference

RTOLS = (1e-3, 1e-6, 1e-9, 1e-12)


@pytest.fixture(scope="module")
def reference():
    return load_reference()


def _counts(method, beta, reference):
    """Totals over the five problems and four tolerances: steps, rejected, evaluations, and the errors."""
    steps = rejected = nfev = 0
    errs = []
    for name, p in PROBLEMS.items():
        t = reference[name]["t"]
        for rtol in RTOLS:
            th, v, st, _, status = _kernel.integrate_timed_v(1, _KCODES[method], _params(p), p["theta0"], p["v0"],
                                                             t, rtol, rtol, 0.0, beta, 0)
            assert status == 0
            steps += st[0]
            rejected += st[2]
            nfev += st[3]
            errs.append(errors(p, reference[name], th, v)["error_max"])
    return steps, rejected, nfev, np.array(errs)


@pytest.mark.parametrize("method", ["dop853", "vern9", "vern8"])
def test_pi_control_rejects_fewer_steps_than_i_control(method, reference):
    """The rejection rate falls at least by half (measured: DOP853 22 % -> 9 %, Verner 9(8) 15 % -> 4 %,
    Verner 8(7) 17 % -> 7 %),
    the evaluations do not grow by more than 2 %, and the errors are no larger on the whole: their
    geometric mean over the 20 runs does not grow (measured: x0.62, x0.66).  One run's global error may
    move either way by a factor of a few at a fixed tolerance (the steps land elsewhere on a long run),
    so single runs are held only to a factor 10, and not at all on the chaotic driven problem (its
    Lyapunov exponent ~0.1 over t = 50 amplifies any difference of the steps by ~e^5)."""
    s0, r0, f0, e0 = _counts(method, 0.0, reference)
    s1, r1, f1, e1 = _counts(method, -1.0, reference)
    assert r1 / s1 < 0.5 * (r0 / s0), (r0 / s0, r1 / s1)
    assert f1 <= 1.02 * f0, (f0, f1)
    ratio = (e1 + 1e-15) / (e0 + 1e-15)
    assert np.exp(np.mean(np.log(ratio))) <= 1.0, ratio
    regular = np.array([name != "driven" for name in PROBLEMS for _ in RTOLS])
    assert ratio[regular].max() < 10.0, ratio


def test_pi_control_of_dopri5_is_hairers_default(reference):
    """DOPRI5's default PI term is Hairer's 0.04: the default and beta = 0.04 take the same steps."""
    assert _counts("dopri5", -1.0, reference)[:3] == _counts("dopri5", 0.04, reference)[:3]


def test_trajectory_reports_the_rejection_rate():
    tr = pendula.simulate(pendula.Scene(v0=3.0, damping=0.16, torque=0.5, t_end=100.0), rtol=1e-9, atol=1e-9)
    st = tr.stats
    assert st["steps"] == st["accepted"] + st["rejected"] and st["rhs_evaluations"] > 12 * st["steps"]
    assert st["rejection_rate"] == pytest.approx(st["rejected"] / st["steps"])
    assert 0.0 < st["rejection_rate"] < 1.0
    assert "rejection_rate" not in pendula.simulate(pendula.Scene(v0=1.0)).stats     # the exact path takes no steps

"""``pendula demo`` fits on one screen: its sweep figures in a few rounded lines, each
"not reached" with its reason, and the source texts named.

The demo itself takes a minute; these tests feed its printing functions results of the
shapes it computes (the numbers are made up: only the text is tested).
"""

import re

import pytest

from pendula import cli
from pendula.demos import sweeps as sweep_demos
from pendula.studies import workprecision as wp
from pendula.studies import workprecision_report as wpr

RESULT = {
    "basins": {"points": 4000, "decided": 1.0, "uncertain": 0, "energy_balance_disagreement": 0.1387},
    "suzuki_8_2": [(2.01, [1, 2], [1, 2], 0.21), (2.4, [1, 2, 3, 4], [0, 1, 2, 3, 4], 0.21000000000000002)],
    "suzuki_8_2_1": {"last_locked": 0.79, "first_running": 0.8, "theta_s_vs_asin_tau": 3.1e-11},
    "iv": {"switch_up": 1.0100000000000002, "retrap": {0.02: 0.030000000000000002, 0.3: 0.375}},
    "bifurcation": {"doublings": [(1.0600000000000003, 1, 2), (1.4500000000000002, 2, 4)]},
    "lyapunov": {"points": 61, "bands": [(1.09, 1.1), (1.48, 1.48)], "max_lambda": 0.1461, "A_max": 1.18,
                 "agree_with_bifurcation": 0.95, "disagree_at": [1.1], "max_sum_rule_error": 9e-11,
                 "seconds": 1.8},
}

FLOAT_NOISE = re.compile(r"\d\.\d*(0000|9999)\d")


def test_sweep_report_is_short_and_rounded():
    lines = "\n".join(sweep_demos.report(RESULT)).splitlines()
    assert len(lines) <= 12
    assert not [line for line in lines if FLOAT_NOISE.search(line)]
    assert max(len(line) for line in lines) <= 120


def test_sweep_report_band_of_one_amplitude_is_one_number():
    text = "\n".join(sweep_demos.report(RESULT))
    assert "1.480-1.480" not in text and "1.480" in text


def test_sweep_report_names_where_the_text_differs():
    text = "\n".join(sweep_demos.report(RESULT))
    assert "Suzuki & Suzuki 8.2" in text and "v0 = 2.01" in text and "for v0 = 2.4 the text also lists well 0" in text


def test_verbose_sweep_report_has_every_row():
    text = "\n".join(sweep_demos.report(RESULT, verbose=True))
    assert "v0 = 2.01" in text and "v0 = 2.40" in text and "agrees with the bifurcation diagram" in text


def _record():
    rows = [{"problem": "damped", "package": p, "method": m, "setting": f"rtol={r:g}", "rtol": r, "error_max": e,
             "seconds": s}
            for p, m, r, e, s in (("pendula", "dop853", 1e-3, 2e-4, 3e-5), ("pendula", "dop853", 1e-9, 4e-8, 9e-5),
                                  ("gsl", "gsl-rk8pd", 1e-9, 3e-8, 8e-5), ("scipy", "DOP853", 1e-9, 5e-8, 1.7e-2))]
    return {"rows": rows, "floors": {"damped": {"floor_error_max": 9.5e-15}}}


def test_work_precision_answer_is_plain_text_with_reasons():
    text = wpr.answer_text(_record())
    assert ".. list-table" not in text and "* -" not in text
    assert "not reached: tightest rtol run 1e-09" in text           # 1e-09 and 1e-12: the run stopped at 1e-9
    assert len(text.splitlines()) == 1 + 4


def test_work_precision_target_below_the_floor_says_so():
    rec = _record()
    rec["floors"]["damped"]["floor_error_max"] = 4.4e-12
    assert "not reached: below the floor 4e-12" in wpr.answer_text(rec)


def test_gallery_sources_are_named_by_author_and_title():
    assert cli._source_of("cord_damped.nml").startswith("Garfinkel")
    assert cli._source_of("huygens_cycloid.nml").startswith("Prusa & Tuma")
    assert cli._source_of("fig4_phase_portrait.nml").startswith("Suzuki & Suzuki")


@pytest.mark.parametrize("width", [40, 100])
def test_wrapped_lines_keep_to_the_width(width):
    words = [f"scene_{k:02d}_" + "x" * (k % 7) for k in range(30)]
    lines = cli._wrapped(words, width=width)
    assert all(len(line) <= width for line in lines)
    assert ", ".join(line.strip() for line in lines) == ", ".join(words)


def test_demo_has_a_verbose_switch(capsys):
    with pytest.raises(SystemExit):
        cli.main(["demo", "--help"])
    assert "-v, --verbose" in capsys.readouterr().out


def test_demo_explains_each_work_precision_figure_in_words():
    """What pendula demo prints of the integrator study: a header naming the problem, then one line per
    target saying what was timed and which is faster by how much (never a bare column of ratios)."""
    from pendula.studies.explained import work_precision_sentences

    lines = work_precision_sentences(_record())
    assert lines[0].startswith("damped pendulum (v0 = ") and "largest error below" in lines[0]
    body = lines[1:]
    # 1e-3: pendula's dop853 at rtol=1e-3 (30 us, error 2e-4) against the peer GSL's rk8pd (80 us) and
    # SciPy's DOP853 (17 ms): 80 / 30 and 17000 / 30
    assert body[0].strip() == "1e-03: pendula's dop853 30 us; the fastest peer, gsl-rk8pd, 80 us: pendula is 2.67x faster"
    assert body[1].strip() == "SciPy's fastest, DOP853, 17 ms: pendula is 567x faster"
    # 1e-6 needs dop853 at rtol=1e-9 (90 us): GSL's 80 us is faster
    assert "pendula is 1.12x slower" in body[2]
    assert body[4:] == ["  1e-09: not reached: tightest rtol run 1e-09", "  1e-12: not reached: tightest rtol run 1e-09"]
    assert all(("x faster" in ln or "x slower" in ln or "as fast" in ln or "not reached" in ln) for ln in body)
    text = "\n".join(lines)
    assert "SciPy / pendula" not in text and not FLOAT_NOISE.search(text)
    assert max(len(ln) for ln in lines) <= 100


def test_pendula_slower_is_said_as_slower():
    from pendula.studies.explained import _faster

    assert _faster(0.5) == "pendula is 2x slower" and _faster(1.0) == "as fast as pendula"

"""The work-precision answer in sentences, for a person at a terminal (``pendula demo``).

:func:`pendula.studies.workprecision_report.answer_text` is the table for someone
who knows its columns; :func:`work_precision_sentences` says the same figures
in words, one line per problem and target error: what was timed, to what
error, how long each took, and which is faster by how much.
"""

from __future__ import annotations

from .workprecision import TARGETS
from .workprecision_report import _ms, _problem_text, _why_not, answer_table

__all__ = ["work_precision_sentences"]


def _who(r) -> str:
    """The integrator of a row, named with its package unless it is pendula's own (or GSL's through pendula)."""
    if r["package"] == "pendula" or r["method"].startswith(r["package"]):
        return r["method"]
    return f"{r['package']}'s {r['method']}"


def _faster(ratio: float) -> str:
    """'pendula is 12x faster' (or slower, or as fast) for a ratio theirs / pendula's."""
    if ratio >= 1.05:
        return f"pendula is {ratio:.3g}x faster"
    if ratio <= 1 / 1.05:
        return f"pendula is {1 / ratio:.3g}x slower"
    return "as fast as pendula"


def work_precision_sentences(record: dict, targets=TARGETS) -> list[str]:
    """The figures of a work-precision record, one explained line each.

    For each problem a header naming it (its scene and time span), then one
    line per target error: the time pendula's fastest integrator takes to
    keep the largest error of the state below the target over the whole run,
    the time of the fastest peer and the ratio in words (and on a second
    line SciPy's fastest, when it is not the peer); or why no run reached
    the target.

    Parameters
    ----------
    record : dict
        A record of :func:`pendula.studies.workprecision.run_study`.
    targets : sequence of float
        The target errors.

    Returns
    -------
    list of str

    Examples
    --------
    >>> from pendula.studies.explained import work_precision_sentences
    >>> rows = [{"problem": "damped", "package": "pendula", "method": "dop853", "setting": "rtol=1e-08",
    ...          "rtol": 1e-8, "error_max": 1e-7, "seconds": 1e-4},
    ...         {"problem": "damped", "package": "scipy", "method": "RK45", "setting": "rtol=1e-08",
    ...          "rtol": 1e-8, "error_max": 1e-7, "seconds": 1.2e-2}]
    >>> rec = {"rows": rows, "floors": {"damped": {"floor_error_max": 1e-14}}}
    >>> print("\\n".join(work_precision_sentences(rec, targets=[1e-6, 1e-9])))
    damped pendulum (v0 = 2.3, beta = 0.1, 0 <= t <= 100), time to keep the largest error below:
      1e-06: pendula's dop853 100 us; the fastest peer, scipy's RK45, 12 ms: pendula is 120x faster
      1e-09: not reached: tightest rtol run 1e-08
    """
    lines, seen = [], None
    for a in answer_table(record, targets):
        if a["problem"] != seen:
            seen = a["problem"]
            lines.append(f"{seen} pendulum ({_problem_text(seen)}), time to keep the largest error below:")
        head = f"  {a['target']:.0e}:"
        p = a["pendula"]
        if p is None:
            lines.append(f"{head} {_why_not(record, a['problem'], a['target'])}")
            continue
        text = f"{head} pendula's {p['method']} {_ms(p['seconds'])}"
        peer, sci = a["peer"], a["scipy"]
        if peer is not None:
            text += f"; the fastest peer, {_who(peer)}, {_ms(peer['seconds'])}: {_faster(a['peer_ratio'])}"
        else:
            text += "; no peer reached it"
        lines.append(text)
        if sci is not None and sci is not peer:
            lines.append(f"{' ' * len(head)} SciPy's fastest, {sci['method']}, {_ms(sci['seconds'])}: "
                         f"{_faster(a['scipy_ratio'])}")
    return lines

"""What accuracy costs in time, the answer: the tables, figures and page made
from a recorded run of the work-precision study (data/bench/work_precision.json;
the study itself is :mod:`pendula.studies.workprecision`), and the one rule of
``method='auto'`` (:func:`auto_picks`), which the kernel's table is generated
from.  See docs/source/work_precision.rst.
"""

from __future__ import annotations

import json
import math
import pathlib

import numpy as np

from .._files import open_text, save_figure  # the one writer: regular files only, whole or absent
from .._optional import require
from .workprecision import DIFFRAX_BATCH, N_OUT, PENDULA_FIXED, PROBLEMS, TARGETS, run_study

__all__ = ["answer_table", "auto_picks", "auto_noise", "AUTO_CANDIDATES", "AUTO_DECADES", "answer_rst",
           "write_figures", "merge_records", "study_main", "regenerate_docs"]



def repo_root() -> pathlib.Path:
    """The source tree: the working directory when it holds data/bench, else the one this module sits in."""
    for base in (pathlib.Path.cwd(), pathlib.Path(__file__).resolve().parents[2]):
        if (base / "data" / "bench").is_dir():
            return base
    raise FileNotFoundError("run from the repository root (data/bench/ not found)")


def record_path() -> pathlib.Path:
    """data/bench/work_precision.json in the source tree (the recorded run)."""
    return repo_root() / "data" / "bench" / "work_precision.json"


def _fastest(rows, target, pred):
    ok = [r for r in rows if pred(r) and r["error_max"] <= target]
    return min(ok, key=lambda r: r["seconds"]) if ok else None


def answer_table(record: dict, targets=TARGETS) -> list[dict]:
    """The answer a user can act on, from a recorded run.

    Parameters
    ----------
    record : dict
        A record of :func:`run_study` (e.g. data/bench/work_precision.json).
    targets : sequence of float
        Target errors (the largest state error over the output times).

    Returns
    -------
    list of dict
        Per problem and target: ``pendula`` (the fastest pendula integrator's row that
        reaches it, or None), ``peer``, ``scipy``, ``compiled`` (the fastest peer other
        than SciPy), and the time ratios ``peer_ratio``, ``scipy_ratio``,
        ``compiled_ratio`` (theirs / pendula's).

    Examples
    --------
    >>> from pendula.studies.workprecision_report import answer_table
    >>> rows = [{"problem": "damped", "package": "pendula", "method": "dop853", "error_max": 1e-7, "seconds": 1e-4},
    ...         {"problem": "damped", "package": "scipy", "method": "RK45", "error_max": 1e-7, "seconds": 1e-2}]
    >>> answer_table({"rows": rows}, targets=[1e-6])[0]["scipy_ratio"]
    100.0
    """
    out = []
    rows = record["rows"]
    problems = list(dict.fromkeys(r["problem"] for r in rows))
    for pname in problems:
        pr = [r for r in rows if r["problem"] == pname]
        for target in targets:
            pend = _fastest(pr, target, lambda r: r["package"] == "pendula" and r["method"] != "exact")
            peer = _fastest(pr, target, lambda r: r["package"] != "pendula")
            sci = _fastest(pr, target, lambda r: r["package"] == "scipy")
            comp = _fastest(pr, target, lambda r: r["package"] not in ("pendula", "scipy"))
            out.append({"problem": pname, "target": target, "pendula": pend, "peer": peer, "scipy": sci,
                        "compiled": comp,
                        "peer_ratio": peer["seconds"] / pend["seconds"] if pend and peer else None,
                        "scipy_ratio": sci["seconds"] / pend["seconds"] if pend and sci else None,
                        "compiled_ratio": comp["seconds"] / pend["seconds"] if pend and comp else None})
    return out


def _cell(r):
    if r is None:
        return "not reached"
    name = r["method"] if r["package"] in ("pendula",) else f"{r['package']} {r['method']}"
    if r["package"] == "gsl":
        name = r["method"]
    return f"{name} {r['setting']}: {_ms(r['seconds'])}"


def _ms(s):
    return f"{s * 1e3:.3g} ms" if s >= 1e-3 else f"{s * 1e6:.3g} us"


def _ratio(x):
    return "-" if x is None else f"{x:.3g}"


def _with_ratio(r, ratio) -> str:
    """A table cell: the run and its time against pendula's fastest (no '-' alone: RST would make it a bullet)."""
    if r is None:
        return "not reached"
    return _cell(r) + (f" ({ratio:.3g}x)" if ratio is not None else "")


def _problem_text(pname: str) -> str:
    p = PROBLEMS[pname]
    desc = ", ".join(f"{k} = {p[k]:g}" for k in ("beta", "tau", "amp", "omega") if p.get(k))
    return f"v0 = {p['v0']:g}{', ' + desc if desc else ''}, 0 <= t <= {p['t_end']:g}"


def answer_rst(record: dict) -> str:
    """The answer of the report page (docs/source/work_precision.rst), generated from the recorded
    run: per problem its work-precision figure and a table of four columns (the target error,
    pendula's fastest, the fastest peer and SciPy's fastest with their times against pendula's)."""
    lines = []
    problems = list(dict.fromkeys(r["problem"] for r in record["rows"]))
    table = answer_table(record)
    for pname in problems:
        title = pname.capitalize()
        lines += [title, "~" * len(title), "", f"{_problem_text(pname)}.", "",
                  f".. image:: ../figures/work_precision_{pname}.png",
                  f"   :alt: work-precision diagram of the {pname} problem", "",
                  ".. list-table::", "   :header-rows: 1", "   :widths: 12 29 30 29", "",
                  "   * - target error", "     - pendula's fastest", "     - fastest peer (time / pendula's)",
                  "     - SciPy's fastest (time / pendula's)"]
        for a in (x for x in table if x["problem"] == pname):
            if a["pendula"] is None:
                why = _why_not(record, pname, a["target"])
                lines += [f"   * - {a['target']:.0e}", f"     - {why}", "     - not reached", "     - not reached"]
                continue
            lines += [f"   * - {a['target']:.0e}", f"     - {_cell(a['pendula'])}",
                      f"     - {_with_ratio(a['peer'], a['peer_ratio'])}",
                      f"     - {_with_ratio(a['scipy'], a['scipy_ratio'])}"]
        lines.append("")
    return "\n".join(lines).rstrip("\n") + "\n"


def _why_not(record: dict, problem: str, target: float) -> str:
    """Why no run reached a target, in a few words: below the double-precision floor, or
    tighter than the tightest tolerance the run tried."""
    floor = record["floors"][problem]["floor_error_max"]
    if target < floor:
        return f"not reached: below the floor {floor:.0e}"
    rtols = [r["rtol"] for r in record["rows"] if r["problem"] == problem and r.get("rtol")]
    return f"not reached: tightest rtol run {min(rtols):.0e}" if rtols else "not reached"


def _short(r) -> str:
    if r is None:
        return "not reached"
    name = r["method"] if r["package"] in ("pendula", "gsl") else f"{r['package']} {r['method']}"
    return f"{name} {r['setting']}: {_ms(r['seconds'])}"


def answer_text(record: dict) -> str:
    """The answer table as plain text for a terminal (what ``pendula accuracy integrators`` and
    ``pendula demo`` print): per problem and target, pendula's fastest, the fastest peer and
    SciPy's fastest with the time ratios, and why a target was not reached.

    Parameters
    ----------
    record : dict
        A record of :func:`run_study`.

    Returns
    -------
    str
        One header line and one line per problem and target.

    Examples
    --------
    >>> from pendula.studies.workprecision_report import answer_text
    >>> rows = [{"problem": "damped", "package": "pendula", "method": "dop853", "setting": "rtol=1e-08",
    ...          "rtol": 1e-8, "error_max": 1e-7, "seconds": 1e-4},
    ...         {"problem": "damped", "package": "scipy", "method": "RK45", "setting": "rtol=1e-08",
    ...          "rtol": 1e-8, "error_max": 1e-7, "seconds": 1e-2}]
    >>> print(answer_text({"rows": rows, "floors": {"damped": {"floor_error_max": 1e-14}}}))
    problem    target  pendula's fastest               fastest peer                    ratio  SciPy / pendula
    damped     1e-03   dop853 rtol=1e-08: 100 us       scipy RK45 rtol=1e-08: 10 ms      100  100
    damped     1e-06   dop853 rtol=1e-08: 100 us       scipy RK45 rtol=1e-08: 10 ms      100  100
    damped     1e-09   not reached: tightest rtol run 1e-08
    damped     1e-12   not reached: tightest rtol run 1e-08
    """
    lines = [f"{'problem':10s} {'target':7s} {'pendula' + chr(39) + 's fastest':31s} {'fastest peer':31s} "
             f"{'ratio':>5s}  SciPy / pendula"]
    for a in answer_table(record):
        head = f"{a['problem']:10s} {a['target']:<7.0e}"
        if a["pendula"] is None:
            lines.append(f"{head} {_why_not(record, a['problem'], a['target'])}")
            continue
        lines.append(f"{head} {_short(a['pendula']):31s} {_short(a['peer']):31s} {_ratio(a['peer_ratio']):>5s}  "
                     f"{_ratio(a['scipy_ratio'])}")
    return "\n".join(lines)


def _same_setting_ratios(record, package, method, ref_method="dop853"):
    """Time ratios package:method / pendula:ref_method at equal problem and rtol."""
    mine = {(r["problem"], r["setting"]): r["seconds"] for r in record["rows"]
            if r["package"] == "pendula" and r["method"] == ref_method}
    return [r["seconds"] / mine[(r["problem"], r["setting"])] for r in record["rows"]
            if r["package"] == package and r["method"] == method and (r["problem"], r["setting"]) in mine]


def summary_rst(record: dict) -> str:
    """The measured verdicts of the report page, as an RST bullet list generated from the record:
    the ratio ranges against SciPy and the compiled peers, and the cells where pendula is slower."""
    table = answer_table(record)
    sci = [a["scipy_ratio"] for a in table if a["scipy_ratio"] is not None]
    comp = [a for a in table if a["compiled_ratio"] is not None]
    slower = [a for a in comp if a["compiled_ratio"] < 1.0]
    lines = []
    if sci:
        lines.append(f"* SciPy's fastest / pendula's fastest: {min(sci):.0f} to {max(sci):.0f} over the {len(sci)} "
                     f"cells both reach; below 30 in {sum(x < 30 for x in sci)} of them.")
    if comp:
        lines.append(f"* fastest compiled peer / pendula's fastest: {min(a['compiled_ratio'] for a in comp):.2f} to "
                     f"{max(a['compiled_ratio'] for a in comp):.2f} over {len(comp)} cells; pendula is slower in "
                     + (f"{len(slower)}: " + ", ".join(f"{a['problem']} {a['target']:.0e} ({_cell(a['compiled'])}, "
                                                       f"{a['compiled_ratio']:.2f})" for a in slower)
                        if slower else "none") + ".")
    slow_sci = [a for a in table if a["scipy_ratio"] is not None and a["scipy_ratio"] < 30]
    if slow_sci:
        lines.append("* below 30 times SciPy: " + ", ".join(
            f"{a['problem']} {a['target']:.0e} (pendula {_cell(a['pendula'])}, SciPy {_cell(a['scipy'])}, "
            f"{a['scipy_ratio']:.0f})" for a in slow_sci) + ".")
    for pkg, method in (("numbalsoda", "dop853"), ("gsl", "gsl-rk8pd"), ("sundials", "CVODE-Adams"),
                        ("numbalsoda", "lsoda"), ("diffrax", "Dopri8"), ("diffrax", f"Dopri8-vmap{DIFFRAX_BATCH}"),
                        ("diffrax", "Tsit5"), ("diffrax", f"Tsit5-vmap{DIFFRAX_BATCH}")):
        r = _same_setting_ratios(record, pkg, method)
        if r:
            lines.append(f"* {pkg} {method} / pendula's dop853 at the same problem and rtol: median "
                         f"{float(np.median(r)):.2f} (from {min(r):.2f} to {max(r):.2f}, {len(r)} settings).")
    ex = [r for r in record["rows"] if r["method"] == "exact"]
    for r in ex:
        integ = [q["seconds"] for q in record["rows"] if q["problem"] == r["problem"] and q["method"] != "exact"]
        lines.append(f"* exact path, {r['problem']}: {_ms(r['seconds'])} for {record.get('n_out', N_OUT) + 1} "
                     f"outputs, error {r['error_max']:.1e}; the cheapest integrator run of any accuracy costs "
                     f"{min(integ) / r['seconds']:.0f} times more.")
    return "\n".join(lines) + "\n"


def versions_rst(record: dict) -> str:
    """Machine, date and versions of the recorded run, as an RST field list."""
    m = record["machine"]
    lines = [f":date: {record['date']}", f":machine: {m['cpu']}, {m['cores']} cores, {m['system']}, "
             f"Python {m['python']}"]
    for k, v in record["versions"].items():
        lines.append(f":{k}: {v if v else 'not installed'}")
    return "\n".join(lines) + "\n"


PACKAGE_STYLE = {"pendula": "-", "gsl": "--", "scipy": ":", "sundials": "-.", "numbalsoda": "-.", "diffrax": ":"}

#: the families of methods a figure shows one curve of (the best), in the legend's order
FAMILIES = (("pendula, adaptive", lambda r: r["package"] == "pendula" and r["method"] not in PENDULA_FIXED
             and r["method"] != "exact"),
            ("pendula, fixed step", lambda r: r["package"] == "pendula" and r["method"] in PENDULA_FIXED),
            ("GSL", lambda r: r["package"] == "gsl"),
            ("SciPy", lambda r: r["package"] == "scipy"),
            ("SUNDIALS", lambda r: r["package"] == "sundials"),
            ("numbalsoda", lambda r: r["package"] == "numbalsoda"))
#: the error levels at which methods are compared for "best of the family"
_LEVELS = tuple(10.0 ** (-k / 2) for k in range(4, 27))


#: the pairs method='auto' chooses from (outputs interpolated, steps not landed) and the rtol decades
AUTO_CANDIDATES = ("dopri5", "dop853", "vern9", "vern8")
AUTO_DECADES = tuple(range(3, 15))
#: a candidate qualifies with an error up to this many times rtol (or up to DOP853's own)
AUTO_SLACK = 10.0
#: the name of the rows that stand for method='auto' in the figures
AUTO = "auto"


def auto_picks(rows: list[dict]) -> dict:
    """What ``method='auto'`` integrates with, per problem and rtol decade, from a recorded study.

    For each of the study's problems (a class of scenes) and each rtol = atol = 10^-k, k = 3 ... 14,
    the fastest of pendula's pairs with an interpolant (AUTO_CANDIDATES) whose largest error over
    the outputs is no larger than DOP853's at that rtol or than 10 rtol, within the study's noise
    (:func:`auto_noise`): the qualifying pairs whose time is within that of the fastest are tied,
    and the tie goes to the smallest error (a time the study cannot tell apart is not a reason to
    give up accuracy).  The one rule: data/bench/gen_auto_methods.py writes it into the kernel's
    dispatcher, the figures draw it.

    Parameters
    ----------
    rows : list of dict
        The rows of a record of :func:`run_study`.

    Returns
    -------
    dict
        (problem, k) -> the row of the pick (None when the record has no candidate there).

    Examples
    --------
    >>> from pendula.studies.workprecision_report import auto_picks
    >>> rows = [dict(problem="damped", package="pendula", method=m, rtol=1e-6, error_max=e, seconds=s)
    ...         for m, e, s in (("dop853", 4e-6, 2.0), ("vern9", 3e-6, 1.5), ("vern8", 9e-5, 1.0))]
    >>> auto_picks(rows)["damped", 6]["method"]
    'vern9'
    """
    cand = [r for r in rows if r["package"] == "pendula" and r["method"] in AUTO_CANDIDATES
            and r.get("error_max") is not None and r.get("rtol")]
    noise = auto_noise(rows)
    out = {}
    for pname in dict.fromkeys(r["problem"] for r in rows):
        for k in AUTO_DECADES:
            rtol = 10.0 ** -k
            at = {r["method"]: r for r in cand if r["problem"] == pname and abs(r["rtol"] - rtol) <= 1e-6 * rtol}
            base = at.get("dop853")
            bound = max(AUTO_SLACK * rtol, base["error_max"] if base else 0.0)
            ok = [r for r in at.values() if r["error_max"] <= bound]
            if not ok:
                out[pname, k] = base
                continue
            fastest = min(r["seconds"] for r in ok)
            tied = [r for r in ok if r["seconds"] <= (1.0 + noise) * fastest]
            out[pname, k] = min(tied, key=lambda r: (r["error_max"], r["seconds"]))
    return out


def auto_noise(rows: list[dict]) -> float:
    """The study's own timing noise among the candidates of ``method='auto'``: the median over
    their rows of the spread of the best three rounds ((third - best) / best, the rows'
    ``spread``); 0 when the rows carry none.

    Parameters
    ----------
    rows : list of dict
        The rows of a record of :func:`run_study`.

    Returns
    -------
    float
        The relative difference in time below which two candidates count as equally fast.

    Examples
    --------
    >>> from pendula.studies.workprecision_report import auto_noise
    >>> rows = [dict(package="pendula", method="vern9", rtol=1e-6, error_max=1e-6, spread=s)
    ...         for s in (0.05, 0.1, 0.2)]
    >>> auto_noise(rows)
    0.1
    """
    sp = sorted(float(r["spread"]) for r in rows if r.get("package") == "pendula"
                and r.get("method") in AUTO_CANDIDATES and r.get("rtol") and r.get("error_max") is not None
                and r.get("spread") is not None and math.isfinite(float(r["spread"])))
    if not sp:
        return 0.0
    n = len(sp)
    return sp[n // 2] if n % 2 else 0.5 * (sp[n // 2 - 1] + sp[n // 2])


def best_of_families(rows: list[dict]) -> list[tuple[str, str, str]]:
    """The curves of a problem's figure: the best method of each family, and what ``method='auto'``
    integrates with (:func:`auto_picks`: rows named 'auto', when the rows have them).

    The best method of a family is the one fastest at the most error levels (10^-2 ... 10^-13 in
    half decades, each reached by at least one of the family); ties go to the smaller sum of log
    times.

    Parameters
    ----------
    rows : list of dict
        The rows of one problem of a record of :func:`run_study`.

    Returns
    -------
    list of (family, package, method)
        At most one per family, plus pendula's DOP853: at most 7 curves.

    Examples
    --------
    >>> from pendula.studies.workprecision_report import best_of_families
    >>> rows = [dict(package="scipy", method=m, error_max=e, seconds=s)
    ...         for m, e, s in (("RK45", 1e-6, 2.0), ("DOP853", 1e-6, 1.0), ("DOP853", 1e-9, 1.5))]
    >>> best_of_families(rows)
    [('SciPy', 'scipy', 'DOP853')]
    """
    out = []
    has_auto = any(r["method"] == AUTO for r in rows)
    rows = [r for r in rows if r["method"] != AUTO]
    for family, member in FAMILIES:
        fam = [r for r in rows if member(r)]
        methods = list(dict.fromkeys((r["package"], r["method"]) for r in fam))
        if not methods:
            continue
        wins = {m: 0 for m in methods}
        logt = {m: 0.0 for m in methods}
        for level in _LEVELS:
            best = {}
            for r in fam:
                if r["error_max"] <= level:
                    key = (r["package"], r["method"])
                    best[key] = min(best.get(key, math.inf), r["seconds"])
            if not best:
                continue
            wins[min(best, key=best.get)] += 1
            for m in methods:
                logt[m] += math.log(best.get(m, 1e3))      # a level a method misses counts as very slow
        pkg, method = max(methods, key=lambda m: (wins[m], -logt[m]))
        out.append((family, pkg, method))
        if family == "pendula, adaptive" and has_auto:
            out.append(("pendula, method='auto'", "pendula", AUTO))
    return out


def write_figures(record: dict, outdir) -> list[pathlib.Path]:
    """One work-precision diagram per problem: the best method of each family.

    Error against CPU time (log-log), at most 8 curves (:func:`best_of_families`),
    with the double-precision floor and (conservative problems) the exact path;
    every method's numbers are in the record and the page's tables.

    Parameters
    ----------
    record : dict
        A record of :func:`run_study`.
    outdir : str or path
        Folder for work_precision_PROBLEM.png (created).

    Returns
    -------
    list of pathlib.Path
        The files written.

    Examples
    --------
    >>> import json
    >>> from pendula.studies.workprecision_report import record_path, write_figures
    >>> write_figures(json.loads(record_path().read_text()), "out")   # doctest: +SKIP
    """
    matplotlib = require("matplotlib", "accuracy", "pendula accuracy integrators (figures)")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    outdir = pathlib.Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    files = []
    rows = record["rows"]
    # method='auto': the rows of its picks, one per rtol decade
    rows = rows + [dict(r, method=AUTO) for r in auto_picks(rows).values() if r is not None]
    for pname in dict.fromkeys(r["problem"] for r in rows):
        pr = [r for r in rows if r["problem"] == pname]
        fig, ax = plt.subplots(figsize=(7.5, 5.8))
        for family, pkg, method in best_of_families(pr):
            sel = sorted((r for r in pr if r["package"] == pkg and r["method"] == method),
                         key=lambda r: r["seconds"])
            err = np.maximum([r["error_max"] for r in sel], 1e-17)
            sec = [r["seconds"] for r in sel]
            ax.loglog(sec, err, PACKAGE_STYLE.get(pkg, "-"), marker="o" if pkg == "pendula" else ".",
                      ms=4, lw=1.4 if pkg == "pendula" else 1.1, label=f"{family}: {method}")
        ex = [r for r in pr if r["method"] == "exact"]
        if ex:
            ax.loglog([ex[0]["seconds"]], [max(ex[0]["error_max"], 1e-17)], "k*", ms=12, label="pendula: exact path")
        floor = record["floors"][pname]["floor_error_max"]
        ax.axhline(floor, color="k", lw=0.8, ls="--")
        ax.text(ax.get_xlim()[0], floor, " double-precision floor (1 ulp in v0)", va="bottom", fontsize=7)
        for target in TARGETS:
            ax.axhline(target, color="0.85", lw=0.5)
        ax.set_xlabel("CPU time of one run (s)")
        ax.set_ylabel("largest state error over the outputs")
        title = f"{pname}: {_problem_text(pname)}"
        if pname == "driven":
            title += "\nchaotic: compared over ~5 Lyapunov times only (lambda ~ 0.1)"
        ax.set_title(title, fontsize=9)
        ax.grid(True, which="both", alpha=0.25)
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=3, frameon=False)
        fig.tight_layout()
        path = outdir / f"work_precision_{pname}.png"
        try:
            save_figure(fig, path, dpi=100)
        finally:
            plt.close(fig)
        files.append(path)
    return files


def merge_records(records: list[dict]) -> dict:
    """One record from runs of the study on disjoint sets of problems (the recorded run was made
    as one process per problem): rows and floors joined, the first record's header kept, the
    dates joined."""
    out = dict(records[0])
    out["rows"] = [r for rec in records for r in rec["rows"]]
    out["floors"] = {k: v for rec in records for k, v in rec["floors"].items()}
    out["date"] = " / ".join(sorted({rec["date"] for rec in records}))
    return out


def study_main(outdir, quick=False, progress=True, record_to=None, problems=None) -> list[pathlib.Path]:
    """``pendula accuracy integrators`` (and its short form in ``make demo``).

    Runs the study, writes the record and the figures, prints the answer table.

    Parameters
    ----------
    outdir : str or path
        Folder for the record (work_precision.json) and the figures.
    quick : bool
        The short form (see :func:`run_study`).
    progress : bool
        Print one line per run.
    record_to : str or path, optional
        Where to write the record instead (e.g. data/bench/work_precision.json).
    problems : sequence of str, optional
        Only these problems.

    Returns
    -------
    list of pathlib.Path
        The files written.

    Examples
    --------
    >>> from pendula.studies.workprecision_report import study_main
    >>> study_main("out", quick=True)      # doctest: +SKIP
    """
    # the optional packages first: a missing one is one line before the study runs, never a traceback after
    require("scipy.integrate", "bench", "pendula accuracy integrators (the SciPy peers)")
    require("matplotlib", "accuracy", "pendula accuracy integrators (figures)")
    outdir = pathlib.Path(outdir)
    if outdir.exists() and not outdir.is_dir():
        raise NotADirectoryError(20, "is not a folder", str(outdir))
    outdir.mkdir(parents=True, exist_ok=True)
    record = run_study(problems=problems, quick=quick, progress=progress)
    path = pathlib.Path(record_to) if record_to else outdir / "work_precision.json"
    with open_text(path) as fh:
        fh.write(json.dumps(record, indent=1) + "\n")
    files = [path] + write_figures(record, outdir)
    print(answer_text(record))
    return files


#: the report page and the markers around its generated parts
PAGE = pathlib.Path("docs") / "source" / "work_precision.rst"
GENERATED = {"table": (".. generated answer table (pendula.studies.workprecision_report.answer_rst): do not edit by hand",
                       ".. end of the generated answer table"),
             "versions": (".. generated run description (pendula.studies.workprecision_report.versions_rst): do not edit",
                          ".. end of the generated run description"),
             "summary": (".. generated verdicts (pendula.studies.workprecision_report.summary_rst): do not edit",
                         ".. end of the generated verdicts")}


def generated_parts(record: dict) -> dict:
    """The page's generated parts from the recorded run: the answer table and the run description."""
    return {"table": answer_rst(record), "versions": versions_rst(record), "summary": summary_rst(record)}


def page_part(text: str, key: str) -> str:
    """The text between one pair of markers of the report page."""
    start, end = GENERATED[key]
    a = text.index(start) + len(start)
    b = text.index(end)
    return text[a:b].strip("\n") + "\n"


def update_page(record: dict, page=None) -> None:
    """Write the generated parts of the report page (docs/source/work_precision.rst) from the record."""
    page = pathlib.Path(page or repo_root() / PAGE)
    text = page.read_text()
    for key, body in generated_parts(record).items():
        start, end = GENERATED[key]
        a = text.index(start) + len(start)
        b = text.index(end)
        text = text[:a] + "\n\n" + body + "\n" + text[b:]
    page.write_text(text)


def regenerate_docs(record_file=None) -> list[pathlib.Path]:
    """The figures and the report page's tables from the recorded run.

    Parameters
    ----------
    record_file : str or path, optional
        The record (default data/bench/work_precision.json).

    Returns
    -------
    list of pathlib.Path
        docs/figures/work_precision_*.png and docs/source/work_precision.rst.

    Examples
    --------
    >>> from pendula.studies.workprecision_report import regenerate_docs
    >>> regenerate_docs()          # doctest: +SKIP
    """
    record = json.loads(pathlib.Path(record_file or record_path()).read_text())
    files = write_figures(record, repo_root() / "docs" / "figures")
    update_page(record)
    return files + [repo_root() / PAGE]

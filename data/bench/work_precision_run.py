"""Re-run the work-precision study side by side: pendula and every peer interleaved in one process.

Each problem's runs (pendula's methods, GSL's rk8pd, SciPy's RK45, DOP853 and LSODA, SUNDIALS CVODE,
numbalsoda, diffrax's Dopri8 and Tsit5 jitted, one problem and vmapped over 256) are calibrated and
timed once, then all again in turn, ROUNDS rounds in all; each keeps its best round
(pendula.studies.workprecision.run_study with interleave).  SciPy's Radau (seconds per run at tight
tolerances, never SciPy's fastest in the stored study) is not re-run: its rows are kept from the
record this run replaces, marked ``"kept_from": <that record's date>``.  The load average of the
machine is recorded before and after.  Writes data/bench/work_precision.json (with ``cells``: per
problem and target, pendula's fastest method, the fastest compiled peer and SciPy's, and the ratios)
and regenerates the report page's tables and figures.

Usage:  python data/bench/work_precision_run.py [--rounds 5] [--problems damped,driven]
"""

import argparse
import json
import os
import pathlib

from pendula.studies import workprecision as wp

RECORD = pathlib.Path(__file__).resolve().parent / "work_precision.json"


def cells(record):
    """Per problem and target: pendula's fastest, the fastest compiled peer, SciPy's fastest, the ratios."""
    out = []
    name = lambda r: None if r is None else f"{r['package']}:{r['method']} {r['setting']}"  # noqa: E731
    for a in wp.answer_table(record):
        out.append({"problem": a["problem"], "target": a["target"], "pendula": name(a["pendula"]),
                     "pendula_seconds": a["pendula"]["seconds"] if a["pendula"] else None,
                     "compiled_peer": name(a["compiled"]), "compiled_ratio": a["compiled_ratio"],
                     "scipy": name(a["scipy"]), "scipy_ratio": a["scipy_ratio"]})
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--problems", default=",".join(wp.PROBLEMS))
    args = ap.parse_args()
    old = json.loads(RECORD.read_text())
    problems = tuple(args.problems.split(","))
    methods = [m for m in set(r[1] for p in wp.PROBLEMS.values() for r in wp._plan(p, wp.TOLS, False))
               if m != "Radau"] + ["exact"]
    load_before = list(os.getloadavg())
    rec = wp.run_study(problems=problems, methods=methods, interleave=args.rounds)
    rec["load_average_1_5_15_before"] = load_before
    kept = [dict(r, kept_from=old["date"]) for r in old["rows"]
            if r["method"] == "Radau" or r["problem"] not in problems]
    rec["rows"] += kept
    rec["floors"] = {**old["floors"], **rec["floors"]}
    rec["note"] = (f"interleaved run, {args.rounds} rounds, best kept; SciPy Radau rows (and the rows of problems "
                   f"not re-run) kept from the run of {old['date']}")
    rec["cells"] = cells(rec)
    RECORD.write_text(json.dumps(rec, indent=1) + "\n")
    print(f"wrote {RECORD}")
    for c in rec["cells"]:
        print(c)
    wp.regenerate_docs(RECORD)


if __name__ == "__main__":
    main()

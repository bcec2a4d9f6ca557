"""Re-run the work-precision study, side by side with the peers.

The runs of each problem (by default every method of pendula, with and without landing on the
outputs, its exact path; GSL's rk8pd; numbalsoda's DOP853 and LSODA; diffrax's Dopri8 and Tsit5,
jitted, one problem and vmapped over 256: every compiled method) are calibrated and timed once,
then all again in turn, ROUNDS rounds in all; each keeps its best round
(pendula.studies.workprecision.run_study with interleave).  The peers called through Python, SciPy
(a Python loop, 70 to 330 times slower in every cell: seconds per run at tight tolerances) and
SUNDIALS CVODE (about 40 times slower), are run by their own invocation (--packages scipy,sundials)
or their rows kept from the record this run replaces, marked ``"kept_from": <that record's date>``.
The machine's load average is recorded before and after each part.  The merged record gets
``cells``: per problem and target, pendula's fastest method, the fastest compiled peer and SciPy's,
and the ratios.

Usage:
    python data/bench/work_precision_run.py --problems damped,driven --out part1.json [--rounds 5]
    python data/bench/work_precision_run.py --packages scipy,sundials --rounds 1 --out part9.json
    python data/bench/work_precision_run.py --problems torqued --tols 1e-3,...,1e-15 --out part2.json
    python data/bench/work_precision_run.py --merge part1.json part2.json ...
        (writes data/bench/work_precision.json and regenerates the report page's tables and figures)
"""

import argparse
import json
import os
import pathlib

from pendula.studies import workprecision as wp
from pendula.studies import workprecision_report as wpr

RECORD = pathlib.Path(__file__).resolve().parent / "work_precision.json"
#: the packages re-run side by side by default: pendula and the compiled peers (not called through Python)
COMPILED = ("pendula", "gsl", "numbalsoda", "diffrax")


def cells(record):
    """Per problem and target: pendula's fastest, the fastest compiled peer, SciPy's fastest, the ratios."""
    out = []
    name = lambda r: None if r is None else f"{r['package']}:{r['method']} {r['setting']}"  # noqa: E731
    for a in wpr.answer_table(record):
        out.append({"problem": a["problem"], "target": a["target"], "pendula": name(a["pendula"]),
                     "pendula_seconds": a["pendula"]["seconds"] if a["pendula"] else None,
                     "compiled_peer": name(a["compiled"]), "compiled_ratio": a["compiled_ratio"],
                     "scipy": name(a["scipy"]), "scipy_ratio": a["scipy_ratio"]})
    return out


def rerun(problems, rounds, out, packages, tols=None):
    load_before = list(os.getloadavg())
    rec = wp.run_study(problems=problems, packages=packages, interleave=rounds, tols=tols)
    rec["load_average_1_5_15_before"] = load_before
    rec["packages"] = list(packages)
    pathlib.Path(out).write_text(json.dumps(rec, indent=1) + "\n")
    print(f"wrote {out}")


def merge(parts):
    old = json.loads(RECORD.read_text())
    recs = [json.loads(pathlib.Path(p).read_text()) for p in parts]
    rec = wpr.merge_records(recs)
    again = {(r["problem"], r["package"], r["method"]) for r in rec["rows"]}
    kept = sorted({r["package"] for r in old["rows"] if (r["problem"], r["package"], r["method"]) not in again})
    rec["rows"] += [dict(r, kept_from=r.get("kept_from", old["date"])) for r in old["rows"]
                    if (r["problem"], r["package"], r["method"]) not in again]
    rec["floors"] = {**old["floors"], **rec["floors"]}
    rec["load_average_1_5_15"] = [x["load_average_1_5_15"] for x in recs]
    rec["load_average_1_5_15_before"] = [x.get("load_average_1_5_15_before") for x in recs]
    parts = "; ".join(dict.fromkeys(f"{', '.join(x.get('packages', []))}: {x['interleave']} interleaved rounds, "
                                    f"best kept" for x in recs))
    rec["note"] = (f"re-run by problem, every method of each package side by side ({parts})"
                   + (f"; the rows of {', '.join(kept)} kept from the run of {old['date']}" if kept else ""))
    rec["cells"] = cells(rec)
    RECORD.write_text(json.dumps(rec, indent=1) + "\n")
    print(f"wrote {RECORD}")
    for c in rec["cells"]:
        print(c)
    wpr.regenerate_docs(RECORD)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--problems", default=",".join(wp.PROBLEMS))
    ap.add_argument("--out")
    ap.add_argument("--merge", nargs="+")
    ap.add_argument("--packages", default=",".join(COMPILED))
    ap.add_argument("--tols", help="rtol settings of the adaptive methods, comma-separated (default: the study's)")
    args = ap.parse_args()
    if args.merge:
        merge(args.merge)
    else:
        tols = [float(x) for x in args.tols.split(",")] if args.tols else None
        rerun(tuple(args.problems.split(",")), args.rounds, args.out, tuple(args.packages.split(",")), tols)


if __name__ == "__main__":
    main()

"""Re-run the work-precision study for the methods whose code changed, side by side with the peers.

The runs of each problem (pendula's DOP853 and Verner 9(8), each with its interpolant and landing
on the outputs; GSL's rk8pd; numbalsoda's DOP853 and LSODA; diffrax's Dopri8 and Tsit5, jitted, one
problem and vmapped over 256) are calibrated and timed once, then all again in turn, ROUNDS rounds
in all; each keeps its best round (pendula.studies.workprecision.run_study with interleave).  The
rows of every other method are kept from the record this run replaces, marked ``"kept_from": <that
record's date>``: pendula's DOPRI5, RKN pair, fixed-step methods and exact path (their code did not
change), SciPy (a Python loop, 70 to 290 times slower in every cell: seconds per run at tight
tolerances) and SUNDIALS CVODE (called through Python, about 40 times slower).  The machine's load
average is recorded.  The merged record gets ``cells``: per problem and target, pendula's fastest
method, the fastest compiled peer and SciPy's, and the ratios.

Usage:
    python data/bench/work_precision_run.py --problems damped,driven --out part1.json [--rounds 5]
    python data/bench/work_precision_run.py --merge part1.json part2.json ...
        (writes data/bench/work_precision.json and regenerates the report page's tables and figures)
"""

import argparse
import json
import os
import pathlib

from pendula.studies import workprecision as wp

RECORD = pathlib.Path(__file__).resolve().parent / "work_precision.json"
#: the methods re-run (pendula's changed ones and the compiled peers that are not called through Python)
RERUN = ("dop853", "dop853" + wp.LANDED, "vern9", "vern9" + wp.LANDED, "gsl-rk8pd", "lsoda",
         "Dopri8", "Tsit5", f"Dopri8-vmap{wp.DIFFRAX_BATCH}", f"Tsit5-vmap{wp.DIFFRAX_BATCH}")
#: packages whose rows named like a re-run method are re-run (SciPy's 'DOP853' is not numbalsoda's 'dop853')
RERUN_PACKAGES = ("pendula", "gsl", "numbalsoda", "diffrax")


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


def rerun(problems, rounds, out):
    load_before = list(os.getloadavg())
    rec = wp.run_study(problems=problems, methods=RERUN, packages=RERUN_PACKAGES, interleave=rounds)
    rec["load_average_1_5_15_before"] = load_before
    pathlib.Path(out).write_text(json.dumps(rec, indent=1) + "\n")
    print(f"wrote {out}")


def merge(parts):
    old = json.loads(RECORD.read_text())
    recs = [json.loads(pathlib.Path(p).read_text()) for p in parts]
    rec = wp.merge_records(recs)
    again = {(r["problem"], r["package"], r["method"]) for r in rec["rows"]}
    rec["rows"] += [dict(r, kept_from=r.get("kept_from", old["date"])) for r in old["rows"]
                    if (r["problem"], r["package"], r["method"]) not in again]
    rec["floors"] = {**old["floors"], **rec["floors"]}
    rec["load_average_1_5_15"] = [x["load_average_1_5_15"] for x in recs]
    rec["load_average_1_5_15_before"] = [x.get("load_average_1_5_15_before") for x in recs]
    rec["note"] = (f"re-run side by side, {recs[0]['interleave']} interleaved rounds, best kept, of "
                   f"{', '.join(RERUN)} (pendula, GSL, numbalsoda, diffrax); every other row kept from the run of "
                   f"{old['date']} (its code did not change, or a peer called through Python: SciPy, CVODE)")
    rec["cells"] = cells(rec)
    RECORD.write_text(json.dumps(rec, indent=1) + "\n")
    print(f"wrote {RECORD}")
    for c in rec["cells"]:
        print(c)
    wp.regenerate_docs(RECORD)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--problems", default=",".join(wp.PROBLEMS))
    ap.add_argument("--out")
    ap.add_argument("--merge", nargs="+")
    args = ap.parse_args()
    if args.merge:
        merge(args.merge)
    else:
        rerun(tuple(args.problems.split(",")), args.rounds, args.out)


if __name__ == "__main__":
    main()

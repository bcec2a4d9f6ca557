#!/bin/sh
# Gauss6 round-off study (issue 15): which ingredient makes the energy drift?
# Builds the stand-alone experiment (not part of pendula), runs the variants
# (form: 0 pendula's a/b form, 1 mu form; stop rule 0/1; sine 0 libm / 1 x87
# sinl) and draws docs/figures/gauss6_roundoff_T{1000,200}.png.
# CPU: ~20 s per variant at 10^7 steps; run niced.  Usage: data/brouwer/run.sh [.venv/bin/python]
set -e
PY=${1:-.venv/bin/python}
here=$(cd "$(dirname "$0")" && pwd)
work=${TMPDIR:-/tmp}/pendula-brouwer
mkdir -p "$work/h1000" "$work/h200"
"$PY" "$here/gen.py" > "$work/coef.inc"
gfortran -O2 -ffree-line-length-none -ffp-contract=off -fno-fast-math -I"$work" "$here/brouwer.f90" -o "$work/brouwer"
for f in 0 1; do for s in 0 1; do for q in 0 1; do
  nice "$work/brouwer" $f $s $q 10000000 1000 > "$work/h1000/r_$f$s$q.txt"
done; done; done
for v in "0 0 0" "1 0 0" "0 0 1" "1 1 1"; do
  set -- $v
  nice "$work/brouwer" $1 $2 $3 20000000 200 > "$work/h200/r_$1$2$3.txt"
done
"$PY" "$here/plot.py" "$work/h1000" docs/figures/gauss6_roundoff_T1000.png 1000
"$PY" "$here/plot.py" "$work/h200" docs/figures/gauss6_roundoff_T200.png 200

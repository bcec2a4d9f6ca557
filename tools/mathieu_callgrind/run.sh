#!/bin/bash
# Instruction counts (valgrind --tool=callgrind) per Mathieu value and per transmon
# spectrum: pendula's kernel (compiled here from kernel/ with the project's flags,
# without -march=native, which valgrind cannot run), GSL's gsl_sf_mathieu_a_e in C,
# SciPy's mathieu_a and numpy's batched eigvalsh.  Each program runs 1 and 3
# repetitions; the difference over 2 repetitions removes start-up and imports.
# Repeatable where wall time on a loaded machine is not; instructions are not
# cycles (a division costs more than an addition), so read both.
#   bash tools/mathieu_callgrind/run.sh     (from the repository's root, after make)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
here="$root/tools/mathieu_callgrind"
py="$root/.venv/bin/python"
w=$(mktemp -d)
trap 'rm -rf "$w"' EXIT
ff="-O3 -ffp-contract=off -fno-fast-math -fno-trapping-math -fimplicit-none -frecursive"
cd "$w"
gfortran $ff -c "$root/kernel/base/pendula_kinds.f90" "$root/kernel/base/pendula_dd.f90"
gfortran $ff -c "$root/kernel/mathieu/pendula_mathieu.f90"
gcc -O3 -ffp-contract=off -fno-math-errno -c "$root/kernel/mathieu/pendula_mathieu_polish.c"
obj="pendula_kinds.o pendula_dd.o pendula_mathieu.o pendula_mathieu_polish.o"
gfortran $ff "$here/pendula_values.f90" $obj -o values
gfortran $ff "$here/pendula_transmon.f90" $obj -o transmon
gcc -O2 "$here/gsl_values.c" -o gsl_values -lgsl -lgslcblas -lm
"$py" "$here/points.py" "$w"
count() { valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 | awk '/Collected/ {print $4}'; }
per() { local a b; a=$(count "${@:3}" 1); b=$(count "${@:3}" 3); echo $(( (b - a) / ($1 * 2) )); }
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
for q in 10 1000; do
  p=$(per 2000 x ./values "pts$q.txt")
  g=$(per 2000 x ./gsl_values "pts$q.txt")
  s=$(per 2000 x "$py" "$here/scipy_values.py" "pts$q.txt")
  echo "a_n(q), n 0..10, q 1e-2..$q: instructions per value: pendula $p, GSL $g, SciPy $s"
done
p=$(per 1000 x ./transmon)
n=$(per 1000 x "$py" "$here/numpy_transmon.py")
echo "transmon E_J/E_C = 50, 10 levels: instructions per offset charge: pendula $p, numpy eigvalsh (ncut 13) $n"

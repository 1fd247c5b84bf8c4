#!/usr/bin/env bash
# dam_break_mpi on 2 processes against dam_break on one: the same CSV columns, the surge front
# and column height within 1 % at every output time (the distributed fluid's tolerance against
# one process, docs/scaling.md), and a parallel VTU with one piece per process for each snapshot.
# Usage: mpi_test.sh <mpiexec> <dam_break> <dam_break_mpi> <output folder> [mpiexec flags...]
set -euo pipefail
mpiexec=$1 serial=$2 distributed=$3 out=$4
shift 4
rm -rf "$out"
options=(--end 0.05 --every 0.025)
"$serial" "${options[@]}" --out "$out/serial" > /dev/null
OMP_NUM_THREADS=1 "$mpiexec" -np 2 "$@" "$distributed" "${options[@]}" --out "$out/mpi" > /dev/null
if ! cmp -s <(head -1 "$out/serial/dam_break.csv") <(head -1 "$out/mpi/dam_break.csv"); then
  echo "FAIL: the CSV columns differ"; exit 1
fi
rows=$(($(wc -l < "$out/serial/dam_break.csv") - 1))
if [ "$rows" -ne 3 ] || [ "$(($(wc -l < "$out/mpi/dam_break.csv") - 1))" -ne "$rows" ]; then
  echo "FAIL: expected 3 rows in both CSVs"; exit 1
fi
# Columns 3 (Z/a) and 5 (H/2a), row by row.
paste -d, <(tail -n +2 "$out/serial/dam_break.csv") <(tail -n +2 "$out/mpi/dam_break.csv") |
  awk -F, '{ for (c = 3; c <= 5; c += 2) { d = $(c + 7) / $c - 1; if (d < 0) d = -d;
             printf "t = %s: column %d serial %s, 2 processes %s\n", $1, c, $c, $(c + 7);
             if (d > 0.01) bad = 1 } } END { exit bad }' || { echo "FAIL: beyond 1 %"; exit 1; }
for k in 0 1 2; do
  for f in "dam_break_$k.pvtu" "dam_break_${k}_p0.vtu" "dam_break_${k}_p1.vtu"; do
    [ -s "$out/mpi/$f" ] || { echo "FAIL: $f missing"; exit 1; }
  done
  grep -q "dam_break_$k.pvtu" "$out/mpi/dam_break.pvd" || { echo "FAIL: dam_break_$k.pvtu not in the .pvd"; exit 1; }
done
echo "PASS"

#!/usr/bin/env bash
# dam_break_mpi on 2 processes against dam_break on one: the same CSV columns, the surge front
# and column height within 1 % at every output time (the distributed fluid's tolerance against
# one process, docs/scaling.md), a parallel VTU with one piece per process for each snapshot, and
# a run continued from its checkpoint.
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
# Checkpoints: a run on 2 processes that ends after its checkpoint at t = 0.025 s, continued from
# it to 0.05 s, writes what the straight run wrote: every .pvtu, piece and the .pvd byte for byte,
# the CSV except its wall-time column.
OMP_NUM_THREADS=1 "$mpiexec" -np 2 "$@" "$distributed" --every 0.025 --end 0.04 --checkpoint-every 0.025 \
  --out "$out/continued" > /dev/null 2>&1
for piece in 0 1; do
  [ -s "$out/continued/checkpoint_000000125_p$piece.bin" ] || { echo "FAIL: checkpoint piece $piece missing"; exit 1; }
done
OMP_NUM_THREADS=1 "$mpiexec" -np 2 "$@" "$distributed" "${options[@]}" --restart "$out/continued/checkpoint_000000125" \
  --out "$out/continued" > /dev/null
for f in "$out"/mpi/dam_break_*.vtu "$out"/mpi/dam_break_*.pvtu "$out/mpi/dam_break.pvd"; do
  cmp "$f" "$out/continued/$(basename "$f")" || { echo "FAIL: $(basename "$f") differs after the restart"; exit 1; }
done
cmp <(cut -d, -f1-6 "$out/mpi/dam_break.csv") <(cut -d, -f1-6 "$out/continued/dam_break.csv") ||
  { echo "FAIL: the CSV differs after the restart"; exit 1; }
echo "continued from the checkpoint at t = 0.025 s on 2 processes: the same files"
# SIGTERM to mpirun, which passes it on: every process writes its piece at the same step, the
# run says how to continue, and it continues.
OMP_NUM_THREADS=1 "$mpiexec" -np 2 "$@" "$distributed" --end 100 --out "$out/term" > "$out/term.log" 2>&1 &
pid=$!
for _ in $(seq 300); do  # until the run has taken its first steps (at most 30 s)
  grep -q "^step " "$out/term.log" 2>/dev/null && break
  sleep 0.1
done
sleep 0.5
kill -TERM "$pid"
set +e
wait "$pid"
code=$?
set -e
[ "$code" != 0 ] || { echo "FAIL: the run was not stopped by SIGTERM"; exit 1; }
stem=$(sed -n 's/.*stopped by a signal; continue with --restart //p' "$out/term.log")
[ -n "$stem" ] && [ -s "${stem}_p0.bin" ] && [ -s "${stem}_p1.bin" ] ||
  { echo "FAIL: no checkpoint or no restart hint after SIGTERM"; cat "$out/term.log"; exit 1; }
step=$(basename "$stem")
step=$((10#${step#checkpoint_}))
OMP_NUM_THREADS=1 "$mpiexec" -np 2 "$@" "$distributed" --end "$(awk -v s="$step" 'BEGIN { print (s + 10) * 2e-4 }')" \
  --restart "$stem" --out "$out/term" > /dev/null 2>&1 || { echo "FAIL: the run stopped by SIGTERM did not continue"; exit 1; }
echo "SIGTERM: checkpoint at step $step on both processes, continued"
# On as many processes only: a checkpoint of 2 processes read on 1 stops with a message.
if OMP_NUM_THREADS=1 "$mpiexec" -np 1 "$@" "$distributed" "${options[@]}" --restart "$out/continued/checkpoint_000000125" \
  --out "$out/one" > "$out/one.log" 2>&1; then
  echo "FAIL: a 2-process checkpoint continued on 1 process"; exit 1
fi
grep -q "processes" "$out/one.log" || { echo "FAIL: no message about the process count"; cat "$out/one.log"; exit 1; }
echo "PASS"

#!/usr/bin/env bash
# Restart test of the bending study (ctest example.three_point_bending.restart): case 02 run
# straight through, and run again with a checkpoint 0.2 ms after the straight run's first failure,
# then continued from that checkpoint. The snapshots, PVD index, load history, failures and final
# state must be byte for byte the same, and so must the summary (its wall-time column aside).
# Usage: restart_test.sh <three_point_bending executable> <scratch folder>
set -euo pipefail
exe=$1
dir=$2
rm -rf "$dir"
"$exe" --case 02 --out "$dir/straight" > /dev/null 2>&1
first_failure=$(awk -F, 'NR == 2 { print $1 }' "$dir/straight/case02_failures.csv")
every=$(awk -v t="$first_failure" 'BEGIN { printf "%.6g", t + 2e-4 }')
"$exe" --case 02 --checkpoint-every "$every" --out "$dir/split" > /dev/null 2> "$dir/split.log"
checkpoint=$(ls "$dir"/split/checkpoint_case02_*.bin | head -n 1)
"$exe" --case 02 --restart "$checkpoint" --out "$dir/split" > "$dir/continued.log" 2>&1
grep -q "continuing from" "$dir/continued.log" || { echo "FAIL: the run did not continue"; exit 1; }
count=0
for f in "$dir"/straight/*.vtu "$dir"/straight/*.pvd "$dir"/straight/case02_*.csv; do
  cmp "$f" "$dir/split/$(basename "$f")" || { echo "FAIL: $(basename "$f") differs"; exit 1; }
  count=$((count + 1))
done
cmp <(cut -d, -f1-16 "$dir/straight/summary.csv") <(cut -d, -f1-16 "$dir/split/summary.csv") ||
  { echo "FAIL: summary.csv differs"; exit 1; }
echo "first failure at t = $first_failure s; continued from $(basename "$checkpoint") (t = $every s): $count files the same"
echo "PASS"

#!/usr/bin/env bash
# Restart test of the elastic-gate example (ctest example.elastic_gate.restart): a coarse run
# (l0 = 2.5 mm, sub-iterated coupling) to 0.08 s straight through, and one that stops at 0.05 s
# after a checkpoint at 0.04 s and is continued from it to 0.08 s. Every VTU, PVD and CSV file of
# the two must be byte for byte the same.
# Usage: restart_test.sh <elastic_gate executable> <scratch folder>
set -euo pipefail
exe=$1
dir=$2
rm -rf "$dir"
common=(--l0 0.0025 --every 0.01)
"$exe" "${common[@]}" --end 0.08 --out "$dir/straight" > /dev/null 2>&1
"$exe" "${common[@]}" --end 0.05 --checkpoint-every 0.04 --out "$dir/split" > /dev/null 2>&1
checkpoint=$(ls "$dir"/split/checkpoint_*.bin | tail -n 1)
"$exe" "${common[@]}" --end 0.08 --restart "$checkpoint" --out "$dir/split" > "$dir/continued.log" 2>&1
grep -q "continuing from" "$dir/continued.log" || { echo "FAIL: the run did not continue"; exit 1; }
count=0
for f in "$dir"/straight/*.vtu "$dir"/straight/*.pvd "$dir"/straight/*.csv; do
  cmp "$f" "$dir/split/$(basename "$f")" || { echo "FAIL: $(basename "$f") differs"; exit 1; }
  count=$((count + 1))
done
[ "$(ls "$dir"/straight/*.vtu | wc -l)" = "$(ls "$dir"/split/*.vtu | wc -l)" ] || { echo "FAIL: snapshot counts differ"; exit 1; }
echo "continued from $(basename "$checkpoint"): $count files the same"
echo "PASS"

#!/usr/bin/env bash
# Restart test of the droplet example with fracture (ctest example.droplet_on_ice_beam.restart):
# a coarse run (l0 = 5 mm) to 4 ms straight through, and one that stops at 2.5 ms after a
# checkpoint at 2 ms (past the first failure, at about 0.7 ms) and is continued from it to 4 ms.
# Every VTU, PVD and CSV file of the two must be byte for byte the same.
# Usage: restart_test.sh <droplet_on_ice_beam executable> <scratch folder>
set -euo pipefail
exe=$1
dir=$2
rm -rf "$dir"
common=(--only with --l0 0.005)
"$exe" "${common[@]}" --end 0.004 --out "$dir/straight" > /dev/null 2>&1
"$exe" "${common[@]}" --end 0.0025 --checkpoint-every 0.002 --out "$dir/split" > /dev/null 2>&1
checkpoint=$(ls "$dir"/split/with_fracture/checkpoint_*.bin | tail -n 1)
"$exe" "${common[@]}" --end 0.004 --restart "$checkpoint" --out "$dir/split" > "$dir/continued.log" 2>&1
grep -q "continuing from" "$dir/continued.log" || { echo "FAIL: the run did not continue"; exit 1; }
count=0
for f in "$dir"/straight/with_fracture/*.vtu "$dir"/straight/with_fracture/*.pvd "$dir"/straight/with_fracture/*.csv; do
  cmp "$f" "$dir/split/with_fracture/$(basename "$f")" || { echo "FAIL: $(basename "$f") differs"; exit 1; }
  count=$((count + 1))
done
failures=$(($(wc -l < "$dir/straight/with_fracture/failures.csv") - 1))
[ "$failures" -gt 0 ] || { echo "FAIL: no failure before the checkpoint"; exit 1; }
echo "continued from $(basename "$checkpoint"): $count files the same, $failures failures"
echo "PASS"

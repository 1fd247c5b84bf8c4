#!/usr/bin/env bash
# Restart test of the dam-break example (ctest example.dam_break.restart). A run continued from a
# checkpoint must write the same files as one run straight through: the VTU snapshots and the
# PVD index byte for byte, the CSV except its wall-time column. Three ways to stop:
#   1. a run that ends after its checkpoint (the rows it wrote after it are dropped on restart);
#   2. SIGTERM: the run writes a checkpoint, says how to continue and exits with 143;
#   3. kill -9 at an arbitrary moment, possibly while a checkpoint is being written: the newest
#      complete checkpoint_*.bin (files are renamed into place only when complete) continues.
# Usage: restart_test.sh <dam_break executable> <scratch folder>
set -euo pipefail
exe=$1
dir=$2
rm -rf "$dir"
mkdir -p "$dir"
common=(--l0 0.02 --every 0.005)

same_output() {  # folder a, folder b
  local a=$1 b=$2 f
  for f in "$a"/dam_break_*.vtu "$a"/dam_break.pvd; do
    cmp "$f" "$b/$(basename "$f")" || { echo "FAIL: $(basename "$f") differs"; exit 1; }
  done
  [ "$(ls "$a"/dam_break_*.vtu | wc -l)" = "$(ls "$b"/dam_break_*.vtu | wc -l)" ] || { echo "FAIL: snapshot counts differ"; exit 1; }
  cmp <(cut -d, -f1-6 "$a/dam_break.csv") <(cut -d, -f1-6 "$b/dam_break.csv") || { echo "FAIL: CSV differs"; exit 1; }
}

end=0.4  # s: 2000 steps of 2e-4 s
"$exe" "${common[@]}" --end $end --out "$dir/straight" > /dev/null 2>&1

# Continues the run in folder $1 from its newest checkpoint to $end and compares it with the
# straight run, if that checkpoint lies before $end (a slow machine may not get that far).
continue_and_compare() {
  local folder=$1 what=$2 checkpoint step
  checkpoint=$(ls "$folder"/checkpoint_*.bin | tail -n 1)
  step=$(basename "$checkpoint" .bin)
  step=$((10#${step#checkpoint_}))
  if [ "$step" -le 2000 ]; then
    "$exe" "${common[@]}" --end $end --restart "$checkpoint" --out "$folder" > /dev/null 2>&1
    same_output "$dir/straight" "$folder"
    echo "$what: continued from step $step, same output"
  else
    "$exe" "${common[@]}" --end "$(awk -v s="$step" 'BEGIN { print (s + 10) * 2e-4 }')" --restart "$checkpoint" \
      --out "$folder" > /dev/null 2>&1
    echo "$what: continued from step $step (past the straight run's end)"
  fi
}

# 1. Stopped after its checkpoint at t = 0.05 s, at t = 0.06 s.
"$exe" "${common[@]}" --end 0.06 --checkpoint-every 0.05 --out "$dir/ended" > /dev/null 2>&1
continue_and_compare "$dir/ended" "ended after a checkpoint"

# 2. SIGTERM.
"$exe" "${common[@]}" --end 100 --out "$dir/term" > "$dir/term.log" 2>&1 &
pid=$!
sleep 0.5
kill -TERM "$pid"
set +e
wait "$pid"
code=$?
set -e
[ "$code" = 143 ] || { echo "FAIL: SIGTERM exit code $code, expected 143"; cat "$dir/term.log"; exit 1; }
grep -q "stopped by a signal; continue with --restart" "$dir/term.log" || { echo "FAIL: no restart hint"; exit 1; }
continue_and_compare "$dir/term" "SIGTERM (exit code 143)"

# 3. kill -9 while checkpoints are written every 10 steps.
"$exe" "${common[@]}" --end 100 --checkpoint-every 0.002 --out "$dir/killed" > /dev/null 2>&1 &
pid=$!
sleep 0.7
kill -KILL "$pid"
set +e
wait "$pid"
code=$?
set -e
[ "$code" = 137 ] || { echo "FAIL: the run ended (code $code) before it was killed"; exit 1; }
continue_and_compare "$dir/killed" "kill -9"
echo "PASS"

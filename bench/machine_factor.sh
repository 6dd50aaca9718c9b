#!/usr/bin/env bash
# How much slower (or faster) this machine runs the exact engine than the machine the cost model
# was calibrated on (src/sweep/cost_model.cpp): stored runs are run again from their seeds, which
# repeats their trajectories event for event (the counts are checked to be equal), and this
# machine's CPU time is divided by the stored one. Two runs at a time, as a sweep on two threads
# loads the machine. The factor scales the timings of runs made here before bench/fit_cost_model.py
# fits them with the calibration machine's (--runs FILE@FACTOR).
#
#   bash bench/machine_factor.sh [--granchain build/granchain] [--store data/paper/paper.db] [SEED ...]
#
# Default seeds: N = 100 at e = 0.3, 0.4, k = 1e6 on the power-law side (T = 1e3 after 100), stored
# 2026-11-28 by the engine the model's current-engine runs were timed with (77 and 75 s there).
# Prints one line per run (seed, stored CPU s, CPU s here, ratio) and the geometric mean; exits 1
# if a run's counts differ from the stored ones (the engine changed: the timings do not compare),
# 2 if a seed has no timed run in the store.
set -euo pipefail

granchain=build/granchain
store=data/paper/paper.db
seeds=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --granchain) granchain=$2; shift 2 ;;
    --store) store=$2; shift 2 ;;
    --*) echo "machine_factor.sh: unknown argument '$1'" >&2; exit 2 ;;
    *) seeds+=("$1"); shift ;;
  esac
done
[[ ${#seeds[@]} -gt 0 ]] || seeds=(2882359534326927462 3602164584461212451)
for s in "${seeds[@]}"; do
  [[ "$s" =~ ^[0-9]+$ ]] || { echo "machine_factor.sh: seed = '$s' is not a stored run's seed (an integer >= 0)" >&2; exit 2; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run_one() {  # seed -> "$work/$seed.stored" (CPU s, counts) and "$work/$seed.json" (the run again)
  local row
  row=$(sqlite3 -separator ' ' "$store" "SELECT N, e, k, T0, T, transient, cpu_seconds, particle_collisions, floor_hits
                                          FROM runs WHERE seed = $1 AND engine = 'exact' AND setup = 'driven_column'
                                          AND cpu_seconds IS NOT NULL LIMIT 1")
  [[ -n "$row" ]] || { echo "machine_factor.sh: seed $1 has no timed exact run in $store" >&2; exit 2; }
  read -r N e k T0 T tr stored <<< "$row"
  echo "$stored" > "$work/$1.stored"
  "$granchain" run --N "$N" --e "$e" --k "$k" --T0 "$T0" --T "$T" --transient "$tr" --seed "$1" --no-db -q \
    --json "$work/$1.json"
}

for ((i = 0; i < ${#seeds[@]}; i += 2)); do
  pids=()
  run_one "${seeds[i]}" &
  pids+=($!)
  if ((i + 1 < ${#seeds[@]})); then
    run_one "${seeds[i + 1]}" &
    pids+=($!)
  fi
  for p in "${pids[@]}"; do wait "$p"; done  # a failed run stops the script with its exit code
done

status=0
for s in "${seeds[@]}"; do
  read -r cpu pc fh <<< "$(/usr/bin/python3 -c "import json, sys; d = json.load(open(sys.argv[1]))
print(d['cost']['cpu_seconds'], d['observables']['particle_collisions'], d['observables']['floor_hits'])" "$work/$s.json")"
  read -r stored spc sfh < "$work/$s.stored"
  if [[ "$pc $fh" != "$spc $sfh" ]]; then
    echo "seed $s: counts $pc, $fh here against $spc, $sfh stored: not the same trajectory" >&2
    status=1
  fi
  echo "$s $stored $cpu" >> "$work/pairs"
done
awk '{ r = $3 / $2; l += log(r); n++; printf "%s stored %.1f s, here %.1f s, ratio %.3f\n", $1, $2, $3, r }
            END { if (n) printf "machine factor (geometric mean of %d): %.3f\n", n, exp(l / n) }' "$work/pairs"
exit $status

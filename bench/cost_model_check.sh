#!/usr/bin/env bash
# The cost model (src/sweep/cost_model.hpp) against the wall time of the runs in a results store:
# each stored run of a preset's sweeps is matched by its seed to the cost that `sweep --dry-run`
# predicts for it, and the ratio predicted / measured is summarised per N. Measured: the run's
# thread CPU time where the store has it (runs stored since it was recorded), else its wall time,
# which a loaded machine stretches.
#
#   bash bench/cost_model_check.sh STORE [--granchain build/granchain] [--preset paper] [--list FILE]
#                                        [--seeds odd|even] [--cpu-only]
# --seeds summarises only the runs with odd or even seeds (the model may be calibrated on the others).
# --cpu-only summarises only the runs with a stored CPU time (their wall times may be stretched).
# --list FILE writes one line per run: N e k T0 T transient predicted_s measured_s seed (the input
# of bench/fit_cost_model.py --runs).
set -euo pipefail

store=${1:?usage: cost_model_check.sh STORE [--granchain BIN] [--preset NAME] [--list FILE]}
shift
granchain=build/granchain
preset=paper
list=""
parity=""
cpu_only=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --granchain) granchain=$2; shift 2 ;;
    --preset) preset=$2; shift 2 ;;
    --list) list=$2; shift 2 ;;
    --seeds) parity=$2; shift 2 ;;
    --cpu-only) cpu_only=1; shift ;;
    *) echo "cost_model_check.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# seed -> predicted seconds, from the dry runs of the preset's sweeps.
bash "$(dirname "$0")/preset_points.sh" "$granchain" "$preset" | awk '{ print $4, $2 }' | sort -u > "$work/predicted"
# seed -> N e k T0 measured seconds, from the store.
"$granchain" export --db "$store" | awk -F, -v cpu_only="$cpu_only" '
  NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  $c["setup"] == "driven_column" && !(cpu_only && !("cpu_seconds" in c && $c["cpu_seconds"] != "")) {
                                   t = ("cpu_seconds" in c && $c["cpu_seconds"] != "") ? $c["cpu_seconds"] : $c["wall_seconds"]
                                   print $c["seed"], $c["N"], $c["e"], $c["k"], $c["T0"], $c["T"], $c["transient"], t }' |
  sort > "$work/measured"
join "$work/predicted" "$work/measured" | awk '{ print $3, $4, $5, $6, $7, $8, $2, $9, $1 }' > "$work/pairs"
[[ -n "$list" ]] && cp "$work/pairs" "$list"
awk -v parity="${parity}" 'parity == "" || (substr($9, length($9)) % 2) == (parity == "odd") {
       r = $7 / $8; n[$1]++; w[$1] += (r >= 0.5 && r <= 2); p[$1] += $7; m[$1] += $8
       lo[$1] = (n[$1] == 1 || r < lo[$1]) ? r : lo[$1]; hi[$1] = (n[$1] == 1 || r > hi[$1]) ? r : hi[$1] }
     END {
       printf "%6s %6s %12s %14s %14s %16s\n", "N", "runs", "within 2x", "predicted h", "measured h", "ratio range"
       for (N in n) { printf "%6d %6d %12d %14.3f %14.3f %7.2f .. %5.2f\n", N, n[N], w[N], p[N] / 3600, m[N] / 3600, lo[N], hi[N] | "sort -n"
                      tn += n[N]; tw += w[N]; tp += p[N]; tm += m[N] }
       close("sort -n")
       printf "all: %d runs, %d predicted within a factor of 2; %.3f CPU-hours predicted, %.3f measured\n", tn, tw, tp / 3600, tm / 3600
     }' "$work/pairs"

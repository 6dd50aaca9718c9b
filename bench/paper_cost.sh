#!/usr/bin/env bash
# Measured cost of a reproduction preset (`granchain reproduce --figure all --preset paper`),
# estimated from a sample of its points.
#
# Every distinct point of the preset's sweeps (`reproduce --print-sweeps`, expanded by
# `sweep --dry-run`) is listed and put in a stratum (N, k, and e below or above 1/2). In each
# stratum every STRIDE-th point (at least two), in a fixed pseudo-random order (by seed), is run
# twice with its own seed and engine: a transient of SETTLE time units, then a window of SHORT or
# of LONG. The difference of the two wall times over LONG - SHORT is the cost per unit time of the
# settled column (settling from the initial state is cheaper than the settled column in the
# condensed regime, so it is left out); times the point's full T + transient it is the point's
# cost. A stratum's cost is the mean over its sample times its number of points; strata are summed
# per N. The error is the stratified-sampling standard error (finite population corrected); the
# timing noise of the machine is in it only through the spread of the sample.
#
#   bash bench/paper_cost.sh [--granchain build/granchain] [--preset paper] [--stride 8]
#                            [--settle 40] [--short 10] [--long 40] [--list FILE]
#                            [--engine NAME] [--where AWK-CONDITION]
# --engine runs the sample with that engine instead of each point's own (the same points: the
# sample depends only on the preset and the stride); --where keeps only the points for which the
# awk condition on the fields N, e, k ($1, $2, $3) holds before strata are formed, e.g.
# --where '$3 <= 1e7 && $2 < 0.5'.
# --list FILE also writes one line per sampled point
# (stratum N e k T0 T transient wall_short_s wall_long_s cost_s).
set -euo pipefail

granchain=build/granchain
preset=paper
stride=8
settle=40
short=10
long=40
list=""
engine_override=""
where="1"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --granchain) granchain=$2; shift 2 ;;
    --preset) preset=$2; shift 2 ;;
    --stride) stride=$2; shift 2 ;;
    --settle) settle=$2; shift 2 ;;
    --short) short=$2; shift 2 ;;
    --long) long=$2; shift 2 ;;
    --list) list=$2; shift 2 ;;
    --engine) engine_override=$2; shift 2 ;;
    --where) where=$2; shift 2 ;;
    *) echo "paper_cost.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
[[ "$stride" =~ ^[1-9][0-9]*$ ]] || { echo "paper_cost.sh: --stride must be a positive integer" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Every distinct point: "N e k T0 T transient seed engine", sorted by N, then e, k, T0.
bash "$(dirname "$0")/preset_points.sh" "$granchain" "$preset" | awk '{
    for (i = 1; i <= NF; ++i) { split($i, kv, "="); v[kv[1]] = kv[2] }
    print v["N"], v["e"], v["k"], v["T0"], v["T"], v["transient"], v["seed"], v["engine"]
  }' | sort -u | sort -k1,1n -k2,2g -k3,3g -k4,4g | awk "$where" > "$work/points"
total=$(wc -l < "$work/points")
echo "# $total distinct points in preset '$preset'; sampling every ${stride}th per stratum (settle $settle, windows $short and $long)"

# The strata: N, k, and e below or above 1/2 (the power-law regime's condensed columns cost far
# more per unit time than the near-elastic ones). The sample: in each stratum, points 0, stride,
# 2 stride, ... and at least two, of its points ordered by seed (a fixed pseudo-random order, so no
# stride lines up with the grid's period in e or T0).
awk '{ print $1 "/" $3 "/" ($2 < 0.5 ? "lo" : "hi"), $0 }' "$work/points" | sort -k1,1 -k8,8 > "$work/strata"
awk -v s="$stride" '{ if ($1 != st) { st = $1; i = 0 } if (i % s == 0 || i == 1) print; ++i }' "$work/strata" > "$work/sample"
: > "$work/timed"
while read -r stratum N e k T0 T transient seed engine; do
  [[ -n "$engine_override" ]] && engine=$engine_override
  walls=()
  for window in "$short" "$long"; do
    walls+=("$("$granchain" run --N "$N" --e "$e" --k "$k" --T0 "$T0" --T "$window" --transient "$settle" \
                 --seed "$seed" --engine "$engine" --no-db | awk '/^  cost:/ { print $(NF-2) }')")
  done
  # Settled cost per unit time; if timing noise makes the difference vanish, the long run's mean.
  cost=$(awk -v a="${walls[0]}" -v b="${walls[1]}" -v s="$settle" -v w1="$short" -v w2="$long" -v T="$T" -v tr="$transient" \
           'BEGIN { r = (b - a) / (w2 - w1); if (!(r > 0)) r = b / (s + w2); printf "%.6g", r * (T + tr) }')
  echo "$stratum $N $e $k $T0 $T $transient ${walls[0]} ${walls[1]} $cost" | tee -a "$work/timed" >&2
done < "$work/sample"
[[ -n "$list" ]] && cp "$work/timed" "$list"

# Stratified estimate: per stratum, population size P, sample size n, mean cost m, variance s2;
# printed summed per N.
awk 'NR == FNR { P[$1]++; next }
     { n[$1]++; sum[$1] += $10; sq[$1] += $10 * $10 }
     END {
       tot = 0; var = 0
       for (st in n) {
         split(st, f, "/"); N = f[1]
         m = sum[st] / n[st]; s2 = n[st] > 1 ? (sq[st] - n[st] * m * m) / (n[st] - 1) : 0
         c = P[st] * m; v = P[st] * P[st] * (1 - n[st] / P[st]) * s2 / n[st]
         cN[N] += c; vN[N] += v; pN[N] += P[st]; nN[N] += n[st]; tot += c; var += v
       }
       printf "%6s %8s %8s %14s %14s\n", "N", "points", "sampled", "CPU-h", "± (1 sigma)"
       for (N in cN) printf "%6d %8d %8d %14.3f %14.3f\n", N, pN[N], nN[N], cN[N] / 3600, sqrt(vN[N]) / 3600 | "sort -n"
       close("sort -n")
       printf "total: %.2f ± %.2f CPU-hours of one core\n", tot / 3600, sqrt(var) / 3600
     }' "$work/strata" "$work/timed"

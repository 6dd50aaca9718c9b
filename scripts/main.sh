#!/usr/bin/env bash
# The main job: install what is missing, build, and run the demonstration — the driven column
# of the paper with N = 25 at k = 1e8 for three restitution coefficients, one in each regime
# (e = 0.5 power-law collapsing, 0.88 near the collapse threshold, 0.95 uncollapsing), with the
# exact event-driven engine. Results go to demo/granchain.db (SQLite) and demo/run_e*.json.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh

out=demo
mkdir -p "$out"
db="$out/granchain.db"
first_id=$(sqlite3 "$db" "SELECT coalesce(max(id), 0) + 1 FROM runs" 2>/dev/null || echo 1)
for e in 0.5 0.88 0.95; do
  echo "running N = 25, e = $e, k = 1e8, T = 500 (transient 50), exact engine ..."
  ./build/granchain run --N 25 --e "$e" --k 1e8 --T 500 --transient 50 --seed 1 \
      --db "$db" --json "$out/run_e$e.json" --quiet
done
echo
echo "n_coll (collisions per particle per unit time, one standard error from blocking):"
sqlite3 -header -column "$db" \
  "SELECT id AS run, N, e, printf('%.0e', k) AS k, printf('%.3f', n_coll) AS n_coll,
          printf('%.3f', n_coll_err) AS error, printf('%.3f', floor_rate) AS floor_rate,
          printf('%.1f', wall_seconds) AS wall_s
   FROM runs WHERE id >= $first_id ORDER BY id"
echo
echo "results: $db (tables runs, profiles) and $out/run_e{0.5,0.88,0.95}.json"
echo "one run in full:  ./build/granchain run --N 25 --e 0.88 --k 1e8 --T 500 --transient 50"

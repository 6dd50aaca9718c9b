#!/usr/bin/env bash
# bench/machine_factor.sh on a store of its own: a stored run run again from its seed repeats its
# trajectory (equal counts, exit 0, one ratio and the geometric mean printed); a stored count that
# the run does not repeat is reported as another trajectory (exit 1); a seed the store lacks is
# refused (exit 2), and so is a seed that is not an integer.
set -euo pipefail
binary=${1:?usage: machine_factor_test.sh GRANCHAIN}
repo=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "machine_factor_test: $*" >&2; exit 1; }

"$binary" run --N 6 --e 0.5 --k 1e6 --T 20 --transient 2 --seed 11 --db store.db -q
"$binary" run --N 8 --e 0.7 --k 1e6 --T 20 --transient 2 --seed 12 --db store.db -q
bash "$repo/bench/machine_factor.sh" --granchain "$binary" --store store.db 11 12 > out.txt ||
  fail "two stored runs, exit $?: $(cat out.txt)"
grep -q "^11 stored .* ratio [0-9.]*$" out.txt || fail "no line for seed 11: $(cat out.txt)"
grep -q "^12 stored .* ratio [0-9.]*$" out.txt || fail "no line for seed 12: $(cat out.txt)"
grep -q "^machine factor (geometric mean of 2): [0-9.]*$" out.txt || fail "no factor: $(cat out.txt)"

sqlite3 store.db "UPDATE runs SET particle_collisions = particle_collisions + 1 WHERE seed = 12"
status=0
bash "$repo/bench/machine_factor.sh" --granchain "$binary" --store store.db 12 > out.txt 2> err.txt || status=$?
[ "$status" -eq 1 ] || fail "a changed count gave exit $status"
grep -q "seed 12: counts .* not the same trajectory" err.txt || fail "changed count: $(cat err.txt)"

status=0
bash "$repo/bench/machine_factor.sh" --granchain "$binary" --store store.db 99 > out.txt 2> err.txt || status=$?
[ "$status" -eq 2 ] || fail "a seed not stored gave exit $status"
grep -q "seed 99 has no timed exact run" err.txt || fail "missing seed: $(cat err.txt)"

status=0
bash "$repo/bench/machine_factor.sh" --granchain "$binary" --store store.db "1; DROP TABLE runs" > out.txt 2> err.txt || status=$?
[ "$status" -eq 2 ] || fail "a seed that is not an integer gave exit $status"
grep -q "seed = .* is not a stored run.s seed" err.txt || fail "bad seed: $(cat err.txt)"
echo "machine_factor_test: ok"

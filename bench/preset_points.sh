#!/usr/bin/env bash
# Every point of a reproduction preset, as `granchain sweep --dry-run` lists them (order, estimated
# cost, replica, seed, key), one line per point of each sweep `reproduce --print-sweeps` prints.
# Shared by paper_cost.sh and cost_model_check.sh.
#
#   bash bench/preset_points.sh GRANCHAIN PRESET
set -euo pipefail
granchain=${1:?usage: preset_points.sh GRANCHAIN PRESET}
preset=${2:?usage: preset_points.sh GRANCHAIN PRESET}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$granchain" reproduce --figure all --preset "$preset" --print-sweeps --db "$work/none.db" |
  grep '^granchain sweep' | while read -r line; do
    # shellcheck disable=SC2086
    "$granchain" ${line#granchain } --dry-run --db "$work/none.db"
  done | grep -v '^#'

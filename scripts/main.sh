#!/usr/bin/env bash
# The main job: install what is missing, build, and reproduce the paper's Fig. 5 (cfreqlogN25,
# N = 25) with the quick preset: a sweep of 155 driven-column runs (e on the paper's grids,
# k = 1e4..1e8, T = 1000) with the exact engine on every core, their analysis (regimes, e_c1,
# e_c2, alpha, the partially condensed state) and the figure, with a report beside the paper's
# numbers. Runs go to reproduce/reproduce.db; a second invocation reuses them.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh

mkdir -p reproduce
./build/granchain reproduce --figure fig5 --preset quick --db reproduce/reproduce.db --out reproduce
echo
sed -n '/^| quantity/,/^$/p' reproduce/report.md

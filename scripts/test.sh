#!/usr/bin/env bash
# Install what is missing, build, and run the whole default test suite (label "long" excluded;
# run those with: ctest --test-dir build -L long).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -LE long -j "$(nproc)"

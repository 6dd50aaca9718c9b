#!/usr/bin/env bash
# Installs, from Debian's packages only, everything granchain needs to build, test and run.
# Idempotent: packages already present are not touched; apt-get runs only when one is missing.
set -euo pipefail

packages=(
  g++ cmake make pkg-config git ca-certificates
  libcli11-dev nlohmann-json3-dev libfmt-dev libsqlite3-dev sqlite3 libfftw3-dev libtomlplusplus-dev libeigen3-dev
  libgtest-dev libgmock-dev
  libopenmpi-dev openmpi-bin
  python3-numpy python3-scipy python3-matplotlib help2man
  pybind11-dev python3-dev python3-pytest
  python3-pandas python3-venv python3-pip python3-setuptools python3-wheel
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ "${#missing[@]}" -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

#!/usr/bin/env bash
# Configures and builds one flavour of aquatoria.
#   scripts/build.sh [release|asan|noomp]   (default release) -> build/, build-asan/, build-noomp/
set -euo pipefail
cd "$(dirname "$0")/.."
flavour="${1:-release}"
case "$flavour" in
  release) dir=build;       args=(-DCMAKE_BUILD_TYPE=Release) ;;
  asan)    dir=build-asan;  args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DAQ_SANITIZE=ON -DAQ_OPENMP=OFF) ;;
  noomp)   dir=build-noomp; args=(-DCMAKE_BUILD_TYPE=Release -DAQ_OPENMP=OFF) ;;
  *) echo "usage: scripts/build.sh [release|asan|noomp]" >&2; exit 2 ;;
esac
jobs="${AQ_JOBS:-$(nproc)}"
cmake -S . -B "$dir" -G Ninja "${args[@]}" >/dev/null
start=$(date +%s)
cmake --build "$dir" -j "$jobs"
echo "build ($flavour): $(( $(date +%s) - start )) s" >&2

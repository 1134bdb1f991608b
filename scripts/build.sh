#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Configures and builds one flavour of aquatoria: everything, or only the given CMake targets.
#   scripts/build.sh [release|asan|noomp] [TARGET...]   (default release, all targets)
#     -> build/, build-asan/, build-noomp/;  e.g. scripts/build.sh release aquatoria
set -euo pipefail
cd "$(dirname "$0")/.."
flavour="${1:-release}"
case "$flavour" in
  release) dir=build;       args=(-DCMAKE_BUILD_TYPE=Release) ;;
  # -O1 -g1 (line tables): what ASan recommends, and half the compile time of -O2 -g (CI budget)
  asan)    dir=build-asan;  args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
                                  -DAQ_SANITIZE=ON -DAQ_OPENMP=OFF) ;;
  noomp)   dir=build-noomp; args=(-DCMAKE_BUILD_TYPE=Release -DAQ_OPENMP=OFF) ;;
  *) echo "usage: scripts/build.sh [release|asan|noomp] [TARGET...]" >&2; exit 2 ;;
esac
shift $(( $# > 0 ? 1 : 0 ))
targets=()
for t in "$@"; do targets+=(--target "$t"); done
jobs="${AQ_JOBS:-$(nproc)}"
cmake -S . -B "$dir" -G Ninja "${args[@]}" >/dev/null
start=$(date +%s)
cmake --build "$dir" -j "$jobs" "${targets[@]}"
echo "build ($flavour): $(( $(date +%s) - start )) s" >&2

#!/usr/bin/env bash
# Builds and runs the whole test suite: Release (with OpenMP), then the sanitizer build
# (ASan+UBSan, OpenMP off, so the no-OpenMP build is tested too), then the slow label (which
# includes the ROMS client tests, label roms: ../shared/clients/roms builds ROMS once into
# $ROMS_CACHE, default ~/.cache/aq-roms, and runs it on our files; skipped when that folder is absent).
#   scripts/test.sh           everything (what CI runs)
#   scripts/test.sh --quick   Release only, without the slow label (local iteration)
set -euo pipefail
cd "$(dirname "$0")/.."
quick=0
[ "${1:-}" = "--quick" ] && quick=1
bash scripts/install_deps.sh
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}"

t0=$(date +%s)
bash scripts/build.sh release
(cd build && ctest --output-on-failure -j 2 -LE slow --timeout 900)
echo "test.sh: release suite done in $(( $(date +%s) - t0 )) s" >&2
[ "$quick" = 1 ] && exit 0

t1=$(date +%s)
bash scripts/build.sh asan
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0
export LSAN_OPTIONS="suppressions=$(pwd)/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
(cd build-asan && ctest --output-on-failure -j 2 -LE "slow|clients" --timeout 1800)
echo "test.sh: sanitizer suite done in $(( $(date +%s) - t1 )) s" >&2

t2=$(date +%s)
(cd build && ctest --output-on-failure -j 1 -L slow --timeout 1800)
echo "test.sh: slow suite done in $(( $(date +%s) - t2 )) s; total $(( $(date +%s) - t0 )) s" >&2

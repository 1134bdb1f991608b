#!/usr/bin/env bash
# Builds and runs the whole test suite: Release (with OpenMP), the configuration sweep (label
# sweep, release build), then the sanitizer build (ASan+UBSan, OpenMP off, so the no-OpenMP build
# is tested too), then the slow label (which includes the ADCIRC, ROMS, FESOM2 and SCHISM client
# tests, labels adcirc, roms, fesom2, schism: ../shared/clients/{adcirc,roms,fesom2,schism} build the
# models once into their caches, default ~/.cache/aq-<model>, and run them on our files; skipped
# when absent).
#   scripts/test.sh           everything (what CI runs)
#   scripts/test.sh --quick   Release only, without the slow and sweep labels (local iteration)
set -euo pipefail
cd "$(dirname "$0")/.."
quick=0
[ "${1:-}" = "--quick" ] && quick=1
bash scripts/install_deps.sh
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}"

t0=$(date +%s)
bash scripts/build.sh release
(cd build && ctest --output-on-failure -j 2 -LE "slow|sweep" --timeout 900)
echo "test.sh: release suite done in $(( $(date +%s) - t0 )) s" >&2
[ "$quick" = 1 ] && exit 0

# The configuration sweep (tests/sweep/sweep.py): 99 runs of the release binary over a
# deterministic sample of the configuration space, every one passing all checks.
ts=$(date +%s)
(cd build && ctest --output-on-failure -j 2 -L sweep --timeout 900)
echo "test.sh: sweep done in $(( $(date +%s) - ts )) s" >&2

t1=$(date +%s)
bash scripts/build.sh asan
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0
export LSAN_OPTIONS="suppressions=$(pwd)/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The two scale benchmarks (10 million triangles, the 1' lattice) check the same invariants in the
# Release suite; under ASan they took 64 and 32 s of the sanitizer suite's 9 minutes.
(cd build-asan && ctest --output-on-failure -j 2 -LE "slow|clients|sweep" -E "^(MeshPerf|MaskPerf)\." --timeout 1800)
echo "test.sh: sanitizer suite done in $(( $(date +%s) - t1 )) s" >&2

t2=$(date +%s)
(cd build && ctest --output-on-failure -j 2 -L slow --timeout 1800)
echo "test.sh: slow suite done in $(( $(date +%s) - t2 )) s; total $(( $(date +%s) - t0 )) s" >&2

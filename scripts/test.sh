#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds and runs the whole test suite: Release (with OpenMP), the configuration sweep (label
# sweep, release build), then the sanitizer build (ASan+UBSan, OpenMP off, so the no-OpenMP build
# is tested too; what it runs is said below), then the slow label (which includes the ADCIRC, ROMS, FESOM2 and SCHISM client
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

# ctest -j2 starts the longest tests first when it knows their durations (Testing/Temporary/
# CTestCostData.txt, written by each run); a fresh clone has none and would start them in the order
# of definition, leaving one core idle behind a long test at the end. tests/ctest_costs/ holds the
# durations of an earlier run (to refresh: the file a full run leaves in build/ or build-asan/, up
# to its "---" line); tests it does not name start after the others.
seed_costs() {
  mkdir -p "$1/Testing/Temporary"
  [ -f "$1/Testing/Temporary/CTestCostData.txt" ] || cp "$2" "$1/Testing/Temporary/CTestCostData.txt"
}

t0=$(date +%s)
bash scripts/build.sh release
seed_costs build tests/ctest_costs/release.txt
(cd build && ctest --output-on-failure -j 2 -LE "slow|sweep" --timeout 900)
echo "test.sh: release suite done in $(( $(date +%s) - t0 )) s" >&2
[ "$quick" = 1 ] && exit 0

# The configuration sweep (tests/sweep/sweep.py): 99 runs of the release binary over a
# deterministic sample of the configuration space, every one passing all checks.
ts=$(date +%s)
(cd build && ctest --output-on-failure -j 2 -L sweep --timeout 900)
echo "test.sh: sweep done in $(( $(date +%s) - ts )) s" >&2

t1=$(date +%s)
# The sanitizer build (tests/CMakeLists.txt builds only what runs here) and what it runs, chosen
# for the CI budget (30 min on 2 cores; it took 23 of the 51 min when it ran every non-slow test):
#  - every unit test and the fuzz regressions: the stage code in-process, where memory and UB bugs
#    live; except the two scale benchmarks (MeshPerf, MaskPerf: 10 M triangles, the 1' lattice; 87 s
#    under ASan) and the one- vs two-thread determinism tests (OneAndTwoThreads: the sanitizer
#    build has no OpenMP, so they compare two identical serial runs);
#  - of the CLI tests (the sanitized aquatoria binary), the error and robustness paths (bad options,
#    keys and files, signals, full disk, streamed-input refusals: Cli, CheckCli, CliInterrupt,
#    Robust*, StreamCli) and one main path of each subcommand and writer family (asan_cli below).
# Release alone runs the other CLI tests and the integration label (the same pipelines again on
# ETOPO5/20/60, checking their numbers; 400 s under ASan).
bash scripts/build.sh asan
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0
export LSAN_OPTIONS="suppressions=$(pwd)/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
asan_cli="^(Cli|CheckCli|CliInterrupt|Robust[A-Za-z]*|StreamCli)\.|^DomainCli\.GlobalSeedRunIsUnchanged$"
asan_cli+="|^RegionalCli\.BlackSeaFromTomlBuildsTheSeedGrid$|^RefineCli\.NorthWesternShelfNestedInTheBlackSea$"
asan_cli+="|^BlocksCli\.ListsBlocksWritesFilesAndTheFirstRunsToItsContour$|^ModelFormatsCli\.DefaultRunHasNoLonelyTriangleAndNoPinch$"
asan_cli+="|^SourcesCli\.StreamedSourcesGiveTheSameFiles$|^MercatorCli\.RotatedEtopo5TrianglesAreWellShapedOnTheSphereAndSizesFollowTheTargets$"
asan_cli+="|^GlobalRunFileCli\.BlocksAndRegionalReuseItWhenTheInputsMatch$|^RegionalBvpCli\.BlackSeaOnTheSphereWritesTheRomsFile$"
asan_cli+="|^RegionalMethodsCli\.BlackSeaEd2WritesEveryFileAndChecks$|^HandoffChainCli\.BlocksRemovesItsEarlierBlocksAndAStaleBlockConfigIsRefused$"
asan_cli+="|^SizeCli\.TimeStepOfTheReportIsTheBruteForceMinimumOverTheUgridFile$"
seed_costs build-asan tests/ctest_costs/asan.txt
# The forest's unit tests (tests/unit/forest: every suite named Forest...) start MPI: OpenMPI leaks
# from plugins it unloads at MPI_Finalize (no module left for a suppression to name), so they run
# in the Release suite and under mpirun only.
(cd build-asan && ctest --output-on-failure -j 2 -L "unit|fuzz" -E "^(MeshPerf|MaskPerf)\.|OneAndTwoThreads|Forest[A-Z][A-Za-z]*\." --timeout 1800)
(cd build-asan && ctest --output-on-failure -j 2 -L cli -R "$asan_cli" --timeout 1800)
echo "test.sh: sanitizer suite done in $(( $(date +%s) - t1 )) s" >&2

t2=$(date +%s)
(cd build && ctest --output-on-failure -j 2 -L slow --timeout 1800)
echo "test.sh: slow suite done in $(( $(date +%s) - t2 )) s; total $(( $(date +%s) - t0 )) s" >&2

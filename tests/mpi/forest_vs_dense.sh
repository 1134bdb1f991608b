#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The forest engine against the dense engine (ctest label mpi; tests/CMakeLists.txt): one
# `aquatoria mesh` run with quadtree.engine = "dense", one with "forest" under
# `mpirun --oversubscribe -np NP`, and every file they write must be the same bytes (the
# _report.json aside: it holds timings). Also asserts the forest run's report names NP ranks.
#   forest_vs_dense.sh AQUATORIA MPIEXEC NP OUTDIR [CONFIG]     (no CONFIG: the seed run)
set -euo pipefail
bin=$1 mpiexec=$2 np=$3 out=$4 cfg=${5:-}
rm -rf "$out"
mkdir -p "$out"
args=()
[ -n "$cfg" ] && args=(-c "$cfg")
"$bin" mesh "${args[@]}" --set quadtree.engine=dense -o "$out/dense" >"$out/dense.log" 2>&1 ||
  { cat "$out/dense.log"; echo "FAIL: the dense run failed"; exit 1; }
"$mpiexec" --oversubscribe -np "$np" "$bin" mesh "${args[@]}" --set quadtree.engine=forest -o "$out/forest" \
  >"$out/forest.log" 2>&1 || { cat "$out/forest.log"; echo "FAIL: the forest run on $np rank(s) failed"; exit 1; }
fail=0
dense_files=$(cd "$out/dense" && ls | grep -v '_report\.json$' || true)
forest_files=$(cd "$out/forest" && ls | grep -v '_report\.json$' || true)
if [ -z "$dense_files" ]; then echo "FAIL: the dense run wrote no file"; exit 1; fi
if [ "$dense_files" != "$forest_files" ]; then
  echo "FAIL: different file sets:"; diff <(echo "$dense_files") <(echo "$forest_files") || true; fail=1
fi
n=0
for f in $dense_files; do
  if ! cmp "$out/dense/$f" "$out/forest/$f"; then fail=1; else n=$((n + 1)); fi
done
ranks=$(python3 -c 'import json,sys,glob; print(json.load(open(glob.glob(sys.argv[1] + "/*_report.json")[0]))["forest"]["ranks"])' "$out/forest")
if [ "$ranks" != "$np" ]; then echo "FAIL: the forest report says $ranks ranks, not $np"; fail=1; fi
[ $fail = 0 ] && echo "OK: $n files identical (forest on $np rank(s) vs dense)"
exit $fail

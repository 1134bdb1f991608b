#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The forest engine against the dense engine (ctest label mpi; tests/CMakeLists.txt): one
# `aquatoria mesh` run with quadtree.engine = "dense", one with "forest" under
# `mpirun --oversubscribe -np NP`, and every file they write must be the same bytes (the
# _report.json aside: it holds timings). Also asserts the forest run's report names NP ranks, that
# the report's floodplain, dropped-sea, passage, time-step and warning sections are the dense
# run's, that the log's warnings and passage table are the same lines, and the memory estimate
# per rank (the mesh's triangle count foreseen exactly, rank 0 near its peak).
#   forest_vs_dense.sh AQUATORIA MPIEXEC NP OUTDIR [CONFIG|-] [ARGS...]   (no CONFIG or -: the seed run;
#   ARGS: more options for both runs, e.g. --set mask.min_depth_m=-5)
set -euo pipefail
bin=$1 mpiexec=$2 np=$3 out=$4 cfg=${5:-}
shift $(($# < 5 ? $# : 5))
rm -rf "$out"
mkdir -p "$out"
args=()
[ -n "$cfg" ] && [ "$cfg" != "-" ] && args=(-c "$cfg")
args+=("$@")
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
# The memory estimate once the leaves are known: one per rank, the triangles the mesh made (an
# exact count from the leaves' templates), and rank 0's estimate within its tolerance of its peak.
python3 - "$out/forest" "$np" <<'PY' || fail=1
import glob, json, sys
r = json.load(open(glob.glob(sys.argv[1] + "/*_report.json")[0]))
per, np = r["forest"]["memory"]["per_rank"], int(sys.argv[2])
tri, est, peak = sum(k["triangles"] for k in per), per[0]["estimate_bytes"], r["memory"]["peak_rss_bytes"]
ok = len(per) == np and tri == r["mesh_counts"]["triangles"] and 0.7 * peak <= est <= 1.5 * peak
print(f"memory: {len(per)} ranks, {tri} triangles foreseen of {r['mesh_counts']['triangles']}, rank 0 estimate "
      f"{est / 1e6:.0f} MB, peak {peak / 1e6:.0f} MB" + ("" if ok else ": FAIL"))
sys.exit(0 if ok else 1)
PY
# The report's sections that say what the mask dropped, flooded and kept (timings aside).
python3 - "$out/dense" "$out/forest" <<'PY' || fail=1
import glob, json, sys
def load(d):
    return json.load(open(glob.glob(d + "/*_report.json")[0]))
def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items() if "timing" not in k and k != "peak_rss_bytes"}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x
d, f = load(sys.argv[1]), load(sys.argv[2])
bad = 0
for path in ["mask.floodplain", "mask.dropped", "mask.passages", "mask.fill", "mask.classes", "floodplain",
             "time_step", "warnings", "boundaries"]:
    a, b = d, f
    for k in path.split("."):
        a = a.get(k) if isinstance(a, dict) else None
        b = b.get(k) if isinstance(b, dict) else None
    if strip(a) != strip(b):
        print(f"FAIL: report section {path} differs:\n  dense  {json.dumps(strip(a))[:400]}\n  forest {json.dumps(strip(b))[:400]}")
        bad = 1
sys.exit(bad)
PY
# The warnings and the passage table in the log (the quadtree's level lines aside).
lines() { grep -E '^warning|critical passages|^  ' "$1" | grep -v 'level [0-9]' || true; }
if ! diff <(lines "$out/dense.log") <(lines "$out/forest.log"); then
  echo "FAIL: the forest's warnings or passage table differ from the dense run's"; fail=1
fi
[ $fail = 0 ] && echo "OK: $n files identical (forest on $np rank(s) vs dense), the same report sections and warnings"
exit $fail

#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The forest's dropped seas beyond the lattice it gathers on rank 0 (forest/pipeline.hpp
# kDroppedSeasMaxPixels, lowered here by the test knob AQ_FOREST_DROPPED_MAX_PIXELS): the dropped
# components are counted over the ranks — the dense engine's count and pixels — said in one warning
# and in the report, and the files are still the dense engine's bytes.
#   forest_dropped_count.sh AQUATORIA MPIEXEC NP OUTDIR
set -euo pipefail
bin=$1 mpiexec=$2 np=$3 out=$4
rm -rf "$out"
mkdir -p "$out"
"$bin" mesh --set quadtree.engine=dense -o "$out/dense" >"$out/dense.log" 2>&1 ||
  { cat "$out/dense.log"; echo "FAIL: the dense run failed"; exit 1; }
AQ_FOREST_DROPPED_MAX_PIXELS=1 "$mpiexec" --oversubscribe -np "$np" "$bin" mesh --set quadtree.engine=forest \
  -o "$out/forest" >"$out/forest.log" 2>&1 || { cat "$out/forest.log"; echo "FAIL: the forest run failed"; exit 1; }
fail=0
for f in $(cd "$out/dense" && ls | grep -v '_report\.json$'); do cmp "$out/dense/$f" "$out/forest/$f" || fail=1; done
python3 - "$out" <<'PY' || fail=1
import glob, json, sys
out = sys.argv[1]
d = json.load(open(glob.glob(out + "/dense/*_report.json")[0]))["mask"]["dropped"]
f = json.load(open(glob.glob(out + "/forest/*_report.json")[0]))["mask"]["dropped"]
ok = f["components"] == d["components"] and f["pixels"] == d["pixels"] and f["named"] is False
ok = ok and d["components"] > 1
print(("OK" if ok else "FAIL") + f": dense {d['components']} components / {d['pixels']} pixels, forest {f}")
sys.exit(0 if ok else 1)
PY
n=$(grep -c '^warning: dropped: .* wet component(s) left out by the fill .*quadtree.engine = "dense" names them' "$out/forest.log" || true)
if [ "$n" != 1 ]; then echo "FAIL: the count's warning printed $n times, not once"; fail=1; fi
[ $fail = 0 ] && echo "OK: dropped components counted over $np rank(s), files identical"
exit $fail

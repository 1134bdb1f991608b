#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A channel only the fine source resolves (ctest label mpi; issue 29's synthetic stack): a coarse
# raster (0.1° cells) where a ridge of land 0.9° wide closes a basin off from the open sea, and a
# fine tile above it (input.paths, first; 0.002° cells over the ridge) where a channel 0.01° wide
# (5 fine cells, about 5 lattice pixels of 0.25°/128) cuts the ridge. Both are ESRI ASCII grids
# written here. The forest on NP ranks must write the dense engine's bytes (forest_vs_dense.sh),
# and the files must show the channel open: fort.14 nodes and triangles in the basin behind it, and
# in the channel; the same run on the coarse raster alone must leave the basin out (so the basin
# is reached through the fine source only). Two patches (level-0 squares) on the ridge are all land
# by the coarse raster's bounds: the forest must not decide them from it where the tile has data.
#   fine_channel.sh AQUATORIA MPIEXEC NP OUTDIR
set -euo pipefail
bin=$1 mpiexec=$2 np=$3 out=$4
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"
mkdir -p "$out"
# The two grids: z = -100 m in the basin (0.1 < lon < 0.55, 0.3 < lat < 1.7), -500 m in the sea
# (lon > 1.45), +50 m elsewhere; the tile adds the channel (|lat - 1| < 0.005, 0.5 < lon < 1.5, -30 m).
/usr/bin/python3 - "$out" <<'PY'
import sys
out = sys.argv[1]
def z(lon, lat, channel):
    if channel and abs(lat - 1.0) < 0.005 and 0.5 < lon < 1.5:
        return -30.0
    if 0.1 < lon < 0.55 and 0.3 < lat < 1.7:
        return -100.0
    if lon > 1.45:
        return -500.0
    return 50.0
def grid(path, x0, y0, cell, nx, ny, channel):
    with open(path, "w") as f:
        f.write(f"ncols {nx}\nnrows {ny}\nxllcorner {x0}\nyllcorner {y0}\ncellsize {cell}\nNODATA_value -99999\n")
        for r in range(ny):  # north row first
            lat = y0 + (ny - r - 0.5) * cell
            f.write(" ".join(f"{z(x0 + (c + 0.5) * cell, lat, channel):g}" for c in range(nx)) + "\n")
grid(out + "/coarse.asc", -1.0, -1.0, 0.1, 40, 40, False)
grid(out + "/tile.asc", 0.4, 0.8, 0.002, 600, 200, True)
PY
toml() {  # toml NAME PATHS
  cat >"$out/$1.toml" <<TOML
[input]
paths = [$2]
[domain]
box = [0.0, 2.0, 0.0, 2.0]
[mask]
seeds = [[1.6, 1.0]]
cursor = 2
[quadtree]
step_deg = 0.25
levels = 7
coast_band = 1
[output]
name = "$1"
formats = ["fort14", "ugrid"]
TOML
}
toml stack "\"$out/tile.asc\", \"$out/coarse.asc\""
toml coarse "\"$out/coarse.asc\""
"$here/forest_vs_dense.sh" "$bin" "$mpiexec" "$np" "$out/run" "$out/stack.toml"
"$mpiexec" --oversubscribe -np "$np" "$bin" mesh -c "$out/coarse.toml" --set quadtree.engine=forest -o "$out/coarse" \
  >"$out/coarse.log" 2>&1 || { cat "$out/coarse.log"; echo "FAIL: the coarse-only run failed"; exit 1; }
# Nodes and triangles of a fort.14 inside a lon/lat box: "nodes triangles" (all 3 corners inside).
count() {  # count FILE LON0 LON1 LAT0 LAT1
  /usr/bin/python3 - "$@" <<'PY'
import sys
path, x0, x1, y0, y1 = sys.argv[1], *map(float, sys.argv[2:])
with open(path) as f:
    f.readline()
    ne, nn = map(int, f.readline().split()[:2])
    inside = set()
    for _ in range(nn):
        k, x, y, _d = f.readline().split()[:4]
        if x0 < float(x) < x1 and y0 < float(y) < y1:
            inside.add(int(k))
    tri = 0
    for _ in range(ne):
        v = f.readline().split()
        tri += all(int(n) in inside for n in v[2:5])
print(len(inside), tri)
PY
}
fail=0
read -r bn bt < <(count "$out/run/forest/stack.14" 0.15 0.5 0.4 1.6)      # the basin behind the ridge
read -r cn ct < <(count "$out/run/forest/stack.14" 0.7 1.3 0.99 1.01)     # inside the channel, mid-ridge
read -r xn xt < <(count "$out/coarse/coarse.14" 0.15 0.5 0.4 1.6)
echo "basin: $bn nodes, $bt triangles; channel: $cn nodes, $ct triangles; basin without the tile: $xn nodes"
if [ "$bn" -lt 50 ] || [ "$bt" -lt 50 ]; then echo "FAIL: the basin behind the channel is not in the mesh"; fail=1; fi
if [ "$cn" -lt 20 ] || [ "$ct" -lt 20 ]; then echo "FAIL: no mesh in the fine source's channel"; fail=1; fi
if [ "$xn" != 0 ]; then echo "FAIL: the coarse raster alone reaches the basin: the test proves nothing"; fail=1; fi
# The fill: one wet component, all of it filled, with the tile; two without it, the basin (about
# 0.45° x 1.4°, 165 000 pixels) left out; the tile's filled pixels hold the coarse run's and the basin.
/usr/bin/python3 - "$out/run/forest/stack_report.json" "$out/coarse/coarse_report.json" <<'PY' || fail=1
import json, sys
s, c = (json.load(open(p))["mask"]["fill"] for p in sys.argv[1:])
print(f"fill: with the tile {s['filled_pixels']} filled of {s['wet_pixels']} wet in {s['wet_components']} "
      f"component(s); coarse alone {c['filled_pixels']} filled, {c['wet_left_out']} wet left out in {c['wet_components']}")
ok = (s["wet_components"] == 1 and s["wet_left_out"] == 0 and c["wet_components"] == 2 and c["wet_left_out"] > 150000
      and s["filled_pixels"] - c["filled_pixels"] >= 0.95 * c["wet_left_out"])
if not ok:
    print("FAIL: the fill does not reach the basin through the channel (or reaches it without the tile)")
sys.exit(0 if ok else 1)
PY
grep -q "tile.asc supplied" "$out/run/forest.log" || { echo "FAIL: the tile supplied no node"; fail=1; }
[ $fail = 0 ] && echo "OK: the channel only the fine tile resolves is open on $np rank(s), as in the dense engine"
exit $fail

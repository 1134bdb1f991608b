#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The forest engine on a 1/9" tile stack (ctest label mpi): data_tools/make_coast_tiles.py makes a
# stack of 0.05° VRT tiles resampled from ETOPO5 over Cape Hatteras (1° × 1°, tiles only where the
# coast runs, none east of -75.5°: the lattice's window reaches past the stack's edge), above ETOPO5
# (input.paths); a 0.5° box meshed at 14" pixels with a coast size term must give the dense
# engine's files on NP ranks, and so must the same box with a floodplain up to 3 m. Both engines
# read the stack in tiles (AQ_RASTER_TILES_ABOVE=1): a VRT that resamples on read can differ in the
# last float bit between one whole read and tile reads.
#   coast_tiles.sh AQUATORIA MPIEXEC NP OUTDIR
set -euo pipefail
bin=$1 mpiexec=$2 np=$3 out=$4
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"
mkdir -p "$out"
/usr/bin/python3 "$here/../../data_tools/make_coast_tiles.py" "$out/stack" -76.5 -75.5 35 36 >"$out/tiles.log" 2>&1
n=$(grep -o "[0-9]* tiles of" "$out/tiles.log" | cut -d" " -f1 || true)
if [ -z "$n" ] || [ "$n" -lt 20 ]; then echo "FAIL: the stack has '$n' tiles"; cat "$out/tiles.log"; exit 1; fi
cat >"$out/coast.toml" <<TOML
[input]
paths = ["$out/stack/tiles.vrt", "/usr/share/ferret-vis/data/etopo5.cdf"]
[domain]
box = [-76.0, -75.5, 35.25, 35.75]
[mask]
seeds = [[-75.6, 35.3]]
[quadtree]
step_deg = 0.25
levels = 6
coast_band = 1
[size.coast]
h0_km = 0.5
alpha = 0.2
[output]
name = "coast"
formats = ["ugrid", "fort14"]
TOML
export AQ_RASTER_TILES_ABOVE=1
"$here/forest_vs_dense.sh" "$bin" "$mpiexec" "$np" "$out/run" "$out/coast.toml"
grep -q "tiles.vrt supplied" "$out/run/forest.log" || { echo "FAIL: the tile stack supplied no node"; exit 1; }
# A floodplain on the stack (land up to 3 m): each patch classified at the threshold and the datum.
"$here/forest_vs_dense.sh" "$bin" "$mpiexec" "$np" "$out/run_floodplain" "$out/coast.toml" --set mask.min_depth_m=-3
grep -q "floodplain: done [1-9]" "$out/run_floodplain/forest.log" || { echo "FAIL: no floodplain node on the stack"; exit 1; }

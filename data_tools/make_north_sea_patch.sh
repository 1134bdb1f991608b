#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Makes the fine source of README "Several bathymetry sources": ETOPO5 resampled (cubic) to a 1'
# grid over the North Sea (4°W..10°E, 50..62°N; 840 × 720 Float32 GeoTIFF) with its sea floor
# raised by a visible 40 m (a GDAL band offset: Dogger Bank and the shallow southern bight fall
# dry), so that a run with input.paths = [patch, ETOPO5] shows where the patch supplied the depths.
# ETOPO5 runs 0..360°E: a copy shifted by -360° is mosaicked beside it first, so the patch across
# Greenwich has no gap. Cached outside the repository, never committed; prints the path.
#   data_tools/make_north_sea_patch.sh            Environment: AQ_CACHE (default ~/.cache/aquatoria)
set -euo pipefail
src="${AQ_ETOPO5:-/usr/share/ferret-vis/data/etopo5.cdf}"
cache="${AQ_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/aquatoria}"
mkdir -p "$cache"
out="$cache/north_sea_1min_plus40m.tif"
if [ ! -s "$out" ]; then
  tmp="$(mktemp -d "$cache/.tmp.XXXXXX")"
  trap 'rm -rf "$tmp"' EXIT
  # ETOPO5's first column is at 0°E (pixel edge -1/24°); the shifted copy covers -360..0.
  gdal_translate -q -of VRT -a_ullr -360.041667052558463 90.041666666666671 -0.041667052558463 -90.041666666666671 \
    "$src" "$tmp/shifted.vrt"
  gdalbuildvrt -q "$tmp/both.vrt" "$tmp/shifted.vrt" "$src"
  gdalwarp -q -te -4 50 10 62 -tr 0.0166666666666667 0.0166666666666667 -r cubic -ot Float32 \
    "$tmp/both.vrt" "$tmp/warped.tif"
  gdal_translate -q -a_offset 40 -a_scale 1 -a_nodata -99999 -co COMPRESS=DEFLATE "$tmp/warped.tif" "$tmp/patch.tif"
  mv "$tmp/patch.tif" "$out"
fi
echo "$out"

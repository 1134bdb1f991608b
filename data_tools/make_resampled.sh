#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Makes a finer global raster from the installed ETOPO5 with aquatoria's own sampling
# (aq_resample; longitude wraps, so there is no seam gap as with gdalwarp on a 0..360 source),
# for benchmarks of big lattices. Cached outside the repository, never committed.
#   data_tools/make_resampled.sh ARCSEC     e.g. 60 -> 1' raster (21600×10800 int16, 466 MB)
#                                                15 -> 15" raster (86400×43200 int16, 7.5 GB)
# Prints the raster's path. Environment: AQ_CACHE (default ~/.cache/aquatoria), AQ_BUILD (build).
set -euo pipefail
cd "$(dirname "$0")/.."
arcsec="${1:?usage: make_resampled.sh ARCSEC}"
src="${AQ_ETOPO5:-/usr/share/ferret-vis/data/etopo5.cdf}"
cache="${AQ_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/aquatoria}"
build="${AQ_BUILD:-build}"
mkdir -p "$cache"
out="$cache/etopo5_${arcsec}s.tif"
if [ ! -s "$out" ]; then
  [ -x "$build/aq_resample" ] || cmake --build "$build" --target aq_resample >&2
  tmp="$cache/.tmp.$$.etopo5_${arcsec}s.tif"
  "$build/aq_resample" "$src" "$tmp" "$arcsec" bilinear int16
  mv "$tmp" "$out"
fi
echo "$out"

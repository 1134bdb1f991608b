#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Fuzzes one parser with libFuzzer (Debian's clang, ASan+UBSan) for SECONDS seconds.
#   scripts/fuzz.sh TARGET SECONDS     e.g. scripts/fuzz.sh config_global 600
#   scripts/fuzz.sh list               the targets (tests/fuzz/targets.hpp says what each reads)
# Builds fuzz_TARGET in build-fuzz/ (its own tree; not part of scripts/test.sh), makes a seed
# corpus from configs/ and small netCDF files, and keeps the growing corpus in
# build-fuzz/corpus/TARGET. Findings land in build-fuzz/findings/TARGET/ (crash-*, timeout-*,
# oom-*); after fixing one, copy the input to tests/fuzz_regressions/TARGET/ so the normal test
# suite replays it. It prints libFuzzer's last status line (executions, cov, ft, findings).
set -euo pipefail
cd "$(dirname "$0")/.."
targets="config_global config_regional izogrid set roms_grid nesting xygrid raster"
if [ "${1:-}" = list ]; then echo "$targets"; exit 0; fi
if [ $# -ne 2 ] || ! [[ " $targets " == *" $1 "* ]] || ! [[ "$2" =~ ^[0-9]+$ ]]; then
  echo "usage: scripts/fuzz.sh TARGET SECONDS   (TARGET: $targets)" >&2
  exit 2
fi
target=$1 seconds=$2
command -v clang++ >/dev/null || { echo "fuzz.sh: needs clang and libclang-rt-14-dev (apt-get install clang libclang-rt-14-dev)" >&2; exit 2; }

py=/usr/bin/python3  # Debian's, with python3-numpy and python3-netcdf4 (not a pyenv/venv one)
[ -x "$py" ] || py=python3
dir=build-fuzz
cmake -S . -B "$dir" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DAQ_FUZZ=ON -DAQ_TESTS=OFF -DAQ_OPENMP=OFF >/dev/null
cmake --build "$dir" --target "fuzz_$target" -j "${AQ_JOBS:-2}" >&2

seeds="$dir/seeds/$target" corpus="$dir/corpus/$target" findings="$dir/findings/$target"
rm -rf "$seeds"; mkdir -p "$seeds" "$corpus" "$findings"
case "$target" in
  config_global|config_regional) cp configs/*.toml "$seeds/" ;;
  izogrid) cp configs/*.izogrid "$seeds/" ;;
  set)  # a first byte choosing global (even) or regional (odd), then one override a line
    "$py" - "$seeds" <<'PY'
import re, sys, os
out = sys.argv[1]
sec, lines = None, []
for raw in open("configs/example.toml"):
    m = re.match(r"\s*\[(\w+)\]", raw)
    if m: sec = m.group(1); continue
    m = re.match(r"\s*(\w+)\s*=\s*(.*?)\s*(#.*)?$", raw)
    if m and sec: lines.append(f"{sec}.{m.group(1)}={m.group(2)}")
for k in range(0, len(lines), 6):
    open(os.path.join(out, f"global_{k:03d}"), "wb").write(b"\0" + "\n".join(lines[k:k + 6]).encode())
open(os.path.join(out, "regional_0"), "wb").write(b"\1regional.ny=20\nregional.proj=\"LC\"\nroms.hmin_m=5")
open(os.path.join(out, "regional_1"), "wb").write(b"\1regional.spline_type=5\nregional.param=\"arc\"\nnesting.refine_factor=3")
PY
    ;;
  roms_grid|nesting|xygrid)  # tiny netCDF-3 files of the layout each reader expects
    "$py" - "$seeds" "$target" <<'PY'
import sys, numpy as np, netCDF4
out, target = sys.argv[1], sys.argv[2]
def grd(path, xr, er, fmt):
    d = netCDF4.Dataset(path, "w", format=fmt)
    for n, l in [("xi_rho", xr), ("eta_rho", er), ("xi_u", xr - 1), ("eta_u", er), ("xi_v", xr), ("eta_v", er - 1),
                 ("xi_psi", xr - 1), ("eta_psi", er - 1)]:
        d.createDimension(n, l)
    for pt, dims in [("rho", ("eta_rho", "xi_rho")), ("u", ("eta_u", "xi_u")), ("v", ("eta_v", "xi_v")), ("psi", ("eta_psi", "xi_psi"))]:
        shape = [len(d.dimensions[x]) for x in dims]
        names = ["lon_", "lat_"] + (["mask_"] if pt != "psi" else [])
        for n in names:
            d.createVariable(n + pt, "f8", dims)[:] = np.arange(np.prod(shape)).reshape(shape) * 0.1
    for n in ["h", "f", "pm", "pn", "dndx", "dmde", "angle"]:
        d.createVariable(n, "f8", ("eta_rho", "xi_rho"))[:] = 1.0
    d.proj = "ME"; d.rlat = 43.0; d.rlon = 34.0; d.rota = 0.0; d.uscale = 1.0; d.izogrid_nx = 3; d.izogrid_ny = 2
    d.close()
def nesting(path, n, fmt):
    d = netCDF4.Dataset(path, "w", format=fmt)
    d.createDimension("point", n); d.createDimension("three", 3)
    for name, t, two in [("point_type", "i1", 0), ("boundary", "i1", 0), ("xi_index", "i4", 0), ("eta_index", "i4", 0),
                         ("lon", "f8", 0), ("lat", "f8", 0), ("x", "f8", 0), ("y", "f8", 0), ("element", "i8", 0),
                         ("element_nodes", "i8", 1), ("weights", "f8", 1), ("element_level", "i1", 0),
                         ("global_element_size", "f8", 0), ("regional_cell_size", "f8", 0), ("refinement_ratio", "f8", 0)]:
        d.createVariable(name, t, ("point", "three") if two else ("point",))[:] = 1
    d.title = "t"; d.history = "h"; d.rlat = 1.5; d.nx = np.int64(3); d.note = "x"
    d.close()
def xygrid(path, nx, ny, fmt):
    d = netCDF4.Dataset(path, "w", format=fmt)
    d.createDimension("eta", ny); d.createDimension("xi", nx)
    x = d.createVariable("x", "f8", ("eta", "xi")); x[:] = np.tile(np.arange(nx), (ny, 1)); x.units = "km"
    d.createVariable("y", "f8", ("eta", "xi"))[:] = np.tile(np.arange(ny), (nx, 1)).T
    d.dxi = 1.0; d.deta = 1.0; d.title = "t"; d.history = "h"; d.nx = np.int32(nx); d.extra = "e"
    d.close()
make = {"roms_grid": lambda p, f: grd(p, 4, 3, f), "nesting": lambda p, f: nesting(p, 4, f),
        "xygrid": lambda p, f: xygrid(p, 3, 2, f)}[target]
# The nesting file has 64-bit integers: only CDF-5 holds them among the classic formats.
for f in ["NETCDF3_64BIT_DATA"] if target == "nesting" else ["NETCDF3_CLASSIC", "NETCDF3_64BIT_OFFSET", "NETCDF3_64BIT_DATA"]:
    make(f"{out}/{target}_{f.lower()}.nc", f)
PY
    ;;
  raster)  # tiny rasters: netCDF-3 (classic, 64-bit offset), netCDF-4 with lat/lon coordinates, GeoTIFF
    "$py" - "$seeds" <<'PY'
import sys, numpy as np, netCDF4
out = sys.argv[1]
for fmt in ["NETCDF3_CLASSIC", "NETCDF3_64BIT_OFFSET", "NETCDF4"]:
    d = netCDF4.Dataset(f"{out}/raster_{fmt.lower()}.nc", "w", format=fmt)
    d.createDimension("lat", 6); d.createDimension("lon", 8)
    la = d.createVariable("lat", "f8", ("lat",)); la[:] = np.arange(6) - 2.5; la.units = "degrees_north"
    lo = d.createVariable("lon", "f8", ("lon",)); lo[:] = np.arange(8) + 0.5; lo.units = "degrees_east"
    z = d.createVariable("z", "i2", ("lat", "lon"), fill_value=-32768); z[:] = np.arange(48).reshape(6, 8) * 10 - 200
    z.scale_factor = 0.5
    d.close()
PY
    gdal_translate -q -of GTiff -ot Int16 "$seeds/raster_netcdf3_classic.nc" "$seeds/raster.tif" 2>/dev/null || true
    ;;
esac

# -rss_limit_mb/-malloc_limit_mb: the parsers must refuse absurd sizes, not try them; -timeout: a
# hang is a finding. -fork=1 with -ignore_*: keep fuzzing after a finding (each lands in findings/).
cd "$dir"
nice -n 10 "./tests/fuzz/fuzz_$target" -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 \
  -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -max_len=65536 \
  -artifact_prefix="findings/$target/" "corpus/$target" "seeds/$target" 2>"findings/$target.log" || true
# Summary: the last status line (#executions: cov: ft: corp: ... oom/timeout/crash: a/b/c time: s).
grep -E "^#[0-9]+: cov:" "findings/$target.log" | tail -n 1 || true
ls "findings/$target" | sed "s/^/finding: /" || true

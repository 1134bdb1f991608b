#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A 1/9-arc-second tile stack of a coast, made from the installed ETOPO5 without storing a pixel.

NOAA's coastal DEMs (CUDEM) come as thousands of 1/9" GeoTIFF tiles of 0.25 degree along the coast,
mosaicked by a GDAL VRT. This tool makes the same layout for tests and benchmarks: every tile is a
small VRT whose one source is ETOPO5 resampled bilinearly onto the tile's 1/9" grid (GDAL computes
the values when they are read), and a mosaic VRT places the tiles. Only tiles near the coast are
made (ETOPO5's bilinear surface crosses sea level inside the tile, and `--ring` tiles around those), so the
fine data covers a coastal strip and the coarse global raster below it in input.paths covers the
rest, as real tile sets do. Real tiles drop in the same way: list them in a VRT (gdalbuildvrt).

  data_tools/make_coast_tiles.py OUT_DIR LON_MIN LON_MAX LAT_MIN LAT_MAX [--tile-deg 0.05]
                                 [--arcsec-div 9] [--ring 0] [--etopo5 PATH]

writes OUT_DIR/tiles.vrt (the mosaic) and OUT_DIR/tiles/t_<row>_<col>.vrt, and prints the mosaic's
path and the number of tiles. Files are small XML (about 1 KB a tile); nothing else is stored. The
box's edges and the tile size must be whole multiples of the tile grid (1/9" cells: a tile of 0.05
degree is 1620 x 1620 cells). Needs python3-numpy and python3-netcdf4 (scripts/install_deps.sh).
"""
import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np
from netCDF4 import Dataset


def geotransform(path, variable):
    """ETOPO5's geotransform and size as GDAL reads it (the VRT sources use GDAL's pixel grid)."""
    info = json.loads(subprocess.check_output(["gdalinfo", "-json", f'NETCDF:"{path}":{variable}']))
    return info["geoTransform"], info["size"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out_dir")
    ap.add_argument("lon_min", type=float)
    ap.add_argument("lon_max", type=float)
    ap.add_argument("lat_min", type=float)
    ap.add_argument("lat_max", type=float)
    ap.add_argument("--tile-deg", type=float, default=0.05, help="tile side in degrees (default 0.05)")
    ap.add_argument("--arcsec-div", type=int, default=9, help="cells per arc-second = 1/this (default 9: 1/9\")")
    ap.add_argument("--ring", type=int, default=0, help="tiles kept around each coastal tile (default 0)")
    ap.add_argument("--etopo5", default="/usr/share/ferret-vis/data/etopo5.cdf")
    ap.add_argument("--variable", default="ROSE")
    a = ap.parse_args()

    cells_per_deg = 3600 * a.arcsec_div
    tile_cells = a.tile_deg * cells_per_deg
    if abs(tile_cells - round(tile_cells)) > 1e-6:
        sys.exit(f"--tile-deg {a.tile_deg}: not a whole number of 1/{a.arcsec_div}\" cells")
    tile_cells = int(round(tile_cells))
    nx = (a.lon_max - a.lon_min) / a.tile_deg
    ny = (a.lat_max - a.lat_min) / a.tile_deg
    if min(nx, ny) <= 0 or abs(nx - round(nx)) > 1e-6 or abs(ny - round(ny)) > 1e-6:
        sys.exit("the box must be a positive whole number of tiles on each side")
    nx, ny = int(round(nx)), int(round(ny))

    gt, (w, h) = geotransform(a.etopo5, a.variable)
    with Dataset(a.etopo5) as ds:
        z = np.asarray(ds.variables[a.variable][:], dtype=np.float64)
        lat = np.asarray(ds.variables[ds.variables[a.variable].dimensions[0]][:], dtype=np.float64)
    if lat[0] < lat[-1]:  # the tiles' source rectangles are in GDAL's north-up rows
        z = z[::-1, :]

    # Which tiles hold coast: ETOPO5's bilinear surface, sampled on a 17 x 17 grid over the tile
    # (edges included), has values on both sides of sea level.
    n = 17
    def bilinear(lon, lat):
        x = ((lon % 360.0) - gt[0]) / gt[1] - 0.5  # pixel centres at whole numbers
        y = (gt[3] - lat) / -gt[5] - 0.5
        x0 = np.floor(x).astype(np.int64)
        y0 = np.clip(np.floor(y).astype(np.int64), 0, h - 2)
        t, u = x - x0, np.clip(y - y0, 0.0, 1.0)
        xa, xb = x0 % w, (x0 + 1) % w
        return ((1 - u) * ((1 - t) * z[y0, xa] + t * z[y0, xb]) + u * ((1 - t) * z[y0 + 1, xa] + t * z[y0 + 1, xb]))

    coast = np.zeros((ny, nx), dtype=bool)
    frac = np.linspace(0.0, 1.0, n)
    for r in range(ny):
        lat0 = a.lat_min + r * a.tile_deg
        lats = lat0 + frac * a.tile_deg
        for c in range(nx):
            lon0 = a.lon_min + c * a.tile_deg
            lon, lat = np.meshgrid(lon0 + frac * a.tile_deg, lats)
            v = bilinear(lon, lat)
            coast[r, c] = v.min() <= 0.0 < v.max()
    keep = coast.copy()
    for _ in range(a.ring):
        grown = keep.copy()
        grown[1:, :] |= keep[:-1, :]
        grown[:-1, :] |= keep[1:, :]
        grown[:, 1:] |= keep[:, :-1]
        grown[:, :-1] |= keep[:, 1:]
        grown[1:, 1:] |= keep[:-1, :-1]
        grown[:-1, :-1] |= keep[1:, 1:]
        grown[1:, :-1] |= keep[:-1, 1:]
        grown[:-1, 1:] |= keep[1:, :-1]
        keep = grown

    os.makedirs(os.path.join(a.out_dir, "tiles"), exist_ok=True)
    source = f'NETCDF:"{os.path.abspath(a.etopo5)}":{a.variable}'
    res = 1.0 / cells_per_deg
    placed = []
    for r in range(ny):
        for c in range(nx):
            if not keep[r, c]:
                continue
            lon0 = a.lon_min + c * a.tile_deg
            lat1 = a.lat_min + (r + 1) * a.tile_deg
            # The tile's extent in ETOPO5's pixel grid (longitudes 0..360 there).
            x_off = ((lon0 % 360.0) - gt[0]) / gt[1]
            y_off = (gt[3] - lat1) / -gt[5]
            size_x = a.tile_deg / gt[1]
            size_y = a.tile_deg / -gt[5]
            name = f"t_{r:04d}_{c:04d}.vrt"
            with open(os.path.join(a.out_dir, "tiles", name), "w") as f:
                f.write(f'<VRTDataset rasterXSize="{tile_cells}" rasterYSize="{tile_cells}">\n'
                        f"  <SRS>EPSG:4326</SRS>\n"
                        f"  <GeoTransform>{lon0!r}, {res!r}, 0, {lat1!r}, 0, {-res!r}</GeoTransform>\n"
                        f'  <VRTRasterBand dataType="Float32" band="1">\n'
                        f'    <ComplexSource resampling="bilinear">\n'
                        f"      <SourceFilename relativeToVRT=\"0\">{source}</SourceFilename>\n"
                        f"      <SourceBand>1</SourceBand>\n"
                        f'      <SrcRect xOff="{x_off!r}" yOff="{y_off!r}" xSize="{size_x!r}" ySize="{size_y!r}"/>\n'
                        f'      <DstRect xOff="0" yOff="0" xSize="{tile_cells}" ySize="{tile_cells}"/>\n'
                        f"    </ComplexSource>\n"
                        f"  </VRTRasterBand>\n"
                        f"</VRTDataset>\n")
            placed.append((name, c * tile_cells, (ny - 1 - r) * tile_cells))

    width, height = nx * tile_cells, ny * tile_cells
    mosaic = os.path.join(a.out_dir, "tiles.vrt")
    with open(mosaic + ".tmp", "w") as f:
        f.write(f'<VRTDataset rasterXSize="{width}" rasterYSize="{height}">\n'
                f"  <SRS>EPSG:4326</SRS>\n"
                f"  <GeoTransform>{a.lon_min!r}, {res!r}, 0, {a.lat_max!r}, 0, {-res!r}</GeoTransform>\n"
                f'  <VRTRasterBand dataType="Float32" band="1">\n'
                f"    <NoDataValue>-32768</NoDataValue>\n")
        for name, x, y in placed:
            f.write(f"    <SimpleSource>\n"
                    f'      <SourceFilename relativeToVRT="1">tiles/{name}</SourceFilename>\n'
                    f"      <SourceBand>1</SourceBand>\n"
                    f'      <SourceProperties RasterXSize="{tile_cells}" RasterYSize="{tile_cells}" '
                    f'DataType="Float32" BlockXSize="128" BlockYSize="128"/>\n'
                    f'      <SrcRect xOff="0" yOff="0" xSize="{tile_cells}" ySize="{tile_cells}"/>\n'
                    f'      <DstRect xOff="{x}" yOff="{y}" xSize="{tile_cells}" ySize="{tile_cells}"/>\n'
                    f"    </SimpleSource>\n")
        f.write("  </VRTRasterBand>\n</VRTDataset>\n")
    os.replace(mosaic + ".tmp", mosaic)
    print(mosaic)
    print(f"{len(placed)} tiles of {tile_cells} x {tile_cells} cells (1/{a.arcsec_div}\"), "
          f"{int(coast.sum())} holding coast, in a {width} x {height} mosaic", file=sys.stderr)


if __name__ == "__main__":
    main()

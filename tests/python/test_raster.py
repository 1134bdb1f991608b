# SPDX-License-Identifier: GPL-3.0-or-later
"""An in-memory raster (numpy array with lon/lat, or an xarray DataArray) gives the same mesh as
the same data written to a GeoTIFF."""

import os
import subprocess

import netCDF4
import numpy as np
import pytest
import xarray as xr

import aquatoria as aq
from conftest import ETOPO_DIR

ETOPO20 = os.path.join(ETOPO_DIR, "etopo20.cdf")


def same(a, b):
    np.testing.assert_array_equal(a.nodes, b.nodes)
    np.testing.assert_array_equal(a.triangles, b.triangles)
    np.testing.assert_array_equal(a.depth, b.depth)
    np.testing.assert_array_equal(a.level, b.level)


@pytest.fixture(scope="module")
def etopo20():
    with netCDF4.Dataset(ETOPO20) as nc:
        nc.set_auto_mask(False)
        rose = nc["ROSE"]
        y, x = rose.dimensions  # ETOPO20Y, ETOPO20X1_1081 (a duplicated 360° column)
        return rose[...], nc[x][...], nc[y][...]


@pytest.fixture(scope="module")
def geotiff(tmp_path_factory, etopo20):
    """The same data as a GeoTIFF, made by GDAL's own tool from the netCDF file."""
    path = str(tmp_path_factory.mktemp("tif") / "etopo20.tif")
    subprocess.run(["gdal_translate", "-q", "-of", "GTiff", "NETCDF:%s:ROSE" % ETOPO20, path], check=True)
    return path


def test_numpy_raster_equals_the_geotiff(etopo20, geotiff):
    values, lon, lat = etopo20
    from_file = aq.mesh(None, {"input.path": geotiff})
    from_memory = aq.mesh(None, raster=values, lon=lon, lat=lat)
    assert len(from_file.triangles) > 1000
    same(from_file, from_memory)
    # and a south-up copy (rows reversed) is the same raster
    same(from_file, aq.mesh(None, raster=values[::-1], lon=lon, lat=lat[::-1]))


def test_dataarray_equals_the_geotiff(geotiff):
    with xr.open_dataset(ETOPO20) as ds:
        da = ds["ROSE"].load()
    same(aq.mesh(None, {"input.path": geotiff}), aq.mesh(None, raster=da))


def test_mask_of_an_in_memory_raster(etopo20, geotiff):
    values, lon, lat = etopo20
    a = aq.mask(None, {"input.path": geotiff})
    b = aq.mask(None, raster=values, lon=lon, lat=lat)
    np.testing.assert_array_equal(a.classes, b.classes)
    np.testing.assert_array_equal(a.levels, b.levels)


def test_bad_in_memory_rasters_are_refused():
    values = np.zeros((4, 5), np.float32)
    with pytest.raises(aq.InputError, match="not equally spaced"):
        aq.mesh(None, raster=values, lon=[0, 1, 2, 3, 5], lat=[0, 1, 2, 3])
    with pytest.raises(aq.InputError, match="lon has 4"):
        aq.mesh(None, raster=values, lon=[0, 1, 2, 3], lat=[0, 1, 2, 3])
    with pytest.raises(aq.InputError, match="not finite"):
        aq.mesh(None, raster=values, lon=[0, 1, 2, 3, np.nan], lat=[0, 1, 2, 3])

# SPDX-License-Identifier: GPL-3.0-or-later
"""aquatoria.mask: the mask stage and the quadtree levels of a run, as arrays, without a mesh."""

from . import _core
from ._config import emit_warnings, prepare, threads_arg
from ._interrupt import call

#: Values of Mask.classes.
DRY, COASTAL, WET = 0, 1, 2
#: Value of Mask.levels where no quadtree leaf is (land, or ocean cut off from the seeds).
NO_LEVEL = 255


def mask(config=None, overrides=None, *, raster=None, lon=None, lat=None, threads=None, verbose=False):
    """Runs the stages before the mesh (read, pixel classes, K-cursor fill, quadtree levels) of
    ``aquatoria mesh`` with the same configuration, and returns them as arrays.

    Parameters are those of :func:`aquatoria.mesh` (config, overrides, raster/lon/lat, threads,
    verbose).

    Returns
    -------
    Mask

    Raises
    ------
    ConfigError, InputError, Error
        As :func:`aquatoria.mesh`.
    """
    config, sets, mem = prepare(config, overrides, raster, lon, lat)
    core = call(_core.MaskRun, config, sets, bool(verbose), threads_arg(threads))
    emit_warnings(core.take_log())
    return Mask(core, mem)


class Mask:
    """The pixel lattice of a run: every array is (ny, nx), row j = 0 the southernmost, column
    i = 0 at longitude lon0 (quadtree.lon0_deg), in the lattice frame (the rotated frame when
    rotation.enabled; Mercator rows for quadtree.lattice = "mercator"; see ``lattice``).

    Attributes
    ----------
    classes : numpy.ndarray of uint8
        0 dry (all 4 pixel corners above -h), 1 coastal, 2 wet (all 4 corners at or below -h).
    filled : numpy.ndarray of bool
        The K-cursor fill from the seeds (the area the mesh covers).
    floodplain : numpy.ndarray of bool
        With mask.min_depth_m < 0 (a storm-surge mesh): the filled pixels that are not wet at the
        datum, land up to -min_depth_m above it (the report's mask.floodplain.floodplain_pixels);
        all False otherwise.
    levels : numpy.ndarray of uint8
        Quadtree level of the leaf holding each pixel, 255 where there is none.
    lon, lat : numpy.ndarray of float64
        Pixel centres (nx and ny values); ``lon_edges``, ``lat_edges``: pixel edges (nx+1, ny+1).
    lattice : dict
        kind, nx, ny, pixel_deg, step0_deg, levels, lon0_deg, rotated, pole_lon_deg, pole_lat_deg.
    report : dict
        The report sections of these stages (input, lattice, mask, quadtree).
    """

    def __init__(self, core, memory_raster=None):
        self._core = core
        self._memory_raster = memory_raster
        self.classes = call(core.classes)
        self.filled = call(core.filled)
        self.floodplain = call(core.floodplain)
        self.levels = call(core.levels)
        self.lon = core.lon
        self.lat = core.lat
        self.lon_edges = core.lon_edges
        self.lat_edges = core.lat_edges

    @property
    def lattice(self):
        """The lattice as a dict (see the class documentation)."""
        report = self.report
        lat = dict(report["lattice"])
        rotation = report["config"]["rotation"]
        lat["rotated"] = bool(rotation["enabled"])
        lat["pole_lon_deg"] = rotation["pole_lon_deg"]
        lat["pole_lat_deg"] = rotation["pole_lat_deg"]
        return lat

    @property
    def report(self):
        """The report of the stages run, as a dict."""
        return self._core.report()

    def to_xarray(self):
        """classes, filled, floodplain and levels as an xarray.Dataset on (lat, lon) pixel centres, with the
        pixel edges as lon_bnds / lat_bnds and the lattice as attributes."""
        import numpy as np
        import xarray as xr

        lon_b = np.stack([self.lon_edges[:-1], self.lon_edges[1:]], axis=1)
        lat_b = np.stack([self.lat_edges[:-1], self.lat_edges[1:]], axis=1)
        lattice = {k: (int(v) if isinstance(v, bool) else v) for k, v in self.lattice.items()}
        ds = xr.Dataset(
            {
                "classes": (("lat", "lon"), self.classes,
                            {"long_name": "pixel class", "flag_values": np.array([0, 1, 2], np.uint8),
                             "flag_meanings": "dry coastal wet"}),
                "filled": (("lat", "lon"), self.filled, {"long_name": "K-cursor fill (the meshed area)"}),
                "floodplain": (("lat", "lon"), self.floodplain,
                               {"long_name": "filled pixels above the datum (mask.min_depth_m < 0)"}),
                "levels": (("lat", "lon"), self.levels,
                           {"long_name": "quadtree level of the leaf holding the pixel", "_FillValue": NO_LEVEL}),
                "lon_bnds": (("lon", "nv"), lon_b),
                "lat_bnds": (("lat", "nv"), lat_b),
            },
            coords={
                "lon": ("lon", self.lon, {"units": "degrees_east", "bounds": "lon_bnds"}),
                "lat": ("lat", self.lat, {"units": "degrees_north", "bounds": "lat_bnds"}),
            },
            attrs={"title": "aquatoria mask stage", **{"lattice_" + k: v for k, v in lattice.items()}},
        )
        return ds

    def __repr__(self):
        lat = self.lattice
        return "<aquatoria.Mask: %d x %d %s pixels of %g', %d filled>" % (
            lat["nx"], lat["ny"], lat["kind"], lat["pixel_deg"] * 60, int(self.filled.sum()))

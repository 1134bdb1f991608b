"""aquatoria.mesh: a global mesh run and its arrays."""

import os
import shutil
import tempfile

from . import _core
from ._config import emit_warnings, prepare, threads_arg


def mesh(config=None, overrides=None, *, raster=None, lon=None, lat=None, threads=None, verbose=False):
    """Builds a global mesh the way ``aquatoria mesh -c config --set key=value ...`` does.

    Parameters
    ----------
    config : str or os.PathLike or None
        A TOML configuration file (see configs/example.toml); None: the built-in defaults (the
        seed's reference run on ETOPO5).
    overrides : dict or list of str, optional
        Keys as for ``--set``: ``{"quadtree.size_km": 110}``, ``{"quadtree": {"levels": 4}}`` or
        ``["quadtree.levels=4"]``. Unknown keys raise ConfigError with a "did you mean" hint.
    raster : numpy.ndarray or xarray.DataArray, optional
        Bathymetry held in memory instead of input.path: elevation in metres (negative below sea
        level, or positive down with ``{"input.positive_down": True}``), shape (lat, lon), at the
        equally spaced points ``lon``, ``lat`` (degrees; a DataArray brings its own coordinates
        named lon/longitude/x and lat/latitude/y). It gives the mesh the same data gives from a
        GeoTIFF file.
    lon, lat : array_like, optional
        The coordinates of a numpy ``raster``.
    threads : int, optional
        OpenMP threads for this call (default: OMP_NUM_THREADS, as for the command line). The
        result does not depend on it.
    verbose : bool
        Print the stage lines the command prints on stderr (default: only warnings, which also
        become Python warnings of class aquatoria._config.AquatoriaWarning).

    Returns
    -------
    Run

    Raises
    ------
    ConfigError
        A bad key or value (the message names the file or ``--set``, the key and the value).
    InputError
        A missing or unreadable raster, a bad in-memory raster.
    Error
        Any other failure of the pipeline (its subclasses NumericalError, InternalError).
    """
    config, sets, mem = prepare(config, overrides, raster, lon, lat)
    core = _core.MeshRun(config, sets, bool(verbose), threads_arg(threads))
    emit_warnings(core.take_log())
    return Run(core, mem)


class Run:
    """The result of :func:`mesh`: the mesh as the geographic files (UGRID, fort.14, text) hold it.

    Arrays are read-only views of the C++ mesh (no copy) except ``nodes`` and ``depth``, made
    once when first asked for. Node and element numbers are 0-based.
    """

    def __init__(self, core, memory_raster=None):
        self._core = core
        self._memory_raster = memory_raster  # keeps an in-memory raster alive with the run

    @property
    def nodes(self):
        """(n, 2) float64: longitude, latitude (degrees) of every node, longitudes in
        [lon0, lon0 + 360) (quadtree.lon0_deg), as the UGRID file's mesh_node_x / mesh_node_y."""
        return self._core.nodes

    @property
    def triangles(self):
        """(m, 3) int64: 0-based node numbers of every triangle, anticlockwise seen from outside
        the sphere (the UGRID file's mesh_face_nodes)."""
        return self._core.triangles

    @property
    def depth(self):
        """(n,) float64: sea-floor depth at the nodes in metres, positive down (the files' depth)."""
        return self._core.depth

    @property
    def elevation(self):
        """(n,) float64: elevation at the nodes in metres, negative below sea level (-depth)."""
        return self._core.elevation

    @property
    def level(self):
        """(m,) uint8: quadtree level of every triangle (0 = the coarsest squares, step_deg)."""
        return self._core.level

    @property
    def node_flags(self):
        """(n,) uint8: node flag bits (1 boundary, 2 midside, 4 centre, 8 pole, 16 seam, 32 cap)."""
        return self._core.node_flags

    @property
    def boundaries(self):
        """The boundary loops: a list of dicts with ``nodes`` (int64 array, anticlockwise around
        the water, first node not repeated) and ``type``: "mainland" for the outer loop (fort.14
        IBTYPE 0), "island" for every other (IBTYPE 1); ``pole`` marks the lattice pole line."""
        out = []
        for loop in self._core.boundary_loops:
            out.append({"nodes": loop["nodes"], "type": "mainland" if loop["outer"] else "island",
                        "pole": loop["pole"]})
        return out

    @property
    def lattice(self):
        """The lattice as a dict: kind ("lonlat" or "mercator"), nx, ny, pixel_deg, step0_deg,
        levels, lon0_deg, rotated, pole_lon_deg, pole_lat_deg."""
        return self._core.lattice

    @property
    def report(self):
        """The run report as a dict (the sections of <name>_report.json the run has so far)."""
        return self._core.report()

    def write(self, prefix, formats=None, *, threads=None):
        """Writes the mesh files as the command line does: ``prefix`` = "out/gm" gives out/gm.msh,
        out/gm.nc, ... and out/gm_report.json, byte for byte the files of ``aquatoria mesh`` with
        output.dir = "out", output.name = "gm" (the report's timings aside).

        Parameters
        ----------
        prefix : str or os.PathLike
            Folder and base name of the files.
        formats : list of str, optional
            Values of output.formats (msh, ugrid, vtu, fort14, text, png, fesom, schism, tif);
            default: the configuration's output.formats.
        threads : int, optional
            OpenMP threads for this call.

        Returns
        -------
        list of str
            The paths written, the report last.

        Raises
        ------
        ConfigError
            An unknown format or bad output option (nothing is written).
        OutputError
            A file could not be written (no file of the call is left behind).
        """
        prefix = os.fspath(prefix)
        folder, name = os.path.split(prefix)
        if not name:
            raise _core.ConfigError("write: %r has no file name part (give folder/name)" % prefix)
        if formats is not None:
            formats = [str(f) for f in ([formats] if isinstance(formats, str) else formats)]
        paths = self._core.write(folder or ".", name, formats, threads_arg(threads))
        emit_warnings(self._core.take_log())
        return paths

    def to_xarray(self):
        """The mesh as a UGRID-1.0 / CF-1.8 xarray.Dataset: the variables, dimensions and attributes
        of the UGRID file ``write(..., formats=["ugrid"])`` gives (mesh_topology ``mesh``,
        mesh_node_x/y, mesh_face_nodes with start_index 0 and _FillValue -1, edges, boundary edges,
        face centres and bounds, depth, node_flags, level, the crs grid mapping), loaded into
        memory. xugrid / uxarray open it as they open the file."""
        import xarray as xr

        folder = tempfile.mkdtemp(prefix="aquatoria_")
        try:
            paths = self.write(os.path.join(folder, "mesh"), formats=["ugrid"])
            with xr.open_dataset(paths[0], mask_and_scale=False) as ds:
                ds = ds.load()
            for v in ds.variables.values():
                # no _FillValue where the file has none (xarray would add NaN to floats on writing)
                if "_FillValue" not in v.attrs:
                    v.encoding["_FillValue"] = None
            return ds
        finally:
            shutil.rmtree(folder, ignore_errors=True)

    def __repr__(self):
        c = self.report.get("mesh_counts", {})
        return "<aquatoria.Run: %s nodes, %s triangles, %s boundary loops>" % (
            c.get("nodes"), c.get("triangles"), c.get("boundary_loops"))

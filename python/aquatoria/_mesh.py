# SPDX-License-Identifier: GPL-3.0-or-later
"""aquatoria.mesh: a global mesh run and its meshes as arrays: the geographic mesh (the UGRID,
VTU and text files), the lattice mesh (MSH, the quadtree's own) and each model format's mesh as
its files hold it (fort.14, hgrid.gr3, FESOM2)."""

import os

from . import _core
from ._config import emit_warnings, prepare, threads_arg
from ._interrupt import call


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
    KeyboardInterrupt
        Ctrl-C: the run stops within a fraction of a second and leaves nothing behind.
    ConfigError
        A bad key or value (the message names the file or ``--set``, the key and the value).
    InputError
        A missing or unreadable raster, a bad in-memory raster.
    Error
        Any other failure of the pipeline (its subclasses NumericalError, InternalError).
    """
    config, sets, mem = prepare(config, overrides, raster, lon, lat)
    core = call(_core.MeshRun, config, sets, bool(verbose), threads_arg(threads))
    emit_warnings(core.take_log())
    return Run(core, mem)


_TYPES = ("mainland", "island", "open", "river")


class Mesh:
    """One mesh of a run as numpy arrays, numbered from 0: :attr:`Run.geographic_mesh` (what the
    UGRID, VTU and text files hold) or :attr:`Run.lattice_mesh` (the quadtree's own mesh on the
    lattice, what the MSH file and the preview draw and the report's mesh_counts count).

    Arrays are read-only views of the C++ mesh (no copy) except ``nodes`` and ``depth``, made once.
    """

    def __init__(self, arrays, what):
        self._a = arrays
        self.what = what  #: "geographic" or "lattice"

    @property
    def nodes(self):
        """(n, 2) float64: longitude, latitude (degrees) of every node, geographic (after the pole
        rotation, if any), longitudes in [lon0, lon0 + 360) (quadtree.lon0_deg)."""
        return self._a["nodes"]

    @property
    def rotated_nodes(self):
        """(n, 2) float64: the nodes in the lattice's (rotated) frame: rlon, rlat (degrees); equal to
        ``nodes`` without rotation (the UGRID file's mesh_node_rlon / rlat with one)."""
        import numpy as np

        return np.column_stack((self._a["rlon"], self._a["rlat"]))

    @property
    def lattice_ij(self):
        """(n, 2) int64: the lattice vertex (I, J) of every node (-1, -1 for a node the pole cap
        added; a node moved onto a domain polygon keeps the vertex it came from)."""
        import numpy as np

        return np.column_stack((self._a["node_i"], self._a["node_j"]))

    @property
    def triangles(self):
        """(m, 3) int64: node numbers of every triangle, anticlockwise seen from outside the sphere
        (the UGRID file's mesh_face_nodes); empty with mesh.elements = "squares"."""
        return self._a["triangles"]

    @property
    def level(self):
        """(m,) uint8: quadtree level of every triangle (0 = the coarsest squares, step_deg)."""
        return self._a["level"]

    @property
    def squares(self):
        """(s, 4) int64: the quadtree squares' corners SW, SE, NE, NW (mesh.elements "squares" or
        "both"; the lattice mesh always has them)."""
        return self._a["squares"]

    @property
    def square_level(self):
        """(s,) uint8: quadtree level of every square."""
        return self._a["square_level"]

    @property
    def depth(self):
        """(n,) float64: sea-floor depth at the nodes in metres, positive down (the files' depth);
        negative on a floodplain above the datum (:attr:`floodplain_top_m` > 0)."""
        return self._a["depth"]

    @property
    def floodplain_top_m(self):
        """float: > 0 for a floodplain mesh (mask.min_depth_m < 0): it reaches land up to this many
        metres above the datum, where :attr:`depth` is negative (dry at rest); 0 otherwise."""
        return self._a["floodplain_top_m"]

    @property
    def elevation(self):
        """(n,) float64: elevation at the nodes in metres, negative below sea level (-depth)."""
        return self._a["elevation"]

    @property
    def node_flags(self):
        """(n,) uint8: node flag bits (1 boundary, 2 midside, 4 centre, 8 pole, 16 seam, 32 cap,
        64 moved onto a domain polygon)."""
        return self._a["node_flags"]

    @property
    def boundary_edges(self):
        """(b, 2) int64: every boundary edge a -> b with the water on its left (the UGRID file's
        mesh_boundary_nodes), and ``boundary_edge_loop`` (b,): the loop of each."""
        return self._a["boundary_edges"]

    @property
    def boundary_edge_loop(self):
        """(b,) int32: boundary loop of each boundary edge."""
        return self._a["boundary_edge_loop"]

    @property
    def boundary_edge_type(self):
        """(b,) uint8 or None: type of each boundary edge of a regional mesh, 0 mainland, 1 island,
        2 open, 3 river inflow (the UGRID file's mesh_boundary_type); None for a global mesh."""
        return self._a.get("boundary_edge_type")

    @property
    def boundaries(self):
        """The boundary as a list of dicts, each with ``nodes`` (int64, water on the left, a
        closed loop's first node not repeated), ``type`` ("open", "mainland", "island" or "river"),
        ``closed`` (a whole loop), ``loop`` (its loop id) and ``pole`` (the lattice pole line).
        A regional mesh ([domain]): its typed segments, the open ones first, each open segment
        sharing its end nodes with the land pieces beside it. A global mesh: one entry per loop,
        "mainland" for the outer loop and "island" for every other one."""
        return self._a["boundaries"]

    @property
    def pinch_nodes(self):
        """(p,) int64: nodes where the wet area touches itself at a corner."""
        return self._a["pinch_nodes"]

    def __repr__(self):
        return "<aquatoria.Mesh (%s): %d nodes, %d triangles, %d squares, %d boundaries>" % (
            self.what, len(self.nodes), len(self.triangles), len(self.squares), len(self.boundaries))


class ModelMesh:
    """The mesh a model format's files hold, from :meth:`Run.model_mesh`: the geographic
    triangles cleaned for the models (no triangle hanging on one edge, no pinch vertex), with the
    numbers the writer writes, made by the writer's own functions. Node and triangle numbers are
    0-based: node k is node k + 1 of the files.

    Attributes
    ----------
    format : str
        "fort14" (ADCIRC fort.14), "schism" (hgrid.gr3 / hgrid.ll) or "fesom" (nod2d.out,
        elem2d.out, aux3d.out).
    nodes : numpy.ndarray, (n, 2) float64
        Longitude in [-180, 180) and latitude (degrees), the files' columns.
    triangles : numpy.ndarray, (m, 3) int64
        The files' triangles in their corner order: anticlockwise (fort.14, hgrid.gr3) or
        clockwise (FESOM2's elem2d.out, n1 n3 n2).
    depth : numpy.ndarray, (n,) float64
        The files' depth column: metres below the datum, positive down (fort.14, hgrid.gr3;
        negative on a floodplain above the datum, which ADCIRC and SCHISM start dry), or FESOM2's
        aux3d.out bottom, negative, 0 where the elevation is at or above the datum (FESOM2 has no
        wetting and drying: model_mesh("fesom") of a floodplain mesh warns as the command does).
    floodplain_top_m : float
        > 0 for a floodplain mesh (mask.min_depth_m < 0): the highest land it reaches above the
        datum (m); 0 otherwise.
    boundaries : list of dict
        The files' boundary lists in their order (fort.14 / hgrid.gr3: the NOPE open segments, then
        the NBOU / NLAND land boundaries): ``type`` ("open", "mainland", "island", "river"), ``open``
        (in the open list: an open segment, or a river inflow of hgrid.gr3), ``flag`` (fort.14
        IBTYPE: 0 / 1 on a global mesh, 20 / 21 / 22 (river) on a regional one; SCHISM's land flag
        0 / 1; 0 for an open list's entry), ``closed``, ``nodes`` (int64 as listed: a closed boundary
        repeats its first node at the end) and ``comment`` (the header line's text). FESOM2's
        files list only the open-boundary nodes (``open_nodes``) and flag the boundary nodes
        (``boundary_flag``); its ``boundaries`` are the same lists of the same mesh.
    open_segments, land_segments : list of dict
        The open and the land entries of ``boundaries``, in order.
    geographic_node, geographic_triangle : numpy.ndarray of int64 or None
        Where each node and triangle is in :attr:`Run.geographic_mesh` (mesh.elements =
        "triangles", the default; None otherwise).
    boundary_flag, open_nodes, levels : numpy.ndarray or None
        FESOM2 only: nod2d.out's flag (1 on the boundary), the open-boundary file's nodes (each
        once, in the open segments' order; empty for a global mesh) and aux3d.out's depth levels (m,
        positive down).
    """

    def __init__(self, arrays, geographic_is_triangles):
        self._a = arrays
        self.format = arrays["format"]
        self.nodes = arrays["nodes"]
        self.triangles = arrays["triangles"]
        self.depth = arrays["depth"]
        self.floodplain_top_m = arrays["floodplain_top_m"]
        self.boundaries = arrays["boundaries"]
        self.open_segments = [b for b in self.boundaries if b["open"]]
        self.land_segments = [b for b in self.boundaries if not b["open"]]
        self.geographic_node = arrays["geographic_node"] if geographic_is_triangles else None
        self.geographic_triangle = arrays["geographic_triangle"] if geographic_is_triangles else None
        self.boundary_flag = arrays.get("boundary_flag")
        self.open_nodes = arrays.get("open_nodes")
        self.levels = arrays.get("levels")

    def __repr__(self):
        return "<aquatoria.ModelMesh (%s): %d nodes, %d triangles, %d open and %d land boundaries>" % (
            self.format, len(self.nodes), len(self.triangles), len(self.open_segments), len(self.land_segments))


class Run:
    """The result of :func:`mesh`. Three meshes, each numbered its own way:

    * :attr:`geographic_mesh`: the mesh of the UGRID, VTU and text files (and of
      :meth:`to_xarray`): the lattice mesh with the pole rows replaced by a pole cap (or merged),
      in geographic coordinates. ``run.nodes``, ``run.triangles``, ``run.depth``, ``run.level``,
      ``run.node_flags`` and ``run.boundaries`` are its arrays.
    * :meth:`model_mesh`: what fort.14, hgrid.gr3 and FESOM2's files hold: the geographic
      triangles cleaned for the models, node for node the files.
    * :attr:`lattice_mesh`: the quadtree's mesh on the lattice (the MSH file, the report's
      mesh_counts).

    Numbers are 0-based.
    """

    def __init__(self, core, memory_raster=None):
        self._core = core
        self._memory_raster = memory_raster  # keeps an in-memory raster alive with the run
        self._geographic = None
        self._lattice = None
        self._models = {}

    @property
    def geographic_mesh(self):
        """The :class:`Mesh` the UGRID, VTU and text files hold (made when first asked for)."""
        if self._geographic is None:
            self._geographic = Mesh(call(self._core.geographic_mesh, 0), "geographic")
            emit_warnings(self._core.take_log())
        return self._geographic

    @property
    def lattice_mesh(self):
        """The :class:`Mesh` on the lattice: the quadtree's triangles and squares as built (pole
        rows of distinct nodes at one point, the seam's nodes once), what the MSH file (in the
        lattice plane) and the preview draw and the report's mesh_counts count."""
        if self._lattice is None:
            self._lattice = Mesh(self._core.lattice_mesh(), "lattice")
        return self._lattice

    def model_mesh(self, format="fort14", *, threads=None):
        """The mesh the files of a model format hold, as a :class:`ModelMesh`.

        Parameters
        ----------
        format : str
            "fort14" (or "adcirc"), "schism" (or "gr3"), "fesom" (or "fesom2"): the values of
            output.formats. All three are the same cleaned mesh; they differ in the numbers their
            files write (FESOM2's clockwise triangles, negative bottom, boundary flag).
        threads : int, optional
            OpenMP threads for this call.

        Raises
        ------
        ConfigError
            An unknown format, or mesh.elements = "squares" (the model formats are triangles).
        """
        format = str(format)
        if format not in self._models:
            arrays = call(self._core.model_mesh, format, threads_arg(threads))
            emit_warnings(self._core.take_log())
            geo_tri = self.report.get("config", {}).get("mesh", {}).get("elements", "triangles") == "triangles"
            self._models[format] = ModelMesh(arrays, geo_tri)
        return self._models[format]

    @property
    def nodes(self):
        """(n, 2) float64: longitude, latitude of the geographic mesh's nodes (the UGRID file's
        mesh_node_x / mesh_node_y); the model files' nodes are :meth:`model_mesh`'s."""
        return self.geographic_mesh.nodes

    @property
    def triangles(self):
        """(m, 3) int64: the geographic mesh's triangles, anticlockwise seen from outside the sphere
        (the UGRID file's mesh_face_nodes)."""
        return self.geographic_mesh.triangles

    @property
    def depth(self):
        """(n,) float64: the geographic mesh's sea-floor depth in metres, positive down (negative on
        a floodplain above the datum)."""
        return self.geographic_mesh.depth

    @property
    def floodplain_top_m(self):
        """float: > 0 for a floodplain mesh (mask.min_depth_m < 0): the mesh reaches land up to this
        many metres above the datum (its nodes there have a negative depth; the report's
        "floodplain" section counts them); 0 otherwise."""
        return self.lattice_mesh.floodplain_top_m

    @property
    def elevation(self):
        """(n,) float64: the geographic mesh's elevation in metres, negative below sea level."""
        return self.geographic_mesh.elevation

    @property
    def level(self):
        """(m,) uint8: quadtree level of every triangle of the geographic mesh."""
        return self.geographic_mesh.level

    @property
    def node_flags(self):
        """(n,) uint8: node flag bits of the geographic mesh (see :attr:`Mesh.node_flags`)."""
        return self.geographic_mesh.node_flags

    @property
    def boundaries(self):
        """The geographic mesh's boundary (see :attr:`Mesh.boundaries`): typed segments of a
        regional mesh, its open segments first; one entry per loop of a global one."""
        return self.geographic_mesh.boundaries

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
        KeyboardInterrupt
            Ctrl-C: no file of the call is left behind, not even a temporary one.
        """
        prefix = os.fspath(prefix)
        folder, name = os.path.split(prefix)
        if not name:
            raise _core.ConfigError("write: %r has no file name part (give folder/name)" % prefix)
        if formats is not None:
            formats = [str(f) for f in ([formats] if isinstance(formats, str) else formats)]
        paths = call(self._core.write, folder or ".", name, formats, threads_arg(threads))
        emit_warnings(self._core.take_log())
        return paths

    def to_xarray(self):
        """The geographic mesh as a UGRID-1.0 / CF-1.8 xarray.Dataset, made in memory by the UGRID
        writer's own description of its file: the variables, dimensions, values and attributes of
        the file ``write(..., formats=["ugrid"])`` gives, decoded as ``xarray.open_dataset(file,
        mask_and_scale=False)`` decodes them (mesh_topology ``mesh``, mesh_node_x/y,
        mesh_face_nodes with start_index 0, edges, boundary edges, face centres and bounds, depth,
        node_flags, level, the crs grid mapping). xugrid / uxarray take it as they take the file;
        ``to_netcdf`` writes it back."""
        import xarray as xr

        d = call(self._core.ugrid_dataset, 0)
        variables = {name: xr.Variable(dims, data, attrs) for name, dims, data, attrs in d["variables"]}
        ds = xr.decode_cf(xr.Dataset(variables, attrs=d["attrs"]), mask_and_scale=False).load()
        for v in ds.variables.values():
            # no _FillValue where the file has none (xarray would add NaN to floats on writing)
            if "_FillValue" not in v.attrs:
                v.encoding["_FillValue"] = None
        return ds

    def __repr__(self):
        c = self.report.get("mesh_counts", {})
        return "<aquatoria.Run: %s nodes, %s triangles, %s boundary loops (lattice mesh)>" % (
            c.get("nodes"), c.get("triangles"), c.get("boundary_loops"))

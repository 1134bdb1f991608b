# SPDX-License-Identifier: GPL-3.0-or-later
"""aquatoria.mesh: the geographic mesh's arrays equal the command line's UGRID file, write() gives
its bytes, to_xarray() (made in memory) equals the UGRID file as xarray reads it and round-trips
through netCDF (seed run and Mercator run). The model formats' meshes: test_model_mesh.py."""

import filecmp
import json
import os

import netCDF4
import numpy as np
import pytest
import xarray as xr

import aquatoria as aq
from conftest import FORMATS


def ugrid(cli_run):
    with netCDF4.Dataset(cli_run.path(".nc")) as nc:
        nc.set_auto_mask(False)
        return {name: nc.variables[name][...] for name in nc.variables}


@pytest.fixture(params=["seed", "mercator"])
def pair(request, seed_cli, mercator_cli, seed_run, mercator_run):
    if request.param == "seed":
        return seed_cli, seed_run
    return mercator_cli, mercator_run


def test_arrays_equal_the_ugrid_file(pair):
    cli_run, run = pair
    u = ugrid(cli_run)
    assert run.nodes.dtype == np.float64 and run.nodes.shape == (len(u["mesh_node_x"]), 2)
    np.testing.assert_array_equal(run.nodes[:, 0], u["mesh_node_x"])
    np.testing.assert_array_equal(run.nodes[:, 1], u["mesh_node_y"])
    assert run.triangles.dtype == np.int64
    np.testing.assert_array_equal(run.triangles, u["mesh_face_nodes"])
    np.testing.assert_array_equal(run.depth, u["depth"])
    np.testing.assert_array_equal(run.elevation, -u["depth"])
    np.testing.assert_array_equal(run.level, u["level"])
    np.testing.assert_array_equal(run.node_flags, u["node_flags"])
    # boundary loops: the boundary edges of the file, loop by loop, in order
    edges = u["mesh_boundary_nodes"]
    loop_of_edge = u["mesh_boundary_loop"]
    loops = run.boundaries
    assert len(loops) == loop_of_edge.max() + 1
    for k, loop in enumerate(loops):
        nodes = loop["nodes"]
        mine = np.stack([nodes, np.roll(nodes, -1)], axis=1)
        theirs = edges[loop_of_edge == k]
        np.testing.assert_array_equal(mine[np.lexsort(mine.T[::-1])], theirs[np.lexsort(theirs.T[::-1])])
        assert loop["type"] in ("mainland", "island")
    assert sum(l["type"] == "mainland" for l in loops) == 1


def test_counts_and_checksums_equal_the_cli_report(pair):
    cli_run, run = pair
    with open(cli_run.path("_report.json")) as f:
        cli_report = json.load(f)
    report = run.report
    assert report["mesh_counts"] == cli_report["mesh_counts"]
    assert report["statistics"] == cli_report["statistics"]
    assert report["mask"] == cli_report["mask"]


def test_triangles_anticlockwise_on_the_sphere(pair):
    _, run = pair
    lon, lat = np.radians(run.nodes[:, 0]), np.radians(run.nodes[:, 1])
    p = np.stack([np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)], axis=1)
    a, b, c = (p[run.triangles[:, k]] for k in range(3))
    orient = np.einsum("ij,ij->i", np.cross(b - a, c - a), a + b + c)
    assert (orient > 0).all()
    assert run.triangles.min() == 0 and run.triangles.max() == len(run.nodes) - 1


def test_write_gives_the_cli_bytes(pair, tmp_path):
    cli_run, run = pair
    paths = run.write(tmp_path / cli_run.name, formats=FORMATS)
    assert paths[-1].endswith("_report.json")
    names = sorted(os.path.basename(p) for p in paths[:-1])
    cli_names = sorted(n for n in os.listdir(cli_run.folder) if not n.endswith("_report.json"))
    assert names == cli_names
    for n in names:
        assert filecmp.cmp(os.path.join(cli_run.folder, n), tmp_path / n, shallow=False), n


def test_arrays_are_views_not_copies(seed_run):
    t = seed_run.triangles
    assert not t.flags.owndata and not t.flags.writeable
    assert seed_run.triangles.__array_interface__["data"][0] == t.__array_interface__["data"][0]
    assert not seed_run.level.flags.owndata and not seed_run.nodes.flags.owndata


def same_attrs(a, b, where):
    assert sorted(a) == sorted(b), where
    for k in b:
        assert np.array_equal(np.asarray(a[k]), np.asarray(b[k])), (where, k)


def test_to_xarray_equals_the_ugrid_file_and_round_trips(pair, tmp_path):
    cli_run, run = pair
    ds = run.to_xarray()
    # made in memory: no file of the call anywhere (the former route wrote one to a temporary folder)
    assert all(not v.encoding.get("source") for v in ds.variables.values())
    mesh = ds["mesh"].attrs
    assert mesh["cf_role"] == "mesh_topology" and mesh["topology_dimension"] == 2
    assert ds["mesh_face_nodes"].attrs["start_index"] == 0
    # triangles need no fill value; polygons (squares with hanging nodes) are padded with -1
    assert ds["mesh_face_nodes"].attrs.get("_FillValue", -1) == -1
    assert "crs" in ds and ds["mesh_node_x"].attrs["standard_name"] == "longitude"
    with xr.open_dataset(cli_run.path(".nc"), mask_and_scale=False) as f:
        assert list(ds.variables) == list(f.variables) and dict(ds.dims) == dict(f.dims)
        assert set(ds.coords) == set(f.coords)
        for name in f.variables:
            assert ds[name].dims == f[name].dims and ds[name].dtype == f[name].dtype, name
            np.testing.assert_array_equal(ds[name].values, f[name].values, err_msg=name)
            same_attrs(ds[name].attrs, f[name].attrs, name)
            for k, v in f[name].attrs.items():
                assert type(ds[name].attrs[k]) == type(v), (name, k)
            assert ds[name].encoding.get("coordinates") == f[name].encoding.get("coordinates"), name
        same_attrs(ds.attrs, f.attrs, "global")
    out = tmp_path / "round.nc"
    ds.to_netcdf(out)
    with xr.open_dataset(out, mask_and_scale=False) as back:
        xr.testing.assert_equal(back, ds)  # names, dimensions, values
        # attributes: all kept, but for what xarray's writer itself changes (bounds variables
        # lose the units of their coordinate, CF's rule)
        for name in ds.variables:
            kept = {k: v for k, v in ds[name].attrs.items() if not (name.endswith("_bnds") and k == "units")}
            same_attrs({k: back[name].attrs[k] for k in kept if k in back[name].attrs}, kept, name)
            assert "_FillValue" not in back[name].attrs or "_FillValue" in ds[name].attrs, name
        same_attrs(back.attrs, ds.attrs, "global")


def test_the_same_run_twice_is_identical(seed_run):
    again = aq.mesh(None, {"output.formats": FORMATS})
    np.testing.assert_array_equal(again.nodes, seed_run.nodes)
    np.testing.assert_array_equal(again.triangles, seed_run.triangles)


def test_several_sources_from_an_override_dict():
    """{"input.paths": [...]} works as an override (a TOML list): ETOPO60 over ETOPO5, both global,
    so the first has data everywhere, supplies every node, and the mesh is ETOPO60's own."""
    data = "/usr/share/ferret-vis/data"
    e5, e60 = os.path.join(data, "etopo5.cdf"), os.path.join(data, "etopo60.cdf")
    run = aq.mesh(None, {"input.paths": [e60, e5]})
    sources = run.report["input"]["sources"]
    assert [s["path"] for s in sources] == [e60, e5]
    assert sources[0]["nodes"] > 10000 and sources[1]["nodes"] == 0
    assert sources[0]["blended_nodes"] == 0 and run.report["input"]["no_data_nodes"] == 0
    alone = aq.mesh(None, {"input.path": e60})
    np.testing.assert_array_equal(run.depth, alone.depth)
    np.testing.assert_array_equal(run.triangles, alone.triangles)

# SPDX-License-Identifier: GPL-3.0-or-later
"""A storm-surge mesh in Python (configs/gulf_surge.toml: mask.min_depth_m = -10, the floodplain
above the datum): negative depths pass through unchanged, the model meshes are the files node for
node (fort.14 and hgrid.gr3 with their negative depths, FESOM2's aux3d.out with 0 there and the
command's warning), the geographic arrays and to_xarray() equal the UGRID file (its depth
`comment`), the floodplain counts are the report's, and Mask.floodplain is the mask's."""

import json
import os

import netCDF4
import numpy as np
import pytest
import xarray as xr

import aquatoria as aq
from conftest import SOURCE_DIR, CliRun, cli
from test_mesh import same_attrs
from test_model_mesh import check_lists, read_fort14

SURGE = os.path.join(SOURCE_DIR, "configs", "gulf_surge.toml")
SURGE_FORMATS = ["fort14", "schism", "fesom", "ugrid"]


@pytest.fixture(scope="module")
def surge_cli(tmp_path_factory):
    folder = str(tmp_path_factory.mktemp("cli_gulf_surge"))
    args = ["mesh", "-q", "-c", SURGE, "-o", folder, "--set", "output.name=gulf_surge",
            "--set", "output.formats=[%s]" % ", ".join('"%s"' % f for f in SURGE_FORMATS)]
    code, err = cli(args, folder)
    assert code == 0, err
    return CliRun(folder, "gulf_surge", SURGE, [])


@pytest.fixture(scope="module")
def surge_run():
    with pytest.warns(aq.AquatoriaWarning, match="lattice finer than its data"):
        return aq.mesh(SURGE, {"output.formats": SURGE_FORMATS})


def test_the_floodplain_is_there_and_counted_as_the_report_does(surge_cli, surge_run):
    with open(surge_cli.path("_report.json")) as f:
        report = json.load(f)
    fp = report["floodplain"]
    assert surge_run.report["floodplain"] == fp
    assert surge_run.floodplain_top_m == 10.0 == fp["top_m"]
    lattice = surge_run.lattice_mesh
    assert lattice.floodplain_top_m == 10.0
    # the report counts the lattice mesh's nodes above the datum: negative depths, unchanged
    assert int((lattice.elevation > 0).sum()) == fp["nodes"] > 0
    np.testing.assert_array_equal(lattice.depth, -lattice.elevation)
    assert lattice.elevation.max() == fp["highest_node_m"]
    # the regional surge mesh keeps its open boundary (across the deep Gulf) beside the floodplain
    assert [s["type"] for s in surge_run.boundaries].count("open") == report["boundaries"]["open_segments"] == 1


@pytest.mark.parametrize("fmt,suffix", [("fort14", ".14"), ("schism", ".gr3")])
def test_fort14_and_gr3_hold_the_negative_depths(surge_cli, surge_run, fmt, suffix):
    m = surge_run.model_mesh(fmt)
    assert m.floodplain_top_m == 10.0
    nodes, tri, open_lists, land_lists = read_fort14(surge_cli.path(suffix))
    np.testing.assert_array_equal(m.nodes, nodes[:, :2])
    np.testing.assert_array_equal(m.depth, nodes[:, 2])
    np.testing.assert_array_equal(m.triangles, tri)
    check_lists(m.open_segments, open_lists)
    check_lists(m.land_segments, land_lists)
    assert (m.depth < 0).sum() > 1000 and m.depth.min() >= -10.0
    assert len(m.open_segments) == 1
    # the geographic mesh's depths, node for node
    g = surge_run.geographic_mesh
    np.testing.assert_array_equal(m.depth, g.depth[m.geographic_node])


def test_fesom_writes_zero_on_the_floodplain_and_warns(surge_cli, surge_run):
    f14 = surge_run.model_mesh("fort14")
    above = int((f14.depth < 0).sum())
    with pytest.warns(aq.AquatoriaWarning, match="FESOM2 has no wetting and drying") as w:
        m = surge_run.model_mesh("fesom")
    text = [str(x.message) for x in w if "wetting" in str(x.message)][0]
    assert "writes the %d nodes of the floodplain" % above in text
    with open(surge_cli.path("_aux3d.out")) as f:
        values = [float(v) for v in f.read().split()]
    nl = int(values[0])
    np.testing.assert_array_equal(m.depth, values[1 + nl:])
    assert (m.depth[f14.depth < 0] == 0).all() and (m.depth <= 0).all()
    v = np.loadtxt(surge_cli.path("_obn.out"), dtype=np.int64)
    np.testing.assert_array_equal(m.open_nodes, v[1:] - 1)


def test_geographic_arrays_and_to_xarray_are_the_ugrid_file(surge_cli, surge_run):
    with netCDF4.Dataset(surge_cli.path(".nc")) as nc:
        nc.set_auto_mask(False)
        depth = nc["depth"][...]
        comment = nc["depth"].getncattr("comment")
    np.testing.assert_array_equal(surge_run.depth, depth)
    assert (depth < 0).any() and "floodplain" in comment and "10" in comment
    ds = surge_run.to_xarray()
    with xr.open_dataset(surge_cli.path(".nc"), mask_and_scale=False) as f:
        assert list(ds.variables) == list(f.variables)
        for name in f.variables:
            assert ds[name].dtype == f[name].dtype, name
            np.testing.assert_array_equal(ds[name].values, f[name].values, err_msg=name)
            same_attrs(ds[name].attrs, f[name].attrs, name)
        same_attrs(ds.attrs, f.attrs, "global")
    assert ds["depth"].attrs["comment"] == comment


def test_mask_floodplain_is_the_mask_stage_s(surge_cli):
    with open(surge_cli.path("_report.json")) as f:
        fp = json.load(f)["mask"]["floodplain"]
    with pytest.warns(aq.AquatoriaWarning):
        m = aq.mask(SURGE)
    assert m.floodplain.dtype == np.bool_ and m.floodplain.shape == m.filled.shape
    assert int(m.floodplain.sum()) == fp["floodplain_pixels"] > 0
    assert not (m.floodplain & ~m.filled).any()
    ds = m.to_xarray()
    np.testing.assert_array_equal(ds["floodplain"].values, m.floodplain)
    with pytest.warns(aq.AquatoriaWarning):
        plain = aq.mask(SURGE, {"mask.min_depth_m": 0.0, "size.inland.h0_km": 0.0, "size.elevation.h0_km": 0.0})
    assert plain.floodplain.shape == plain.filled.shape and not plain.floodplain.any()

# SPDX-License-Identifier: GPL-3.0-or-later
"""aquatoria.mask: the classes, the filled area and the levels agree with the mesh run's report
and its global run file; georeferencing of the lattice."""

import numpy as np

import aquatoria as aq


def test_mask_matches_the_mesh_run(seed_run):
    m = aq.mask(None)
    lat = m.lattice
    assert m.classes.shape == (lat["ny"], lat["nx"]) == (360, 720)
    report = seed_run.report["mask"]
    assert int(m.filled.sum()) == report["fill"]["filled_pixels_final"]
    assert int((m.classes == aq._mask.WET).sum()) == m.report["mask"]["classes"]["wet"]
    assert int((m.classes == aq._mask.COASTAL).sum()) == m.report["mask"]["classes"]["coastal"]
    assert m.report["mask"] == seed_run.report["mask"]
    # every filled pixel is wet and lies in a quadtree leaf; the levels are 0..L
    assert (m.classes[m.filled] == aq._mask.WET).all()
    assert (m.levels[m.filled] <= lat["levels"]).all()
    assert set(np.unique(m.levels)) <= set(range(lat["levels"] + 1)) | {255}
    # the finest level is where the coast is
    assert (m.levels[m.filled & (np.roll(~m.filled, 1, axis=1))] == lat["levels"]).all()


def test_georeferencing():
    m = aq.mask(None)
    assert m.lon_edges[0] == -180.0 and m.lon_edges[-1] == 180.0
    assert m.lat_edges[0] == -90.0 and m.lat_edges[-1] == 90.0
    np.testing.assert_allclose(np.diff(m.lon), 0.5)
    assert m.lon[0] == -179.75 and m.lat[0] == -89.75
    ds = m.to_xarray()
    assert ds["classes"].dims == ("lat", "lon") and ds["lon"].attrs["units"] == "degrees_east"

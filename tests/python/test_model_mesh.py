# SPDX-License-Identifier: GPL-3.0-or-later
"""Run.model_mesh: the arrays are the model files, node for node, triangle for triangle, boundary
list for boundary list, read back from the files `aquatoria mesh` writes (fort.14, hgrid.gr3 /
hgrid.ll and bctides.in, FESOM2's nod2d/elem2d/aux3d/obn), on the seed's reference run (a global
mesh: land loops only) and the North Sea (open segments, mainland pieces, islands). The numbers in
the files are printed shortest-round-trip, so equality is exact."""

import os

import numpy as np
import pytest

import aquatoria as aq


def read_fort14(path):
    """fort.14 / hgrid.gr3 as written: nodes (x, y, depth), 0-based triangles, and the boundary
    lists [(header count, flag or None, 0-based nodes, comment)] of the open and the land part."""
    with open(path) as f:
        lines = f.read().splitlines()
    ne, nn = (int(v) for v in lines[1].split()[:2])
    nodes = np.array([l.split()[1:4] for l in lines[2:2 + nn]], dtype=np.float64)
    assert [int(l.split()[0]) for l in lines[2:2 + nn]] == list(range(1, nn + 1))
    tri_lines = lines[2 + nn:2 + nn + ne]
    assert all(l.split()[1] == "3" for l in tri_lines)
    tri = np.array([l.split()[2:5] for l in tri_lines], dtype=np.int64) - 1
    k = 2 + nn + ne

    def lists(total_with_nodes):
        nonlocal k
        count = int(lines[k].split("!")[0])
        total = int(lines[k + 1].split("!")[0])
        k += 2
        out = []
        for _ in range(count):
            head, comment = lines[k].split("!", 1)
            words = head.split()
            n = int(words[0])
            flag = int(words[1]) if len(words) > 1 else None
            out.append((n, flag, np.array([int(v) - 1 for v in lines[k + 1:k + 1 + n]], dtype=np.int64),
                        comment.strip()))
            k += 1 + n
        assert sum(len(o[2]) for o in out) == total
        return out

    open_lists = lists(True)
    land_lists = lists(True)
    assert k == len(lines)
    return nodes, tri, open_lists, land_lists


@pytest.fixture(params=["seed", "north_sea"])
def pair(request, seed_cli, seed_run, north_sea_cli, north_sea_run):
    if request.param == "seed":
        return seed_cli, seed_run
    return north_sea_cli, north_sea_run


def check_lists(segments, lists):
    assert len(segments) == len(lists)
    for seg, (n, flag, nodes, comment) in zip(segments, lists):
        assert len(seg["nodes"]) == n
        np.testing.assert_array_equal(seg["nodes"], nodes)
        assert seg["flag"] == flag and seg["comment"] == comment
        if seg["closed"]:
            assert seg["nodes"][0] == seg["nodes"][-1]


@pytest.mark.parametrize("fmt,suffix", [("fort14", ".14"), ("schism", ".gr3"), ("gr3", ".ll")])
def test_fort14_and_gr3_are_the_files(pair, fmt, suffix):
    cli_run, run = pair
    m = run.model_mesh(fmt)
    assert m.format == ("schism" if fmt == "gr3" else fmt)
    nodes, tri, open_lists, land_lists = read_fort14(cli_run.path(suffix))
    assert m.nodes.shape == (len(nodes), 2) and m.triangles.shape == tri.shape
    np.testing.assert_array_equal(m.nodes, nodes[:, :2])
    np.testing.assert_array_equal(m.depth, nodes[:, 2])
    np.testing.assert_array_equal(m.triangles, tri)
    check_lists(m.open_segments, open_lists)
    check_lists(m.land_segments, land_lists)
    assert m.boundaries == m.open_segments + m.land_segments
    # the types the header comments (and the flags) say
    for seg in m.land_segments:
        assert seg["type"] in seg["comment"] and seg["type"] in ("mainland", "island")
        assert seg["closed"] == (seg["nodes"][0] == seg["nodes"][-1])
    assert all(s["type"] == "open" and not s["closed"] for s in m.open_segments)
    if fmt != "fort14" and m.open_segments:
        # SCHISM's land flags are 0 / 1 where fort.14 has IBTYPE 20 / 21
        assert {s["flag"] for s in m.land_segments} <= {0, 1}


def test_the_global_mesh_is_closed_and_the_regional_one_open(seed_run, north_sea_run):
    seed = seed_run.model_mesh("fort14")
    assert seed.open_segments == [] and len(seed.land_segments) == len(seed_run.model_mesh("fesom").land_segments)
    assert sum(s["type"] == "mainland" for s in seed.land_segments) == 1
    ns = north_sea_run.model_mesh("fort14")
    assert len(ns.open_segments) >= 1
    assert {s["type"] for s in ns.land_segments} == {"mainland", "island"}
    assert {s["flag"] for s in ns.land_segments} == {20, 21}
    # each open segment shares its end nodes with the mainland pieces beside it
    ends = {int(s["nodes"][0]) for s in ns.land_segments} | {int(s["nodes"][-1]) for s in ns.land_segments}
    for s in ns.open_segments:
        assert int(s["nodes"][0]) in ends and int(s["nodes"][-1]) in ends


def test_bctides_lists_the_open_segments(north_sea_cli, north_sea_run):
    m = north_sea_run.model_mesh("schism")
    with open(north_sea_cli.path("_bctides.in")) as f:
        lines = f.read().splitlines()
    k = [i for i, l in enumerate(lines) if "!nope" in l][0]
    assert int(lines[k].split()[0]) == len(m.open_segments)
    k += 1
    for seg in m.open_segments:
        n = int(lines[k].split()[0])
        nodes = [int(l.split("!node")[1]) - 1 for l in lines[k + 2:k + 2 + n]]
        np.testing.assert_array_equal(seg["nodes"], nodes)
        k += 2 + n


def test_fesom_is_the_files(pair):
    cli_run, run = pair
    m = run.model_mesh("fesom")
    nod = np.loadtxt(cli_run.path("_nod2d.out"), skiprows=1)
    np.testing.assert_array_equal(nod[:, 0], np.arange(1, len(nod) + 1))
    np.testing.assert_array_equal(m.nodes, nod[:, 1:3])
    np.testing.assert_array_equal(m.boundary_flag, nod[:, 3])
    elem = np.loadtxt(cli_run.path("_elem2d.out"), skiprows=1, dtype=np.int64)
    np.testing.assert_array_equal(m.triangles, elem - 1)
    with open(cli_run.path("_aux3d.out")) as f:
        values = [float(v) for v in f.read().split()]
    nl = int(values[0])
    np.testing.assert_array_equal(-np.array(values[1:1 + nl]), m.levels)
    np.testing.assert_array_equal(m.depth, values[1 + nl:])
    assert (m.depth <= 0).all()
    obn = cli_run.path("_obn.out")
    if os.path.exists(obn):
        v = np.loadtxt(obn, dtype=np.int64)
        assert v[0] == len(v) - 1
        np.testing.assert_array_equal(m.open_nodes, v[1:] - 1)
    else:
        assert len(m.open_nodes) == 0 and m.open_segments == []
    # the same cleaned mesh as fort.14, clockwise, with FESOM's bottom sign
    f14 = run.model_mesh("fort14")
    np.testing.assert_array_equal(m.nodes, f14.nodes)
    np.testing.assert_array_equal(m.triangles, f14.triangles[:, [0, 2, 1]])
    np.testing.assert_array_equal(m.depth, np.minimum(-f14.depth, 0.0))


def test_model_mesh_maps_into_the_geographic_mesh(pair):
    _, run = pair
    g = run.geographic_mesh
    m = run.model_mesh("fort14")
    lon = (g.nodes[m.geographic_node, 0] + 180.0) % 360.0 - 180.0
    np.testing.assert_array_equal(m.nodes[:, 0], lon)
    np.testing.assert_array_equal(m.nodes[:, 1], g.nodes[m.geographic_node, 1])
    np.testing.assert_array_equal(m.depth, g.depth[m.geographic_node])
    np.testing.assert_array_equal(m.geographic_node[m.triangles], g.triangles[m.geographic_triangle])
    # the cleaning dropped what the report says
    c = run.report["cleaning"]
    assert (len(m.nodes), len(m.triangles)) == (c["nodes"], c["triangles"])
    assert len(g.nodes) - len(m.nodes) == c["nodes_removed"]
    assert len(np.unique(m.geographic_node)) == len(m.nodes)


def test_three_meshes_with_names_that_say_what_they_are(seed_cli, seed_run):
    import json

    with open(seed_cli.path("_report.json")) as f:
        report = json.load(f)
    lattice = seed_run.lattice_mesh
    assert lattice.what == "lattice" and seed_run.geographic_mesh.what == "geographic"
    counts = report["mesh_counts"]
    assert (len(lattice.nodes), len(lattice.triangles), len(lattice.squares)) == (
        counts["nodes"], counts["triangles"], counts["squares"])
    g = report["geographic_mesh"]
    assert (len(seed_run.nodes), len(seed_run.triangles)) == (g["nodes"], g["triangles"])
    c = report["cleaning"]
    m = seed_run.model_mesh()
    assert (len(m.nodes), len(m.triangles)) == (c["nodes"], c["triangles"])
    # the seed run's meshes all differ: the pole cap adds nodes, the cleaning removes some
    assert len({len(lattice.nodes), len(seed_run.nodes), len(m.nodes)}) == 3
    np.testing.assert_array_equal(lattice.lattice_ij[:, 0], lattice._a["node_i"])
    assert (seed_run.geographic_mesh.lattice_ij[seed_run.geographic_mesh.node_flags & 32 > 0] == -1).all()


def test_regional_boundaries_show_the_open_segments(north_sea_cli, north_sea_run):
    import netCDF4

    b = north_sea_run.boundaries
    types = [s["type"] for s in b]
    assert "open" in types and "mainland" in types and "island" in types
    assert types == sorted(types, key=lambda t: t != "open")  # open segments first
    with netCDF4.Dataset(north_sea_cli.path(".nc")) as nc:
        nc.set_auto_mask(False)
        edges = nc["mesh_boundary_nodes"][...]
        etype = nc["mesh_boundary_type"][...]
    names = {0: "mainland", 1: "island", 2: "open"}
    typed = {(int(a), int(c)): names[int(t)] for (a, c), t in zip(edges, etype)}
    np.testing.assert_array_equal(north_sea_run.geographic_mesh.boundary_edge_type, etype)
    for s in b:
        n = s["nodes"]
        pairs = list(zip(n[:-1], n[1:])) + ([(n[-1], n[0])] if s["closed"] else [])
        assert all(typed[(int(x), int(y))] == s["type"] for x, y in pairs), s["type"]
    assert sum(len(s["nodes"]) - (0 if s["closed"] else 1) for s in b) == len(edges)


def test_model_mesh_refuses_what_it_cannot_give(seed_run):
    with pytest.raises(aq.ConfigError, match="unknown model format"):
        seed_run.model_mesh("gmsh")
    squares = aq.mesh(None, {"mesh.elements": "squares", "output.formats": ["msh"]})
    with pytest.raises(aq.ConfigError, match='mesh.elements = "squares"'):
        squares.model_mesh("fort14")


def test_a_river_inflow_is_a_land_boundary_of_fort14_and_an_open_one_of_hgrid(tmp_path):
    # A basin at 2..28°E × 2..18°N in land, a box to 30°E around it, and a river drawn from the
    # basin east out of the box: where it crosses the box's edge it is a river inflow (IBTYPE 22
    # in fort.14's land list; an open (flow) boundary in hgrid.gr3's open list).
    lon = -180.0 + (np.arange(1440) + 0.5) * 0.25
    lat = -90.0 + (np.arange(720) + 0.5) * 0.25
    z = np.full((720, 1440), 100.0, dtype=np.float32)
    z[np.ix_((lat > 2.0) & (lat < 18.0), (lon > 2.0) & (lon < 28.0))] = -800.0
    river = tmp_path / "river.geojson"
    river.write_text('{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": '
                     '{"name": "Test River", "width_m": 2000, "depth_m": 6}, "geometry": {"type": "LineString", '
                     '"coordinates": [[25.0, 10.0], [29.0, 10.2], [34.0, 11.0]]}}]}')
    run = aq.mesh(None, {"domain.box": [0.0, 30.0, 0.0, 20.0], "quadtree.step_deg": 1, "quadtree.levels": 2,
                         "mask.seeds": [[10.0, 10.0]], "mask.channels": str(river),
                         "output.formats": ["fort14", "schism", "ugrid"]}, raster=z, lon=lon, lat=lat)
    assert 3 in set(run.geographic_mesh.boundary_edge_type.tolist())
    assert [s["type"] for s in run.boundaries].count("river") == 1
    f14 = run.model_mesh("fort14")
    assert f14.open_segments == []
    rivers = [s for s in f14.land_segments if s["type"] == "river"]
    assert len(rivers) == 1 and rivers[0]["flag"] == 22 and not rivers[0]["open"]
    assert "river inflow" in rivers[0]["comment"] and len(rivers[0]["nodes"]) >= 3
    np.testing.assert_array_equal(f14.nodes[rivers[0]["nodes"], 0], 30.0)
    gr3 = run.model_mesh("schism")
    assert [s["type"] for s in gr3.open_segments] == ["river"]
    assert gr3.open_segments[0]["open"] and gr3.open_segments[0]["flag"] == 0
    assert gr3.open_segments[0]["comment"] == "open boundary 1 (river inflow)"
    np.testing.assert_array_equal(gr3.open_segments[0]["nodes"], rivers[0]["nodes"])
    assert all(s["type"] in ("mainland", "island") for s in gr3.land_segments)

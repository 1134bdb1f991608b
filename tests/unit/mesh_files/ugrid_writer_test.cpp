// SPDX-License-Identifier: GPL-3.0-or-later
// UGRID-1.0 writer: read the file back with the netCDF-C API and check conventions, topology
// attributes, connectivity rows, unique edges, seam-aware face centres, data and errors.
#include "mesh_files/ugrid_writer.hpp"

#include <gtest/gtest.h>
#include <netcdf.h>

#include <cmath>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "support/file_size_limit.hpp"
#include "support/io_test_mesh.hpp"
#include "support/msh_parse.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_mesh_files_ugrid_writer_test {
namespace {

// Minimal checked reader.
class Nc {
 public:
  explicit Nc(const std::filesystem::path& p) { ok(nc_open(p.c_str(), NC_NOWRITE, &id_)); }
  ~Nc() { nc_close(id_); }
  static void ok(int s) {
    if (s != NC_NOERR) throw std::runtime_error(nc_strerror(s));
  }
  [[nodiscard]] bool has_var(const std::string& name) const {
    int v = 0;
    return nc_inq_varid(id_, name.c_str(), &v) == NC_NOERR;
  }
  [[nodiscard]] int var(const std::string& name) const {
    int v = 0;
    ok(nc_inq_varid(id_, name.c_str(), &v));
    return v;
  }
  [[nodiscard]] std::size_t dim(const std::string& name) const {
    int d = 0;
    std::size_t len = 0;
    ok(nc_inq_dimid(id_, name.c_str(), &d));
    ok(nc_inq_dimlen(id_, d, &len));
    return len;
  }
  [[nodiscard]] std::string text(const std::string& var, const std::string& att) const {
    const int v = var.empty() ? NC_GLOBAL : this->var(var);
    std::size_t len = 0;
    ok(nc_inq_attlen(id_, v, att.c_str(), &len));
    std::string s(len, '\0');
    ok(nc_get_att_text(id_, v, att.c_str(), s.data()));
    return s;
  }
  [[nodiscard]] double number(const std::string& var, const std::string& att) const {
    double x = 0;
    ok(nc_get_att_double(id_, var.empty() ? NC_GLOBAL : this->var(var), att.c_str(), &x));
    return x;
  }
  [[nodiscard]] std::vector<long long> ints(const std::string& var) const {
    std::vector<long long> out(size(var));
    ok(nc_get_var_longlong(id_, this->var(var), out.data()));
    return out;
  }
  [[nodiscard]] std::vector<double> doubles(const std::string& var) const {
    std::vector<double> out(size(var));
    ok(nc_get_var_double(id_, this->var(var), out.data()));
    return out;
  }
  [[nodiscard]] std::size_t size(const std::string& var) const {
    int nd = 0, dims[NC_MAX_VAR_DIMS];
    ok(nc_inq_varndims(id_, this->var(var), &nd));
    ok(nc_inq_vardimid(id_, this->var(var), dims));
    std::size_t n = 1;
    for (int k = 0; k < nd; ++k) {
      std::size_t len = 0;
      ok(nc_inq_dimlen(id_, dims[k], &len));
      n *= len;
    }
    return n;
  }

 private:
  int id_ = -1;
};

TEST(UgridWriter, ConventionsAndTopologyAttributes) {
  testing::TempDir dir;
  const auto m = testing::tiny_mesh();
  const WriteStats st = write_ugrid(m, dir / "m.nc");
  EXPECT_EQ(st.nodes, 21);
  EXPECT_EQ(st.elements, 17);
  EXPECT_EQ(st.boundary_edges, 19);
  EXPECT_EQ(st.bytes, static_cast<std::int64_t>(std::filesystem::file_size(dir / "m.nc")));
  Nc nc(dir / "m.nc");
  EXPECT_EQ(nc.text("", "Conventions"), "CF-1.8 UGRID-1.0");
  EXPECT_FALSE(nc.text("", "title").empty());
  EXPECT_FALSE(nc.text("", "history").empty());
  EXPECT_FALSE(nc.text("", "source").empty());
  EXPECT_EQ(nc.text("mesh", "cf_role"), "mesh_topology");
  EXPECT_EQ(nc.number("mesh", "topology_dimension"), 2.0);
  EXPECT_EQ(nc.text("mesh", "node_coordinates"), "mesh_node_x mesh_node_y");
  EXPECT_EQ(nc.text("mesh", "face_node_connectivity"), "mesh_face_nodes");
  EXPECT_EQ(nc.text("mesh", "edge_node_connectivity"), "mesh_edge_nodes");
  EXPECT_EQ(nc.text("mesh", "boundary_node_connectivity"), "mesh_boundary_nodes");
  EXPECT_EQ(nc.text("mesh", "face_coordinates"), "mesh_face_x mesh_face_y");
  EXPECT_EQ(nc.text("mesh_face_nodes", "cf_role"), "face_node_connectivity");
  EXPECT_EQ(nc.number("mesh_face_nodes", "start_index"), 0.0);
  EXPECT_EQ(nc.text("mesh_node_x", "standard_name"), "longitude");
  EXPECT_EQ(nc.text("mesh_node_x", "units"), "degrees_east");
  EXPECT_EQ(nc.text("mesh_node_y", "standard_name"), "latitude");
  EXPECT_EQ(nc.text("mesh_node_y", "units"), "degrees_north");
  EXPECT_EQ(nc.text("crs", "grid_mapping_name"), "latitude_longitude");
  EXPECT_EQ(nc.dim("nMesh_node"), 21u);
  EXPECT_EQ(nc.dim("nMesh_face"), 17u);
  EXPECT_EQ(nc.dim("nMaxMesh_face_nodes"), 3u);
  EXPECT_EQ(nc.dim("nMesh_boundary"), 19u);
  EXPECT_EQ(nc.dim("nMesh_edge"), 35u);  // Euler: V - E + F = 3 discs
  EXPECT_FALSE(nc.has_var("rotated_pole"));
}

TEST(UgridWriter, ConnectivityRowsEdgesAndBoundary) {
  testing::TempDir dir;
  const auto m = testing::tiny_mesh();
  write_ugrid(m, dir / "m.nc");
  Nc nc(dir / "m.nc");
  const auto faces = nc.ints("mesh_face_nodes");
  ASSERT_EQ(faces.size(), 51u);
  for (std::size_t t = 0; t < 17; ++t)
    for (std::size_t a = 0; a < 3; ++a) EXPECT_EQ(faces[3 * t + a], m.triangles[t][a]) << t;
  // Row 9 is the first triangle of the seam-crossing square C: (15,2), (0,2), (0,3).
  EXPECT_EQ(m.node_i[faces[27]], 15);
  EXPECT_EQ(m.node_i[faces[28]], 0);
  EXPECT_EQ(m.node_i[faces[29]], 0);

  const auto edges = nc.ints("mesh_edge_nodes");
  std::set<std::pair<long long, long long>> unique;
  for (std::size_t e = 0; e < edges.size(); e += 2) {
    EXPECT_TRUE(unique.insert({std::min(edges[e], edges[e + 1]), std::max(edges[e], edges[e + 1])}).second)
        << "edge listed twice";
  }
  for (const auto& t : m.triangles)
    for (int a = 0; a < 3; ++a)
      EXPECT_TRUE(unique.count({std::min(t[a], t[(a + 1) % 3]), std::max(t[a], t[(a + 1) % 3])}));

  const auto bnd = nc.ints("mesh_boundary_nodes");
  ASSERT_EQ(bnd.size(), 38u);
  for (std::size_t e = 0; e < 19; ++e) {
    EXPECT_EQ(bnd[2 * e], m.boundary_edges[e][0]);
    EXPECT_EQ(bnd[2 * e + 1], m.boundary_edges[e][1]);
  }
  const auto loop = nc.ints("mesh_boundary_loop");
  EXPECT_EQ(loop[0], m.boundary_edge_loop[0]);
}

// The edges are made again while they are written, in chunks of 2^20 rows: over more than one
// chunk (the last one shorter) the file holds exactly the list made whole, in face order: the
// half-edge a -> b of a face when a < b or when it is a boundary edge (the top row's edges run
// towards smaller ids, so they come from the boundary set).
TEST(UgridWriter, EdgesWrittenInChunksAreTheWholeListInFaceOrder) {
  testing::TempDir dir;
  const Lattice lat = Lattice::make(1.0, 2, -180.0);  // nx = 1440
  const auto m = testing::regular_band_mesh(lat, 100, 480);
  std::set<std::pair<NodeId, NodeId>> boundary;
  for (const auto& e : m.boundary_edges) boundary.insert({e[0], e[1]});
  std::vector<long long> want;
  for (const auto& t : m.triangles)
    for (int a = 0; a < 3; ++a) {
      const NodeId u = t[a], v = t[(a + 1) % 3];
      if (u < v || boundary.count({u, v}) > 0) {
        want.push_back(u);
        want.push_back(v);
      }
    }
  ASSERT_GT(want.size() / 2, std::size_t{1} << 20);  // more than one chunk
  ASSERT_NE(want.size() / 2 % (std::size_t{1} << 20), 0u);
  UgridOptions o;
  o.deflate = 0;
  write_ugrid(m, dir / "m.nc", o);
  Nc nc(dir / "m.nc");
  EXPECT_EQ(nc.dim("nMesh_edge"), want.size() / 2);
  EXPECT_TRUE(nc.ints("mesh_edge_nodes") == want);
}

TEST(UgridWriter, NodeDataFlagsAndFaceLevels) {
  testing::TempDir dir;
  const auto m = testing::tiny_mesh();
  write_ugrid(m, dir / "m.nc");
  Nc nc(dir / "m.nc");
  EXPECT_EQ(nc.text("depth", "standard_name"), "sea_floor_depth_below_geoid");
  EXPECT_EQ(nc.text("depth", "units"), "m");
  EXPECT_NE(nc.text("depth", "long_name").find("positive down"), std::string::npos);
  EXPECT_EQ(nc.text("depth", "mesh"), "mesh");
  EXPECT_EQ(nc.text("depth", "location"), "node");
  const auto depth = nc.doubles("depth");
  for (std::size_t n = 0; n < 21; ++n) EXPECT_EQ(depth[n], -m.depth_m[n]);
  EXPECT_GT(depth[0], 0.0);
  const auto lon = nc.doubles("mesh_node_x");
  EXPECT_EQ(lon, m.lon_deg);
  const auto flags = nc.ints("node_flags");
  for (std::size_t n = 0; n < 21; ++n) EXPECT_EQ(flags[n], m.node_flags[n]);
  EXPECT_EQ(nc.text("node_flags", "flag_meanings"),
            "boundary midside_hanging_node centre_node pole seam pole_cap_node");
  EXPECT_EQ(nc.text("level", "location"), "face");
  const auto level = nc.ints("level");
  for (std::size_t t = 0; t < 17; ++t) EXPECT_EQ(level[t], m.triangle_level[t]);
}

TEST(UgridWriter, FaceCentresAndBoundsAreSeamAware) {
  testing::TempDir dir;
  write_ugrid(testing::tiny_mesh(), dir / "m.nc");
  Nc nc(dir / "m.nc");
  const auto fx = nc.doubles("mesh_face_x");
  const auto fy = nc.doubles("mesh_face_y");
  const auto bx = nc.doubles("mesh_face_x_bnds");
  EXPECT_EQ(nc.text("mesh_face_x", "bounds"), "mesh_face_x_bnds");
  // Triangle 9: (15,2), (16,2), (16,3) in the plane: centre I = 15.667, J = 2.333.
  EXPECT_NEAR(fx[9], -180.0 + 47.0 / 3.0 * 22.5, 1e-12);
  EXPECT_NEAR(fy[9], -90.0 + 7.0 / 3.0 * 22.5, 1e-12);
  EXPECT_EQ(bx[27], 157.5);
  EXPECT_EQ(bx[28], 180.0);
  EXPECT_EQ(bx[29], 180.0);
  for (std::size_t f = 0; f < 17; ++f) {
    EXPECT_GE(fx[f], -180.0);
    EXPECT_LT(fx[f], 180.0);
    for (std::size_t a = 0; a < 3; ++a) EXPECT_LE(std::abs(bx[3 * f + a] - fx[f]), 45.0) << f;
  }
}

TEST(UgridWriter, SquaresArePolygonsWithHangingNodes) {
  testing::TempDir dir;
  const auto m = testing::tiny_mesh(false);
  UgridOptions o;
  o.elements = ElementKinds::kSquares;
  write_ugrid(m, dir / "q.nc", o);
  Nc nc(dir / "q.nc");
  EXPECT_EQ(nc.dim("nMesh_face"), 7u);
  EXPECT_EQ(nc.dim("nMaxMesh_face_nodes"), 5u);
  const auto faces = nc.ints("mesh_face_nodes");
  // Square A: SW, SE, hanging node (4,3), NE, NW.
  EXPECT_EQ(faces[0], m.squares[0][0]);
  EXPECT_EQ(faces[1], m.squares[0][1]);
  EXPECT_EQ(faces[2], m.square_midside[0][1]);
  EXPECT_EQ(faces[3], m.squares[0][2]);
  EXPECT_EQ(faces[4], m.squares[0][3]);
  EXPECT_EQ(faces[9], -1);  // B1 has 4 nodes: padded with the fill value
  EXPECT_EQ(nc.dim("nMesh_edge"), 20u + 7u - 3u);
  const auto by = nc.doubles("mesh_face_y_bnds");
  EXPECT_EQ(by[9], by[8]);  // bounds padded by repeating the last corner

  o.elements = ElementKinds::kBoth;
  write_ugrid(testing::tiny_mesh(), dir / "b.nc", o);
  Nc both(dir / "b.nc");
  EXPECT_EQ(both.text("mesh_squares", "cf_role"), "mesh_topology");
  EXPECT_EQ(both.text("mesh_squares", "node_coordinates"), "mesh_node_x mesh_node_y");
  EXPECT_EQ(both.dim("nMesh_face"), 17u);
  EXPECT_EQ(both.dim("nMesh_squares_face"), 7u);
  EXPECT_EQ(both.text("level_squares", "mesh"), "mesh_squares");
}

TEST(UgridWriter, RotatedPoleIsDescribed) {
  testing::TempDir dir;
  const auto m = testing::tiny_mesh(true, {true, -44.858333, 78.141667});
  write_ugrid(m, dir / "r.nc");
  Nc nc(dir / "r.nc");
  EXPECT_EQ(nc.text("rotated_pole", "grid_mapping_name"), "rotated_latitude_longitude");
  EXPECT_DOUBLE_EQ(nc.number("rotated_pole", "grid_north_pole_latitude"), 78.141667);
  EXPECT_DOUBLE_EQ(nc.number("rotated_pole", "grid_north_pole_longitude"), -44.858333);
  EXPECT_EQ(nc.number("rotated_pole", "north_pole_grid_longitude"), 180.0);
  EXPECT_EQ(nc.text("mesh_node_rlon", "standard_name"), "grid_longitude");
  EXPECT_EQ(nc.doubles("mesh_node_rlat"), m.rlat_deg);
  EXPECT_EQ(nc.doubles("mesh_node_x"), m.lon_deg);
  EXPECT_EQ(nc.text("depth", "grid_mapping"), "rotated_pole");
  for (const double x : nc.doubles("mesh_face_x")) {
    EXPECT_GE(x, -180.0);
    EXPECT_LT(x, 180.0);
  }
}

TEST(UgridWriter, SameBytesEveryRun) {
  testing::TempDir dir;
  const auto m = testing::tiny_mesh();
  write_ugrid(m, dir / "1.nc");
  write_ugrid(m, dir / "2.nc");
  EXPECT_EQ(testing::read_file_bytes((dir / "1.nc").string()), testing::read_file_bytes((dir / "2.nc").string()));
}

TEST(UgridWriter, UnwritablePathThrowsOutputErrorNamingIt) {
  testing::TempDir dir;
  std::ofstream(dir / "plain_file") << "x";
  const auto bad = dir / "plain_file" / "m.nc";
  try {
    write_ugrid(testing::tiny_mesh(), bad);
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
}

TEST(UgridWriter, FullDiskThrowsOutputErrorNamingThePath) {
  testing::TempDir dir;
  const auto p = dir / "big.nc";
  const auto m = testing::band_mesh(Lattice::make(4.0, 1, -180.0), 10, 80);
  testing::FileSizeLimit limit(64 * 1024);
  try {
    write_ugrid(m, p);
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
  }
}

TEST(UgridWriter, InconsistentBoundaryIsAnInternalError) {
  testing::TempDir dir;
  auto m = testing::tiny_mesh();
  m.boundary_edges.pop_back();
  m.boundary_edge_loop.pop_back();
  EXPECT_THROW(write_ugrid(m, dir / "x.nc"), InternalError);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.nc"));
}

}  // namespace
}  // namespace aq::io::unit_mesh_files_ugrid_writer_test

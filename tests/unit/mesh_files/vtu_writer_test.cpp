// SPDX-License-Identifier: GPL-3.0-or-later
// VTU writer: decode the appended raw arrays by their declared offsets and check counts, pole
// merging, cell types, coordinates, data and errors.
#include "mesh_files/vtu_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <regex>

#include "core/error.hpp"
#include "support/file_size_limit.hpp"
#include "support/io_test_mesh.hpp"
#include "support/msh_parse.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_mesh_files_vtu_writer_test {
namespace {

struct Vtu {
  std::int64_t points = 0, cells = 0;
  std::map<std::string, std::string> arrays;  // name -> payload bytes
  std::map<std::string, std::string> types;
  template <typename T>
  std::vector<T> get(const std::string& name) const {
    const std::string& b = arrays.at(name);
    std::vector<T> v(b.size() / sizeof(T));
    std::memcpy(v.data(), b.data(), b.size());
    return v;
  }
};

Vtu read_vtu(const std::filesystem::path& p) {
  const std::string s = testing::read_file_bytes(p.string());
  Vtu v;
  std::smatch m;
  const std::string head = s.substr(0, s.find("<AppendedData"));
  EXPECT_TRUE(std::regex_search(head, m, std::regex("NumberOfPoints=\"(\\d+)\" NumberOfCells=\"(\\d+)\"")));
  v.points = std::stoll(m[1]);
  v.cells = std::stoll(m[2]);
  const std::size_t data = s.find('_', s.find("<AppendedData")) + 1;
  const std::regex arr("<DataArray type=\"(\\w+)\" Name=\"(\\w+)\"[^>]* offset=\"(\\d+)\"/>");
  for (auto it = std::sregex_iterator(head.begin(), head.end(), arr); it != std::sregex_iterator(); ++it) {
    const std::size_t off = data + std::stoull((*it)[3]);
    std::uint64_t n = 0;
    std::memcpy(&n, s.data() + off, 8);
    v.arrays[(*it)[2]] = s.substr(off + 8, n);
    v.types[(*it)[2]] = (*it)[1];
  }
  EXPECT_NE(s.find("</AppendedData>\n</VTKFile>\n"), std::string::npos);
  return v;
}

TEST(VtuWriter, PoleRowMergedAndDegenerateTrianglesDropped) {
  testing::TempDir dir;
  const WriteStats st = write_vtu(testing::tiny_mesh(), dir / "m.vtu");
  EXPECT_EQ(st.merged_pole_nodes, 2);
  EXPECT_EQ(st.dropped_elements, 2);
  EXPECT_EQ(st.nodes, 19);
  EXPECT_EQ(st.elements, 15);
  const Vtu v = read_vtu(dir / "m.vtu");
  EXPECT_EQ(v.points, 19);
  EXPECT_EQ(v.cells, 15);
  const auto pts = v.get<double>("Points");
  ASSERT_EQ(pts.size(), 57u);
  int north = 0;
  for (std::size_t k = 0; k < 19; ++k) {
    EXPECT_NEAR(std::hypot(pts[3 * k], pts[3 * k + 1], pts[3 * k + 2]), 1.0, 1e-15);
    north += pts[3 * k + 2] > 1.0 - 1e-12 ? 1 : 0;
  }
  EXPECT_EQ(north, 1);
  const auto conn = v.get<std::int64_t>("connectivity");
  const auto offs = v.get<std::int64_t>("offsets");
  const auto types = v.get<std::uint8_t>("types");
  ASSERT_EQ(conn.size(), 45u);
  ASSERT_EQ(offs.size(), 15u);
  EXPECT_EQ(offs.back(), 45);
  for (const auto t : types) EXPECT_EQ(t, 5);
  for (const auto c : conn) {
    EXPECT_GE(c, 0);
    EXPECT_LT(c, 19);
  }
  EXPECT_EQ(v.types.at("connectivity"), "Int64");
}

TEST(VtuWriter, PointAndCellData) {
  testing::TempDir dir;
  const auto m = testing::tiny_mesh();
  write_vtu(m, dir / "m.vtu");
  const Vtu v = read_vtu(dir / "m.vtu");
  const auto depth = v.get<double>("depth_m");
  const auto flags = v.get<std::uint8_t>("flags");
  const auto lat = v.get<double>("lat_deg");
  ASSERT_EQ(depth.size(), 19u);
  // No pole nodes before the pole row: the first 18 points are mesh nodes 0..17, in order.
  for (std::size_t n = 0; n < 18; ++n) {
    EXPECT_EQ(depth[n], -m.depth_m[n]);
    EXPECT_EQ(flags[n], m.node_flags[n]);
    EXPECT_EQ(lat[n], m.lat_deg[n]);
  }
  EXPECT_EQ(lat[18], 90.0);
  EXPECT_TRUE(flags[18] & mesh::kNodePole);
  const auto level = v.get<std::uint8_t>("level");
  ASSERT_EQ(level.size(), 15u);
  for (std::size_t c = 0; c < 15; ++c) EXPECT_EQ(level[c], c < 5 ? 0 : 1);
  EXPECT_EQ(v.arrays.count("kind"), 0u);
}

TEST(VtuWriter, SquaresAreQuadsOrPolygonsWithHangingNodes) {
  testing::TempDir dir;
  VtuOptions o;
  o.elements = ElementKinds::kSquares;
  const WriteStats st = write_vtu(testing::tiny_mesh(false), dir / "q.vtu", o);
  EXPECT_EQ(st.dropped_elements, 0);
  const Vtu v = read_vtu(dir / "q.vtu");
  const auto types = v.get<std::uint8_t>("types");
  ASSERT_EQ(types.size(), 7u);
  EXPECT_EQ(types[0], 7);  // A: polygon with its hanging node
  for (std::size_t c = 1; c < 5; ++c) EXPECT_EQ(types[c], 9);
  EXPECT_EQ(types[5], 5);  // P, P2 lose a corner at the pole
  EXPECT_EQ(types[6], 5);
  EXPECT_EQ(v.get<std::int64_t>("offsets")[0], 5);

  o.elements = ElementKinds::kBoth;
  write_vtu(testing::tiny_mesh(), dir / "b.vtu", o);
  const Vtu b = read_vtu(dir / "b.vtu");
  EXPECT_EQ(b.cells, 22);
  const auto kind = b.get<std::uint8_t>("kind");
  EXPECT_EQ(kind[0], 0);
  EXPECT_EQ(kind[21], 1);
}

TEST(VtuWriter, Wgs84CoordinatesInMetres) {
  testing::TempDir dir;
  VtuOptions o;
  o.coordinates = VtuCoordinates::kWgs84;
  write_vtu(testing::tiny_mesh(), dir / "w.vtu", o);
  const auto pts = read_vtu(dir / "w.vtu").get<double>("Points");
  EXPECT_NEAR(pts[3 * 18 + 2], 6356752.314245, 1e-3);  // North pole: the polar radius
  const double r = std::hypot(pts[0], pts[1], pts[2]);
  EXPECT_GT(r, 6356752.0);
  EXPECT_LT(r, 6378137.1);
  EXPECT_EQ(parse_name<VtuCoordinates>("sphere"), VtuCoordinates::kUnitSphere);
  EXPECT_FALSE(parse_name<VtuCoordinates>("ecef").has_value());
}

TEST(VtuWriter, SameBytesEveryRun) {
  testing::TempDir dir;
  const auto m = testing::tiny_mesh();
  write_vtu(m, dir / "1.vtu");
  write_vtu(m, dir / "2.vtu");
  EXPECT_EQ(testing::read_file_bytes((dir / "1.vtu").string()), testing::read_file_bytes((dir / "2.vtu").string()));
}

TEST(VtuWriter, UnwritableAndFullDiskThrowOutputErrorNamingThePath) {
  testing::TempDir dir;
  std::ofstream(dir / "plain_file") << "x";
  const auto bad = dir / "plain_file" / "m.vtu";
  try {
    write_vtu(testing::tiny_mesh(), bad);
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
  const auto big = dir / "big.vtu";
  const auto m = testing::band_mesh(Lattice::make(4.0, 1, -180.0), 10, 80);
  testing::FileSizeLimit limit(64 * 1024);
  EXPECT_THROW(write_vtu(m, big), OutputError);
}

}  // namespace
}  // namespace aq::io::unit_mesh_files_vtu_writer_test

// SPDX-License-Identifier: GPL-3.0-or-later
// Gmsh MSH 4.1 writer: parse the written file back (ASCII and binary) with an independent reader
// and check counts, seam duplication, $Periodic pairs, data views, pole merging in 3-D, errors.
#include "mesh_files/msh_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>

#include "core/error.hpp"
#include "support/file_size_limit.hpp"
#include "support/io_test_mesh.hpp"
#include "support/msh_parse.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_mesh_files_msh_writer_test {
namespace {

using testing::MshFile;

constexpr double kPix = 22.5;  // pixel of the tiny lattice, degrees

MshFile write_and_parse(const mesh::Mesh& m, const MshOptions& o, const std::filesystem::path& p,
                        WriteStats* stats = nullptr) {
  const WriteStats s = write_msh(m, p, o);
  EXPECT_EQ(s.bytes, static_cast<std::int64_t>(std::filesystem::file_size(p)));
  if (stats != nullptr) *stats = s;
  return testing::parse_msh(p.string());
}

double signed_area(const MshFile& f, const MshFile::Element& e) {
  const auto& a = f.nodes.at(e.nodes[0]);
  const auto& b = f.nodes.at(e.nodes[1]);
  const auto& c = f.nodes.at(e.nodes[2]);
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

TEST(MshWriter, AsciiPlaneTrianglesCountsSectionsAndPhysicals) {
  testing::TempDir dir;
  WriteStats st;
  const MshFile f = write_and_parse(testing::tiny_mesh(), {}, dir / "m.msh", &st);
  EXPECT_FALSE(f.binary);
  EXPECT_EQ(f.version, "4.1");
  EXPECT_EQ(f.sections, (std::vector<std::string>{"MeshFormat", "PhysicalNames", "Entities", "Nodes", "Elements",
                                                  "Periodic", "NodeData", "ElementData"}));
  EXPECT_EQ(f.nodes.size(), 23u);  // 21 nodes + 2 seam duplicates
  EXPECT_EQ(f.nodes_declared, 23u);
  EXPECT_EQ(f.min_node, 1u);
  EXPECT_EQ(f.max_node, 23u);
  EXPECT_EQ(f.count_type(2), 17u);
  EXPECT_EQ(f.count_type(3), 0u);
  EXPECT_EQ(f.count_type(1), 19u);
  EXPECT_EQ(f.elements_declared, 36u);
  EXPECT_EQ(st.nodes, 23);
  EXPECT_EQ(st.elements, 17);
  EXPECT_EQ(st.boundary_edges, 19);
  EXPECT_EQ(st.seam_duplicates, 2);
  EXPECT_EQ(st.dropped_elements, 0);

  ASSERT_EQ(f.physical_names.size(), 2u);
  EXPECT_EQ(f.physical_names[0].first, std::make_pair(1, 1));
  EXPECT_EQ(f.physical_names[0].second, "coast");
  EXPECT_EQ(f.physical_names[1].first, std::make_pair(2, 2));
  EXPECT_EQ(f.physical_names[1].second, "ocean");
  EXPECT_EQ(f.entity_counts, (std::array<std::size_t, 4>{0, 3, 1, 0}));
  EXPECT_EQ(f.entity_physicals.at({2, 1}), std::vector<int>{2});
  EXPECT_EQ(f.entity_physicals.at({1, 1}), std::vector<int>{1});
  EXPECT_TRUE(f.entity_physicals.at({1, 2}).empty());
  // Element tags 1..36 in order, triangles in surface 1, lines in curve 1.
  for (std::size_t k = 0; k < f.elements.size(); ++k) {
    EXPECT_EQ(f.elements[k].tag, k + 1);
    EXPECT_EQ(f.elements[k].entity, 1);
  }
}

TEST(MshWriter, PlaneElementsAreAnticlockwiseAndNeverSpanTheSeam) {
  testing::TempDir dir;
  const MshFile f = write_and_parse(testing::tiny_mesh(), {}, dir / "m.msh");
  for (const auto& e : f.elements) {
    double lo = 1e9, hi = -1e9;
    for (const auto n : e.nodes) {
      lo = std::min(lo, f.nodes.at(n)[0]);
      hi = std::max(hi, f.nodes.at(n)[0]);
      EXPECT_EQ(f.nodes.at(n)[2], 0.0);
    }
    EXPECT_LE(hi - lo, 2 * kPix) << "element " << e.tag;
    EXPECT_GE(lo, -180.0);
    EXPECT_LE(hi, 180.0);
    if (e.type == 2) {
      EXPECT_GT(signed_area(f, e), 0.0) << "triangle " << e.tag;
    }
  }
  // The seam-crossing square C (I 15..16, J 2..3) gives two triangles reaching x = 180.
  int at_180 = 0;
  for (const auto& e : f.elements)
    if (e.type == 2)
      for (const auto n : e.nodes) at_180 += f.nodes.at(n)[0] == 180.0 ? 1 : 0;
  EXPECT_EQ(at_180, 3);  // (SW, SE', NE') and (SW, NE', NW)
}

TEST(MshWriter, PeriodicLinksEachDuplicateToItsOriginal) {
  testing::TempDir dir;
  const MshFile f = write_and_parse(testing::tiny_mesh(), {}, dir / "m.msh");
  ASSERT_EQ(f.periodic.size(), 1u);
  const auto& p = f.periodic[0];
  EXPECT_EQ(p.dim, 1);
  EXPECT_EQ(p.slave, 3);
  EXPECT_EQ(p.master, 2);
  ASSERT_EQ(p.affine.size(), 16u);
  EXPECT_EQ(p.affine[3], 360.0);
  EXPECT_EQ(p.affine[0] + p.affine[5] + p.affine[10] + p.affine[15], 4.0);
  ASSERT_EQ(p.pairs.size(), 2u);
  std::set<double> ys;
  for (const auto& [slave, master] : p.pairs) {
    const auto& s = f.nodes.at(slave);
    const auto& m = f.nodes.at(master);
    EXPECT_EQ(m[0], -180.0);
    EXPECT_EQ(s[0], m[0] + 360.0);
    EXPECT_EQ(s[1], m[1]);
    EXPECT_EQ(f.node_entity.at(slave), std::make_pair(1, 3));
    EXPECT_EQ(f.node_entity.at(master), std::make_pair(1, 2));
    EXPECT_EQ(f.node_data.at("depth_m").at(slave), f.node_data.at("depth_m").at(master));
    ys.insert(m[1]);
  }
  EXPECT_EQ(ys, (std::set<double>{-90.0 + 2 * kPix, -90.0 + 3 * kPix}));
}

TEST(MshWriter, NodeDepthPositiveDownAndElementLevels) {
  testing::TempDir dir;
  const MshFile f = write_and_parse(testing::tiny_mesh(), {}, dir / "m.msh");
  const auto& depth = f.node_data.at("depth_m");
  ASSERT_EQ(depth.size(), f.nodes.size());
  for (const auto& [tag, x] : f.nodes) {
    const auto i = static_cast<std::int64_t>(std::lround((x[0] + 180.0) / kPix)) % 16;
    const auto j = static_cast<std::int64_t>(std::lround((x[1] + 90.0) / kPix));
    EXPECT_DOUBLE_EQ(depth.at(tag), -testing::test_elevation_m(i, j)) << "node " << tag;
    EXPECT_GT(depth.at(tag), 0.0);
  }
  const auto& level = f.element_data.at("level");
  ASSERT_EQ(level.size(), 17u);
  for (std::size_t t = 1; t <= 17; ++t) EXPECT_EQ(level.at(t), t <= 5 ? 0.0 : 1.0) << "triangle " << t;
}

TEST(MshWriter, CoastLinesFollowTheWetSideAcrossTheSeam) {
  testing::TempDir dir;
  const MshFile f = write_and_parse(testing::tiny_mesh(), {}, dir / "m.msh");
  int seam_lines = 0;
  for (const auto& e : f.elements) {
    if (e.type != 1) continue;
    const auto& a = f.nodes.at(e.nodes[0]);
    const auto& b = f.nodes.at(e.nodes[1]);
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    EXPECT_LE(len, 2 * kPix + 1e-12);
    EXPECT_GT(len, 0.0);
    if (a[0] == 180.0 || b[0] == 180.0) ++seam_lines;
  }
  EXPECT_EQ(seam_lines, 2);  // (15,2)->(16,2) and (16,3)->(15,3)
}

TEST(MshWriter, BinaryHasTheSameContentAsAscii) {
  testing::TempDir dir;
  const auto m = testing::tiny_mesh();
  const MshFile a = write_and_parse(m, {}, dir / "a.msh");
  MshOptions o;
  o.binary = true;
  const MshFile b = write_and_parse(m, o, dir / "b.msh");
  EXPECT_TRUE(b.binary);
  EXPECT_EQ(a.sections, b.sections);
  EXPECT_EQ(a.physical_names, b.physical_names);
  EXPECT_EQ(a.entity_physicals, b.entity_physicals);
  EXPECT_EQ(a.entity_boxes, b.entity_boxes);
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.node_entity, b.node_entity);
  ASSERT_EQ(a.elements.size(), b.elements.size());
  for (std::size_t k = 0; k < a.elements.size(); ++k) {
    EXPECT_EQ(a.elements[k].tag, b.elements[k].tag);
    EXPECT_EQ(a.elements[k].type, b.elements[k].type);
    EXPECT_EQ(a.elements[k].nodes, b.elements[k].nodes);
  }
  ASSERT_EQ(b.periodic.size(), 1u);
  EXPECT_EQ(a.periodic[0].pairs, b.periodic[0].pairs);
  EXPECT_EQ(a.periodic[0].affine, b.periodic[0].affine);
  EXPECT_EQ(a.node_data, b.node_data);
  EXPECT_EQ(a.element_data, b.element_data);
}

// A mesh large enough that the binary records are filled by all threads in several batches
// (and the file written in several chunks): the same content as the ASCII file.
TEST(MshWriter, BinaryOfALargeMeshHasTheSameContentAsAscii) {
  testing::TempDir dir;
  const auto m = testing::band_mesh(Lattice::make(1.0, 3, -180.0), 700, 800);
  ASSERT_GT(m.triangle_count(), std::int64_t{1} << 19);
  const MshFile a = write_and_parse(m, {}, dir / "a.msh");
  MshOptions o;
  o.binary = true;
  const MshFile b = write_and_parse(m, o, dir / "b.msh");
  EXPECT_EQ(a.nodes, b.nodes);
  ASSERT_EQ(a.elements.size(), b.elements.size());
  std::size_t differ = 0;
  for (std::size_t k = 0; k < a.elements.size(); ++k)
    differ += a.elements[k].tag != b.elements[k].tag || a.elements[k].type != b.elements[k].type ||
                      a.elements[k].nodes != b.elements[k].nodes
                  ? 1
                  : 0;
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(a.node_data, b.node_data);
  EXPECT_EQ(a.element_data, b.element_data);
}

TEST(MshWriter, SphereMergesPoleNodesAndDropsDegenerateTriangles) {
  testing::TempDir dir;
  MshOptions o;
  o.coordinates = MshCoordinates::kSphere;
  WriteStats st;
  const MshFile f = write_and_parse(testing::tiny_mesh(), o, dir / "s.msh", &st);
  EXPECT_EQ(f.nodes.size(), 19u);  // 21 - 2 merged pole nodes, no duplicates
  EXPECT_EQ(f.count_type(2), 15u);
  EXPECT_EQ(f.count_type(1), 17u);  // two coast edges along the pole row vanish
  EXPECT_TRUE(f.periodic.empty());
  EXPECT_EQ(st.merged_pole_nodes, 2);
  EXPECT_EQ(st.dropped_elements, 2);
  EXPECT_EQ(st.seam_duplicates, 0);
  int poles = 0;
  for (const auto& [tag, x] : f.nodes) {
    EXPECT_NEAR(std::hypot(x[0], x[1], x[2]), 1.0, 1e-15);
    poles += x[2] > 1.0 - 1e-12 ? 1 : 0;
  }
  EXPECT_EQ(poles, 1);
  for (const auto& e : f.elements) {
    if (e.type != 2) continue;
    const auto& a = f.nodes.at(e.nodes[0]);
    const auto& b = f.nodes.at(e.nodes[1]);
    const auto& c = f.nodes.at(e.nodes[2]);
    const std::array<double, 3> u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double outward =
        (u[1] * v[2] - u[2] * v[1]) * a[0] + (u[2] * v[0] - u[0] * v[2]) * a[1] + (u[0] * v[1] - u[1] * v[0]) * a[2];
    EXPECT_GT(outward, 0.0) << "triangle " << e.tag << " is not anticlockwise seen from outside";
  }
  EXPECT_EQ(f.node_data.at("depth_m").size(), 19u);
  EXPECT_EQ(f.element_data.at("level").size(), 15u);
}

TEST(MshWriter, SquaresAsQuadsAndBothKindsInTwoSurfaces) {
  testing::TempDir dir;
  MshOptions o;
  o.elements = ElementKinds::kSquares;
  const MshFile q = write_and_parse(testing::tiny_mesh(false), o, dir / "q.msh");
  EXPECT_EQ(q.count_type(3), 7u);
  EXPECT_EQ(q.count_type(2), 0u);
  EXPECT_EQ(q.nodes.size(), 20u + 2u);  // no centre node without triangles
  for (const auto& e : q.elements)
    if (e.type == 3) {
      EXPECT_GT(signed_area(q, e), 0.0);
    }

  o.elements = ElementKinds::kBoth;
  const MshFile b = write_and_parse(testing::tiny_mesh(), o, dir / "b.msh");
  EXPECT_EQ(b.count_type(2), 17u);
  EXPECT_EQ(b.count_type(3), 7u);
  ASSERT_EQ(b.physical_names.size(), 3u);
  EXPECT_EQ(b.physical_names[2].second, "ocean_squares");
  EXPECT_EQ(b.entity_physicals.at({2, 2}), std::vector<int>{3});
  for (const auto& e : b.elements) {
    if (e.type == 3) {
      EXPECT_EQ(e.entity, 2);
    }
    if (e.type == 2) {
      EXPECT_EQ(e.entity, 1);
    }
  }
  EXPECT_EQ(b.element_data.at("level").size(), 24u);

  o.coordinates = MshCoordinates::kSphere;
  o.elements = ElementKinds::kSquares;
  const MshFile s = write_and_parse(testing::tiny_mesh(false), o, dir / "s.msh");
  EXPECT_EQ(s.count_type(3), 5u);  // P and P2 become triangles at the pole
  EXPECT_EQ(s.count_type(2), 2u);
}

TEST(MshWriter, RotatedPlaneCarriesGeographicCoordinates) {
  testing::TempDir dir;
  mesh::RotationInfo rot{true, -44.858333, 78.141667};
  const auto m = testing::tiny_mesh(true, rot);
  const MshFile f = write_and_parse(m, {}, dir / "r.msh");
  ASSERT_TRUE(f.node_data.count("lon_deg"));
  ASSERT_TRUE(f.node_data.count("lat_deg"));
  EXPECT_DOUBLE_EQ(f.node_data.at("lon_deg").at(1), m.lon_deg[0]);
  EXPECT_DOUBLE_EQ(f.node_data.at("lat_deg").at(21), m.lat_deg[20]);
  EXPECT_DOUBLE_EQ(f.nodes.at(1)[0], m.lattice.lon_of(m.node_i[0]));  // plane = lattice coordinates
}

TEST(MshWriter, SameBytesEveryRun) {
  testing::TempDir dir;
  const auto m = testing::tiny_mesh();
  for (const bool binary : {false, true}) {
    MshOptions o;
    o.binary = binary;
    write_msh(m, dir / "1.msh", o);
    write_msh(m, dir / "2.msh", o);
    EXPECT_EQ(testing::read_file_bytes((dir / "1.msh").string()), testing::read_file_bytes((dir / "2.msh").string()));
  }
}

TEST(MshWriter, UnwritablePathThrowsOutputErrorNamingIt) {
  testing::TempDir dir;
  std::ofstream(dir / "plain_file") << "x";
  const auto bad = dir / "plain_file" / "m.msh";  // parent is not a directory
  try {
    write_msh(testing::tiny_mesh(), bad);
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
}

TEST(MshWriter, FullDiskThrowsOutputErrorNamingThePath) {
  testing::TempDir dir;
  const auto p = dir / "big.msh";
  MshOptions o;
  o.binary = true;
  const auto m = testing::band_mesh(Lattice::make(4.0, 1, -180.0), 10, 80);  // a few MB
  testing::FileSizeLimit limit(64 * 1024);
  try {
    write_msh(m, p, o);
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(p.string()), std::string::npos) << what;
    EXPECT_NE(what.find("too large"), std::string::npos) << what;  // EFBIG, as ENOSPC would be reported
  }
}

TEST(MshWriter, TrianglesAskedFromASquaresOnlyMeshIsAnInternalError) {
  testing::TempDir dir;
  EXPECT_THROW(write_msh(testing::tiny_mesh(false), dir / "x.msh"), InternalError);
}

}  // namespace
}  // namespace aq::io::unit_mesh_files_msh_writer_test

// SPDX-License-Identifier: GPL-3.0-or-later
// ADCIRC fort.14 and plain-text writers: header counts, node and element lines, land
// boundaries (IBTYPE rule, closed loops), text sections, determinism and errors.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "mesh_files/fort14_writer.hpp"
#include "mesh_files/text_writer.hpp"
#include "support/file_size_limit.hpp"
#include "support/io_test_mesh.hpp"
#include "support/msh_parse.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_mesh_files_fort14_text_writer_test {
namespace {

std::vector<std::string> lines_of(const std::filesystem::path& p) {
  std::istringstream in(testing::read_file_bytes(p.string()));
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

TEST(Fort14Writer, HeaderNodesElementsAndLandBoundaries) {
  testing::TempDir dir;
  const auto m = testing::tiny_mesh();
  const WriteStats st = write_fort14(m, dir / "m.14");
  EXPECT_EQ(st.nodes, 21);
  EXPECT_EQ(st.elements, 17);
  EXPECT_EQ(st.boundary_edges, 19);
  const auto l = lines_of(dir / "m.14");
  EXPECT_EQ(l[0], "aquatoria global ocean mesh");
  EXPECT_EQ(l[1], "17 21");
  // Node 1 is lattice vertex (0, 2): λ = -180, φ = -45, elevation -102 m.
  EXPECT_EQ(l[2], "1 -180 -45 102");
  // Every node line: id lon lat depth with lon in [-180, 180).
  for (int n = 0; n < 21; ++n) {
    std::istringstream s(l[static_cast<std::size_t>(2 + n)]);
    long id = 0;
    double lon = 0, lat = 0, dp = 0;
    s >> id >> lon >> lat >> dp;
    EXPECT_EQ(id, n + 1);
    EXPECT_GE(lon, -180.0);
    EXPECT_LT(lon, 180.0);
    EXPECT_EQ(dp, -m.depth_m[static_cast<std::size_t>(n)]);
  }
  // Element 10 is the first triangle of the seam-crossing square: kept, with its wrapped nodes.
  const auto& t = m.triangles[9];
  EXPECT_EQ(l[2 + 21 + 9], fmt::format("10 3 {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1));
  std::size_t k = 2 + 21 + 17;
  EXPECT_EQ(l[k++].substr(0, 2), "0 ");   // NOPE
  EXPECT_EQ(l[k++].substr(0, 2), "0 ");   // NETA
  EXPECT_EQ(l[k++].substr(0, 2), "3 ");   // NBOU: one per loop
  EXPECT_EQ(l[k++].substr(0, 3), "22 ");  // NVEL = 19 edges + 3 closing nodes
  int mainland = 0, island = 0;
  for (std::size_t b = 0; b < m.loops.size(); ++b) {
    std::istringstream s(l[k++]);
    std::size_t nvell = 0;
    int ibtype = -1;
    s >> nvell >> ibtype;
    EXPECT_EQ(nvell, m.loops[b].nodes.size() + 1);
    EXPECT_EQ(ibtype, m.loops[b].outer ? 0 : 1);
    (ibtype == 0 ? mainland : island) += 1;
    for (std::size_t j = 0; j < nvell; ++j) {
      EXPECT_EQ(std::stol(l[k++]), m.loops[b].nodes[j % m.loops[b].nodes.size()] + 1);
    }
  }
  EXPECT_EQ(mainland, 1);
  EXPECT_EQ(island, 2);
  EXPECT_EQ(k, l.size());
}

TEST(Fort14Writer, ZeroElevationIsWrittenAsZeroDepthNotMinusZero) {
  testing::TempDir dir;
  auto m = testing::tiny_mesh();
  m.depth_m[0] = 0.0;
  write_fort14(m, dir / "m.14");
  write_text(m, dir / "m.txt");
  EXPECT_EQ(lines_of(dir / "m.14")[2], "1 -180 -45 0");
  EXPECT_NE(testing::read_file_bytes((dir / "m.txt").string()).find("\n0 -180 -45 0 17 0 2\n"), std::string::npos);
}

TEST(Fort14Writer, NeedsTrianglesAndReportsWriteErrors) {
  testing::TempDir dir;
  EXPECT_THROW(write_fort14(testing::tiny_mesh(false), dir / "q.14"), InternalError);
  std::ofstream(dir / "plain_file") << "x";
  const auto bad = dir / "plain_file" / "m.14";
  try {
    write_fort14(testing::tiny_mesh(), bad);
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
  const auto m = testing::band_mesh(Lattice::make(4.0, 1, -180.0), 10, 80);
  testing::FileSizeLimit limit(64 * 1024);
  EXPECT_THROW(write_fort14(m, dir / "big.14"), OutputError);
}

TEST(TextWriter, SectionsAndRecords) {
  testing::TempDir dir;
  const auto m = testing::tiny_mesh();
  TextOptions o;
  o.elements = ElementKinds::kBoth;
  const WriteStats st = write_text(m, dir / "m.txt", o);
  EXPECT_EQ(st.elements, 24);
  const auto l = lines_of(dir / "m.txt");
  EXPECT_EQ(l[0], "# aquatoria mesh, plain text format 1");
  EXPECT_EQ(l[1], "# lattice lon0_deg=-180 step0_deg=45 levels=1 nx=16 ny=8");
  EXPECT_EQ(l[2], "# rotation none");
  auto find = [&](const std::string& head) {
    for (std::size_t k = 0; k < l.size(); ++k)
      if (l[k] == head) return k;
    ADD_FAILURE() << "no line '" << head << "'";
    return l.size();
  };
  const std::size_t nodes = find("nodes 21");
  EXPECT_EQ(l[nodes + 2], "0 -180 -45 102 17 0 2");  // flags 17 = boundary | seam
  const std::size_t tris = find("triangles 17");
  const auto& t = m.triangles[0];
  EXPECT_EQ(l[tris + 2], fmt::format("0 0 {} {} {}", t[0], t[1], t[2]));
  const std::size_t sq = find("squares 7");
  const auto& c = m.squares[0];
  EXPECT_EQ(l[sq + 2], fmt::format("0 0 {} {} {} {} -1 {} -1 -1", c[0], c[1], c[2], c[3], m.square_midside[0][1]));
  const std::size_t loops = find("loops 3");
  EXPECT_EQ(l[loops + 2 + 1], "1 1 0 7");  // loop 1 (A+B) is the outer one, 7 edges
  const std::size_t bnd = find("boundary_edges 19");
  EXPECT_EQ(l[bnd + 2],
            fmt::format("{} {} {}", m.boundary_edge_loop[0], m.boundary_edges[0][0], m.boundary_edges[0][1]));
  EXPECT_EQ(bnd + 2 + 19, l.size());
}

TEST(TextWriter, TrianglesOnlyByDefaultAndDeterministic) {
  testing::TempDir dir;
  const auto m = testing::tiny_mesh();
  write_text(m, dir / "1.txt");
  write_text(m, dir / "2.txt");
  const std::string a = testing::read_file_bytes((dir / "1.txt").string());
  EXPECT_EQ(a, testing::read_file_bytes((dir / "2.txt").string()));
  EXPECT_EQ(a.find("\nsquares "), std::string::npos);
  EXPECT_NE(a.find("\ntriangles 17\n"), std::string::npos);
}

TEST(TextWriter, UnwritablePathThrowsOutputErrorNamingIt) {
  testing::TempDir dir;
  std::ofstream(dir / "plain_file") << "x";
  const auto bad = dir / "plain_file" / "m.txt";
  try {
    write_text(testing::tiny_mesh(), bad);
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace aq::io::unit_mesh_files_fort14_text_writer_test

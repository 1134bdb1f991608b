// SPDX-License-Identifier: GPL-3.0-or-later
// The model files' numbers as data (mesh_files/model_columns.hpp, fort14_boundaries,
// schism_hgrid_layout, fesom_boundary_flags, fesom_open_boundary_nodes): what the Python package
// hands over as arrays must be what the writers print. Each test writes the file and reads the
// numbers back: the node columns, the boundary lists of fort.14 and hgrid.gr3 (a global mesh's
// closed loops, a regional mesh's open segment, mainland piece and island), and FESOM2's flags and
// open-boundary list.
#include <gtest/gtest.h>

#include <cstdlib>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "mesh/boundaries.hpp"
#include "mesh_files/fesom_writer.hpp"
#include "mesh_files/fort14_writer.hpp"
#include "mesh_files/model_columns.hpp"
#include "mesh_files/schism_writer.hpp"
#include "support/io_test_mesh.hpp"
#include "support/msh_parse.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_mesh_files_model_files_test {
namespace {

std::vector<std::string> lines_of(const std::filesystem::path& p) {
  std::istringstream in(testing::read_file_bytes(p.string()));
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// One list as the file has it: the header's count, flag and comment, then the 0-based nodes.
struct FileList {
  std::size_t count = 0;
  int flag = 0;
  std::string comment;
  std::vector<NodeId> nodes;
};

// The open and land lists of a fort.14 / hgrid.gr3 file.
std::pair<std::vector<FileList>, std::vector<FileList>> read_lists(const std::filesystem::path& p, std::int64_t np,
                                                                   std::int64_t ne) {
  const auto l = lines_of(p);
  std::size_t k = static_cast<std::size_t>(2 + np + ne);
  auto section = [&] {
    const std::size_t count = std::stoul(l.at(k));
    const std::size_t total = std::stoul(l.at(k + 1));
    k += 2;
    std::vector<FileList> out;
    std::size_t nodes = 0;
    for (std::size_t s = 0; s < count; ++s) {
      FileList f;
      std::istringstream head(l.at(k).substr(0, l.at(k).find('!')));
      head >> f.count >> f.flag;
      f.comment = l.at(k).substr(l.at(k).find("! ") + 2);
      for (std::size_t n = 0; n < f.count; ++n) f.nodes.push_back(std::stoll(l.at(k + 1 + n)) - 1);
      k += 1 + f.count;
      nodes += f.count;
      out.push_back(f);
    }
    EXPECT_EQ(nodes, total);
    return out;
  };
  auto open = section();
  auto land = section();
  EXPECT_EQ(k, l.size());
  return {open, land};
}

void expect_same(const std::vector<Fort14Boundary>& lists, const std::vector<FileList>& file) {
  ASSERT_EQ(lists.size(), file.size());
  for (std::size_t s = 0; s < lists.size(); ++s) {
    EXPECT_EQ(lists[s].nodes.size(), file[s].count) << s;
    EXPECT_EQ(lists[s].nodes, file[s].nodes) << s;
    EXPECT_EQ(lists[s].flag, file[s].flag) << s;
    EXPECT_EQ(lists[s].comment, file[s].comment) << s;
    if (lists[s].closed) {
      EXPECT_EQ(lists[s].nodes.front(), lists[s].nodes.back()) << s;
    }
  }
}

// A band of level-1 pixels around the globe (two boundary loops, rows J = 10 and J = 12), typed
// with an open run along ten edges of the lower row: an open segment, the rest of that loop a
// mainland piece, the other loop closed land.
mesh::Mesh typed_band() {
  mesh::Mesh m = testing::band_mesh(Lattice::make(10.0, 1, -180.0), 10, 12);
  const auto open = [&m](NodeId a, NodeId b) {
    const auto ia = m.node_i[static_cast<std::size_t>(a)], ib = m.node_i[static_cast<std::size_t>(b)];
    return m.node_j[static_cast<std::size_t>(a)] == 10 && m.node_j[static_cast<std::size_t>(b)] == 10 && ia >= 5 &&
           ia < 16 && ib >= 5 && ib < 16;
  };
  mesh::type_boundaries(m, open, nullptr);
  return m;
}

TEST(ModelFiles, Fort14ListsOfAGlobalMeshAreItsLoopsClosed) {
  testing::TempDir dir;
  const auto m = testing::tiny_mesh();
  write_fort14(m, dir / "m.14");
  const Fort14Boundaries b = fort14_boundaries(m);
  EXPECT_TRUE(b.open.empty());
  ASSERT_EQ(b.land.size(), m.loops.size());
  for (std::size_t l = 0; l < m.loops.size(); ++l) {
    auto nodes = m.loops[l].nodes;
    nodes.push_back(nodes.front());
    EXPECT_EQ(b.land[l].nodes, nodes);
    EXPECT_TRUE(b.land[l].closed);
    EXPECT_EQ(b.land[l].flag, m.loops[l].outer ? 0 : 1);
    EXPECT_EQ(b.land[l].type, m.loops[l].outer ? mesh::BoundaryType::kMainland : mesh::BoundaryType::kIsland);
  }
  const auto [open, land] = read_lists(dir / "m.14", m.node_count(), m.triangle_count());
  EXPECT_TRUE(open.empty());
  expect_same(b.land, land);
}

TEST(ModelFiles, Fort14AndGr3ListsOfARegionalMeshAreTheFiles) {
  testing::TempDir dir;
  const auto m = typed_band();
  ASSERT_TRUE(m.typed);
  for (const bool schism : {false, true}) {
    const auto path = dir / (schism ? "m.gr3" : "m.14");
    if (schism)
      write_schism_hgrid(m, path);
    else
      write_fort14(m, path);
    const Fort14Boundaries b = fort14_boundaries(m, schism ? schism_hgrid_layout() : Fort14Options{});
    ASSERT_EQ(b.open.size(), 1U);
    EXPECT_EQ(b.open[0].nodes.size(), 11U);  // ten open edges
    EXPECT_FALSE(b.open[0].closed);
    std::set<mesh::BoundaryType> types;
    for (const auto& l : b.land) types.insert(l.type);
    EXPECT_EQ(types.count(mesh::BoundaryType::kMainland), 1U);
    for (const auto& l : b.land) {
      const int island = schism ? 1 : 21, mainland = schism ? 0 : 20;
      EXPECT_EQ(l.flag, l.type == mesh::BoundaryType::kIsland ? island : mainland);
    }
    // The mainland piece runs from the open segment's last node round to its first.
    const auto& piece = *std::find_if(b.land.begin(), b.land.end(), [](const auto& l) { return !l.closed; });
    EXPECT_EQ(piece.nodes.front(), b.open[0].nodes.back());
    EXPECT_EQ(piece.nodes.back(), b.open[0].nodes.front());
    const auto [open, land] = read_lists(path, m.node_count(), m.triangle_count());
    expect_same(b.open, open);
    expect_same(b.land, land);
  }
}

TEST(ModelFiles, NodeColumnsAreTheWrittenNumbers) {
  testing::TempDir dir;
  auto m = testing::tiny_mesh();
  m.depth_m[3] = 0.0;   // written as 0, not -0, in both conventions
  m.depth_m[4] = 17.5;  // above the datum: a negative depth in fort.14, bottom 0 in FESOM2
  write_fort14(m, dir / "m.14");
  write_fesom_nod2d(m, dir / "nod2d.out");
  write_fesom_elem2d(m, dir / "elem2d.out");
  write_fesom_aux3d(m, dir / "aux3d.out", default_fesom_levels_m());
  const auto f14 = lines_of(dir / "m.14");
  const auto nod = lines_of(dir / "nod2d.out");
  const auto elem = lines_of(dir / "elem2d.out");
  const auto aux = lines_of(dir / "aux3d.out");
  const auto nl = default_fesom_levels_m().size();
  for (std::size_t n = 0; n < m.lon_deg.size(); ++n) {
    std::istringstream s(f14.at(2 + n));
    long id = 0;
    double x = 0, y = 0, z = 0;
    s >> id >> x >> y >> z;
    EXPECT_EQ(x, model_lon_deg(m.lon_deg[n])) << n;
    EXPECT_EQ(y, m.lat_deg[n]) << n;
    EXPECT_EQ(z, fort14_depth_m(m.depth_m[n])) << n;
    EXPECT_EQ(std::stod(aux.at(1 + nl + n)), fesom_bottom_m(m.depth_m[n])) << n;
    std::istringstream t(nod.at(1 + n));
    t >> id >> x;
    EXPECT_EQ(x, model_lon_deg(m.lon_deg[n])) << n;
  }
  EXPECT_EQ(f14.at(2 + 3).substr(f14.at(2 + 3).rfind(' ')), " 0");
  EXPECT_EQ(fort14_depth_m(17.5), -17.5);
  EXPECT_EQ(fesom_bottom_m(17.5), 0.0);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto c = fesom_triangle(m.triangles[t]);
    EXPECT_EQ(elem.at(1 + t),
              std::to_string(c[0] + 1) + " " + std::to_string(c[1] + 1) + " " + std::to_string(c[2] + 1));
  }
}

TEST(ModelFiles, FesomFlagsAndOpenNodesAreTheFiles) {
  testing::TempDir dir;
  const auto m = typed_band();
  write_fesom_nod2d(m, dir / "nod2d.out");
  write_fesom_open_boundary(m, dir / "obn.out");
  const auto flags = fesom_boundary_flags(m);
  const auto nod = lines_of(dir / "nod2d.out");
  std::int64_t flagged = 0;
  for (std::size_t n = 0; n < flags.size(); ++n) {
    EXPECT_EQ(nod.at(1 + n).back() - '0', flags[n]) << n;
    flagged += flags[n];
  }
  EXPECT_EQ(flagged, static_cast<std::int64_t>(2 * m.lattice.nx));  // both rows of the band
  const auto open = fesom_open_boundary_nodes(m);
  const auto obn = lines_of(dir / "obn.out");
  ASSERT_EQ(std::stoul(obn.at(0)), open.size());
  for (std::size_t k = 0; k < open.size(); ++k) EXPECT_EQ(std::stoll(obn.at(1 + k)) - 1, open[k]);
  EXPECT_EQ(open.size(), 11U);
  EXPECT_TRUE(fesom_open_boundary_nodes(testing::tiny_mesh()).empty());
}

}  // namespace
}  // namespace aq::io::unit_mesh_files_model_files_test

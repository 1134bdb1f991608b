// SPDX-License-Identifier: GPL-3.0-or-later
// The model formats hold meshes the models accept (issue 20): fort.14, SCHISM's gr3 and FESOM2's
// elem2d.out of the default run, configs/rotated_greenland.toml and configs/global_mercator.toml
// are parsed back and have no triangle with fewer than two edge neighbours (FESOM2's partitioner
// stops on one) and no pinch vertex (SCHISM stops on one), counted here independently of
// mesh/model_cleaning.hpp; every boundary edge is on exactly one land boundary of fort.14/gr3,
// and every boundary node on one. On main before the cleaning these meshes had 833 / 762 / 1279
// triangles with one neighbour and 2 / 4 / 2 pinches.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "support/fort14_read.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace cli_model_formats_cli_test {

namespace fs = std::filesystem;
using aq::test::run_command;

namespace {

using Tri = std::array<long, 3>;

struct Defects {
  long lonely = 0, pinches = 0, shared_edges = 0;
  std::set<std::pair<long, long>> boundary;  // undirected boundary edges
};

Defects count_defects(const std::vector<Tri>& tris) {
  std::map<std::pair<long, long>, int> edge_count;
  for (const auto& t : tris)
    for (int e = 0; e < 3; ++e) ++edge_count[std::minmax(t[e], t[(e + 1) % 3])];
  Defects d;
  for (const auto& t : tris) {
    int n = 0;
    for (int e = 0; e < 3; ++e) n += edge_count[std::minmax(t[e], t[(e + 1) % 3])] >= 2 ? 1 : 0;
    d.lonely += n < 2 ? 1 : 0;
  }
  std::map<long, int> boundary_at;
  for (const auto& [e, c] : edge_count) {
    d.shared_edges += c > 2 ? 1 : 0;
    if (c != 1) continue;
    d.boundary.insert(e);
    ++boundary_at[e.first];
    ++boundary_at[e.second];
  }
  for (const auto& [v, c] : boundary_at) d.pinches += c > 2 ? 1 : 0;
  return d;
}

// fort.14 / gr3: triangles and the land boundaries' edges (consecutive nodes of each segment),
// 0-based.
struct ModelMesh {
  std::vector<Tri> tris;
  std::vector<std::pair<long, long>> land_edges;
  std::map<long, int> land_node_count;  // segments (less the closing repeat) listing a node
  long nodes = 0;
};

ModelMesh read_model_mesh(const fs::path& p) {
  const aq::test::Fort14 f = aq::test::read_fort14(p);
  EXPECT_TRUE(f.error.empty()) << f.error;
  ModelMesh m;
  m.nodes = f.nodes();
  m.tris = f.triangles;
  for (std::size_t b = 0; b < f.land.size(); ++b) {
    const std::vector<long>& seg = f.land[b].nodes;
    for (std::size_t k = 0; k + 1 < seg.size(); ++k) m.land_edges.emplace_back(std::minmax(seg[k], seg[k + 1]));
    for (std::size_t k = 0; k + 1 < seg.size(); ++k) ++m.land_node_count[seg[k]];
    EXPECT_EQ(seg.front(), seg.back()) << p << " boundary " << b;
  }
  return m;
}

std::vector<Tri> read_elem2d(const fs::path& p) {
  std::ifstream in(p);
  long ne = 0;
  in >> ne;
  std::vector<Tri> t(static_cast<std::size_t>(ne));
  for (auto& x : t) in >> x[0] >> x[1] >> x[2];
  EXPECT_TRUE(in.good()) << p;
  return t;
}

void check_run(const std::string& config, const std::string& name) {
  const aq::testing::TempDir dir;
  const std::string cfg = config.empty() ? "" : " -c " + (fs::path(AQ_SOURCE_DIR) / config).string();
  const auto r = run_command(std::string(AQ_BINARY) + " mesh -o " + dir.path().string() + cfg +
                             " --set 'output.formats=[\"fort14\",\"schism\",\"fesom\"]'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("mesh cleaning: "), std::string::npos) << r.err;
  // What each model needs to know: FESOM's &geometry for every mesh (FESOM's standard frame
  // without rotation), SCHISM's time steps.
  const std::string fesom_line = config.empty() ? "FESOM namelist.config &geometry: force_rotation = .true., "
                                                  "alphaEuler = 50, betaEuler = 15, gammaEuler = -90"
                                                : "FESOM namelist.config &geometry: force_rotation = .true., "
                                                  "alphaEuler = 45.141667, betaEuler = 11.858333, gammaEuler = -90";
  EXPECT_NE(r.err.find(fesom_line), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("SCHISM time step: advection off (nadv = 0) "), std::string::npos) << r.err;
  const auto report = nlohmann::json::parse(std::ifstream(dir / (name + "_report.json")));
  const auto& cleaning = report.at("cleaning");
  EXPECT_GT(cleaning.at("one_neighbour_triangles_removed").get<long>(), 0);  // there were some to remove

  for (const char* ext : {".14", ".gr3"}) {
    const ModelMesh f = read_model_mesh(dir / (name + ext));
    const Defects d = count_defects(f.tris);
    EXPECT_EQ(d.lonely, 0) << name << ext;
    EXPECT_EQ(d.pinches, 0) << name << ext;
    EXPECT_EQ(d.shared_edges, 0) << name << ext;
    EXPECT_EQ(static_cast<long>(f.tris.size()), cleaning.at("triangles").get<long>());
    EXPECT_EQ(f.nodes, cleaning.at("nodes").get<long>());
    // Every boundary edge once on a land boundary, and nothing else there; every boundary node
    // on exactly one (SCHISM: "Incomplete ball" / "Illegal bnd node" otherwise).
    const std::set<std::pair<long, long>> land(f.land_edges.begin(), f.land_edges.end());
    EXPECT_EQ(land.size(), f.land_edges.size()) << name << ext;
    EXPECT_EQ(land, d.boundary) << name << ext;
    std::set<long> boundary_nodes;
    for (const auto& e : d.boundary) boundary_nodes.insert({e.first, e.second});
    EXPECT_EQ(f.land_node_count.size(), boundary_nodes.size()) << name << ext;
    for (const auto& [v, c] : f.land_node_count) EXPECT_EQ(c, 1) << name << ext << " node " << v;
  }
  const Defects fesom = count_defects(read_elem2d(dir / (name + "_elem2d.out")));
  EXPECT_EQ(fesom.lonely, 0) << name;
  EXPECT_EQ(fesom.pinches, 0) << name;
  EXPECT_EQ(fesom.shared_edges, 0) << name;
}

TEST(ModelFormatsCli, DefaultRunHasNoLonelyTriangleAndNoPinch) { check_run("", "seed_4deg_L3"); }

TEST(ModelFormatsCli, RotatedGreenlandHasNoLonelyTriangleAndNoPinch) {
  check_run("configs/rotated_greenland.toml", "rotated_greenland");
}

TEST(ModelFormatsCli, MercatorHasNoLonelyTriangleAndNoPinch) {
  check_run("configs/global_mercator.toml", "global_mercator");
}

}  // namespace

}  // namespace cli_model_formats_cli_test

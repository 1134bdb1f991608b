// SPDX-License-Identifier: GPL-3.0-or-later
// Regional configuration: example_regional.toml documents exactly the known keys; a TOML config
// and the seed's .izogrid file give the same parameters; errors name file, line and key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <toml.hpp>

#include "config/regional.hpp"
#include "core/error.hpp"

namespace unit_config_regional_config_test {

namespace fs = std::filesystem;
using aq::config::load_regional;
using ::testing::HasSubstr;

namespace {
fs::path write_temp(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "aq_regional_config_test";
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}
const fs::path kConfigs = fs::path(AQ_SOURCE_DIR) / "configs";
// The message of the error loading `p` with `sets`, or "(loaded)".
std::string load_error(const fs::path& p, const std::vector<std::string>& sets = {}) {
  try {
    (void)load_regional(p.string(), sets);
  } catch (const aq::Error& e) {
    return e.what();
  }
  return "(loaded)";
}
}  // namespace

TEST(ExampleRegionalToml, ListsExactlyTheKeysTheCodeKnows) {
  const toml::value doc = toml::parse((kConfigs / "example_regional.toml").string());
  std::set<std::string> in_file;
  for (const auto& [sec, table] : doc.as_table())
    for (const auto& [key, v] : table.as_table()) in_file.insert(sec + "." + key);
  const auto keys = aq::config::regional_keys();
  const std::set<std::string> in_code(keys.begin(), keys.end());
  for (const auto& k : in_code)
    EXPECT_TRUE(in_file.count(k)) << k << " is in the code but not in example_regional.toml";
  for (const auto& k : in_file)
    EXPECT_TRUE(in_code.count(k)) << k << " is in example_regional.toml but not in the code";
  EXPECT_EQ(keys.size(), in_code.size()) << "a key is registered twice";
}

TEST(RegionalConfig, ExampleLoadsWithDefaults) {
  const auto c = load_regional((kConfigs / "example_regional.toml").string(), {});
  EXPECT_EQ(c.options.params.ny, 50);
  EXPECT_EQ(c.options.params.spline_type, 5);
  EXPECT_TRUE(std::isnan(c.options.params.west_edge));
}

TEST(RegionalConfig, TomlAndIzogridFileAgree) {
  const auto from_file = load_regional((kConfigs / "black_sea.izogrid").string(), {});
  const auto from_toml = load_regional((kConfigs / "black_sea.toml").string(), {});
  const auto& a = from_file.options.params;
  const auto& b = from_toml.options.params;
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.corner, b.corner);
  EXPECT_EQ(a.ny, 50);
  EXPECT_DOUBLE_EQ(b.projection.rlat_deg, 43.75);
  EXPECT_DOUBLE_EQ(b.projection.uscale, 0.001);
  EXPECT_EQ(a.mode, 1);  // the seed's file stops after the contour
  EXPECT_EQ(from_toml.options.stop_after, aq::curvilinear::Stage::kGrid);
  EXPECT_EQ(from_toml.echo["regional"]["stop_after"], "grid");
  EXPECT_FALSE(from_file.options.stop_after.has_value());
  EXPECT_EQ(from_file.echo["regional"]["stop_after"], "");
  EXPECT_EQ(from_toml.options.name, "black_sea");
}

TEST(RegionalConfig, InlinePointsAndCorners) {
  const auto p = write_temp("square.toml",
                            "[regional]\nproj = \"ME\"\nrlat = 10.0\nny = 8\n"
                            "control_points = [[-10, -10], [10, -10], [10, 10], [-10, 10], [-10, 0]]\n"
                            "corners = [1, 2, 3, 4]\n");
  const auto c = load_regional(p.string(), {"regional.ny=12"});
  ASSERT_EQ(c.options.params.x.size(), 5u);
  EXPECT_EQ(c.options.params.corner, (std::vector<bool>{true, true, true, true, false}));
  EXPECT_EQ(c.options.params.ny, 12);
}

TEST(RegionalConfig, ErrorsNameLineAndKey) {
  const auto p = write_temp("bad.toml", "[regional]\nproj = \"XX\"\nny = \"many\"\nbogus = 1\n");
  const std::string m = load_error(p);
  EXPECT_THAT(m, HasSubstr("bad.toml:2:"));
  EXPECT_THAT(m, HasSubstr("regional.proj"));
  EXPECT_THAT(m, HasSubstr("bad.toml:3:"));
  EXPECT_THAT(m, HasSubstr("regional.ny"));
  EXPECT_THAT(m, HasSubstr("regional.bogus: unknown key"));
}

TEST(RegionalConfig, CornerNumbersOutOfRange) {
  const auto p = write_temp("corners.toml",
                            "[regional]\ncontrol_points = [[0, 0], [1, 0], [1, 1], [0, 1]]\ncorners = [1, 2, 3, 9]\n");
  const std::string m = load_error(p);
  EXPECT_THAT(m, HasSubstr("corners.toml:3:11: regional.corners, regional.control_points: point number 9 is "
                           "outside 1..4"));
}

// Every problem of a regional config at load, in one message, each at the position of its value:
// the izogrid keys' ranges (regional_params_problems), the enumerated keys, the cross-key checks
// (a stage the method does not have, a refinement grid stopped early, the depth weight without a
// raster), the nesting keys.
TEST(RegionalConfig, EveryBadValueIsReportedWithItsPosition) {
  const auto p = write_temp("many_bad.toml",
                            "[regional]\n"
                            "method = \"tfi\"\n"            // 2
                            "stop_after = \"conformal\"\n"  // 3: tfi has no conformal stage
                            "weight_depth = 0.5\n"          // 4: needs [input] path
                            "ny = 0\n"                      // 5
                            "solver = \"lu\"\n"             // 6
                            "[roms]\n"
                            "distances = \"flat\"\n"        // 8
                            "depth_statistic = \"mode\"\n"  // 9
                            "[nesting]\n"
                            "parent_box = [2, 5, 2, 5]\n"  // 11: only with refine_factor
                            "[input]\n"
                            "path = \"\"\n");  // 13: no raster for weight_depth
  const std::string m = load_error(p, {"regional.interp_points=9"});
  EXPECT_THAT(m, HasSubstr("8 configuration errors"));
  EXPECT_THAT(m, HasSubstr("many_bad.toml:3:14: regional.stop_after, regional.method: method = tfi has no conformal "
                           "stage"));
  EXPECT_THAT(m, HasSubstr("many_bad.toml:13:8: regional.weight_depth, input.path: regional.weight_depth = 0.5 needs "
                           "the bathymetry"));
  EXPECT_THAT(m, HasSubstr("many_bad.toml:5:6: regional.ny: ny = 0: must be >= 1"));
  EXPECT_THAT(m, HasSubstr("many_bad.toml:6:10: regional.solver: 'lu' is not one of \"dst\", \"sor\""));
  EXPECT_THAT(m, HasSubstr("many_bad.toml:8:13: roms.distances: \"flat\" is not one of \"sphere\", \"wgs84\""));
  EXPECT_THAT(m, HasSubstr("many_bad.toml:9:19: roms.depth_statistic: \"mode\" is not one of \"auto\", \"point\", "
                           "\"mean\", \"median\", \"min\""));
  EXPECT_THAT(m, HasSubstr("many_bad.toml:11:14: nesting.parent_box: only used with nesting.refine_factor"));
  EXPECT_THAT(m, HasSubstr("--set regional.interp_points=9: regional.interp_points: interp_points = 9: must be "
                           "within 2..8"));
}

// The projection's checks (once made when the map was drawn) are made at load: a Lambert conic
// whose standard parallels give a cylinder, a parallel at a pole.
TEST(RegionalConfig, ProjectionProblemsAreReportedAtLoad) {
  const auto p = write_temp("lc.toml", "[regional]\nproj = \"LC\"\nrlat = 40.0\nlat1 = 30.0\nlat2 = -30.0\n");
  const std::string m = load_error(p, {"regional.rota=nan"});
  EXPECT_THAT(m, HasSubstr("lc.toml:4:8: regional.lat1: lat1 = 30, lat2 = -30: the LC standard parallels give "
                           "a cylinder"));
  EXPECT_THAT(m, HasSubstr("--set regional.rota=nan: regional.rota: rota = nan: must be a finite angle"));
  EXPECT_THAT(load_error(p, {"regional.lat2=90"}),
              HasSubstr("regional.lat2: lat2 = 90: an LC standard parallel must be inside (-90, 90)"));
}

// A bad value of the seed-format contour file is reported at its line there; a value of that file
// that a TOML key makes bad (a pole as the centre of the Mercator projection the TOML asks) at the
// file, as the place the value came from.
TEST(RegionalConfig, AValueOfTheContourFileIsReportedThere) {
  (void)write_temp("bad_mode.izogrid", "mode=9\nny=8\n---\n0 0\n1 0 <\n1 1 <\n0 1 <\n");
  const auto p = write_temp("uses_bad.toml", "[regional]\ncontour_file = \"bad_mode.izogrid\"\n");
  EXPECT_THAT(load_error(p), HasSubstr("bad_mode.izogrid:1: mode = 9: must be 0..5"));
  (void)write_temp("polar.izogrid", "proj=ST\nrlat=90\nny=8\n---\n0 0\n1 0 <\n1 1 <\n0 1 <\n");
  const auto q = write_temp("uses_polar.toml", "[regional]\ncontour_file = \"polar.izogrid\"\nproj = \"ME\"\n");
  EXPECT_THAT(load_error(q),
              HasSubstr("polar.izogrid (regional.contour_file) or built-in default: regional.rlat: rlat = "
                        "90: a Mercator centre cannot be a pole"));
}

// Every name of an enumerated key is accepted (as the seed's files write them, in any case) and
// echoed as its table has it; every such key is documented with all its names in
// example_regional.toml.
TEST(RegionalConfig, EnumeratedKeysTakeEveryNameOfTheirTable) {
  const std::string text = [] {
    std::ifstream in(kConfigs / "example_regional.toml");
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  int enumerated = 0;
  for (const auto& k : aq::config::regional_key_info()) {
    if (k.values.empty()) continue;
    ++enumerated;
    const std::string name = k.key.substr(k.key.find('.') + 1);
    const auto at = text.find("\n" + name + " = ");
    ASSERT_NE(at, std::string::npos) << k.key;
    const std::string line = text.substr(at + 1, text.find('\n', at + 1) - at - 1);
    for (const std::string& v : k.values) {
      EXPECT_NE(line.find("\"" + v + "\""), std::string::npos) << k.key << ": \"" << v << "\" is not in " << line;
      std::vector<std::string> sets{k.key + "=\"" + v + "\""};
      if (k.key == "regional.surface") sets.push_back("regional.method=\"bvp\"");
      const auto c = load_regional((kConfigs / "black_sea.toml").string(), sets);
      const auto [sec, key] = std::pair{k.key.substr(0, k.key.find('.')), name};
      EXPECT_EQ(c.echo[sec][key], v) << k.key;
    }
  }
  EXPECT_GE(enumerated, 10);
  const auto lower = load_regional((kConfigs / "black_sea.toml").string(), {"regional.proj=\"st\""});
  EXPECT_EQ(lower.echo["regional"]["proj"], "ST");
}

}  // namespace unit_config_regional_config_test

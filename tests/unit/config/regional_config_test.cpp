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
  EXPECT_DOUBLE_EQ(b.rlat, 43.75);
  EXPECT_DOUBLE_EQ(b.uscale, 0.001);
  EXPECT_EQ(a.mode, 1);  // the seed's file stops after the contour
  EXPECT_EQ(from_toml.options.stop_after, "grid");
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
  try {
    (void)load_regional(p.string(), {});
    FAIL() << "expected ConfigError";
  } catch (const aq::ConfigError& e) {
    const std::string m = e.what();
    EXPECT_THAT(m, HasSubstr("bad.toml:2:"));
    EXPECT_THAT(m, HasSubstr("regional.proj"));
    EXPECT_THAT(m, HasSubstr("bad.toml:3:"));
    EXPECT_THAT(m, HasSubstr("regional.ny"));
    EXPECT_THAT(m, HasSubstr("regional.bogus: unknown key"));
  }
}

TEST(RegionalConfig, CornerNumbersOutOfRange) {
  const auto p = write_temp("corners.toml",
                            "[regional]\ncontrol_points = [[0, 0], [1, 0], [1, 1], [0, 1]]\ncorners = [1, 2, 3, 9]\n");
  EXPECT_THROW((void)load_regional(p.string(), {}), aq::ConfigError);
}

}  // namespace unit_config_regional_config_test

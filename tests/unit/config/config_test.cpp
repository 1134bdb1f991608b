// Configuration: example.toml documents exactly the keys the code knows; unknown keys and bad
// values are reported with file:line, all of them in one run; --set overrides; path resolution.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <set>
#include <toml.hpp>

#include "config/load.hpp"
#include "core/error.hpp"

namespace unit_config_config_test {

namespace fs = std::filesystem;
using aq::config::load_global;
using ::testing::HasSubstr;

namespace {

fs::path write_temp(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "aq_config_test";
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

std::string error_of(const std::optional<std::string>& path, const std::vector<std::string>& over = {}) {
  try {
    (void)load_global(path, over);
  } catch (const aq::ConfigError& e) {
    EXPECT_EQ(e.exit_code(), 2);
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ExampleToml, ListsExactlyTheKeysTheCodeKnows) {
  const fs::path example = fs::path(AQ_SOURCE_DIR) / "configs" / "example.toml";
  const toml::value doc = toml::parse(example.string());
  std::set<std::string> in_file;
  // [size.coast] etc. are sub-tables of [size]: their keys are size.coast.h0_km, ...
  const std::function<void(const std::string&, const toml::value&)> add = [&](const std::string& prefix,
                                                                                const toml::value& table) {
    for (const auto& [key, v] : table.as_table()) {
      if (v.is_table())
        add(prefix + key + ".", v);
      else
        in_file.insert(prefix + key);
    }
  };
  for (const auto& [sec, table] : doc.as_table()) add(sec + ".", table);
  const auto keys = aq::config::global_keys();
  const std::set<std::string> in_code(keys.begin(), keys.end());
  for (const auto& k : in_code) EXPECT_TRUE(in_file.count(k)) << k << " is in the code but not in example.toml";
  for (const auto& k : in_file) EXPECT_TRUE(in_code.count(k)) << k << " is in example.toml but not in the code";
  EXPECT_GE(in_code.size(), 30u);
}

// Every value output.formats accepts is named in example.toml's formats line and in README's
// "Output formats" section (issue 12 added fesom and schism).
TEST(ExampleToml, AndReadmeListEveryOutputFormat) {
  auto read = [](const fs::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string example = read(fs::path(AQ_SOURCE_DIR) / "configs" / "example.toml");
  const auto line_at = example.find("\nformats = ");
  ASSERT_NE(line_at, std::string::npos);
  const std::string formats_line = example.substr(line_at + 1, example.find('\n', line_at + 1) - line_at - 1);
  const std::string readme = read(fs::path(AQ_SOURCE_DIR) / "README.md");
  const auto from = readme.find("## Output formats");
  ASSERT_NE(from, std::string::npos);
  const std::string section = readme.substr(from, readme.find("\n## ", from + 1) - from);
  for (const auto& f : aq::config::output_format_names()) {
    EXPECT_NE(formats_line.find("\"" + f + "\""), std::string::npos) << f << " is not in example.toml's formats line";
    EXPECT_NE(section.find("`" + f + "`"), std::string::npos) << f << " is not in README's Output formats section";
  }
  EXPECT_EQ(aq::config::output_format_names().size(), 9u);
}

TEST(ExampleToml, StatesTheDefaults) {
  const fs::path example = fs::path(AQ_SOURCE_DIR) / "configs" / "example.toml";
  const auto from_file = load_global(example.string(), {});
  const auto defaults = load_global(std::nullopt, {});
  EXPECT_EQ(from_file.echo.dump(), defaults.echo.dump());
  EXPECT_EQ(defaults.options.quadtree.levels, 3);
  EXPECT_EQ(defaults.options.mask.cursor, 2);
  EXPECT_DOUBLE_EQ(defaults.options.quadtree.step_deg, 4.0);
}

TEST(Config, UnknownKeyNamesKeyAndLine) {
  const auto p = write_temp("unknown.toml", "[mask]\ncursor = 3\ncursr = 2\n");
  const std::string e = error_of(p.string());
  EXPECT_THAT(e, HasSubstr("mask.cursr"));
  EXPECT_THAT(e, HasSubstr("unknown.toml:3:"));
  EXPECT_THAT(e, HasSubstr("did you mean mask.cursor"));
}

TEST(Config, UnknownSectionIsAnError) {
  const auto p = write_temp("section.toml", "[quadtre]\nlevels = 3\n");
  EXPECT_THAT(error_of(p.string()), HasSubstr("unknown section [quadtre]"));
}

TEST(Config, AllBadValuesReportedInOneRun) {
  const auto p =
      write_temp("three.toml", "[mask]\ncursor = 0\n[quadtree]\nstep_deg = 7.0\n[mesh]\ndiagonal = \"sw\"\n");
  const std::string e = error_of(p.string());
  EXPECT_THAT(e, HasSubstr("3 configuration errors"));
  EXPECT_THAT(e, HasSubstr("three.toml:2:"));
  EXPECT_THAT(e, HasSubstr("mask.cursor"));
  EXPECT_THAT(e, HasSubstr("three.toml:4:"));
  EXPECT_THAT(e, HasSubstr("quadtree.step_deg"));
  EXPECT_THAT(e, HasSubstr("three.toml:6:"));
  EXPECT_THAT(e, HasSubstr("\"sw\" is not one of"));
}

TEST(Config, WrongTypeIsReported) {
  const auto p = write_temp("type.toml", "[quadtree]\nlevels = \"three\"\n");
  EXPECT_THAT(error_of(p.string()), HasSubstr("expected an integer"));
}

TEST(Config, SyntaxErrorNamesFile) {
  const auto p = write_temp("syntax.toml", "[mask\ncursor = 3\n");
  EXPECT_THAT(error_of(p.string()), HasSubstr("syntax.toml"));
}

TEST(Config, MissingFile) { EXPECT_THAT(error_of("/nonexistent/x.toml"), HasSubstr("/nonexistent/x.toml")); }

TEST(Config, SetOverridesFileAndDefaults) {
  const auto p = write_temp("set.toml", "[mask]\nmin_depth_m = 10.0\n");
  const auto c = load_global(p.string(), {"mask.min_depth_m=200", "quadtree.levels=4", "output.dir=out2",
                                          "mask.seeds=[[10.0, -40.0], [170, 0]]"});
  EXPECT_DOUBLE_EQ(c.options.mask.min_depth_m, 200.0);
  EXPECT_EQ(c.options.quadtree.levels, 4);
  EXPECT_EQ(c.options.output.dir, "out2");
  ASSERT_EQ(c.options.mask.seeds.size(), 2u);
  EXPECT_DOUBLE_EQ(c.options.mask.seeds[1][0], 170.0);
  EXPECT_EQ(c.echo["quadtree"]["levels"], 4);
}

TEST(Config, BadSetIsReported) {
  EXPECT_THAT(error_of(std::nullopt, {"quadtree.levles=4"}), HasSubstr("did you mean quadtree.levels"));
  EXPECT_THAT(error_of(std::nullopt, {"nodot=4"}), HasSubstr("section.key=value"));
  EXPECT_THAT(error_of(std::nullopt, {"mask.cursor=abc"}), HasSubstr("expected an integer"));
}

TEST(Config, RelativeInputPathResolvesAgainstConfigFolder) {
  const auto p = write_temp("rel.toml", "[input]\npath = \"data/x.nc\"\n");
  const auto c = load_global(p.string(), {});
  EXPECT_EQ(c.options.input.path, (p.parent_path() / "data/x.nc").lexically_normal().string());
}

TEST(Config, RulesParseAndCrossCheckLevels) {
  const auto p = write_temp(
      "rules.toml",
      "[quadtree]\nlevels = 3\ndepth_rules = [{min_depth_m = 0.0, max_depth_m = 200.0, level = 2}]\n"
      "box_rules = [{lon_min_deg = -10.0, lon_max_deg = 40.0, lat_min_deg = 30.0, lat_max_deg = 46.0, level = 5}]\n");
  EXPECT_THAT(error_of(p.string()), HasSubstr("quadtree.box_rules[0]: level 5 exceeds quadtree.levels = 3"));
  const auto ok = load_global(p.string(), {"quadtree.levels=5"});
  ASSERT_EQ(ok.options.quadtree.depth_rules.size(), 1u);
  EXPECT_EQ(ok.options.quadtree.depth_rules[0].level, 2);
  EXPECT_DOUBLE_EQ(ok.options.quadtree.box_rules[0].lat_max_deg, 46.0);
}

TEST(Config, RulesInKilometresParseAndEchoAsGiven) {
  const auto p = write_temp("km_rules.toml",
                            "[quadtree]\ndepth_rules = [{min_depth_m = 0.0, max_depth_m = 200.0, size_km = 25.5}]\n"
                            "box_rules = [{lon_min_deg = -10.0, lon_max_deg = 40.0, lat_min_deg = 30.0, lat_max_deg = "
                            "46.0, level = 2},\n  {lon_min_deg = 0.0, lon_max_deg = 5.0, lat_min_deg = 0.0, "
                            "lat_max_deg = 5.0, size_km = 100}]\n");
  const auto c = load_global(p.string(), {});
  ASSERT_EQ(c.options.quadtree.depth_rules.size(), 1u);
  EXPECT_DOUBLE_EQ(c.options.quadtree.depth_rules[0].size_km, 25.5);
  EXPECT_EQ(c.options.quadtree.depth_rules[0].level, 0);
  ASSERT_EQ(c.options.quadtree.box_rules.size(), 2u);
  EXPECT_EQ(c.options.quadtree.box_rules[0].level, 2);
  EXPECT_EQ(c.options.quadtree.box_rules[0].size_km, 0.0);
  EXPECT_DOUBLE_EQ(c.options.quadtree.box_rules[1].size_km, 100.0);
  // The echo (the report's config) has each rule in the form it was given: size_km or level.
  const auto& depth = c.echo["quadtree"]["depth_rules"][0];
  EXPECT_EQ(depth["size_km"], 25.5);
  EXPECT_FALSE(depth.contains("level"));
  const auto& boxes = c.echo["quadtree"]["box_rules"];
  EXPECT_EQ(boxes[0]["level"], 2);
  EXPECT_FALSE(boxes[0].contains("size_km"));
  EXPECT_EQ(boxes[1]["size_km"], 100.0);
  EXPECT_FALSE(boxes[1].contains("level"));
  // Through --set; a km rule is not checked against quadtree.levels (it asks at most level L).
  const auto s = load_global(std::nullopt, {"quadtree.levels=1",
                                            "quadtree.box_rules=[{lon_min_deg = -50, lon_max_deg "
                                            "= -20, lat_min_deg = 0, lat_max_deg = 50, size_km = 0.5}]"});
  EXPECT_DOUBLE_EQ(s.options.quadtree.box_rules.at(0).size_km, 0.5);
}

TEST(Config, RulesNeedExactlyOneOfLevelAndSizeKm) {
  const std::string box = "lon_min_deg = 0, lon_max_deg = 5, lat_min_deg = 0, lat_max_deg = 5";
  const auto bad = [&](const std::string& second) {
    return error_of(std::nullopt, {"quadtree.box_rules=[{" + box + ", level = 1}, {" + box + second + "}]"});
  };
  EXPECT_THAT(bad(", level = 1, size_km = 50"), HasSubstr("quadtree.box_rules[1]: gives both level and size_km"));
  EXPECT_THAT(bad(""), HasSubstr("quadtree.box_rules[1]: needs level or size_km"));
  EXPECT_THAT(bad(", size_km = -5"), HasSubstr("quadtree.box_rules[1].size_km: -5 is not a finite number > 0"));
  EXPECT_THAT(bad(", size_km = 0"), HasSubstr("quadtree.box_rules[1].size_km: 0 is not a finite number > 0"));
  EXPECT_THAT(bad(", size_km = nan"), HasSubstr("quadtree.box_rules[1].size_km: nan is not a finite number > 0"));
  EXPECT_THAT(bad(", size_km = inf"), HasSubstr("quadtree.box_rules[1].size_km: inf is not a finite number > 0"));
  EXPECT_THAT(bad(", size_km = \"50\""), HasSubstr("quadtree.box_rules[1].size_km: expected a number"));
  const auto p = write_temp("km_depth_bad.toml",
                            "[quadtree]\ndepth_rules = [{min_depth_m = 0.0, max_depth_m = 200.0, level = 1},\n"
                            "  {min_depth_m = 200.0, max_depth_m = 4000.0}, {min_depth_m = 9.0, max_depth_m = 1.0, "
                            "size_km = 10, level = 2}]\n");
  const std::string e = error_of(p.string());
  EXPECT_THAT(e, HasSubstr("km_depth_bad.toml:2:"));
  EXPECT_THAT(e, HasSubstr("quadtree.depth_rules[1]: needs level or size_km"));
  // Every bad rule is reported: the third has an empty range and both forms.
  EXPECT_THAT(e, HasSubstr("quadtree.depth_rules[2]: needs min_depth_m < max_depth_m"));
  EXPECT_THAT(e, HasSubstr("quadtree.depth_rules[2]: gives both level and size_km"));
}

TEST(Config, ShippedConfigsLoad) {
  for (const char* name : {"seed_4deg_L3.toml", "global_1deg_L5.toml", "rotated_greenland.toml", "global_15s.toml",
                           "global_mercator.toml"}) {
    const fs::path p = fs::path(AQ_SOURCE_DIR) / "configs" / name;
    EXPECT_NO_THROW((void)load_global(p.string(), {})) << name;
  }
}

// A floodplain (README "A storm-surge mesh"): mask.min_depth_m down to -100 m, refused below with
// the key, the file position and the range; the floodplain's size terms with their ranges and only
// with a floodplain; the shipped surge config loads.
TEST(Config, FloodplainThresholdAndSizeTermsAreCheckedAtLoad) {
  const auto ok = load_global(std::nullopt, {"mask.min_depth_m=-100", "size.inland.h0_km=2", "size.elevation.h0_km=3"});
  EXPECT_DOUBLE_EQ(ok.options.mask.min_depth_m, -100.0);
  EXPECT_DOUBLE_EQ(ok.options.size.inland.h0_km, 2.0);
  EXPECT_DOUBLE_EQ(ok.options.size.inland.alpha, 0.2);
  EXPECT_DOUBLE_EQ(ok.options.size.elevation.km_per_m, 0.5);
  const auto p = write_temp("flood.toml", "[mask]\nmin_depth_m = -250.0\n[size.inland]\nalpha = -0.1\n");
  const std::string e = error_of(p.string());
  EXPECT_THAT(e, HasSubstr("flood.toml:2:"));
  EXPECT_THAT(e, HasSubstr("mask.min_depth_m: -250 is outside [-100, 12000]"));
  EXPECT_THAT(e, HasSubstr("flood.toml:4:"));
  EXPECT_THAT(e, HasSubstr("size.inland.alpha: -0.1 is outside [0, 10]"));
  EXPECT_THAT(error_of(std::nullopt, {"size.elevation.h0_km=4"}),
              HasSubstr("size.elevation.h0_km sizes the floodplain (land above the datum inside the mesh), but "
                        "mask.min_depth_m = 0 >= 0"));
  EXPECT_THAT(error_of(std::nullopt, {"mask.min_depth_m=-5", "size.elevation.km_per_m=1e4"}),
              HasSubstr("size.elevation.km_per_m: 10000 is outside [0, 1000]"));
  EXPECT_THAT(error_of(std::nullopt, {"output.png_color=\"depth\""}), HasSubstr("\"elevation\""));
  EXPECT_NO_THROW((void)load_global((fs::path(AQ_SOURCE_DIR) / "configs" / "gulf_surge.toml").string(), {}));
}

TEST(Config, InputPathTildeIsHome) {
  const char* home = std::getenv("HOME");
  if (home == nullptr || *home == '\0') GTEST_SKIP() << "no HOME";
  const auto c = load_global(std::nullopt, {"input.path=\"~/x/y.tif\""});
  EXPECT_EQ(c.options.input.path, (fs::path(home) / "x" / "y.tif").lexically_normal().string());
}

// Names say what was run (issue 11): config::default_run_name.
TEST(RunName, SeedRunKeepsTheSeedName) {
  const auto c =
      load_global(std::nullopt, {"output.formats=[\"text\"]", "output.dir=x", "blocks.top=3", "quadtree.levels=3"});
  const auto n = aq::config::default_run_name(c.options);
  EXPECT_EQ(n.name, "seed_4deg_L3");
  EXPECT_TRUE(n.changed.empty());
}

TEST(RunName, FollowsTheParameters) {
  const auto name = [](const std::vector<std::string>& sets) {
    return aq::config::default_run_name(load_global(std::nullopt, sets).options).name;
  };
  EXPECT_EQ(name({"quadtree.step_deg=1", "quadtree.levels=3"}), "global_1deg_L3");
  EXPECT_EQ(name({"quadtree.step_deg=0.2666666666666667", "quadtree.levels=4", "mask.min_depth_m=200", "mask.cursor=3",
                  "rotation.enabled=true"}),
            "global_16min_L4_h200_K3_rot");
  EXPECT_EQ(name({"quadtree.step_deg=0.5"}), "global_30min_L3");
  EXPECT_EQ(name({"quadtree.step_deg=0.0625"}), "global_225sec_L3");
  EXPECT_EQ(name({"input.path=/data/my etopo1.nc", "quadtree.balance=\"corner\"", "quadtree.coast_band=0",
                  "mesh.elements=\"squares\""}),
            "global_4deg_L3_my_etopo1_corner_cb0_squares");
  // A key that changes the mesh but has no part in the name still gives a parameter name.
  EXPECT_EQ(name({"mesh.diagonal=\"nw\""}), "global_4deg_L3");
}

TEST(RunName, ListsWhatDiffersFromTheSeedRun) {
  const auto n = aq::config::default_run_name(
      load_global(std::nullopt, {"quadtree.step_deg=1", "mask.min_depth_m=10", "output.name=ignored"}).options);
  EXPECT_THAT(n.changed, ::testing::ElementsAre("mask.min_depth_m = 10.0", "quadtree.step_deg = 1.0"));
}

}  // namespace unit_config_config_test

// SPDX-License-Identifier: GPL-3.0-or-later
// Configuration: example.toml documents exactly the keys the code knows; unknown keys and bad
// values are reported with file:line, all of them in one run; --set overrides; path resolution.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <set>
#include <toml.hpp>

#include "config/load.hpp"
#include "core/enum_names.hpp"
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
  for (const auto& row : aq::names_of<aq::config::OutputFormat>()) {
    const std::string f(row.name);
    EXPECT_NE(formats_line.find("\"" + f + "\""), std::string::npos) << f << " is not in example.toml's formats line";
    EXPECT_NE(section.find("`" + f + "`"), std::string::npos) << f << " is not in README's Output formats section";
  }
  EXPECT_EQ(aq::names_of<aq::config::OutputFormat>().size(), 9u);
}

// The comment of every enumerated key in example.toml names every value of the key's table (the
// one list of names: config/kinds.hpp, core/lattice.hpp), and every name loads and echoes as itself.
TEST(ExampleToml, CommentsNameEveryValueOfEveryEnumeratedKey) {
  std::ifstream in(fs::path(AQ_SOURCE_DIR) / "configs" / "example.toml");
  const std::string text(std::istreambuf_iterator<char>(in), {});
  int enumerated = 0;
  for (const auto& k : aq::config::global_key_info()) {
    if (k.values.empty()) continue;
    ++enumerated;
    const std::string section = k.key.substr(0, k.key.find('.')), name = k.key.substr(k.key.find('.') + 1);
    const auto sec_at = text.find("\n[" + section + "]");
    ASSERT_NE(sec_at, std::string::npos) << k.key;
    const auto at = text.find("\n" + name + " = ", sec_at);
    ASSERT_NE(at, std::string::npos) << k.key;
    const std::string line = text.substr(at + 1, text.find('\n', at + 1) - at - 1);
    for (const std::string& v : k.values) {
      EXPECT_NE(line.find("\"" + v + "\""), std::string::npos) << k.key << ": \"" << v << "\" is not in: " << line;
      const std::string value = k.key == "output.formats" ? "[\"" + v + "\"]" : "\"" + v + "\"";
      std::vector<std::string> sets{k.key + "=" + value};
      if (v == "box") sets.push_back("domain.box=[-5, 10, 49, 61]");
      if (v == "polygon") sets.push_back("domain.polygon=\"x.geojson\"");
      if (v == "squares") sets.push_back("output.formats=[\"msh\"]");
      const auto c = load_global(std::nullopt, sets);
      const auto& echoed = c.echo[section][name];
      EXPECT_EQ(k.key == "output.formats" ? echoed[0] : echoed, v) << k.key;
    }
    EXPECT_THAT(k.help, HasSubstr("one of \"" + k.values[0] + "\"")) << k.key;
  }
  EXPECT_EQ(enumerated, 11);  // with quadtree.engine (dense, forest)
}

// Each enumerated key refuses a name its table does not have, listing the ones it has.
TEST(Config, AnUnknownNameListsTheTable) {
  EXPECT_THAT(
      error_of(std::nullopt, {"mask.sampling=\"bilinear\""}),
      HasSubstr("--set mask.sampling=\"bilinear\": mask.sampling: \"bilinear\" is not one of \"vertex\", \"area\""));
  EXPECT_THAT(error_of(std::nullopt, {"output.formats=[\"msh\", \"stl\"]"}),
              HasSubstr("output.formats: element 1: \"stl\" is not one of \"msh\", \"ugrid\", \"vtu\", \"fort14\", "
                        "\"text\", \"png\", \"fesom\", \"schism\", \"tif\""));
  EXPECT_THAT(error_of(std::nullopt, {"quadtree.lattice=3"}),
              HasSubstr("quadtree.lattice: expected one of \"lonlat\", \"mercator\" in quotes"));
}

// One config with a bad value of nearly every kind: every one is reported in one message, each at
// the file:line:column of its value (a cross-key problem at the key set last, naming both keys).
TEST(Config, EveryBadValueIsReportedWithItsPositionInOneMessage) {
  const auto p = write_temp("many_bad.toml",
                            "[input]\n"
                            "interpolation = \"cubic\"\n"  // 2
                            "[mask]\n"
                            "min_depth_m = -500.0\n"     // 4
                            "cursor = 0\n"               // 5
                            "sampling = \"bilinear\"\n"  // 6
                            "seeds = [[0.0, nan]]\n"     // 7
                            "[quadtree]\n"
                            "step_deg = 7.0\n"      // 9
                            "levels = 2\n"          // 10
                            "balance = \"edge\"\n"  // 11
                            "box_rules = [{lon_min_deg = 0, lon_max_deg = 5, lat_min_deg = 0, lat_max_deg = 5, "
                            "level = 4}]\n"  // 12
                            "[size]\n"
                            "h_min_km = 50.0\n"  // 14
                            "h_max_km = 10.0\n"  // 15
                            "[domain]\n"
                            "box = [10.0, -5.0, 49.0, 61.0]\n"  // 17
                            "[mesh]\n"
                            "elements = \"squares\"\n"  // 19
                            "[output]\n"
                            "formats = [\"msh\", \"fort14\"]\n"         // 21
                            "png_color = \"angle\"\n"                   // 22
                            "png_width = 100\n"                         // 23
                            "png_zoom = [0.0, 400.0, -10.0, 10.0]\n");  // 24
  const std::string e = error_of(p.string(), {"output.vtu_coordinates=\"ecef\""});
  const std::string f = p.string();
  const std::vector<std::string> expected{
      f + ":2:17: input.interpolation: \"cubic\" is not one of \"bilinear\", \"bicubic\"",
      f + ":4:15: mask.min_depth_m: -500 is outside [-100, 12000]",
      f + ":5:10: mask.cursor: 0 is outside [1, 64]",
      f + ":6:12: mask.sampling: \"bilinear\" is not one of \"vertex\", \"area\"",
      f + ":7:9: mask.seeds: seed 0 = [0, nan]: expected a longitude in [-360, 360] and a latitude in [-90, 90]",
      f + ":9:12: quadtree.step_deg: 7: ",
      f + ":11:11: quadtree.balance: \"edge\" is not one of \"face\", \"corner\"",
      f + ":12:13: quadtree.box_rules[0].level, quadtree.levels: level 4 exceeds quadtree.levels = 2",
      f + ":15:12: size.h_min_km, size.h_max_km: size.h_min_km = 50 is above size.h_max_km = 10",
      f + ":17:7: domain.box: lon_min = 10 > lon_max = -5 reads as a box across the seam 345° wide",
      f + ":21:11: output.formats, mesh.elements: \"fort14\" needs triangles but mesh.elements = \"squares\"",
      f + ":22:13: output.png_color, mesh.elements: output.png_color = \"angle\" colours triangles",
      f + ":23:13: output.png_width: 100 is outside [200, 20000]",
      f + ":24:12: output.png_zoom: expected 4 finite numbers",
      "--set output.vtu_coordinates=\"ecef\": output.vtu_coordinates: \"ecef\" is not one of \"sphere\", \"wgs84\""};
  EXPECT_THAT(e, HasSubstr(fmt::format("{} configuration errors:", expected.size())));
  std::size_t last = 0;
  for (const std::string& x : expected) {
    const auto at = e.find(x);
    EXPECT_NE(at, std::string::npos) << "missing: " << x << "\nin:\n" << e;
    if (at != std::string::npos) {
      EXPECT_GT(at, last) << "out of order: " << x;  // sorted by position, --set after the file
      last = at;
    }
  }
}

// A cross-key problem is reported where the key set last was set: a --set when the other key is
// at its default (the default output.formats hold fort14).
TEST(Config, ACrossKeyProblemNamesWhereItsKeysWereSet) {
  EXPECT_THAT(error_of(std::nullopt, {"size.h_max_km=10", "size.h_min_km=20"}),
              HasSubstr("--set size.h_min_km=20: size.h_min_km, size.h_max_km: size.h_min_km = 20 is above "
                        "size.h_max_km = 10"));
  EXPECT_NO_THROW((void)load_global(std::nullopt, {"size.h_min_km=20"}));  // h_max_km = 0: no upper clamp
  EXPECT_THAT(error_of(std::nullopt, {"mesh.elements=\"squares\""}),
              HasSubstr("--set mesh.elements=\"squares\": output.formats, mesh.elements: \"fort14\" needs triangles"));
  EXPECT_THAT(error_of(std::nullopt, {"domain.kind=\"box\""}),
              HasSubstr("--set domain.kind=\"box\": domain.kind: \"box\" needs domain.box"));
}

// Found by probing (issue 33): a seed at longitude 1e300 meshed from wherever it landed, a box
// rule at 1e15° applied nowhere, a zoom at 1000° drew nothing; a FIFO as domain.polygon blocked
// OGR for ever and one as size.raster was refused only when the run reached the size stage.
TEST(Config, LongitudesAreWithin360AndInputFilesAreFilesAtLoad) {
  EXPECT_THAT(error_of(std::nullopt, {"mask.seeds=[[1e300, 0]]"}),
              HasSubstr("mask.seeds: seed 0 = [1e+300, 0]: expected a longitude in [-360, 360]"));
  EXPECT_THAT(error_of(std::nullopt, {"quadtree.box_rules=[{lon_min_deg = 1e15, lon_max_deg = 2e15, lat_min_deg = "
                                      "0, lat_max_deg = 10, level = 1}]"}),
              HasSubstr("quadtree.box_rules[0]: needs -360 <= lon_min_deg < lon_max_deg <= 360"));
  EXPECT_THAT(error_of(std::nullopt, {"output.png_zoom=[1000, 1100, 0, 10]"}), HasSubstr("output.png_zoom: expected"));
  EXPECT_THAT(error_of(std::nullopt, {"blocks.boxes=[[400, 410, 0, 10]]"}), HasSubstr("blocks.boxes: box 0"));
  EXPECT_NO_THROW((void)load_global(std::nullopt, {"mask.seeds=[[350, -50]]", "output.png_zoom=[150, 210, 0, 10]"}));
  const fs::path dir = fs::temp_directory_path() / "aq_config_test";
  fs::create_directories(dir);
  const fs::path fifo = dir / "fifo";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THAT(error_of(std::nullopt, {"domain.polygon=\"" + fifo.string() + "\""}),
              HasSubstr("domain.polygon: " + fifo.string() + " is a FIFO (named pipe), not a regular file"));
  EXPECT_THAT(error_of(std::nullopt, {"size.raster=\"" + fifo.string() + "\""}),
              HasSubstr("size.raster: " + fifo.string() + " is a FIFO (named pipe), not a regular file"));
  fs::remove(fifo);
}

// Issue 33: `domain.box = [10, -5, 49, 61]` (meant as [-5, 10, ...]) meshed a 345° band of the
// North Pacific. A box across the seam wider than 180° is refused with both readings; one
// narrower than 180° is taken as across the seam, and the wide one can still be written with
// lon_max > lon_min.
TEST(Config, AWideBoxAcrossTheSeamIsRefusedNamingBothReadings) {
  const std::string e = error_of(std::nullopt, {"domain.box=[10, -5, 49, 61]"});
  EXPECT_THAT(e, HasSubstr("reads as a box across the seam 345° wide (east from 10° to -5°)"));
  EXPECT_THAT(e, HasSubstr("for the 15° from -5° to 10° write [-5, 10, 49, 61] (lon_max > lon_min)"));
  EXPECT_THAT(e, HasSubstr("for that seam-crossing box write [10, 355, 49, 61]"));
  EXPECT_THAT(error_of(std::nullopt, {"domain.box=[100, 10, 49, 61]"}), HasSubstr("write [-260, 10, 49, 61]"));
  EXPECT_NO_THROW((void)load_global(std::nullopt, {"domain.box=[200, 10, 49, 61]"}));  // 170° across the seam
  const auto across = load_global(std::nullopt, {"domain.box=[170, -170, -10, 10]"});  // 20° across the seam
  EXPECT_EQ(across.options.domain.resolved, aq::config::DomainKind::kBox);
  const auto wide = load_global(std::nullopt, {"domain.box=[10, 355, 49, 61]"});  // the 345° band, unambiguous
  EXPECT_EQ(wide.options.domain.box[1], 355.0);
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

TEST(Config, AStepNotWithinRoundingIsRefusedWithTheReason) {
  EXPECT_THAT(error_of(std::nullopt, {"quadtree.step_deg=0.26667"}),
              HasSubstr("quadtree.step_deg: 0.26667: Δ0 = 960.012\" is not a whole number of arc-seconds"));
  EXPECT_THAT(error_of(std::nullopt, {"quadtree.mercator_lat_max_deg=90"}),
              HasSubstr("quadtree.mercator_lat_max_deg: 90 is outside [1, 89.5]"));
}

TEST(Config, PreviewSizeAndZoomAreCheckedAtLoad) {
  EXPECT_THAT(error_of(std::nullopt, {"output.png_width=10"}),
              HasSubstr("output.png_width: 10 is outside [200, 20000]"));
  for (const char* z : {"[1, 2, 3]", "[10, 5, 0, 1]", "[0, 10, 20, 10]", "[0, 10, -95, 0]", "[0, inf, 0, 1]",
                        "[0, 400, 0, 1]", "[0, nan, 0, 1]"})
    EXPECT_THAT(error_of(std::nullopt, {std::string("output.png_zoom=") + z}),
                HasSubstr("output.png_zoom: expected 4 finite numbers"))
        << z;
  EXPECT_NO_THROW((void)load_global(std::nullopt, {"output.png_zoom=[150, 210, -60, -10]"}));
}

// The size targets and depth bands the quadtree and size stages once checked themselves.
TEST(Config, SizeTargetsAndRuleRangesAreCheckedAtLoad) {
  EXPECT_THAT(error_of(std::nullopt, {"quadtree.size_km=-1"}),
              HasSubstr("quadtree.size_km: -1 is outside [0, 100000]"));
  EXPECT_THAT(error_of(std::nullopt, {"quadtree.coast_size_km=nan"}),
              HasSubstr("quadtree.coast_size_km: nan is outside [0, 100000]"));
  EXPECT_THAT(error_of(std::nullopt, {"quadtree.coast_band=-1"}),
              HasSubstr("quadtree.coast_band: -1 is outside [0, 64]"));
  EXPECT_THAT(error_of(std::nullopt, {"quadtree.depth_rules=[{min_depth_m = 100, max_depth_m = 50, level = 1}]"}),
              HasSubstr("quadtree.depth_rules[0]: needs min_depth_m < max_depth_m"));
  EXPECT_THAT(
      error_of(std::nullopt, {"quadtree.box_rules=[{lon_min_deg = 0, lon_max_deg = 10, lat_min_deg = 20, "
                              "lat_max_deg = 10, level = 1}]"}),
      HasSubstr("quadtree.box_rules[0]: needs -360 <= lon_min_deg < lon_max_deg <= 360 and -90 <= lat_min_deg"));
  EXPECT_THAT(error_of(std::nullopt, {"quadtree.depth_rules=[{min_depth_m = 0, max_depth_m = 50, level = 9}]"}),
              HasSubstr("quadtree.depth_rules[0].level, quadtree.levels: level 9 exceeds quadtree.levels = 3"));
}

// Found by fuzzing (issue 33): toml11 read past its buffer on an invalid UTF-8 byte inside a
// literal string. A configuration file or --set value that is not UTF-8 is refused first.
TEST(Config, TextThatIsNotUtf8IsRefusedWithItsPosition) {
  const auto p = write_temp("latin1.toml", "[output]\nname = 'Caf\xe9'\n");
  EXPECT_THAT(error_of(p.string()), HasSubstr("latin1.toml: line 2, column 12: not UTF-8 text"));
  EXPECT_THAT(error_of(std::nullopt, {"output.name='\xff'"}), HasSubstr("value is neither TOML nor plain text"));
  EXPECT_NO_THROW((void)load_global(std::nullopt, {"output.name='Café'"}));
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
  EXPECT_THAT(
      error_of(p.string()),
      HasSubstr("rules.toml:4:13: quadtree.box_rules[0].level, quadtree.levels: level 5 exceeds quadtree.levels = 3"));
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

// Issue 33: what the forest engine cannot do was refused inside its stages, one problem at a time
// and with no position (mask.sampling = "area", quadtree.levels = 0, a coastal band or K-cursor
// wider than its patches of 2^min(L, 7) pixels, the global run file). Now at load, every one at
// the position of the key set last, together with the other problems of the file.
TEST(Config, WhatTheForestEngineCannotDoIsRefusedAtLoadAllAtOnce) {
  if (!aq::config::forest_engine_built()) GTEST_SKIP() << "built without the forest engine (AQ_MPI=OFF)";
  const auto p = write_temp("forest_bad.toml",
                            "[quadtree]\n"
                            "engine = \"forest\"\n"  // 2
                            "levels = 2\n"           // 3: patches of 4 x 4 pixels
                            "coast_band = 8\n"       // 4
                            "[mask]\n"
                            "cursor = 5\n"           // 6
                            "sampling = \"area\"\n"  // 7
                            "[output]\n"
                            "formats = [\"msh\", \"tif\"]\n"  // 9
                            "png_width = 10\n");              // 10: a problem of one key beside them
  const std::string e = error_of(p.string());
  const std::string f = p.string();
  const std::vector<std::string> expected{
      f + ":4:14: quadtree.coast_band, quadtree.levels, quadtree.engine: quadtree.coast_band = 8: the forest engine "
          "needs at most 4 pixels (its patches of 2^min(quadtree.levels, 7) pixels)",
      f + ":6:10: mask.cursor, quadtree.levels, quadtree.engine: mask.cursor = 5: the forest engine needs K <= 4 "
          "pixels",
      f + ":7:12: mask.sampling, quadtree.engine: mask.sampling = \"area\": the forest engine classifies by the "
          "vertex rule only",
      f + ":9:11: output.formats, quadtree.engine: output.formats = [..., \"tif\"]: the global run file holds the "
          "lattice's bitmaps, which the forest engine never makes",
      f + ":10:13: output.png_width: 10 is outside [200, 20000]"};
  EXPECT_THAT(e, HasSubstr(fmt::format("{} configuration errors:", expected.size())));
  for (const std::string& x : expected) EXPECT_THAT(e, HasSubstr(x));
  // The same keys on the dense engine are fine.
  EXPECT_NO_THROW((void)load_global(std::nullopt, {"quadtree.levels=2", "quadtree.coast_band=8", "mask.cursor=5",
                                                   "mask.sampling=\"area\"", "output.formats=[\"msh\", \"tif\"]"}));
  // quadtree.levels = 0: one problem (not the band and the cursor as well), where levels was set.
  const std::string zero = error_of(std::nullopt, {"quadtree.engine=\"forest\"", "quadtree.levels=0"});
  EXPECT_THAT(zero, HasSubstr("1 configuration error:"));
  EXPECT_THAT(zero, HasSubstr("--set quadtree.levels=0: quadtree.levels, quadtree.engine: quadtree.levels = 0: the "
                              "forest engine needs at least one level"));
  // Patches stop growing at 2^7 = 128 pixels: L = 9 with a band of 64 and K = 64 fits.
  EXPECT_NO_THROW((void)load_global(std::nullopt, {"quadtree.engine=\"forest\"", "quadtree.step_deg=4",
                                                   "quadtree.levels=9", "quadtree.coast_band=64", "mask.cursor=64"}));
  EXPECT_EQ(aq::config::forest_patch_pixels(0), 1);
  EXPECT_EQ(aq::config::forest_patch_pixels(3), 8);
  EXPECT_EQ(aq::config::forest_patch_pixels(12), 128);
}

// A build without MPI and p4est refuses the forest engine at load, with the key's position (it
// was refused when the pipeline started).
TEST(Config, TheForestEngineIsRefusedAtLoadWhereItIsNotBuilt) {
  const std::string e = error_of(std::nullopt, {"quadtree.engine=\"forest\""});
  if (aq::config::forest_engine_built()) {
    EXPECT_EQ(e, "");
  } else {
    EXPECT_THAT(e, HasSubstr("--set quadtree.engine=\"forest\": quadtree.engine: \"forest\": this aquatoria was "
                             "built without the forest engine"));
  }
}

// Issue 33: `aquatoria blocks` and a regional ROMS grid's roms.global_config refused a floodplain
// (and the ROMS grid several rasters) once the run had started, without a position; the command's
// use of the configuration now joins the checks at load.
TEST(Config, WhatACommandCannotTakeIsRefusedAtLoadWithItsPosition) {
  using aq::config::GlobalUse;
  const auto error_for = [](const std::vector<std::string>& over, GlobalUse use) -> std::string {
    try {
      (void)load_global(std::nullopt, over, use);
    } catch (const aq::ConfigError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error_for({"mask.min_depth_m=-5"}, GlobalUse::kMesh), "");  // a surge mesh
  EXPECT_THAT(error_for({"mask.min_depth_m=-5"}, GlobalUse::kBlocks),
              HasSubstr("--set mask.min_depth_m=-5: mask.min_depth_m: mask.min_depth_m = -5 meshes a floodplain above "
                        "the datum; the blocks' regional ROMS grids share this run's land mask"));
  const auto p = write_temp("roms_global_bad.toml",
                            "[input]\n"
                            "paths = [\"" AQ_ETOPO_DIR "/etopo20.cdf\", \"" AQ_ETOPO_DIR
                            "/etopo60.cdf\"]\n"  // 2
                            "[mask]\n"
                            "min_depth_m = -2.0\n");  // 4
  const std::string f = p.string();
  std::string e;
  try {
    (void)load_global(f, {}, GlobalUse::kRomsGlobal);
  } catch (const aq::ConfigError& x) {
    e = x.what();
  }
  EXPECT_THAT(e, HasSubstr("2 configuration errors:"));
  EXPECT_THAT(e, HasSubstr(f + ":2:9: input.paths: input.paths lists 2 rasters; a ROMS grid's cell depths"));
  EXPECT_THAT(e, HasSubstr(f + ":4:15: mask.min_depth_m: mask.min_depth_m = -2 meshes a floodplain up to 2 m above "
                               "the datum, which a ROMS grid's land mask"));
  EXPECT_NO_THROW((void)load_global(f, {}));  // the same file meshes a surge domain
  // Python's mask() returns the dense engine's bitmaps.
  EXPECT_THAT(error_for({"quadtree.engine=\"forest\""}, GlobalUse::kMask),
              aq::config::forest_engine_built()
                  ? HasSubstr("--set quadtree.engine=\"forest\": quadtree.engine: \"forest\": the "
                              "mask and levels are the dense engine's bitmaps")
                  : HasSubstr("built without the forest engine"));
  EXPECT_EQ(error_for({}, GlobalUse::kMask), "");
}

// output.png_zoom on the Mercator lattice must reach its rows: refused at load (it was refused
// when the preview was drawn, after the whole run).
TEST(Config, APngZoomBeyondTheMercatorRowsIsRefusedAtLoad) {
  EXPECT_THAT(error_of(std::nullopt, {"quadtree.lattice=\"mercator\"", "output.png_zoom=[0, 10, 89.9, 90]"}),
              HasSubstr("--set output.png_zoom=[0, 10, 89.9, 90]: output.png_zoom, quadtree.mercator_lat_max_deg, "
                        "quadtree.lattice: output.png_zoom: latitudes [89.9, 90] are outside the Mercator lattice's "
                        "rows"));
  EXPECT_NO_THROW(
      (void)load_global(std::nullopt, {"quadtree.lattice=\"mercator\"", "output.png_zoom=[0, 10, 80, 90]"}));
  EXPECT_NO_THROW((void)load_global(std::nullopt, {"output.png_zoom=[0, 10, 89.9, 90]"}));  // lon/lat rows reach 90°
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
                  "mesh.elements=\"squares\"", "output.formats=[\"msh\"]"}),
            "global_4deg_L3_my_etopo1_corner_cb0_squares");
  // A key that changes the mesh but has no part in the name still gives a parameter name.
  EXPECT_EQ(name({"mesh.diagonal=\"nw\""}), "global_4deg_L3");
}

TEST(RunName, ListsWhatDiffersFromTheSeedRun) {
  const auto n = aq::config::default_run_name(
      load_global(std::nullopt, {"quadtree.step_deg=1", "mask.min_depth_m=10", "output.name=ignored"}).options);
  EXPECT_THAT(n.changed, ::testing::ElementsAre("mask.min_depth_m = 10.0", "quadtree.step_deg = 1.0"));
  EXPECT_TRUE(n.unnamed.empty());  // both are in the name
}

// What the name does not show is listed (`aquatoria mesh` warns: such runs write the same files).
TEST(RunName, ListsWhatTheNameDoesNotShow) {
  const auto n = aq::config::default_run_name(
      load_global(std::nullopt, {"quadtree.step_deg=1", "mesh.diagonal=\"nw\"", "size.wavelength.wl=30"}).options);
  EXPECT_EQ(n.name, "global_1deg_L3");
  EXPECT_THAT(n.unnamed, ::testing::ElementsAre("size.wavelength.wl = 30.0", "mesh.diagonal = \"nw\""));
  EXPECT_TRUE(aq::config::default_run_name(load_global(std::nullopt, {}).options).unnamed.empty());
}

}  // namespace unit_config_config_test

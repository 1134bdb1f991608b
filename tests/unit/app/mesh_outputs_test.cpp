// write_mesh_outputs: file names per format, one log line per file, facts, option errors before
// any file is written, and all-or-nothing through the OutputSet.
#include "app/mesh_outputs.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "support/file_size_limit.hpp"
#include "support/io_test_mesh.hpp"
#include "support/temp_dir.hpp"

namespace aq::io {
namespace {

raster::Bathymetry flat_sea() {
  return raster::Bathymetry::from_grid(std::vector<float>(36 * 19, -3000.0f), 36, 19, -180.0, -90.0, 10.0, 10.0);
}

std::set<std::string> files_in(const std::filesystem::path& dir) {
  std::set<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

struct CapturedLog {
  std::vector<std::string> lines;
  Logger logger{[this](LogLevel, std::string_view m) { lines.emplace_back(m); }};
};

TEST(MeshOutputs, EveryFormatWithItsFileNameAndOneLogLine) {
  testing::TempDir dir;
  config::OutputOptions o;
  o.name = "tiny";
  o.png_width = 400;
  o.png_zoom = {150.0, 210.0, -60.0, -10.0};
  CapturedLog log;
  std::vector<WrittenFile> w;
  {
    OutputSet set(dir.path());
    w = write_mesh_outputs(testing::tiny_mesh(), flat_sea(), o, set, log.logger);
    set.commit();
  }
  std::vector<std::string> names, formats;
  for (const auto& f : w) {
    names.push_back(f.name);
    formats.push_back(f.format);
    EXPECT_EQ(f.bytes, static_cast<std::int64_t>(std::filesystem::file_size(f.path))) << f.name;
    EXPECT_GE(f.seconds, 0.0);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"tiny.msh", "tiny.nc", "tiny.vtu", "tiny.14", "tiny.txt", "tiny.png",
                                             "tiny_zoom.png"}));
  EXPECT_EQ(formats, (std::vector<std::string>{"msh", "ugrid", "vtu", "fort14", "text", "png", "png_zoom"}));
  EXPECT_EQ(files_in(dir.path()), std::set<std::string>(names.begin(), names.end()));
  // One line per file, one for the geographic mesh and one for its shape quality on the sphere,
  // both before the first file: the tiny mesh's pole row is not all ocean, so it is merged (3
  // nodes into 1, 2 triangles dropped).
  ASSERT_EQ(log.lines.size(), 9u);
  EXPECT_NE(log.lines[0].find("geographic mesh: North pole: pole row merged into one node (2 nodes merged, 2 "
                              "degenerate triangles dropped)"),
            std::string::npos)
      << log.lines[0];
  EXPECT_EQ(log.lines[1].rfind("quality: 15 triangles on the sphere: min angle", 0), 0u) << log.lines[1];
  EXPECT_NE(log.lines[4].find("tiny.vtu"), std::string::npos);
  EXPECT_NE(log.lines[4].find("19 points, 15 cells"), std::string::npos) << log.lines[4];
  // UGRID, VTU, fort.14 and text write the same geographic mesh; MSH (λ–φ plane) the lattice one.
  for (const std::size_t k : {1, 2, 3, 4}) EXPECT_EQ(w[k].stats.nodes, 19) << w[k].name;
  EXPECT_EQ(w[0].stats.nodes, 21 + 2);
  EXPECT_EQ(w[0].stats.seam_duplicates, 2);
}

TEST(MeshOutputs, UnknownFormatIsAConfigErrorAndNothingIsWritten) {
  testing::TempDir dir;
  config::OutputOptions o;
  o.formats = {"msh", "stl"};
  try {
    OutputSet set(dir.path());
    write_mesh_outputs(testing::tiny_mesh(), flat_sea(), o, set, Logger::null());
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("output.formats"), std::string::npos) << what;
    EXPECT_NE(what.find("\"stl\""), std::string::npos) << what;
  }
  EXPECT_TRUE(files_in(dir.path()).empty());
}

TEST(MeshOutputs, OptionErrorsNameTheirKeys) {
  auto message = [](const config::OutputOptions& o, ElementKinds k) {
    try {
      check_mesh_output_options(o, k);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  config::OutputOptions o;
  EXPECT_EQ(message(o, ElementKinds::kTriangles), "");
  EXPECT_NE(message(o, ElementKinds::kSquares).find("mesh.elements"), std::string::npos);
  o.vtu_coordinates = "ecef";
  EXPECT_NE(message(o, ElementKinds::kTriangles).find("output.vtu_coordinates"), std::string::npos);
  o = {};
  o.png_zoom = {1, 2};
  EXPECT_NE(message(o, ElementKinds::kTriangles).find("output.png_zoom"), std::string::npos);
  o = {};
  o.name = "a/b";
  EXPECT_NE(message(o, ElementKinds::kTriangles).find("output.name"), std::string::npos);
}

TEST(MeshOutputs, SquaresOnlyAndDuplicateFormats) {
  testing::TempDir dir;
  config::OutputOptions o;
  o.formats = {"msh", "ugrid", "msh", "text"};
  MeshOutputInfo info;
  info.elements = ElementKinds::kSquares;
  OutputSet set(dir.path());
  const auto w = write_mesh_outputs(testing::tiny_mesh(false), flat_sea(), o, set, Logger::null(), info);
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[0].stats.elements, 7);
  EXPECT_EQ(w[1].stats.elements, 7);
}

TEST(MeshOutputs, AFailingWriterLeavesNoFiles) {
  testing::TempDir dir;
  config::OutputOptions o;
  o.formats = {"text", "msh"};
  const auto m = testing::band_mesh(Lattice::make(4.0, 1, -180.0), 10, 80);
  try {
    OutputSet set(dir.path());
    testing::FileSizeLimit limit(64 * 1024);
    write_mesh_outputs(m, flat_sea(), o, set, Logger::null());
    set.commit();
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("mesh.txt"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(files_in(dir.path()).empty());
}

}  // namespace
}  // namespace aq::io

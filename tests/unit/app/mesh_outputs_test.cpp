// SPDX-License-Identifier: GPL-3.0-or-later
// write_mesh_outputs: file names per format, one log line per file, facts, option errors before
// any file is written, and all-or-nothing through the OutputSet.
#include "app/mesh_outputs.hpp"

#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "support/file_size_limit.hpp"
#include "support/io_test_mesh.hpp"
#include "support/msh_parse.hpp"
#include "support/synthetic_raster.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_app_mesh_outputs_test {
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

// The lines with their timings ("0.012 s", "0.004 s CPU") replaced by "T s".
std::vector<std::string> without_times(const std::vector<std::string>& lines) {
  static const std::regex seconds("[0-9]+\\.[0-9]+ s");
  std::vector<std::string> out;
  for (const auto& l : lines) out.push_back(std::regex_replace(l, seconds, "T s"));
  return out;
}

struct Written {
  std::vector<WrittenFile> files;
  std::vector<std::string> lines;
  std::vector<std::string> bytes;  // of each file, in order
};

Written write_all(const std::filesystem::path& dir, const mesh::Mesh& m, const raster::Bathymetry& bathy,
                  bool concurrent, ElementKinds elements = ElementKinds::kTriangles) {
  config::OutputOptions o;
  o.name = "tiny";
  o.png_width = 400;
  o.png_zoom = {150.0, 210.0, -60.0, -10.0};
  using F = config::OutputFormat;
  o.formats = {F::kMsh, F::kUgrid, F::kVtu, F::kFort14, F::kText, F::kPng, F::kFesom, F::kSchism};
  MeshOutputInfo info;
  info.concurrent = concurrent;
  info.elements = elements;
  CapturedLog log;
  Written w;
  OutputSet set(dir);
  w.files = write_mesh_outputs(m, bathy, o, set, log.logger, info);
  set.commit();
  w.lines = without_times(log.lines);
  for (const auto& f : w.files) w.bytes.push_back(testing::read_file_bytes(f.path.string()));
  return w;
}

// The UGRID file written beside the others: the same files, bytes, lines (in the same order) and
// facts as one file after another. With squares and triangles, the UGRID file's geographic mesh
// is built for it, and its line comes after the msh file's.
TEST(MeshOutputs, WritingUgridBesideTheOthersChangesNothingButTheThread) {
  testing::TempDir one, two;
  const auto m = testing::tiny_mesh(true, {true, -44.858333, 78.141667});
  const Written seq = write_all(one.path(), m, flat_sea(), false, ElementKinds::kBoth);
  const Written con = write_all(two.path(), m, flat_sea(), true, ElementKinds::kBoth);
  ASSERT_EQ(seq.files.size(), 12u);
  ASSERT_EQ(con.files.size(), seq.files.size());
  for (std::size_t k = 0; k < seq.files.size(); ++k) {
    EXPECT_EQ(con.files[k].name, seq.files[k].name);
    EXPECT_EQ(con.files[k].bytes, seq.files[k].bytes) << seq.files[k].name;
    EXPECT_EQ(con.files[k].facts, seq.files[k].facts) << seq.files[k].name;
    EXPECT_TRUE(con.bytes[k] == seq.bytes[k]) << seq.files[k].name;
    EXPECT_FALSE(seq.files[k].own_thread);
    EXPECT_EQ(con.files[k].own_thread, con.files[k].format == "ugrid") << con.files[k].name;
  }
  EXPECT_EQ(con.lines, seq.lines);
  // The held-back lines (geographic meshes, quality, FESOM namelist) stay where they were.
  std::string all;
  for (const auto& l : seq.lines) all += l + "\n";
  ASSERT_EQ(seq.lines.size(), 18u) << all;
  EXPECT_EQ(seq.lines[0].rfind("geographic mesh: ", 0), 0u) << seq.lines[0];
  EXPECT_EQ(seq.lines[2].rfind("output: tiny.msh", 0), 0u) << seq.lines[2];
  EXPECT_EQ(seq.lines[3].rfind("geographic mesh: ", 0), 0u) << seq.lines[3];
  EXPECT_EQ(seq.lines[4].rfind("output: tiny.nc", 0), 0u) << seq.lines[4];
  EXPECT_EQ(seq.lines[6].rfind("mesh cleaning: 7 triangles with one neighbour removed in 2 rounds, 0 pinches", 0), 0u)
      << seq.lines[6];
  EXPECT_EQ(seq.lines[7].rfind("output: tiny.14", 0), 0u) << seq.lines[7];
  EXPECT_EQ(seq.lines[14].rfind("FESOM namelist.config &geometry: force_rotation = .true.", 0), 0u) << seq.lines[14];
  EXPECT_EQ(seq.lines[15].rfind("SCHISM time step: ", 0), 0u) << seq.lines[15];
}

// A streamed raster is read through GDAL while the preview samples it: nothing beside.
TEST(MeshOutputs, AStreamedRasterWritesOneFileAfterAnother) {
  testing::TempDir dir;
  raster::OpenOptions ro;
  ro.path = aq::test::write_tiff(dir / "sea.tif", 2.0, true, true).string();
  ro.allow_streaming = true;
  ro.streaming = raster::OpenOptions::Streaming::kAlways;
  const auto streamed = raster::Bathymetry::open(ro);
  ASSERT_TRUE(streamed.info().streamed);
  ro.streaming = raster::OpenOptions::Streaming::kNever;
  const auto held = raster::Bathymetry::open(ro);
  ASSERT_FALSE(held.info().streamed);
  std::filesystem::create_directories(dir / "streamed");
  std::filesystem::create_directories(dir / "held");
  const auto m = testing::tiny_mesh();
  const Written s = write_all(dir / "streamed", m, streamed, true);
  const Written h = write_all(dir / "held", m, held, true);
  ASSERT_EQ(s.files.size(), h.files.size());
  int beside = 0;
  for (std::size_t k = 0; k < s.files.size(); ++k) {
    EXPECT_FALSE(s.files[k].own_thread) << s.files[k].name;
    beside += h.files[k].own_thread ? 1 : 0;
    EXPECT_TRUE(s.bytes[k] == h.bytes[k]) << s.files[k].name;
  }
  EXPECT_EQ(beside, 1);
  EXPECT_EQ(s.lines, h.lines);
}

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
  std::string all;
  for (const auto& l : log.lines) all += l + "\n";
  ASSERT_EQ(log.lines.size(), 10u) << all;
  EXPECT_NE(log.lines[0].find("geographic mesh: North pole: pole row merged into one node (2 nodes merged, 2 "
                              "degenerate triangles dropped)"),
            std::string::npos)
      << log.lines[0];
  EXPECT_EQ(log.lines[1].rfind("quality: 15 triangles on the sphere: min angle", 0), 0u) << log.lines[1];
  EXPECT_NE(log.lines[4].find("tiny.vtu"), std::string::npos);
  EXPECT_NE(log.lines[4].find("19 points, 15 cells"), std::string::npos) << log.lines[4];
  // UGRID, VTU and text write the same geographic mesh; MSH (λ–φ plane) the lattice one; fort.14
  // the geographic mesh cleaned for the models: the seam strip C+D, the merged pole pair and B1's
  // corner triangle have (or come to have) one neighbour; A's fan and 3 of B's triangles stay.
  for (const std::size_t k : {1, 2, 4}) EXPECT_EQ(w[k].stats.nodes, 19) << w[k].name;
  EXPECT_EQ(log.lines[5].rfind("mesh cleaning: 7 triangles with one neighbour removed in 2 rounds", 0), 0u)
      << log.lines[5];
  EXPECT_EQ(w[3].stats.nodes, 8);
  EXPECT_EQ(w[3].stats.elements, 8);
  EXPECT_EQ(w[0].stats.nodes, 21 + 2);
  EXPECT_EQ(w[0].stats.seam_duplicates, 2);
}

// A model format of a mesh without triangles is refused before anything is written.
TEST(MeshOutputs, AModelFormatWithoutTrianglesIsAConfigErrorAndNothingIsWritten) {
  testing::TempDir dir;
  config::OutputOptions o;
  o.formats = {config::OutputFormat::kMsh, config::OutputFormat::kFort14};
  MeshOutputInfo info;
  info.elements = ElementKinds::kSquares;
  try {
    OutputSet set(dir.path());
    write_mesh_outputs(testing::tiny_mesh(false), flat_sea(), o, set, Logger::null(), info);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("output.formats, mesh.elements"), std::string::npos) << what;
    EXPECT_NE(what.find("\"fort14\" needs triangles"), std::string::npos) << what;
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
  o.png_color = config::PreviewColour::kAngle;
  o.formats = {config::OutputFormat::kPng};
  EXPECT_NE(message(o, ElementKinds::kSquares).find("output.png_color, mesh.elements"), std::string::npos);
  o = {};
  o.name = "a/b";
  EXPECT_NE(message(o, ElementKinds::kTriangles).find("output.name"), std::string::npos);
  o.name = "..";
  EXPECT_NE(message(o, ElementKinds::kTriangles).find("output.name"), std::string::npos);
}

TEST(MeshOutputs, SquaresOnlyAndDuplicateFormats) {
  testing::TempDir dir;
  config::OutputOptions o;
  using F = config::OutputFormat;
  o.formats = {F::kMsh, F::kUgrid, F::kMsh, F::kText};
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
  o.formats = {config::OutputFormat::kText, config::OutputFormat::kMsh};
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
}  // namespace aq::io::unit_app_mesh_outputs_test

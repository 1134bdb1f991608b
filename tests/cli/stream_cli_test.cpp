// SPDX-License-Identifier: GPL-3.0-or-later
// Memory estimate and refusal of `aquatoria mesh` (issue 9): the estimate is printed before the
// run and written to the report with the measured peak; a run whose estimate is above
// input.max_memory_gb exits 2 before any raster data is read, naming the key and both numbers.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/cli_outputs.hpp"
#include "support/run_command.hpp"

namespace cli_stream_cli_test {

using aq::test::fresh_dir;
using aq::test::run_aquatoria;
using ::testing::HasSubstr;
using ::testing::MatchesRegex;
using ::testing::Not;
namespace fs = std::filesystem;

namespace {

// A VRT with a valid header whose data file does not exist: opening it works, reading fails.
fs::path unreadable_vrt() {
  const fs::path dir = fs::temp_directory_path() / ("aq_stream_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path p = dir / "header_only.vrt";
  std::ofstream(p) << R"(<VRTDataset rasterXSize="4320" rasterYSize="2160">
  <SRS>EPSG:4326</SRS>
  <GeoTransform>-180, 0.0833333333333333, 0, 90, 0, -0.0833333333333333</GeoTransform>
  <VRTRasterBand dataType="Int16" band="1">
    <SimpleSource>
      <SourceFilename relativeToVRT="1">missing_tile.tif</SourceFilename>
      <SourceBand>1</SourceBand>
      <SrcRect xOff="0" yOff="0" xSize="4320" ySize="2160"/>
      <DstRect xOff="0" yOff="0" xSize="4320" ySize="2160"/>
    </SimpleSource>
  </VRTRasterBand>
</VRTDataset>
)";
  return p;
}

}  // namespace

TEST(StreamCli, MemoryRefusalExits2BeforeReading) {
  const fs::path vrt = unreadable_vrt();
  const fs::path dir = fresh_dir("stream", "refuse");
  // Without a limit the run gets as far as reading, which fails (exit 1)...
  auto r = run_aquatoria("mesh -q -o " + dir.string() + " --set input.path=\"" + vrt.string() + "\"");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("missing_tile.tif"));
  // ...with a limit below the estimate it is refused before that (exit 2), naming the key.
  r = run_aquatoria("mesh -q -o " + dir.string() + " --set input.path=\"" + vrt.string() +
                    "\" --set input.max_memory_gb=0.05");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("input.max_memory_gb = 0.05 GB"));
  EXPECT_THAT(r.err, MatchesRegex("(.|\n)*estimated to need 0\\.[0-9]+ GB(.|\n)*"));
  EXPECT_THAT(r.err, HasSubstr("nothing was read"));
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("missing_tile.tif: read error")));
  EXPECT_TRUE(!fs::exists(dir) || fs::is_empty(dir));
}

TEST(StreamCli, EstimateIsPrintedAndReportedWithThePeak) {
  const fs::path dir = fresh_dir("stream", "estimate");
  const auto r = run_aquatoria("mesh -o " + dir.string() + " --set 'output.formats=[\"text\"]'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("memory: estimate "));
  EXPECT_THAT(r.err, HasSubstr("held whole"));
  const auto rep = aq::test::read_report(dir, "seed_4deg_L3");
  const auto& m = rep.at("memory");
  EXPECT_GT(m.at("estimate_bytes").get<double>(), m.at("estimate_raster_bytes").get<double>());
  EXPECT_GT(m.at("peak_rss_bytes").get<double>(), 1e6);
  // The model is within a factor 2 of the measured peak on this small run.
  EXPECT_LT(m.at("peak_rss_bytes").get<double>(), 2.0 * m.at("estimate_bytes").get<double>());
  EXPECT_FALSE(m.at("raster_streamed").get<bool>());
}

namespace {

// `aquatoria info` streams a raster it cannot hold (a 15" GEBCO/ETOPO 2022 file needs 15 GB as
// float32): one banded pass gives the same statistics and samples as holding it whole.
TEST(StreamCli, InfoStreamsABigRasterWithTheSameStatistics) {
  const std::string etopo5 = "/usr/share/ferret-vis/data/etopo5.cdf";
  const auto whole = run_aquatoria("info " + etopo5 + " --at -150,0 --at 10,50");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const auto streamed = run_aquatoria("info " + etopo5 + " --at -150,0 --at 10,50 --max-memory-gb 0.02");
  ASSERT_EQ(streamed.exit_code, 0) << streamed.err;
  EXPECT_THAT(streamed.out, HasSubstr("streamed in bands of"));
  EXPECT_THAT(whole.out, Not(HasSubstr("streamed")));
  const auto line = [](const std::string& text, const std::string& head) {
    const auto p = text.find(head);
    return p == std::string::npos ? std::string() : text.substr(p, text.find('\n', p) - p);
  };
  for (const std::string head : {"elevation:", "at -150,0:", "at 10,50:", "size:", "latitude:"}) {
    EXPECT_FALSE(line(whole.out, head).empty()) << head;
    EXPECT_EQ(line(whole.out, head), line(streamed.out, head));
  }
  EXPECT_THAT(line(whole.out, "elevation:"), HasSubstr("min -10376.0 m, max 7833.0 m"));
  const auto bad = run_aquatoria("info " + etopo5 + " --max-memory-gb -1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("--max-memory-gb"));
}

}  // namespace

namespace {

// The memory model (src/app/global_run.cpp) against the measured peak of a medium run: ETOPO5
// on a 1.875' lattice (Δ0 = 1°, L = 5), unrotated so the geographic files hold a pole cap (the
// write stage's copy of the mesh), binary MSH + UGRID. With the mesh's own triangle count the
// model is within its stated 25 %; the bitmaps are freed before the mesh (no tif), so the
// estimate takes the larger of the bitmap and mesh parts.
TEST(StreamCli, EstimateForTheMeshIsWithinItsToleranceOfThePeak) {
#if defined(__SANITIZE_ADDRESS__)
  // ASan's shadow memory and redzones add to every allocation: the peak of a sanitized binary is
  // not the one the model states (1.47 x it here). The Release suite checks it.
  GTEST_SKIP() << "the peak RSS of an AddressSanitizer build is not the product's";
#endif
  const fs::path dir = fresh_dir("stream", "estimate_medium");
  const auto r = run_aquatoria("mesh -q -o " + dir.string() +
                               " --set quadtree.step_deg=1.0 --set quadtree.levels=5 --set output.name=medium"
                               " --set 'output.formats=[\"msh\", \"ugrid\"]' --set output.msh_binary=true");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rep = aq::test::read_report(dir, "medium");
  const auto& m = rep.at("memory");
  EXPECT_FALSE(m.at("masks_kept").get<bool>());
  const double peak = m.at("peak_rss_bytes").get<double>(), model = m.at("estimate_bytes_for_mesh").get<double>();
  // A run the tolerance is stated for: a mesh part (215 bytes per triangle) above 0.4 GB.
  EXPECT_GT(215.0 * rep.at("mesh_counts").at("triangles").get<double>(), 0.4e9);
  EXPECT_LT(peak, 1.25 * model) << "peak " << peak << " model " << model;
  EXPECT_GT(peak, 0.75 * model) << "peak " << peak << " model " << model;
}

}  // namespace

}  // namespace cli_stream_cli_test

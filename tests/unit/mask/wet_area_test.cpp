// SPDX-License-Identifier: GPL-3.0-or-later
// The mask stage entry point on an in-memory raster: stage lines, report section, pinches,
// option validation.
#include "mask/wet_area.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace aq::mask::unit_mask_wet_area_test {
namespace {

// 1° global raster: ocean (-3000 m) with a land continent, an inland lake and 150 pairs of
// single +10 m points two degrees apart on a diagonal. On a 1° lattice each point makes the 2×2
// pixels around it non-wet, and each pair touches at one corner: a pinch of the filled set.
raster::Bathymetry test_raster() {
  const std::int64_t nc = 360, nr = 181;
  std::vector<float> v(static_cast<std::size_t>(nc * nr), -3000.0f);
  const auto at = [nc](std::int64_t lon, std::int64_t lat) {
    return static_cast<std::size_t>((lat + 90) * nc + (lon + 180));
  };
  for (std::int64_t lat = 20; lat <= 60; ++lat)
    for (std::int64_t lon = 0; lon <= 60; ++lon) v[at(lon, lat)] = 500.0f;  // continent
  for (std::int64_t lat = 35; lat <= 45; ++lat)
    for (std::int64_t lon = 25; lon <= 35; ++lon) v[at(lon, lat)] = -20.0f;  // lake inside it
  int pairs = 0;
  for (std::int64_t lat = -60; lat <= 0 && pairs < 150; lat += 6)
    for (std::int64_t lon = -170; lon <= -20 && pairs < 150; lon += 6, ++pairs) {
      v[at(lon, lat)] = 10.0f;
      v[at(lon + 2, lat + 2)] = 10.0f;
    }
  return raster::Bathymetry::from_grid(std::move(v), nc, nr, -180.0, -90.0, 1.0, 1.0);
}

struct Captured {
  std::vector<std::string> lines;
  Logger logger() {
    return Logger([this](LogLevel, std::string_view m) { lines.emplace_back(m); });
  }
  [[nodiscard]] bool has(const std::string& prefix) const {
    for (const auto& l : lines)
      if (l.rfind(prefix, 0) == 0) return true;
    return false;
  }
};

TEST(WetArea, RunsAllStagesAndWritesTheReportSection) {
  const auto bathy = test_raster();
  const Lattice lat = Lattice::make(4.0, 2, -180.0);  // 1° pixels, 360 × 180
  config::MaskOptions o;
  o.cursor = 2;
  Captured cap;
  const Logger log = cap.logger();
  Report report;
  const WetArea a = compute_wet_area(bathy, lat, PoleRotation(), o, log, &report);
  EXPECT_TRUE(cap.has("classify: done"));
  EXPECT_TRUE(cap.has("fill: done"));
  EXPECT_TRUE(cap.has("pinches: done"));
  EXPECT_TRUE(cap.has("passages: done"));
  // The lake (10×10 vertices of -20 m => 10×10 wet pixels) is wet but left out of the fill.
  EXPECT_EQ(a.fill.wet_components, 2);
  EXPECT_EQ(a.fill.wet_components_filled, 1);
  EXPECT_EQ(a.fill.wet_left_out, 100);
  EXPECT_EQ(a.fill.filled_pixels + a.fill.wet_left_out, a.fill.wet_pixels);
  EXPECT_EQ(a.classes.wet + a.classes.coastal + a.classes.dry, lat.pixel_count());
  EXPECT_EQ(a.filled.count(), a.filled_pixels);
  EXPECT_EQ(a.pinches.total, 150);
  EXPECT_EQ(a.passages.size(), critical_passages().size());
  const Json& m = report.root()["mask"];
  EXPECT_EQ(m["cursor"], 2);
  EXPECT_EQ(m["fill"]["wet_left_out"], 100);
  EXPECT_EQ(m["pinches"]["total"], 150);
  EXPECT_EQ(m["pinches"]["listed"].size(), 100U);
  EXPECT_EQ(m["pinches"]["listed"][0]["pattern"], "1001 (NW-SE)");
  // First pinch: the pair at (-170, -60) / (-168, -58) touches at vertex λ = -169, φ = -59.
  EXPECT_EQ(m["pinches"]["listed"][0]["geographic"][0], -169.0);
  EXPECT_EQ(m["pinches"]["listed"][0]["geographic"][1], -59.0);
  EXPECT_EQ(m["passages"].size(), critical_passages().size());
  EXPECT_EQ(m["seeds"][0]["moved"], false);
  ASSERT_GE(report.root()["stages"].size(), 4U);
  EXPECT_EQ(report.root()["stages"][0]["stage"], "classify");
}

TEST(WetArea, RemovePinchesLeavesNone) {
  const auto bathy = test_raster();
  const Lattice lat = Lattice::make(4.0, 2, -180.0);
  config::MaskOptions o;
  o.remove_pinches = true;
  o.passages = false;
  Report report;
  const WetArea a = compute_wet_area(bathy, lat, PoleRotation(), o, Logger::null(), &report);
  EXPECT_EQ(a.pinches.total, 0);
  EXPECT_EQ(a.pinches.removal.pinches_found, 150);
  EXPECT_GE(a.pinches.removal.pixels_removed, 150);
  EXPECT_EQ(a.filled_pixels, a.fill.filled_pixels - a.pinches.removal.pixels_removed);
  EXPECT_EQ(count_pinches(a.filled), 0);
  EXPECT_TRUE(a.passages.empty());
  EXPECT_EQ(report.root()["mask"]["pinches"]["removal"]["pinches_found"], 150);
}

// The option ranges are checked at load (tests/unit/config/config_test.cpp); what needs the data
// stays here: a seed with no all-wet window within the radius.
TEST(WetArea, ASeedOnLandIsAConfigErrorNamingTheKey) {
  const auto bathy = test_raster();
  const Lattice lat = Lattice::make(4.0, 2, -180.0);
  const auto expect_error = [&](const config::MaskOptions& o, const std::string& key) {
    try {
      (void)compute_wet_area(bathy, lat, PoleRotation(), o, Logger::null(), nullptr);
      ADD_FAILURE() << "no error for " << key;
    } catch (const ConfigError& e) {
      EXPECT_THAT(e.what(), testing::HasSubstr(key));
    }
  };
  config::MaskOptions o;
  o.seeds = {{10.0, 40.0}};  // on the continent, about 8° from its coast
  o.seed_radius_deg = 2.0;
  expect_error(o, "mask.seeds[0] = (10, 40)");
}

}  // namespace
}  // namespace aq::mask::unit_mask_wet_area_test

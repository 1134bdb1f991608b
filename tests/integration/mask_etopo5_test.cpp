// SPDX-License-Identifier: GPL-3.0-or-later
// The mask stage on the real NOAA ETOPO5 (5', 4320×2161) at the seed's reference parameters
// (Δ0 = 4°, L = 3: 720×360 pixels of 0.5°; K = 2; h = 0), plus a rotated pole and finer lattices.
// The numbers asserted here are what ETOPO5 gives (measured when the test was written), with the
// stated tolerances.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "mask/wet_area.hpp"

namespace aq::mask::integration_mask_etopo5_test {
namespace {

const std::string kEtopo5 = std::string(AQ_ETOPO_DIR) + "/etopo5.cdf";

const raster::Bathymetry& etopo5() {
  static const raster::Bathymetry b = [] {
    raster::OpenOptions o;
    o.path = kEtopo5;
    return raster::Bathymetry::open(o);
  }();
  return b;
}

struct MaskRun {
  Lattice lattice;
  PoleRotation rot;
  WetArea area;
};

MaskRun run(double step0, int levels, int k, const PoleRotation& rot = PoleRotation()) {
  MaskRun r{Lattice::make(step0, levels, -180.0), rot, {}};
  config::MaskOptions o;
  o.cursor = k;
  o.min_depth_m = 0.0;
  r.area = compute_wet_area(etopo5(), r.lattice, rot, o, Logger::null(), nullptr);
  return r;
}

// (wet, filled) of the pixel holding a geographic point.
std::pair<bool, bool> at(const MaskRun& r, double lon, double lat) {
  double x = 0.0, y = 0.0;
  deg_to_lattice_xy(r.lattice, geographic_to_lattice(r.rot, {lon, lat}), x, y);
  const auto i = static_cast<std::int64_t>(x), j = static_cast<std::int64_t>(y);
  return {r.area.wet.get(i, j), r.area.filled.get(i, j)};
}

PassageStatus status(const MaskRun& r, const std::string& name) {
  for (const PassageResult& p : r.area.passages)
    if (p.name == name) return p.status;
  ADD_FAILURE() << "no passage " << name;
  return PassageStatus::kClosed;
}

std::int64_t filled_in_row(const MaskRun& r, std::int64_t j) {
  std::int64_t n = 0;
  for (std::int64_t i = 0; i < r.lattice.nx; ++i) n += r.area.filled.get(i, j) ? 1 : 0;
  return n;
}

class MaskEtopo5 : public testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(kEtopo5)) GTEST_SKIP() << kEtopo5 << " not installed (ferret-datasets)";
  }
};

TEST_F(MaskEtopo5, SeedReferenceParameters) {
  const MaskRun r = run(4.0, 3, 2);
  const WetArea& a = r.area;
  ASSERT_EQ(r.lattice.nx, 720);
  ASSERT_EQ(r.lattice.ny, 360);
  EXPECT_EQ(a.classes.wet + a.classes.coastal + a.classes.dry, 720 * 360);
  EXPECT_FALSE(a.seeds[0].moved);  // (-30, -50) is open South Atlantic
  // Measured: 165182 filled pixels = 0.637 of the lattice; 168565 wet; 93 wet components.
  const double frac = static_cast<double>(a.filled_pixels) / (720.0 * 360.0);
  EXPECT_GT(frac, 0.60);
  EXPECT_LT(frac, 0.75);
  EXPECT_NEAR(static_cast<double>(a.fill.wet_pixels), 168565.0, 0.01 * 168565.0);
  EXPECT_GT(a.fill.wet_components, 1);
  EXPECT_NEAR(static_cast<double>(a.fill.wet_components), 93.0, 30.0);
  EXPECT_EQ(a.fill.wet_components_filled, 1);
  EXPECT_NEAR(static_cast<double>(a.fill.wet_left_out), 3383.0, 0.2 * 3383.0);
  // The Caspian (surface about -28 m) is wet at h = 0 but a separate basin: left out.
  for (const auto& [lon, lat] : {std::pair{50.5, 42.5}, {51.0, 39.0}, {50.0, 45.5}}) {
    EXPECT_TRUE(at(r, lon, lat).first) << lon << "," << lat;
    EXPECT_FALSE(at(r, lon, lat).second) << lon << "," << lat;
  }
  // What ETOPO5 gives at 0.5° pixels: the Strait of Gibraltar (about 14 km, a quarter of a pixel)
  // does not carry even a 1-pixel wet channel, so the Mediterranean is a separate wet component
  // and is left out, together with the Black Sea, Baltic, Red Sea, Persian Gulf and Hudson Bay
  // (their straits are narrower than 2 pixels). At 3.75' it is connected (test below).
  EXPECT_EQ(status(r, "Gibraltar"), PassageStatus::kClosed);
  for (const auto& [lon, lat] :
       {std::pair{18.0, 35.0}, {5.0, 39.0}, {34.0, 43.5}, {19.0, 57.0}, {38.0, 21.0}, {-86.0, 60.0}, {51.0, 27.0}}) {
    EXPECT_TRUE(at(r, lon, lat).first) << lon << "," << lat;
    EXPECT_FALSE(at(r, lon, lat).second) << lon << "," << lat;
  }
  // Wide passages are open; a strait below the pixel size is not resolvable.
  for (const char* n : {"Drake", "Fram", "Davis", "Denmark", "Luzon", "Yucatan", "Florida", "Bering"})
    EXPECT_EQ(status(r, n), PassageStatus::kOpen) << n;
  for (const char* n : {"Dover", "Sicily", "Hudson", "Bab-el-Mandeb", "Danish straits"})
    EXPECT_EQ(status(r, n), PassageStatus::kClosed) << n;
  EXPECT_EQ(status(r, "Bosphorus"), PassageStatus::kNotResolvable);
  // Without rotation the Arctic is wet at 90°N: the top pixel row is filled, the bottom is not.
  EXPECT_EQ(filled_in_row(r, 359), 720);
  EXPECT_EQ(filled_in_row(r, 0), 0);
  EXPECT_LT(a.pinches.total, 20);  // measured: 2
}

TEST_F(MaskEtopo5, LargerCursorFillsASubset) {
  const MaskRun k1 = run(4.0, 3, 1);
  const MaskRun k2 = run(4.0, 3, 2);
  const auto& w1 = k1.area.filled.words();
  const auto& w2 = k2.area.filled.words();
  for (std::size_t q = 0; q < w1.size(); ++q) ASSERT_EQ(w2[q] & ~w1[q], 0U);
  // Measured: 166096 (K=1) vs 165182 (K=2); K=1 also opens Hormuz, Bass, La Perouse and Taiwan.
  EXPECT_GT(k1.area.filled_pixels, k2.area.filled_pixels);
  EXPECT_LT(k1.area.filled_pixels - k2.area.filled_pixels, 3000);
  EXPECT_EQ(status(k1, "Bass"), PassageStatus::kOpen);
  EXPECT_EQ(status(k2, "Bass"), PassageStatus::kClosed);
}

TEST_F(MaskEtopo5, RotatedPolePutsBothPolesOnLand) {
  const MaskRun r = run(4.0, 3, 2, PoleRotation(-44.858333, 78.141667));
  // Measured: 158597 filled pixels (0.612 of the rotated lattice).
  const double frac = static_cast<double>(r.area.filled_pixels) / (720.0 * 360.0);
  EXPECT_GT(frac, 0.58);
  EXPECT_LT(frac, 0.66);
  EXPECT_EQ(filled_in_row(r, 0), 0);
  EXPECT_EQ(filled_in_row(r, 359), 0);
  EXPECT_FALSE(r.area.seeds[0].moved);
  EXPECT_EQ(status(r, "Drake"), PassageStatus::kOpen);
  EXPECT_EQ(status(r, "Fram"), PassageStatus::kOpen);
  EXPECT_FALSE(at(r, 50.5, 42.5).second);  // Caspian still left out
}

TEST_F(MaskEtopo5, FinerLatticeConnectsTheMediterranean) {
  // Δ0 = 1°, L = 4: 5760×2880 pixels of 3.75'.
  const MaskRun r = run(1.0, 4, 2);
  EXPECT_EQ(status(r, "Gibraltar"), PassageStatus::kOpen);
  EXPECT_TRUE(at(r, 18.0, 35.0).second);   // Ionian Sea filled
  EXPECT_TRUE(at(r, -86.0, 60.0).second);  // Hudson Bay filled
  // ETOPO5 has no Bosphorus: +2..+6 m across 28.7-29.5°E at 41.08-41.17°N. The Black Sea stays out.
  EXPECT_EQ(status(r, "Bosphorus"), PassageStatus::kClosed);
  EXPECT_FALSE(at(r, 34.0, 43.5).second);
  EXPECT_FALSE(at(r, 50.5, 42.5).second);  // Caspian
  const double frac = static_cast<double>(r.area.filled_pixels) / static_cast<double>(r.lattice.pixel_count());
  EXPECT_NEAR(frac, 0.663, 0.01);  // measured 0.6630
}

TEST_F(MaskEtopo5, PassageBoxesAreRightOnTheWetMask) {
  // The boxes of the built-in table, judged on the wet pixels themselves (not the fill) at
  // 1.875' (11520×5760): every strait ETOPO5 resolves is open, so each box spans its strait and
  // its sides are water. ETOPO5 closes two: the Bosphorus (+2..+6 m across it) and the Little
  // Belt (its 5' cells meet only at a corner, 9.71°E 55.54°N, on land's side of the bilinear saddle).
  const Lattice l = Lattice::make(0.5, 4, -180.0);
  const PixelClasses pc = classify_pixels(etopo5(), l, PoleRotation(), ClassifyOptions{});
  const std::vector<PassageResult> rs = judge_passages(critical_passages(), pc.wet, l, PoleRotation());
  ASSERT_EQ(rs.size(), critical_passages().size());
  for (const PassageResult& p : rs) {
    if (p.name == "Bosphorus" || p.name == "Little Belt")
      EXPECT_EQ(p.status, PassageStatus::kClosed) << p.name;
    else
      EXPECT_EQ(p.status, PassageStatus::kOpen) << p.name << ": " << p.note;
    EXPECT_GT(p.filled_side_a, 0) << p.name;  // both sides are wet
    EXPECT_GT(p.filled_side_b, 0) << p.name;
  }
}

}  // namespace
}  // namespace aq::mask::integration_mask_etopo5_test

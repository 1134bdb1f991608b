// SPDX-License-Identifier: GPL-3.0-or-later
// Corridor edits of the sampled elevation (raster/elevation_edits.hpp): the corridor is the set
// of points within the half-width of the polyline on the sphere (checked against the brute-force
// distance), channels lower and blockages raise (land wins), the raster's own water stays under a
// channel with a keep threshold, no-data under a channel is water; a Bathymetry with edits gives
// the same edited values through every sampling path; the value bounds include them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "core/error.hpp"
#include "core/types.hpp"
#include "raster/bathymetry.hpp"
#include "raster/elevation_edits.hpp"
#include "raster/value_bounds.hpp"

namespace aq::raster::unit_raster_elevation_edits_test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Great-circle distance (degrees), haversine.
double gc(double lon1, double lat1, double lon2, double lat2) {
  const double p1 = lat1 * kDegToRad, p2 = lat2 * kDegToRad, dp = p2 - p1, dl = (lon2 - lon1) * kDegToRad;
  const double h =
      std::sin(dp / 2) * std::sin(dp / 2) + std::cos(p1) * std::cos(p2) * std::sin(dl / 2) * std::sin(dl / 2);
  return 2.0 * std::asin(std::sqrt(std::min(1.0, h))) * kRadToDeg;
}

// Distance (degrees) from p to the great-circle arc a-b, by dense sampling of the arc.
double arc_distance(double lon, double lat, double lon_a, double lat_a, double lon_b, double lat_b) {
  double best = 1e9;
  const auto u = [](double lo, double la) {
    return std::array<double, 3>{std::cos(la * kDegToRad) * std::cos(lo * kDegToRad),
                                 std::cos(la * kDegToRad) * std::sin(lo * kDegToRad), std::sin(la * kDegToRad)};
  };
  const auto a = u(lon_a, lat_a), b = u(lon_b, lat_b);
  for (int k = 0; k <= 4000; ++k) {
    const double t = k / 4000.0;
    std::array<double, 3> q{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
    const double l = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    const double qlon = std::atan2(q[1], q[0]) * kRadToDeg, qlat = std::asin(q[2] / l) * kRadToDeg;
    best = std::min(best, gc(lon, lat, qlon, qlat));
  }
  return best;
}

Corridor channel(std::vector<double> lon, std::vector<double> lat, double r, double elevation) {
  Corridor c;
  c.name = "c";
  c.kind = EditKind::kChannel;
  c.elevation_m = elevation;
  c.lon_deg = std::move(lon);
  c.lat_deg = std::move(lat);
  c.half_width_deg.assign(c.lon_deg.size() == 1 ? 1 : c.lon_deg.size() - 1, r);
  return c;
}

TEST(ElevationEdits, CorridorIsTheHalfWidthAroundTheArcOnTheSphere) {
  // An oblique arc of 3.6° at high latitude (split into pieces by the index), half-width 0.3°.
  const ElevationEdits e({channel({10.0, 13.0}, {60.0, 62.0}, 0.3, -50.0)});
  int inside = 0, outside = 0;
  for (double lat = 59.0; lat <= 63.0; lat += 0.061)
    for (double lon = 8.0; lon <= 15.0; lon += 0.097) {
      const double d = arc_distance(lon, lat, 10.0, 60.0, 13.0, 62.0);
      if (std::abs(d - 0.3) < 2e-3) continue;  // too near the edge for the sampled reference
      const double z = e.apply(lon, lat, 100.0);
      if (d < 0.3) {
        EXPECT_EQ(z, -50.0) << lon << " " << lat << " d=" << d;
        ++inside;
      } else {
        EXPECT_EQ(z, 100.0) << lon << " " << lat << " d=" << d;
        ++outside;
      }
    }
  EXPECT_GT(inside, 150);
  EXPECT_GT(outside, 1500);
}

TEST(ElevationEdits, DiscAcrossTheSeamAndNearThePole) {
  const ElevationEdits seam({channel({179.9}, {10.0}, 0.5, -20.0)});
  EXPECT_EQ(seam.apply(-179.7, 10.0, 5.0), -20.0);  // 0.4° east across the seam
  EXPECT_EQ(seam.apply(180.3, 10.0, 5.0), -20.0);   // the same point, another longitude range
  EXPECT_EQ(seam.apply(-179.3, 10.0, 5.0), 5.0);
  EXPECT_TRUE(seam.touches_lat(10.0));
  EXPECT_FALSE(seam.touches_lat(40.0));
  // An arc over the pole: every longitude at 89.9°N is near it.
  const ElevationEdits pole({channel({0.0, 180.0}, {89.0, 89.0}, 0.2, -30.0)});
  for (double lon = -180.0; lon < 180.0; lon += 7.0) EXPECT_EQ(pole.apply(lon, 89.95, 1.0), -30.0) << lon;
  EXPECT_EQ(pole.apply(90.0, 89.0, 1.0), 1.0);  // 1° from the arc (the 0°/180° meridian)
}

TEST(ElevationEdits, ChannelsLowerBlockagesRaiseLandWinsNoDataIsWater) {
  Corridor block = channel({0.0, 2.0}, {1.0, 1.0}, 0.2, 10.0);
  block.kind = EditKind::kBlockage;
  const ElevationEdits e({channel({1.0, 1.0}, {0.0, 2.0}, 0.2, -40.0), block});
  EXPECT_EQ(e.apply(1.0, 0.5, 3.0), -40.0);          // channel only
  EXPECT_EQ(e.apply(1.0, 0.5, -100.0), -100.0);      // deeper water stays
  EXPECT_EQ(e.apply(0.5, 1.0, -100.0), 10.0);        // blockage only
  EXPECT_EQ(e.apply(1.0, 1.0, -100.0), 10.0);        // both: land wins
  EXPECT_EQ(e.apply(1.0, 0.5, kNaN), -40.0);         // no-data under a channel is water
  EXPECT_TRUE(std::isnan(e.apply(0.5, 1.0, kNaN)));  // and stays no-data under a blockage
  EXPECT_EQ(e.apply(5.0, 5.0, 7.0), 7.0);            // far away
}

TEST(ElevationEdits, KeepThresholdLeavesTheRastersOwnWater) {
  Corridor c = channel({0.0, 1.0}, {0.0, 0.0}, 0.2, -30.0);
  c.keep_at_or_below_m = -10.0;  // wet at h = 10 m already: kept
  const ElevationEdits e({c});
  EXPECT_EQ(e.apply(0.5, 0.0, -12.0), -12.0);
  EXPECT_EQ(e.apply(0.5, 0.0, -10.0), -10.0);
  EXPECT_EQ(e.apply(0.5, 0.0, -9.0), -30.0);
  EXPECT_EQ(e.apply(0.5, 0.0, 200.0), -30.0);
}

TEST(ElevationEdits, RowEqualsPointsReachAndFingerprint) {
  const ElevationEdits e({channel({20.0, 22.0, 22.5}, {-5.0, -4.0, -2.0}, 0.25, -15.0)});
  std::vector<double> lons;
  for (double lon = 19.0; lon < 24.0; lon += 0.01) lons.push_back(lon);
  for (double lat = -6.0; lat < -1.0; lat += 0.05) {
    std::vector<float> row(lons.size(), 3.0F);
    e.apply_row(lons.data(), lat, row.data(), static_cast<std::int64_t>(lons.size()));
    for (std::size_t k = 0; k < lons.size(); ++k) ASSERT_EQ(row[k], static_cast<float>(e.apply(lons[k], lat, 3.0)));
  }
  const auto in = e.reach_in_box(20.5, 21.0, -5.0, -4.0);
  EXPECT_TRUE(in.channel);
  EXPECT_EQ(in.channel_min_m, -15.0);
  EXPECT_FALSE(in.blockage);
  EXPECT_FALSE(e.reach_in_box(100.0, 101.0, 40.0, 41.0).channel);
  const ElevationEdits same({channel({20.0, 22.0, 22.5}, {-5.0, -4.0, -2.0}, 0.25, -15.0)});
  const ElevationEdits deeper({channel({20.0, 22.0, 22.5}, {-5.0, -4.0, -2.0}, 0.25, -16.0)});
  EXPECT_EQ(e.fingerprint(), same.fingerprint());
  EXPECT_NE(e.fingerprint(), deeper.fingerprint());
}

TEST(ElevationEdits, BadCorridorsAreInputErrorsNamingThem) {
  EXPECT_THROW(ElevationEdits({channel({0.0, 1.0}, {0.0, 95.0}, 0.1, -1.0)}), InputError);
  EXPECT_THROW(ElevationEdits({channel({0.0, 1.0}, {0.0, 0.0}, 0.0, -1.0)}), InputError);
  EXPECT_THROW(ElevationEdits({channel({0.0, 180.0}, {0.0, 0.0}, 0.1, -1.0)}), InputError);  // antipodal
  Corridor c = channel({0.0, 1.0, 2.0}, {0.0, 0.0, 0.0}, 0.1, -1.0);
  c.half_width_deg = {0.1};  // 2 arcs
  try {
    ElevationEdits bad({c});
    FAIL();
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("\"c\""), std::string::npos) << err.what();
  }
}

// A 1° raster of +100 m land; a channel across it: every sampling path of the Bathymetry gives
// the same edited values, and the value bounds hold them.
TEST(ElevationEdits, EverySamplingPathOfTheBathymetryAgrees) {
  const std::int64_t nc = 360, nr = 181;
  std::vector<float> v(static_cast<std::size_t>(nc * nr), 100.0F);
  Bathymetry b = Bathymetry::from_grid(v, nc, nr, -180.0, -90.0, 1.0, 1.0);
  auto e = std::make_shared<const ElevationEdits>(std::vector<Corridor>{channel({10.0, 20.0}, {5.0, 8.0}, 1.2, -60.0)});
  const ValueBounds raw_bounds(b, 4);
  b.set_edits(e);
  ASSERT_NE(b.edits(), nullptr);
  std::vector<double> lons, lats;
  for (double lon = 5.0; lon < 25.0; lon += 0.13) lons.push_back(lon);
  for (double lat = 0.0; lat < 13.0; lat += 0.11) lats.push_back(lat);
  const Bathymetry::Columns cols = b.prepare_columns(lons.data(), static_cast<std::int64_t>(lons.size()));
  std::vector<float> row(lons.size());
  std::int64_t wet = 0;
  for (const double lat : lats) {
    b.sample_row(cols, lat, row.data());
    std::vector<double> pl(lons.size(), lat), pz(lons.size());
    b.sample_points(lons.data(), pl.data(), static_cast<std::int64_t>(lons.size()), pz.data());
    for (std::size_t k = 0; k < lons.size(); ++k) {
      const double want = e->apply(lons[k], lat, 100.0);
      ASSERT_EQ(b.sample(lons[k], lat), want);
      ASSERT_EQ(pz[k], want);
      ASSERT_EQ(row[k], static_cast<float>(want));
      wet += want < 0.0 ? 1 : 0;
    }
  }
  EXPECT_GT(wet, 100);
  b.sample_rows(cols, lats.data(), static_cast<std::int64_t>(lats.size()), [&](std::int64_t k, const float* values) {
    for (std::size_t q = 0; q < lons.size(); ++q)
      ASSERT_EQ(values[q], static_cast<float>(e->apply(lons[q], lats[static_cast<std::size_t>(k)], 100.0)));
  });
  // value / values at the raster points' positions.
  EXPECT_EQ(b.value(15 + 180, 6 + 90), static_cast<float>(e->apply(15.0, 6.0, 100.0)));
  std::vector<float> block(20 * 10);
  b.values(5 + 180, 20, 90, 10, block.data());
  for (int r = 0; r < 10; ++r)
    for (int c = 0; c < 20; ++c)
      ASSERT_EQ(block[static_cast<std::size_t>(r * 20 + c)], static_cast<float>(e->apply(5.0 + c, r, 100.0)));
  // The raw bounds say "all land" over the corridor; the edited bounds include its bottom.
  EXPECT_EQ(side_of_threshold(raw_bounds.in_box(14.0, 16.0, 5.5, 7.5), 0.0), -1);
  const ValueBounds bounds(b, 4);
  const ValueRange r = bounds.in_box(14.0, 16.0, 5.5, 7.5);
  EXPECT_LE(r.lo, -60.0);
  EXPECT_EQ(side_of_threshold(r, 0.0), 0);
  b.set_edits(nullptr);
  EXPECT_EQ(b.sample(15.0, 6.5), 100.0);
}

}  // namespace
}  // namespace aq::raster::unit_raster_elevation_edits_test

// SPDX-License-Identifier: GPL-3.0-or-later
// The K-cursor fill on the Mercator lattice measures channel width physically (issue 12): an
// east–west and a north–south channel of the same width in km at 60°N are both open (or both
// closed) on the Mercator lattice; on the lon-lat lattice of the same λ step the east–west channel
// (whose width runs along φ, where a pixel is twice as long as along λ at 60°) closes while the
// north–south one stays open.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mask/lattice_coords.hpp"
#include "mask/wet_area.hpp"

namespace aq::mask::unit_mask_mercator_fill_test {
namespace {

constexpr double kKmPerDeg = 6371.0088 * kPi / 180.0;

// 0.02° raster over [0, 20] × [48, 72] (NaN, dry, elsewhere), elevation -100 m in the water:
//  * basins W [1, 5] × [57, 63] and E [9, 13] × [57, 63] joined by an east–west channel along
//    φ = 60° of width `width_km` (its half-width in φ is constant);
//  * basins S [15, 19] × [50, 57] and N [15, 19] × [63, 70] joined by a north–south channel along
//    λ = 17° of the same width in km at every latitude (half-width in λ grows as 1/cos φ).
raster::Bathymetry channels(double width_km) {
  const double d = 0.02;
  const std::int64_t nc = 1001, nr = 1201;
  std::vector<float> v(static_cast<std::size_t>(nc * nr), 100.0f);
  const double half = 0.5 * width_km / kKmPerDeg;  // degrees of a great circle
  for (std::int64_t r = 0; r < nr; ++r) {
    const double lat = 48.0 + static_cast<double>(r) * d;
    for (std::int64_t c = 0; c < nc; ++c) {
      const double lon = static_cast<double>(c) * d;
      const auto in = [&](double x0, double x1, double y0, double y1) {
        return lon >= x0 && lon <= x1 && lat >= y0 && lat <= y1;
      };
      bool wet = in(1, 5, 57, 63) || in(9, 13, 57, 63) || in(15, 19, 50, 57) || in(15, 19, 63, 70);
      wet = wet || (lon >= 5 && lon <= 9 && std::fabs(lat - 60.0) <= half);
      wet = wet || (lat >= 57 && lat <= 63 && std::fabs(lon - 17.0) <= half / std::cos(lat * kDegToRad));
      if (wet) v[static_cast<std::size_t>(r * nc + c)] = -100.0f;
    }
  }
  return raster::Bathymetry::from_grid(std::move(v), nc, nr, 0.0, 48.0, d, d);
}

struct Reached {
  bool east = false;   ///< the fill from basin W reached basin E (through the east–west channel)
  bool north = false;  ///< the fill from basin S reached basin N (through the north–south channel)
};

Reached fill(const raster::Bathymetry& bathy, const Lattice& lat) {
  config::MaskOptions o;
  o.cursor = 2;
  o.seeds = {{3.0, 60.0}, {17.0, 53.5}};
  o.seed_radius_deg = 1.0;
  o.passages = false;
  const WetArea a = compute_wet_area(bathy, lat, PoleRotation(), o, Logger::null(), nullptr);
  const auto at = [&](double lon, double la) {
    double x = 0.0, y = 0.0;
    deg_to_lattice_xy(lat, {lon, la}, x, y);
    return a.filled.get(static_cast<std::int64_t>(x), static_cast<std::int64_t>(y));
  };
  EXPECT_TRUE(at(3.0, 60.0));
  EXPECT_TRUE(at(17.0, 53.5));
  return {at(11.0, 60.0), at(17.0, 66.5)};
}

TEST(MercatorFill, ChannelsOfTheSameWidthInKmAreAlikeOnTheMercatorLatticeOnly) {
  const Lattice merc = Lattice::make_mercator(1.0, 2, -180.0, 86.5);  // 0.25° in λ: 13.9 km at 60°
  const Lattice lonlat = Lattice::make(1.0, 2, -180.0);               // 0.25°: 13.9 km E–W, 27.8 km N–S
  // 50 km: 3.6 Mercator pixels both ways; on the lon-lat lattice 3.6 columns but 1.8 rows.
  const auto wide = channels(50.0);
  const Reached m = fill(wide, merc);
  EXPECT_TRUE(m.east);
  EXPECT_TRUE(m.north);
  const Reached g = fill(wide, lonlat);
  EXPECT_FALSE(g.east) << "the lon-lat lattice's rows are twice as tall as its columns are wide at 60°";
  EXPECT_TRUE(g.north);
  // 20 km: 1.4 Mercator pixels both ways: a K = 2 cursor passes neither.
  const Reached n = fill(channels(20.0), merc);
  EXPECT_FALSE(n.east);
  EXPECT_FALSE(n.north);
}

}  // namespace
}  // namespace aq::mask::unit_mask_mercator_fill_test

// SPDX-License-Identifier: GPL-3.0-or-later
// The size field of a floodplain and of a regional domain (size/size_field.hpp with coast
// sources, mask/coast.hpp), on a synthetic strip: sea west of column 100, a floodplain of
// columns 100..139 whose elevation rises 0.5 m per degree east of the shoreline, land beyond.
// The coast term measures from the shoreline at the datum and sizes the sea only; the inland term
// (h0 + α·d from the nearest sea cell) and the elevation term (h0 + k·z) size the floodplain;
// open water beyond a domain edge is no coast; without sources the edge of the fill is the coast.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/log.hpp"
#include "raster/bathymetry.hpp"
#include "size/limit_gradient.hpp"
#include "size/size_field.hpp"
#include "size/terms.hpp"

namespace aq::size::unit_size_floodplain_terms_test {
namespace {

constexpr std::int64_t kShore = 100, kLand = 140;  // first floodplain column, first unfilled column

// Δ0 = 10°, L = 3: 288 x 144 pixels of 1.25°; the field grid is the pixels (level 3).
Lattice lattice() { return Lattice::make(10.0, 3, -180.0); }

// Elevation 0.5 m per degree east of the shoreline's western edge (λ = -180 + 100·1.25 = -55°).
double elevation(double lon) { return 0.5 * (lon + 55.0); }

raster::Bathymetry strip_raster() {
  const std::int64_t nc = 361, nr = 181;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  for (std::int64_t r = 0; r < nr; ++r)
    for (std::int64_t c = 0; c < nc; ++c)
      v[static_cast<std::size_t>(r * nc + c)] = static_cast<float>(elevation(-180.0 + static_cast<double>(c)));
  return raster::Bathymetry::from_grid(std::move(v), nc, nr, -180.0, -90.0, 1.0, 1.0);
}

struct Strip {
  Lattice lat = lattice();
  Bitmap filled, sea, open;
  Strip() : filled(lat.nx, lat.ny), sea(lat.nx, lat.ny), open(lat.nx, lat.ny) {
    for (std::int64_t j = 0; j < lat.ny; ++j)
      for (std::int64_t i = 0; i < kLand; ++i) {
        filled.set(i, j);
        if (i < kShore) sea.set(i, j);
      }
  }
};

config::GlobalConfig floodplain_config() {
  config::GlobalConfig c;
  c.mask.min_depth_m = -30.0;
  c.size.grid_level = 3;
  c.size.coast.h0_km = 30.0;
  c.size.coast.alpha = 0.1;
  c.size.inland.h0_km = 20.0;
  c.size.inland.alpha = 0.5;
  c.size.elevation.h0_km = 50.0;
  c.size.elevation.km_per_m = 4.0;
  return c;
}

// Row 72: the cells just north of the equator, where the nearest cell of a column is on the row.
constexpr std::int64_t kRow = 72;

double cells_km(const FieldGrid& g, std::int64_t a, std::int64_t b) {
  return g.distance_km(g.index(a, kRow), g.index(b, kRow));
}

TEST(FloodplainTerms, CoastFromTheShorelineInlandAndElevationOnTheFloodplain) {
  const Strip s;
  const raster::Bathymetry bathy = strip_raster();
  const config::GlobalConfig c = floodplain_config();
  Report report;
  const SizeField f = build_size_field(s.filled, s.lat, c, PoleRotation(), &bathy, Logger::null(), &report,
                                       mask::CoastSources{nullptr, &s.sea});
  const FieldGrid& g = f.grid();
  ASSERT_EQ(g.pixels_per_cell(), 1);
  for (const char* term : {"coast", "inland", "elevation"}) EXPECT_TRUE(report["size"]["terms"].contains(term)) << term;
  // Sea: 30 + 0.1·d to the shoreline (the first floodplain column).
  for (const std::int64_t i : {std::int64_t{60}, std::int64_t{90}, std::int64_t{99}})
    EXPECT_NEAR(f.at_pixel(i, kRow), 30.0 + 0.1 * cells_km(g, i, kShore), 0.02 * 30.0) << "sea column " << i;
  // Floodplain: min(20 + 0.5·d from the last sea column, 50 + 4·z at the centre); never the coast's 30.
  for (const std::int64_t i : {kShore, std::int64_t{101}, std::int64_t{110}, std::int64_t{120}, std::int64_t{139}}) {
    const double z = elevation(g.lon_deg(i));
    const double expect = std::min(20.0 + 0.5 * cells_km(g, i, kShore - 1), 50.0 + 4.0 * std::max(0.0, z));
    EXPECT_NEAR(f.at_pixel(i, kRow), expect, 0.01 * expect) << "floodplain column " << i;
    EXPECT_GT(f.at_pixel(i, kRow), 40.0);
  }
  // Near the shoreline the elevation term is the smaller, far inland too (z grows slower than d).
  EXPECT_NEAR(f.at_pixel(kShore, kRow), 50.0 + 4.0 * elevation(g.lon_deg(kShore)), 0.01);
}

TEST(FloodplainTerms, WithoutSourcesTheEdgeOfTheFillIsTheCoastAndTheFloodplainTermsAreOff) {
  const Strip s;
  const raster::Bathymetry bathy = strip_raster();
  config::GlobalConfig c = floodplain_config();
  Report report;
  const SizeField f = build_size_field(s.filled, s.lat, c, PoleRotation(), &bathy, Logger::null(), &report);
  const FieldGrid& g = f.grid();
  EXPECT_FALSE(report["size"]["terms"].contains("inland"));
  EXPECT_FALSE(report["size"]["terms"].contains("elevation"));
  for (const std::int64_t i : {std::int64_t{90}, std::int64_t{120}, std::int64_t{139}})
    EXPECT_NEAR(f.at_pixel(i, kRow), 30.0 + 0.1 * cells_km(g, i, kLand), 0.02 * 30.0) << "column " << i;
}

TEST(FloodplainTerms, OpenWaterBeyondTheDomainIsNoCoast) {
  // The strip cut by a domain edge at column 20: the water west of it is open, not land; so is
  // everything east of a land strip of columns 140..159 (round the seam to column 0).
  Strip s;
  for (std::int64_t j = 0; j < s.lat.ny; ++j)
    for (std::int64_t i = 0; i < s.lat.nx; ++i) {
      if (i >= 20 && i < kLand + 20) continue;
      s.filled.clear(i, j);
      s.sea.clear(i, j);
      if (i < 20 || i >= kLand + 20) s.open.set(i, j);
    }
  const raster::Bathymetry bathy = strip_raster();
  config::GlobalConfig c;
  c.size.grid_level = 3;
  c.size.coast.h0_km = 30.0;
  c.size.coast.alpha = 0.1;
  const SizeField open = build_size_field(s.filled, s.lat, c, PoleRotation(), &bathy, Logger::null(), nullptr,
                                          mask::CoastSources{&s.open, nullptr});
  const SizeField plain = build_size_field(s.filled, s.lat, c, PoleRotation(), &bathy, Logger::null(), nullptr);
  const FieldGrid& g = open.grid();
  // Away from the open edge the coast is the real one (column 140) either way ...
  EXPECT_NEAR(open.at_pixel(100, kRow), 30.0 + 0.1 * cells_km(g, 100, kLand), 0.02 * 30.0);
  EXPECT_NEAR(plain.at_pixel(100, kRow), 30.0 + 0.1 * cells_km(g, 100, kLand), 0.02 * 30.0);
  // ... next to the open edge counting it as coast gave h0 + α·(one cell); now the real coast is
  // far (its nearest cells are beyond 80° of arc, over the pole rows).
  EXPECT_NEAR(plain.at_pixel(20, kRow), 30.0 + 0.1 * cells_km(g, 20, 19), 0.02 * 30.0);
  EXPECT_GT(open.at_pixel(20, kRow), 30.0 + 0.1 * 8000.0);
  // The shore cells themselves.
  const std::vector<std::uint8_t> shore = shore_cells(g, s.filled, mask::CoastSources{&s.open, nullptr});
  EXPECT_EQ(shore[static_cast<std::size_t>(g.index(19, kRow))], 0);
  EXPECT_EQ(shore[static_cast<std::size_t>(g.index(20, kRow))], 0);
  EXPECT_EQ(shore[static_cast<std::size_t>(g.index(kLand, kRow))], 1);
  const std::vector<std::uint8_t> at_datum = shore_cells(g, s.filled, mask::CoastSources{&s.open, &s.sea});
  EXPECT_EQ(at_datum[static_cast<std::size_t>(g.index(kShore - 1, kRow))], 0);
  EXPECT_EQ(at_datum[static_cast<std::size_t>(g.index(kShore, kRow))], 1);
}

}  // namespace
}  // namespace aq::size::unit_size_floodplain_terms_test

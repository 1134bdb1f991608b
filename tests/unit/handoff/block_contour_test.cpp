// SPDX-License-Identifier: GPL-3.0-or-later
// Block contours: projection choice, the written .izogrid + TOML loading back through
// config::load_regional with the expected centre and 4 corners, upright boxes of a rotated
// lattice, poles, shrink-to-wet (moves over land only, smooth, corners kept at 90°), and the
// squares of the Mercator lattice (box coordinates and contours on its rows).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "config/regional.hpp"
#include "core/error.hpp"
#include "core/types.hpp"
#include "curvilinear/regional.hpp"
#include "curvilinear/common/spline_contour.hpp"
#include "handoff/block_contour.hpp"
#include "handoff/block_files.hpp"
#include "mask/lattice_coords.hpp"
#include "support/temp_dir.hpp"

namespace unit_handoff_block_contour_test {

namespace {

using aq::Bitmap;
using aq::Lattice;
using aq::PoleRotation;
using aq::handoff::BlockBox;
using aq::handoff::BlockContour;
using aq::handoff::BoxFrame;
using aq::handoff::SideInsets;

aq::curvilinear::SplineContour spline_of(const BlockContour& c) {
  std::vector<bool> corner(c.x.size(), false);
  for (const int k : c.corners) corner[static_cast<std::size_t>(k)] = true;
  return aq::curvilinear::SplineContour(c.x, c.y, corner);
}

// Sine of the angle between the incoming and the outgoing tangent at each corner (0 = right angle).
void expect_right_angles(const aq::curvilinear::SplineContour& s) {
  using aq::curvilinear::Side;
  const Side sides[4] = {Side::kSouth, Side::kEast, Side::kNorth, Side::kWest};
  for (int q = 0; q < 4; ++q) {
    const Side out = sides[q], in = sides[(q + 3) % 4];
    const double at = s.side_begin(out);
    const auto a = s.side_derivative(in, q == 0 ? s.period() : at);
    const auto b = s.side_derivative(out, at);
    const double cosine = (a.x * b.x + a.y * b.y) / std::hypot(a.x, a.y) / std::hypot(b.x, b.y);
    EXPECT_NEAR(cosine, 0.0, 1e-12) << "corner " << q;
  }
}

Bitmap all_filled(const Lattice& lat) {
  Bitmap f(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx; ++i) f.set(i, j);
  return f;
}

// Clears every pixel whose centre (lattice degrees) satisfies `land`.
template <typename F>
void draw_land(Bitmap& f, const Lattice& lat, F land) {
  for (std::int64_t j = 0; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx; ++i) {
      const auto c = aq::mask::pixel_center_lattice_deg(lat, {i, j});
      if (land(c.lon_deg, c.lat_deg)) f.clear(i, j);
    }
}

bool filled_at(const Bitmap& f, const Lattice& lat, const aq::curvilinear::GeoPoint& p) {
  double x = 0, y = 0;
  aq::mask::deg_to_lattice_xy(lat, {p.lon_deg, p.lat_deg}, x, y);
  return f.get(static_cast<std::int64_t>(x), std::min(static_cast<std::int64_t>(y), lat.ny - 1));
}

// At every station of the insets, every sample cell between the box's side and the shrunk side
// is land (the guarantee holds at the stations' resolution; the spline through the control
// points may cut across a station spacing).
void expect_strips_dry(const BoxFrame& fr, const SideInsets& in, const Bitmap& f, const Lattice& lat) {
  const int n = in.n;
  for (int side = 0; side < 4; ++side) {
    for (int k = 0; k < n; ++k) {
      const double x = (k + 0.5) / n;
      const double e = in.e[static_cast<std::size_t>(side)][static_cast<std::size_t>(k)];
      for (int m = 0; (m + 0.5) / n < e; ++m) {
        const double d = (m + 0.5) / n;
        double s = 0, t = 0;
        switch (side) {
          case 0:
            s = x;
            t = d;
            break;
          case 1:
            s = 1 - d;
            t = x;
            break;
          case 2:
            s = x;
            t = 1 - d;
            break;
          default:
            s = d;
            t = x;
            break;
        }
        EXPECT_FALSE(filled_at(f, lat, fr.system(s, t))) << "side " << side << " at " << x << ", inset " << d;
      }
    }
  }
}

}  // namespace

TEST(BlockProjection, MercatorCentredWithUscaleForGraphPaper) {
  const BoxFrame fr(BlockBox{28.0, 32.0, 40.0, 44.0, true}, PoleRotation());
  const auto p = aq::handoff::choose_projection(fr);
  EXPECT_EQ(p.kind, aq::curvilinear::ProjectionKind::kMercator);
  EXPECT_DOUBLE_EQ(p.rlat_deg, 42.0);
  EXPECT_DOUBLE_EQ(p.rlon_deg, 30.0);
  EXPECT_EQ(p.rota_deg, 0.0);
  // Half-width 2° of longitude at 40°N ≈ 0.0267 rad, half-height ≈ 0.035 rad -> uscale 0.0005.
  EXPECT_DOUBLE_EQ(p.uscale, 0.0005);
  const BlockContour c = aq::handoff::block_contour(fr, {}, 6);
  double m = 0;
  for (std::size_t k = 0; k < c.x.size(); ++k) m = std::max({m, std::abs(c.x[k]), std::abs(c.y[k])});
  EXPECT_LE(m, 100.0);
  EXPECT_GT(m, 40.0);
}

TEST(BlockProjection, StereographicNearThePolesAndPolarSidesTrimmed) {
  const BoxFrame fr(BlockBox{0.0, 90.0, 70.0, 90.0, false}, PoleRotation());
  EXPECT_TRUE(fr.trimmed());
  EXPECT_DOUBLE_EQ(fr.box().lat_max_deg, 89.0);
  const auto p = aq::handoff::choose_projection(fr);
  EXPECT_EQ(p.kind, aq::curvilinear::ProjectionKind::kStereographic);
  const BlockContour c = aq::handoff::block_contour(fr, {}, 8);
  expect_right_angles(spline_of(c));
}

TEST(BlockProjection, RotatedLatticeBoxStandsUpright) {
  const PoleRotation rot(-44.858333, 78.141667);
  const BoxFrame fr(BlockBox{100.0, 104.0, 20.0, 24.0, true}, rot);
  const auto p = aq::handoff::choose_projection(fr);
  EXPECT_NE(p.rota_deg, 0.0);
  const BlockContour c = aq::handoff::block_contour(fr, {}, 4);
  // The box is symmetric about its central (rotated) meridian, which is the plane's y axis.
  const std::size_t sw = 0, se = 4, ne = 8, nw = 12;
  EXPECT_NEAR(c.y[sw], c.y[se], 1e-9 * std::abs(c.y[sw]));
  EXPECT_NEAR(c.x[sw], -c.x[se], 1e-9 * std::abs(c.x[sw]));
  EXPECT_NEAR(c.y[ne], c.y[nw], 1e-9 * std::abs(c.y[ne]));
  EXPECT_GT(c.y[nw], c.y[sw]);
  expect_right_angles(spline_of(c));
}

TEST(BlockFiles, WrittenConfigLoadsWithCentreAndFourCorners) {
  const BoxFrame fr(BlockBox{28.0, 32.0, 40.0, 44.0, true}, PoleRotation());
  const BlockContour c = aq::handoff::block_contour(fr, {}, 5);
  aq::testing::TempDir dir;
  aq::handoff::BlockConfigInfo info;
  info.name = "block_007";
  info.izogrid_file = "block_007.izogrid";
  info.description = "test block\nsecond line";
  info.ny = 24;
  info.input_path = "/usr/share/ferret-vis/data/etopo60.cdf";
  info.coast_level_m = -10.0;
  info.output_dir = (dir / "out \"quoted\"").string();
  info.global_config = (dir / "global.toml").string();
  std::ofstream(dir / "block_007.izogrid") << aq::handoff::izogrid_text(c, 24, 1.0, info.description);
  std::ofstream(dir / "block_007.toml") << aq::handoff::regional_config_text(info);

  const auto loaded = aq::config::load_regional((dir / "block_007.toml").string(), {});
  const auto& r = loaded.options;
  EXPECT_EQ(r.name, "block_007");
  EXPECT_EQ(r.params.projection.kind, aq::curvilinear::ProjectionKind::kMercator);
  EXPECT_NEAR(r.params.projection.rlat_deg, 42.0, 1e-12);
  EXPECT_NEAR(r.params.projection.rlon_deg, 30.0, 1e-12);
  EXPECT_EQ(r.params.projection.rota_deg, 0.0);
  EXPECT_EQ(r.params.ny, 24);
  EXPECT_DOUBLE_EQ(r.params.projection.uscale, 0.0005);
  EXPECT_FALSE(r.params.points_lonlat);
  ASSERT_EQ(r.params.x.size(), 20u);
  std::vector<std::size_t> corners;
  for (std::size_t k = 0; k < r.params.corner.size(); ++k)
    if (r.params.corner[k]) corners.push_back(k);
  EXPECT_EQ(corners, (std::vector<std::size_t>{0, 5, 10, 15}));
  // The corners are the box's corners, projected.
  const aq::curvilinear::Projection proj(r.params.projection);
  const double lon[4] = {28, 32, 32, 28}, lat[4] = {40, 40, 44, 44};
  for (int q = 0; q < 4; ++q) {
    const auto e = proj.forward(lon[q], lat[q]);
    EXPECT_NEAR(r.params.x[corners[static_cast<std::size_t>(q)]], e.x, 1e-9);
    EXPECT_NEAR(r.params.y[corners[static_cast<std::size_t>(q)]], e.y, 1e-9);
  }
  EXPECT_EQ(r.output_dir, info.output_dir);
  EXPECT_EQ(r.roms.global_config, info.global_config);
  EXPECT_DOUBLE_EQ(r.coast_level_m, -10.0);
  expect_right_angles(spline_of(c));
}

TEST(BlockFiles, TomlStringsEscape) { EXPECT_EQ(aq::handoff::toml_string("a\"b\\c\n"), "\"a\\\"b\\\\c\\n\""); }

TEST(ShrinkToWet, WestSideMovesOverAStraightCoast) {
  const Lattice lat = Lattice::make(4.0, 3, -180.0);  // 0.5° pixels
  Bitmap f = all_filled(lat);
  draw_land(f, lat, [](double lon, double la) { return lon >= -2.0 && lon < 1.0 && la > 36.0 && la < 48.0; });
  const BoxFrame fr(BlockBox{0.0, 4.0, 40.0, 44.0, true}, PoleRotation());
  const SideInsets in = aq::handoff::shrink_to_wet(fr, f, lat, PoleRotation(), 0.3);
  EXPECT_EQ(in.n, 32);
  EXPECT_DOUBLE_EQ(in.max(3), 0.25);
  EXPECT_DOUBLE_EQ(in.at(3, 0.0), 0.25);
  EXPECT_DOUBLE_EQ(in.at(3, 1.0), 0.25);
  EXPECT_EQ(in.max(0), 0.0);
  EXPECT_EQ(in.max(1), 0.0);
  EXPECT_EQ(in.max(2), 0.0);
  expect_strips_dry(fr, in, f, lat);
  const BlockContour c = aq::handoff::block_contour(fr, in, 8);
  const aq::curvilinear::Projection proj(c.projection);
  const auto sw = proj.forward(1.0, 40.0), nw = proj.forward(1.0, 44.0), se = proj.forward(4.0, 40.0);
  EXPECT_NEAR(c.x[0], sw.x, 1e-9);
  EXPECT_NEAR(c.y[0], sw.y, 1e-9);
  EXPECT_NEAR(c.x[24], nw.x, 1e-9);
  EXPECT_NEAR(c.y[24], nw.y, 1e-9);
  EXPECT_NEAR(c.x[8], se.x, 1e-9);
  expect_right_angles(spline_of(c));
}

TEST(ShrinkToWet, CappedInsetAndNothingMovesOverWater) {
  const Lattice lat = Lattice::make(4.0, 3, -180.0);
  Bitmap f = all_filled(lat);
  draw_land(f, lat, [](double lon, double la) { return lon >= -2.0 && lon < 3.0 && la > 36.0 && la < 48.0; });
  const BoxFrame fr(BlockBox{0.0, 4.0, 40.0, 44.0, true}, PoleRotation());
  const SideInsets capped = aq::handoff::shrink_to_wet(fr, f, lat, PoleRotation(), 0.2);
  EXPECT_DOUBLE_EQ(capped.max(3), 0.1875);  // floor(0.2 · 32) / 32: the last whole cell under the cap
  const SideInsets none = aq::handoff::shrink_to_wet(fr, all_filled(lat), lat, PoleRotation(), 0.3);
  for (int s = 0; s < 4; ++s) EXPECT_EQ(none.max(s), 0.0);
}

TEST(ShrinkToWet, BumpyCoastGivesSmoothSidesWithStraightCorners) {
  const Lattice lat = Lattice::make(4.0, 4, -180.0);  // 0.25° pixels: n = 32
  Bitmap f = all_filled(lat);
  // A southern coast with a peninsula (land reaching 41.25°N between 1.5°E and 2.5°E) and a
  // western coast that is deeper in the middle.
  draw_land(f, lat, [](double lon, double la) {
    const bool south = la < 40.5 || (lon > 1.5 && lon < 2.5 && la < 41.25);
    const bool west = lon < 0.25 + (std::abs(la - 42.0) < 0.6 ? 0.75 : 0.0);
    return (south || west) && lon > -3.0 && la > 37.0 && la < 47.0;
  });
  const BoxFrame fr(BlockBox{0.0, 4.0, 40.0, 44.0, true}, PoleRotation());
  const SideInsets in = aq::handoff::shrink_to_wet(fr, f, lat, PoleRotation(), 0.3);
  expect_strips_dry(fr, in, f, lat);
  for (int side = 0; side < 4; ++side) {
    const auto& e = in.e[static_cast<std::size_t>(side)];
    for (std::size_t k = 1; k < e.size(); ++k) EXPECT_LE(std::abs(e[k] - e[k - 1]), 0.5 / in.n + 1e-15);
    // Flat corner zones: constant within max_inset (+ a cell) of both ends.
    for (std::size_t k = 0; k < e.size(); ++k) {
      const double x = (static_cast<double>(k) + 0.5) / in.n;
      if (x < 0.3 + 1.0 / in.n) {
        EXPECT_EQ(e[k], e[0]);
      }
      if (x > 0.7 - 1.0 / in.n) {
        EXPECT_EQ(e[k], e.back());
      }
    }
  }
  EXPECT_DOUBLE_EQ(in.at(0, 0.0), 0.125);   // S moved over the coast at 40.5°N
  EXPECT_GT(in.at(0, 0.5), 0.125);          // and further up the peninsula, slope-limited
  EXPECT_LT(in.at(0, 0.5), 0.3125);         // but not all the way (41.25°N is 0.3125)
  EXPECT_DOUBLE_EQ(in.at(3, 0.0), 0.0625);  // W by the 0.25° strip, the deeper middle ignored near corners
  EXPECT_GT(in.at(3, 0.5), 0.0625);
  const BlockContour c = aq::handoff::block_contour(fr, in, 8);
  expect_right_angles(spline_of(c));
  // The contour stays inside the box: all points within its projected outline's extent.
  const aq::curvilinear::Projection proj(c.projection);
  const auto lo = proj.forward(0.0, 40.0), hi = proj.forward(4.0, 44.0);
  for (std::size_t k = 0; k < c.x.size(); ++k) {
    EXPECT_GE(c.y[k], lo.y - 1e-9);
    EXPECT_LE(c.y[k], hi.y + 1e-9);
  }
}

// A level-0 square of the Mercator lattice (Δ0 = 4°, L = 3, rows to ±86.5° as
// configs/global_mercator.toml): its 8 rows are evenly spaced in the Mercator ordinate, not in φ.
namespace {

Lattice mercator_lattice() { return Lattice::make_mercator(4.0, 3, -180.0, 86.5); }

// The square (a, b) of the Mercator lattice as rank_blocks makes it.
BlockBox mercator_square(const Lattice& lat, std::int64_t a, std::int64_t b) {
  const std::int64_t s = lat.pixels_per_square(0);
  return BlockBox{lat.lon_of(a * s), lat.lon_of((a + 1) * s), lat.lat_of(b * s), lat.lat_of((b + 1) * s), true, true};
}

// Fractional row of φ' from the Mercator formula written out (independent of Lattice::row_of_lat).
double mercator_row(const Lattice& lat, double lat_deg) {
  const double y = std::log(std::tan(M_PI / 4.0 + 0.5 * lat_deg * aq::kDegToRad)) * aq::kRadToDeg;
  return (y - lat.y0_deg) / lat.pixel_deg();
}

}  // namespace

TEST(MercatorBlock, BoxCoordinatesFollowTheMercatorRowsAndTheContourLiesOnThem) {
  const Lattice lat = mercator_lattice();
  const std::int64_t b = lat.ny / 16 + 17;  // a level-0 square at about 56° N of the lattice frame
  const BoxFrame fr(mercator_square(lat, 45, b), PoleRotation());
  EXPECT_FALSE(fr.trimmed());
  for (int m = 0; m <= 8; ++m)
    EXPECT_NEAR(mercator_row(lat, fr.system(0.3, m / 8.0).lat_deg), static_cast<double>(b * 8 + m), 1e-9) << m;
  // φ-linear box coordinates would put the middle row 0.059 pixel off here.
  const double phi_mid = 0.5 * (fr.box().lat_min_deg + fr.box().lat_max_deg);
  EXPECT_GT(std::abs(mercator_row(lat, phi_mid) - static_cast<double>(b * 8 + 4)), 0.05);
  // 8 control points per side: every one on a lattice vertex of the square's outline.
  const BlockContour c = aq::handoff::block_contour(fr, {}, 8);
  ASSERT_EQ(c.x.size(), 32u);
  const aq::curvilinear::Projection proj(c.projection);
  for (std::size_t k = 0; k < c.x.size(); ++k) {
    const auto g = proj.inverse(c.x[k], c.y[k]);
    const double col = (g.lon_deg - lat.lon0_deg) / lat.pixel_deg(), row = mercator_row(lat, g.lat_deg);
    EXPECT_NEAR(col, std::round(col), 1e-7) << k;
    EXPECT_NEAR(row, std::round(row), 1e-7) << k;
    const double b0 = static_cast<double>(b * 8);
    EXPECT_TRUE(std::round(col) == 360.0 || std::round(col) == 368.0 || std::round(row) == b0 ||
                std::round(row) == b0 + 8.0)
        << k;
  }
  expect_right_angles(spline_of(c));
}

TEST(MercatorBlock, ShrinkToWetStopsAtTheCoastRow) {
  const Lattice lat = mercator_lattice();
  const std::int64_t b = lat.ny / 16 + 17;
  Bitmap f = all_filled(lat);
  // Land: the three southern rows of the square (and beyond it, west to east).
  for (std::int64_t j = b * 8 - 4; j < b * 8 + 3; ++j)
    for (std::int64_t i = 40 * 8; i < 50 * 8; ++i) f.clear(i, j);
  const BoxFrame fr(mercator_square(lat, 45, b), PoleRotation());
  const SideInsets in = aq::handoff::shrink_to_wet(fr, f, lat, PoleRotation(), 0.45);
  EXPECT_EQ(in.n, 32);  // 2 stations per pixel of the 8 x 8 square, at least 32
  EXPECT_DOUBLE_EQ(in.max(0), 3.0 / 8.0);
  EXPECT_DOUBLE_EQ(in.at(0, 0.5), 3.0 / 8.0);
  EXPECT_EQ(in.max(1), 0.0);
  EXPECT_EQ(in.max(2), 0.0);
  EXPECT_EQ(in.max(3), 0.0);
  expect_strips_dry(fr, in, f, lat);
  // The shrunk south side is the Mercator row 3 of the square.
  const BlockContour c = aq::handoff::block_contour(fr, in, 8);
  const aq::curvilinear::Projection proj(c.projection);
  const auto sw = proj.inverse(c.x[0], c.y[0]);
  EXPECT_NEAR(mercator_row(lat, sw.lat_deg), static_cast<double>(b * 8 + 3), 1e-7);
}

// A one-pixel inlet reaching the box's east edge between two control points (P = 4, spaced 1°):
// the station profile dips to 0 there, but with control points on the profile the side ran
// straight from 42°N to 43°N, 0.2° into the inlet. The contour itself (the spline, sampled
// densely) must leave only land behind.
TEST(ShrinkToWet, ControlPointsDoNotCutAcrossANarrowInlet) {
  const Lattice lat = Lattice::make(4.0, 4, -180.0);  // 0.25° pixels: n = 32
  Bitmap f = all_filled(lat);
  draw_land(f, lat, [](double lon, double la) {
    const bool inlet = la > 42.25 && la < 42.5;
    return lon > 3.0 && lon < 6.0 && la > 37.0 && la < 47.0 && !inlet;
  });
  const BoxFrame fr(BlockBox{0.0, 4.0, 40.0, 44.0, true}, PoleRotation());
  const SideInsets in = aq::handoff::shrink_to_wet(fr, f, lat, PoleRotation(), 0.3);
  expect_strips_dry(fr, in, f, lat);
  EXPECT_DOUBLE_EQ(in.at(1, 0.59), 0.0);  // the profile opens at the inlet
  EXPECT_GT(in.max(1), 0.1);              // and moves over the land elsewhere
  const BlockContour c = aq::handoff::block_contour(fr, in, 4);
  const auto spline = spline_of(c);
  expect_right_angles(spline);
  const aq::curvilinear::Projection proj(c.projection);
  using aq::curvilinear::Side;
  const double s0 = spline.side_begin(Side::kEast), s1 = spline.side_end(Side::kEast);
  int wet_behind = 0;
  for (int k = 0; k <= 2000; ++k) {
    const auto p = spline.point(s0 + (s1 - s0) * k / 2000.0);
    const auto g = proj.inverse(p.x, p.y);
    // Half a station (0.0625°) east of the side up to the box's edge.
    for (double lon = g.lon_deg + 0.0625; lon < 4.0; lon += 0.03125)
      if (filled_at(f, lat, {lon, g.lat_deg})) {
        ++wet_behind;
        break;
      }
  }
  EXPECT_EQ(wet_behind, 0);
}

}  // namespace unit_handoff_block_contour_test

// RotatedParallel: the positions found from one atan2/asin per run agree with atan2/asin at every
// point within kMaxErrorDeg, on every row of a picture from pole to pole, for several rotations
// (the error is measured, and stays well under the bound); and exact_positions is the rotation.
#include "pictures/rotated_parallel.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace aq::io {
namespace {

// λ' of the column centres of a map `w` pixels wide starting at λ0 (as preview_png draws them).
std::vector<double> column_lons(int w, double lon0) {
  std::vector<double> v(static_cast<std::size_t>(w));
  for (std::size_t x = 0; x < v.size(); ++x) v[x] = lon0 + (static_cast<double>(x) + 0.5) * 360.0 / w;
  return v;
}

double lon_difference(double a, double b) {
  double d = std::abs(a - b);
  return std::min(d, 360.0 - d);
}

struct Worst {
  double error_deg = 0.0;  // largest |positions - exact_positions| (λ or φ)
  double lat_deg = 0.0;    // the φ' of its row
};

// Rows every 0.25° of φ' from -89.875 to 89.875, plus rows near the rotated poles.
Worst worst_error(const PoleRotation& rotation, int w, double lon0) {
  const RotatedParallel p(rotation, column_lons(w, lon0));
  std::vector<double> rlat;
  for (int k = 0; k < 720; ++k) rlat.push_back(-89.875 + 0.25 * k);
  for (const double a : {89.99, 89.999999, -89.99, -89.999999, 0.0}) rlat.push_back(a);
  std::vector<double> lon(static_cast<std::size_t>(w)), lat(lon.size()), elon(lon.size()), elat(lon.size());
  Worst worst;
  for (const double phi : rlat) {
    p.positions(phi, lon.data(), lat.data());
    p.exact_positions(phi, elon.data(), elat.data());
    for (std::size_t x = 0; x < lon.size(); ++x) {
      EXPECT_GE(lon[x], -180.0);
      EXPECT_LE(lon[x], 180.0);
      const double e = std::max(lon_difference(lon[x], elon[x]), std::abs(lat[x] - elat[x]));
      if (e > worst.error_deg) worst = {e, phi};
    }
  }
  return worst;
}

TEST(RotatedParallel, PositionsAgreeWithAtan2AndAsinAtEveryPoint) {
  // The Greenland pole of the Mercator run, a pole on the equator, a southern one, one next to
  // the geographic North pole (the rotated frame almost the geographic one, λ' ≈ λ + 180°: the
  // seam of atan2 falls inside runs) and one off a whole degree.
  const std::vector<std::array<double, 2>> poles = {
      {-44.858333, 78.141667}, {30.0, 0.0}, {100.0, -60.0}, {0.0, 89.999}, {-170.3, 41.7}};
  for (const auto& pole : poles) {
    for (const int w : {2400, 997}) {
      const Worst worst = worst_error(PoleRotation(pole[0], pole[1]), w, -180.0);
      EXPECT_LE(worst.error_deg, RotatedParallel::kMaxErrorDeg)
          << "pole (" << pole[0] << ", " << pole[1] << "), width " << w << ", row " << worst.lat_deg;
      // What the header quotes: the series' truncation and rounding only.
      EXPECT_LE(worst.error_deg, 1e-11) << "pole (" << pole[0] << ", " << pole[1] << "), width " << w;
    }
  }
}

TEST(RotatedParallel, ExactPositionsAreThePoleRotation) {
  const PoleRotation rotation(-44.858333, 78.141667);
  const std::vector<double> rlon = column_lons(360, 20.0);
  const RotatedParallel p(rotation, rlon);
  std::vector<double> lon(rlon.size()), lat(rlon.size());
  for (const double phi : {-80.0, -33.3, 0.0, 45.0, 86.5}) {
    p.exact_positions(phi, lon.data(), lat.data());
    for (std::size_t x = 0; x < rlon.size(); ++x) {
      double glon = 0, glat = 0;
      rotation.to_geographic(rlon[x], phi, glon, glat);
      EXPECT_LE(lon_difference(lon[x], glon), 1e-9) << rlon[x] << ", " << phi;
      EXPECT_NEAR(lat[x], glat, 1e-9) << rlon[x] << ", " << phi;
    }
  }
}

// A row shorter than a run, and a run of one point at the end.
TEST(RotatedParallel, ShortRows) {
  const PoleRotation rotation(10.0, 50.0);
  for (const int n : {1, 5, RotatedParallel::kRun + 1}) {
    const RotatedParallel p(rotation, column_lons(n, -180.0));
    std::vector<double> lon(static_cast<std::size_t>(n)), lat(lon.size()), elon(lon.size()), elat(lon.size());
    p.positions(12.5, lon.data(), lat.data());
    p.exact_positions(12.5, elon.data(), elat.data());
    for (std::size_t x = 0; x < lon.size(); ++x) {
      EXPECT_LE(lon_difference(lon[x], elon[x]), RotatedParallel::kMaxErrorDeg) << n << " " << x;
      EXPECT_NEAR(lat[x], elat[x], RotatedParallel::kMaxErrorDeg) << n << " " << x;
    }
  }
}

}  // namespace
}  // namespace aq::io

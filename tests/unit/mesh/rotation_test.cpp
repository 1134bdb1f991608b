// SPDX-License-Identifier: GPL-3.0-or-later
// Pole rotation round trips (core/rotation.hpp, used by the mesh stage; ARCHITECTURE §4.7):
// geographic -> rotated -> geographic and back to 1e-12°.
#include "core/rotation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aq::unit_mesh_rotation_test {
namespace {

double lon_diff(double a, double b) {
  double d = std::fmod(a - b, 360.0);
  if (d > 180.0) d -= 360.0;
  if (d < -180.0) d += 360.0;
  return std::abs(d);
}

struct Pole {
  double lon, lat;
};

class RotationRoundTrip : public ::testing::TestWithParam<Pole> {};

TEST_P(RotationRoundTrip, Within1e12Degrees) {
  // Error of a round trip as an angle on the sphere (degrees): the longitude difference counts
  // with cos φ, since near the poles a tiny displacement is a large change of λ. The bare
  // longitude error is also checked away from the poles.
  const Pole p = GetParam();
  const PoleRotation rot(p.lon, p.lat);
  double worst = 0.0, worst_lon = 0.0;
  const auto record = [&](double lon0, double lat0, double lon1, double lat1) {
    const double dl = lon_diff(lon1, lon0);
    worst = std::max(worst, std::hypot(lat1 - lat0, dl * std::cos(lat0 * 3.14159265358979323846 / 180.0)));
    if (std::abs(lat0) <= 80.0) worst_lon = std::max(worst_lon, dl);
  };
  for (double lat = -89.5; lat <= 89.5; lat += 0.7) {
    for (double lon = -180.0; lon < 180.0; lon += 1.3) {
      double rl = 0, rf = 0, gl = 0, gf = 0;
      rot.to_rotated(lon, lat, rl, rf);
      rot.to_geographic(rl, rf, gl, gf);
      record(lon, lat, gl, gf);
      // And the other way: a rotated point through geographic and back.
      rot.to_geographic(lon, lat, gl, gf);
      rot.to_rotated(gl, gf, rl, rf);
      record(lon, lat, rl, rf);
    }
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_lon, 1e-12);
  // The rotated North pole is the given geographic point, and the geographic point maps back to it.
  double lon = 0, lat = 0;
  rot.to_geographic(0.0, 90.0, lon, lat);
  EXPECT_NEAR(lat, p.lat, 1e-12);
  if (p.lat < 90.0 - 1e-9) {
    EXPECT_LT(lon_diff(lon, p.lon), 1e-12);
  }
  rot.to_rotated(p.lon, p.lat, lon, lat);
  EXPECT_NEAR(lat, 90.0, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Poles, RotationRoundTrip,
                         ::testing::Values(Pole{-44.858333, 78.141667},  // the seed's Greenland pole
                                           Pole{0.0, 90.0}, Pole{120.0, 10.0}, Pole{-170.0, -45.0}, Pole{30.0, 0.0}));

TEST(Rotation, GreenlandPoleMovesTheGeographicNorthPoleOffTheLatticePole) {
  const PoleRotation rot(-44.858333, 78.141667);
  EXPECT_FALSE(rot.identity());
  double rlon = 0, rlat = 0;
  rot.to_rotated(0.0, 90.0, rlon, rlat);
  EXPECT_NEAR(rlat, 78.141667, 1e-9);  // the geographic pole is 90° - φp from the rotated pole
  EXPECT_TRUE(PoleRotation().identity());
}

}  // namespace
}  // namespace aq::unit_mesh_rotation_test

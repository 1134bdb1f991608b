// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the conformal projections (seed 000 Sec. 2.1, digest izogrid.md §3): round trips,
// the Black Sea plane coordinates of the seed's Fig. 3, conformality and the scale factor
// (numerical Jacobian), the rota convention, and the refused configurations.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.hpp"
#include "curvilinear/common/projection.hpp"

namespace aq::curvilinear::unit_curvilinear_projection_test {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Great-circle distance on the sphere of radius R, metres.
double distance_m(double lon1, double lat1, double lon2, double lat2, double r) {
  const double a = std::sin(0.5 * (lat2 - lat1) * kDeg);
  const double b = std::sin(0.5 * (lon2 - lon1) * kDeg);
  const double h = a * a + std::cos(lat1 * kDeg) * std::cos(lat2 * kDeg) * b * b;
  return 2.0 * r * std::asin(std::sqrt(h));
}

double lon_diff(double a, double b) {
  double d = std::fmod(a - b, 360.0);
  if (d > 180.0) d -= 360.0;
  if (d < -180.0) d += 360.0;
  return d;
}

struct Case {
  ProjectionKind kind;
  double rlat, rlon, rota, lat1, lat2;
};

std::vector<Case> cases() {
  return {{ProjectionKind::kMercator, 43.75, 34.5, 0.0, NAN, NAN},
          {ProjectionKind::kMercator, -35.0, 150.0, 30.0, NAN, NAN},
          {ProjectionKind::kMercator, 0.0, -179.5, -75.0, NAN, NAN},
          {ProjectionKind::kStereographic, 90.0, 0.0, 0.0, NAN, NAN},
          {ProjectionKind::kStereographic, -71.0, 20.0, 15.0, NAN, NAN},
          {ProjectionKind::kStereographic, 43.75, 34.5, 0.0, NAN, NAN},
          {ProjectionKind::kLambertConic, 45.0, 10.0, 0.0, 35.0, 55.0},
          {ProjectionKind::kLambertConic, -30.0, 140.0, 20.0, -20.0, -40.0},
          {ProjectionKind::kLambertConic, 60.0, -40.0, 0.0, NAN, NAN}};
}

ProjectionParams make(const Case& c) {
  ProjectionParams p;
  p.kind = c.kind;
  p.rlat_deg = c.rlat;
  p.rlon_deg = c.rlon;
  p.rota_deg = c.rota;
  p.lat1_deg = c.lat1;
  p.lat2_deg = c.lat2;
  return p;
}

TEST(ProjectionTest, RoundTripsToOneTrillionthOfADegree) {
  std::mt19937 rng(20240607);
  for (const Case& c : cases()) {
    const Projection proj(make(c));
    std::uniform_real_distribution<double> dlat(-25.0, 25.0), dlon(-30.0, 30.0);
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const double lat = std::clamp(c.rlat + dlat(rng), -89.0, 89.0);
      const double lon = c.rlon + dlon(rng);
      const PlanePoint q = proj.forward(lon, lat);
      ASSERT_TRUE(std::isfinite(q.x) && std::isfinite(q.y)) << name_of(c.kind) << " at " << lon << " " << lat;
      const GeoPoint g = proj.inverse(q.x, q.y);
      worst = std::max({worst, std::fabs(g.lat_deg - lat), std::fabs(lon_diff(g.lon_deg, lon)) * std::cos(lat * kDeg)});
      // And the other way: plane -> sphere -> plane.
      const PlanePoint back = proj.forward(g.lon_deg, g.lat_deg);
      worst = std::max({worst, std::fabs(back.x - q.x) * 1e-3, std::fabs(back.y - q.y) * 1e-3});
    }
    EXPECT_LT(worst, 1e-12) << name_of(c.kind) << " centred at " << c.rlat << ", " << c.rlon;
  }
}

TEST(ProjectionTest, CentreIsOriginAndAxesFollowRota) {
  for (const Case& c : cases()) {
    const Projection proj(make(c));
    const PlanePoint o = proj.forward(c.rlon, c.rlat);
    EXPECT_NEAR(o.x, 0.0, 1e-9);
    EXPECT_NEAR(o.y, 0.0, 1e-9);
    // A point a little north of the centre lies at azimuth -rota from the +y axis, i.e. in
    // direction (-sin rota, cos rota) of the plane.
    if (std::fabs(c.rlat) < 89.0) {
      const PlanePoint n = proj.forward(c.rlon, c.rlat + 0.01);
      const double len = std::hypot(n.x, n.y);
      EXPECT_NEAR(n.x / len, -std::sin(c.rota * kDeg), 1e-4) << name_of(c.kind);
      EXPECT_NEAR(n.y / len, std::cos(c.rota * kDeg), 1e-4) << name_of(c.kind);
    }
  }
}

TEST(ProjectionTest, BlackSeaControlPointsInsideTheSeedMapLimits) {
  // Seed Fig. 3: rotated Mercator at 43.75N 34.5E, uscale = 0.001 (plane units are milliradians
  // of the rotated sphere); the same file's map limits 26.5..43E, 40.75..47.25N frame the region,
  // so every control point must fall inside them (the NE corner at 47.29N sits on the edge). Independently of the
  // rotation code, the angular distance from the centre of the rotated-sphere point (λ', φ') = (x, asinh⁻¹ y)·uscale is
  // acos(cos φ' cos λ').
  ProjectionParams p;
  p.rlat_deg = 43.75;
  p.rlon_deg = 34.5;
  const Projection proj(p);
  const std::vector<double> x{-97, -77, -44, -9, 25, 75, 104, 89.2, 55, 38, 57.5, 3, -40, -74, -84};
  const std::vector<double> y{-26, -39.5, -46, -31.5, -44, -47, -33, -14, 10, 29, 63.5, 47, 60, 12, -6.2};
  for (std::size_t k = 0; k < x.size(); ++k) {
    const GeoPoint g = proj.inverse(x[k], y[k]);
    EXPECT_GT(g.lon_deg, 26.5) << k;
    EXPECT_LT(g.lon_deg, 43.0) << k;
    EXPECT_GT(g.lat_deg, 40.75) << k;
    EXPECT_LT(g.lat_deg, 47.25 + 0.05) << k;
    const double lam = x[k] * 1e-3, phi = std::atan(std::sinh(y[k] * 1e-3));
    const double c = std::acos(std::cos(phi) * std::cos(lam));
    EXPECT_NEAR(distance_m(34.5, 43.75, g.lon_deg, g.lat_deg, 1.0), c, 1e-12) << k;
  }
  // The north-east corner is at the head of the Sea of Azov (Taganrog Bay, ~39.2E 47.2N), the
  // south-west one on the coast at Burgas (~27.5E 42.5N), the south-east one at Batumi (~41.6E
  // 41.6N): the contour frames the sea, corners on or just inside the land (masked later).
  const GeoPoint ne = proj.inverse(57.5, 63.5), sw = proj.inverse(-97.0, -26.0), se = proj.inverse(104.0, -33.0);
  EXPECT_NEAR(ne.lon_deg, 39.2, 0.5);
  EXPECT_NEAR(ne.lat_deg, 47.2, 0.5);
  EXPECT_NEAR(sw.lon_deg, 27.5, 0.6);
  EXPECT_NEAR(sw.lat_deg, 42.5, 0.5);
  EXPECT_NEAR(se.lon_deg, 41.6, 1.0);
  EXPECT_NEAR(se.lat_deg, 41.6, 0.5);
  // One plane unit at the centre is radius * uscale = 6371 m.
  EXPECT_DOUBLE_EQ(proj.metres_per_unit(0.0, 0.0), 6371.0);
}

TEST(ProjectionTest, ConformalWithTheStatedScaleFactor) {
  // Numerical Jacobian of the inverse map: the two plane directions map to perpendicular sphere
  // directions of equal length metres_per_unit(x, y) * h.
  for (const Case& c : cases()) {
    const Projection proj(make(c));
    for (const auto& [x, y] : {std::pair{0.0, 0.0}, std::pair{150.0, -80.0}, std::pair{-220.0, 310.0}}) {
      const double h = 1e-3;
      const GeoPoint o = proj.inverse(x, y), ex = proj.inverse(x + h, y), ey = proj.inverse(x, y + h);
      const double k = proj.metres_per_unit(x, y) * h;
      const double r = proj.params().radius_m;
      EXPECT_NEAR(distance_m(o.lon_deg, o.lat_deg, ex.lon_deg, ex.lat_deg, r) / k, 1.0, 2e-6) << name_of(c.kind);
      EXPECT_NEAR(distance_m(o.lon_deg, o.lat_deg, ey.lon_deg, ey.lat_deg, r) / k, 1.0, 2e-6) << name_of(c.kind);
      // Perpendicular: the diagonal has length sqrt(2) k.
      const GeoPoint exy = proj.inverse(x + h, y + h);
      const GeoPoint em = proj.inverse(x + h, y - h);
      const double d1 = distance_m(o.lon_deg, o.lat_deg, exy.lon_deg, exy.lat_deg, r);
      const double d2 = distance_m(ey.lon_deg, ey.lat_deg, em.lon_deg, em.lat_deg, r);
      EXPECT_NEAR(d1 / (std::sqrt(2.0) * k), 1.0, 1e-5) << name_of(c.kind);
      EXPECT_NEAR(d2 / (std::sqrt(5.0) * k), 1.0, 1e-5) << name_of(c.kind);
    }
  }
}

TEST(ProjectionTest, MercatorMatchesTheClassicFormulaWhenNotRotated) {
  ProjectionParams p;
  p.rlat_deg = 0.0;
  p.rlon_deg = 10.0;
  p.uscale = 1.0;
  const Projection proj(p);
  const PlanePoint q = proj.forward(40.0, 60.0);
  EXPECT_NEAR(q.x, 30.0 * kDeg, 1e-14);
  EXPECT_NEAR(q.y, std::log(std::tan(0.25 * 3.14159265358979323846 + 30.0 * kDeg)), 1e-14);
}

TEST(ProjectionTest, RefusesSingularConfigurations) {
  ProjectionParams p;
  p.rlat_deg = 90.0;
  try {
    Projection bad(p);
    FAIL() << "a Mercator centre at the pole was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("rlat = 90"), std::string::npos) << e.what();
  }
  p.rlat_deg = -90.0;
  EXPECT_THROW(Projection{p}, ConfigError);
  p.kind = ProjectionKind::kStereographic;
  EXPECT_NO_THROW(Projection{p});  // polar stereographic is fine
  p.kind = ProjectionKind::kLambertConic;
  p.rlat_deg = 10.0;
  p.lat1_deg = -30.0;
  p.lat2_deg = 30.0;
  EXPECT_THROW(Projection{p}, ConfigError);  // a cylinder: use ME
  p.lat1_deg = 30.0;
  p.uscale = 0.0;
  EXPECT_THROW(Projection{p}, ConfigError);
  EXPECT_FALSE(parse_name_any_case<ProjectionKind>("XY").has_value());
  EXPECT_EQ(parse_name_any_case<ProjectionKind>("me"), ProjectionKind::kMercator);
  EXPECT_EQ(parse_name_any_case<ProjectionKind>("Lambert"), ProjectionKind::kLambertConic);
  EXPECT_FALSE(parse_name<ProjectionKind>("me").has_value());  // exact names only
  EXPECT_EQ(name_of(ProjectionKind::kStereographic), "ST");
  EXPECT_EQ(name_list<ProjectionKind>(), "\"ME\", \"LC\", \"ST\"");  // aliases are not listed
}

}  // namespace
}  // namespace aq::curvilinear::unit_curvilinear_projection_test

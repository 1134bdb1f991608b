// SPDX-License-Identifier: GPL-3.0-or-later
// The ROMS C-grid on the sphere: metrics against great circles computed here independently
// (haversine), angles against the bearings of ξ lines and against the projection's rotation,
// f = 2Ω sin φ, the ρ/u/v/ψ index convention, and bad input.
#include "curvilinear/common/cgrid.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "support/uniform_grid.hpp"

namespace aq::curvilinear::unit_curvilinear_cgrid_test {
namespace {

constexpr double kR = 6371000.0;
constexpr double kD2R = 3.14159265358979323846 / 180.0;

// Independent of the library: haversine distance and initial/final bearings (radians).
double haversine(double lon1, double lat1, double lon2, double lat2, double r = kR) {
  const double p1 = lat1 * kD2R, p2 = lat2 * kD2R;
  const double a = std::sin(0.5 * (lat2 - lat1) * kD2R), b = std::sin(0.5 * (lon2 - lon1) * kD2R);
  return 2.0 * r * std::asin(std::sqrt(a * a + std::cos(p1) * std::cos(p2) * b * b));
}
double initial_bearing(double lon1, double lat1, double lon2, double lat2) {
  const double p1 = lat1 * kD2R, p2 = lat2 * kD2R, dl = (lon2 - lon1) * kD2R;
  return std::atan2(std::sin(dl) * std::cos(p2),
                    std::cos(p1) * std::sin(p2) - std::sin(p1) * std::cos(p2) * std::cos(dl));
}

// A plane rectangle [-ax, ax] x [-ay, ay] as a (2nx+1) x (2ny+1) supergrid with uniform steps.
Grid2D rectangle(int nx, int ny, double ax, double ay) { return aq::testing::uniform_supergrid(nx, ny, ax, ay); }

Projection mercator(double rlat, double rlon, double rota) {
  ProjectionParams p;
  p.kind = ProjectionKind::kMercator;
  p.rlat_deg = rlat;
  p.rlon_deg = rlon;
  p.rota_deg = rota;
  p.uscale = 0.001;
  p.radius_m = kR;
  return Projection(p);
}

TEST(CGrid, DimensionsAndIndexConventionFollowGrdSphericalCdl) {
  const Grid2D g = rectangle(7, 5, 80.0, 50.0);
  const Projection pr = mercator(43.75, 34.5, 0.0);
  const CGrid c = build_cgrid(g, pr);
  EXPECT_EQ(c.L, 7);
  EXPECT_EQ(c.M, 5);
  EXPECT_EQ(c.rho.ni, 8);  // xi_rho = L+1
  EXPECT_EQ(c.rho.nj, 6);  // eta_rho = M+1
  EXPECT_EQ(c.u.ni, 7);    // xi_u = L
  EXPECT_EQ(c.u.nj, 6);
  EXPECT_EQ(c.v.ni, 8);
  EXPECT_EQ(c.v.nj, 5);  // eta_v = M
  EXPECT_EQ(c.psi.ni, 7);
  EXPECT_EQ(c.psi.nj, 5);
  EXPECT_EQ(c.pm.size(), 48u);
  // ρ(i,j) = G[2i][2j], u(k,j) = G[2k+1][2j], v(i,l) = G[2i][2l+1], ψ(k,l) = G[2k+1][2l+1].
  const auto geo = [&](int I, int J) { return pr.inverse(g.x[g.at(I, J)], g.y[g.at(I, J)]); };
  EXPECT_EQ(c.rho.lon_deg[c.rho.at(3, 2)], geo(6, 4).lon_deg);
  EXPECT_EQ(c.rho.lat_deg[c.rho.at(0, 0)], geo(0, 0).lat_deg);  // boundary ρ on the contour
  EXPECT_EQ(c.rho.lat_deg[c.rho.at(7, 5)], geo(14, 10).lat_deg);
  EXPECT_EQ(c.u.lon_deg[c.u.at(0, 1)], geo(1, 2).lon_deg);
  EXPECT_EQ(c.u.lat_deg[c.u.at(6, 5)], geo(13, 10).lat_deg);
  EXPECT_EQ(c.v.lat_deg[c.v.at(7, 4)], geo(14, 9).lat_deg);
  EXPECT_EQ(c.psi.lon_deg[c.psi.at(2, 3)], geo(5, 7).lon_deg);
  // x, y in metres: plane units times R·uscale at the centre of a Mercator map.
  EXPECT_NEAR(c.xy_metres_per_unit, kR * 0.001, 1e-9);
  EXPECT_NEAR(c.rho.x_m[c.rho.at(0, 0)], -80.0 * kR * 0.001, 1e-6);
  EXPECT_NEAR(c.psi.y_m[c.psi.at(0, 4)], (-50.0 + 100.0 * 9.0 / 10.0) * kR * 0.001, 1e-6);
}

TEST(CGrid, PmPnAreInverseGreatCircleLengthsThroughRho) {
  const Grid2D g = rectangle(20, 12, 150.0, 90.0);
  const CGrid c = build_cgrid(g, mercator(43.75, 34.5, 17.0));
  double worst = 0.0;
  for (int j = 0; j <= c.M; ++j)
    for (int i = 0; i <= c.L; ++i) {
      const std::size_t k = c.rho.at(i, j);
      // ξ: u(i-1) -> ρ(i) -> u(i) (file indices i-1 and i). On the contour the outer half step
      // is extrapolated from the inner ones: h1 = ρ(0)..u(0), h2 = u(0)..ρ(1), step 3·h1 − h2.
      const auto hu = [&](int ri, int ui) {
        const std::size_t a = c.rho.at(ri, j), b = c.u.at(ui, j);
        return haversine(c.rho.lon_deg[a], c.rho.lat_deg[a], c.u.lon_deg[b], c.u.lat_deg[b]);
      };
      const auto hv = [&](int rj, int vj) {
        const std::size_t a = c.rho.at(i, rj), b = c.v.at(i, vj);
        return haversine(c.rho.lon_deg[a], c.rho.lat_deg[a], c.v.lon_deg[b], c.v.lat_deg[b]);
      };
      double dx = 0.0, dy = 0.0;
      if (i == 0) {
        dx = std::max(3.0 * hu(0, 0) - hu(1, 0), 1.5 * hu(0, 0));
      } else if (i == c.L) {
        dx = std::max(3.0 * hu(c.L, c.L - 1) - hu(c.L - 1, c.L - 1), 1.5 * hu(c.L, c.L - 1));
      } else {
        dx = hu(i, i - 1) + hu(i, i);
      }
      if (j == 0) {
        dy = std::max(3.0 * hv(0, 0) - hv(1, 0), 1.5 * hv(0, 0));
      } else if (j == c.M) {
        dy = std::max(3.0 * hv(c.M, c.M - 1) - hv(c.M - 1, c.M - 1), 1.5 * hv(c.M, c.M - 1));
      } else {
        dy = hv(j, j - 1) + hv(j, j);
      }

      worst = std::max(worst, std::fabs(c.pm[k] * dx - 1.0));
      worst = std::max(worst, std::fabs(c.pn[k] * dy - 1.0));
    }
  EXPECT_LT(worst, 1e-10);
  // ρ steps are 300/20 plane units of 6.371 km: pm is about 1/(95 km), and the map conformal.
  const CGridStats s = cgrid_stats(c);
  EXPECT_GT(s.pm_min, 1.0 / 120000.0);
  EXPECT_LT(s.pm_max, 1.0 / 80000.0);
  EXPECT_LT(s.isotropy_max_interior, 1e-3);
  EXPECT_GT(s.isotropy_max_interior, 0.0);
  EXPECT_LT(s.isotropy_max, 1e-3);  // the extrapolated boundary steps are as isotropic
}

TEST(CGrid, EarthRadiusScalesTheMetrics) {
  const Grid2D g = rectangle(6, 4, 60.0, 40.0);
  const Projection pr = mercator(10.0, -40.0, 0.0);
  CGridOptions o;
  o.earth_radius_m = 6378137.0;
  const CGrid a = build_cgrid(g, pr);
  const CGrid b = build_cgrid(g, pr, o);
  EXPECT_NEAR(a.pm[12] / b.pm[12], 6378137.0 / kR, 1e-12);
  EXPECT_NEAR(b.xl_m / a.xl_m, 6378137.0 / kR, 1e-12);
  EXPECT_NEAR(b.xy_metres_per_unit, 6378137.0 * 0.001, 1e-9);
}

TEST(CGrid, Wgs84GeodesicsDifferFromTheSphereByTheFlattening) {
  const Grid2D g = rectangle(6, 4, 60.0, 40.0);
  const Projection pr = mercator(60.0, 10.0, 0.0);
  CGridOptions o;
  o.distances = DistanceModel::kWgs84;
  const CGrid s = build_cgrid(g, pr);
  const CGrid w = build_cgrid(g, pr, o);
  for (std::size_t k = 0; k < s.pm.size(); ++k) {
    const double rel = std::fabs(w.pm[k] / s.pm[k] - 1.0);
    EXPECT_LT(rel, 0.01);                       // WGS84 vs a 6371 km sphere: within 1 %
    EXPECT_GT(rel, 1e-5);                       // but not the same model
    EXPECT_NEAR(w.angle[k], s.angle[k], 2e-3);  // geodetic vs spherical azimuths at 60°N
  }
  EXPECT_EQ(parse_name<DistanceModel>("wgs84"), DistanceModel::kWgs84);
  EXPECT_FALSE(parse_name<DistanceModel>("ellipsoid").has_value());
}

TEST(CGrid, AngleFollowsTheBearingOfXiLines) {
  // (a) Against bearings computed here at each interior ρ: the bisector of the initial bearing
  // from ρ towards u(i) and the reverse of the initial bearing from ρ towards u(i-1).
  const Projection pr = mercator(43.75, 34.5, 25.0);
  const CGrid c = build_cgrid(rectangle(16, 10, 150.0, 90.0), pr);
  double worst = 0.0;
  for (int j = 0; j <= c.M; ++j)
    for (int i = 1; i < c.L; ++i) {
      const std::size_t r = c.rho.at(i, j), a = c.u.at(i - 1, j), b = c.u.at(i, j);
      const double lo = c.rho.lon_deg[r], la = c.rho.lat_deg[r];
      const double t1 = initial_bearing(lo, la, c.u.lon_deg[b], c.u.lat_deg[b]);
      const double t2 = initial_bearing(lo, la, c.u.lon_deg[a], c.u.lat_deg[a]) + 3.141592653589793;
      const double expected = std::atan2(std::cos(t1) + std::cos(t2), std::sin(t1) + std::sin(t2));
      worst = std::max(worst, std::fabs(std::remainder(c.angle[r] - expected, 2.0 * 3.141592653589793)));
    }
  EXPECT_LT(worst, 1e-9);

  // (b) Against the true direction of the ξ line (+x of the plane) at every ρ point, boundary
  // included: the bearing between two points ±h around it on the line, h tiny. The library's
  // differences are second order: refining the grid twice divides the error by about 4.
  double err[2] = {0.0, 0.0};
  for (int refine = 0; refine < 2; ++refine) {
    const Grid2D g = rectangle(16 << refine, 10 << refine, 150.0, 90.0);
    const CGrid cr = build_cgrid(g, pr);
    const double h = 2e-3;  // 13 m: truncation ~1e-12, round-off ~1e-10
    for (int j = 0; j <= cr.M; ++j)
      for (int i = 0; i <= cr.L; ++i) {
        const std::size_t s = g.at(2 * i, 2 * j);
        const GeoPoint p0 = pr.inverse(g.x[s], g.y[s]);
        const GeoPoint pa = pr.inverse(g.x[s] - h, g.y[s]), pb = pr.inverse(g.x[s] + h, g.y[s]);
        const double t1 = initial_bearing(p0.lon_deg, p0.lat_deg, pb.lon_deg, pb.lat_deg);
        const double t2 = initial_bearing(p0.lon_deg, p0.lat_deg, pa.lon_deg, pa.lat_deg) + 3.141592653589793;
        const double truth = std::atan2(std::cos(t1) + std::cos(t2), std::sin(t1) + std::sin(t2));
        err[refine] = std::max(err[refine],
                               std::fabs(std::remainder(cr.angle[cr.rho.at(i, j)] - truth, 2.0 * 3.141592653589793)));
      }
  }
  EXPECT_LT(err[0], 1e-7);  // measured 1.9e-8 -> 2.3e-9
  EXPECT_LT(err[1], err[0] / 3.0) << err[0] << " -> " << err[1];
}

TEST(CGrid, AngleOfARotatedMercatorIsMinusRotaAtTheCentre) {
  // +y of the plane points at azimuth rota (clockwise from north), so ξ (+x) points at rota + 90°
  // and the angle from east, counter-clockwise, is −rota at the centre.
  for (const double rlat : {0.0, 43.75, -60.0}) {
    const Grid2D g = rectangle(10, 10, 100.0, 100.0);
    const CGrid c = build_cgrid(g, mercator(rlat, 34.5, 30.0));
    const std::size_t centre = c.rho.at(5, 5);
    EXPECT_NEAR(c.rho.lat_deg[centre], rlat, 1e-12);
    EXPECT_NEAR(c.angle[centre], -30.0 * kD2R, 1e-9) << "rlat " << rlat;
  }
  // Unrotated Mercator on the equator: ξ lines are parallels, the angle is 0 (to round-off inside,
  // to the one-sided difference's O(Δ²) on the boundary columns).
  const CGrid e = build_cgrid(rectangle(8, 6, 100.0, 60.0), mercator(0.0, 0.0, 0.0));
  for (int j = 0; j <= e.M; ++j)
    for (int i = 0; i <= e.L; ++i)
      EXPECT_NEAR(e.angle[e.rho.at(i, j)], 0.0, (i == 0 || i == e.L) ? 1e-7 : 1e-14) << i << "," << j;
}

TEST(CGrid, CoriolisIsTwoOmegaSinLatitude) {
  const CGrid c = build_cgrid(rectangle(6, 6, 200.0, 200.0), mercator(-20.0, 150.0, 10.0));
  for (std::size_t k = 0; k < c.f.size(); ++k)
    EXPECT_NEAR(c.f[k], 2.0 * 7.2921e-5 * std::sin(c.rho.lat_deg[k] * kD2R), 1e-19);
  EXPECT_LT(c.f[c.rho.at(3, 0)], c.f[c.rho.at(3, 6)]);  // southern hemisphere: more negative to the south
}

TEST(CGrid, DerivativesOfTheInverseMetricsAndDomainLengths) {
  const CGrid c = build_cgrid(rectangle(8, 6, 80.0, 60.0), mercator(0.0, 0.0, 0.0));
  // Along parallels on the equator-centred Mercator: 1/pn depends on latitude only, so dndx ≈ 0,
  // while dmde is the change of 1/pm per η step.
  const std::size_t k = c.rho.at(4, 2);
  EXPECT_NEAR(c.dndx[k], 0.0, 1e-6);
  EXPECT_NEAR(c.dmde[k], 0.5 * (1.0 / c.pm[c.rho.at(4, 3)] - 1.0 / c.pm[c.rho.at(4, 1)]), 1e-9);
  EXPECT_NEAR(c.dmde[c.rho.at(4, 0)], 1.0 / c.pm[c.rho.at(4, 1)] - 1.0 / c.pm[c.rho.at(4, 0)], 1e-9);
  // xl: mean ρ-row length; the rows are parallels, each R·cosφ·Δλ long (great-circle chords of a
  // parallel are shorter by ~(Δλ)² sin²φ/24: negligible here).
  double sum = 0.0;
  for (int j = 0; j <= c.M; ++j) {
    const double lat = c.rho.lat_deg[c.rho.at(0, j)];
    const double dl = c.rho.lon_deg[c.rho.at(c.L, j)] - c.rho.lon_deg[c.rho.at(0, j)];
    sum += kR * std::cos(lat * kD2R) * dl * kD2R;
  }
  EXPECT_NEAR(c.xl_m / (sum / (c.M + 1)), 1.0, 1e-7);
  EXPECT_NEAR(c.el_m, haversine(0.0, c.rho.lat_deg[c.rho.at(4, 0)], 0.0, c.rho.lat_deg[c.rho.at(4, c.M)]), 1e-3);
}

TEST(CGrid, BadInputIsRefused) {
  const Projection pr = mercator(43.75, 34.5, 0.0);
  EXPECT_THROW(build_cgrid(Grid2D(6, 5), pr), InputError);             // even size
  EXPECT_THROW(build_cgrid(rectangle(1, 3, 10, 10), pr), InputError);  // L = 1
  CGridOptions o;
  o.earth_radius_m = -1.0;
  EXPECT_THROW(build_cgrid(rectangle(3, 3, 10, 10), pr, o), InternalError);
  Grid2D same = rectangle(3, 3, 10, 10);
  same.x[same.at(1, 2)] = same.x[same.at(2, 2)];  // u and ρ coincide
  same.y[same.at(1, 2)] = same.y[same.at(2, 2)];
  EXPECT_THROW(build_cgrid(same, pr), NumericalError);
  Grid2D nan = rectangle(3, 3, 10, 10);
  nan.x[4] = std::nan("");
  EXPECT_THROW(build_cgrid(nan, pr), InputError);
  // A Mercator centre at a pole is refused by the projection, naming rlat.
  ProjectionParams pole;
  pole.rlat_deg = 90.0;
  try {
    const Projection bad(pole);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("rlat = 90"), std::string::npos) << e.what();
  }
}

TEST(CGrid, GreatCircleMatchesHaversine) {
  EXPECT_NEAR(great_circle_m(10.0, 20.0, 10.001, 20.002, kR) / haversine(10.0, 20.0, 10.001, 20.002), 1.0, 1e-12);
  EXPECT_NEAR(great_circle_m(0.0, 0.0, 180.0, 0.0, kR), kR * 3.141592653589793, 1e-6);
}

}  // namespace
}  // namespace aq::curvilinear::unit_curvilinear_cgrid_test

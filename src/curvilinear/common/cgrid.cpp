// SPDX-License-Identifier: GPL-3.0-or-later
// The C-grid of a ROMS grid file from the izogrid supergrid; conventions in cgrid.hpp (digest
// izogrid.md §9 [S], ROMS grd_spherical.cdl). Spherical distances use the atan2 form of the
// great-circle angle (Vincenty's special case of the sphere) written without cancellation, exact to
// round-off at every range; directions come from Earth-centred positions projected on the local
// east and north (Snyder 1987 for the sphere, GeographicLib Geocentric for WGS84).
#include "curvilinear/common/cgrid.hpp"

#include <fmt/format.h>
#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/types.hpp"

namespace aq::curvilinear {

namespace {

// Great-circle distance, differences first and the products written so that nothing cancels
// for short steps: cos p1 sin p2 − sin p1 cos p2 cos Δλ = sin Δφ + 2 sin p1 cos p2 sin²(Δλ/2),
// sin p1 sin p2 + cos p1 cos p2 cos Δλ = cos Δφ − 2 cos p1 cos p2 sin²(Δλ/2).
double sphere_distance(double lon1, double lat1, double lon2, double lat2, double radius) {
  const double p1 = lat1 * kDegToRad, p2 = lat2 * kDegToRad;
  const double dp = (lat2 - lat1) * kDegToRad, dl = (lon2 - lon1) * kDegToRad;
  const double c1 = std::cos(p1), s1 = std::sin(p1), c2 = std::cos(p2);
  const double hav = 2.0 * std::sin(0.5 * dl) * std::sin(0.5 * dl);  // 1 − cos Δλ
  const double a = c2 * std::sin(dl), b = std::sin(dp) + s1 * c2 * hav;
  return radius * std::atan2(std::hypot(a, b), std::cos(dp) - c1 * c2 * hav);
}

double wgs84_distance(double lon1, double lat1, double lon2, double lat2) {
  double s12 = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(lat1, lon1, lat2, lon2, s12);
  return s12;
}

}  // namespace

double great_circle_m(double lon1_deg, double lat1_deg, double lon2_deg, double lat2_deg, double radius_m) {
  return sphere_distance(lon1_deg, lat1_deg, lon2_deg, lat2_deg, radius_m);
}

CGrid build_cgrid(const Grid2D& g, const Projection& projection, const CGridOptions& options) {
  // roms.earth_radius_m is validated at load: a bad radius here is a bug.
  if (!(options.earth_radius_m > 0.0) || !std::isfinite(options.earth_radius_m))
    throw InternalError(fmt::format("build_cgrid: earth radius {} m", options.earth_radius_m));
  if (g.nx_pts < 5 || g.ny_pts < 5 || g.nx_pts % 2 == 0 || g.ny_pts % 2 == 0 || g.x.size() != g.at(0, g.ny_pts) ||
      g.y.size() != g.x.size())
    throw InputError(fmt::format(
        "ROMS C-grid: the supergrid is {} x {} points; it needs odd sizes 2L+1, 2M+1 with L, M >= 2 (nx, ny >= 2)",
        g.nx_pts, g.ny_pts));

  const int nI = g.nx_pts, nJ = g.ny_pts;
  const int L = (nI - 1) / 2, M = (nJ - 1) / 2;
  const std::size_t n = g.x.size();

  // Geographic coordinates of every supergrid point.
  std::vector<double> glon(n), glat(n);
  for (std::size_t k = 0; k < n; ++k) {
    const GeoPoint q = projection.inverse(g.x[k], g.y[k]);
    if (!std::isfinite(q.lon_deg) || !std::isfinite(q.lat_deg) || !std::isfinite(g.x[k]) || !std::isfinite(g.y[k])) {
      const auto i = static_cast<int>(k % static_cast<std::size_t>(nI)),
                 j = static_cast<int>(k / static_cast<std::size_t>(nI));
      throw InputError(
          fmt::format("ROMS C-grid: supergrid point ({}, {}) at plane ({}, {}) has no finite longitude/latitude", i, j,
                      g.x[k], g.y[k]));
    }
    glon[k] = q.lon_deg;
    glat[k] = q.lat_deg;
  }

  CGrid c;
  c.L = L;
  c.M = M;
  c.options = options;
  c.xy_metres_per_unit = projection.metres_per_unit(0.0, 0.0) * options.earth_radius_m / projection.params().radius_m;
  const double scale = c.xy_metres_per_unit;

  // Staggered families: family point (a, b) is supergrid point (2a + di, 2b + dj).
  const auto fill = [&](StaggeredPoints& s, int ni, int nj, int di, int dj) {
    s.ni = ni;
    s.nj = nj;
    s.lon_deg.resize(s.size());
    s.lat_deg.resize(s.size());
    s.x_m.resize(s.size());
    s.y_m.resize(s.size());
    for (int b = 0; b < nj; ++b)
      for (int a = 0; a < ni; ++a) {
        const std::size_t src = g.at(2 * a + di, 2 * b + dj), dst = s.at(a, b);
        s.lon_deg[dst] = glon[src];
        s.lat_deg[dst] = glat[src];
        s.x_m[dst] = g.x[src] * scale;
        s.y_m[dst] = g.y[src] * scale;
      }
  };
  fill(c.rho, L + 1, M + 1, 0, 0);
  fill(c.u, L, M + 1, 1, 0);
  fill(c.v, L + 1, M, 0, 1);
  fill(c.psi, L, M, 1, 1);

  const bool wgs84 = options.distances == DistanceModel::kWgs84;
  const double radius = options.earth_radius_m;
  const auto dist = [&](std::size_t a, std::size_t b) {
    return wgs84 ? wgs84_distance(glon[a], glat[a], glon[b], glat[b])
                 : sphere_distance(glon[a], glat[a], glon[b], glat[b], radius);
  };
  // Earth-centred positions (the sphere's, or WGS84's through GeographicLib) for the directions.
  std::vector<double> pos(3 * n);
  for (std::size_t k = 0; k < n; ++k) {
    double* q = &pos[3 * k];
    if (wgs84) {
      GeographicLib::Geocentric::WGS84().Forward(glat[k], glon[k], 0.0, q[0], q[1], q[2]);
    } else {
      const double p = glat[k] * kDegToRad, l = glon[k] * kDegToRad;
      q[0] = radius * std::cos(p) * std::cos(l);
      q[1] = radius * std::cos(p) * std::sin(l);
      q[2] = radius * std::sin(p);
    }
  }

  const std::size_t nr = c.rho.size();
  c.pm.assign(nr, 0.0);
  c.pn.assign(nr, 0.0);
  c.angle.assign(nr, 0.0);
  c.f.assign(nr, 0.0);
  std::vector<double> row_xi(static_cast<std::size_t>(M + 1), 0.0);  // ξ length of each ρ row
  std::vector<double> eta_half(nr, 0.0);  // per ρ point: its η half steps (undoubled), summed per column
  int zero_i = -1, zero_j = -1;

#pragma omp parallel for schedule(static) default(none) shared(c, g, glon, glat, pos, dist, row_xi, eta_half, L, M) \
    reduction(max                                                                                                   \
              : zero_i, zero_j)
  for (int j = 0; j <= M; ++j) {
    const int J = 2 * j;
    double line_xi = 0.0;
    for (int i = 0; i <= L; ++i) {
      const int I = 2 * i;
      const std::size_t k = c.rho.at(i, j), here = g.at(I, J);
      // ξ and η: the half steps on either side of ρ.
      const double west = i > 0 ? dist(g.at(I - 1, J), here) : 0.0;
      const double east = i < L ? dist(here, g.at(I + 1, J)) : 0.0;
      const double south = j > 0 ? dist(g.at(I, J - 1), here) : 0.0;
      const double north = j < M ? dist(here, g.at(I, J + 1)) : 0.0;
      if ((i > 0 && !(west > 0.0)) || (i < L && !(east > 0.0)) || (j > 0 && !(south > 0.0)) ||
          (j < M && !(north > 0.0))) {
        zero_i = std::max(zero_i, i);
        zero_j = std::max(zero_j, j);
      }
      line_xi += west + east;
      eta_half[k] = south + north;
      // On the contour the missing outer half step is extrapolated linearly from the two inner
      // ones (h_out = 2·h1 − h2, so the ρ step is 3·h1 − h2), but at least h1/2 (step ≥ 1.5·h1).
      double dx = west + east, dy = south + north;
      if (i == 0) dx = std::max(3.0 * east - dist(g.at(1, J), g.at(2, J)), 1.5 * east);
      if (i == L) dx = std::max(3.0 * west - dist(g.at(I - 2, J), g.at(I - 1, J)), 1.5 * west);
      if (j == 0) dy = std::max(3.0 * north - dist(g.at(I, 1), g.at(I, 2)), 1.5 * north);
      if (j == M) dy = std::max(3.0 * south - dist(g.at(I, J - 2), g.at(I, J - 1)), 1.5 * south);
      c.pm[k] = 1.0 / dx;
      c.pn[k] = 1.0 / dy;

      // Tangent of the ξ line at ρ: centred difference of the supergrid neighbours, one-sided
      // second order (−3, 4, −1) on the boundary; then its east and north components.
      double t[3];
      const auto P = [&](int ii) { return &pos[3 * g.at(ii, J)]; };
      for (int d = 0; d < 3; ++d) {
        if (i == 0) {
          t[d] = -3.0 * P(0)[d] + 4.0 * P(1)[d] - P(2)[d];
        } else if (i == L) {
          t[d] = 3.0 * P(2 * L)[d] - 4.0 * P(2 * L - 1)[d] + P(2 * L - 2)[d];
        } else {
          t[d] = P(I + 1)[d] - P(I - 1)[d];
        }
      }
      const double ph = glat[here] * kDegToRad, la = glon[here] * kDegToRad;
      const double te = -std::sin(la) * t[0] + std::cos(la) * t[1];
      const double tn = -std::sin(ph) * std::cos(la) * t[0] - std::sin(ph) * std::sin(la) * t[1] + std::cos(ph) * t[2];
      c.angle[k] = std::atan2(tn, te);
      c.f[k] = 2.0 * kEarthOmega * std::sin(ph);
    }
    row_xi[static_cast<std::size_t>(j)] = line_xi;
  }
  if (zero_i >= 0)
    throw NumericalError(fmt::format(
        "ROMS C-grid: neighbouring supergrid points coincide on the Earth near ρ ({}, {}); pm or pn would be infinite",
        zero_i, zero_j));

  std::vector<double> col_eta(static_cast<std::size_t>(L + 1), 0.0);
  for (int j = 0; j <= M; ++j)
    for (int i = 0; i <= L; ++i) col_eta[static_cast<std::size_t>(i)] += eta_half[c.rho.at(i, j)];
  double sx = 0.0, sy = 0.0;
  for (const double v : row_xi) sx += v;
  for (const double v : col_eta) sy += v;
  c.xl_m = sx / static_cast<double>(row_xi.size());
  c.el_m = sy / static_cast<double>(col_eta.size());

  // dndx = d(1/pn)/dξ, dmde = d(1/pm)/dη: centred inside, one-sided on the boundary.
  c.dndx.assign(nr, 0.0);
  c.dmde.assign(nr, 0.0);
  for (int j = 0; j <= M; ++j)
    for (int i = 0; i <= L; ++i) {
      const int ia = std::max(i - 1, 0), ib = std::min(i + 1, L);
      const int ja = std::max(j - 1, 0), jb = std::min(j + 1, M);
      const std::size_t k = c.rho.at(i, j);
      c.dndx[k] = (1.0 / c.pn[c.rho.at(ib, j)] - 1.0 / c.pn[c.rho.at(ia, j)]) / static_cast<double>(ib - ia);
      c.dmde[k] = (1.0 / c.pm[c.rho.at(i, jb)] - 1.0 / c.pm[c.rho.at(i, ja)]) / static_cast<double>(jb - ja);
    }
  return c;
}

void rho_cell_corners(const CGrid& g, std::vector<double>& lon_deg, std::vector<double>& lat_deg) {
  const int na = g.L + 2, nb = g.M + 2;  // corners; ψ is L × M
  const auto at = [na](int a, int b) {
    return static_cast<std::size_t>(b) * static_cast<std::size_t>(na) + static_cast<std::size_t>(a);
  };
  lon_deg.assign(static_cast<std::size_t>(na) * static_cast<std::size_t>(nb), 0.0);
  lat_deg.assign(lon_deg.size(), 0.0);
  for (auto* pair : {&lon_deg, &lat_deg}) {
    std::vector<double>& c = *pair;
    const std::vector<double>& psi = pair == &lon_deg ? g.psi.lon_deg : g.psi.lat_deg;
    for (int b = 1; b < nb - 1; ++b) {
      for (int a = 1; a < na - 1; ++a) c[at(a, b)] = psi[g.psi.at(a - 1, b - 1)];
      c[at(0, b)] = 2.0 * c[at(1, b)] - c[at(2, b)];
      c[at(na - 1, b)] = 2.0 * c[at(na - 2, b)] - c[at(na - 3, b)];
    }
    for (int a = 0; a < na; ++a) {
      c[at(a, 0)] = 2.0 * c[at(a, 1)] - c[at(a, 2)];
      c[at(a, nb - 1)] = 2.0 * c[at(a, nb - 2)] - c[at(a, nb - 3)];
    }
  }
  for (double& v : lat_deg) v = std::clamp(v, -90.0, 90.0);
}

AreaJump max_area_jump(const CGrid& g) {
  AreaJump w;
  const int ni = g.L + 1, nj = g.M + 1;
  const auto area = [&](int i, int j) {
    const std::size_t k = g.rho.at(i, j);
    return 1.0 / (g.pm[k] * g.pn[k]);
  };
  for (int j = 1; j < nj - 1; ++j)
    for (int i = 1; i < ni - 1; ++i) {
      const auto jump = [&](int i2, int j2) {
        if (i2 < 1 || j2 < 1 || i2 > ni - 2 || j2 > nj - 2) return;
        const double a = area(i, j), b = area(i2, j2);
        const double r = std::max(a, b) / std::min(a, b);
        if (r > w.ratio) {
          w.ratio = r;
          w.i = i;
          w.j = j;
        }
      };
      jump(i + 1, j);
      jump(i, j + 1);
    }
  return w;
}

FinerThanRaster finer_than_raster(const CGrid& g, double dlon_deg, double dlat_deg, double radius_m) {
  constexpr double kRad = 3.14159265358979323846 / 180.0;
  const int ni = g.L + 1, nj = g.M + 1;
  FinerThanRaster f;
  for (int j = 1; j < nj - 1; ++j)
    for (int i = 1; i < ni - 1; ++i) {
      const std::size_t k = g.rho.at(i, j);
      ++f.interior;
      const double rx = dlon_deg * kRad * radius_m * std::cos(g.rho.lat_deg[k] * kRad), ry = dlat_deg * kRad * radius_m;
      const double dx = 1.0 / g.pm[k], dy = 1.0 / g.pn[k];
      const double ratio = std::min(rx / dx, ry / dy);  // > 1: the cell is finer than the raster both ways
      if (ratio > 1.0) {
        ++f.finer;
        if (ratio > f.worst) {
          f.worst = ratio;
          f.worst_k = k;
        }
      }
    }
  return f;
}

CGridStats cgrid_stats(const CGrid& g) {
  CGridStats s;
  s.pm_min = s.pn_min = s.angle_min = std::numeric_limits<double>::infinity();
  s.pm_max = s.pn_max = s.angle_max = -std::numeric_limits<double>::infinity();
  for (int j = 0; j <= g.M; ++j)
    for (int i = 0; i <= g.L; ++i) {
      const std::size_t k = g.rho.at(i, j);
      s.pm_min = std::min(s.pm_min, g.pm[k]);
      s.pm_max = std::max(s.pm_max, g.pm[k]);
      s.pn_min = std::min(s.pn_min, g.pn[k]);
      s.pn_max = std::max(s.pn_max, g.pn[k]);
      s.angle_min = std::min(s.angle_min, g.angle[k]);
      s.angle_max = std::max(s.angle_max, g.angle[k]);
      const double iso = std::fabs(g.pm[k] / g.pn[k] - 1.0);
      if (iso > s.isotropy_max) {
        s.isotropy_max = iso;
        s.isotropy_worst_i = i;
        s.isotropy_worst_j = j;
      }
      if (i > 0 && i < g.L && j > 0 && j < g.M) s.isotropy_max_interior = std::max(s.isotropy_max_interior, iso);
    }
  s.dx_min_m = 1.0 / std::max(s.pm_max, s.pn_max);
  s.dx_max_m = 1.0 / std::min(s.pm_min, s.pn_min);
  return s;
}

}  // namespace aq::curvilinear

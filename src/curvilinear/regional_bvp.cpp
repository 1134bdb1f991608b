// The bvp method of the regional pipeline; see regional_bvp.hpp.
#include "curvilinear/regional_bvp.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

#include "core/error.hpp"
#include "curvilinear/transfinite_interpolation.hpp"

namespace aq::curvilinear {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Plane <-> 3-D: the plane itself (z = 0) or the unit sphere through the projection.
struct Embedding {
  const Projection& projection;
  bool sphere;
  [[nodiscard]] Vec3 to3d(PlanePoint q) const {
    if (!sphere) return {q.x, q.y, 0.0};
    const GeoPoint g = projection.inverse(q.x, q.y);
    const double lon = g.lon_deg * kDeg, lat = g.lat_deg * kDeg;
    return {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)};
  }
  [[nodiscard]] PlanePoint to_plane(Vec3 p) const {
    if (!sphere) return {p.x, p.y};
    const double lon = std::atan2(p.y, p.x) / kDeg, lat = std::atan2(p.z, std::hypot(p.x, p.y)) / kDeg;
    const PlanePoint q = projection.forward(lon, lat);
    if (!std::isfinite(q.x) || !std::isfinite(q.y))
      throw InputError(fmt::format("bvp on the sphere: node at ({:.4f}, {:.4f}) lies where the {} projection is singular",
                                   lon, lat, projection_code(projection.params().kind)));
    return q;
  }
};

// Closest points on one side of the contour, started from the nearest of its reference nodes.
class SideProjector {
 public:
  SideProjector(const SplineContour& c, const BoundaryNodes& reference, Side side)
      : c_(c), side_(side), s_(side_parameters(c, reference, side)) {
    for (double s : s_) q_.push_back(c.point(s));
  }
  // Parameter of the point of the side closest to x.
  [[nodiscard]] double closest(PlanePoint x) const {
    std::size_t best = 0;
    double d_best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < q_.size(); ++k) {
      const double d = std::hypot(q_[k].x - x.x, q_[k].y - x.y);
      if (d < d_best) {
        d_best = d;
        best = k;
      }
    }
    const double lo = s_[best > 0 ? best - 1 : 0], hi = s_[std::min(best + 1, s_.size() - 1)];
    double s = s_[best];
    for (int it = 0; it < 20; ++it) {
      const PlanePoint p = c_.point(s), d1 = c_.side_derivative(side_, s, 1),
                       d2 = c_.side_derivative(side_, s, 2);
      const double f = d1.x * (p.x - x.x) + d1.y * (p.y - x.y);
      const double df = d2.x * (p.x - x.x) + d2.y * (p.y - x.y) + d1.x * d1.x + d1.y * d1.y;
      if (!(df > 0.0)) break;
      const double next = std::clamp(s - f / df, lo, hi);
      if (std::fabs(next - s) <= 1e-15 * std::max(1.0, std::fabs(s))) {
        s = next;
        break;
      }
      s = next;
    }
    return s;
  }

 private:
  const SplineContour& c_;
  Side side_;
  std::vector<double> s_;
  std::vector<PlanePoint> q_;
};

// Boundary node k (contour order along `side`, corners excluded) of an L × M grid: its (i, j).
std::array<int, 2> side_node(Side side, int k, int L, int M) {
  switch (side) {
    case Side::kSouth:
      return {k, 0};
    case Side::kEast:
      return {L - 1, k};
    case Side::kNorth:
      return {L - 1 - k, M - 1};
    default:
      return {0, M - 1 - k};
  }
}

constexpr std::array<Side, 4> kSides{Side::kSouth, Side::kEast, Side::kNorth, Side::kWest};

}  // namespace

RegionalBvp regional_bvp(const SplineContour& contour, const BoundaryNodes& uniform, const Projection& projection,
                         const RegionalParams& params) {
  const Embedding emb{projection, params.surface == RegionalSurface::kSphere};
  const int L0 = uniform.nx_pts, M0 = uniform.ny_pts;
  Grid2D boundary(L0, M0);
  set_grid_boundary(contour, uniform, boundary);
  std::vector<Vec3> south, east, north, west;
  for (int i = 0; i < L0; ++i) {
    south.push_back(emb.to3d({boundary.x[boundary.at(i, 0)], boundary.y[boundary.at(i, 0)]}));
    north.push_back(emb.to3d({boundary.x[boundary.at(i, M0 - 1)], boundary.y[boundary.at(i, M0 - 1)]}));
  }
  for (int j = 0; j < M0; ++j) {
    west.push_back(emb.to3d({boundary.x[boundary.at(0, j)], boundary.y[boundary.at(0, j)]}));
    east.push_back(emb.to3d({boundary.x[boundary.at(L0 - 1, j)], boundary.y[boundary.at(L0 - 1, j)]}));
  }
  SurfaceGrid reference = transfinite_interpolation(south, east, north, west);
  if (emb.sphere)
    for (Vec3& p : reference.p) p = (1.0 / norm(p)) * p;

  RegionalBvp out;
  // Grid size: ny kept, nx from the conformal modulus of a first solve (square cells).
  out.aspect_ratio = solve_theta_eta(reference).aspect_ratio();
  out.nx = params.nx;
  if (params.auto_nx || out.nx <= 0) out.nx = std::max(1, static_cast<int>(std::lround(params.ny * out.aspect_ratio)));
  const int L = 2 * out.nx + 1, M = 2 * params.ny + 1;

  const std::array<SideProjector, 4> sides{SideProjector(contour, uniform, Side::kSouth),
                                           SideProjector(contour, uniform, Side::kEast),
                                           SideProjector(contour, uniform, Side::kNorth),
                                           SideProjector(contour, uniform, Side::kWest)};
  BvpOptions o;
  o.theta_levels = graded_levels(L - 1, params.bvp_ratio_xi);
  o.eta_levels = graded_levels(M - 1, params.bvp_ratio_eta);
  o.interpolation = params.bvp_interpolation;
  o.max_iterations = params.bvp_iterations;
  o.min_iterations = std::min(2, params.bvp_iterations);
  o.project = [&](SurfaceGrid& g) {
    if (emb.sphere)
      for (Vec3& p : g.p) p = (1.0 / norm(p)) * p;
    for (std::size_t s = 0; s < 4; ++s) {
      const int n = s % 2 == 0 ? L : M;
      for (int k = 1; k + 1 < n; ++k) {
        const auto [i, j] = side_node(kSides[s], k, L, M);
        g(i, j) = emb.to3d(contour.point(sides[s].closest(emb.to_plane(g(i, j)))));
      }
    }
  };
  out.bvp = orthogonal_bvp(reference, o);

  // The plane grid and the boundary nodes' contour parameters.
  const SurfaceGrid& g = out.bvp.grid;
  out.grid = Grid2D(L, M);
  for (int j = 0; j < M; ++j)
    for (int i = 0; i < L; ++i) {
      const PlanePoint q = emb.to_plane(g(i, j));
      out.grid.x[out.grid.at(i, j)] = q.x;
      out.grid.y[out.grid.at(i, j)] = q.y;
    }
  out.nodes.nx_pts = L;
  out.nodes.ny_pts = M;
  out.nodes.s.assign(static_cast<std::size_t>(out.nodes.count()), 0.0);
  for (std::size_t s = 0; s < 4; ++s) {
    const int n = s % 2 == 0 ? L : M;
    std::vector<double> par(static_cast<std::size_t>(n));
    par.front() = contour.side_begin(kSides[s]);
    par.back() = contour.side_end(kSides[s]);
    for (int k = 1; k + 1 < n; ++k) {
      const auto [i, j] = side_node(kSides[s], k, L, M);
      par[static_cast<std::size_t>(k)] = sides[s].closest({out.grid.x[out.grid.at(i, j)], out.grid.y[out.grid.at(i, j)]});
    }
    set_side_parameters(out.nodes, kSides[s], par);
  }
  // Corners exactly at the contour's corners in the plane.
  for (const auto& [i, j, s] : {std::tuple{0, 0, contour.side_begin(Side::kSouth)},
                                std::tuple{L - 1, 0, contour.side_begin(Side::kEast)},
                                std::tuple{L - 1, M - 1, contour.side_begin(Side::kNorth)},
                                std::tuple{0, M - 1, contour.side_begin(Side::kWest)}}) {
    const PlanePoint q = contour.point(s);
    out.grid.x[out.grid.at(i, j)] = q.x;
    out.grid.y[out.grid.at(i, j)] = q.y;
  }
  return out;
}

}  // namespace aq::curvilinear

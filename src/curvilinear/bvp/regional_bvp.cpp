// SPDX-License-Identifier: GPL-3.0-or-later
// The bvp method of the regional pipeline; see regional_bvp.hpp.
#include "curvilinear/bvp/regional_bvp.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

#include "core/error.hpp"
#include "curvilinear/bvp/bvp_two_blocks.hpp"
#include "curvilinear/bvp/transfinite_interpolation.hpp"

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
      throw InputError(
          fmt::format("bvp on the sphere: node at ({:.4f}, {:.4f}) lies where the {} projection is singular", lon, lat,
                      std::string(name_of(projection.params().kind))));
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
      const PlanePoint p = c_.point(s), d1 = c_.side_derivative(side_, s, 1), d2 = c_.side_derivative(side_, s, 2);
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

// One block: its TFI reference grid (in 3-D), its side projectors and its size.
struct Block {
  const SplineContour& contour;
  const BoundaryNodes& uniform;
  SurfaceGrid reference;
  std::array<SideProjector, 4> sides;
  ThetaEta first;  // θ, η on the reference grid (gives the modulus; iteration 1 reuses it)
  double aspect_ratio = 0.0;
  int nx = 0;

  Block(const SplineContour& c, const BoundaryNodes& u, const Embedding& emb, int nx_fixed, bool auto_nx, int ny)
      : contour(c),
        uniform(u),
        sides{SideProjector(c, u, Side::kSouth), SideProjector(c, u, Side::kEast), SideProjector(c, u, Side::kNorth),
              SideProjector(c, u, Side::kWest)} {
    const int L0 = u.nx_pts, M0 = u.ny_pts;
    Grid2D boundary(L0, M0);
    set_grid_boundary(c, u, boundary);
    auto at = [&](int i, int j) { return emb.to3d({boundary.x[boundary.at(i, j)], boundary.y[boundary.at(i, j)]}); };
    std::vector<Vec3> south, east, north, west;
    for (int i = 0; i < L0; ++i) {
      south.push_back(at(i, 0));
      north.push_back(at(i, M0 - 1));
    }
    for (int j = 0; j < M0; ++j) {
      west.push_back(at(0, j));
      east.push_back(at(L0 - 1, j));
    }
    reference = transfinite_interpolation(south, east, north, west);
    if (emb.sphere)
      for (Vec3& p : reference.p) p = (1.0 / norm(p)) * p;
    // Grid size: ny kept, nx from the conformal modulus of a first solve (square cells).
    first = solve_theta_eta(reference);
    aspect_ratio = first.aspect_ratio();
    nx = nx_fixed;
    if (auto_nx || nx <= 0) nx = std::max(1, static_cast<int>(std::lround(ny * aspect_ratio)));
  }

  // Nodes back onto the sphere, boundary nodes back onto the contour (corners stay).
  [[nodiscard]] std::function<void(SurfaceGrid&)> projector(const Embedding& emb) const {
    return [this, &emb](SurfaceGrid& g) {
      if (emb.sphere)
        for (Vec3& p : g.p) p = (1.0 / norm(p)) * p;
      for (std::size_t s = 0; s < 4; ++s) {
        const int n = s % 2 == 0 ? g.nx_pts : g.ny_pts;
        for (int k = 1; k + 1 < n; ++k) {
          const auto [i, j] = side_node(kSides[s], k, g.nx_pts, g.ny_pts);
          g(i, j) = emb.to3d(contour.point(sides[s].closest(emb.to_plane(g(i, j)))));
        }
      }
    };
  }

  // The grid in the plane (corners exactly at the contour's) and its boundary nodes' parameters.
  void to_plane(const Embedding& emb, const SurfaceGrid& g, Grid2D& grid, BoundaryNodes& nodes) const {
    const int L = g.nx_pts, M = g.ny_pts;
    grid = Grid2D(L, M);
    for (int j = 0; j < M; ++j)
      for (int i = 0; i < L; ++i) {
        const PlanePoint q = emb.to_plane(g(i, j));
        grid.x[grid.at(i, j)] = q.x;
        grid.y[grid.at(i, j)] = q.y;
      }
    nodes.nx_pts = L;
    nodes.ny_pts = M;
    nodes.s.assign(static_cast<std::size_t>(nodes.count()), 0.0);
    for (std::size_t s = 0; s < 4; ++s) {
      const int n = s % 2 == 0 ? L : M;
      std::vector<double> par(static_cast<std::size_t>(n));
      par.front() = contour.side_begin(kSides[s]);
      par.back() = contour.side_end(kSides[s]);
      for (int k = 1; k + 1 < n; ++k) {
        const auto [i, j] = side_node(kSides[s], k, L, M);
        par[static_cast<std::size_t>(k)] = sides[s].closest({grid.x[grid.at(i, j)], grid.y[grid.at(i, j)]});
      }
      set_side_parameters(nodes, kSides[s], par);
    }
    for (const auto& [i, j, side] : {std::tuple{0, 0, Side::kSouth}, std::tuple{L - 1, 0, Side::kEast},
                                     std::tuple{L - 1, M - 1, Side::kNorth}, std::tuple{0, M - 1, Side::kWest}}) {
      const PlanePoint q = contour.point(contour.side_begin(side));
      grid.x[grid.at(i, j)] = q.x;
      grid.y[grid.at(i, j)] = q.y;
    }
  }
};

}  // namespace

RegionalBvp regional_bvp(const SplineContour& contour, const BoundaryNodes& uniform, const Projection& projection,
                         const RegionalParams& params, const SplineContour* contour2, const BoundaryNodes* uniform2) {
  const Embedding emb{projection, params.surface == RegionalSurface::kSphere};
  const Block a(contour, uniform, emb, params.nx, params.auto_nx, params.ny);
  RegionalBvp out;
  out.aspect_ratio = a.aspect_ratio;
  out.nx = a.nx;
  const int M = 2 * params.ny + 1;
  BvpOptions o;
  o.theta_levels = graded_levels(2 * a.nx, params.bvp_ratio_xi);
  o.eta_levels = graded_levels(M - 1, params.bvp_ratio_eta);
  o.interpolation = params.bvp_interpolation;
  o.max_iterations = params.bvp_iterations;
  o.min_iterations = std::min(2, params.bvp_iterations);
  o.project = a.projector(emb);
  if (contour2 == nullptr || uniform2 == nullptr) {
    out.bvp = orthogonal_bvp(a.reference, o, &a.first);
    a.to_plane(emb, out.bvp.grid, out.grid, out.nodes);
    return out;
  }
  // Two blocks, merged into one supergrid: A's columns 0..LA−1, then B's 1..LB−1.
  const Block b(*contour2, *uniform2, emb, params.nx2, params.nx2 <= 0, params.ny);
  const TwoBlockResult t =
      orthogonal_bvp_two_blocks(a.reference, b.reference, o, graded_levels(2 * b.nx), b.projector(emb));
  Grid2D ga, gb;
  BoundaryNodes nb;
  a.to_plane(emb, t.a, ga, out.nodes);
  b.to_plane(emb, t.b, gb, nb);
  const int la = ga.nx_pts, lb = gb.nx_pts;
  out.grid = Grid2D(la + lb - 1, M);
  for (int j = 0; j < M; ++j) {
    for (int i = 0; i < la; ++i) {
      out.grid.x[out.grid.at(i, j)] = ga.x[ga.at(i, j)];
      out.grid.y[out.grid.at(i, j)] = ga.y[ga.at(i, j)];
    }
    for (int i = 1; i < lb; ++i) {
      out.grid.x[out.grid.at(la - 1 + i, j)] = gb.x[gb.at(i, j)];
      out.grid.y[out.grid.at(la - 1 + i, j)] = gb.y[gb.at(i, j)];
    }
  }
  out.nx = a.nx + b.nx;
  out.aspect_ratio = a.aspect_ratio + b.aspect_ratio;  // W/H add along ξ for blocks side by side
  out.bvp.f_max = t.f_max;
  out.bvp.f_avg = t.f_avg;
  out.bvp.iterations = t.iterations;
  out.bvp.best_iteration = t.iterations;
  out.interface_kink = t.max_kink;
  return out;
}

}  // namespace aq::curvilinear

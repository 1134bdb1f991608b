// SPDX-License-Identifier: GPL-3.0-or-later
// Nesting data in the global mesh (see nesting.hpp).
#include "handoff/nesting.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace aq::handoff {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Twice the area of a triangle of the mesh in pixel² (exact integers in doubles).
double twice_area_px2(const mesh::Mesh& m, const std::array<NodeId, 3>& t) {
  double X[3], Y[3];
  for (std::size_t q = 0; q < 3; ++q) {
    X[q] = static_cast<double>(m.unwrapped_i(t, t[q]));
    Y[q] = static_cast<double>(m.node_j[static_cast<std::size_t>(t[q])]);
  }
  return std::abs((X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]));
}

// Regional cell size √(1/(pm·pn)) at ρ (i, j).
double rho_cell_m(const curvilinear::CGrid& g, int i, int j) {
  const std::size_t k = g.rho.at(i, j);
  return std::sqrt(1.0 / (g.pm[k] * g.pn[k]));
}

}  // namespace

std::array<int, 2> supergrid_index(CPointType type, int xi, int eta) {
  switch (type) {
    case CPointType::kRho:
      return {2 * xi, 2 * eta};
    case CPointType::kU:
      return {2 * xi + 1, 2 * eta};
    default:
      return {2 * xi, 2 * eta + 1};
  }
}

std::vector<BoundaryPoint> boundary_points(int L, int M) {
  std::vector<BoundaryPoint> out;
  const auto add = [&](CPointType type, RomsBoundary b, int xi, int eta) {
    BoundaryPoint p;
    p.type = type;
    p.boundary = b;
    p.xi = xi;
    p.eta = eta;
    const auto s = supergrid_index(type, xi, eta);
    p.si = s[0];
    p.sj = s[1];
    out.push_back(p);
  };
  using T = CPointType;
  using B = RomsBoundary;
  for (int j = 0; j <= M; ++j) add(T::kRho, B::kWest, 0, j);
  for (int j = 0; j <= M; ++j) add(T::kU, B::kWest, 0, j);
  for (int l = 0; l < M; ++l) add(T::kV, B::kWest, 0, l);
  for (int i = 0; i <= L; ++i) add(T::kRho, B::kSouth, i, 0);
  for (int k = 0; k < L; ++k) add(T::kU, B::kSouth, k, 0);
  for (int i = 0; i <= L; ++i) add(T::kV, B::kSouth, i, 0);
  for (int j = 0; j <= M; ++j) add(T::kRho, B::kEast, L, j);
  for (int j = 0; j <= M; ++j) add(T::kU, B::kEast, L - 1, j);
  for (int l = 0; l < M; ++l) add(T::kV, B::kEast, L, l);
  for (int i = 0; i <= L; ++i) add(T::kRho, B::kNorth, i, M);
  for (int k = 0; k < L; ++k) add(T::kU, B::kNorth, k, M);
  for (int i = 0; i <= L; ++i) add(T::kV, B::kNorth, i, M - 1);
  return out;
}

io::NestingFile global_nesting(const curvilinear::Grid2D& g, const curvilinear::CGrid& cg, const mesh::Mesh& mesh,
                               NestingSummary* summary) {
  if (g.nx_pts != 2 * cg.L + 1 || g.ny_pts != 2 * cg.M + 1 || cg.pm.size() != cg.rho.size()) {
    throw InternalError(fmt::format("global_nesting: a {} x {} supergrid with a C-grid of L = {}, M = {}", g.nx_pts,
                                    g.ny_pts, cg.L, cg.M));
  }
  const MeshLocator locator(mesh);
  const auto points = boundary_points(cg.L, cg.M);
  const Lattice& lat = mesh.lattice;
  const double pixel_rad = lat.pixel_deg() * kDegToRad;
  const double radius = cg.options.earth_radius_m;

  io::NestingFile f;
  const std::size_t n = points.size();
  f.point_type.resize(n);
  f.boundary.resize(n);
  f.element_level.resize(n);
  f.xi_index.resize(n);
  f.eta_index.resize(n);
  f.lon.resize(n);
  f.lat.resize(n);
  f.x.resize(n);
  f.y.resize(n);
  f.element.resize(n);
  f.element_nodes.resize(n);
  f.weights.resize(n);
  f.global_element_size_m.resize(n);
  f.regional_cell_size_m.resize(n);
  f.refinement_ratio.resize(n);
  std::vector<double> ratios;
  std::int64_t outside = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const BoundaryPoint& p = points[k];
    const curvilinear::StaggeredPoints& sp =
        p.type == CPointType::kRho ? cg.rho : (p.type == CPointType::kU ? cg.u : cg.v);
    const std::size_t a = sp.at(p.xi, p.eta);
    f.point_type[k] = static_cast<std::int8_t>(p.type);
    f.boundary[k] = static_cast<std::int8_t>(p.boundary);
    f.xi_index[k] = p.xi;
    f.eta_index[k] = p.eta;
    f.lon[k] = sp.lon_deg[a];
    f.lat[k] = sp.lat_deg[a];
    const std::size_t s = g.at(p.si, p.sj);
    f.x[k] = g.x[s];
    f.y[k] = g.y[s];
    double cell = 0.0;
    switch (p.type) {
      case CPointType::kRho:
        cell = rho_cell_m(cg, p.xi, p.eta);
        break;
      case CPointType::kU:
        cell = 0.5 * (rho_cell_m(cg, p.xi, p.eta) + rho_cell_m(cg, p.xi + 1, p.eta));
        break;
      default:
        cell = 0.5 * (rho_cell_m(cg, p.xi, p.eta) + rho_cell_m(cg, p.xi, p.eta + 1));
        break;
    }
    f.regional_cell_size_m[k] = cell;
    const MeshLocation loc = locator.locate_geographic(f.lon[k], f.lat[k]);
    if (!loc.inside()) {
      ++outside;
      f.element[k] = -1;
      f.element_nodes[k] = {-1, -1, -1};
      f.weights[k] = {0.0, 0.0, 0.0};
      f.element_level[k] = -1;
      f.global_element_size_m[k] = kNaN;
      f.refinement_ratio[k] = kNaN;
      continue;
    }
    f.element[k] = loc.triangle;
    f.element_nodes[k] = loc.nodes;
    f.weights[k] = loc.weights;
    f.element_level[k] = static_cast<std::int8_t>(loc.level);
    const double leg_px = std::sqrt(twice_area_px2(mesh, loc.nodes));
    const double size = leg_px * pixel_rad * radius * lat.size_scale(loc.lattice_row);
    f.global_element_size_m[k] = size;
    f.refinement_ratio[k] = size / cell;
    ratios.push_back(size / cell);
  }

  NestingSummary sum;
  sum.points = static_cast<std::int64_t>(n);
  sum.outside = outside;
  if (ratios.empty()) {
    sum.ratio_median = sum.ratio_min = sum.ratio_max = kNaN;
  } else {
    std::sort(ratios.begin(), ratios.end());
    sum.ratio_median = ratios[(ratios.size() - 1) / 2];
    sum.ratio_min = ratios.front();
    sum.ratio_max = ratios.back();
  }
  if (summary != nullptr) *summary = sum;

  f.attributes.emplace_back("staggering",
                            "rho(i,j) = G[2i][2j] on the contour, u(k,j) = G[2k+1][2j], v(i,l) = G[2i][2l+1] "
                            "(supergrid G; aquatoria curvilinear/cgrid.hpp)");
  f.attributes.emplace_back("weights_plane",
                            lat.mercator()
                                ? "global lattice plane: lon and the Mercator ordinate y = ln tan(pi/4 + lat/2) "
                                  "(rotated lon/lat when the pole is rotated), lon unwrapped to the element: value = "
                                  "sum of weights * node values"
                                : "global lattice plane (rotated lon/lat when the pole is rotated), lon unwrapped to "
                                  "the element: value = sum of weights * node values");
  f.attributes.emplace_back("points_total", sum.points);
  f.attributes.emplace_back("points_outside", sum.outside);
  f.attributes.emplace_back("refinement_ratio", sum.ratio_median);
  f.attributes.emplace_back("refinement_ratio_min", sum.ratio_min);
  f.attributes.emplace_back("refinement_ratio_max", sum.ratio_max);
  f.attributes.emplace_back("global_mesh_nodes", mesh.node_count());
  f.attributes.emplace_back("global_mesh_triangles", mesh.triangle_count());
  f.attributes.emplace_back("lattice_kind", std::string(lat.kind_name()));
  f.attributes.emplace_back("lattice_step0_deg", lat.step0_deg);
  f.attributes.emplace_back("lattice_levels", static_cast<std::int64_t>(lat.levels));
  f.attributes.emplace_back("lattice_lon0_deg", lat.lon0_deg);
  if (lat.mercator()) f.attributes.emplace_back("lattice_y0_deg", lat.y0_deg);
  if (mesh.rotation.enabled) {
    f.attributes.emplace_back("pole_lon_deg", mesh.rotation.pole_lon_deg);
    f.attributes.emplace_back("pole_lat_deg", mesh.rotation.pole_lat_deg);
  }
  return f;
}

}  // namespace aq::handoff

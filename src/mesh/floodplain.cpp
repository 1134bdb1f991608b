// SPDX-License-Identifier: GPL-3.0-or-later
// The floodplain of a surge mesh (see floodplain.hpp).
#include "mesh/floodplain.hpp"

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/Math.hpp>
#include <GeographicLib/PolygonArea.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace aq::mesh {

namespace {

// WGS84 area (m², unsigned) of a polygon of up to 4 (lon, lat) vertices.
double lonlat_polygon_area_m2(const std::array<std::array<double, 2>, 4>& p, int n) {
  GeographicLib::PolygonArea poly(GeographicLib::Geodesic::WGS84());
  for (int v = 0; v < n; ++v) poly.AddPoint(p[static_cast<std::size_t>(v)][1], p[static_cast<std::size_t>(v)][0]);
  double perimeter = 0.0, area = 0.0;
  poly.Compute(false, false, perimeter, area);
  return area;
}

// The area (m²) of triangle t where the linear surface of its node elevations is above 0 m.
double area_above_datum_m2(const Mesh& m, const std::array<NodeId, 3>& t) {
  std::array<double, 3> z{}, lon{}, lat{};
  int above = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const auto n = static_cast<std::size_t>(t[k]);
    z[k] = m.depth_m[n];
    lat[k] = m.lat_deg[n];
    // Longitudes unwrapped against the first node (a triangle across the seam).
    lon[k] = k == 0 ? m.lon_deg[n]
                    : lon[0] + GeographicLib::Math::AngDiff(m.lon_deg[static_cast<std::size_t>(t[0])], m.lon_deg[n]);
    above += z[k] > 0.0 ? 1 : 0;
  }
  if (above == 0 || !std::isfinite(z[0] + z[1] + z[2])) return 0.0;
  std::array<std::array<double, 2>, 4> p{};
  const auto node = [&](std::size_t k) { return std::array<double, 2>{lon[k], lat[k]}; };
  const auto cut = [&](std::size_t a, std::size_t b) {  // the 0 m point on edge a-b (z[a], z[b] of opposite sides)
    const double s = z[a] / (z[a] - z[b]);
    return std::array<double, 2>{lon[a] + s * (lon[b] - lon[a]), lat[a] + s * (lat[b] - lat[a])};
  };
  if (above == 3) {
    p = {node(0), node(1), node(2), {}};
    return lonlat_polygon_area_m2(p, 3);
  }
  // The corner alone on its side of the datum: k (above == 1: the node above; 2: the one at or below).
  std::size_t k = 0;
  for (std::size_t a = 0; a < 3; ++a)
    if ((z[a] > 0.0) == (above == 1)) k = a;
  const std::size_t a = (k + 1) % 3, b = (k + 2) % 3;
  if (above == 1) {
    p = {node(k), cut(k, a), cut(k, b), {}};
    return lonlat_polygon_area_m2(p, 3);
  }
  p = {cut(k, a), node(a), node(b), cut(k, b)};
  return lonlat_polygon_area_m2(p, 4);
}

}  // namespace

Floodplain floodplain(const Mesh& mesh, double top_m) {
  Floodplain f;
  f.top_m = top_m;
  const auto nn = mesh.depth_m.size();
  f.highest_node_m = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < nn; ++k) {
    if (mesh.depth_m[k] > 0.0) ++f.nodes;
    if (std::isfinite(mesh.depth_m[k])) f.highest_node_m = std::max(f.highest_node_m, mesh.depth_m[k]);
  }
  std::vector<std::uint8_t> land(nn, 0);
  for (std::size_t e = 0; e < mesh.boundary_edges.size(); ++e) {
    if (mesh.typed && e < mesh.boundary_edge_type.size() && mesh.boundary_edge_type[e] == BoundaryType::kOpen) continue;
    for (const NodeId n : mesh.boundary_edges[e]) land[static_cast<std::size_t>(n)] = 1;
  }
  for (std::size_t k = 0; k < nn; ++k) {
    f.land_boundary_nodes += land[k];
    if (land[k] != 0 && mesh.depth_m[k] > 0.0) ++f.land_boundary_nodes_above;
  }
  const auto nt = static_cast<std::int64_t>(mesh.triangles.size());
  std::vector<double> area(static_cast<std::size_t>(nt), 0.0);
#pragma omp parallel for default(none) shared(mesh, area, nt) schedule(dynamic, 4096)
  for (std::int64_t t = 0; t < nt; ++t)
    area[static_cast<std::size_t>(t)] = area_above_datum_m2(mesh, mesh.triangles[static_cast<std::size_t>(t)]);
  double sum = 0.0;
  for (std::int64_t t = 0; t < nt; ++t) {
    const auto& tri = mesh.triangles[static_cast<std::size_t>(t)];
    bool any = false;
    for (const NodeId n : tri) any = any || mesh.depth_m[static_cast<std::size_t>(n)] > 0.0;
    f.triangles += any ? 1 : 0;
    sum += area[static_cast<std::size_t>(t)];
  }
  f.area_km2 = sum / 1e6;
  if (!std::isfinite(f.highest_node_m)) f.highest_node_m = 0.0;
  return f;
}

Json floodplain_json(const Floodplain& f) {
  return Json{{"top_m", f.top_m},
              {"nodes", f.nodes},
              {"triangles", f.triangles},
              {"area_km2", std::round(f.area_km2 * 1000.0) / 1000.0},
              {"highest_node_m", f.highest_node_m},
              {"land_boundary_nodes", f.land_boundary_nodes},
              {"land_boundary_nodes_above_datum", f.land_boundary_nodes_above},
              {"definition",
               "nodes above the datum (elevation > 0; dry at rest); area (WGS84) where the linear "
               "surface of node elevations over each triangle is above 0 m"}};
}

}  // namespace aq::mesh

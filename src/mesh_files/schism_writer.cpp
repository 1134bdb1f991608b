// SPDX-License-Identifier: GPL-3.0-or-later
// SCHISM hgrid.gr3 / hgrid.ll (see schism_writer.hpp): the fort.14 layout with SCHISM's names.
#include "mesh_files/schism_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/error.hpp"
#include "io/file_writer.hpp"
#include "mesh_files/fort14_writer.hpp"
#include "mesh_files/geographic_mesh.hpp"

namespace aq::io {

Fort14Options schism_hgrid_layout(const SchismOptions& options) {
  Fort14Options o;
  o.title = options.title;
  o.land_count_name = "NLAND";
  o.mainland_type = 0;  // SCHISM's land flag: 0 land, 1 island
  o.island_type = 1;
  o.rivers_open = true;  // SCHISM: a river is an open (flow) boundary; bctides.in sets its ifltype
  return o;
}

WriteStats write_schism_hgrid(const mesh::Mesh& mesh, const std::filesystem::path& path, const SchismOptions& options) {
  return write_fort14(mesh, path, schism_hgrid_layout(options));
}

WriteStats write_schism_bctides(const mesh::Mesh& mesh, const std::filesystem::path& path, const std::string& title) {
  std::int64_t nope = 0, neta = 0;
  for (const auto& s : mesh.segments)
    if (s.type == mesh::BoundaryType::kOpen || s.type == mesh::BoundaryType::kRiver) {
      ++nope;
      neta += static_cast<std::int64_t>(s.nodes.size());
    }
  if (!mesh.typed || nope == 0) throw InternalError("bctides.in: the mesh has no open boundary");
  FileWriter f(path);
  f.print("{} (skeleton: M2 on the open boundaries, amplitudes and phases 0)\n", title.substr(0, 80));
  f.print("0 0. !ntip: # of tidal-potential constituents (none); tip_dp\n");
  f.print("1 !nbfr: # of tidal boundary forcing frequencies\nM2\n");
  f.print("1.405189025e-4 1. 0. !frequency [rad/s], nodal factor, equilibrium argument [deg]\n");
  f.print("{} !nope: # of open boundaries\n", nope);
  std::int64_t k = 0;
  for (const auto& s : mesh.segments) {
    if (s.type == mesh::BoundaryType::kRiver) {  // in hgrid.gr3's order: the open list holds both
      f.print(
          "{} 0 2 0 0 !open boundary {}: # of nodes, iettype 0, ifltype 2 (river inflow: constant discharge), "
          "T and S none\n0. !discharge [m^3/s], negative into the domain: set the river's flow\n",
          s.nodes.size(), ++k);
      continue;
    }
    if (s.type != mesh::BoundaryType::kOpen) continue;
    f.print("{} 3 0 0 0 !open boundary {}: # of nodes, iettype 3 (tidal elevation), ifltype 0, T and S none\nM2\n",
            s.nodes.size(), ++k);
    for (std::size_t n = 0; n < s.nodes.size(); ++n) f.print("0. 0. !node {}\n", s.nodes[n] + 1);
  }
  WriteStats stats;
  stats.bytes = f.close();
  stats.nodes = neta;
  stats.boundary_edges = nope;
  return stats;
}

SchismTimeStep schism_time_step(const mesh::Mesh& m) {
  constexpr double kG = 9.81, kRadiusM = 6371007.2, kInverseCfl = 0.4;
  const auto nn = static_cast<std::size_t>(m.node_count());
  std::vector<double> dx(nn, std::numeric_limits<double>::infinity());
  for (const auto& t : m.triangles) {
    for (std::size_t k = 0; k < 3; ++k) {
      const auto a = static_cast<std::size_t>(t[k]), b = static_cast<std::size_t>(t[(k + 1) % 3]);
      const auto pa = unit_vector_deg(m.lon_deg[a], m.lat_deg[a]), pb = unit_vector_deg(m.lon_deg[b], m.lat_deg[b]);
      const double chord = std::sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                                     (pa[2] - pb[2]) * (pa[2] - pb[2]));
      const double len = 2.0 * std::asin(std::min(1.0, 0.5 * chord)) * kRadiusM;
      dx[a] = std::min(dx[a], len);
      dx[b] = std::min(dx[b], len);
    }
  }
  std::vector<double> need;  // Δt for C = 0.4 at each wet node
  for (std::size_t n = 0; n < nn; ++n) {
    const double h = -m.depth_m[n];
    if (h > 0.0 && std::isfinite(dx[n])) need.push_back(kInverseCfl * dx[n] / std::sqrt(kG * h));
  }
  SchismTimeStep s;
  s.wet_nodes = static_cast<std::int64_t>(need.size());
  if (need.empty()) return s;
  std::sort(need.begin(), need.end());
  auto at = [&](double q) {
    return need[static_cast<std::size_t>(std::ceil(q * static_cast<double>(need.size() - 1)))];
  };
  s.dt_half_s = at(0.5);
  s.dt_p95_s = at(0.95);
  s.dt_all_s = need.back();
  return s;
}

std::string SchismTimeStep::describe() const {
  auto range = [](double lo) {
    return lo <= kMaxDtS ? fmt::format("{:.0f}-{:.0f} s", std::ceil(lo), kMaxDtS)
                         : fmt::format("none (it needs {:.0f} s, above {:.0f} s)", std::ceil(lo), kMaxDtS);
  };
  return fmt::format(
      "SCHISM time step: advection off (nadv = 0) {}, advection on (nadv = 1) {} (√(gH)·Δt/Δx ≥ 0.4 at half / 95% "
      "of the {} wet nodes, {:.0f} s at all; upper bound 1/50 of the M2 period){}",
      range(dt_half_s), range(dt_p95_s), wet_nodes, std::ceil(dt_all_s),
      dt_p95_s > kMaxDtS ? ": keep advection off or refine the shallow coast" : "");
}

}  // namespace aq::io

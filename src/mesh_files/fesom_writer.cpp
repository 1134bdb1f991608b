// SPDX-License-Identifier: GPL-3.0-or-later
// FESOM2 nod2d.out, elem2d.out, aux3d.out (see fesom_writer.hpp).
#include "mesh_files/fesom_writer.hpp"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "core/error.hpp"
#include "core/types.hpp"
#include "io/file_writer.hpp"
#include "mesh_files/element_kinds.hpp"
#include "mesh_files/model_columns.hpp"

namespace aq::io {

namespace {

void check_triangles(const mesh::Mesh& mesh, const std::filesystem::path& path) {
  check_elements(mesh, ElementKinds::kTriangles);
  if (mesh.triangles.empty())
    throw InternalError(fmt::format("FESOM writer: the mesh has no triangles ({})", path.string()));
}

// -x without printing "-0".
double negated(double x) { return 0.0 - x; }

}  // namespace

const std::vector<double>& default_fesom_levels_m() {
  static const std::vector<double> levels{0,    5,    10,   20,   30,   40,   50,   60,   70,   80,   90,   100,
                                          115,  135,  160,  190,  230,  280,  340,  410,  490,  580,  680,  790,
                                          910,  1040, 1180, 1330, 1500, 1700, 1920, 2150, 2400, 2650, 2900, 3150,
                                          3400, 3650, 3900, 4150, 4400, 4650, 4900, 5150, 5400, 5650, 6000, 6250};
  return levels;
}

FesomRotation fesom_rotation(const mesh::RotationInfo& r) {
  FesomRotation f;
  f.force_rotation = true;
  if (!r.enabled) {
    // FESOM's standard frame for geographic meshes (its namelist.config): the model pole on
    // Greenland, on land, away from the pole cap's island.
    f.alpha_deg = 50.0;
    f.beta_deg = 15.0;
    f.gamma_deg = -90.0;
    return f;
  }
  // Our rotated -> geographic matrix is R = Rz(λp)·Ry(90° − φp) (core/rotation.cpp); FESOM's
  // geographic -> rotated matrix for (α, β, γ) equals Rᵀ for α = λp + 90°, β = 90° − φp,
  // γ = −90° (the entries agree one by one; tests/unit/mesh_files/fesom_schism_writer_test.cpp
  // checks it against FESOM's formula).
  double alpha = std::fmod(r.pole_lon_deg + 90.0, 360.0);
  if (alpha > 180.0) alpha -= 360.0;
  if (alpha <= -180.0) alpha += 360.0;
  f.alpha_deg = alpha;
  f.beta_deg = 90.0 - r.pole_lat_deg;
  f.gamma_deg = -90.0;
  return f;
}

std::string FesomRotation::namelist() const {
  return fmt::format("force_rotation = {}, alphaEuler = {:.10g}, betaEuler = {:.10g}, gammaEuler = {:.10g}",
                     force_rotation ? ".true." : ".false.", alpha_deg, beta_deg, gamma_deg);
}

std::vector<std::uint8_t> fesom_boundary_flags(const mesh::Mesh& mesh) {
  std::vector<std::uint8_t> boundary(static_cast<std::size_t>(mesh.node_count()), 0);
  for (const auto& e : mesh.boundary_edges) {
    boundary[static_cast<std::size_t>(e[0])] = 1;
    boundary[static_cast<std::size_t>(e[1])] = 1;
  }
  return boundary;
}

std::vector<NodeId> fesom_open_boundary_nodes(const mesh::Mesh& mesh) {
  std::vector<NodeId> nodes;
  std::vector<char> seen(static_cast<std::size_t>(mesh.node_count()), 0);
  for (const auto& s : mesh.segments) {
    if (s.type != mesh::BoundaryType::kOpen) continue;
    for (const NodeId n : s.nodes) {
      if (seen[static_cast<std::size_t>(n)] != 0) continue;
      seen[static_cast<std::size_t>(n)] = 1;
      nodes.push_back(n);
    }
  }
  return nodes;
}

WriteStats write_fesom_nod2d(const mesh::Mesh& mesh, const std::filesystem::path& path) {
  check_triangles(mesh, path);
  const std::int64_t np = mesh.node_count();
  const std::vector<std::uint8_t> boundary = fesom_boundary_flags(mesh);
  FileWriter f(path);
  auto& buf = f.buffer();
  f.print("{}\n", np);
  std::int64_t flagged = 0;
  for (NodeId n = 0; n < np; ++n) {
    const int flag = boundary[static_cast<std::size_t>(n)];
    flagged += flag;
    fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{} {} {} {}\n"), n + 1, model_lon_deg(mesh.lon_deg[n]),
                   mesh.lat_deg[n], flag);
    f.maybe_flush();
  }
  WriteStats stats;
  stats.bytes = f.close();
  stats.nodes = np;
  stats.boundary_edges = flagged;
  return stats;
}

WriteStats write_fesom_open_boundary(const mesh::Mesh& mesh, const std::filesystem::path& path) {
  const std::vector<NodeId> nodes = fesom_open_boundary_nodes(mesh);
  if (!mesh.typed || nodes.empty()) throw InternalError("FESOM open-boundary file: the mesh has no open boundary");
  FileWriter f(path);
  f.print("{}\n", nodes.size());
  for (const NodeId n : nodes) f.print("{}\n", n + 1);
  WriteStats stats;
  stats.bytes = f.close();
  stats.nodes = static_cast<std::int64_t>(nodes.size());
  return stats;
}

WriteStats write_fesom_elem2d(const mesh::Mesh& mesh, const std::filesystem::path& path) {
  check_triangles(mesh, path);
  FileWriter f(path);
  auto& buf = f.buffer();
  f.print("{}\n", mesh.triangle_count());
  for (const auto& t : mesh.triangles) {
    const auto c = fesom_triangle(t);  // clockwise
    fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{} {} {}\n"), c[0] + 1, c[1] + 1, c[2] + 1);
    f.maybe_flush();
  }
  WriteStats stats;
  stats.bytes = f.close();
  stats.nodes = mesh.node_count();
  stats.elements = mesh.triangle_count();
  return stats;
}

WriteStats write_fesom_aux3d(const mesh::Mesh& mesh, const std::filesystem::path& path,
                             const std::vector<double>& levels_m) {
  check_triangles(mesh, path);
  // output.fesom_levels is checked with the configuration (config/global_config.cpp).
  if (levels_m.size() < 5 || levels_m[0] != 0.0 ||
      std::adjacent_find(levels_m.begin(), levels_m.end(), [](double a, double b) { return !(b > a); }) !=
          levels_m.end())
    throw InternalError(fmt::format("FESOM aux3d.out: unusable depth levels ({})", path.string()));
  FileWriter f(path);
  auto& buf = f.buffer();
  f.print("{}\n", levels_m.size());
  for (const double z : levels_m) f.print("{}\n", negated(z));
  for (const double e : mesh.depth_m) {
    fmt::format_to(std::back_inserter(buf), FMT_COMPILE("{}\n"), fesom_bottom_m(e));
    f.maybe_flush();
  }
  WriteStats stats;
  stats.bytes = f.close();
  stats.nodes = mesh.node_count();
  return stats;
}

}  // namespace aq::io
